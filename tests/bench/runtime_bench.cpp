// runtime_bench.cpp - speed of the runtime against baselines measured in the same run: tile evaluation
// vs spectral ADSN synthesis with KissFFT (2048 x 2048 RGB, 31 x 31 texton, 30 impacts per pixel; with
// each copy of the tile code the CPU runs: SSE2, AVX2, AVX-512 on x86-64), per-point evaluation vs
// stb_perlin_noise3 (512 x 512 grid), small tiles vs per point, other texton sizes and densities. Also the
// impulses examined per sample, sizeof(dsn_noise), the stack of a per-point and of a tile call, and the
// chosen cell size.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include <time.h>

#include <kiss_fftnd.h>
#include <stb_perlin.h>

#include "bench_timing.h"
#include "fixtures/test_assets.h"
#include "painted_stack.h"
#include "runtime/core/cell_walk.h"
#include "runtime/core/poisson_count.h"

namespace {

using bench::best_time;
using bench::thread_seconds;

// The median of sorted times.
double median(const std::vector<double> &sorted) { return sorted[sorted.size() / 2]; }

// Spectral ADSN of the same texton on an n x n torus, as a careful KissFFT user writes it: one forward
// FFT of the white noise shared by the channels, the texton spectra applied, and two inverse FFTs (R and
// G packed as real and imaginary parts of one, then B). The texton spectra are precomputed (like loading
// an asset; mean, colour transform and 1/sqrt(lambda) fold into them for free): only the synthesis is
// timed. All transforms are complex because this package's real N-D transform (kiss_fftndr) fails to
// allocate at this size; a hand-built real 2-D FFT could save up to a third of this baseline.
struct SpectralAdsn {
    int n;
    kiss_fftnd_cfg forward, inverse;
    std::vector<std::complex<float>> texton_spectrum[3], noise, spectrum, result;
    std::vector<float> image;

    SpectralAdsn(const dsn_asset &asset, int side) : n(side) {
        const int dims[2] = {n, n};
        forward = kiss_fftnd_alloc(dims, 2, 0, nullptr, nullptr);
        inverse = kiss_fftnd_alloc(dims, 2, 1, nullptr, nullptr);
        const size_t size = size_t(n) * n;
        noise.resize(size);
        spectrum.resize(size);
        result.resize(size);
        image.resize(size * 3);
        for (uint32_t c = 0; c < 3; c++) {
            std::vector<std::complex<float>> texton(size);
            const int rx = int(asset.width - 1) / 2, ry = int(asset.height - 1) / 2;
            for (uint32_t row = 0; row < asset.height; row++)
                for (uint32_t column = 0; column < asset.width; column++) {
                    int x = (int(column) - rx + n) % n, y = (int(row) - ry + n) % n;
                    texton[size_t(y) * n + x] = float(dsn_asset_texton_value(&asset, row, column, c));
                }
            texton_spectrum[c].resize(size);
            kiss_fftnd(forward, reinterpret_cast<kiss_fft_cpx *>(texton.data()),
                       reinterpret_cast<kiss_fft_cpx *>(texton_spectrum[c].data()));
        }
    }
    ~SpectralAdsn() {
        kiss_fft_free(forward);
        kiss_fft_free(inverse);
    }

    void synthesize(uint32_t seed) {
        const size_t size = size_t(n) * n;
        uint32_t state = seed * 2654435761u + 1;
        for (size_t i = 0; i < size; i++) { // uniform white noise, zero mean
            state ^= state << 13, state ^= state >> 17, state ^= state << 5;
            noise[i] = float(int32_t(state >> 8) - (1 << 23)) * (1.0f / (1 << 23));
        }
        kiss_fftnd(forward, reinterpret_cast<kiss_fft_cpx *>(noise.data()),
                   reinterpret_cast<kiss_fft_cpx *>(spectrum.data()));
        const std::complex<float> i_unit(0, 1);
        for (size_t i = 0; i < size; i++)
            noise[i] = spectrum[i] * (texton_spectrum[0][i] + i_unit * texton_spectrum[1][i]);
        kiss_fftnd(inverse, reinterpret_cast<kiss_fft_cpx *>(noise.data()),
                   reinterpret_cast<kiss_fft_cpx *>(result.data()));
        for (size_t i = 0; i < size; i++)
            image[3 * i] = result[i].real(), image[3 * i + 1] = result[i].imag();
        for (size_t i = 0; i < size; i++) noise[i] = spectrum[i] * texton_spectrum[2][i];
        kiss_fftnd(inverse, reinterpret_cast<kiss_fft_cpx *>(noise.data()),
                   reinterpret_cast<kiss_fft_cpx *>(result.data()));
        for (size_t i = 0; i < size; i++) image[3 * i + 2] = result[i].real();
    }
};

// Cells visited and impulses examined by the per-point path at (x, y): the same walk, counted.
void count_work(const dsn_noise &noise, uint32_t x, uint32_t y, uint64_t *cells, uint64_t *impulses) {
    dsn_axis axis_x, axis_y;
    dsn_axis_init(&axis_x, x, 1, dsn_state(&noise)->radius[0], dsn_state(&noise)->cell_shift,
                  dsn_state(&noise)->period[0]);
    dsn_axis_init(&axis_y, y, 1, dsn_state(&noise)->radius[1], dsn_state(&noise)->cell_shift,
                  dsn_state(&noise)->period[1]);
    dsn_span span_x = dsn_axis_span(&axis_x, 0), span_y = dsn_axis_span(&axis_y, 0);
    for (uint32_t i = 0; i < span_y.cell_count; i++)
        for (uint32_t j = 0; j < span_x.cell_count; j++) {
            uint32_t key =
                dsn_cell_key(dsn_state(&noise), dsn_span_cell(&span_x, j, dsn_state(&noise)->cell_shift),
                             dsn_span_cell(&span_y, i, dsn_state(&noise)->cell_shift));
            *cells += 1;
            *impulses += dsn_cell_impulse_count(dsn_state(&noise), key);
        }
}

} // namespace

int main() {
    auto fields = dsn_test::synthetic_fields(3, 31, 8, DSN_SHAPE_RECTANGLE, 7);
    dsn_test::LoadedNoise loaded(fields, dsn_test::make_config(1, 30));
    const dsn_noise &noise = loaded.noise;
    std::printf("asset: RGB 31x31 8-bit texton, 30 impacts per pixel; cell size %u (mean %.2f impulses per "
                "cell, %u Poisson draw(s), table of %u entries)\n",
                1u << dsn_state(&noise)->cell_shift,
                30.0 / 961 * double(1u << (2 * dsn_state(&noise)->cell_shift)),
                dsn_state(&noise)->poisson_parts, dsn_state(&noise)->poisson_size);

    // Tile vs spectral ADSN: thread CPU times, minimum and median of several runs of each. The machine
    // has slower phases lasting about a second, so the runs are interleaved one by one: every round runs
    // each of them once, in an order shuffled anew each round (with a fixed seed; a rotation would keep
    // which job follows which), and no copy's runs clump in one phase.
    const uint32_t side = 2048;
    const size_t values = size_t(side) * side * 3;
    std::vector<int32_t> tile(values);
    std::vector<uint8_t> tile_u8(values);
    std::vector<float> tile_float(values);
    std::vector<unsigned char> scratch(dsn_lattice_tile_scratch_size(&noise, side, side));
    SpectralAdsn adsn(loaded.asset, int(side));
    uint32_t seed = 0;
    // The same tile with the other copies of the tile code this CPU runs (the rows of the kernel table
    // before the chosen one: on x86-64 SSE2, AVX2, AVX-512), timed in the same rounds as often as the
    // chosen copy.
    const uint32_t other_copies = dsn_state(&noise)->tile_kernel;
    const char *copy_names[] = {"SSE2", "AVX2", "AVX-512", "AVX-512 (AVX2 RGB lattice tiles)"};
    std::vector<double> tile_times, u8_times, float_times, adsn_times;
    std::vector<std::vector<double>> copy_times(other_copies);
    std::vector<dsn_noise> copies(other_copies, noise);
    for (uint32_t kernel = 0; kernel < other_copies; kernel++)
        dsn_state(&copies[kernel])->tile_kernel = kernel;
    auto time_once = [](std::vector<double> &times, auto work) {
        const double start = thread_seconds();
        work();
        times.push_back(thread_seconds() - start);
    };
    // Job j of a round: 0 the chosen copy (fixed), 1 u8, 2 float, 3 ADSN, 4 + k the other copy k.
    auto run_job = [&](uint32_t job) {
        if (job == 0)
            time_once(tile_times, [&] {
                dsn_lattice_tile_fixed(&noise, -1000, 5000, side, side, tile.data(), nullptr, 0);
            });
        else if (job == 1)
            time_once(u8_times, [&] {
                dsn_lattice_tile_u8(&noise, -1000, 5000, side, side, tile_u8.data(), scratch.data(),
                                    scratch.size());
            });
        else if (job == 2)
            time_once(float_times, [&] {
                dsn_lattice_tile_float(&noise, -1000, 5000, side, side, tile_float.data(), scratch.data(),
                                       scratch.size());
            });
        else if (job == 3)
            time_once(adsn_times, [&] { adsn.synthesize(++seed); });
        else
            time_once(copy_times[job - 4], [&] {
                dsn_lattice_tile_fixed(&copies[job - 4], -1000, 5000, side, side, tile.data(), nullptr, 0);
            });
    };
    std::vector<uint32_t> order(4 + other_copies);
    for (uint32_t j = 0; j < order.size(); j++) order[j] = j;
    std::mt19937 shuffler(12345);
    for (int round = 0; round < 9; round++) {
        std::shuffle(order.begin(), order.end(), shuffler);
        for (uint32_t job : order) run_job(job);
    }
    for (auto *times : {&tile_times, &u8_times, &float_times, &adsn_times})
        std::sort(times->begin(), times->end());
    for (auto &times : copy_times) std::sort(times.begin(), times.end());
    double megapixels = double(side) * side / 1e6;
    std::printf("tile 2048x2048 RGB, %s tile code (thread CPU time, min / median of %zu runs): fixed %.1f / "
                "%.1f ms (%.0f Mpixel/s), u8 %.1f / %.1f ms, float %.1f / %.1f ms\n",
                other_copies != 0 ? copy_names[dsn_state(&noise)->tile_kernel] : "default", tile_times.size(),
                tile_times[0] * 1e3, median(tile_times) * 1e3, megapixels / tile_times[0], u8_times[0] * 1e3,
                median(u8_times) * 1e3, float_times[0] * 1e3, median(float_times) * 1e3);
    std::printf("spectral ADSN (KissFFT) %.1f / %.1f ms; tile speed-up min/min %.1fx, median/median %.1fx "
                "(target >= 30x)\n",
                adsn_times[0] * 1e3, median(adsn_times) * 1e3, adsn_times[0] / tile_times[0],
                median(adsn_times) / median(tile_times));
    for (uint32_t kernel = 0; kernel < other_copies; kernel++)
        std::printf(
            "the %s tile code on the same tile: fixed %.1f / %.1f ms, speed-up over ADSN min/min %.1fx, "
            "median/median %.1fx\n",
            copy_names[kernel], copy_times[kernel][0] * 1e3, median(copy_times[kernel]) * 1e3,
            adsn_times[0] / copy_times[kernel][0], median(adsn_times) / median(copy_times[kernel]));

    // Per point vs stb_perlin_noise3 over a 512 x 512 grid, the two timed in turn seven times (the
    // machine is shared): the ratio of the best times, and the median of the seven ratios.
    const int grid = 512;
    volatile int32_t sink = 0;
    volatile float perlin_sink = 0;
    auto point_pass = [&] {
        int32_t out[3], total = 0;
        for (int y = 0; y < grid; y++)
            for (int x = 0; x < grid; x++) {
                dsn_lattice_point_fixed(&noise, x, y, out);
                total += out[0] ^ out[1] ^ out[2];
            }
        sink = total;
    };
    auto perlin_pass = [&] {
        float total = 0;
        for (int y = 0; y < grid; y++)
            for (int x = 0; x < grid; x++)
                total += stb_perlin_noise3(float(x) * 0.173f, float(y) * 0.173f, 0.5f, 0, 0, 0);
        perlin_sink = total;
    };
    double point_time = 1e30, perlin_time = 1e30;
    std::vector<double> ratios;
    for (int run = 0; run < 7; run++) {
        double point_run = best_time(1, point_pass), perlin_run = best_time(1, perlin_pass);
        point_time = std::min(point_time, point_run);
        perlin_time = std::min(perlin_time, perlin_run);
        ratios.push_back(point_run / perlin_run);
    }
    std::sort(ratios.begin(), ratios.end());
    double samples = double(grid) * grid;
    uint64_t cells = 0, impulses = 0;
    for (int y = 0; y < grid; y++)
        for (int x = 0; x < grid; x++) count_work(noise, uint32_t(x), uint32_t(y), &cells, &impulses);
    std::printf(
        "per point: %.1f ns per RGB sample; stb_perlin_noise3 %.1f ns per call; ratio %.2fx best, %.2fx "
        "median of 7 (target <= 8x); %.1f cells and %.1f impulses examined per sample (%.1f reach it)\n",
        point_time / samples * 1e9, perlin_time / samples * 1e9, point_time / perlin_time, ratios[3],
        double(cells) / samples, double(impulses) / samples,
        30.0 * loaded.asset.width * loaded.asset.height / loaded.asset.support_size);
    // Small tiles (a tile call prepares the texton once, then its cost is per pixel): per pixel, and as
    // a speed-up over the per-point calls timed above.
    std::printf("small tiles, ns per pixel (speed-up over per point):");
    for (uint32_t small : {8u, 16u, 32u, 64u, 256u}) {
        std::vector<int32_t> small_tile(size_t(small) * small * 3);
        const long calls = std::max(8L, long(1u << 20) / long(small * small));
        double small_time = 1e30;
        for (int run = 0; run < 5; run++)
            small_time = std::min(small_time, best_time(1, [&] {
                                      for (long i = 0; i < calls; i++)
                                          dsn_lattice_tile_fixed(&noise, int32_t(i * 977), int32_t(i * 131),
                                                                 small, small, small_tile.data(), nullptr, 0);
                                  }));
        const double per_pixel = small_time / (double(calls) * small * small);
        std::printf(" %ux%u %.1f (%.0fx)", small, small, per_pixel * 1e9, point_time / samples / per_pixel);
    }
    std::printf("\n");
    // Other texton sizes and densities (denser noises get smaller rectangles, the densest the 32-bit
    // path): 512 x 512 RGB tiles, ns per pixel, and as a multiple of this run's 31 x 31, 30 impacts tile.
    std::printf("512x512 tiles by texton side and impacts, ns per pixel (x the 31x31/30 tile):");
    std::vector<int32_t> sweep_tile(512 * 512 * 3);
    const double reference = tile_times[0] / (double(side) * side);
    for (uint32_t texton_side : {9u, 21u, 31u, 41u})
        for (double impacts : {10.0, 60.0}) {
            dsn_test::LoadedNoise other(dsn_test::synthetic_fields(3, texton_side, 8, DSN_SHAPE_RECTANGLE, 7),
                                        dsn_test::make_config(1, impacts));
            double sweep_time = 1e30;
            for (int run = 0; run < 3; run++)
                sweep_time = std::min(sweep_time, best_time(1, [&] {
                                          dsn_lattice_tile_fixed(&other.noise, 77, -88, 512, 512,
                                                                 sweep_tile.data(), nullptr, 0);
                                      }));
            const double per_pixel = sweep_time / (512.0 * 512.0);
            std::printf(" %u/%.0f %.1f (%.1fx)", texton_side, impacts, per_pixel * 1e9,
                        per_pixel / reference);
        }
    std::printf("\n");
    // A default (bilinear) bake read on the lattice reads its lattice texton (format 1.3) through a view of
    // the noise: per point and per 512 x 512 tile against the 31 x 31 lattice asset above, interleaved,
    // best of 7. A 29 x 29 bilinear texton has a 31 x 31 lattice texton (the view's own cost); a 31 x 31
    // one, the default bake's size, has 33 x 33.
    std::printf("default bake on the lattice (x the 31x31 lattice asset), per point / 512x512 tile:");
    for (uint32_t bilinear_side : {29u, 31u}) {
        dsn::AssetFields bilinear = dsn_test::synthetic_fields(3, bilinear_side, 8, DSN_SHAPE_RECTANGLE, 7);
        bilinear.interpolation = DSN_INTERPOLATION_BILINEAR;
        dsn::set_lattice_texton(bilinear);
        dsn_test::LoadedNoise viewed(bilinear, dsn_test::make_config(1, 30));
        double times[2][2] = {{1e30, 1e30}, {1e30, 1e30}}; /* [asset][point, tile] */
        for (int run = 0; run < 7; run++)
            for (int which = 0; which < 2; which++) {
                const dsn_noise &each = which == 0 ? noise : viewed.noise;
                times[which][0] = std::min(times[which][0], best_time(1, [&] {
                                               int32_t out[3], total = 0;
                                               for (int y = 0; y < 256; y++)
                                                   for (int x = 0; x < 256; x++) {
                                                       dsn_lattice_point_fixed(&each, x, y, out);
                                                       total += out[0];
                                                   }
                                               sink = total;
                                           }));
                times[which][1] = std::min(times[which][1], best_time(1, [&] {
                                               dsn_lattice_tile_fixed(&each, 77, -88, 512, 512,
                                                                      sweep_tile.data(), nullptr, 0);
                                           }));
            }
        std::printf(" %ux%u bilinear (lattice texton %ux%u) %.2fx / %.2fx", bilinear_side, bilinear_side,
                    bilinear.lattice_width, bilinear.lattice_height, times[1][0] / times[0][0],
                    times[1][1] / times[0][1]);
    }
    std::printf("\n");
    int32_t point_out[3];
    std::vector<int32_t> tile_out(64 * 64 * 3);
    const size_t point_stack =
        bench::painted_stack([&] { dsn_lattice_point_fixed(&noise, 12345, -678, point_out); });
    std::printf("sizeof(dsn_noise) = %zu bytes, sizeof(dsn_asset) = %zu bytes; stack (painted) of one "
                "per-point call: %zu bytes, of a tile call:",
                sizeof(dsn_noise), sizeof(dsn_asset), point_stack);
    for (uint32_t kernel = 0; kernel <= other_copies; kernel++) {
        dsn_noise copy = noise;
        dsn_state(&copy)->tile_kernel = kernel;
        const size_t tile_stack = bench::painted_stack(
            [&] { dsn_lattice_tile_fixed(&copy, 5, 7, 64, 64, tile_out.data(), nullptr, 0); });
        std::printf(" %zu bytes (%s tile code)", tile_stack,
                    other_copies != 0 ? copy_names[kernel] : "default");
    }
    std::printf("\n");
    (void)sink;
    (void)perlin_sink;
    return 0;
}
