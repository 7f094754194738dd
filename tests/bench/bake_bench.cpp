// bake_bench.cpp - speed of the SOT: 256x256 RGB, r = 15, 1000 iterations (target <= 4 s on one core),
// the share of that time spent in FFTs, and the pruned iteration against the straightforward full-FFT
// reference measured in the same run. Then whole default bakes (early stop, every core) of 256x256 and
// 1024x1024 RGB (targets <= 0.5 s and <= 5 s wall), each against the 1000-iteration bake of the same
// exemplar in the same run: time ratio and RME difference, over several runs (the machine is shared).
// Then every photo in ../shared/textures (DSN_TEXTURES overrides it; skipped when absent): its default
// bake against its 1000-iteration bake, the early stop's RME gap (target <= 0.005) and time. Last, the
// histogram-preserving bake (--histogram) of the 256x256 exemplar against the plain one, runs
// interleaved, and the time of its own steps (colour basis, Gaussianization, tables) alone.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <stdexcept>
#include <string>
#include <vector>

#include <kiss_fft.h>

#include "fixtures/bake_fixtures.h"
#include "offline/bake_internal.h"

namespace {

struct Timing {
    double wall, cpu;
};

template <typename Work>
Timing measure(Work work) {
    const auto wall_start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    work();
    return {std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count(),
            double(std::clock() - cpu_start) / CLOCKS_PER_SEC};
}

// A 256x256 RGB texture: colour-correlated filtered noise, like a photo's spectrum (decaying).
dsn::Image exemplar(int size) {
    dsn::Image image;
    image.width = image.height = size, image.channels = 3;
    const dsn::Image noise = dsn::white_noise(size, size, 17);
    image.values.resize(size_t(size) * size_t(size) * 3);
    for (int c = 0; c < 3; c++)
        for (int y = 0; y < size; y++)
            for (int x = 0; x < size; x++) {
                double sum = 0;
                for (int d = -2; d <= 2; d++)
                    sum += noise.at((x + d + size) % size, y, 0) +
                           noise.at(x, (y + d * (c + 1) + size) % size, 0);
                image.at(x, y, c) = 0.5 + 0.03 * sum;
            }
    return image;
}

// The FFTs one pruned iteration performs (sot.cpp): C (M/2 + 1) column transforms each way of length N,
// and ceil(C (2r+1) / 2) row transforms each way of length M.
double fft_only_seconds(int width, int height, int channels, int radius, int iterations) {
    kiss_fft_cfg column = kiss_fft_alloc(height, 0, nullptr, nullptr);
    kiss_fft_cfg row = kiss_fft_alloc(width, 0, nullptr, nullptr);
    std::vector<kiss_fft_cpx> in(size_t(std::max(width, height)), kiss_fft_cpx{0.25f, -0.5f}), out(in.size());
    const int columns = 2 * channels * (width / 2 + 1), rows = 2 * ((channels * (2 * radius + 1) + 1) / 2);
    const Timing timing = measure([&] {
        for (int i = 0; i < iterations; i++) {
            for (int k = 0; k < columns; k++) kiss_fft(column, in.data(), out.data());
            for (int k = 0; k < rows; k++) kiss_fft(row, in.data(), out.data());
        }
    });
    kiss_fft_free(column);
    kiss_fft_free(row);
    return timing.cpu;
}

} // namespace

// Default bakes of a size x size exemplar, `runs` times, against one 1000-iteration bake.
void default_bake(int size, int runs, double target_seconds) {
    const dsn::Image image = exemplar(size);
    dsn::BakeOptions options;
    std::vector<double> walls, cpus;
    dsn::BakeResult result;
    for (int run = 0; run < runs; run++) {
        const Timing timing = measure([&] { result = dsn::bake(image, options); });
        walls.push_back(timing.wall);
        cpus.push_back(timing.cpu);
    }
    options.stop_tolerance = 0;
    dsn::BakeResult full;
    const Timing full_timing = measure([&] { full = dsn::bake(image, options); });
    std::sort(walls.begin(), walls.end());
    std::sort(cpus.begin(), cpus.end());
    std::printf("default bake %dx%d RGB: %zu iterations (%s), wall %.2f s median (%.2f..%.2f over %d runs), "
                "CPU %.2f s  [target <= %.1f s wall: %s]\n",
                size, size, result.sot.rme_per_iteration.size(),
                result.sot.stop == dsn::SotStop::Converged ? "converged" : "iteration limit",
                walls[walls.size() / 2], walls.front(), walls.back(), runs, cpus[cpus.size() / 2],
                target_seconds, walls[walls.size() / 2] <= target_seconds ? "met" : "NOT met");
    std::printf(
        "  1000-iteration bake: wall %.2f s, CPU %.2f s: the default bake is %.1fx faster (wall), RME "
        "%.4f vs %.4f (+%.4f)\n",
        full_timing.wall, full_timing.cpu, full_timing.wall / walls[walls.size() / 2], result.rme, full.rme,
        result.rme - full.rme);
}

// Exemplars too small for the default radius are baked at the largest radius that fits, as the
// baker's refusal suggests.
void shared_texture_gaps() {
    const std::vector<std::string> paths = bake_fixtures::texture_paths();
    if (paths.empty()) {
        std::printf("shared textures: skipped (%s not found)\n", bake_fixtures::textures_folder().c_str());
        return;
    }
    double worst = 0, default_seconds = 0, full_seconds = 0;
    std::string worst_name;
    int within = 0, baked = 0, refused = 0;
    for (const std::string &path : paths) {
        const std::string name = path.substr(path.find_last_of('/') + 1);
        const dsn::Image image = dsn::load_exemplar(path, nullptr);
        dsn::BakeOptions options;
        options.radius = std::min(options.radius, (std::min(image.width, image.height) - 1) / 4);
        if (options.radius < 1) continue;
        dsn::BakeResult early, full;
        Timing early_timing{}, full_timing{};
        try {
            early_timing = measure([&] { early = dsn::bake(image, options); });
            options.stop_tolerance = 0;
            full_timing = measure([&] { full = dsn::bake(image, options); });
        } catch (const std::exception &) { // a constant image: nothing to bake
            refused++;
            continue;
        }
        const double gap = early.rme - full.rme;
        if (gap > worst || worst_name.empty()) worst = gap, worst_name = name;
        within += gap <= 0.005;
        baked++;
        default_seconds += early_timing.wall;
        full_seconds += full_timing.wall;
    }
    std::printf(
        "shared textures: %d photos, default bake RME within 0.005 of the 1000-iteration bake on %d of "
        "%d (largest gap %+.4f, %s) [target: all]; wall %.1f s vs %.1f s in all; %d refused (constant "
        "images)\n",
        baked, within, baked, worst, worst_name.c_str(), default_seconds, full_seconds, refused);
}

// Plain and histogram-preserving default bakes of a size x size exemplar, interleaved, `runs` each.
void histogram_bake(int size, int runs) {
    const dsn::Image image = exemplar(size);
    dsn::BakeOptions options;
    std::vector<double> plain_walls, mapped_walls;
    dsn::BakeResult plain, mapped;
    for (int run = 0; run < runs; run++) {
        options.histogram = false;
        plain_walls.push_back(measure([&] { plain = dsn::bake(image, options); }).wall);
        options.histogram = true;
        mapped_walls.push_back(measure([&] { mapped = dsn::bake(image, options); }).wall);
    }
    std::vector<double> step_walls;
    for (int run = 0; run < runs; run++)
        step_walls.push_back(measure([&] {
                                 const dsn::HistogramModel model = dsn::histogram_model(image);
                                 dsn::gaussianize(image, model);
                                 dsn::histogram_mapping(model, mapped.fields);
                             }).wall);
    std::sort(plain_walls.begin(), plain_walls.end());
    std::sort(mapped_walls.begin(), mapped_walls.end());
    std::sort(step_walls.begin(), step_walls.end());
    const double plain_median = plain_walls[plain_walls.size() / 2];
    std::printf(
        "histogram-preserving bake %dx%d RGB: wall %.3f s median vs plain %.3f s (ratio %.2fx; %zu vs "
        "%zu iterations, the early stop sees another model); its own steps %.4f s = %.1f%% of the "
        "plain bake\n",
        size, size, mapped_walls[mapped_walls.size() / 2], plain_median,
        mapped_walls[mapped_walls.size() / 2] / plain_median, mapped.sot.rme_per_iteration.size(),
        plain.sot.rme_per_iteration.size(), step_walls[step_walls.size() / 2],
        100 * step_walls[step_walls.size() / 2] / plain_median);
}

int main() {
    const int size = 256, radius = 15, iterations = 1000, reference_iterations = 40;
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar(size), true);
    const dsn::Support support = dsn::support_mask(radius, DSN_SHAPE_RECTANGLE);
    dsn::SotOptions options;
    options.iterations = iterations;
    dsn::SotResult pruned;
    const Timing fast =
        measure([&] { pruned = dsn::sot_alternating_projections(model.spectrum, support, options); });
    options.iterations = reference_iterations;
    options.reference = true;
    const Timing reference =
        measure([&] { dsn::sot_alternating_projections(model.spectrum, support, options); });
    const double ffts = fft_only_seconds(size, size, 3, radius, iterations);

    const double fast_per_iteration = fast.cpu / iterations,
                 reference_per_iteration = reference.cpu / reference_iterations;
    std::printf(
        "SOT 256x256 RGB, r = 15, %d iterations: %.2f s CPU (%.2f s wall), RME %.4f  [target <= 4 s: %s]\n",
        iterations, fast.cpu, fast.wall, pruned.rme_per_iteration.back(), fast.cpu <= 4 ? "met" : "NOT met");
    std::printf("  FFTs alone (same calls and sizes): %.2f s = %.0f%% of the SOT time\n", ffts,
                100 * ffts / fast.cpu);
    std::printf("  per iteration: pruned %.2f ms, full-FFT reference %.2f ms (measured over %d): ratio %.2fx "
                "faster\n",
                1e3 * fast_per_iteration, 1e3 * reference_per_iteration, reference_iterations,
                reference_per_iteration / fast_per_iteration);
    default_bake(256, 5, 0.5);
    default_bake(1024, 3, 5.0);
    shared_texture_gaps();
    histogram_bake(256, 5);
    return 0;
}
