// histogram_mapping_test.cpp - format 1.2's histogram-preserving output (format.h, "Meaning of the
// mapping"; dsn.h): the writer and the loader agree on the section, the runtime's mapping gives the values
// of the specification's formula (computed here with exact integer division, from the writer's fields
// rather than the file), and every evaluation path (lattice point and tile in every kernel copy,
// continuous point, tile and batch, filtered point and tile, float output) gives the per-point bits with
// a mapping. The Gaussian-space values the formula maps come from the same noise configured with
// DSN_FLAG_NO_HISTOGRAM.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "dsn/gpu.h"
#include "fixtures/test_assets.h"
#include "offline/bake_internal.h"
#include "runtime/core/histogram_map.h"
#include "runtime/kernels/kernels.h"

using dsn_test::LoadedNoise;
using dsn_test::make_config;

namespace {

using Bytes = std::vector<unsigned char>;

// ---- The specification's formula, computed independently: exact floor division, no shifts ----

int64_t floor_divide(int64_t numerator, int64_t denominator) { // denominator > 0
    int64_t quotient = numerator / denominator;
    if (numerator % denominator != 0 && numerator < 0) quotient--;
    return quotient;
}

// round(numerator / denominator), halves up: floor((2 numerator + denominator) / (2 denominator)).
int64_t round_half_up(int64_t numerator, int64_t denominator) {
    return floor_divide(2 * numerator + denominator, 2 * denominator);
}

// X_l of format.h (the level's interpolated table value times 2^d), from the writer's fields.
int64_t reference_read(const dsn::HistogramMapping &m, uint32_t channels, uint32_t level, uint32_t k,
                       int32_t g) {
    const int64_t unit = int64_t(1) << (16 - m.step_shift);
    if (level >= m.level_count) return int64_t(m.expected_q16[k]) * unit;
    int64_t u = int64_t(g) - m.input_low_q16;
    const int64_t top = int64_t(m.entry_count - 1) * unit;
    u = u < 0 ? 0 : u > top ? top : u;
    const int64_t i = u / unit, f = u - i * unit, j = i + 1 < m.entry_count ? i + 1 : m.entry_count - 1;
    const size_t row = (size_t(level) * channels + k) * m.entry_count;
    const int64_t low = m.tables[row + size_t(i)], high = m.tables[row + size_t(j)];
    return (low * unit + (high - low) * f) * 16;
}

// out_c of format.h for Gaussian-space values g, blending `level` and level + 1 with weight blend / 256.
std::vector<int32_t> reference_map(const dsn::HistogramMapping &m, uint32_t channels, const int32_t *g,
                                   uint32_t level = 0, uint32_t blend = 0) {
    const int64_t unit = int64_t(1) << (16 - m.step_shift);
    int64_t v[3] = {0, 0, 0};
    for (uint32_t k = 0; k < channels; k++)
        v[k] = round_half_up(int64_t(256 - blend) * reference_read(m, channels, level, k, g[k]) +
                                 int64_t(blend) * reference_read(m, channels, level + 1, k, g[k]),
                             256 * unit);
    std::vector<int32_t> out(channels);
    for (uint32_t c = 0; c < channels; c++) {
        int64_t sum = int64_t(m.centre[c]) * 65536;
        for (uint32_t k = 0; k < channels; k++) sum += int64_t(m.rotation[c * 3 + k]) * v[k];
        const int64_t value = round_half_up(sum, int64_t(1) << 24);
        out[c] = int32_t(value > INT32_MAX ? INT32_MAX : value < INT32_MIN ? INT32_MIN : value);
    }
    return out;
}

// ---- Mappings ----

// A smooth increasing table per level and channel over [-4, 4] (65 entries, step 1/8): an odd cubic,
// flatter at coarser levels, shifted per channel; a rotation with every entry used, and a centre.
dsn::HistogramMapping smooth_mapping(uint32_t channels, uint32_t levels) {
    dsn::HistogramMapping m;
    m.level_count = levels;
    for (uint32_t l = 0; l < levels; l++)
        for (uint32_t k = 0; k < channels; k++)
            for (uint32_t i = 0; i < m.entry_count; i++) {
                const double x = -4.0 + i / 8.0, flatten = 1.0 - 0.15 * l;
                const double value = flatten * (0.3 * x + 0.05 * x * x * x) + 0.1 * k - 0.2;
                m.tables.push_back(int32_t(std::lround(value * 4096)));
            }
    if (channels == 3) {
        const double P[9] = {0.8, -0.3, 0.2, 0.35, 0.9, -0.1, -0.25, 0.15, 1.05};
        for (int i = 0; i < 9; i++) m.rotation[i] = int32_t(std::lround(P[i] * DSN_Q24_ONE));
    } else {
        m.rotation[0] = int32_t(std::lround(0.7 * DSN_Q24_ONE));
        for (int i = 1; i < 9; i++) m.rotation[i] = 0;
    }
    for (uint32_t c = 0; c < channels; c++) {
        m.centre[c] = int32_t(std::lround((0.45 + 0.05 * c) * DSN_Q24_ONE));
        m.expected_q16[c] = int32_t(-3000 + 1700 * int32_t(c));
    }
    return m;
}

// A step table of 9 entries spanning [0.25, 0.75] (s = 4): -1.5 below 0.5, +2 above, odd shift on the
// grid; the Gaussian-space noise around its mean 0.5 falls on both sides and clamps at both ends.
dsn::HistogramMapping step_mapping(uint32_t channels) {
    dsn::HistogramMapping m;
    m.entry_count = 9;
    m.step_shift = 4;
    m.input_low_q16 = 16384 + 3;
    for (uint32_t k = 0; k < channels; k++)
        for (uint32_t i = 0; i < 9; i++) m.tables.push_back(i < 4 ? -6144 : 8192 - int32_t(k));
    if (channels == 1)
        for (int i = 1; i < 9; i++) m.rotation[i] = 0;
    return m;
}

// Identity-like: entry i is the Gaussian-space value it stands for (s = 0: steps of 1), a 90 degree
// rotation of the first two channels.
dsn::HistogramMapping rotation_mapping(uint32_t channels) {
    dsn::HistogramMapping m;
    m.entry_count = 7;
    m.step_shift = 0;
    m.input_low_q16 = -3 * 65536;
    for (uint32_t k = 0; k < channels; k++)
        for (uint32_t i = 0; i < 7; i++) m.tables.push_back((int32_t(i) - 3) * 4096);
    if (channels == 3) {
        const int32_t one = DSN_Q24_ONE;
        const int32_t P[9] = {0, -one, 0, one, 0, 0, 0, 0, one};
        std::memcpy(m.rotation, P, sizeof P);
    } else {
        m.rotation[0] = -DSN_Q24_ONE; // a mirror: out = -g on the entries' range
        for (int i = 1; i < 9; i++) m.rotation[i] = 0;
    }
    return m;
}

dsn::AssetFields mapped_fields(uint32_t channels, uint32_t bits, bool pyramid, uint64_t seed = 11) {
    dsn::AssetFields fields = dsn_test::synthetic_fields(channels, 31, bits, DSN_SHAPE_RECTANGLE, seed);
    fields.interpolation = DSN_INTERPOLATION_BILINEAR;
    if (pyramid) fields.pyramid = dsn::texton_pyramid(fields);
    fields.histogram = smooth_mapping(channels, uint32_t(1 + fields.pyramid.size()));
    return fields;
}

// The same asset twice: mapped, and with DSN_FLAG_NO_HISTOGRAM (its Gaussian-space values).
struct MappedPair {
    LoadedNoise mapped, gaussian;
    MappedPair(const dsn::AssetFields &fields, uint32_t seed)
        : mapped(fields, make_config(seed)),
          gaussian(fields, make_config(seed, 30, 0, 0, DSN_FLAG_NO_HISTOGRAM)) {}
};

const int64_t kOne = int64_t(1) << 32;

} // namespace

TEST_CASE("histogram: the writer's mapping round-trips through the loader, in a 1.2 file with the flag") {
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u})
            for (bool pyramid : {false, true}) {
                CAPTURE(channels);
                CAPTURE(bits);
                CAPTURE(pyramid);
                const dsn::AssetFields fields = mapped_fields(channels, bits, pyramid);
                const Bytes bytes = dsn::encode_asset(fields);
                CHECK(dsn_read_u16le(&bytes[DSN_OFFSET_VERSION_MINOR]) == DSN_FORMAT_HISTOGRAM_MINOR);
                CHECK(dsn_read_u32le(&bytes[DSN_OFFSET_FLAGS]) == DSN_FLAG_HISTOGRAM);
                dsn_asset asset;
                REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
                const dsn::HistogramMapping &m = fields.histogram;
                CHECK(asset.version_minor == 2);
                CHECK(asset.pyramid_levels == fields.pyramid.size());
                REQUIRE(asset.histogram_table != nullptr);
                CHECK(asset.histogram_entries == m.entry_count);
                CHECK(asset.histogram_levels == m.level_count);
                CHECK(asset.histogram_step_shift == m.step_shift);
                CHECK(asset.histogram_input_low_q16 == m.input_low_q16);
                CHECK(std::memcmp(asset.histogram_rotation, m.rotation, sizeof m.rotation) == 0);
                CHECK(std::memcmp(asset.histogram_centre, m.centre, sizeof m.centre) == 0);
                CHECK(std::memcmp(asset.histogram_expected_q16, m.expected_q16, sizeof m.expected_q16) == 0);
                size_t differences = 0;
                for (size_t i = 0; i < m.tables.size(); i++)
                    differences += dsn_read_i16le(asset.histogram_table + 2 * i) != m.tables[i];
                CHECK(differences == 0);
                // The texton and the pyramid read as without the mapping.
                dsn::AssetFields plain = fields;
                plain.histogram.tables.clear();
                const Bytes plain_bytes = dsn::encode_asset(plain);
                dsn_asset plain_asset;
                REQUIRE(dsn_asset_load(&plain_asset, plain_bytes.data(), plain_bytes.size()) == DSN_OK);
                CHECK(plain_asset.histogram_table == nullptr);
                CHECK(plain_asset.version_minor == (pyramid ? 1u : 0u));
                CHECK(std::memcmp(plain_asset.texton, asset.texton, size_t(31) * 31 * channels * bits / 8) ==
                      0);
            }
}

TEST_CASE("histogram: the writer refuses every field the loader would reject") {
    const dsn::AssetFields good = mapped_fields(1, 8, false);
    REQUIRE_NOTHROW(dsn::encode_asset(good));
    auto refused = [&](void (*spoil)(dsn::AssetFields &)) {
        dsn::AssetFields fields = good;
        spoil(fields);
        CHECK_THROWS_AS(dsn::encode_asset(fields), std::invalid_argument);
    };
    refused([](dsn::AssetFields &f) { f.histogram.entry_count = 1, f.histogram.tables.resize(1); });
    refused([](dsn::AssetFields &f) { f.histogram.entry_count = 1025, f.histogram.tables.resize(1025); });
    refused([](dsn::AssetFields &f) { f.histogram.level_count = 0; });
    refused([](dsn::AssetFields &f) { f.histogram.level_count = 2, f.histogram.tables.resize(130); });
    refused([](dsn::AssetFields &f) { f.histogram.step_shift = 17; });
    refused([](dsn::AssetFields &f) { f.histogram.tables.pop_back(); });
    refused([](dsn::AssetFields &f) { f.histogram.tables[3] = -32768; });
    refused([](dsn::AssetFields &f) { f.histogram.tables[3] = 32768; });
    refused([](dsn::AssetFields &f) { f.histogram.rotation[4] = 1; });
    refused([](dsn::AssetFields &f) { f.histogram.centre[1] = 1; });
    refused([](dsn::AssetFields &f) { f.histogram.expected_q16[2] = 1; });
    refused([](dsn::AssetFields &f) { f.histogram.expected_q16[0] = DSN_HISTOGRAM_EXPECTED_LIMIT + 1; });
    refused([](dsn::AssetFields &f) { f.histogram.expected_q16[0] = -DSN_HISTOGRAM_EXPECTED_LIMIT - 1; });
    dsn::AssetFields limits = good;
    limits.histogram.expected_q16[0] = -DSN_HISTOGRAM_EXPECTED_LIMIT;
    limits.histogram.tables[0] = -32767;
    CHECK_NOTHROW(dsn::encode_asset(limits));
}

TEST_CASE("histogram: the mapping of hand-built tables gives the specification's values exactly") {
    // Literal cases worked by hand: N = 3, s = 0 (d = 16), input_low = -1, T = (-1, 0, 2) in Q3.12,
    // grey rotation 1, centre 0, so out = v.
    dsn::AssetFields fields = dsn_test::synthetic_fields(1, 3, 8, DSN_SHAPE_RECTANGLE, 1);
    dsn::HistogramMapping &m = fields.histogram;
    m.entry_count = 3, m.step_shift = 0, m.input_low_q16 = -65536;
    for (int i = 1; i < 9; i++) m.rotation[i] = 0;
    m.tables = {-4096, 0, 8192};
    Bytes bytes = dsn::encode_asset(fields);
    dsn_asset asset;
    REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    struct Case {
        int32_t g, out;
    };
    // Each case's value mapped by the runtime is the expected one and the reference formula's.
    auto check_cases = [&](const auto &list) {
        for (const Case &c : list) {
            int32_t value = c.g;
            dsn_internal_histogram_map(&asset, &value, 0, 0);
            CAPTURE(c.g);
            CHECK(value == c.out);
            CHECK(value == reference_map(m, 1, &c.g)[0]);
        }
    };
    // 0.5 lies halfway from 0 to 2: 1. -0.25: three quarters from -1 to 0: -0.25. Beyond the ends:
    // clamped to -1 and 2. An exact entry: 0 at g = 0.
    const Case cases[] = {{32768, 65536}, {-16384, -16384},    {-5 * 65536, -65536}, {7 << 16, 131072},
                          {0, 0},         {INT32_MIN, -65536}, {INT32_MAX, 131072}};
    check_cases(cases);
    // Rounding halves up: T = (0, 1/4096, -1/4096) with s = 16 (d = 0) is exact, so take s = 4 (d = 12):
    // the table steps of 1/4096 over 1/16 give v = 16 f / 2^12 per unit step, a half at f = 128.
    m.step_shift = 4, m.input_low_q16 = 0, m.tables = {0, 1, -1};
    bytes = dsn::encode_asset(fields);
    REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    // v = 16 (T_i 4096 + (T_j - T_i) f) / 4096: at g = 128, 0.5 rounds up to 1; at 127, 0.496 to 0; from
    // entry 1 (value 1/4096) toward entry 2 (-1/4096), f = 2112 gives -0.5 (up: 0) and f = 2240 gives
    // -1.5 (up: -1); the last entry is -16 exactly.
    const Case halves[] = {{128, 1}, {127, 0}, {4096 + 2112, 0}, {4096 + 2240, -1}, {4096, 16}, {8192, -16}};
    check_cases(halves);

    // Step shift 16 (d = 0) from input 0: entries 2^-16 apart, so every rounding shift is 0 (where
    // dsn_round_saturate's signed subtraction used to overflow, as UBSan reported in every evaluator):
    // g = i maps to T[i] 16 exactly, clamped beyond the ends.
    m.step_shift = 16, m.input_low_q16 = 0, m.tables = {-4096, 0, 8192};
    bytes = dsn::encode_asset(fields);
    REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    const Case unit_steps[] = {{0, -65536},        {1, 0}, {2, 131072}, {-5, -65536}, {INT32_MAX, 131072},
                               {INT32_MIN, -65536}};
    check_cases(unit_steps);
    dsn_test::LoadedNoise unit_noise(fields,
                                     dsn_test::make_config(3, 30, 0, 0, DSN_FLAG_ALLOW_LATTICE_CONTINUOUS));
    int32_t lattice_value = 1, continuous_value = 1;
    dsn_lattice_point_fixed(&unit_noise.noise, 5, -7, &lattice_value);
    REQUIRE(dsn_continuous_point_fixed(&unit_noise.noise, int64_t(5) << 32, -(int64_t(7) << 32),
                                       &continuous_value) == DSN_OK);
    for (int32_t value : {lattice_value, continuous_value})
        CHECK((value == -65536 || value == 0 || value == 131072));

    // Grey, RGB and the three kinds of table over a sweep of Gaussian-space values and blends.
    for (uint32_t channels : {1u, 3u}) {
        const dsn::HistogramMapping mappings[] = {smooth_mapping(channels, 1), step_mapping(channels),
                                                  rotation_mapping(channels)};
        for (const dsn::HistogramMapping &mapping : mappings) {
            dsn::AssetFields f = dsn_test::synthetic_fields(channels, 3, 8, DSN_SHAPE_RECTANGLE, 2);
            f.histogram = mapping;
            const Bytes b = dsn::encode_asset(f);
            dsn_asset a;
            REQUIRE(dsn_asset_load(&a, b.data(), b.size()) == DSN_OK);
            size_t differences = 0;
            dsn_test::TestRandom random(channels);
            for (int n = 0; n < 20000; n++) {
                int32_t g[3];
                for (uint32_t k = 0; k < channels; k++)
                    g[k] = n < 100 ? int32_t(random.next()) : random.range(-6 * 65536, 6 * 65536);
                const uint32_t level = n % 3 == 0 ? 0u : 1u, blend = n % 3 == 0 ? 0u : uint32_t(n % 256);
                const std::vector<int32_t> expected = reference_map(mapping, channels, g, level, blend);
                dsn_internal_histogram_map(&a, g, level, blend);
                for (uint32_t c = 0; c < channels; c++) differences += g[c] != expected[size_t(c)];
            }
            CHECK(differences == 0);
        }
    }
    // The rotation mapping on RGB: (g0, g1, g2) -> (-g1, g0, g2) on the entries (identity tables).
    dsn::AssetFields rgb = dsn_test::synthetic_fields(3, 3, 8, DSN_SHAPE_RECTANGLE, 2);
    rgb.histogram = rotation_mapping(3);
    const Bytes rgb_bytes = dsn::encode_asset(rgb);
    REQUIRE(dsn_asset_load(&asset, rgb_bytes.data(), rgb_bytes.size()) == DSN_OK);
    int32_t g[3] = {65536, -2 * 65536, 3 * 65536};
    dsn_internal_histogram_map(&asset, g, 0, 0);
    CHECK(g[0] == 2 * 65536);
    CHECK(g[1] == 65536);
    CHECK(g[2] == 3 * 65536);
}

TEST_CASE("histogram: per-point lattice and continuous values are the formula applied to the "
          "Gaussian-space values") {
    for (uint32_t channels : {1u, 3u})
        for (int kind = 0; kind < 3; kind++) {
            CAPTURE(channels);
            CAPTURE(kind);
            dsn::AssetFields fields = mapped_fields(channels, 8, false);
            if (kind == 1) fields.histogram = step_mapping(channels);
            if (kind == 2) fields.histogram = rotation_mapping(channels);
            MappedPair pair(fields, 77);
            size_t differences = 0, changed = 0;
            for (int32_t y = -40; y < 40; y += 3)
                for (int32_t x = -40; x < 40; x += 3) {
                    int32_t mapped[3], gaussian[3];
                    dsn_lattice_point_fixed(&pair.mapped.noise, x, y, mapped);
                    dsn_lattice_point_fixed(&pair.gaussian.noise, x, y, gaussian);
                    std::vector<int32_t> expected = reference_map(fields.histogram, channels, gaussian);
                    for (uint32_t c = 0; c < channels; c++) {
                        differences += mapped[c] != expected[c];
                        changed += mapped[c] != gaussian[c];
                    }
                    const int64_t cx = x * kOne + 0x3A5B0000LL, cy = y * kOne - 0x71C00000LL;
                    REQUIRE(dsn_continuous_point_fixed(&pair.mapped.noise, cx, cy, mapped) == DSN_OK);
                    REQUIRE(dsn_continuous_point_fixed(&pair.gaussian.noise, cx, cy, gaussian) == DSN_OK);
                    expected = reference_map(fields.histogram, channels, gaussian);
                    for (uint32_t c = 0; c < channels; c++) differences += mapped[c] != expected[c];
                }
            CHECK(differences == 0);
            CHECK(changed > 0);
        }
}

namespace {

// Values where a lattice tile (fixed, float, u8) differs from the per-point functions, with every kernel
// copy this CPU runs (runtime/kernels/kernels.h).
size_t lattice_tile_differences(const dsn_noise &noise, int32_t x0, int32_t y0, uint32_t width,
                                uint32_t height) {
    const uint32_t channels = dsn_noise_channels(&noise);
    const size_t values = size_t(width) * height * channels;
    size_t count = 0;
    for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_state(&noise)->tile_kernel; kernel++) {
        dsn_noise copy = noise;
        dsn_state(&copy)->tile_kernel = kernel;
        std::vector<int32_t> fixed(values);
        std::vector<float> floats(values);
        std::vector<uint8_t> bytes(values);
        std::vector<unsigned char> scratch(dsn_lattice_tile_scratch_size(&copy, width, height));
        REQUIRE(dsn_lattice_tile_fixed(&copy, x0, y0, width, height, fixed.data(), nullptr, 0) == DSN_OK);
        REQUIRE(dsn_lattice_tile_float(&copy, x0, y0, width, height, floats.data(), scratch.data(),
                                       scratch.size()) == DSN_OK);
        REQUIRE(dsn_lattice_tile_u8(&copy, x0, y0, width, height, bytes.data(), scratch.data(),
                                    scratch.size()) == DSN_OK);
        for (uint32_t j = 0; j < height; j++)
            for (uint32_t i = 0; i < width; i++) {
                const int32_t x = int32_t(uint32_t(x0) + i), y = int32_t(uint32_t(y0) + j);
                int32_t point[3];
                float point_float[3];
                uint8_t point_u8[3];
                dsn_lattice_point_fixed(&copy, x, y, point);
                dsn_lattice_point_float(&copy, x, y, point_float);
                dsn_lattice_point_u8(&copy, x, y, point_u8);
                for (uint32_t c = 0; c < channels; c++) {
                    const size_t index = (size_t(j) * width + i) * channels + c;
                    count += fixed[index] != point[c];
                    count += std::memcmp(&floats[index], &point_float[c], sizeof(float)) != 0;
                    count += bytes[index] != point_u8[c];
                    const float as_float = dsn_fixed_to_float(point[c]);
                    count += std::memcmp(&point_float[c], &as_float, sizeof(float)) != 0;
                }
            }
    }
    return count;
}

// Values where a continuous grid tile (fixed, float, u8) differs from the per-point functions.
size_t continuous_tile_differences(const dsn_noise &noise, const dsn_grid &grid, uint32_t width,
                                   uint32_t height, bool *splat) {
    const uint32_t channels = dsn_noise_channels(&noise);
    const size_t values = size_t(width) * height * channels;
    std::vector<int32_t> fixed(values);
    std::vector<float> floats(values);
    std::vector<uint8_t> bytes(values);
    const size_t scratch_size = dsn_continuous_tile_scratch_size(&noise, &grid, width, height);
    *splat = scratch_size > 0;
    std::vector<unsigned char> scratch(scratch_size);
    REQUIRE(dsn_continuous_tile_fixed(&noise, &grid, width, height, fixed.data(), scratch.data(),
                                      scratch.size()) == DSN_OK);
    REQUIRE(dsn_continuous_tile_float(&noise, &grid, width, height, floats.data(), scratch.data(),
                                      scratch.size()) == DSN_OK);
    REQUIRE(dsn_continuous_tile_u8(&noise, &grid, width, height, bytes.data(), scratch.data(),
                                   scratch.size()) == DSN_OK);
    size_t count = 0;
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            int64_t x, y;
            dsn_test::grid_point(grid, i, j, &x, &y);
            int32_t point[3];
            REQUIRE(dsn_continuous_point_fixed(&noise, x, y, point) == DSN_OK);
            for (uint32_t c = 0; c < channels; c++) {
                const size_t index = (size_t(j) * width + i) * channels + c;
                const float as_float = dsn_fixed_to_float(point[c]);
                count += fixed[index] != point[c];
                count += std::memcmp(&floats[index], &as_float, sizeof(float)) != 0;
                count += bytes[index] != dsn_fixed_to_u8(point[c]);
            }
        }
    return count;
}

dsn_grid grid_of(double x, double y, double cx, double cy, double rx, double ry) {
    const double q = 4294967296.0;
    dsn_grid grid;
    grid.origin_x = int64_t(std::floor(x * q)), grid.origin_y = int64_t(std::floor(y * q));
    grid.column_step_x = int64_t(std::floor(cx * q)), grid.column_step_y = int64_t(std::floor(cy * q));
    grid.row_step_x = int64_t(std::floor(rx * q)), grid.row_step_y = int64_t(std::floor(ry * q));
    return grid;
}

} // namespace

TEST_CASE("histogram: lattice tiles in every kernel copy and every output type equal the per-point bits") {
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u}) {
            CAPTURE(channels);
            CAPTURE(bits);
            dsn::AssetFields fields = mapped_fields(channels, bits, false);
            fields.interpolation = DSN_INTERPOLATION_LATTICE;
            const LoadedNoise loaded(fields, make_config(5));
            CHECK(lattice_tile_differences(loaded.noise, -37, 5, 70, 45) == 0);
            CHECK(lattice_tile_differences(loaded.noise, INT32_MAX - 20, INT32_MIN + 3, 41, 9) == 0);
            CHECK(lattice_tile_differences(loaded.noise, 1000, -1000, 1, 1) == 0);
            // A dense noise, whose sums go past the 16-bit strips to the 32-bit path.
            const LoadedNoise dense(fields, make_config(5, 600));
            CHECK(lattice_tile_differences(dense.noise, 3, 4, 33, 17) == 0);
        }
}

TEST_CASE("histogram: continuous tiles (splat and point by point), batches and float output equal the "
          "per-point bits") {
    for (uint32_t channels : {1u, 3u}) {
        CAPTURE(channels);
        const LoadedNoise loaded(mapped_fields(channels, 8, false), make_config(9));
        const dsn_noise &noise = loaded.noise;
        bool splat = false;
        size_t splats = 0;
        const dsn_grid grids[] = {grid_of(-3.3, 7.9, 0.37, 0, 0, 0.37),
                                  grid_of(100.1, -50.7, 0.8, 0.6, -0.6, 0.8),
                                  grid_of(5.5, 5.5, 1.7, -0.2, 0.3, 2.1), grid_of(0, 0, 20000, 3, -3, 20000)};
        for (const dsn_grid &grid : grids) {
            CHECK(continuous_tile_differences(noise, grid, 37, 23, &splat) == 0);
            splats += splat;
        }
        CHECK(splats > 0);
        CHECK(splats < 4); // both the splat and the point-by-point tiles ran
        // Batches, in every kernel copy, and the float variants of the point functions.
        std::vector<int64_t> xs, ys;
        std::vector<double> dxs, dys;
        dsn_test::TestRandom random(channels);
        for (int k = 0; k < 301; k++) {
            dxs.push_back(random.range(-100000, 100000) / 97.0);
            dys.push_back(random.range(-100000, 100000) / 89.0);
            xs.push_back(dsn_coordinate_from_double(dxs.back()));
            ys.push_back(dsn_coordinate_from_double(dys.back()));
        }
        size_t differences = 0;
        for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_state(&noise)->tile_kernel; kernel++) {
            dsn_noise copy = noise;
            dsn_state(&copy)->tile_kernel = kernel;
            std::vector<unsigned char> scratch(dsn_continuous_batch_scratch_size(&copy));
            std::vector<int32_t> fixed(xs.size() * channels);
            std::vector<float> floats(xs.size() * channels);
            REQUIRE(dsn_continuous_batch_fixed(&copy, xs.data(), ys.data(), uint32_t(xs.size()), fixed.data(),
                                               scratch.data(), scratch.size()) == DSN_OK);
            REQUIRE(dsn_continuous_batch_float(&copy, dxs.data(), dys.data(), uint32_t(xs.size()),
                                               floats.data(), scratch.data(), scratch.size()) == DSN_OK);
            for (size_t k = 0; k < xs.size(); k++) {
                int32_t point[3];
                float point_float[3], sample[3];
                REQUIRE(dsn_continuous_point_fixed(&copy, xs[k], ys[k], point) == DSN_OK);
                REQUIRE(dsn_continuous_point_float(&copy, dxs[k], dys[k], point_float) == DSN_OK);
                REQUIRE(dsn_sample(&copy, float(dxs[k]), float(dys[k]), sample) == DSN_OK);
                int32_t at_float[3];
                REQUIRE(dsn_continuous_point_fixed(&copy, dsn_coordinate_from_float(float(dxs[k])),
                                                   dsn_coordinate_from_float(float(dys[k])),
                                                   at_float) == DSN_OK);
                for (uint32_t c = 0; c < channels; c++) {
                    const float expected = dsn_fixed_to_float(point[c]),
                                expected_sample = dsn_fixed_to_float(at_float[c]);
                    differences += fixed[k * channels + c] != point[c];
                    differences += std::memcmp(&floats[k * channels + c], &expected, sizeof(float)) != 0;
                    differences += std::memcmp(&point_float[c], &expected, sizeof(float)) != 0;
                    differences += std::memcmp(&sample[c], &expected_sample, sizeof(float)) != 0;
                }
            }
        }
        CHECK(differences == 0);
    }
}

TEST_CASE("histogram: the filtered evaluation maps its Gaussian-space value through two levels' tables, "
          "its tiles are its points, and it fades to centre + P expected") {
    for (uint32_t channels : {1u, 3u})
        for (uint32_t tables : {0u, 2u}) { // 0: one table per level and the texton (M = 1 + L)
            CAPTURE(channels);
            CAPTURE(tables);
            dsn::AssetFields fields = mapped_fields(channels, 8, true);
            if (tables != 0) fields.histogram = smooth_mapping(channels, tables);
            const uint32_t levels = uint32_t(fields.pyramid.size());
            REQUIRE(levels >= 3);
            MappedPair pair(fields, 21);
            const dsn::HistogramMapping &m = fields.histogram;
            int32_t zero[3] = {0, 0, 0};
            const std::vector<int32_t> fade = reference_map(m, channels, zero, m.level_count, 0);
            // The fade colour: dsn_noise_mean_float, and the filtered value at the coarsest levels of detail.
            float mean[3];
            REQUIRE(dsn_noise_mean_float(&pair.mapped.noise, mean) == DSN_OK);
            for (uint32_t c = 0; c < channels; c++) {
                const float expected = dsn_fixed_to_float(fade[c]);
                CHECK(std::memcmp(&mean[c], &expected, sizeof(float)) == 0);
            }
            size_t differences = 0, faded = 0, blended = 0;
            const double sizes[] = {0.5, 0.9, 1.3, 2.0, 2.7, 3.9, 6.0, 9.5, 15.0, 40.0, 300.0, 1e6};
            for (double size : sizes)
                for (uint32_t max_taps : {1u, 4u}) {
                    dsn_footprint footprint;
                    REQUIRE(dsn_footprint_from_float(&footprint, size, 0.1 * size, -0.3 * size / max_taps,
                                                     size / max_taps, max_taps) == DSN_OK);
                    int32_t lod = 0;
                    uint32_t taps = 0;
                    REQUIRE(dsn_filter_level(&pair.mapped.noise, &footprint, &lod, &taps) == DSN_OK);
                    const uint32_t lower = uint32_t(lod) >> 8, blend = uint32_t(lod) & 255;
                    faded += lower >= m.level_count;
                    blended += lower < m.level_count && blend != 0;
                    for (int n = 0; n < 12; n++) {
                        const int64_t x = dsn_coordinate_from_double(n * 13.7 - 50),
                                      y = dsn_coordinate_from_double(n * -7.3 + 3);
                        int32_t mapped[3], gaussian[3];
                        REQUIRE(dsn_filtered_point_fixed(&pair.mapped.noise, x, y, &footprint, mapped) ==
                                DSN_OK);
                        REQUIRE(dsn_filtered_point_fixed(&pair.gaussian.noise, x, y, &footprint, gaussian) ==
                                DSN_OK);
                        const std::vector<int32_t> expected =
                            reference_map(m, channels, gaussian, lower, blend);
                        for (uint32_t c = 0; c < channels; c++) {
                            differences += mapped[c] != expected[c];
                            if (lower >= m.level_count) differences += mapped[c] != fade[c];
                        }
                        float as_float[3];
                        REQUIRE(dsn_filtered_point_float(&pair.mapped.noise, n * 13.7 - 50, n * -7.3 + 3,
                                                         &footprint, as_float) == DSN_OK);
                        for (uint32_t c = 0; c < channels; c++) {
                            const float expected_float = dsn_fixed_to_float(mapped[c]);
                            differences += std::memcmp(&as_float[c], &expected_float, sizeof(float)) != 0;
                        }
                    }
                    // The grid of this footprint: its tile is its points.
                    dsn_grid grid;
                    grid.origin_x = dsn_coordinate_from_double(-20.25),
                    grid.origin_y = dsn_coordinate_from_double(7.5);
                    grid.column_step_x = footprint.column_step_x,
                    grid.column_step_y = footprint.column_step_y;
                    grid.row_step_x = footprint.row_step_x, grid.row_step_y = footprint.row_step_y;
                    const uint32_t width = 9, height = 5;
                    std::vector<int32_t> tile(size_t(width) * height * channels);
                    std::vector<unsigned char> scratch(
                        dsn_filtered_tile_scratch_size(&pair.mapped.noise, &grid, max_taps, width, height));
                    REQUIRE(dsn_filtered_tile_fixed(&pair.mapped.noise, &grid, max_taps, width, height,
                                                    tile.data(), scratch.data(), scratch.size()) == DSN_OK);
                    for (uint32_t j = 0; j < height; j++)
                        for (uint32_t i = 0; i < width; i++) {
                            int32_t point[3];
                            int64_t x, y;
                            dsn_test::grid_point(grid, i, j, &x, &y);
                            REQUIRE(dsn_filtered_point_fixed(&pair.mapped.noise, x, y, &footprint, point) ==
                                    DSN_OK);
                            for (uint32_t c = 0; c < channels; c++)
                                differences += tile[(size_t(j) * width + i) * channels + c] != point[c];
                        }
                }
            CHECK(differences == 0);
            CHECK(faded > 0);
            CHECK(blended > 0);
        }
}

TEST_CASE("histogram: DSN_FLAG_NO_HISTOGRAM, GPU packing, altered assets and 1.1 assets") {
    const dsn::AssetFields fields = mapped_fields(3, 8, true);
    MappedPair pair(fields, 3);
    // The Gaussian-space noise is the asset's noise without the mapping: the bits of the same asset
    // written without one.
    dsn::AssetFields plain = fields;
    plain.histogram.tables.clear();
    const LoadedNoise unmapped(plain, make_config(3));
    size_t differences = 0;
    for (int32_t y = -5; y < 5; y++)
        for (int32_t x = -5; x < 5; x++) {
            int32_t a[3], b[3];
            dsn_lattice_point_fixed(&pair.gaussian.noise, x, y, a);
            dsn_lattice_point_fixed(&unmapped.noise, x, y, b);
            differences += std::memcmp(a, b, sizeof a) != 0;
        }
    CHECK(differences == 0);
    float mean_gaussian[3], mean_plain[3];
    REQUIRE(dsn_noise_mean_float(&pair.gaussian.noise, mean_gaussian) == DSN_OK);
    REQUIRE(dsn_noise_mean_float(&unmapped.noise, mean_plain) == DSN_OK);
    CHECK(std::memcmp(mean_gaussian, mean_plain, sizeof mean_plain) == 0);
    // dsn.glsl has no mapping: a mapped noise is refused, its Gaussian-space configuration packs.
    std::vector<uint32_t> words(dsn_gpu_word_count(&pair.mapped.noise));
    CHECK(dsn_gpu_pack(&pair.mapped.noise, words.data(), words.size()) == DSN_ERR_UNSUPPORTED);
    CHECK(dsn_gpu_pack(&pair.gaussian.noise, words.data(), words.size()) == DSN_OK);
    // dsn_noise_init refuses mapping fields the evaluators cannot read.
    dsn_config config = make_config(3);
    dsn_noise noise;
    const auto init_code = [&](void (*alter)(dsn_asset &)) {
        dsn_asset altered = pair.mapped.asset;
        alter(altered);
        return dsn_noise_init(&noise, &altered, &config);
    };
    CHECK(init_code([](dsn_asset &a) { a.histogram_step_shift = 17; }) == DSN_ERR_ARGUMENT);
    CHECK(init_code([](dsn_asset &a) { a.histogram_entries = 1; }) == DSN_ERR_ARGUMENT);
    CHECK(init_code([](dsn_asset &a) { a.histogram_levels = 0; }) == DSN_ERR_ARGUMENT);
    CHECK(init_code([](dsn_asset &a) { a.histogram_expected_q16[1] = INT32_MIN; }) == DSN_ERR_ARGUMENT);
    CHECK(init_code([](dsn_asset &a) { (void)a; }) == DSN_OK);
    // An asset without a mapping (1.0 and 1.1 files) loads and evaluates as before: no table.
    CHECK(unmapped.asset.histogram_table == nullptr);
    CHECK(unmapped.asset.histogram_entries == 0);
    CHECK(unmapped.asset.version_minor == 1);
}
