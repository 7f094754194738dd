// renderer_bench.cpp - the renderer's mode against the nearest published system, in the same run: per
// point, the continuous mode vs the lattice mode vs Texton Noise (texton_noise_baseline.h) on the same
// asset (RGB 31 x 31 8-bit bilinear texton), density (30 impacts per pixel) and rotated grid of 512 x 512
// points, one thread; and the lattice tile's throughput (what dsn-render's tile mode can reach).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <time.h>

#include "bench_timing.h"
#include "fixtures/continuous_fixtures.h"
#include "runtime/setup/noise_state.h"
#include "texton_noise_baseline.h"

namespace {

using bench::best_thread_time;
const uint32_t kSide = 512;
const double kImpacts = 30;

int64_t checksum = 0; // keeps the evaluations observable
float float_sink = 0; // the same for the float baseline

// Per-channel mean and standard deviation of values (channels interleaved).
template <typename Value>
void moments(const std::vector<Value> &values, uint32_t channels, double scale, double *mean,
             double *deviation) {
    for (uint32_t c = 0; c < channels; c++) {
        double sum = 0, squares = 0;
        const size_t count = values.size() / channels;
        for (size_t i = 0; i < count; i++) {
            const double value = double(values[i * channels + c]) * scale;
            sum += value, squares += value * value;
        }
        mean[c] = sum / double(count);
        deviation[c] = std::sqrt(std::max(0.0, squares / double(count) - mean[c] * mean[c]));
    }
}

} // namespace

int main() {
    using namespace continuous_fixtures;
    auto made = make_noise(random_texton_asset(3, 15, 8, 1), 1, uint32_t(kImpacts * 65536));
    const dsn_noise *noise = &made->noise;
    const texton_noise::Baseline baseline(made->asset, kImpacts, 1);
    const double samples = double(kSide) * kSide;

    // A rotated grid of real-valued points (what a renderer asks for), about 3 texels apart so that
    // consecutive points share few cells (as a renderer's scattered ray hits).
    const double step_x = 2.8191, step_y = 1.0261;
    std::vector<int64_t> points(size_t(samples) * 2);
    std::vector<float> float_points(size_t(samples) * 2);
    for (uint32_t y = 0, i = 0; y < kSide; y++)
        for (uint32_t x = 0; x < kSide; x++, i++) {
            const double px = 1000.0 + x * step_x - y * step_y + 1.0 / 3,
                         py = 2000.0 + x * step_y + y * step_x + 1.0 / 7;
            points[2 * i] = dsn_coordinate_from_double(px);
            points[2 * i + 1] = dsn_coordinate_from_double(py);
            float_points[2 * i] = float(px);
            float_points[2 * i + 1] = float(py);
        }
    std::vector<int32_t> continuous_values(size_t(samples) * 3);
    std::vector<float> baseline_values(size_t(samples) * 3);

    auto lattice_pass = [&] {
        int32_t out[3];
        for (uint32_t y = 0; y < kSide; y++)
            for (uint32_t x = 0; x < kSide; x++) {
                dsn_lattice_point_fixed(noise, int32_t(x * 3), int32_t(y * 3), out);
                checksum += out[0];
            }
    };
    auto continuous_pass = [&] {
        for (size_t i = 0; i < size_t(samples); i++)
            dsn_continuous_point_fixed(noise, points[2 * i], points[2 * i + 1], &continuous_values[3 * i]);
        checksum += continuous_values[7];
    };
    auto baseline_pass = [&] {
        for (size_t i = 0; i < size_t(samples); i++)
            baseline.evaluate(float_points[2 * i], float_points[2 * i + 1], &baseline_values[3 * i]);
        float_sink += baseline_values[7];
    };
    // The three timed in rounds (the machine is shared): best of each, and the median of the per-round
    // ratios.
    const int rounds = 5;
    const auto times = bench::timed_rounds(rounds, {lattice_pass, continuous_pass, baseline_pass});
    const double lattice_time = bench::fastest(times[0]), continuous_time = bench::fastest(times[1]),
                 baseline_time = bench::fastest(times[2]);

    // The lattice tile (2048 x 2048, fixed point), the ceiling of a renderer's tile mode.
    const uint32_t tile_side = 2048;
    std::vector<int32_t> tile(size_t(tile_side) * tile_side * 3);
    const double tile_time = best_thread_time(3, [&] {
        dsn_lattice_tile_fixed(noise, -1000, 5000, tile_side, tile_side, tile.data(), nullptr, 0);
        checksum += tile[7];
    });

    // Both noises have the asset's mean and nearly its covariance: their moments over the grid show that
    // the baseline computes the same texture (bilinear spots and the Gaussian count change little).
    double dsn_mean[3], dsn_deviation[3], baseline_mean[3], baseline_deviation[3];
    moments(continuous_values, 3, 1.0 / DSN_ONE, dsn_mean, dsn_deviation);
    moments(baseline_values, 3, 1.0, baseline_mean, baseline_deviation);

    std::printf("renderer mode, RGB 31x31 8-bit bilinear texton, %.0f impacts per pixel, cell side %u, one "
                "thread (thread CPU time), 512x512 points of a rotated grid:\n",
                kImpacts, 1u << dsn_state(noise)->cell_shift);
    std::printf(
        "  per point: lattice %.0f ns, continuous %.0f ns, Texton Noise (float, Gaussian counts) %.0f "
        "ns per RGB sample\n",
        lattice_time / samples * 1e9, continuous_time / samples * 1e9, baseline_time / samples * 1e9);
    std::printf("  continuous / lattice %.2fx best, %.2fx median of %d (target <= 2.5x); Texton Noise / "
                "continuous %.2fx best, %.2fx median (target >= 4x)\n",
                continuous_time / lattice_time, bench::median_ratio(times[1], times[0]), rounds,
                baseline_time / continuous_time, 1 / bench::median_ratio(times[1], times[2]));
    std::printf("  lattice tile 2048x2048 fixed: %.0f Mpixel/s\n",
                double(tile_side) * tile_side / tile_time / 1e6);
    std::printf("  moments over the grid, mean / deviation per channel: continuous");
    for (int c = 0; c < 3; c++) std::printf(" %.3f/%.3f", dsn_mean[c], dsn_deviation[c]);
    std::printf("; Texton Noise");
    for (int c = 0; c < 3; c++) std::printf(" %.3f/%.3f", baseline_mean[c], baseline_deviation[c]);
    std::printf("\n  (checksum %lld %g)\n", static_cast<long long>(checksum), double(float_sink));
    return 0;
}
