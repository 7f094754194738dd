// tests/support/test_assets.h - .dsnt assets built by tests from fixed integers (no FFT baker), and a
// loaded asset + noise pair that owns its bytes.
#ifndef DSN_TEST_ASSETS_H
#define DSN_TEST_ASSETS_H

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "dsn/asset_writer.h"
#include "dsn/dsn.h"

namespace dsn_test {

// A small deterministic integer generator (the tests' own: never the runtime's hash).
struct TestRandom {
    uint64_t state;
    explicit TestRandom(uint64_t seed) : state(seed * 0x9E3779B97F4A7C15u + 1) {}
    uint32_t next() {
        state = state * 6364136223846793005u + 1442695040888963407u;
        return uint32_t(state >> 33);
    }
    int32_t range(int32_t low, int32_t high) { return low + int32_t(next() % uint32_t(high - low + 1)); }
};

// A synthetic texton from fixed integers: a smooth bump times a striped sign pattern plus small integer
// noise, different per channel, in [-127, 127] (or its 16-bit counterpart), zero outside a disk support.
inline dsn::AssetFields synthetic_fields(uint32_t channels, uint32_t side, uint32_t bits, uint32_t shape,
                                         uint64_t seed) {
    dsn::AssetFields fields;
    fields.channels = channels;
    fields.bits = bits;
    fields.shape = shape;
    fields.width = fields.height = side;
    const int32_t top = bits == 8 ? 127 : 32767;
    TestRandom random(seed);
    const int r = int(side - 1) / 2;
    for (int row = 0; row < int(side); row++)
        for (int column = 0; column < int(side); column++)
            for (uint32_t c = 0; c < channels; c++) {
                int dx = column - r, dy = row - r;
                bool inside = shape != DSN_SHAPE_DISK || dx * dx + dy * dy <= r * r;
                double envelope = std::exp(-double(dx * dx + dy * dy) / (0.5 * (r + 1) * (r + 1)));
                double wave = std::cos(0.7 * dx + 0.4 * double(c) * dy + double(c));
                int32_t value =
                    int32_t(std::lround(0.8 * top * envelope * wave)) + random.range(-top / 8, top / 8);
                value = value > top ? top : value < -top ? -top : value;
                fields.texton.push_back(inside ? value : 0);
            }
    for (uint32_t c = 0; c < channels; c++) {
        fields.scale[c] = (bits == 8 ? 1u << 30 : 1u << 22) + 12345u * c; // ~2^-10 per q unit (8 bits)
        fields.mean[c] = int32_t((0.5 + 0.1 * c) * DSN_Q24_ONE);
    }
    if (channels == 3) {
        const double K[9] = {0.9, 0.2, -0.1, 0.15, 1.1, 0.05, -0.2, 0.1, 0.8};
        for (int i = 0; i < 9; i++) fields.color_transform[i] = int32_t(std::lround(K[i] * DSN_Q24_ONE));
    } else {
        dsn::set_identity_color_transform(fields);
    }
    return fields;
}

// Encoded bytes plus the loaded asset and a configured noise (the asset points into `bytes`).
struct LoadedNoise {
    std::vector<unsigned char> bytes;
    dsn_asset asset{};
    dsn_noise noise{};

    LoadedNoise(const dsn::AssetFields &fields, const dsn_config &config) : bytes(dsn::encode_asset(fields)) {
        if (dsn_asset_load(&asset, bytes.data(), bytes.size()) != DSN_OK)
            throw std::runtime_error("load failed");
        if (dsn_noise_init(&noise, &asset, &config) != DSN_OK) throw std::runtime_error("init failed");
    }
    LoadedNoise(const LoadedNoise &) = delete;
    LoadedNoise &operator=(const LoadedNoise &) = delete;
};

inline dsn_config make_config(uint32_t seed, double impacts = 30, uint32_t period_x = 0,
                              uint32_t period_y = 0, uint32_t flags = 0) {
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = seed;
    config.impacts_q16 = uint32_t(std::lround(impacts * 65536));
    config.period_x = period_x;
    config.period_y = period_y;
    config.flags = flags;
    return config;
}

// The number of values where a tile at (x0, y0) differs from the per-point function (the tile's pixel
// (i, j) is the point (x0 + i, y0 + j) modulo 2^32); SIZE_MAX when the tile call itself fails.
inline size_t tile_point_differences(const dsn_noise &noise, int32_t x0, int32_t y0, uint32_t width,
                                     uint32_t height) {
    const uint32_t channels = noise.asset.channels;
    std::vector<int32_t> tile(size_t(width) * height * channels);
    if (dsn_tile_fixed(&noise, x0, y0, width, height, tile.data(), nullptr, 0) != DSN_OK) return SIZE_MAX;
    size_t differences = 0;
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            int32_t point[3];
            dsn_eval_fixed(&noise, int32_t(uint32_t(x0) + i), int32_t(uint32_t(y0) + j), point);
            for (uint32_t c = 0; c < channels; c++)
                differences += point[c] != tile[(size_t(j) * width + i) * channels + c];
        }
    return differences;
}

} // namespace dsn_test

#endif
