// fuzz_asset_loader.cpp - arbitrary bytes -> asset loader -> when accepted, a configuration taken from the
// bytes after the asset -> points (extreme coordinates included) and a small tile, which must agree.
#include <cstdint>
#include <vector>

#include "../../runtime/format_bytes.h"
#include "dsn/dsn.h"
#include "fuzz_input.h"

namespace {

const int32_t kCoordinates[] = {0, 1, -1, 2147483647, -2147483647 - 1, 65535, -65536, 123456789};

void check_points_and_tile(const dsn_noise &noise, uint32_t channels, FuzzInput &input) {
    int32_t value[DSN_MAX_CHANNELS];
    for (int32_t x : kCoordinates)
        for (int32_t y : kCoordinates) dsn_lattice_point_fixed(&noise, x, y, value);

    // A 5x4 tile at an origin from the input (often straddling the 32-bit wrap) equals its points.
    const uint32_t width = 5, height = 4;
    const int32_t x0 = int32_t(2147483645u + (input.byte() & 7u)), y0 = input.i32();
    std::vector<int32_t> tile(width * height * channels);
    std::vector<unsigned char> scratch(dsn_lattice_tile_scratch_size(&noise, width, height) + 1);
    fuzz_require(dsn_lattice_tile_fixed(&noise, x0, y0, width, height, tile.data(), scratch.data(),
                                        scratch.size()) == DSN_OK);
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            dsn_lattice_point_fixed(&noise, int32_t(uint32_t(x0) + i), int32_t(uint32_t(y0) + j), value);
            for (uint32_t c = 0; c < channels; c++)
                fuzz_require(tile[(j * width + i) * channels + c] == value[c]);
        }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    dsn_asset asset;
    if (dsn_asset_load(&asset, data, size) != DSN_OK) return 0;
    fuzz_require(asset.channels == 1 || asset.channels == 3);

    // The bytes after the asset choose the configuration; small periods are the interesting ones.
    const size_t asset_size = dsn_read_u32le(data + DSN_OFFSET_TOTAL_SIZE);
    FuzzInput input(data + asset_size, size - asset_size);
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = input.u32();
    config.impacts_q16 = input.byte() < 128 ? 0u : input.u32() % (DSN_IMPACTS_MAX_Q16 + 2);
    config.period_x = input.byte() & 63u;
    config.period_y = input.byte() < 128 ? 0u : input.u32();
    config.flags = input.byte() & 7u;
    dsn_noise noise;
    if (dsn_noise_init(&noise, &asset, &config) != DSN_OK) return 0;
    check_points_and_tile(noise, asset.channels, input);
    return 0;
}
