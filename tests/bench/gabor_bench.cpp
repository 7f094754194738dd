// gabor_bench.cpp - the baseline: Gabor noise by example (Galerne, Lagae, Lefebvre and Drettakis,
// SIGGRAPH 2012), against our discrete spot noise on the same grey exemplars (the luminance of texture
// photos), in one run: cost per sample evaluated point by point (and ours on the colour photo), relative
// error of the power spectrum each noise has in expectation, excess kurtosis of each at the density it
// runs, and a side-by-side picture. Float is fine here: this is a measuring stick, not a product.
//
// Gabor noise by example, as the paper builds it:
//   - the exemplar's power spectrum P (of its periodic component, mean removed, |DFT|^2 / N);
//   - a bank of Gabor kernels exp(-pi a^2 |x|^2) cos(2 pi f_k . x + phase) whose frequencies f_k are
//     quantized on a grid of step a / 2 (bandwidth-quantized), one kernel per +-f_k pair; the power
//     spectrum of kernel k under a uniform random phase is B_k(f) = G(f - f_k) + G(f + f_k), with
//     G(f) = exp(-2 pi |f|^2 / a^2) / a^4 (up to a constant folded into the weights);
//   - non-negative least squares: weights w >= 0 minimizing sum_xi (sum_k w_k B_k(xi) - P(xi))^2 over
//     the exemplar's DFT frequencies (here by accelerated projected gradient);
//   - the noise by sparse convolution: the plane cut into cells of the kernel's radius 1/a, each cell
//     seeded by a hash of its coordinates, a Poisson number of impulses per cell, each with a uniform
//     position, a kernel drawn with probability w_k / sum w and a uniform phase; a point sums the
//     impulses of its 3 x 3 cells.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../offline/bake_internal.h"
#include "../../offline/tools/file_output.h"
#include "../../offline/tools/png_output.h"
#include "../fixtures/bake_fixtures.h"
#include "bench_timing.h"
#include "dsn/dsn.h"

namespace {

const double kPi = 3.14159265358979323846;
const double kImpactsPerPixel = 30; // both methods: 30 impulses overlap each point on average

// ---- Gabor noise by example ----

struct GaborNoise {
    double a = 0;                   // Gaussian width: the kernel's radius is 1/a pixels
    std::vector<double> fx, fy;     // the quantized frequencies (cycles per pixel)
    std::vector<double> cumulative; // of w_k / sum w: the kernel of an impulse
    double impulses_per_cell = 0, amplitude = 0;
    double cell = 0; // cell side = 1/a
    uint32_t seed = 1;
};

// Squared distance between two frequencies on the unit torus (the DFT's frequencies wrap).
double wrapped_squared(double dx, double dy) {
    dx -= std::round(dx);
    dy -= std::round(dy);
    return dx * dx + dy * dy;
}

double kernel_spectrum(const GaborNoise &noise, size_t k, double fx, double fy) {
    const double scale = -2 * kPi / (noise.a * noise.a);
    return std::exp(scale * wrapped_squared(fx - noise.fx[k], fy - noise.fy[k])) +
           std::exp(scale * wrapped_squared(fx + noise.fx[k], fy + noise.fy[k]));
}

// The weights of the kernel bank fitted to `power` (width x height, |DFT|^2 / N of the grey exemplar), and
// the amplitude that gives the noise the fitted spectrum at `impacts_per_pixel`.
GaborNoise fit_gabor(const std::vector<double> &power, int width, int height, double a,
                     std::vector<double> *model) {
    GaborNoise noise;
    noise.a = a;
    noise.cell = 1 / a;
    const double step = a / 2;
    const int steps = int(std::floor(0.5 / step));
    for (int j = 0; j <= steps; j++) // half plane: f and -f are one kernel
        for (int i = -steps; i <= steps; i++) {
            if (j == 0 && i < 0) continue;
            if (i == 0 && j == 0) continue; // the mean is not modelled
            noise.fx.push_back(i * step);
            noise.fy.push_back(j * step);
        }
    const size_t kernels = noise.fx.size(), frequencies = size_t(width) * size_t(height);
    std::vector<float> bank(kernels * frequencies);
    for (size_t k = 0; k < kernels; k++)
        for (int y = 0; y < height; y++)
            for (int x = 0; x < width; x++)
                bank[k * frequencies + size_t(y) * size_t(width) + size_t(x)] =
                    float(kernel_spectrum(noise, k, double(x) / width, double(y) / height));
    auto apply = [&](const std::vector<double> &w, std::vector<double> &out) { // out = B w
        out.assign(frequencies, 0.0);
        for (size_t k = 0; k < kernels; k++)
            if (w[k] != 0)
                for (size_t i = 0; i < frequencies; i++) out[i] += w[k] * bank[k * frequencies + i];
    };
    auto apply_transposed = [&](const std::vector<double> &r, std::vector<double> &out) { // out = B^T r
        out.assign(kernels, 0.0);
        for (size_t k = 0; k < kernels; k++) {
            double sum = 0;
            for (size_t i = 0; i < frequencies; i++) sum += bank[k * frequencies + i] * r[i];
            out[k] = sum;
        }
    };
    // The step: 1 / L, L = the largest eigenvalue of B^T B (power iteration).
    std::vector<double> v(kernels, 1.0), bv, btbv;
    double lipschitz = 1;
    for (int iteration = 0; iteration < 30; iteration++) {
        apply(v, bv);
        apply_transposed(bv, btbv);
        double norm = 0;
        for (double value : btbv) norm += value * value;
        lipschitz = std::sqrt(norm);
        for (size_t k = 0; k < kernels; k++) v[k] = btbv[k] / lipschitz;
    }
    // Accelerated projected gradient (FISTA) on 1/2 |B w - P|^2, w >= 0.
    std::vector<double> w(kernels, 0.0), previous = w, y = w, residual, gradient;
    double t = 1;
    for (int iteration = 0; iteration < 400; iteration++) {
        apply(y, residual);
        for (size_t i = 0; i < frequencies; i++) residual[i] -= power[i];
        apply_transposed(residual, gradient);
        previous = w;
        for (size_t k = 0; k < kernels; k++) w[k] = std::max(0.0, y[k] - gradient[k] / (1.1 * lipschitz));
        const double next_t = (1 + std::sqrt(1 + 4 * t * t)) / 2;
        for (size_t k = 0; k < kernels; k++) y[k] = w[k] + (t - 1) / next_t * (w[k] - previous[k]);
        t = next_t;
    }
    apply(w, *model);
    double total = 0;
    for (double value : w) total += value;
    noise.cumulative.resize(kernels);
    double running = 0;
    for (size_t k = 0; k < kernels; k++) noise.cumulative[k] = (running += w[k]) / total;
    // Impulse density lambda per pixel: lambda * (pi / a^2) = impacts per pixel (the kernel's disk).
    const double lambda = kImpactsPerPixel * a * a / kPi;
    noise.impulses_per_cell = lambda * noise.cell * noise.cell;
    // Power of the noise = lambda amplitude^2 E_k[|FT kernel_k|^2] = lambda amplitude^2 sum p_k B_k / (4 a^4)
    // (FT of exp(-pi a^2 |x|^2) is exp(-pi |f|^2 / a^2) / a^2; a random phase halves each of the two
    // lobes' power: 1/4). Matching sum w_k B_k: amplitude^2 = 4 a^4 total / lambda.
    noise.amplitude = std::sqrt(4 * std::pow(a, 4) * total / lambda);
    return noise;
}

uint32_t hash(uint32_t value) { // lowbias32
    value ^= value >> 16;
    value *= 0x7feb352du;
    value ^= value >> 15;
    value *= 0x846ca68bu;
    value ^= value >> 16;
    return value;
}

struct CellRandom {
    uint32_t state;
    double uniform() { return ((state = hash(state + 0x9e3779b9u)) >> 8) * (1.0 / 16777216.0); }
    int poisson(double mean) { // Knuth: mean is small (a few dozen)
        const double limit = std::exp(-mean);
        int count = 0;
        for (double product = uniform(); product > limit; product *= uniform()) count++;
        return count;
    }
};

float gabor_point(const GaborNoise &noise, double x, double y) {
    const int cx = int(std::floor(x / noise.cell)), cy = int(std::floor(y / noise.cell));
    double sum = 0;
    for (int j = cy - 1; j <= cy + 1; j++)
        for (int i = cx - 1; i <= cx + 1; i++) {
            CellRandom random{hash(uint32_t(i) * 73856093u ^ uint32_t(j) * 19349663u ^ noise.seed)};
            const int impulses = random.poisson(noise.impulses_per_cell);
            for (int n = 0; n < impulses; n++) {
                const double px = (i + random.uniform()) * noise.cell,
                             py = (j + random.uniform()) * noise.cell;
                const double pick = random.uniform(), phase = 2 * kPi * random.uniform();
                const size_t k =
                    size_t(std::lower_bound(noise.cumulative.begin(), noise.cumulative.end(), pick) -
                           noise.cumulative.begin());
                const double dx = x - px, dy = y - py, r2 = dx * dx + dy * dy;
                if (r2 * noise.a * noise.a >= 1) continue; // truncated at the radius 1/a
                sum += std::exp(-kPi * noise.a * noise.a * r2) *
                       std::cos(2 * kPi *
                                    (noise.fx[std::min(k, noise.fx.size() - 1)] * dx +
                                     noise.fy[std::min(k, noise.fy.size() - 1)] * dy) +
                                phase);
            }
        }
    return float(sum * noise.amplitude);
}

// ---- Measures ----

double excess_kurtosis(const std::vector<float> &values) {
    double mean = 0;
    for (float value : values) mean += value;
    mean /= double(values.size());
    double m2 = 0, m4 = 0;
    for (float value : values) {
        const double d = value - mean;
        m2 += d * d;
        m4 += d * d * d * d;
    }
    m2 /= double(values.size());
    m4 /= double(values.size());
    return m4 / (m2 * m2) - 3;
}

// sqrt(sum (P_method - P)^2 / sum P^2) over the frequencies but the mean's.
double spectrum_error(const std::vector<double> &method, const std::vector<double> &power) {
    double error = 0, reference = 0;
    for (size_t i = 1; i < power.size(); i++) {
        error += (method[i] - power[i]) * (method[i] - power[i]);
        reference += power[i] * power[i];
    }
    return std::sqrt(error / reference);
}

dsn::Image luminance(const dsn::Image &image) {
    if (image.channels == 1) return image;
    dsn::Image grey;
    grey.width = image.width;
    grey.height = image.height;
    grey.channels = 1;
    const size_t plane = size_t(image.width) * size_t(image.height);
    grey.values.resize(plane);
    for (size_t i = 0; i < plane; i++)
        grey.values[i] =
            0.299 * image.values[i] + 0.587 * image.values[plane + i] + 0.114 * image.values[2 * plane + i];
    return grey;
}

int64_t checksum = 0;

// The side-by-side picture: one row of three 256 x 256 panels per exemplar (exemplar tiled, ours, Gabor
// noise by example), each noise shown with the exemplar's mean and standard deviation.
const int kPanel = 256;
std::vector<unsigned char> picture;

void add_row(const dsn::Image &grey, const std::vector<float> &ours, const std::vector<float> &gabor) {
    const size_t row_at = picture.size();
    picture.resize(row_at + size_t(kPanel) * kPanel * 3);
    double mean = 0, deviation = 0;
    for (double value : grey.values) mean += value / double(grey.values.size());
    for (double value : grey.values)
        deviation += (value - mean) * (value - mean) / double(grey.values.size());
    deviation = std::sqrt(deviation);
    auto put = [&](int panel, int x, int y, double value) {
        picture[row_at + (size_t(y) * kPanel * 3 + size_t(panel) * kPanel + size_t(x))] =
            static_cast<unsigned char>(std::lround(std::min(1.0, std::max(0.0, value)) * 255));
    };
    auto show = [&](int panel, const std::vector<float> &values) {
        double own_mean = 0, own_deviation = 0;
        for (float value : values) own_mean += value / double(values.size());
        for (float value : values)
            own_deviation += (value - own_mean) * (value - own_mean) / double(values.size());
        own_deviation = std::sqrt(own_deviation);
        for (int y = 0; y < kPanel; y++)
            for (int x = 0; x < kPanel; x++)
                put(panel, x, y,
                    mean + (values[size_t(y) * kPanel + size_t(x)] - own_mean) / own_deviation * deviation);
    };
    for (int y = 0; y < kPanel; y++)
        for (int x = 0; x < kPanel; x++) put(0, x, y, grey.at(x % grey.width, y % grey.height, 0));
    show(1, ours);
    show(2, gabor);
}

// A runtime noise of a lattice bake (200 iterations) of `exemplar`, at the bench's density.
struct BakedNoise {
    dsn::BakeResult result;
    dsn_asset asset;
    dsn_noise noise;
};
std::unique_ptr<BakedNoise> bake_noise(const dsn::Image &exemplar) {
    auto baked = std::make_unique<BakedNoise>();
    dsn::BakeOptions options;
    options.iterations = 200;
    options.interpolation = DSN_INTERPOLATION_LATTICE;
    baked->result = dsn::bake(exemplar, options);
    dsn_config config;
    int err = dsn_asset_load(&baked->asset, baked->result.asset.data(), baked->result.asset.size());
    dsn_config_defaults(&config);
    config.impacts_q16 = uint32_t(kImpactsPerPixel * 65536);
    config.flags = DSN_FLAG_ALLOW_LATTICE_CONTINUOUS; // the continuous timing: its cost, whatever the bake
    if (err == DSN_OK) err = dsn_noise_init(&baked->noise, &baked->asset, &config);
    if (err != DSN_OK) throw std::runtime_error(dsn_error_message(err));
    return baked;
}

void compare(const std::string &name, const dsn::Image &colour, const dsn::Image &grey) {
    const dsn::GaussianModel model = dsn::gaussian_model(grey, true);
    const size_t plane = model.spectrum.plane_size();
    std::vector<double> power(plane);
    for (size_t i = 0; i < plane; i++) power[i] = std::norm(std::complex<double>(model.spectrum.values[i]));

    // Gabor noise by example: kernel radius 15 pixels, like our texton's (r = 15).
    std::vector<double> gabor_model;
    const GaborNoise gabor = fit_gabor(power, grey.width, grey.height, 1.0 / 15, &gabor_model);

    // Ours: lattice bakes of the same grey exemplar and of its colour original.
    const std::unique_ptr<BakedNoise> baked = bake_noise(grey), baked_colour = bake_noise(colour);
    const dsn_noise &noise = baked->noise;
    const dsn::Spectrum texton =
        dsn::texton_spectrum(baked->result.quantized_texton, grey.width, grey.height);
    std::vector<double> ours_model(plane);
    for (size_t i = 0; i < plane; i++) ours_model[i] = std::norm(std::complex<double>(texton.values[i]));

    const uint32_t side = kPanel;
    const double samples = double(side) * side;
    const size_t count = size_t(side) * side;
    std::vector<float> gabor_values(count), ours_values(count);
    const double gabor_time = bench::best_time(3, [&] {
        for (uint32_t y = 0; y < side; y++)
            for (uint32_t x = 0; x < side; x++)
                gabor_values[y * side + x] = gabor_point(gabor, x + 0.25, y + 0.75);
    });
    const double ours_time = bench::best_time(3, [&] {
        int32_t out[3];
        for (uint32_t y = 0; y < side; y++)
            for (uint32_t x = 0; x < side; x++) {
                dsn_lattice_point_fixed(&noise, int32_t(x), int32_t(y), out);
                ours_values[y * side + x] = float(out[0]);
                checksum += out[0];
            }
    });
    const double colour_time = bench::best_time(3, [&] {
        int32_t out[3];
        for (uint32_t y = 0; y < side; y++)
            for (uint32_t x = 0; x < side; x++) {
                dsn_lattice_point_fixed(&baked_colour->noise, int32_t(x), int32_t(y), out);
                checksum += out[0] + out[2];
            }
    });
    const int64_t one = int64_t(1) << 32;
    const double continuous_time = bench::best_time(3, [&] {
        int32_t out[3];
        for (uint32_t y = 0; y < side; y++)
            for (uint32_t x = 0; x < side; x++) {
                dsn_continuous_point_fixed(&noise, int64_t(x) * one + one / 4, int64_t(y) * one + one / 3,
                                           out);
                checksum += out[0];
            }
    });
    std::printf("  %-20s %4dx%-4d  grey: Gabor %6.0f ns/sample, ours lattice %4.0f, continuous %4.0f "
                "(Gabor / lattice %.1f); ours RGB lattice %4.0f ns/sample (%d channels)\n",
                name.c_str(), grey.width, grey.height, gabor_time / samples * 1e9, ours_time / samples * 1e9,
                continuous_time / samples * 1e9, gabor_time / ours_time, colour_time / samples * 1e9,
                colour.channels);
    // The Gabor noise's variance against the exemplar's: 1 but for the kernels' truncation at 1/a.
    double exemplar_variance = 0, gabor_variance = 0, gabor_mean = 0;
    for (size_t i = 1; i < plane; i++) exemplar_variance += power[i] / double(plane);
    for (float value : gabor_values) gabor_mean += value / samples;
    for (float value : gabor_values) gabor_variance += (value - gabor_mean) * (value - gabor_mean) / samples;
    std::printf("  %-20s spectrum error: Gabor %.3f, ours %.3f; excess kurtosis: Gabor %+.3f, ours %+.3f "
                "(%u kernels, %.1f impulses per cell, variance / exemplar's %.2f)\n",
                "", spectrum_error(gabor_model, power), spectrum_error(ours_model, power),
                excess_kurtosis(gabor_values), excess_kurtosis(ours_values), unsigned(gabor.fx.size()),
                gabor.impulses_per_cell, gabor_variance / exemplar_variance);
    add_row(grey, ours_values, gabor_values);
}

} // namespace

int main(int, char **argv) {
    std::printf(
        "Gabor noise by example (kernel radius 15 px, frequency step a/2, NNLS fit) against DSN "
        "(r = 15 square texton, 200 iterations, lattice bake), grey, %.0f impacts per pixel, one thread, "
        "256x256 points:\n",
        kImpactsPerPixel);
    std::vector<std::pair<std::string, dsn::Image>> exemplars; // colour (or grey) originals
    if (bake_fixtures::textures_available()) {
        for (const char *name : {"animal_leather", "fabric_burlap", "paper_crinklepaper"}) {
            std::vector<std::string> warnings;
            try {
                exemplars.emplace_back(
                    name,
                    dsn::load_exemplar(bake_fixtures::textures_folder() + "/" + name + ".png", &warnings));
            } catch (const std::exception &error) {
                std::printf("  %s: skipped (%s)\n", name, error.what());
            }
        }
    }
    if (exemplars.empty()) {
        std::printf("  (the texture photos are absent: a synthetic exemplar instead)\n");
        dsn::Image image = dsn::white_noise(96, 96, 3);
        dsn::Image smooth = image;
        for (int y = 0; y < 96; y++)
            for (int x = 0; x < 96; x++)
                smooth.at(x, y, 0) = 0.5 + 0.05 * (image.at(x, y, 0) + image.at((x + 1) % 96, y, 0) +
                                                   image.at(x, (y + 2) % 96, 0));
        exemplars.emplace_back("synthetic", smooth);
    }
    try {
        for (const auto &exemplar : exemplars)
            compare(exemplar.first, exemplar.second, luminance(exemplar.second));
    } catch (const std::exception &error) {
        std::printf("gabor_bench: %s\n", error.what());
        return 1;
    }
    // Beside the program: build/bench/gabor_side_by_side.png.
    std::string path = argv[0];
    path = path.substr(0, path.find_last_of('/') + 1) + "gabor_side_by_side.png";
    dsn::write_file_atomically(
        path, dsn::encode_png(3 * kPanel, int(exemplars.size()) * kPanel, 1, picture.data()));
    std::printf("  side by side (exemplar | ours | Gabor noise by example): %s\n", path.c_str());
    std::printf("  (checksum %lld)\n", static_cast<long long>(checksum));
    return 0;
}
