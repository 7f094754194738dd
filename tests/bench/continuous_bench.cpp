// continuous_bench.cpp - cost of the continuous (renderer) mode as ratios to the lattice mode measured in
// the same run: per point over a 512 x 512 grid, and as a tile, RGB, 31 x 31 texton, 30 impacts per
// pixel, one thread.
#include <chrono>
#include <cstdio>
#include <vector>

#include "../../runtime/noise_state.h"
#include "../fixtures/continuous_fixtures.h"
#include "bench_timing.h"

namespace {

using bench::best_time;
const uint32_t kSide = 512;

int64_t checksum = 0; // keeps the evaluations observable

} // namespace

int main() {
    using namespace continuous_fixtures;
    auto noise = make_noise(random_texton_asset(3, 15, 8, 1), 1, 30u << 16);
    const dsn_noise *n = &noise->noise;
    const double samples = double(kSide) * kSide;
    const int64_t one = int64_t(1) << 32;

    const double lattice_point = best_time(3, [&] {
        int32_t out[3];
        for (uint32_t y = 0; y < kSide; y++)
            for (uint32_t x = 0; x < kSide; x++) {
                dsn_lattice_point_fixed(n, int32_t(x * 3), int32_t(y * 3), out);
                checksum += out[0];
            }
    });
    // Real-valued points off the lattice, on a rotated grid (what a renderer asks for).
    const int64_t step_x = int64_t(2.8191 * double(one)), step_y = int64_t(1.0261 * double(one));
    const double continuous_point = best_time(3, [&] {
        int32_t out[3];
        for (uint32_t y = 0; y < kSide; y++)
            for (uint32_t x = 0; x < kSide; x++) {
                dsn_continuous_point_fixed(n, int64_t(x) * step_x - int64_t(y) * step_y + one / 3,
                                           int64_t(x) * step_y + int64_t(y) * step_x + one / 7, out);
                checksum += out[0];
            }
    });
    std::vector<int32_t> tile(size_t(samples) * 3);
    std::vector<unsigned char> scratch(dsn_lattice_tile_scratch_size(n, kSide, kSide));
    const double lattice_tile = best_time(3, [&] {
        dsn_lattice_tile_fixed(n, 0, 0, kSide, kSide, tile.data(), scratch.data(), scratch.size());
        checksum += tile[7];
    });
    // A rotated grid (evaluated point by point) and an axis-aligned zoom (splatted into the scratch).
    const dsn_grid rotated = {one / 3, one / 7, step_x, step_y, -step_y, step_x};
    const double rotated_tile = best_time(3, [&] {
        dsn_continuous_tile_fixed(n, &rotated, kSide, kSide, tile.data(), nullptr, 0);
        checksum += tile[7];
    });
    const int64_t zoom_step = int64_t(0.7 * double(one));
    const dsn_grid zoomed = {one / 3, one / 7, zoom_step, 0, 0, zoom_step};
    std::vector<unsigned char> grid_scratch(dsn_continuous_tile_scratch_size(n, &zoomed, kSide, kSide));
    const double zoomed_tile = best_time(3, [&] {
        dsn_continuous_tile_fixed(n, &zoomed, kSide, kSide, tile.data(), grid_scratch.data(),
                                  grid_scratch.size());
        checksum += tile[7];
    });

    std::printf("continuous mode, RGB 31x31 texton, 30 impacts per pixel, cell side %u, one thread:\n",
                1u << dsn_state(n)->cell_shift);
    std::printf("  per point: lattice %.0f ns/sample, continuous %.0f ns/sample: ratio %.2f\n",
                lattice_point / samples * 1e9, continuous_point / samples * 1e9,
                continuous_point / lattice_point);
    std::printf("  tile 512x512: lattice %.1f Mpixel/s; continuous axis-aligned zoom 1/0.7 %.1f Mpixel/s "
                "(ratio %.2f), rotated %.1f Mpixel/s (ratio %.2f)\n",
                samples / lattice_tile / 1e6, samples / zoomed_tile / 1e6, zoomed_tile / lattice_tile,
                samples / rotated_tile / 1e6, rotated_tile / lattice_tile);
    std::printf("  (checksum %lld)\n", static_cast<long long>(checksum));
    return 0;
}
