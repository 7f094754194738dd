// fuzz_asset_loader.cpp - arbitrary bytes -> asset loader -> when accepted, a configuration taken from the
// bytes after the asset -> points (extreme coordinates included) and a small tile, which must agree; then
// filtered points and a filtered tile under a footprint from the bytes (any int64 steps, any max_taps,
// float derivatives NaN and infinities included), the tile equal to its points; then a mix of the noise
// with a second configuration of the asset under a control from the bytes (any size, spacing, origin and
// flags, any weights), its tiles equal to its points, and material 0's own bits where its weight is all.
#include <cstdint>
#include <vector>

#include "dsn/dsn.h"
#include "fuzz_input.h"
#include "runtime/setup/format_bytes.h"

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

int64_t i64(FuzzInput &input) { return int64_t(uint64_t(input.u32()) | (uint64_t(input.u32()) << 32)); }

// A step: often small (a few texels, the interesting levels of detail), sometimes any int64.
int64_t step(FuzzInput &input) {
    const uint32_t kind = input.byte();
    if (kind < 160) return int64_t(int32_t(input.u32())) * 8;    // within +-2^34: up to 4 texels per unit
    if (kind < 240) return int64_t(int32_t(input.u32())) * 4096; // within +-2^43
    return i64(input);
}

void check_filtered(const dsn_noise &noise, uint32_t channels, FuzzInput &input) {
    dsn_footprint footprint{step(input), step(input), step(input), step(input), input.byte() % 18u};
    const bool valid_taps = footprint.max_taps >= 1 && footprint.max_taps <= DSN_FILTER_MAX_TAPS;
    const bool continuous = dsn_continuous_check(&noise) == DSN_OK;
    int32_t lod_q8;
    uint32_t taps;
    const int level_error = dsn_filter_level(&noise, &footprint, &lod_q8, &taps);
    fuzz_require(level_error == (valid_taps ? DSN_OK : DSN_ERR_ARGUMENT));
    if (level_error == DSN_OK)
        fuzz_require(taps >= 1 && taps <= footprint.max_taps && (taps & (taps - 1)) == 0);
    const int expected = !continuous ? DSN_ERR_CONTINUOUS_MISMATCH : valid_taps ? DSN_OK : DSN_ERR_ARGUMENT;

    const dsn_grid grid{
        i64(input),           i64(input),          footprint.column_step_x, footprint.column_step_y,
        footprint.row_step_x, footprint.row_step_y};
    const uint32_t width = 3, height = 2;
    std::vector<int32_t> tile(width * height * channels);
    std::vector<unsigned char> scratch(
        dsn_filtered_tile_scratch_size(&noise, &grid, footprint.max_taps, width, height) + 1);
    const int tile_error = dsn_filtered_tile_fixed(&noise, &grid, footprint.max_taps, width, height,
                                                   tile.data(), scratch.data(), scratch.size());
    fuzz_require(tile_error == expected);
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            const int64_t x = int64_t(uint64_t(grid.origin_x) + i * uint64_t(grid.column_step_x) +
                                      j * uint64_t(grid.row_step_x));
            const int64_t y = int64_t(uint64_t(grid.origin_y) + i * uint64_t(grid.column_step_y) +
                                      j * uint64_t(grid.row_step_y));
            int32_t value[DSN_MAX_CHANNELS];
            fuzz_require(dsn_filtered_point_fixed(&noise, x, y, &footprint, value) == expected);
            for (uint32_t c = 0; expected == DSN_OK && c < channels; c++)
                fuzz_require(tile[(j * width + i) * channels + c] == value[c]);
        }

    // Float derivatives from raw bits (NaN and infinities included): DSN_ERR_ARGUMENT or a footprint.
    double derivatives[4];
    for (double &d : derivatives) {
        const uint64_t bits = uint64_t(input.u32()) | (uint64_t(input.u32()) << 32);
        __builtin_memcpy(&d, &bits, sizeof d);
    }
    dsn_footprint from_float;
    if (dsn_footprint_from_float(&from_float, derivatives[0], derivatives[1], derivatives[2], derivatives[3],
                                 1u + input.byte() % 16u) == DSN_OK) {
        float value[DSN_MAX_CHANNELS];
        fuzz_require(dsn_filtered_point_float(&noise, 0.5, -3.25, &from_float, value) ==
                     (continuous ? DSN_OK : DSN_ERR_CONTINUOUS_MISMATCH));
    }
}

void check_mix(const dsn_noise &noise, const dsn_asset &asset, FuzzInput &input) {
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = input.u32();
    config.flags = input.byte() & 7u;
    dsn_noise second;
    if (dsn_noise_init(&second, &asset, &config) != DSN_OK) return;
    const dsn_noise *materials[2] = {&noise, &second};
    dsn_mix mix;
    const int init = dsn_mix_init(&mix, materials, 2);
    fuzz_require(init == DSN_OK || init == DSN_ERR_UNSUPPORTED || init == DSN_ERR_COST);
    if (init != DSN_OK) {
        fuzz_require(dsn_mix_channels(&mix) == 0);
        return;
    }
    std::vector<uint8_t> weights(2 * 6 * 6);
    for (uint8_t &weight : weights) weight = input.byte();
    dsn_mix_control control{weights.data(),       input.byte() % 7u,    input.byte() % 7u, input.byte() % 18u,
                            int32_t(input.u32()), int32_t(input.u32()), input.byte() % 5u};
    const bool valid =
        control.width >= 1 && control.height >= 1 && control.spacing_shift <= 16 && control.flags <= 3;
    const bool continuous = dsn_continuous_check(&noise) == DSN_OK && dsn_continuous_check(&second) == DSN_OK;
    const uint32_t width = 3, height = 2, channels = asset.channels;
    const int32_t x0 = input.i32(), y0 = input.i32();
    std::vector<int32_t> tile(width * height * channels);
    fuzz_require(dsn_mix_lattice_tile_fixed(&mix, &control, x0, y0, width, height, tile.data(), nullptr, 0) ==
                 (valid ? DSN_OK : DSN_ERR_ARGUMENT));
    for (uint32_t j = 0; valid && j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            int32_t value[DSN_MAX_CHANNELS];
            fuzz_require(dsn_mix_lattice_point_fixed(&mix, &control, int32_t(uint32_t(x0) + i),
                                                     int32_t(uint32_t(y0) + j), value) == DSN_OK);
            for (uint32_t c = 0; c < channels; c++)
                fuzz_require(tile[(j * width + i) * channels + c] == value[c]);
        }
    const int64_t x = i64(input), y = i64(input);
    int32_t mixed[DSN_MAX_CHANNELS];
    fuzz_require(dsn_mix_continuous_point_fixed(&mix, &control, x, y, mixed) ==
                 (!valid       ? DSN_ERR_ARGUMENT
                  : continuous ? DSN_OK
                               : DSN_ERR_CONTINUOUS_MISMATCH));
    // All the weight on material 0: its own noise.
    const uint8_t first[2] = {uint8_t(1 + input.byte() % 255u), 0};
    const dsn_mix_control on_first{first, 1, 1, 0, 0, 0, 0};
    int32_t own[DSN_MAX_CHANNELS];
    dsn_lattice_point_fixed(&noise, x0, y0, own);
    fuzz_require(dsn_mix_lattice_point_fixed(&mix, &on_first, x0, y0, mixed) == DSN_OK);
    for (uint32_t c = 0; c < channels; c++) fuzz_require(mixed[c] == own[c]);
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
    check_filtered(noise, asset.channels, input);
    check_mix(noise, asset, input);
    return 0;
}
