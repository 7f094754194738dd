// bench_native.cpp - the native half of examples/web/bench-wasm: renders 256 x 256 tiles of an asset with
// the native runtime on one thread for about SECONDS and prints the throughput in Mpixel/s, so that the
// wasm build can be compared with it in the same run.
// Usage: dsn-web-bench-native ASSET.dsnt lattice|continuous SECONDS
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "dsn/dsn.h"

int main(int argc, char **argv) {
    if (argc != 4 || (std::strcmp(argv[2], "lattice") != 0 && std::strcmp(argv[2], "continuous") != 0)) {
        std::fprintf(stderr, "usage: dsn-web-bench-native ASSET.dsnt lattice|continuous SECONDS\n");
        return 2;
    }
    std::ifstream file(argv[1], std::ios::binary);
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    const bool continuous = std::strcmp(argv[2], "continuous") == 0;
    const double seconds = std::atof(argv[3]);
    dsn_asset asset;
    dsn_noise noise;
    dsn_config config;
    int err = dsn_asset_load(&asset, bytes.data(), bytes.size());
    dsn_config_defaults(&config);
    config.seed = 1;
    config.flags = DSN_FLAG_ALLOW_LATTICE_CONTINUOUS;
    if (err == DSN_OK) err = dsn_noise_init(&noise, &asset, &config);
    if (err != DSN_OK) {
        std::fprintf(stderr, "dsn-web-bench-native: %s: %s\n", argv[1], dsn_error_message(err));
        return 1;
    }
    const uint32_t side = 256;
    std::vector<uint8_t> out(side * side * asset.channels);
    dsn_grid grid = {0, 0, DSN_COORDINATE_ONE, 0, 0, DSN_COORDINATE_ONE};
    std::vector<unsigned char> scratch(continuous
                                           ? dsn_continuous_tile_scratch_size(&noise, &grid, side, side)
                                           : dsn_lattice_tile_scratch_size(&noise, side, side));
    const auto start = std::chrono::steady_clock::now();
    double elapsed = 0;
    long tiles = 0;
    // Tiles march along x, as the page's do when it pans: every tile is new work.
    for (; elapsed < seconds; tiles++) {
        const int32_t x = static_cast<int32_t>(tiles * side);
        grid.origin_x = static_cast<int64_t>(x) * DSN_COORDINATE_ONE;
        err = continuous
                  ? dsn_continuous_tile_u8(&noise, &grid, side, side, out.data(), scratch.data(),
                                           scratch.size())
                  : dsn_lattice_tile_u8(&noise, x, 0, side, side, out.data(), scratch.data(), scratch.size());
        if (err != DSN_OK) {
            std::fprintf(stderr, "dsn-web-bench-native: %s\n", dsn_error_message(err));
            return 1;
        }
        elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    std::printf("%.3f\n", static_cast<double>(tiles) * side * side / elapsed / 1e6);
    return 0;
}
