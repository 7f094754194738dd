// continuous_bench.cpp - cost of the continuous (renderer) mode as ratios to the lattice mode measured in
// the same run: per point over a 512 x 512 grid, tiles rotated and axis-aligned at two zooms with every
// copy of the tile code this CPU runs (each timed in rounds beside its own lattice tile), and random points
// one by one and as a batch (the batch in every copy too), RGB, 31 x 31 texton, 30 impacts per pixel, one
// thread; and each copy's splat kernel in its best case (splat_best_case.h) against what a tile at 1/8 of
// the lattice tile leaves each impulse and pixel.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "bench_timing.h"
#include "fixtures/continuous_fixtures.h"
#include "painted_stack.h"
#include "runtime/setup/noise_state.h"
#include "splat_best_case.h"

namespace {

using bench::best_time;
const uint32_t kSide = 512;

int64_t checksum = 0; // keeps the evaluations observable

} // namespace

int main() {
    using namespace continuous_fixtures;
    const uint32_t impacts = 30; // per pixel
    auto noise = make_noise(random_texton_asset(3, 15, 8, 1), 1, impacts << 16);
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
    // Grids a renderer asks for, all splatted into the scratch: rotated by 30 degrees and axis-aligned, at
    // 0.7 and 1.7 texels per pixel, each timed with every copy of the tile code this CPU runs (x86-64:
    // SSE2, AVX2, AVX-512) against the lattice tile of the same copy.
    const struct {
        const char *name;
        double degrees, step;
    } grids[] = {{"rotated 30 degrees, 0.7 texel/pixel", 30, 0.7},
                 {"rotated 30 degrees, 1.7 texel/pixel", 30, 1.7},
                 {"axis-aligned, 0.7 texel/pixel", 0, 0.7},
                 {"axis-aligned, 1.7 texel/pixel", 0, 1.7}};
    const uint32_t grid_count = sizeof grids / sizeof grids[0];
    const char *copy_names[] = {"default (SSE2 on x86-64)", "AVX2", "AVX-512",
                                "AVX-512 (AVX2 RGB lattice tiles)"};
    const uint32_t widest = dsn_state(n)->tile_kernel;
    // Each grid tile is timed in rounds beside the lattice tile of the same copy (bench::paired_ratio).
    const int tile_rounds = 5;
    std::vector<double> lattice_tiles(widest + 1, 1e30);
    std::vector<bench::PairedRatio> grid_tiles((widest + 1) * grid_count);
    std::vector<size_t> grid_stacks(widest + 1, 0); // the deepest painted stack of a grid tile call
    for (uint32_t kernel = 0; kernel <= widest; kernel++) {
        dsn_noise copy = *n;
        dsn_state(&copy)->tile_kernel = kernel;
        auto lattice_tile = [&] {
            dsn_lattice_tile_fixed(&copy, 0, 0, kSide, kSide, tile.data(), scratch.data(), scratch.size());
            checksum += tile[7];
        };
        for (uint32_t g = 0; g < grid_count; g++) {
            const double angle = grids[g].degrees * 3.14159265358979323846 / 180.0;
            const int64_t c = int64_t(std::cos(angle) * grids[g].step * double(one));
            const int64_t s = int64_t(std::sin(angle) * grids[g].step * double(one));
            const dsn_grid grid = {one / 3, one / 7, c, s, -s, c};
            std::vector<unsigned char> grid_scratch(
                dsn_continuous_tile_scratch_size(&copy, &grid, kSide, kSide));
            const bench::PairedRatio cost = bench::paired_ratio(tile_rounds, lattice_tile, [&] {
                dsn_continuous_tile_fixed(&copy, &grid, kSide, kSide, tile.data(), grid_scratch.data(),
                                          grid_scratch.size());
                checksum += tile[7];
            });
            grid_tiles[kernel * grid_count + g] = cost;
            grid_stacks[kernel] =
                std::max(grid_stacks[kernel], bench::painted_stack([&] {
                             dsn_continuous_tile_fixed(&copy, &grid, kSide, kSide, tile.data(),
                                                       grid_scratch.data(), grid_scratch.size());
                         }));
            lattice_tiles[kernel] = std::min(lattice_tiles[kernel], cost.baseline_best);
        }
    }
    // 4096 random points (a renderer's ray hits) one by one, against as many lattice points.
    const size_t batch = 4096;
    std::vector<int64_t> batch_x(batch), batch_y(batch);
    std::vector<int32_t> lattice_x(batch), lattice_y(batch), batch_out(batch * 3);
    std::mt19937_64 random(42);
    for (size_t k = 0; k < batch; k++) {
        batch_x[k] = int64_t(random() >> 20) - (int64_t(1) << 43);
        batch_y[k] = int64_t(random() >> 20) - (int64_t(1) << 43);
        lattice_x[k] = int32_t(batch_x[k] >> 32);
        lattice_y[k] = int32_t(batch_y[k] >> 32);
    }
    auto points_pass = [&] {
        for (size_t k = 0; k < batch; k++)
            dsn_continuous_point_fixed(n, batch_x[k], batch_y[k], &batch_out[k * 3]);
        checksum += batch_out[5];
    };
    // The same points as one batch (dsn_continuous_batch_fixed).
    std::vector<unsigned char> batch_scratch(dsn_continuous_batch_scratch_size(n));
    auto batch_pass = [&] {
        dsn_continuous_batch_fixed(n, batch_x.data(), batch_y.data(), uint32_t(batch), batch_out.data(),
                                   batch_scratch.data(), batch_scratch.size());
        checksum += batch_out[5];
    };
    auto lattice_pass = [&] {
        int32_t out[3];
        for (size_t k = 0; k < batch; k++) {
            dsn_lattice_point_fixed(n, lattice_x[k], lattice_y[k], out);
            checksum += out[0];
        }
    };
    // The three timed in rounds (the machine is shared): best of each, and the median of the per-round
    // ratios to the lattice per point.
    const int rounds = 7;
    const auto times = bench::timed_rounds(rounds, {points_pass, batch_pass, lattice_pass});
    const double batch_time = bench::fastest(times[0]), batch_call_time = bench::fastest(times[1]),
                 lattice_random = bench::fastest(times[2]);
    // The batch in the narrower kernels this CPU runs too (the copies built for other instruction sets).
    std::vector<double> copy_batch_times;
    for (uint32_t kernel = 0; kernel < widest; kernel++) {
        dsn_noise copy = *n;
        dsn_state(&copy)->tile_kernel = kernel;
        copy_batch_times.push_back(best_time(5, [&] {
            dsn_continuous_batch_fixed(&copy, batch_x.data(), batch_y.data(), uint32_t(batch),
                                       batch_out.data(), batch_scratch.data(), batch_scratch.size());
            checksum += batch_out[5];
        }));
    }

    std::printf("continuous mode, RGB 31x31 texton, 30 impacts per pixel, cell side %u, one thread:\n",
                1u << dsn_state(n)->cell_shift);
    std::printf("  per point: lattice %.0f ns/sample, continuous %.0f ns/sample: ratio %.2f\n",
                lattice_point / samples * 1e9, continuous_point / samples * 1e9,
                continuous_point / lattice_point);
    for (uint32_t kernel = widest + 1; kernel-- > 0;) {
        std::printf("  %s tile code: lattice tile 512x512 %.1f Mpixel/s (best of its runs)\n",
                    copy_names[kernel], samples / lattice_tiles[kernel] / 1e6);
        for (uint32_t g = 0; g < grid_count; g++) {
            const bench::PairedRatio &cost = grid_tiles[kernel * grid_count + g];
            std::printf("    continuous tile %s: %.1f Mpixel/s, 1/%.1f of the lattice tile (best over best; "
                        "median of %d paired rounds 1/%.1f)\n",
                        grids[g].name, samples / (cost.best * cost.baseline_best) / 1e6, cost.best,
                        tile_rounds, cost.median);
        }
        // What 1/8 of the lattice tile (the target) leaves each impulse and pixel, against the splat kernel
        // alone.
        std::printf(
            "    the splat kernel at its best (splat_best_case.h): %.2f ns per impulse and pixel, where a "
            "tile at 1/8 of the lattice tile has %.2f in all\n",
            bench::splat_best_case(n, kernel) * 1e9, 8 * lattice_tiles[kernel] / samples / impacts * 1e9);
    }
    std::printf("  %zu random points: continuous %.0f ns/point, lattice per point %.0f ns/point: "
                "ratio %.2f best, %.2f median of %d\n",
                batch, batch_time / double(batch) * 1e9, lattice_random / double(batch) * 1e9,
                batch_time / lattice_random, bench::median_ratio(times[0], times[2]), rounds);
    std::printf(
        "  %zu random points as one batch: %.0f ns/point: ratio %.2f best, %.2f median to the lattice "
        "per point (target <= 1.5), %.2f to the continuous per point\n",
        batch, batch_call_time / double(batch) * 1e9, batch_call_time / lattice_random,
        bench::median_ratio(times[1], times[2]), batch_call_time / batch_time);
    for (uint32_t kernel = 0; kernel < widest; kernel++)
        std::printf("    the batch in the %s copy: %.0f ns/point: ratio %.2f to the lattice per point\n",
                    kernel < 3 ? copy_names[kernel] : "other", copy_batch_times[kernel] / double(batch) * 1e9,
                    copy_batch_times[kernel] / lattice_random);
    int32_t point_out[3];
    std::printf(
        "  stack (painted) of a continuous per-point call: %zu bytes, of a batch call: %zu bytes, of a "
        "continuous tile call:",
        bench::painted_stack([&] { dsn_continuous_point_fixed(n, one / 3, one / 7, point_out); }),
        bench::painted_stack([&] {
            dsn_continuous_batch_fixed(n, batch_x.data(), batch_y.data(), uint32_t(batch), batch_out.data(),
                                       batch_scratch.data(), batch_scratch.size());
        }));
    for (uint32_t kernel = widest + 1; kernel-- > 0;)
        std::printf(" %zu bytes (%s)", grid_stacks[kernel], copy_names[kernel]);
    std::printf("\n  (checksum %lld)\n", static_cast<long long>(checksum));
    return 0;
}
