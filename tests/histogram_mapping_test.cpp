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

#include "../offline/bake_internal.h"
#include "../runtime/histogram_map.h"
#include "../runtime/kernels.h"
#include "dsn/gpu.h"
#include "fixtures/test_assets.h"

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
        : mapped(fields, make_config(seed)), gaussian(fields, make_config(seed, 30, 0, 0, DSN_FLAG_NO_HISTOGRAM)) {}
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
                CHECK(std::memcmp(plain_asset.texton, asset.texton,
                                  size_t(31) * 31 * channels * bits / 8) == 0);
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
    // 0.5 lies halfway from 0 to 2: 1. -0.25: three quarters from -1 to 0: -0.25. Beyond the ends:
    // clamped to -1 and 2. An exact entry: 0 at g = 0.
    const Case cases[] = {{32768, 65536}, {-16384, -16384}, {-5 * 65536, -65536}, {7 << 16, 131072}, {0, 0},
                          {INT32_MIN, -65536}, {INT32_MAX, 131072}};
    for (const Case &c : cases) {
        int32_t value = c.g;
        dsn_internal_histogram_map(&asset, &value, 0, 0);
        CAPTURE(c.g);
        CHECK(value == c.out);
        CHECK(value == reference_map(m, 1, &c.g)[0]);
    }
    // Rounding halves up: T = (0, 1/4096, -1/4096) with s = 16 (d = 0) is exact, so take s = 4 (d = 12):
    // the table steps of 1/4096 over 1/16 give v = 16 f / 2^12 per unit step, a half at f = 128.
    m.step_shift = 4, m.input_low_q16 = 0, m.tables = {0, 1, -1};
    bytes = dsn::encode_asset(fields);
    REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    // v = 16 (T_i 4096 + (T_j - T_i) f) / 4096: at g = 128, 0.5 rounds up to 1; at 127, 0.496 to 0; from
    // entry 1 (value 1/4096) toward entry 2 (-1/4096), f = 2112 gives -0.5 (up: 0) and f = 2240 gives
    // -1.5 (up: -1); the last entry is -16 exactly.
    const Case halves[] = {{128, 1}, {127, 0}, {4096 + 2112, 0}, {4096 + 2240, -1}, {4096, 16}, {8192, -16}};
    for (const Case &c : halves) {
        int32_t value = c.g;
        dsn_internal_histogram_map(&asset, &value, 0, 0);
        CAPTURE(c.g);
        CHECK(value == c.out);
        CHECK(value == reference_map(m, 1, &c.g)[0]);
    }

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
