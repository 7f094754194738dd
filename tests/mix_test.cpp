// mix_test.cpp - the mixing of materials (dsn.h, "Mixing"): where the weights are one material's, the bits of
// that material's own noise; tiles equal to points; a constant 50/50 mix with the average mean and
// covariance of the two materials, against the bilinear-spot theory; the variance across a transition
// following the weights (no dip, where a crossfade dips); no seam; and every bad input.
//
// Theory of a constant mix. Each impulse of the Poisson process of intensity lambda picks material m with
// probability p_m, independently: material m's impulses form a Poisson process of intensity p_m lambda
// (thinning), independent of the others. Material m's sum, normalized by K_m / sqrt(lambda), then has
// mean p_m (its expected sum) and covariance p_m C_m(h), C_m the material's own covariance; the offsets
// weighted by p_m complete the means. So out has mean sum_m p_m mean_m and covariance sum_m p_m C_m(h),
// auto- and cross-channel, C_m(h) = sum_kl K_ck K_dl integral t~_k(y) t~_l(y + h) dy as in
// continuous_statistics_test.cpp. Samples at sites 24 texels apart (beyond the reach plus the lags) are
// independent; covariances are estimated over 20 batches and compared within 4 standard errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <vector>

#include "fixtures/continuous_fixtures.h"
#include "fixtures/test_assets.h"
#include "offline/bake_internal.h"
#include "runtime/core/mix_weights.h"
#include "runtime/evaluators/mix_evaluation.h"
#include "runtime/kernels/kernels.h"

using namespace continuous_fixtures;

namespace {

const int64_t kOne = int64_t(1) << 32;

// A control of width x height samples of `count` weights each, from a function of the sample.
struct Control {
    std::vector<uint8_t> weights;
    dsn_mix_control control{};
    Control(uint32_t count, uint32_t width, uint32_t height, uint32_t spacing_shift,
            const std::function<std::vector<uint8_t>(uint32_t, uint32_t)> &sample, uint32_t flags = 0) {
        for (uint32_t j = 0; j < height; j++)
            for (uint32_t i = 0; i < width; i++) {
                const auto values = sample(i, j);
                weights.insert(weights.end(), values.begin(), values.end());
            }
        control.weights = weights.data();
        control.width = width;
        control.height = height;
        control.spacing_shift = spacing_shift;
        control.flags = flags;
        (void)count;
    }
};

// A constant control: one sample.
Control constant(std::vector<uint8_t> weights) {
    return Control(uint32_t(weights.size()), 1, 1, 0, [&](uint32_t, uint32_t) { return weights; });
}

dsn_mix make_mix(std::initializer_list<const dsn_noise *> materials) {
    std::vector<const dsn_noise *> list(materials);
    dsn_mix mix;
    REQUIRE(dsn_mix_init(&mix, list.data(), uint32_t(list.size())) == DSN_OK);
    return mix;
}

// Asset fields with another mean, so that a mix's mean shows which material it comes from.
dsn::AssetFields with_means(dsn::AssetFields fields, int32_t a, int32_t b, int32_t c) {
    fields.mean[0] = a;
    if (fields.channels == 3) fields.mean[1] = b, fields.mean[2] = c;
    return fields;
}

// Four materials of four kinds on a process with a period: RGB 8-bit 31 x 31 (the lead, period 29 along
// x), grey 16-bit 19 x 19 at 12 impacts (ignored: the lead's density rules), RGB 8-bit 9 x 9 with other
// means, RGB 16-bit 13 x 13; seeds from `seed`.
struct FourMaterials {
    std::unique_ptr<Noise> a, b, c, d;
    dsn_mix mix;
    explicit FourMaterials(uint32_t seed)
        : a(make_noise(random_texton_asset(3, 15, 8, seed), seed + 1, 0, 29, 0)),
          b(make_noise(random_texton_asset(1, 9, 16, seed + 2), seed + 3, 12u << 16)),
          c(make_noise(with_means(random_texton_asset(3, 4, 8, seed + 4), 1 << 22, -(1 << 21), 1 << 20),
                       seed + 5)),
          d(make_noise(random_texton_asset(3, 6, 16, seed + 6), seed + 7)),
          mix(make_mix({&a->noise, &b->noise, &c->noise, &d->noise})) {}
};

// The outputs that differ from the points' values: fixed, u8 and (where given) float.
size_t output_differences(const std::vector<int32_t> &expected, const std::vector<int32_t> &fixed,
                          const std::vector<uint8_t> &bytes, const std::vector<float> &floats) {
    size_t differences = 0;
    for (size_t at = 0; at < expected.size(); at++) {
        differences += fixed[at] != expected[at];
        differences += bytes[at] != dsn_fixed_to_u8(expected[at]);
        if (!floats.empty()) differences += floats[at] != dsn_fixed_to_float(expected[at]);
    }
    return differences;
}

// A copy of `mix` whose materials run kernel `kernel` (copied bytewise: the state is written through
// another type).
dsn_mix on_kernel(const dsn_mix &mix, uint32_t kernel) {
    dsn_mix copy;
    std::memcpy(&copy, &mix, sizeof copy);
    dsn_mix_state *state = dsn_mix_state_of(&copy);
    for (uint32_t m = 0; m < state->count; m++) state->material[m].tile_kernel = kernel;
    return copy;
}

// Four 8-bit materials of `channels` channels (31 x 31, 30 impacts) and their twins stored in 16 bits (the
// same values and scales: the same noises), which the kernels' vector evaluators leave to the generic walk;
// mixes of the first `count` of each.
struct TwinMaterials {
    std::vector<std::unique_ptr<Noise>> narrow, wide;
    TwinMaterials(uint32_t channels, uint32_t asset_seed, uint32_t noise_seed) {
        for (uint32_t m = 0; m < 4; m++) {
            dsn::AssetFields fields = random_texton_asset(channels, 15, 8, asset_seed + m);
            narrow.push_back(make_noise(fields, noise_seed + m, 30u << 16));
            fields.bits = 16;
            wide.push_back(make_noise(fields, noise_seed + m, 30u << 16));
        }
    }
    void mixes(uint32_t count, dsn_mix *mix, dsn_mix *wide_mix) const {
        std::vector<const dsn_noise *> list, wide_list;
        for (uint32_t m = 0; m < count; m++)
            list.push_back(&narrow[m]->noise), wide_list.push_back(&wide[m]->noise);
        REQUIRE(dsn_mix_init(mix, list.data(), count) == DSN_OK);
        REQUIRE(dsn_mix_init(wide_mix, wide_list.data(), count) == DSN_OK);
    }
};

// Where the weights vary: `count` weights at sample (i, j), some of them 0, and some samples of no weight.
std::vector<uint8_t> varying_weights(uint32_t count, uint32_t i, uint32_t j) {
    std::vector<uint8_t> weights(count);
    for (uint32_t m = 0; m < count; m++)
        weights[m] = (i * 3 + j + m) % 5 == 0 ? 0 : uint8_t((i * 89 + j * 43 + m * 67) % 256);
    if ((i + j) % 11 == 4) weights.assign(count, 0);
    return weights;
}

// A control's size, spacing, axes and origin, its weights varying_weights's.
struct ControlKind {
    uint32_t width, height, spacing_shift, flags;
    int32_t origin_x, origin_y;
};

Control varying_control(uint32_t count, const ControlKind &kind) {
    Control control(
        count, kind.width, kind.height, kind.spacing_shift,
        [count](uint32_t i, uint32_t j) { return varying_weights(count, i, j); }, kind.flags);
    control.control.origin_x = kind.origin_x, control.control.origin_y = kind.origin_y;
    return control;
}

// Test point k of a control: a third anywhere, a third near the control, a third by the wrap of x -
// origin_x.
void point_by_control(const ControlKind &kind, int k, std::mt19937_64 &random, int64_t *x, int64_t *y) {
    const uint64_t extent_x = uint64_t(kind.width) << kind.spacing_shift, extent_y = uint64_t(kind.height)
                                                                                     << kind.spacing_shift;
    *x = int64_t(random()), *y = int64_t(random());
    if (k % 3 != 0) {
        *x = int64_t((uint64_t(uint32_t(kind.origin_x)) + random() % (extent_x + 80) - 40) << 32) +
             int64_t(random() >> 32);
        *y = int64_t((uint64_t(uint32_t(kind.origin_y)) + random() % (extent_y + 80) - 40) << 32) +
             int64_t(random() >> 32);
    }
    if (k % 3 == 2)
        *x = int64_t(uint64_t(uint32_t(kind.origin_x) + 0x80000000u - 20u + random() % 40) << 32) +
             int64_t(random() >> 32);
}

} // namespace

TEST_CASE("mix: where the weights are material 0's, the bits of its own noise, lattice and continuous") {
    for (uint32_t channels : {1u, 3u})
        for (uint32_t period : {0u, 37u}) {
            // material 1 is wider than material 0: the walk's reach is larger than material 0's own
            auto lead = make_noise(random_texton_asset(channels, 5, 8, 11), 77, 30u << 16, period, period);
            auto other = make_noise(random_texton_asset(channels, 8, 16, 12), 5, 12u << 16);
            const dsn_mix mix = make_mix({&lead->noise, &other->noise});
            CHECK(dsn_mix_channels(&mix) == channels);
            const Control on_lead = constant({255, 0});
            std::vector<int64_t> xs, ys;
            renderer_points(3 + period, 400, &xs, &ys);
            size_t differences = 0;
            for (size_t k = 0; k < xs.size(); k++) {
                int32_t own[3] = {}, mixed[3] = {};
                REQUIRE(dsn_continuous_point_fixed(&lead->noise, xs[k], ys[k], own) == DSN_OK);
                REQUIRE(dsn_mix_continuous_point_fixed(&mix, &on_lead.control, xs[k], ys[k], mixed) ==
                        DSN_OK);
                differences += std::memcmp(own, mixed, sizeof own) != 0;
                const int32_t x = int32_t(uint32_t(uint64_t(xs[k]) >> 32)),
                              y = int32_t(uint32_t(uint64_t(ys[k]) >> 32));
                dsn_lattice_point_fixed(&lead->noise, x, y, own);
                REQUIRE(dsn_mix_lattice_point_fixed(&mix, &on_lead.control, x, y, mixed) == DSN_OK);
                differences += std::memcmp(own, mixed, sizeof own) != 0;
            }
            CHECK(differences == 0);
        }
}

TEST_CASE("mix: where the weights are another material's, the bits of its noise on material 0's impulses") {
    // Same window and density as material 0, so the same cells and Poisson table: material 1's own noise
    // with material 0's seed has exactly the mix's impulses, all picked by material 1.
    auto lead = make_noise(random_texton_asset(3, 6, 8, 21), 9, 20u << 16);
    auto other_fields = with_means(random_texton_asset(3, 6, 16, 22), 3 << 22, 1 << 20, 5 << 21);
    auto other = make_noise(other_fields, 4, 20u << 16);
    auto other_on_lead_seed = make_noise(other_fields, 9, 20u << 16);
    const dsn_mix mix = make_mix({&lead->noise, &other->noise});
    std::vector<int64_t> xs, ys;
    renderer_points(8, 400, &xs, &ys);
    // Any scale of weights: (0, 1) and (0, 200) are the same normalized weights.
    for (uint8_t weight : {1, 200, 255}) {
        const Control on_other = constant({0, weight});
        size_t differences = 0;
        for (size_t k = 0; k < xs.size(); k++) {
            int32_t own[3] = {}, mixed[3] = {};
            dsn_continuous_point_fixed(&other_on_lead_seed->noise, xs[k], ys[k], own);
            dsn_mix_continuous_point_fixed(&mix, &on_other.control, xs[k], ys[k], mixed);
            differences += std::memcmp(own, mixed, sizeof own) != 0;
            const int32_t x = int32_t(uint32_t(uint64_t(xs[k]) >> 32)),
                          y = int32_t(uint32_t(uint64_t(ys[k]) >> 32));
            dsn_lattice_point_fixed(&other_on_lead_seed->noise, x, y, own);
            dsn_mix_lattice_point_fixed(&mix, &on_other.control, x, y, mixed);
            differences += std::memcmp(own, mixed, sizeof own) != 0;
        }
        CHECK(differences == 0);
    }
    // No weight at all: material 0's noise.
    const Control none = constant({0, 0});
    for (size_t k = 0; k < 50; k++) {
        int32_t own[3] = {}, mixed[3] = {};
        dsn_continuous_point_fixed(&lead->noise, xs[k], ys[k], own);
        dsn_mix_continuous_point_fixed(&mix, &none.control, xs[k], ys[k], mixed);
        CHECK(std::memcmp(own, mixed, sizeof own) == 0);
    }
}

TEST_CASE("mix: normalized weights, whatever their scale; tiles are their points") {
    auto a = make_noise(random_texton_asset(3, 5, 8, 31), 1);
    auto b = make_noise(with_means(random_texton_asset(1, 7, 8, 32), 1 << 22, 0, 0), 2);
    const dsn_mix mix = make_mix({&a->noise, &b->noise});
    CHECK(dsn_mix_channels(&mix) == 3); // grey with RGB: 3 channels
    const Control low = constant({10, 10}), high = constant({200, 200});
    // A ramp with a periodic and a clamped axis, samples 4 texels apart, origin off the grid.
    Control ramp(
        2, 9, 5, 2,
        [](uint32_t i, uint32_t j) {
            return std::vector<uint8_t>{uint8_t(i * 31 % 256), uint8_t((j * 50 + 7 * i) % 256)};
        },
        DSN_MIX_PERIODIC_X);
    ramp.control.origin_x = -13;
    ramp.control.origin_y = 2;
    std::vector<int64_t> xs, ys;
    renderer_points(5, 300, &xs, &ys);
    for (size_t k = 0; k < xs.size(); k++) {
        int32_t first[3], second[3];
        dsn_mix_continuous_point_fixed(&mix, &low.control, xs[k], ys[k], first);
        dsn_mix_continuous_point_fixed(&mix, &high.control, xs[k], ys[k], second);
        CHECK(std::memcmp(first, second, sizeof first) == 0);
    }
    // Tiles: a rotated grid and a lattice window, fixed and float, equal to the points.
    const dsn_grid grid = {int64_t(-20) * kOne + 12345, int64_t(7) * kOne,    int64_t(0.87 * kOne),
                           int64_t(0.5 * kOne),         int64_t(-0.5 * kOne), int64_t(0.87 * kOne)};
    const uint32_t width = 23, height = 17;
    std::vector<int32_t> fixed(width * height * 3);
    std::vector<float> floats(width * height * 3);
    REQUIRE(dsn_mix_continuous_tile_fixed(&mix, &ramp.control, &grid, width, height, fixed.data(), nullptr,
                                          0) == DSN_OK);
    REQUIRE(dsn_mix_continuous_tile_float(&mix, &ramp.control, &grid, width, height, floats.data(), nullptr,
                                          0) == DSN_OK);
    size_t differences = 0;
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            int32_t point[3];
            const int64_t x = int64_t(uint64_t(grid.origin_x) + i * uint64_t(grid.column_step_x) +
                                      j * uint64_t(grid.row_step_x));
            const int64_t y = int64_t(uint64_t(grid.origin_y) + i * uint64_t(grid.column_step_y) +
                                      j * uint64_t(grid.row_step_y));
            dsn_mix_continuous_point_fixed(&mix, &ramp.control, x, y, point);
            for (int c = 0; c < 3; c++) {
                const size_t at = (j * width + i) * 3 + size_t(c);
                differences += fixed[at] != point[c];
                differences += floats[at] != dsn_fixed_to_float(point[c]);
            }
        }
    REQUIRE(dsn_mix_lattice_tile_fixed(&mix, &ramp.control, INT32_MAX - 9, -8, width, height, fixed.data(),
                                       nullptr, 0) == DSN_OK);
    REQUIRE(dsn_mix_lattice_tile_float(&mix, &ramp.control, INT32_MAX - 9, -8, width, height, floats.data(),
                                       nullptr, 0) == DSN_OK);
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            int32_t point[3];
            dsn_mix_lattice_point_fixed(&mix, &ramp.control, int32_t(uint32_t(INT32_MAX - 9) + i),
                                        int32_t(j) - 8, point);
            for (int c = 0; c < 3; c++) {
                const size_t at = (j * width + i) * 3 + size_t(c);
                differences += fixed[at] != point[c];
                differences += floats[at] != dsn_fixed_to_float(point[c]);
            }
        }
    CHECK(differences == 0);
    float point[3];
    REQUIRE(dsn_mix_continuous_point_float(&mix, &ramp.control, 3.25, -7.5, point) == DSN_OK);
    int32_t fixed_point[3];
    dsn_mix_continuous_point_fixed(&mix, &ramp.control, 13 * (kOne / 4), -30 * (kOne / 4), fixed_point);
    for (int c = 0; c < 3; c++) CHECK(point[c] == dsn_fixed_to_float(fixed_point[c]));
}

TEST_CASE("mix: draw_threshold is the smallest hash that pick_material's draw takes past a running sum") {
    std::mt19937_64 random(17);
    for (int trial = 0; trial < 20000; trial++) {
        const uint32_t total = trial < 4 ? uint32_t(1) << (trial * 6) : 1u + uint32_t(random() % 261120u);
        const uint32_t running = trial % 5 == 0   ? total
                                 : trial % 7 == 0 ? 0u
                                                  : uint32_t(random() % (total + 1u));
        uint32_t upto = 0, upto_in_digits = 0;
        const uint64_t threshold = draw_threshold(running, total, &upto);
        CAPTURE(total);
        CAPTURE(running);
        CHECK(draw_threshold_in_digits(running, total, &upto_in_digits) == threshold); // the 32-bit targets'
        // and the point weights' running sum from the same division, point_weights's
        CHECK(upto == (running << 14) / total);
        CHECK(upto_in_digits == upto);
        REQUIRE(threshold <= (uint64_t(1) << 32));
        // floor(hash total / 2^32) >= running exactly from the threshold on
        if (threshold < (uint64_t(1) << 32)) CHECK(((threshold * total) >> 32) >= running);
        if (threshold > 0) CHECK((((threshold - 1u) * total) >> 32) < running);
    }
}

TEST_CASE("mix: a uniform region's draws are point_weights's weights and draw_threshold's thresholds") {
    std::mt19937_64 random(23);
    for (int trial = 0; trial < 4000; trial++) {
        const uint32_t count = 1u + uint32_t(trial % 4);
        MixWeights weights = MixWeights();
        uint32_t total = 0, nonzero = 0, only = 0;
        for (uint32_t m = 0; m < count; m++) {
            const uint32_t weight = random() % 3 == 0 ? 0u : uint32_t(random() % 256u);
            total += weight << 8;
            weights.cumulative[m] = total;
            if (weight != 0) nonzero++, only = m;
        }
        CAPTURE(trial);
        UniformDraws draws;
        uniform_draws(weights, count, &draws);
        uint32_t expected[DSN_MIX_MAX_MATERIALS] = {0, 0, 0, 0};
        point_weights(weights, count, expected);
        for (uint32_t m = 0; m < DSN_MIX_MAX_MATERIALS; m++) CHECK(draws.weights[m] == expected[m]);
        for (uint32_t m = 0; m + 1 < DSN_MIX_MAX_MATERIALS; m++) {
            uint32_t upto = 0;
            CHECK(draws.thresholds[m] == (total != 0 && m + 1 < count
                                              ? draw_threshold(weights.cumulative[m], total, &upto)
                                              : uint64_t(1) << 32));
        }
        if (nonzero <= 1) { // the region's single material: the same draws without a division
            UniformDraws single;
            single_draws(only, &single);
            CHECK(std::memcmp(&single, &draws, sizeof draws) == 0);
        }
    }
}

// What the kernels' mixed point asks of a pick (kernels.h's dsn_point_materials): here the uniform weights'
// draw by pick_material itself, so that a kernel's thresholds can be checked against it.
struct UniformPick {
    MixWeights weights;
    uint32_t count;
};
uint32_t uniform_pick(const void *context, uint32_t hash, uint32_t, uint32_t) {
    const UniformPick *pick = static_cast<const UniformPick *>(context);
    return pick_material(pick->weights, pick->count, hash);
}

TEST_CASE("mix: saturating_add is the 64-bit sum of two int32 saturated, at the limits and anywhere") {
    // The lattice tile's passes sum two materials' values so (mix_evaluation.h).
    std::mt19937_64 random(31);
    const int32_t edges[] = {INT32_MIN, INT32_MIN + 1, -(1 << 30),    -2,       -1, 0, 1,
                             2,         1 << 30,       INT32_MAX - 1, INT32_MAX};
    std::vector<std::pair<int32_t, int32_t>> pairs;
    for (const int32_t a : edges)
        for (const int32_t b : edges) pairs.push_back({a, b});
    for (int k = 0; k < 100000; k++)
        pairs.push_back({int32_t(uint32_t(random())), int32_t(uint32_t(random()))});
    size_t differences = 0, saturated = 0;
    for (const auto &pair : pairs) {
        const int64_t sum = int64_t(pair.first) + pair.second;
        const int32_t expected = int32_t(std::clamp<int64_t>(sum, INT32_MIN, INT32_MAX));
        differences += saturating_add(pair.first, pair.second) != expected;
        saturated += sum != expected;
    }
    CHECK(differences == 0);
    CHECK(saturated > 20000); // about a quarter of the random pairs overflow, both ways
}

TEST_CASE("mix: lattice points of materials of one texton size, through every kernel's vector walk, are the "
          "generic walk's") {
    struct Setting {
        uint32_t channels, radius, bits, impacts;
    };
    std::mt19937_64 random(23);
    // 50 impacts on a 31 x 31 texton: about 13 impulses a cell, many past the vector walk's 16 a cell
    for (const Setting setting : {Setting{3, 15, 8, 30}, Setting{1, 15, 16, 50}, Setting{3, 13, 16, 40}}) {
        CAPTURE(setting.channels);
        CAPTURE(setting.bits);
        std::vector<std::unique_ptr<Noise>> noises;
        for (uint32_t m = 0; m < 4; m++)
            noises.push_back(
                make_noise(random_texton_asset(setting.channels, setting.radius, setting.bits, 40 + m), 7 + m,
                           setting.impacts << 16));
        for (uint32_t count = 2; count <= 4; count++) {
            CAPTURE(count);
            std::vector<const dsn_noise *> list;
            for (uint32_t m = 0; m < count; m++) list.push_back(&noises[m]->noise);
            dsn_mix mix;
            REQUIRE(dsn_mix_init(&mix, list.data(), count) == DSN_OK);
            const dsn_mix_state *state = dsn_mix_state_of(&mix);
            const dsn_noise_state *lead = &state->material[0];
            // the vector walk's noises (lattice_point_walk.h's cells16_walk)
            REQUIRE(lead->cell_shift == 4);
            REQUIRE(lead->poisson_parts == 1);
            const std::vector<uint8_t> uneven_weights = {200, 0, 55, 9};
            const Control even = constant(std::vector<uint8_t>(count, 128));
            const Control uneven =
                constant(std::vector<uint8_t>(uneven_weights.begin(), uneven_weights.begin() + count));
            const Control varying(
                count, 6, 5, 2,
                [&](uint32_t i, uint32_t j) {
                    std::vector<uint8_t> weights(count);
                    for (uint32_t m = 0; m < count; m++)
                        weights[m] = uint8_t((i * 53 + j * 97 + m * 71) % 256);
                    return weights;
                },
                DSN_MIX_PERIODIC_X | DSN_MIX_PERIODIC_Y);
            // The API's point (the kernel's walk) against a 1 x 1 tile without scratch (the generic walk).
            size_t differences = 0;
            for (const Control *control : {&even, &uneven, &varying})
                for (int k = 0; k < 60; k++) {
                    const int32_t x = int32_t(uint32_t(random())), y = int32_t(uint32_t(random()));
                    int32_t point[3] = {}, tile[3] = {};
                    REQUIRE(dsn_mix_lattice_point_fixed(&mix, &control->control, x, y, point) == DSN_OK);
                    REQUIRE(dsn_mix_lattice_tile_fixed(&mix, &control->control, x, y, 1, 1, tile, nullptr,
                                                       0) == DSN_OK);
                    differences += std::memcmp(point, tile, sizeof point) != 0;
                }
            CHECK(differences == 0);
            // Every kernel this CPU runs: the even and uneven weights by thresholds and by a pick of the same
            // draw give the default kernel's sums.
            const dsn_texton_window texton = dsn_lattice_texton_window(lead);
            dsn_point_materials by_thresholds = {
                count, {nullptr, nullptr, nullptr, nullptr}, {0, 0, 0}, nullptr, nullptr, nullptr};
            for (uint32_t m = 0; m < count; m++)
                by_thresholds.values[m] = dsn_lattice_texton_window(&state->material[m]).values;
            size_t kernel_differences = 0, walked = 0;
            for (const Control *control : {&even, &uneven}) {
                UniformPick uniform = {MixWeights(), count};
                mix_weights_at(&control->control, count, 0, 0, &uniform.weights);
                const uint32_t total = uniform.weights.cumulative[count - 1];
                UniformDraws draws;
                uniform_draws(uniform.weights, count, &draws);
                for (uint32_t m = 0; m < 3; m++) {
                    uint32_t upto = 0;
                    by_thresholds.thresholds[m] =
                        m + 1 < count ? draw_threshold(uniform.weights.cumulative[m], total, &upto)
                                      : uint64_t(1) << 32;
                    CHECK(draws.thresholds[m] == by_thresholds.thresholds[m]);
                }
                dsn_point_materials by_pick = by_thresholds;
                by_pick.pick = uniform_pick;
                by_pick.context = &uniform;
                for (int k = 0; k < 40; k++) {
                    const uint32_t x = uint32_t(random()), y = uint32_t(random());
                    uint32_t expected[12] = {};
                    dsn_lattice_point_entry *reference = dsn_internal_kernels[0].entries->lattice_point;
                    REQUIRE(bool(reference));
                    REQUIRE(reference(lead, &texton, x, y, 1, expected, &by_pick) == 1);
                    for (uint32_t i = 0; i < dsn_internal_kernel_count; i++) {
                        const dsn_kernel &kernel = dsn_internal_kernels[i];
                        if (kernel.cpu_runs != nullptr && !kernel.cpu_runs()) continue;
                        for (const dsn_point_materials *materials : {&by_thresholds, &by_pick}) {
                            uint32_t sums[12] = {};
                            REQUIRE(kernel.entries->lattice_point(lead, &texton, x, y, 1, sums, materials) ==
                                    1);
                            kernel_differences +=
                                std::memcmp(sums, expected, 3 * count * sizeof sums[0]) != 0;
                            walked++;
                        }
                    }
                }
            }
            CHECK(kernel_differences == 0);
            CHECK(walked >= 160);
        }
    }
}

TEST_CASE(
    "mix: continuous points of materials of one texton size, through the kernels' vector evaluator, are "
    "the generic walk's") {
    // The reference: the twins stored in 16 bits (TwinMaterials).
    std::mt19937_64 random(29);
    for (const uint32_t channels : {3u, 1u}) {
        CAPTURE(channels);
        const TwinMaterials twins(channels, 50, 3);
        // the twins are one noise
        int32_t narrow_value[3] = {}, wide_value[3] = {};
        dsn_continuous_point_fixed(&twins.narrow[0]->noise, kOne / 3, kOne / 7, narrow_value);
        dsn_continuous_point_fixed(&twins.wide[0]->noise, kOne / 3, kOne / 7, wide_value);
        REQUIRE(std::memcmp(narrow_value, wide_value, sizeof narrow_value) == 0);
        for (uint32_t count = 2; count <= 4; count++) {
            CAPTURE(count);
            dsn_mix mix, wide_mix;
            twins.mixes(count, &mix, &wide_mix);
            const std::vector<uint8_t> uneven_weights = {30, 200, 0, 90};
            const Control even = constant(std::vector<uint8_t>(count, 128));
            const Control uneven =
                constant(std::vector<uint8_t>(uneven_weights.begin(), uneven_weights.begin() + count));
            // Weights changing every 2 texels, with zero weights and samples of no weight: each point's
            // candidates pick their materials at their positions' integer parts (the vector evaluator per
            // point), the twins' walk at its impulses'.
            const Control varying(
                count, 7, 5, 1,
                [&](uint32_t i, uint32_t j) {
                    std::vector<uint8_t> weights(count);
                    for (uint32_t m = 0; m < count; m++)
                        weights[m] = (i + 2 * j + m) % 4 == 0 ? 0 : uint8_t((i * 61 + j * 37 + m * 83) % 256);
                    if (i == 3 && j == 2) weights.assign(count, 0);
                    return weights;
                },
                DSN_MIX_PERIODIC_X);
            // Points, and tiles (their groups), against the twins'.
            size_t differences = 0;
            for (const Control *control : {&even, &uneven, &varying}) {
                for (int k = 0; k < 150; k++) {
                    const int64_t x = int64_t(random()), y = int64_t(random());
                    int32_t reference[3] = {};
                    REQUIRE(dsn_mix_continuous_point_fixed(&wide_mix, &control->control, x, y, reference) ==
                            DSN_OK);
                    // every kernel this CPU runs (the AVX2 and AVX-512 copies' evaluators)
                    for (uint32_t kernel = DSN_KERNEL_DEFAULT;
                         kernel <= dsn_mix_state_of(&mix)->material[0].tile_kernel; kernel++) {
                        const dsn_mix copy = on_kernel(mix, kernel);
                        int32_t point[3] = {};
                        REQUIRE(dsn_mix_continuous_point_fixed(&copy, &control->control, x, y, point) ==
                                DSN_OK);
                        differences += std::memcmp(point, reference, sizeof point) != 0;
                    }
                }
                const dsn_grid grid = {int64_t(random()), int64_t(random()), kOne / 3,
                                       kOne / 5,          -kOne / 5,         kOne / 3};
                std::vector<int32_t> tile(20 * 6 * channels), reference(tile.size());
                REQUIRE(dsn_mix_continuous_tile_fixed(&mix, &control->control, &grid, 20, 6, tile.data(),
                                                      nullptr, 0) == DSN_OK);
                REQUIRE(dsn_mix_continuous_tile_fixed(&wide_mix, &control->control, &grid, 20, 6,
                                                      reference.data(), nullptr, 0) == DSN_OK);
                differences += tile != reference;
            }
            CHECK(differences == 0);
        }
    }
}

TEST_CASE(
    "mix: continuous and lattice points where the weights vary, their materials read from the control on "
    "vectors (the AVX2 and AVX-512 copies), are the generic walk's") {
    // The continuous points against the 16-bit twins as above, the lattice points against a tile of one
    // without scratch (the generic walk). Controls of every kind the lanes read (mix_pick_lanes.h):
    // periodic and clamped axes, samples 1, 4, 16, 2^9 and 2^16 texels apart (the fraction shifted up and
    // down), origins on both sides, samples of no weight; points near the controls and anywhere, some
    // where a periodic axis's window crosses the wrap of position - origin (the pick goes impulse by
    // impulse there).
    std::mt19937_64 random(31);
    for (const uint32_t channels : {3u, 1u}) {
        CAPTURE(channels);
        const TwinMaterials twins(channels, 60, 9);
        for (uint32_t count = 2; count <= 4; count++) {
            CAPTURE(count);
            dsn_mix mix, wide_mix;
            twins.mixes(count, &mix, &wide_mix);
            const ControlKind kinds[] = {{64, 48, 2, DSN_MIX_PERIODIC_X, -40, 13},
                                         {40, 40, 0, 0, 5, -7},
                                         {45, 38, 0, DSN_MIX_PERIODIC_X | DSN_MIX_PERIODIC_Y, 3, 2},
                                         {20, 30, 9, DSN_MIX_PERIODIC_X | DSN_MIX_PERIODIC_Y, -3000, 1000},
                                         {9, 7, 4, DSN_MIX_PERIODIC_Y, 70, -90},
                                         {3, 2, 16, DSN_MIX_PERIODIC_X, 0, 0},
                                         {9, 9, 2, DSN_MIX_PERIODIC_X | DSN_MIX_PERIODIC_Y, 1, -2}};
            size_t differences = 0, points = 0, laned = 0;
            for (const ControlKind &kind : kinds) {
                const Control control = varying_control(count, kind);
                for (int k = 0; k < 120; k++) {
                    int64_t x, y;
                    point_by_control(kind, k, random, &x, &y);
                    const uint32_t reach_x = dsn_mix_state_of(&mix)->material[0].radius[0] + 2u,
                                   reach_y = dsn_mix_state_of(&mix)->material[0].radius[1] + 2u;
                    PickWindowAxis ax, ay;
                    laned += lanes_read_control(&control.control, count,
                                                uint32_t(uint64_t(x) >> 32) - reach_x, 2 * reach_x,
                                                uint32_t(uint64_t(y) >> 32) - reach_y, 2 * reach_y, &ax, &ay);
                    int32_t reference[3] = {};
                    REQUIRE(dsn_mix_continuous_point_fixed(&wide_mix, &control.control, x, y, reference) ==
                            DSN_OK);
                    const int32_t lattice_x = int32_t(uint64_t(x) >> 32),
                                  lattice_y = int32_t(uint64_t(y) >> 32);
                    int32_t lattice_reference[3] = {};
                    REQUIRE(dsn_mix_lattice_tile_fixed(&mix, &control.control, lattice_x, lattice_y, 1, 1,
                                                       lattice_reference, nullptr, 0) == DSN_OK);
                    for (uint32_t kernel = DSN_KERNEL_DEFAULT;
                         kernel <= dsn_mix_state_of(&mix)->material[0].tile_kernel; kernel++) {
                        const dsn_mix copy = on_kernel(mix, kernel);
                        int32_t point[3] = {}, lattice[3] = {};
                        REQUIRE(dsn_mix_continuous_point_fixed(&copy, &control.control, x, y, point) ==
                                DSN_OK);
                        REQUIRE(dsn_mix_lattice_point_fixed(&copy, &control.control, lattice_x, lattice_y,
                                                            lattice) == DSN_OK);
                        differences += std::memcmp(point, reference, sizeof point) != 0;
                        differences += std::memcmp(lattice, lattice_reference, sizeof lattice) != 0;
                        points++;
                    }
                }
                // A tile near the control (its groups of points each by the kernel's point where the lanes
                // read the group's weights, else the groups' walk) against the twins' tile.
                const dsn_grid grid = {int64_t(uint64_t(uint32_t(kind.origin_x) + 7u) << 32) + kOne / 3,
                                       int64_t(uint64_t(uint32_t(kind.origin_y) + 5u) << 32) + kOne / 7,
                                       int64_t(0.606 * double(kOne)),
                                       int64_t(0.35 * double(kOne)),
                                       int64_t(-0.35 * double(kOne)),
                                       int64_t(0.606 * double(kOne))};
                std::vector<int32_t> tile_reference(24 * 5 * channels);
                REQUIRE(dsn_mix_continuous_tile_fixed(&wide_mix, &control.control, &grid, 24, 5,
                                                      tile_reference.data(), nullptr, 0) == DSN_OK);
                for (uint32_t kernel = DSN_KERNEL_DEFAULT;
                     kernel <= dsn_mix_state_of(&mix)->material[0].tile_kernel; kernel++) {
                    const dsn_mix copy = on_kernel(mix, kernel);
                    std::vector<int32_t> tile(tile_reference.size());
                    REQUIRE(dsn_mix_continuous_tile_fixed(&copy, &control.control, &grid, 24, 5, tile.data(),
                                                          nullptr, 0) == DSN_OK);
                    differences += tile != tile_reference;
                }
            }
            CHECK(differences == 0);
            CHECK(points >= 840);
            // most points take the lanes; most of those by a periodic x's wrap (a sixth) do not
            CHECK(laned >= 580);
            CHECK(laned <= 740);
        }
    }
}

TEST_CASE("mix: lattice tiles where the weights mix are their points: runs of every length, bands of every "
          "height, periods, the int32 sign change") {
    // Without scratch a mixed lattice tile is summed in runs of up to 32 points per row, each impulse
    // splatted over the points of the run it reaches; a period that does not divide 2^32 breaks the run at
    // the sign change. With scratch it goes in bands of as many rows as the scratch holds (each impulse
    // splatted over the band), but across such a sign change. Three materials of three sizes (grey and
    // RGB, 8 and 16 bits), weights changing every 2 texels; scratch of every size that changes the bands,
    // and misaligned.
    auto a = make_noise(random_texton_asset(3, 4, 8, 41), 11, 0, 13, 0);
    auto b = make_noise(random_texton_asset(1, 9, 16, 42), 12);
    auto c = make_noise(random_texton_asset(3, 2, 8, 43), 13);
    const dsn_mix mix = make_mix({&a->noise, &b->noise, &c->noise});
    Control varying(
        3, 7, 6, 1,
        [](uint32_t i, uint32_t j) {
            return std::vector<uint8_t>{uint8_t(i * 71 % 256), uint8_t((j * 90 + 7 * i) % 256),
                                        uint8_t((i + j) % 3 == 0 ? 0 : 140)};
        },
        DSN_MIX_PERIODIC_X | DSN_MIX_PERIODIC_Y);
    const struct {
        int32_t x0, y0;
        uint32_t width, height;
    } windows[] = {{INT32_MAX - 40, 5, 83, 3},
                   {INT32_MAX - 3, -2, 7, 4},
                   {-17, INT32_MIN, 33, 2},
                   {100, 7, 1, 5},
                   {0, 0, 32, 2},
                   {-64, 31, 65, 1}};
    size_t differences = 0, points = 0;
    for (const auto &window : windows) {
        CAPTURE(window.x0);
        CAPTURE(window.width);
        std::vector<int32_t> expected(size_t(window.width) * window.height * 3);
        for (uint32_t j = 0; j < window.height; j++)
            for (uint32_t i = 0; i < window.width; i++, points++)
                REQUIRE(dsn_mix_lattice_point_fixed(&mix, &varying.control, int32_t(uint32_t(window.x0) + i),
                                                    int32_t(uint32_t(window.y0) + j),
                                                    &expected[(size_t(j) * window.width + i) * 3]) == DSN_OK);
        // A band row holds 7 values a point (3 + 1 + 3 channels), 4 bytes each.
        const size_t row_bytes = size_t(window.width) * 7 * 4;
        const size_t full = dsn_mix_lattice_tile_scratch_size(&mix, window.width, window.height);
        CHECK(full >= row_bytes * window.height);
        std::vector<unsigned char> scratch(full + 1);
        for (const size_t size : {size_t(0), row_bytes - 1, row_bytes, 2 * row_bytes + 3, full}) {
            CAPTURE(size);
            for (const size_t misaligned : {size_t(0), size_t(1)}) {
                unsigned char *start = scratch.data() + misaligned;
                std::vector<int32_t> tile(expected.size());
                std::vector<uint8_t> bytes(expected.size());
                REQUIRE(dsn_mix_lattice_tile_fixed(&mix, &varying.control, window.x0, window.y0, window.width,
                                                   window.height, tile.data(), start, size) == DSN_OK);
                REQUIRE(dsn_mix_lattice_tile_u8(&mix, &varying.control, window.x0, window.y0, window.width,
                                                window.height, bytes.data(), start, size) == DSN_OK);
                for (size_t at = 0; at < expected.size(); at++) {
                    differences += tile[at] != expected[at];
                    differences += bytes[at] != dsn_fixed_to_u8(expected[at]);
                }
            }
        }
    }
    CHECK(points == 83 * 3 + 7 * 4 + 33 * 2 + 5 + 64 + 65);
    CHECK(differences == 0);
}

TEST_CASE("mix: lattice tiles whose weights are uniform over a band go by material passes or mixed strips, "
          "every kernel, the bits of their points") {
    // A band whose weights are the same over its reach is the sum of one lattice tile per material, each
    // from the impulses whose hashes draw that material, normalized from its weighted offset (the strip
    // path for 8-bit textons, the 32-bit one for 16-bit ones); where two 8-bit materials of the mix's
    // channels are drawn, the kernel's mixed strips instead (the whole tile where its weights are uniform,
    // with or without scratch); the other bands are walked. Four materials of four sizes (RGB and grey, 8
    // and 16 bits) on a process with a period; weights constant (two 8-bit RGB: mixed strips; RGB with
    // grey, and 8- with 16-bit RGB: passes) and in horizontal bands 32 texels tall (one material alone,
    // three mixed, two 8-bit RGB), whose tile bands are uniform or not; no scratch, scratch for whole
    // bands and for 1, 5 and 40 rows (misaligned: a walked band is at most 32 of them); every kernel this
    // CPU runs; fixed, u8 and float outputs.
    const FourMaterials materials(51);
    const dsn_mix &mix = materials.mix;
    const Control even = constant({128, 128, 0, 0}), one_zero = constant({200, 0, 55, 0}),
                  wide = constant({100, 0, 0, 155});
    const Control banded(4, 1, 10, 5, [](uint32_t, uint32_t j) {
        return j < 3   ? std::vector<uint8_t>{255, 0, 0, 0}
               : j < 6 ? std::vector<uint8_t>{90, 60, 105, 0}
                       : std::vector<uint8_t>{140, 0, 115, 0};
    });
    const int32_t x0 = -70, y0 = 3;
    const uint32_t width = 150, height = 300;
    const size_t row = size_t(width) * 10 * 4; // each material's values: 3 + 1 + 3 + 3, 4 bytes each
    const size_t full = dsn_mix_lattice_tile_scratch_size(&mix, width, height);
    CHECK(full >= 128 * row);
    std::vector<unsigned char> scratch(full + 8);
    size_t differences = 0, tiles = 0;
    for (const Control *control : {&even, &one_zero, &wide, &banded}) {
        std::vector<int32_t> expected(size_t(width) * height * 3);
        for (uint32_t j = 0; j < height; j++)
            for (uint32_t i = 0; i < width; i++)
                REQUIRE(dsn_mix_lattice_point_fixed(&mix, &control->control, x0 + int32_t(i), y0 + int32_t(j),
                                                    &expected[(size_t(j) * width + i) * 3]) == DSN_OK);
        for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_mix_state_of(&mix)->material[0].tile_kernel;
             kernel++) {
            CAPTURE(kernel);
            const dsn_mix copy = on_kernel(mix, kernel);
            for (const size_t size : {size_t(0), full, row + 3, 5 * row + 3, 40 * row + 3}) {
                CAPTURE(size);
                unsigned char *start = scratch.data() + (size == full ? 0 : 1);
                std::vector<int32_t> tile(expected.size());
                std::vector<uint8_t> bytes(expected.size());
                std::vector<float> floats(expected.size());
                REQUIRE(dsn_mix_lattice_tile_fixed(&copy, &control->control, x0, y0, width, height,
                                                   tile.data(), start, size) == DSN_OK);
                REQUIRE(dsn_mix_lattice_tile_u8(&copy, &control->control, x0, y0, width, height, bytes.data(),
                                                start, size) == DSN_OK);
                REQUIRE(dsn_mix_lattice_tile_float(&copy, &control->control, x0, y0, width, height,
                                                   floats.data(), start, size) == DSN_OK);
                differences += output_differences(expected, tile, bytes, floats);
                tiles++;
            }
        }
    }
    CHECK(tiles >= 20);
    CHECK(differences == 0);
}

TEST_CASE("mix: a lattice tile of two materials of one texton size, listed from one walk, every kernel, the "
          "bits of its points") {
    // The mixed strips list both materials' impulses from one walk where their textons have one size
    // (tile_mix.h); RGB and grey, 50/50 and uneven, a period crossing the tile, no scratch.
    for (const uint32_t channels : {3u, 1u}) {
        auto a = make_noise(random_texton_asset(channels, 12, 8, 71), 51, 0, 0, 37);
        auto b = make_noise(with_means(random_texton_asset(channels, 12, 8, 72), 1 << 22, 0, -(1 << 22)), 52);
        const dsn_mix mix = make_mix({&a->noise, &b->noise});
        const int32_t x0 = 1000, y0 = -20;
        const uint32_t width = 140, height = 90;
        size_t differences = 0, tiles = 0;
        const Control controls[] = {constant({128, 128}), constant({30, 225})};
        for (const Control &control : controls) {
            std::vector<int32_t> expected(size_t(width) * height * channels);
            for (uint32_t j = 0; j < height; j++)
                for (uint32_t i = 0; i < width; i++)
                    REQUIRE(
                        dsn_mix_lattice_point_fixed(&mix, &control.control, x0 + int32_t(i), y0 + int32_t(j),
                                                    &expected[(size_t(j) * width + i) * channels]) == DSN_OK);
            for (uint32_t kernel = DSN_KERNEL_DEFAULT;
                 kernel <= dsn_mix_state_of(&mix)->material[0].tile_kernel; kernel++) {
                const dsn_mix copy = on_kernel(mix, kernel);
                std::vector<int32_t> tile(expected.size());
                std::vector<uint8_t> bytes(expected.size());
                REQUIRE(dsn_mix_lattice_tile_fixed(&copy, &control.control, x0, y0, width, height,
                                                   tile.data(), nullptr, 0) == DSN_OK);
                REQUIRE(dsn_mix_lattice_tile_u8(&copy, &control.control, x0, y0, width, height, bytes.data(),
                                                nullptr, 0) == DSN_OK);
                differences += output_differences(expected, tile, bytes, {});
                tiles++;
            }
        }
        CHECK(tiles >= 2);
        CHECK(differences == 0);
    }
}

TEST_CASE("mix: continuous tiles whose weights are uniform go by material splats, every kernel, the bits "
          "of their points") {
    // Where the weights are the same over a continuous tile's reach, each material's impulses (those whose
    // hashes draw it) are splatted with its texton into its own block sums, normalized from its weighted
    // offset, and summed. Four materials (RGB and grey, 8 and 16 bits, 8-bit ones from cell records for
    // the first two drawn) on a process with a period; two, three and four drawn; a rotated and a
    // magnified grid; the scratch asked for (misaligned) and too little (the groups then go); every
    // kernel this CPU runs; fixed, u8 and float outputs.
    const FourMaterials materials(61);
    const dsn_mix &mix = materials.mix;
    const Control controls[] = {constant({128, 128, 0, 0}), constant({200, 0, 55, 0}),
                                constant({0, 90, 80, 70}), constant({60, 61, 62, 63})};
    const int64_t one = kOne;
    const dsn_grid grids[] = {{-40 * one + 777, 3 * one, int64_t(0.61 * double(one)),
                               int64_t(0.35 * double(one)), -int64_t(0.35 * double(one)),
                               int64_t(0.61 * double(one))},
                              {5 * one + 99, -7 * one, one / 3, 0, 0, one / 3}};
    const uint32_t width = 90, height = 70;
    size_t differences = 0, tiles = 0;
    for (const dsn_grid &grid : grids)
        for (const Control &control : controls) {
            std::vector<int32_t> expected(size_t(width) * height * 3);
            for (uint32_t j = 0; j < height; j++)
                for (uint32_t i = 0; i < width; i++) {
                    int64_t x, y;
                    dsn_test::grid_point(grid, i, j, &x, &y);
                    REQUIRE(dsn_mix_continuous_point_fixed(&mix, &control.control, x, y,
                                                           &expected[(size_t(j) * width + i) * 3]) == DSN_OK);
                }
            const size_t full = dsn_mix_continuous_tile_scratch_size(&mix, &grid, width, height);
            REQUIRE(full > 0);
            std::vector<unsigned char> scratch(full + 1);
            for (uint32_t kernel = DSN_KERNEL_DEFAULT;
                 kernel <= dsn_mix_state_of(&mix)->material[0].tile_kernel; kernel++) {
                CAPTURE(kernel);
                const dsn_mix copy = on_kernel(mix, kernel);
                for (const size_t size : {full, full / 2}) {
                    std::vector<int32_t> tile(expected.size());
                    std::vector<uint8_t> bytes(expected.size());
                    std::vector<float> floats(expected.size());
                    unsigned char *start = scratch.data() + 1;
                    REQUIRE(dsn_mix_continuous_tile_fixed(&copy, &control.control, &grid, width, height,
                                                          tile.data(), start, size) == DSN_OK);
                    REQUIRE(dsn_mix_continuous_tile_u8(&copy, &control.control, &grid, width, height,
                                                       bytes.data(), start, size) == DSN_OK);
                    REQUIRE(dsn_mix_continuous_tile_float(&copy, &control.control, &grid, width, height,
                                                          floats.data(), start, size) == DSN_OK);
                    differences += output_differences(expected, tile, bytes, floats);
                    tiles++;
                }
            }
        }
    CHECK(tiles >= 16);
    CHECK(differences == 0);
}

TEST_CASE("mix: continuous tiles and batches of nearby points, walked in groups, are their points") {
    // Up to 16 points within 32 texels of each other are walked at once (a tile's row, a batch's
    // neighbours); on a periodic axis a group whose window crosses the int32 sign change goes point by
    // point. Periods of 13 and 29 texels, which do not divide 2^32, around that change and elsewhere.
    auto a = make_noise(random_texton_asset(3, 4, 8, 51), 21, 0, 13, 29);
    auto b = make_noise(random_texton_asset(1, 7, 16, 52), 22);
    const dsn_mix mix = make_mix({&a->noise, &b->noise});
    Control varying(
        2, 5, 7, 1,
        [](uint32_t i, uint32_t j) {
            return std::vector<uint8_t>{uint8_t(i * 61 % 256), uint8_t((j * 45 + 3 * i) % 256)};
        },
        DSN_MIX_PERIODIC_Y);
    std::mt19937_64 random(77);
    size_t differences = 0, points = 0;
    const int64_t centres[][2] = {{int64_t(INT32_MAX) * kOne, 5 * kOne},
                                  {-3 * kOne, int64_t(INT32_MIN) * kOne},
                                  {1000 * kOne + kOne / 3, -777 * kOne}};
    for (const auto &centre : centres) {
        // a batch of 40 points scattered over 20 x 20 texels around the centre
        std::vector<int64_t> xs, ys;
        for (int k = 0; k < 40; k++) {
            xs.push_back(
                int64_t(uint64_t(centre[0]) + (random() >> 32) * 20 - uint64_t(10) * uint64_t(kOne)));
            ys.push_back(
                int64_t(uint64_t(centre[1]) + (random() >> 32) * 20 - uint64_t(10) * uint64_t(kOne)));
        }
        std::vector<int32_t> batch(xs.size() * 3);
        REQUIRE(dsn_mix_continuous_batch_fixed(&mix, &varying.control, xs.data(), ys.data(),
                                               uint32_t(xs.size()), batch.data()) == DSN_OK);
        for (size_t k = 0; k < xs.size(); k++, points++) {
            int32_t point[3];
            REQUIRE(dsn_mix_continuous_point_fixed(&mix, &varying.control, xs[k], ys[k], point) == DSN_OK);
            for (size_t c = 0; c < 3; c++) differences += batch[k * 3 + c] != point[c];
        }
        // a tile rotated by 30 degrees at 0.7 texel per pixel from 12 texels before the centre
        const dsn_grid grid = {int64_t(uint64_t(centre[0]) - uint64_t(12 * kOne)),
                               int64_t(uint64_t(centre[1]) - uint64_t(12 * kOne)),
                               int64_t(0.606 * double(kOne)),
                               int64_t(0.35 * double(kOne)),
                               int64_t(-0.35 * double(kOne)),
                               int64_t(0.606 * double(kOne))};
        const uint32_t width = 37, height = 9;
        std::vector<int32_t> tile(width * height * 3);
        REQUIRE(dsn_mix_continuous_tile_fixed(&mix, &varying.control, &grid, width, height, tile.data(),
                                              nullptr, 0) == DSN_OK);
        for (uint32_t j = 0; j < height; j++)
            for (uint32_t i = 0; i < width; i++, points++) {
                const int64_t x = int64_t(uint64_t(grid.origin_x) + i * uint64_t(grid.column_step_x) +
                                          j * uint64_t(grid.row_step_x));
                const int64_t y = int64_t(uint64_t(grid.origin_y) + i * uint64_t(grid.column_step_y) +
                                          j * uint64_t(grid.row_step_y));
                int32_t point[3];
                REQUIRE(dsn_mix_continuous_point_fixed(&mix, &varying.control, x, y, point) == DSN_OK);
                for (size_t c = 0; c < 3; c++)
                    differences += tile[(size_t(j) * width + i) * 3 + c] != point[c];
            }
    }
    CHECK(points == 3 * (40 + 37 * 9));
    CHECK(differences == 0);
}

TEST_CASE("mix: one material's weights give the same bits by its own evaluators and by the mix's walk") {
    // Material 1 differs from material 0 in size, bits and density: the mix's walk (taken where the
    // weights differ from sample to sample, here (0, 255) and (0, 100): still material 1's alone) and
    // material 1's own evaluators on material 0's impulses (taken where the weights are the same all
    // around) must agree bit for bit.
    for (uint32_t period : {0u, 29u}) {
        auto lead = make_noise(random_texton_asset(3, 6, 8, 81), 31, 25u << 16, period, 0);
        auto other =
            make_noise(with_means(random_texton_asset(3, 9, 16, 82), 1 << 23, 1 << 21, 0), 32, 7u << 16);
        auto grey = make_noise(random_texton_asset(1, 4, 8, 83), 33);
        const dsn_mix mix = make_mix({&lead->noise, &other->noise, &grey->noise});
        const Control uniform = constant({0, 255, 0});
        const Control varying(
            3, 5, 4, 1,
            [](uint32_t i, uint32_t j) {
                return std::vector<uint8_t>{0, uint8_t((i + j) % 2 ? 255 : 100), 0};
            },
            DSN_MIX_PERIODIC_X | DSN_MIX_PERIODIC_Y);
        std::vector<int64_t> xs, ys;
        renderer_points(90 + period, 300, &xs, &ys);
        size_t differences = 0;
        for (size_t k = 0; k < xs.size(); k++) {
            int32_t first[3], second[3];
            dsn_mix_continuous_point_fixed(&mix, &uniform.control, xs[k], ys[k], first);
            dsn_mix_continuous_point_fixed(&mix, &varying.control, xs[k], ys[k], second);
            differences += std::memcmp(first, second, sizeof first) != 0;
            const int32_t x = int32_t(uint32_t(uint64_t(xs[k]) >> 32)),
                          y = int32_t(uint32_t(uint64_t(ys[k]) >> 32));
            dsn_mix_lattice_point_fixed(&mix, &uniform.control, x, y, first);
            dsn_mix_lattice_point_fixed(&mix, &varying.control, x, y, second);
            differences += std::memcmp(first, second, sizeof first) != 0;
        }
        CHECK(differences == 0);
        // The grey material alone: its value in each of the mix's three channels.
        const Control on_grey = constant({0, 0, 9});
        const Control grey_varying(3, 3, 3, 0, [](uint32_t i, uint32_t) {
            return std::vector<uint8_t>{0, 0, uint8_t(1 + i)};
        });
        for (size_t k = 0; k < 40; k++) {
            int32_t first[3], second[3];
            dsn_mix_continuous_point_fixed(&mix, &on_grey.control, xs[k], ys[k], first);
            dsn_mix_continuous_point_fixed(&mix, &grey_varying.control, xs[k], ys[k], second);
            CHECK(std::memcmp(first, second, sizeof first) == 0);
            CHECK((first[0] == first[1] && first[1] == first[2]));
        }
        // Tiles: with scratch a one-material tile is that material's tile (splatted or by strips); the
        // same pixels point by point.
        const int64_t one = kOne;
        const dsn_grid grid = {-40 * one + 777,
                               3 * one,
                               int64_t(0.61 * double(one)),
                               int64_t(0.35 * double(one)),
                               -int64_t(0.35 * double(one)),
                               int64_t(0.61 * double(one))};
        const uint32_t width = 70, height = 40;
        std::vector<unsigned char> scratch(
            std::max(dsn_mix_continuous_tile_scratch_size(&mix, &grid, width, height),
                     dsn_mix_lattice_tile_scratch_size(&mix, width, height)));
        CHECK(scratch.size() > 0);
        std::vector<int32_t> fast(width * height * 3), slow(fast.size());
        std::vector<float> fast_float(fast.size()), slow_float(fast.size());
        size_t tile_differences = 0;
        for (int lattice = 0; lattice < 2; lattice++) {
            if (lattice) {
                REQUIRE(dsn_mix_lattice_tile_fixed(&mix, &uniform.control, -30, 77, width, height,
                                                   fast.data(), scratch.data(), scratch.size()) == DSN_OK);
                REQUIRE(dsn_mix_lattice_tile_fixed(&mix, &varying.control, -30, 77, width, height,
                                                   slow.data(), nullptr, 0) == DSN_OK);
                REQUIRE(dsn_mix_lattice_tile_float(&mix, &uniform.control, -30, 77, width, height,
                                                   fast_float.data(), scratch.data(),
                                                   scratch.size()) == DSN_OK);
                REQUIRE(dsn_mix_lattice_tile_float(&mix, &uniform.control, -30, 77, width, height,
                                                   slow_float.data(), nullptr, 0) == DSN_OK);
            } else {
                REQUIRE(dsn_mix_continuous_tile_fixed(&mix, &uniform.control, &grid, width, height,
                                                      fast.data(), scratch.data(), scratch.size()) == DSN_OK);
                REQUIRE(dsn_mix_continuous_tile_fixed(&mix, &varying.control, &grid, width, height,
                                                      slow.data(), nullptr, 0) == DSN_OK);
                REQUIRE(dsn_mix_continuous_tile_float(&mix, &uniform.control, &grid, width, height,
                                                      fast_float.data(), scratch.data(),
                                                      scratch.size()) == DSN_OK);
                REQUIRE(dsn_mix_continuous_tile_float(&mix, &uniform.control, &grid, width, height,
                                                      slow_float.data(), nullptr, 0) == DSN_OK);
            }
            for (size_t i = 0; i < fast.size(); i++) {
                tile_differences += fast[i] != slow[i];
                tile_differences += fast_float[i] != slow_float[i];
                tile_differences += fast_float[i] != dsn_fixed_to_float(fast[i]);
            }
        }
        CHECK(tile_differences == 0);
    }
}

TEST_CASE("mix: u8 outputs and batches are the points' values") {
    auto a = make_noise(random_texton_asset(3, 5, 8, 91), 1);
    auto b = make_noise(random_texton_asset(1, 6, 16, 92), 2);
    const dsn_mix mix = make_mix({&a->noise, &b->noise});
    const Control ramp(2, 6, 3, 2, [](uint32_t i, uint32_t j) {
        return std::vector<uint8_t>{uint8_t(40 * i), uint8_t(255 - 30 * j)};
    });
    std::vector<int64_t> xs, ys;
    renderer_points(17, 150, &xs, &ys);
    const uint32_t count = uint32_t(xs.size());
    std::vector<int32_t> fixed(count * 3);
    std::vector<float> floats(count * 3);
    std::vector<uint8_t> bytes(count * 3);
    std::vector<double> xd(count), yd(count);
    for (uint32_t k = 0; k < count; k++)
        xd[k] = double(xs[k] >> 20) / 4096.0, yd[k] = double(ys[k] >> 22) / 1024.0;
    REQUIRE(dsn_mix_continuous_batch_fixed(&mix, &ramp.control, xs.data(), ys.data(), count, fixed.data()) ==
            DSN_OK);
    REQUIRE(dsn_mix_continuous_batch_u8(&mix, &ramp.control, xs.data(), ys.data(), count, bytes.data()) ==
            DSN_OK);
    REQUIRE(dsn_mix_continuous_batch_float(&mix, &ramp.control, xd.data(), yd.data(), count, floats.data()) ==
            DSN_OK);
    size_t differences = 0;
    for (uint32_t k = 0; k < count; k++) {
        int32_t point[3];
        uint8_t point_bytes[3];
        float point_floats[3];
        dsn_mix_continuous_point_fixed(&mix, &ramp.control, xs[k], ys[k], point);
        dsn_mix_continuous_point_u8(&mix, &ramp.control, xs[k], ys[k], point_bytes);
        dsn_mix_continuous_point_float(&mix, &ramp.control, xd[k], yd[k], point_floats);
        for (int c = 0; c < 3; c++) {
            differences += fixed[k * 3 + size_t(c)] != point[c];
            differences += bytes[k * 3 + size_t(c)] != dsn_fixed_to_u8(point[c]);
            differences += point_bytes[c] != dsn_fixed_to_u8(point[c]);
            differences += floats[k * 3 + size_t(c)] != point_floats[c];
        }
        const int32_t x = int32_t(uint32_t(uint64_t(xs[k]) >> 32)),
                      y = int32_t(uint32_t(uint64_t(ys[k]) >> 32));
        dsn_mix_lattice_point_fixed(&mix, &ramp.control, x, y, point);
        dsn_mix_lattice_point_u8(&mix, &ramp.control, x, y, point_bytes);
        for (int c = 0; c < 3; c++) differences += point_bytes[c] != dsn_fixed_to_u8(point[c]);
    }
    CHECK(differences == 0);
    // Tiles in u8, with and without scratch, where the weights are one material's and where they mix.
    const Control on_first = constant({3, 0});
    const dsn_grid grid = {-5 * kOne, 7 * kOne + 99, kOne * 3 / 4, kOne / 8, -kOne / 8, kOne * 3 / 4};
    const uint32_t width = 30, height = 20;
    std::vector<unsigned char> scratch(
        std::max(dsn_mix_continuous_tile_scratch_size(&mix, &grid, width, height),
                 dsn_mix_lattice_tile_scratch_size(&mix, width, height)));
    for (const Control *control : {&ramp, &on_first}) {
        std::vector<uint8_t> tile(width * height * 3), tile_lattice(tile.size());
        std::vector<int32_t> reference(tile.size()), reference_lattice(tile.size());
        REQUIRE(dsn_mix_continuous_tile_u8(&mix, &control->control, &grid, width, height, tile.data(),
                                           scratch.data(), scratch.size()) == DSN_OK);
        REQUIRE(dsn_mix_continuous_tile_fixed(&mix, &control->control, &grid, width, height, reference.data(),
                                              nullptr, 0) == DSN_OK);
        REQUIRE(dsn_mix_lattice_tile_u8(&mix, &control->control, -9, 4, width, height, tile_lattice.data(),
                                        scratch.data(), scratch.size()) == DSN_OK);
        REQUIRE(dsn_mix_lattice_tile_fixed(&mix, &control->control, -9, 4, width, height,
                                           reference_lattice.data(), nullptr, 0) == DSN_OK);
        size_t tile_differences = 0;
        for (size_t i = 0; i < tile.size(); i++) {
            tile_differences += tile[i] != dsn_fixed_to_u8(reference[i]);
            tile_differences += tile_lattice[i] != dsn_fixed_to_u8(reference_lattice[i]);
        }
        CHECK(tile_differences == 0);
    }
    // Batch errors: null coordinates with a count, all points zeroed.
    std::vector<int32_t> zeroed(6, 7);
    CHECK(dsn_mix_continuous_batch_fixed(&mix, &ramp.control, nullptr, ys.data(), 2, zeroed.data()) ==
          DSN_ERR_NULL);
    for (int32_t v : zeroed) CHECK(v == 0);
    CHECK(dsn_mix_continuous_batch_fixed(&mix, &ramp.control, nullptr, nullptr, 0, zeroed.data()) == DSN_OK);
}

TEST_CASE(
    "mix: the filtered evaluation: one material's bits, the mix's walk, unfiltered = continuous, tiles") {
    // Two materials with pyramids (of different depths: 16- and 8-bit textons of radius 5 and 7).
    auto lead_fields = random_texton_asset(3, 5, 8, 101);
    lead_fields.pyramid = dsn::texton_pyramid(lead_fields);
    auto other_fields = with_means(random_texton_asset(3, 7, 16, 102), 1 << 23, 3 << 21, 1 << 20);
    other_fields.pyramid = dsn::texton_pyramid(other_fields);
    auto lead = make_noise(lead_fields, 41, 24u << 16);
    auto other = make_noise(other_fields, 42);
    const dsn_mix mix = make_mix({&lead->noise, &other->noise});
    const Control on_lead = constant({200, 0}), on_other = constant({0, 255});
    const Control other_varying(2, 4, 4, 2, [](uint32_t i, uint32_t j) {
        return std::vector<uint8_t>{0, uint8_t((i + j) % 2 ? 255 : 90)};
    });
    const Control ramp(2, 4, 3, 3, [](uint32_t i, uint32_t j) {
        return std::vector<uint8_t>{uint8_t(60 * i), uint8_t(255 - 60 * i + 3 * j)};
    });
    // Minifications by 1.5, 3 and 6 (levels of detail about 0.6, 1.6, 2.6), one anisotropic by 4:1.
    const dsn_footprint footprints[] = {{kOne * 3 / 2, 0, 0, kOne * 3 / 2, 1},
                                        {3 * kOne, kOne / 3, -kOne / 3, 3 * kOne, 4},
                                        {6 * kOne, 0, 0, 6 * kOne, 1},
                                        {4 * kOne, 0, 0, kOne, 8}};
    std::vector<int64_t> xs, ys;
    renderer_points(103, 40, &xs, &ys);
    size_t differences = 0;
    for (const dsn_footprint &footprint : footprints)
        for (size_t k = 0; k < xs.size(); k++) {
            int32_t own[3], mixed[3], varying[3];
            REQUIRE(dsn_filtered_point_fixed(&lead->noise, xs[k], ys[k], &footprint, own) == DSN_OK);
            REQUIRE(dsn_mix_filtered_point_fixed(&mix, &on_lead.control, xs[k], ys[k], &footprint, mixed) ==
                    DSN_OK);
            differences += std::memcmp(own, mixed, sizeof own) != 0;
            // Material 1 alone, by its own filtered point (uniform weights) and by the mix's walk.
            dsn_mix_filtered_point_fixed(&mix, &on_other.control, xs[k], ys[k], &footprint, mixed);
            dsn_mix_filtered_point_fixed(&mix, &other_varying.control, xs[k], ys[k], &footprint, varying);
            differences += std::memcmp(varying, mixed, sizeof mixed) != 0;
        }
    CHECK(differences == 0);
    // A footprint of at most one texel: the continuous mix's bits, where the weights mix.
    const dsn_footprint unfiltered = {kOne / 2, 0, 0, kOne / 2, 16};
    for (size_t k = 0; k < xs.size(); k++) {
        int32_t filtered[3], continuous[3];
        dsn_mix_filtered_point_fixed(&mix, &ramp.control, xs[k], ys[k], &unfiltered, filtered);
        dsn_mix_continuous_point_fixed(&mix, &ramp.control, xs[k], ys[k], continuous);
        CHECK(std::memcmp(filtered, continuous, sizeof filtered) == 0);
    }
    // Slightly minified (a level of detail of a few 1/256), the filtered mix stays close to the continuous
    // one: the level-1 blend weight b <= 4/256 times the difference of the two levels' values, which these
    // points keep under 2^11 units (1499 measured); a filtered walk whose impulses picked other materials
    // than the continuous walk's would differ by whole impulses' values (over 10^5 units, measured with the
    // pick's hash moved by one impulse).
    const dsn_footprint slight = {int64_t(1.006 * double(kOne)), 0, 0, int64_t(1.006 * double(kOne)), 1};
    int32_t lod_q8;
    uint32_t taps;
    REQUIRE(dsn_filter_level(&lead->noise, &slight, &lod_q8, &taps) == DSN_OK);
    REQUIRE((lod_q8 >= 1 && lod_q8 <= 4 && taps == 1));
    int32_t largest = 0;
    for (size_t k = 0; k < xs.size(); k++) {
        int32_t filtered[3], continuous[3];
        dsn_mix_filtered_point_fixed(&mix, &ramp.control, xs[k], ys[k], &slight, filtered);
        dsn_mix_continuous_point_fixed(&mix, &ramp.control, xs[k], ys[k], continuous);
        for (int c = 0; c < 3; c++) largest = std::max(largest, std::abs(filtered[c] - continuous[c]));
    }
    INFO("largest difference " << largest);
    CHECK(largest < 2048);
    // Tiles equal their points (the grid's steps are the footprint), fixed, float and u8.
    const dsn_grid grid = {-7 * kOne + 321, 11 * kOne, 2 * kOne, kOne / 2, -kOne / 2, 2 * kOne};
    const uint32_t width = 9, height = 6, max_taps = 2;
    const dsn_footprint grid_footprint = {grid.column_step_x, grid.column_step_y, grid.row_step_x,
                                          grid.row_step_y, max_taps};
    std::vector<unsigned char> scratch(
        dsn_mix_filtered_tile_scratch_size(&mix, &grid, max_taps, width, height));
    for (const Control *control : {&ramp, &on_other}) {
        std::vector<int32_t> tile(width * height * 3);
        std::vector<float> floats(tile.size());
        std::vector<uint8_t> bytes(tile.size());
        REQUIRE(dsn_mix_filtered_tile_fixed(&mix, &control->control, &grid, max_taps, width, height,
                                            tile.data(), scratch.data(), scratch.size()) == DSN_OK);
        REQUIRE(dsn_mix_filtered_tile_float(&mix, &control->control, &grid, max_taps, width, height,
                                            floats.data(), nullptr, 0) == DSN_OK);
        REQUIRE(dsn_mix_filtered_tile_u8(&mix, &control->control, &grid, max_taps, width, height,
                                         bytes.data(), scratch.data(), scratch.size()) == DSN_OK);
        size_t tile_differences = 0;
        for (uint32_t j = 0; j < height; j++)
            for (uint32_t i = 0; i < width; i++) {
                int32_t point[3];
                const int64_t x = int64_t(uint64_t(grid.origin_x) + i * uint64_t(grid.column_step_x) +
                                          j * uint64_t(grid.row_step_x));
                const int64_t y = int64_t(uint64_t(grid.origin_y) + i * uint64_t(grid.column_step_y) +
                                          j * uint64_t(grid.row_step_y));
                dsn_mix_filtered_point_fixed(&mix, &control->control, x, y, &grid_footprint, point);
                for (int c = 0; c < 3; c++) {
                    const size_t at = (j * width + i) * 3 + size_t(c);
                    tile_differences += tile[at] != point[c];
                    tile_differences += floats[at] != dsn_fixed_to_float(point[c]);
                    tile_differences += bytes[at] != dsn_fixed_to_u8(point[c]);
                }
            }
        CHECK(tile_differences == 0);
    }
    // Far minified, a constant 50/50 mix fades to the average of the means (each material's half rounded).
    const Control half = constant({128, 128});
    const dsn_footprint far = {4096 * kOne, 0, 0, 4096 * kOne, 1};
    int32_t faded[3];
    REQUIRE(dsn_mix_filtered_point_fixed(&mix, &half.control, 5 * kOne, 9 * kOne, &far, faded) == DSN_OK);
    for (int c = 0; c < 3; c++) {
        const double expected = (lead_fields.mean[c] + other_fields.mean[c]) / 2.0 / 256.0;
        CHECK(std::fabs(faded[c] - expected) <= 1.0);
    }
    // Errors: a bad footprint, and a lattice-baked material.
    int32_t out[3] = {7, 7, 7};
    dsn_footprint no_taps = footprints[0];
    no_taps.max_taps = 0;
    CHECK(dsn_mix_filtered_point_fixed(&mix, &half.control, 0, 0, &no_taps, out) == DSN_ERR_ARGUMENT);
    CHECK((out[0] == 0 && out[1] == 0 && out[2] == 0));
    CHECK(dsn_mix_filtered_point_fixed(&mix, &half.control, 0, 0, nullptr, out) == DSN_ERR_NULL);
    auto lattice_fields = random_texton_asset(3, 4, 8, 104);
    lattice_fields.interpolation = DSN_INTERPOLATION_LATTICE;
    auto lattice = make_noise(lattice_fields, 5);
    const dsn_mix with_lattice = make_mix({&lead->noise, &lattice->noise});
    CHECK(dsn_mix_filtered_point_fixed(&with_lattice, &half.control, 0, 0, &footprints[0], out) ==
          DSN_ERR_CONTINUOUS_MISMATCH);
}

namespace {

// Four materials with pyramids and these means: RGB 8-bit 31 x 31 (period 29 along x), RGB 8-bit 9 x 9,
// RGB 16-bit 13 x 13 and grey 8-bit 13 x 13, their textons and seeds from `seed` on.
struct PyramidMaterials {
    std::unique_ptr<Noise> lead, small, wide, grey;
};

PyramidMaterials pyramid_materials(uint64_t seed, std::array<int32_t, 3> means) {
    auto fields = [&](uint32_t channels, uint32_t radius, uint32_t bits, uint64_t texton_seed) {
        auto made = with_means(random_texton_asset(channels, radius, bits, texton_seed), means[0], means[1],
                               means[2]);
        made.pyramid = dsn::texton_pyramid(made);
        return made;
    };
    PyramidMaterials out;
    out.lead = make_noise(fields(3, 15, 8, seed), seed + 1, 0, 29, 0);
    out.small = make_noise(fields(3, 4, 8, seed + 2), seed + 3);
    out.wide = make_noise(fields(3, 6, 16, seed + 4), seed + 5);
    out.grey = make_noise(fields(1, 6, 8, seed + 6), seed + 7);
    return out;
}

// Levels of detail about 0.6, 1.6 and 2.6, and one anisotropic by 4:1 with 4 taps.
const dsn_footprint pyramid_footprints[] = {{kOne * 3 / 2, 0, 0, kOne * 3 / 2, 1},
                                            {3 * kOne, kOne / 3, -kOne / 3, 3 * kOne, 4},
                                            {6 * kOne, 0, 0, 6 * kOne, 1},
                                            {4 * kOne, 0, 0, kOne, 4}};

} // namespace

TEST_CASE("mix: filtered points where the weights mix read 8-bit levels through every kernel's vector "
          "reads, with the bits of the one-by-one reads") {
    // Every material's impulses are found by one walk and read per material; the AVX2 and AVX-512 copies
    // read 8-bit levels on vectors, the default copy one by one. Three materials with pyramids: RGB 8-bit
    // 31 x 31 (the lead, period 29 along x), RGB 8-bit 9 x 9 with other means and RGB 16-bit 13 x 13 (read
    // one by one in every copy); and a grey 8-bit 13 x 13 with an RGB 8-bit 9 x 9.
    const PyramidMaterials made = pyramid_materials(201, {1 << 22, -(1 << 21), 1 << 20});
    const dsn_mix three = make_mix({&made.lead->noise, &made.small->noise, &made.wide->noise});
    const dsn_mix grey_lead = make_mix({&made.grey->noise, &made.small->noise});
    const Control thirds = constant({90, 80, 85});
    const Control ramp(3, 5, 4, 3, [](uint32_t i, uint32_t j) {
        return std::vector<uint8_t>{uint8_t(50 * i), uint8_t(255 - 50 * i), uint8_t(20 * j)};
    });
    const Control halves = constant({128, 128});
    const Control grey_ramp(2, 5, 4, 3, [](uint32_t i, uint32_t j) {
        return std::vector<uint8_t>{uint8_t(50 * i + j), uint8_t(255 - 50 * i)};
    });
    const struct {
        const dsn_mix *mix;
        const Control *control;
    } cases[] = {{&three, &thirds}, {&three, &ramp}, {&grey_lead, &halves}, {&grey_lead, &grey_ramp}};
    std::vector<int64_t> xs, ys;
    renderer_points(209, 60, &xs, &ys);
    size_t differences = 0, compared = 0, spread = 0;
    for (const auto &mixed : cases)
        for (const dsn_footprint &footprint : pyramid_footprints)
            for (size_t k = 0; k < xs.size(); k++) {
                const dsn_mix reference = on_kernel(*mixed.mix, DSN_KERNEL_DEFAULT);
                int32_t expected[3];
                REQUIRE(dsn_mix_filtered_point_fixed(&reference, &mixed.control->control, xs[k], ys[k],
                                                     &footprint, expected) == DSN_OK);
                spread += expected[0] != expected[1];
                for (uint32_t kernel = DSN_KERNEL_DEFAULT + 1;
                     kernel <= dsn_mix_state_of(mixed.mix)->material[0].tile_kernel; kernel++) {
                    const dsn_mix copy = on_kernel(*mixed.mix, kernel);
                    int32_t value[3];
                    REQUIRE(dsn_mix_filtered_point_fixed(&copy, &mixed.control->control, xs[k], ys[k],
                                                         &footprint, value) == DSN_OK);
                    differences += std::memcmp(value, expected, sizeof value) != 0;
                    compared++;
                }
            }
    INFO(compared << " points compared");
    CHECK(spread > 0); // the values are noise, not a constant
    CHECK(differences == 0);
}

TEST_CASE("mix: filtered points where the weights vary, their materials picked on vectors (the AVX2 and "
          "AVX-512 copies), are the default copy's") {
    // Each tap's impulses listed, then their materials picked 8 at a time from the control where the lanes
    // read it around the tap (kernels.h's dsn_mix_picks_entry), else one by one, as the default copy
    // always does. Controls larger than a tap's reach, samples 1, 4 and 16 texels apart, periodic and
    // clamped axes, origins on both sides; points near the controls, anywhere, and by the wrap of x -
    // origin_x; levels of detail about 0.6 and 1.6 and one anisotropic footprint.
    const PyramidMaterials made = pyramid_materials(401, {1 << 22, -(1 << 21), 1 << 20});
    const dsn_mix three = make_mix({&made.lead->noise, &made.small->noise, &made.wide->noise});
    const dsn_mix two = make_mix({&made.lead->noise, &made.small->noise});
    std::mt19937_64 random(43);
    size_t differences = 0, compared = 0;
    for (const dsn_mix *mix : {&two, &three}) {
        const uint32_t count = dsn_mix_state_of(mix)->count;
        const ControlKind kinds[] = {{90, 70, 0, 0, 5, -7},
                                     {64, 48, 2, DSN_MIX_PERIODIC_X, -40, 13},
                                     {80, 60, 0, DSN_MIX_PERIODIC_X | DSN_MIX_PERIODIC_Y, 3, 2},
                                     {12, 9, 4, DSN_MIX_PERIODIC_Y, 70, -90}};
        for (const ControlKind &kind : kinds) {
            const Control control = varying_control(count, kind);
            for (int k = 0; k < 30; k++) {
                int64_t x, y;
                point_by_control(kind, k, random, &x, &y);
                for (const dsn_footprint &footprint :
                     {pyramid_footprints[0], pyramid_footprints[1], pyramid_footprints[3]}) {
                    const dsn_mix reference = on_kernel(*mix, DSN_KERNEL_DEFAULT);
                    int32_t expected[3];
                    REQUIRE(dsn_mix_filtered_point_fixed(&reference, &control.control, x, y, &footprint,
                                                         expected) == DSN_OK);
                    for (uint32_t kernel = DSN_KERNEL_DEFAULT + 1;
                         kernel <= dsn_mix_state_of(mix)->material[0].tile_kernel; kernel++) {
                        const dsn_mix copy = on_kernel(*mix, kernel);
                        int32_t value[3];
                        REQUIRE(dsn_mix_filtered_point_fixed(&copy, &control.control, x, y, &footprint,
                                                             value) == DSN_OK);
                        differences += std::memcmp(value, expected, sizeof value) != 0;
                        compared++;
                    }
                }
            }
        }
    }
    INFO(compared << " points compared");
    CHECK(differences == 0);
}

TEST_CASE("mix: filtered points where the weights are uniform (each material's sifted walk over the "
          "impulses that draw it) have the bits of the mix's walk") {
    // Equal weights in every sample: the draws and the point's weights depend on the weights' ratios alone,
    // so a control whose samples vary in size only (the mix's walk: its region is not uniform) gives the
    // bits of a constant one (each material's sifted walk, its impulses kept by their hashes). Three
    // materials (thresholds at 1/3 and 2/3; 8-bit 31 x 31 with a period, 8-bit 9 x 9, 16-bit 13 x 13), a
    // grey lead with an RGB material (1/2), and two RGB 8-bit 31 x 31 materials (1/2: listed together in
    // one walk by the AVX2 and AVX-512 copies, each impulse into its material's list), through every
    // kernel.
    const PyramidMaterials made = pyramid_materials(301, {-(1 << 21), 1 << 22, 1 << 20});
    const PyramidMaterials alike = pyramid_materials(311, {1 << 21, -(1 << 20), 1 << 22});
    const dsn_mix three = make_mix({&made.lead->noise, &made.small->noise, &made.wide->noise});
    const dsn_mix grey_lead = make_mix({&made.grey->noise, &made.small->noise});
    const dsn_mix two_alike = make_mix({&made.lead->noise, &alike.lead->noise});
    const Control thirds = constant({70, 70, 70}), halves = constant({200, 200});
    const Control thirds_varying(3, 3, 2, 2, [](uint32_t i, uint32_t j) {
        const uint8_t w = uint8_t((i + j) % 2 ? 70 : 13 + 40 * i);
        return std::vector<uint8_t>{w, w, w};
    });
    const Control halves_varying(2, 3, 2, 2, [](uint32_t i, uint32_t j) {
        const uint8_t w = uint8_t((i + j) % 2 ? 200 : 255 - 70 * i);
        return std::vector<uint8_t>{w, w};
    });
    const struct {
        const dsn_mix *mix;
        const Control *uniform, *varying;
    } cases[] = {{&three, &thirds, &thirds_varying},
                 {&grey_lead, &halves, &halves_varying},
                 {&two_alike, &halves, &halves_varying}};
    std::vector<int64_t> xs, ys;
    renderer_points(309, 50, &xs, &ys);
    size_t differences = 0, compared = 0, spread = 0;
    for (const auto &mixed : cases)
        for (uint32_t kernel = DSN_KERNEL_DEFAULT;
             kernel <= dsn_mix_state_of(mixed.mix)->material[0].tile_kernel; kernel++) {
            const dsn_mix copy = on_kernel(*mixed.mix, kernel);
            for (const dsn_footprint &footprint : pyramid_footprints)
                for (size_t k = 0; k < xs.size(); k++) {
                    int32_t walked[3], kept[3];
                    REQUIRE(dsn_mix_filtered_point_fixed(&copy, &mixed.varying->control, xs[k], ys[k],
                                                         &footprint, walked) == DSN_OK);
                    REQUIRE(dsn_mix_filtered_point_fixed(&copy, &mixed.uniform->control, xs[k], ys[k],
                                                         &footprint, kept) == DSN_OK);
                    differences += std::memcmp(walked, kept, sizeof kept) != 0;
                    spread += kept[0] != kept[1];
                    compared++;
                }
        }
    INFO(compared << " points compared");
    CHECK(spread > 0);
    CHECK(differences == 0);
}

namespace {

// The covariance of one material's continuous noise at a lag, channels c and d (theory above).
double material_covariance(const dsn::AssetFields &fields, int c, int d, double hx, double hy) {
    const auto t = texton_values(fields);
    const int side = int(fields.width);
    double sum = 0;
    for (uint32_t k = 0; k < fields.channels; k++)
        for (uint32_t l = 0; l < fields.channels; l++)
            sum += fields.color_transform[size_t(c) * 3 + k] / 16777216.0 *
                   (fields.color_transform[size_t(d) * 3 + l] / 16777216.0) *
                   bilinear_correlation(t[k], t[l], side, hx, hy);
    return sum;
}

struct Estimate {
    double value = 0, standard_error = 0;
};

Estimate over_batches(const std::vector<double> &per_batch) {
    double mean = 0, square = 0;
    for (double v : per_batch) mean += v;
    mean /= double(per_batch.size());
    for (double v : per_batch) square += (v - mean) * (v - mean);
    return {mean, std::sqrt(square / double(per_batch.size() - 1) / double(per_batch.size()))};
}

} // namespace

TEST_CASE("mix: a constant 50/50 mix has the average mean and covariance, auto- and cross-channel") {
    const auto fields_a = random_texton_asset(3, 5, 8, 41);
    const auto fields_b = with_means(random_texton_asset(3, 5, 8, 42), 3 << 21, 5 << 21, 1 << 20);
    auto a = make_noise(fields_a, 400, 30u << 16);
    auto b = make_noise(fields_b, 401, 30u << 16);
    const dsn_mix mix = make_mix({&a->noise, &b->noise});
    const Control half = constant({128, 128});
    const double lags[][2] = {{0, 0}, {1, 0}, {0, 1}, {3, 2}, {0.5, 0.25}};
    const int lag_count = 5, batches = 20, sites = 600;
    std::vector<double> means[3], covariances[5][3][3];
    std::mt19937_64 random(42);
    for (int batch = 0; batch < batches; batch++) {
        std::vector<std::array<double, 3>> values[5];
        for (int s = 0; s < sites; s++) {
            const int64_t site = int64_t(batch) * sites + s;
            const int64_t x = (site % 1000) * 24 * kOne + int64_t(random() >> 32);
            const int64_t y = (site / 1000) * 24 * kOne + int64_t(random() >> 32);
            for (int h = 0; h < lag_count; h++) {
                int32_t out[3];
                dsn_mix_continuous_point_fixed(&mix, &half.control, x + int64_t(lags[h][0] * double(kOne)),
                                               y + int64_t(lags[h][1] * double(kOne)), out);
                values[h].push_back({out[0] / 65536.0, out[1] / 65536.0, out[2] / 65536.0});
            }
        }
        for (int c = 0; c < 3; c++) {
            double sum = 0;
            for (const auto &v : values[0]) sum += v[size_t(c)];
            means[c].push_back(sum / sites);
        }
        for (int h = 0; h < lag_count; h++)
            for (int c = 0; c < 3; c++)
                for (int d = 0; d < 3; d++) {
                    double sum = 0;
                    for (int s = 0; s < sites; s++)
                        sum += (values[0][size_t(s)][size_t(c)] - means[c].back()) *
                               (values[h][size_t(s)][size_t(d)] - means[d].back());
                    covariances[h][c][d].push_back(sum / (sites - 1));
                }
    }
    for (int c = 0; c < 3; c++) {
        const Estimate mean = over_batches(means[c]);
        const double expected = 0.5 * (fields_a.mean[c] + fields_b.mean[c]) / 16777216.0;
        CHECK(std::fabs(mean.value - expected) < 4 * mean.standard_error);
    }
    for (int h = 0; h < lag_count; h++)
        for (int c = 0; c < 3; c++)
            for (int d = 0; d < 3; d++) {
                const Estimate covariance = over_batches(covariances[h][c][d]);
                const double expected = 0.5 * (material_covariance(fields_a, c, d, lags[h][0], lags[h][1]) +
                                               material_covariance(fields_b, c, d, lags[h][0], lags[h][1]));
                INFO("lag " << h << " channels " << c << d << ": " << covariance.value << " expected "
                            << expected << " +- " << covariance.standard_error);
                CHECK(std::fabs(covariance.value - expected) < 4 * covariance.standard_error);
            }
}

TEST_CASE("mix: across a transition the variance follows the weights' mixture; a crossfade's dips") {
    // Grey materials; the weights go from all A at x = 0 to all B at x = 512 (two samples 512 texels apart).
    const auto fields_a = random_texton_asset(1, 5, 8, 51);
    const auto fields_b = with_means(random_texton_asset(1, 5, 8, 52), 3 << 21, 0, 0);
    auto a = make_noise(fields_a, 500, 30u << 16);
    auto b = make_noise(fields_b, 501, 30u << 16);
    const dsn_mix mix = make_mix({&a->noise, &b->noise});
    const Control ramp(2, 2, 1, 9, [](uint32_t i, uint32_t) {
        return i == 0 ? std::vector<uint8_t>{255, 0} : std::vector<uint8_t>{0, 255};
    });
    const double variance_a = material_covariance(fields_a, 0, 0, 0, 0);
    const double variance_b = material_covariance(fields_b, 0, 0, 0, 0);
    const int rows = 4000;
    std::mt19937_64 random(7);
    for (int at : {64, 256, 448}) {
        const double w = 1.0 - at / 512.0; // material A's weight
        std::vector<double> mixed, faded;
        for (int row = 0; row < rows; row++) {
            const int64_t x = int64_t(at) * kOne + int64_t(random() >> 40);
            const int64_t y = int64_t(row) * 24 * kOne + int64_t(random() >> 32);
            int32_t value, value_a, value_b;
            dsn_mix_continuous_point_fixed(&mix, &ramp.control, x, y, &value);
            dsn_continuous_point_fixed(&a->noise, x, y, &value_a);
            dsn_continuous_point_fixed(&b->noise, x, y, &value_b);
            mixed.push_back(value / 65536.0);
            faded.push_back((w * value_a + (1 - w) * value_b) / 65536.0);
        }
        auto variance = [](const std::vector<double> &v) {
            double mean = 0, square = 0;
            for (double x : v) mean += x;
            mean /= double(v.size());
            for (double x : v) square += (x - mean) * (x - mean);
            return square / double(v.size() - 1);
        };
        const double expected = w * variance_a + (1 - w) * variance_b;
        // The sample variance of n independent values has a standard error of about sqrt(2 / n) of the
        // variance for a near-Gaussian noise (its excess kurtosis here is about 0.1).
        const double standard_error = expected * std::sqrt((2.0 + 0.2) / rows);
        INFO("x " << at << ": mix " << variance(mixed) << " crossfade " << variance(faded) << " expected "
                  << expected);
        CHECK(std::fabs(variance(mixed) - expected) < 4 * standard_error);
        const double crossfade = w * w * variance_a + (1 - w) * (1 - w) * variance_b;
        CHECK(std::fabs(variance(faded) - crossfade) < 4 * crossfade * std::sqrt(2.2 / rows));
        if (at == 256) CHECK(variance(faded) < expected - 8 * standard_error); // the crossfade's dip
    }
}

TEST_CASE("mix: no seam: the largest jump between neighbouring pixels across a transition") {
    const auto fields_a = random_texton_asset(1, 5, 8, 61);
    const auto fields_b = with_means(random_texton_asset(1, 5, 8, 62), 3 << 21, 0, 0);
    auto a = make_noise(fields_a, 600, 30u << 16);
    auto b = make_noise(fields_b, 601, 30u << 16);
    const dsn_mix mix = make_mix({&a->noise, &b->noise});
    // From all A to all B over 8 texels at x in [0, 8].
    const Control step(2, 2, 1, 3, [](uint32_t i, uint32_t) {
        return i == 0 ? std::vector<uint8_t>{255, 0} : std::vector<uint8_t>{0, 255};
    });
    // Segments of 32 texels sampled every 1/8 texel: inside A, across the transition, inside B.
    auto largest_jump = [&](double from) {
        int32_t largest = 0;
        for (int row = 0; row < 200; row++) {
            const int64_t y = int64_t(row) * 24 * kOne + (int64_t(row) * 7919 % 1000) * (kOne / 1000);
            int32_t previous = 0;
            for (int k = 0; k <= 256; k++) {
                int32_t value;
                dsn_mix_continuous_point_fixed(&mix, &step.control,
                                               int64_t(from * double(kOne)) + k * (kOne / 8), y, &value);
                if (k > 0) largest = std::max(largest, std::abs(value - previous));
                previous = value;
            }
        }
        return largest;
    };
    const int32_t inside_a = largest_jump(-80), across = largest_jump(-12), inside_b = largest_jump(60);
    INFO("largest jumps: inside A " << inside_a << ", across " << across << ", inside B " << inside_b);
    CHECK(across <= std::max(inside_a, inside_b));
}

TEST_CASE("mix: bad input gets an error code and zeroed output, never undefined behaviour") {
    auto a = make_noise(random_texton_asset(3, 4, 8, 71), 1);
    auto grey = make_noise(random_texton_asset(1, 4, 8, 72), 2);
    const dsn_noise *materials[] = {&a->noise, &grey->noise, &a->noise, &grey->noise, &a->noise};
    dsn_mix mix;
    CHECK(dsn_mix_init(nullptr, materials, 2) == DSN_ERR_NULL);
    CHECK(dsn_mix_init(&mix, nullptr, 2) == DSN_ERR_NULL);
    CHECK(dsn_mix_init(&mix, materials, 0) == DSN_ERR_ARGUMENT);
    CHECK(dsn_mix_init(&mix, materials, DSN_MIX_MAX_MATERIALS + 1) == DSN_ERR_ARGUMENT);
    CHECK(dsn_mix_channels(&mix) == 0);
    dsn_noise unconfigured;
    std::memset(&unconfigured, 0x5A, sizeof unconfigured);
    const dsn_noise *with_garbage[] = {&a->noise, &unconfigured};
    CHECK(dsn_mix_init(&mix, with_garbage, 2) == DSN_ERR_NULL);
    const dsn_noise *with_null[] = {&a->noise, nullptr};
    CHECK(dsn_mix_init(&mix, with_null, 2) == DSN_ERR_NULL);
    // A material with a histogram mapping is refused; configured without it, it mixes.
    auto mapped_fields = random_texton_asset(1, 4, 8, 73);
    mapped_fields.histogram.entry_count = 5;
    mapped_fields.histogram.step_shift = 1;
    mapped_fields.histogram.input_low_q16 = -65536;
    mapped_fields.histogram.tables = {-4000, -2000, 0, 2000, 4000};
    for (int i = 1; i < 9; i++) mapped_fields.histogram.rotation[i] = 0;
    auto mapped = make_noise(mapped_fields, 3);
    const dsn_noise *with_mapping[] = {&a->noise, &mapped->noise};
    CHECK(dsn_mix_init(&mix, with_mapping, 2) == DSN_ERR_UNSUPPORTED);
    auto unmapped = make_noise(mapped_fields, 3, 0, 0, 0, DSN_FLAG_NO_HISTOGRAM);
    const dsn_noise *without_mapping[] = {&a->noise, &unmapped->noise};
    CHECK(dsn_mix_init(&mix, without_mapping, 2) == DSN_OK);

    // The largest count, and refused calls on a mix that is not configured.
    REQUIRE(dsn_mix_init(&mix, materials, DSN_MIX_MAX_MATERIALS) == DSN_OK);
    std::vector<uint8_t> weights(4 * 3 * 2, 60);
    dsn_mix_control control{weights.data(), 3, 2, 0, 0, 0, 0};
    int32_t out[3] = {7, 7, 7};
    CHECK(dsn_mix_continuous_point_fixed(&mix, &control, 0, 0, out) == DSN_OK);
    dsn_mix zeroed;
    std::memset(&zeroed, 0, sizeof zeroed);
    out[0] = 7;
    CHECK(dsn_mix_continuous_point_fixed(&zeroed, &control, 0, 0, out) == DSN_ERR_NULL);
    CHECK(out[0] == 0);
    dsn_mix altered = mix;
    altered.words[0] ^= 1; // the count
    out[0] = out[1] = out[2] = 7;
    CHECK(dsn_mix_lattice_point_fixed(&altered, &control, 0, 0, out) == DSN_ERR_NULL);
    CHECK(out[0] == 0);

    // Controls out of their ranges.
    auto expect_refused = [&](dsn_mix_control bad, int expected) {
        int32_t values[3] = {7, 7, 7};
        CHECK(dsn_mix_continuous_point_fixed(&mix, &bad, 0, 0, values) == expected);
        CHECK((values[0] == 0 && values[1] == 0 && values[2] == 0));
        std::vector<float> tile(2 * 2 * 3, 1.0f);
        CHECK(dsn_mix_lattice_tile_float(&mix, &bad, 0, 0, 2, 2, tile.data(), nullptr, 0) == expected);
        for (float v : tile) CHECK(v == 0.0f);
    };
    expect_refused({nullptr, 3, 2, 0, 0, 0, 0}, DSN_ERR_NULL);
    expect_refused({weights.data(), 0, 2, 0, 0, 0, 0}, DSN_ERR_ARGUMENT);
    expect_refused({weights.data(), 3, 0, 0, 0, 0, 0}, DSN_ERR_ARGUMENT);
    expect_refused({weights.data(), 65536, 1, 0, 0, 0, 0}, DSN_ERR_ARGUMENT);
    expect_refused({weights.data(), 65535, 65535, 0, 0, 0, 0}, DSN_ERR_ARGUMENT); // past 2^24 samples
    expect_refused({weights.data(), 3, 2, 17, 0, 0, 0}, DSN_ERR_ARGUMENT);
    expect_refused({weights.data(), 3, 2, 0, 0, 0, 4}, DSN_ERR_ARGUMENT);
    CHECK(dsn_mix_continuous_point_fixed(&mix, nullptr, 0, 0, out) == DSN_ERR_NULL);
    CHECK(dsn_mix_continuous_point_fixed(&mix, &control, 0, 0, nullptr) == DSN_ERR_NULL);
    const dsn_grid grid = {0, 0, kOne, 0, 0, kOne};
    std::vector<int32_t> tile(4 * 3, 7);
    CHECK(dsn_mix_continuous_tile_fixed(&mix, &control, nullptr, 2, 2, tile.data(), nullptr, 0) ==
          DSN_ERR_NULL);
    for (int32_t v : tile) CHECK(v == 0);
    tile.assign(4 * 3, 7);
    CHECK(dsn_mix_continuous_tile_fixed(&mix, &control, &grid, 0, 2, tile.data(), nullptr, 0) ==
          DSN_ERR_TILE_SIZE);
    CHECK(dsn_mix_lattice_tile_fixed(&mix, &control, 0, 0, 2, DSN_TILE_MAX_SIDE + 1, tile.data(), nullptr,
                                     0) == DSN_ERR_TILE_SIZE);
    CHECK(tile[0] == 7); // a tile refused for its size is left as it is

    // The continuous functions check every material's mode.
    auto lattice_fields = random_texton_asset(3, 4, 8, 74);
    lattice_fields.interpolation = DSN_INTERPOLATION_LATTICE;
    auto lattice = make_noise(lattice_fields, 5);
    const dsn_noise *with_lattice[] = {&a->noise, &lattice->noise};
    REQUIRE(dsn_mix_init(&mix, with_lattice, 2) == DSN_OK);
    CHECK(dsn_mix_continuous_point_fixed(&mix, &control, 0, 0, out) == DSN_ERR_CONTINUOUS_MISMATCH);
    CHECK(dsn_mix_lattice_point_fixed(&mix, &control, 0, 0, out) == DSN_OK);

    // Float weights.
    CHECK(dsn_mix_weight_from_float(std::nanf("")) == 0);
    CHECK(dsn_mix_weight_from_float(-1.0f) == 0);
    CHECK(dsn_mix_weight_from_float(-0.0f) == 0);
    CHECK(dsn_mix_weight_from_float(0.0f) == 0);
    CHECK(dsn_mix_weight_from_float(1e-30f) == 0);
    CHECK(dsn_mix_weight_from_float(0.5f) == 128); // 127.5 rounds half up
    CHECK(dsn_mix_weight_from_float(0.25f) == 64);
    CHECK(dsn_mix_weight_from_float(0.999f) == 255);
    CHECK(dsn_mix_weight_from_float(1.0f) == 255);
    CHECK(dsn_mix_weight_from_float(7.0f) == 255);
    CHECK(dsn_mix_weight_from_float(INFINITY) == 255);
    for (int i = 0; i <= 1000; i++) {
        const float w = float(i) / 1000.0f;
        CHECK(dsn_mix_weight_from_float(w) == uint8_t(std::floor(255.0 * double(w) + 0.5)));
    }
}
