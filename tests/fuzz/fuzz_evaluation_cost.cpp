// fuzz_evaluation_cost.cpp - the work of one filtered point against the bound dsn_noise_init enforces
// (dsn.h, DSN_MAX_POINT_IMPULSES): bytes -> an asset of any geometry the format allows (texton, shape,
// pyramid levels of any size), a density, periods and a seed -> init; where init accepts, filtered points
// under a footprint from the bytes (any steps, up to 16 taps, often at a level's widest) at points from
// the bytes (the 32-bit wrap of the coordinates included) must list no more candidates than the expected
// count init bounded, beyond a Poisson tail that no input reaches by chance.
#include <cmath>
#include <cstdint>
#include <vector>

#include "dsn/asset_writer.h"
#include "dsn/dsn.h"
#include "fuzz_input.h"
#include "runtime/core/filtered_internal.h"
#include "runtime/setup/init_internal.h"

namespace {

// An odd side 1..255, small ones as likely as large ones.
uint32_t side(FuzzInput &input) {
    const uint32_t kind = input.byte();
    return kind < 128 ? 2u * (kind % 8u) + 1u : 2u * (input.byte() % 128u) + 1u;
}

dsn::AssetFields asset_from(FuzzInput &input) {
    dsn::AssetFields fields;
    fields.channels = (input.byte() & 1u) ? 3u : 1u;
    fields.interpolation = DSN_INTERPOLATION_BILINEAR;
    fields.width = side(input);
    fields.height = (input.byte() & 1u) ? fields.width : side(input);
    fields.shape =
        fields.width == fields.height && (input.byte() & 1u) ? DSN_SHAPE_DISK : DSN_SHAPE_RECTANGLE;
    for (uint32_t c = 0; c < fields.channels; c++) fields.scale[c] = 1u << 30;
    dsn::set_identity_color_transform(fields);
    // Every support value 1: no all-zero margin shortens a level's reach, the costliest texton of its size.
    fields.texton.assign(size_t(fields.width) * fields.height * fields.channels, 0);
    const int64_t r = (int64_t(fields.width) - 1) / 2;
    for (uint32_t j = 0; j < fields.height; j++)
        for (uint32_t i = 0; i < fields.width; i++) {
            const int64_t dx = int64_t(i) - r, dy = int64_t(j) - r;
            if (fields.shape == DSN_SHAPE_RECTANGLE || dx * dx + dy * dy <= r * r)
                for (uint32_t c = 0; c < fields.channels; c++)
                    fields.texton[(size_t(j) * fields.width + i) * fields.channels + c] = 1;
        }
    const uint32_t levels = input.byte() % (DSN_PYRAMID_MAX_LEVELS + 1u);
    for (uint32_t l = 0; l < levels; l++) {
        dsn::PyramidLevel level;
        level.width = side(input);
        level.height = side(input);
        level.values.assign(size_t(level.width) * level.height * fields.channels, 1);
        fields.pyramid.push_back(level);
    }
    return fields;
}

// A footprint step: often one whose level of detail lies within the pyramid, sometimes any int64.
int64_t step(FuzzInput &input) {
    const uint32_t kind = input.byte();
    const int64_t value = int64_t(int32_t(input.u32()));
    if (kind < 200) return value * (int64_t(1) << (kind % 16u)); // up to 2^46 in Q32.32: 2^14 texels
    return int64_t(uint64_t(input.u32()) | (uint64_t(input.u32()) << 32));
}

// A coordinate: anywhere, or within a few texels of the int32 wrap, where the taps walk one by one.
int64_t coordinate(FuzzInput &input) {
    const uint32_t kind = input.byte();
    const int64_t low = int64_t(input.u32());
    if (kind < 128) return int64_t((uint64_t(0x7FFFFFF0u) << 32) + uint64_t(low) * 16u);
    return int64_t(uint64_t(low) | (uint64_t(input.u32()) << 32));
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FuzzInput input(data, size);
    const std::vector<unsigned char> bytes = dsn::encode_asset(asset_from(input));
    dsn_asset asset;
    fuzz_require(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = input.u32();
    const uint32_t impacts = input.u32() % (DSN_IMPACTS_MAX_Q16 - DSN_IMPACTS_MIN_Q16 + 1u);
    config.impacts_q16 = DSN_IMPACTS_MIN_Q16 + ((input.byte() & 1u) ? impacts : impacts >> 10);
    config.period_x = (input.byte() & 3u) == 0 ? 1u + input.byte() : 0u;
    config.period_y = (input.byte() & 3u) == 0 ? 1u + input.u32() % 4096u : 0u;
    dsn_noise noise;
    const int err = dsn_noise_init(&noise, &asset, &config);
    fuzz_require(err == DSN_OK || err == DSN_ERR_COST);
    if (err != DSN_OK) return 0;
    const dsn_noise_state *state = dsn_state(&noise);
    const uint64_t expected = dsn_internal_point_cost(state);
    fuzz_require(expected <= DSN_MAX_POINT_IMPULSES);

    // The impulses of the cells a walk visits are a sum of independent Poisson draws, of mean at most
    // `expected` (what init bounded): a count above mean + 10 sd + 10 has a probability below 1e-20, so
    // any such count is a walk that visits more than init accounted for.
    const uint64_t limit = expected + uint64_t(10.0 * std::sqrt(double(expected))) + 11u;
    for (uint32_t footprints = 0; footprints < 2; footprints++) {
        const dsn_footprint footprint{step(input), step(input), step(input), step(input),
                                      1u + input.byte() % DSN_FILTER_MAX_TAPS};
        dsn_filter_plan plan;
        fuzz_require(dsn_internal_filter_plan(&footprint, asset.pyramid_levels, &plan) == DSN_OK);
        int32_t faded[DSN_MAX_CHANNELS];
        if (dsn_internal_filter_fade(state, &plan, faded)) continue; // the mean colour: no walk
        dsn_walked_level walked[2];
        const uint32_t count = dsn_internal_filter_walked_levels(state, &plan, walked);
        for (uint32_t points = 0; points < 2; points++) {
            const uint64_t x = uint64_t(coordinate(input)), y = uint64_t(coordinate(input));
            fuzz_require(dsn_internal_filter_listing_only(state, x, y, &plan, walked, count) <= limit);
        }
    }
    return 0;
}
