// evaluation_cost_test.cpp - the bound on one point's work (dsn.h, DSN_MAX_POINT_IMPULSES): init refuses
// the hostile assets and configurations (a tiny texton at a high density under wide pyramid levels, small
// periods under large cells) with DSN_ERR_COST, accepts assets of dsn-bake's geometry with a margin, and
// the expected count it bounds is what filtered points at their widest footprints do list.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "dsn/asset_writer.h"
#include "dsn/dsn.h"
#include "runtime/core/filtered_internal.h"
#include "runtime/setup/init_internal.h"

namespace {

// A grey or RGB bilinear asset, every support value 1 (no all-zero margin shortens a level's reach), with
// the given levels.
dsn::AssetFields spot(uint32_t radius, uint32_t channels, uint32_t bits, uint32_t shape,
                      const std::vector<uint32_t> &level_sides) {
    dsn::AssetFields fields;
    fields.channels = channels;
    fields.bits = bits;
    fields.shape = shape;
    fields.interpolation = DSN_INTERPOLATION_BILINEAR;
    fields.width = fields.height = 2 * radius + 1;
    for (uint32_t c = 0; c < channels; c++) fields.scale[c] = 1u << 30;
    dsn::set_identity_color_transform(fields);
    fields.default_impacts_q16 = DSN_IMPACTS_DEFAULT_Q16;
    fields.texton.assign(size_t(fields.width) * fields.height * channels, 0);
    for (uint32_t j = 0; j < fields.height; j++)
        for (uint32_t i = 0; i < fields.width; i++) {
            const int64_t dx = int64_t(i) - radius, dy = int64_t(j) - radius;
            if (shape == DSN_SHAPE_RECTANGLE || dx * dx + dy * dy <= int64_t(radius) * radius)
                for (uint32_t c = 0; c < channels; c++)
                    fields.texton[(size_t(j) * fields.width + i) * channels + c] = 1;
        }
    for (uint32_t side : level_sides) {
        dsn::PyramidLevel level;
        level.width = level.height = side;
        level.values.assign(size_t(side) * side * channels, 1);
        fields.pyramid.push_back(level);
    }
    return fields;
}

// dsn-bake's pyramid for a texton of radius r (format.h): floor(log2 r) + 1 levels, level l of radius
// ceil((r + 1 + 3 sigma_l) / 2^l), sigma_l = 2^(l - 1).
std::vector<uint32_t> bake_levels(uint32_t radius) {
    std::vector<uint32_t> sides;
    for (uint32_t l = 1; radius != 0 && l <= uint32_t(std::floor(std::log2(double(radius)))) + 1; l++)
        sides.push_back(2 * ((2 * radius + 2 + 3 * (1u << l) + (2u << l) - 1) / (2u << l)) + 1);
    return sides;
}

struct Configured {
    std::vector<unsigned char> bytes;
    dsn_asset asset;
    dsn_noise noise;
    int err;
};

void configure(Configured &out, const dsn::AssetFields &fields, uint32_t impacts_q16, uint32_t period) {
    out.bytes = dsn::encode_asset(fields);
    REQUIRE(dsn_asset_load(&out.asset, out.bytes.data(), out.bytes.size()) == DSN_OK);
    dsn_config config;
    dsn_config_defaults(&config);
    config.impacts_q16 = impacts_q16;
    config.period_x = config.period_y = period;
    out.err = dsn_noise_init(&out.noise, &out.asset, &config);
}

// A footprint whose level of detail is lod_q8 / 256 with `taps` taps spread along the diagonal: the
// widest box its level's walk can have.
dsn_footprint widest(double lod, uint32_t taps) {
    const double minor = std::exp2(lod), major = taps * minor, half = std::sqrt(0.5);
    dsn_footprint footprint;
    REQUIRE(dsn_footprint_from_float(&footprint, major * half, major * half, -minor * half, minor * half,
                                     taps) == DSN_OK);
    return footprint;
}

} // namespace

TEST_CASE("evaluation cost: assets and configurations that make one point examine too many impulses are "
          "refused with DSN_ERR_COST") {
    Configured configured;
    // A few hundred bytes: a 1 x 1 texton at 1024 impacts under 8 levels of 5 x 5 values. Level 8 reaches
    // 768 texels each side of a point, a square of 1536^2 texels at 1024 impulses each.
    dsn::AssetFields tiny = spot(0, 1, 8, DSN_SHAPE_RECTANGLE, std::vector<uint32_t>(8, 5));
    tiny.default_impacts_q16 = DSN_IMPACTS_MAX_Q16;
    configure(configured, tiny, 0, 0);
    CHECK(configured.bytes.size() < 512);
    CHECK(configured.err == DSN_ERR_COST);
    CHECK(dsn_noise_channels(&configured.noise) == 0); // zeroed, so refused by every evaluator
    int32_t value[DSN_MAX_CHANNELS] = {7, 7, 7};
    CHECK(dsn_continuous_point_fixed(&configured.noise, 0, 0, value) == DSN_ERR_NULL);
    dsn_noise loaded;
    CHECK(dsn_noise_load(&loaded, configured.bytes.data(), configured.bytes.size(), 1) == DSN_ERR_COST);

    // The 0.5 MB one: 8 levels of 255 x 255 values, at any density down to the default.
    const dsn::AssetFields wide = spot(0, 1, 8, DSN_SHAPE_RECTANGLE, std::vector<uint32_t>(8, 255));
    for (uint32_t impacts : {DSN_IMPACTS_MAX_Q16, DSN_IMPACTS_DEFAULT_Q16, DSN_IMPACTS_MIN_Q16}) {
        CAPTURE(impacts);
        configure(configured, wide, impacts, 0);
        CHECK(configured.err == DSN_ERR_COST);
    }
    // One level of 255 x 255 at 1024 impacts (before the bound: 314 million impulses, about a minute, for
    // one filtered point of 16 taps).
    configure(configured, spot(0, 1, 8, DSN_SHAPE_RECTANGLE, {255}), DSN_IMPACTS_MAX_Q16, 0);
    CHECK(configured.err == DSN_ERR_COST);

    // A period far smaller than the cells: every copy of the period draws a whole cell. dsn-bake's largest
    // texton at its density takes cells of 128 texels; with period 1 each texel of a walk draws one.
    const dsn::AssetFields largest = spot(126, 3, 16, DSN_SHAPE_DISK, bake_levels(126));
    configure(configured, largest, 0, 1);
    CHECK(configured.err == DSN_ERR_COST);
    configure(configured, largest, 0, 0);
    CHECK(configured.err == DSN_OK);
}

TEST_CASE("evaluation cost: assets of dsn-bake's geometry are accepted with a margin of 8 at their density") {
    // dsn-bake --radius 126 --bits 16 (its largest texton, RGB disk), --radius 127 (a rectangle at the
    // format's largest side), the default --radius 15, and the smallest textons.
    struct Bake {
        uint32_t radius, shape, bits;
    };
    for (const Bake bake :
         {Bake{126, DSN_SHAPE_DISK, 16}, Bake{127, DSN_SHAPE_RECTANGLE, 16}, Bake{15, DSN_SHAPE_DISK, 8},
          Bake{1, DSN_SHAPE_RECTANGLE, 8}, Bake{0, DSN_SHAPE_RECTANGLE, 8}}) {
        for (uint32_t period : {0u, 256u}) {
            CAPTURE(bake.radius);
            CAPTURE(period);
            Configured configured;
            configure(configured, spot(bake.radius, 3, bake.bits, bake.shape, bake_levels(bake.radius)), 0,
                      period);
            REQUIRE(configured.err == DSN_OK);
            const uint64_t cost = dsn_internal_point_cost(dsn_state(&configured.noise));
            MESSAGE("radius " << bake.radius << " period " << period << ": " << cost << " impulses");
            CHECK(cost * 8 <= DSN_MAX_POINT_IMPULSES);
        }
    }
}

TEST_CASE(
    "evaluation cost: filtered points at their widest footprints list no more than the expected count") {
    // Per level of detail, 16 taps along the diagonal at the top of the level's range (the widest box of
    // its walk), at points far apart (independent cells) and across the int32 wrap (each tap alone).
    struct Case {
        uint32_t radius;
        std::vector<uint32_t> levels;
        uint32_t impacts_q16;
    };
    for (const Case &test :
         {Case{0, {}, DSN_IMPACTS_DEFAULT_Q16}, Case{15, bake_levels(15), DSN_IMPACTS_DEFAULT_Q16},
          Case{0, {7, 7, 7}, 4u << 16}}) {
        Configured configured;
        configure(configured, spot(test.radius, 1, 8, DSN_SHAPE_RECTANGLE, test.levels), test.impacts_q16, 0);
        REQUIRE(configured.err == DSN_OK);
        const dsn_noise_state *state = dsn_state(&configured.noise);
        const uint64_t expected = dsn_internal_point_cost(state);
        double most = 0;
        for (uint32_t lower = 0; lower <= configured.asset.pyramid_levels; lower++) {
            const dsn_footprint footprint = widest(lower + 0.99, 16);
            dsn_filter_plan plan;
            REQUIRE(dsn_internal_filter_plan(&footprint, configured.asset.pyramid_levels, &plan) == DSN_OK);
            REQUIRE(plan.taps == 16);
            REQUIRE((plan.lod_q8 >> 8) == int32_t(lower));
            dsn_walked_level walked[2];
            const uint32_t count = dsn_internal_filter_walked_levels(state, &plan, walked);
            for (const bool seam : {false, true}) {
                const uint32_t points = 16;
                uint64_t listed = 0;
                for (uint32_t p = 0; p < points; p++) {
                    const uint64_t x = seam ? (uint64_t(0x7FFFFFFFu) << 32) + (uint64_t(p) << 28)
                                            : uint64_t(p) * 0x1000000000000u;
                    listed += dsn_internal_filter_listing_only(state, x, x * 3u, &plan, walked, count);
                }
                const double mean = double(listed) / points;
                most = std::max(most, mean);
                CAPTURE(test.radius);
                CAPTURE(lower);
                CAPTURE(seam);
                // The mean of 16 counts whose expectations are at most `expected`: its standard deviation
                // is at most sqrt(expected / 16); 6 of them is a tail below 1e-9.
                CHECK(mean <= double(expected) + 6.0 * std::sqrt(double(expected) / points));
            }
        }
        MESSAGE("radius " << test.radius << ": bound " << expected << ", the widest listing " << most);
    }
}
