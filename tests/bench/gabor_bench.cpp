// gabor_bench.cpp - our discrete spot noise against the procedural baseline built for the same job,
// Gabor noise by example (gabor_by_example.h), on the same colour exemplars (generated ones, and texture
// photos when present), in one run:
//   - cost per RGB sample evaluated point by point: Gabor noise by example, ours on the lattice and ours
//     in the continuous mode (the lattice bake read bilinearly: the cost does not depend on the bake);
//   - quality: the relative error between the exemplar's power spectrum (3 x 3 cross-spectral matrix per
//     frequency, T_u T_u^*) and the spectrum each noise has in expectation, sqrt(sum |S_method - S|^2 /
//     sum |S|^2) over every frequency, raw and after averaging both over 5 x 5 neighbouring frequencies
//     (the exemplar's spectrum is one noisy periodogram, which Gabor noise by example smooths on purpose);
//     the excess kurtosis of each noise at the density it runs, exact (from its cumulants) and sampled
//     on 256 x 256 points;
//   - a side-by-side picture, one row per exemplar: exemplar (tiled), ours, Gabor noise by example.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "dsn/dsn.h"
#include "fixtures/bake_fixtures.h"
#include "gabor_by_example.h"
#include "offline/bake_internal.h"
#include "offline/tools/file_output.h"
#include "offline/tools/png_output.h"

namespace {

// Ours: 30 impacts per pixel (spots covering a pixel); Gabor: 30 kernels overlapping a point per
// bandwidth level and decorrelated channel.
const double kImpacts = 30;
const int kPanel = 256;
int64_t checksum = 0;

using Cross = std::vector<std::complex<double>>; // 3 x 3 (or 1 x 1) per frequency, DFT order

Cross exemplar_cross(const dsn::Spectrum &spectrum) {
    const int n = spectrum.channels;
    const size_t plane = spectrum.plane_size();
    Cross out(plane * size_t(n * n));
    for (size_t i = 0; i < plane; i++)
        for (int c = 0; c < n; c++)
            for (int d = 0; d < n; d++)
                out[i * size_t(n * n) + size_t(c * n + d)] =
                    std::complex<double>(spectrum.values[size_t(c) * plane + i]) *
                    std::conj(std::complex<double>(spectrum.values[size_t(d) * plane + i]));
    return out;
}

// Ours: K T(xi) (K T(xi))^* with T the quantized texton's DFT on the exemplar's torus.
Cross ours_cross(const dsn::BakeResult &result, int width, int height) {
    dsn::Spectrum spectrum = dsn::texton_spectrum(result.quantized_texton, width, height);
    const int n = spectrum.channels;
    const size_t plane = spectrum.plane_size();
    if (n == 3)
        for (size_t i = 0; i < plane; i++) {
            std::complex<float> t[3], k[3];
            for (int c = 0; c < 3; c++) t[c] = spectrum.values[size_t(c) * plane + i];
            for (int c = 0; c < 3; c++)
                k[c] = float(result.color_transform[size_t(c * 3)]) * t[0] +
                       float(result.color_transform[size_t(c * 3 + 1)]) * t[1] +
                       float(result.color_transform[size_t(c * 3 + 2)]) * t[2];
            for (int c = 0; c < 3; c++) spectrum.values[size_t(c) * plane + i] = k[c];
        }
    return exemplar_cross(spectrum);
}

// Gabor: mixing diag(P_k) mixing^T (the decorrelated noises are independent).
Cross gabor_cross(const gabor::ColourNoise &noise) {
    const int n = noise.channels;
    const size_t plane = noise.spectra[0].size();
    Cross out(plane * size_t(n * n));
    for (size_t i = 0; i < plane; i++)
        for (int c = 0; c < n; c++)
            for (int d = 0; d < n; d++) {
                double value = 0;
                for (int k = 0; k < n; k++)
                    value += noise.mixing[size_t(c * 3 + k)] * noise.mixing[size_t(d * 3 + k)] *
                             noise.spectra[size_t(k)][i];
                out[i * size_t(n * n) + size_t(c * n + d)] = value;
            }
    return out;
}

// Every entry averaged over the 5 x 5 frequencies around (wrapping).
Cross smoothed(const Cross &cross, int width, int height, int entries) {
    Cross out(cross.size());
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            for (int e = 0; e < entries; e++) {
                std::complex<double> sum = 0;
                for (int j = -2; j <= 2; j++)
                    for (int i = -2; i <= 2; i++)
                        sum += cross[(size_t((y + j + height) % height) * size_t(width) +
                                      size_t((x + i + width) % width)) *
                                         size_t(entries) +
                                     size_t(e)];
                out[(size_t(y) * size_t(width) + size_t(x)) * size_t(entries) + size_t(e)] = sum / 25.0;
            }
    return out;
}

double spectrum_error(const Cross &method, const Cross &exemplar) {
    double error = 0, reference = 0;
    for (size_t i = 0; i < exemplar.size(); i++) {
        error += std::norm(method[i] - exemplar[i]);
        reference += std::norm(exemplar[i]);
    }
    return std::sqrt(error / reference);
}

// Mean over the channels of the sample excess kurtosis of planar values.
double sampled_kurtosis(const std::vector<float> &values, int channels) {
    const size_t plane = values.size() / size_t(channels);
    double total = 0;
    for (int c = 0; c < channels; c++) {
        double mean = 0, m2 = 0, m4 = 0;
        for (size_t i = 0; i < plane; i++) mean += values[size_t(c) * plane + i] / double(plane);
        for (size_t i = 0; i < plane; i++) {
            const double d = values[size_t(c) * plane + i] - mean;
            m2 += d * d / double(plane);
            m4 += d * d * d * d / double(plane);
        }
        total += (m4 / (m2 * m2) - 3) / channels;
    }
    return total;
}

// Ours, exact: per channel of the colour-transformed texton t' = K t, sum t'^4 / (lambda (sum t'^2)^2).
double ours_kurtosis(const dsn::BakeResult &result) {
    dsn::Texton texton = result.quantized_texton;
    const size_t plane = texton.support.mask.size();
    if (texton.channels == 3)
        for (size_t i = 0; i < plane; i++) {
            double t[3], k[3];
            for (int c = 0; c < 3; c++) t[c] = texton.values[size_t(c) * plane + i];
            for (int c = 0; c < 3; c++)
                k[c] = result.color_transform[size_t(c * 3)] * t[0] +
                       result.color_transform[size_t(c * 3 + 1)] * t[1] +
                       result.color_transform[size_t(c * 3 + 2)] * t[2];
            for (int c = 0; c < 3; c++) texton.values[size_t(c) * plane + i] = k[c];
        }
    double total = 0;
    for (double value : dsn::excess_kurtosis(texton, kImpacts)) total += value / texton.channels;
    return total;
}

// Gabor, exact: per RGB channel, the decorrelated noises' cumulants mixed (they are independent).
double gabor_kurtosis(const gabor::ColourNoise &noise) {
    double total = 0;
    for (int c = 0; c < noise.channels; c++) {
        double variance = 0, fourth = 0;
        for (int k = 0; k < noise.channels; k++) {
            const gabor::Cumulants cumulants = gabor::cumulants(noise.noises[size_t(k)]);
            const double m = noise.mixing[size_t(c * 3 + k)];
            variance += m * m * cumulants.variance;
            fourth += m * m * m * m * cumulants.fourth;
        }
        total += fourth / (variance * variance) / noise.channels;
    }
    return total;
}

// The side-by-side picture: one row of three 256 x 256 RGB panels per exemplar.
std::vector<unsigned char> picture;

void add_row(const dsn::Image &exemplar, const std::vector<float> &ours,
             const std::vector<float> &gabor_values) {
    const size_t row_at = picture.size(), plane = size_t(kPanel) * kPanel;
    picture.resize(row_at + plane * 3 * 3);
    auto put = [&](int panel, int x, int y, int c, double value) {
        picture[row_at + (size_t(y) * kPanel * 3 + size_t(panel) * kPanel + size_t(x)) * 3 + size_t(c)] =
            static_cast<unsigned char>(std::lround(std::min(1.0, std::max(0.0, value)) * 255));
    };
    for (int y = 0; y < kPanel; y++)
        for (int x = 0; x < kPanel; x++)
            for (int c = 0; c < 3; c++) {
                const int channel = std::min(c, exemplar.channels - 1);
                put(0, x, y, c, exemplar.at(x % exemplar.width, y % exemplar.height, channel));
                put(1, x, y, c, ours[size_t(channel) * plane + size_t(y) * kPanel + size_t(x)]);
                put(2, x, y, c, gabor_values[size_t(channel) * plane + size_t(y) * kPanel + size_t(x)]);
            }
}

// A runtime noise of a lattice bake (200 iterations) of `exemplar`, at the bench's density; continuous
// reads allowed (their cost does not depend on the bake).
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
    config.impacts_q16 = uint32_t(kImpacts * 65536);
    config.flags = DSN_FLAG_ALLOW_LATTICE_CONTINUOUS;
    if (err == DSN_OK) err = dsn_noise_init(&baked->noise, &baked->asset, &config);
    if (err != DSN_OK) throw std::runtime_error(dsn_error_message(err));
    return baked;
}

struct Totals {
    double gabor = 0, lattice = 0, continuous = 0, matched = 0;
    int count = 0;
};

void compare(const std::string &name, const dsn::Image &exemplar, Totals &totals) {
    const int channels = exemplar.channels, width = exemplar.width, height = exemplar.height;
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, true);
    const auto fit_start = bench::Clock::now();
    const gabor::ColourNoise gabor_noise = gabor::fit_colour_noise(model, kImpacts, 12345u);
    const double fit_seconds = bench::seconds_since(fit_start);
    const auto bake_start = bench::Clock::now();
    const std::unique_ptr<BakedNoise> baked = bake_noise(exemplar);
    const double bake_seconds = bench::seconds_since(bake_start);
    const dsn_noise &noise = baked->noise;

    const size_t plane = size_t(kPanel) * kPanel;
    const double samples = double(plane);
    std::vector<float> gabor_values(plane * size_t(channels)), ours_values(plane * size_t(channels));
    const double gabor_time = bench::best_time(2, [&] {
        float out[3];
        for (int y = 0; y < kPanel; y++)
            for (int x = 0; x < kPanel; x++) {
                gabor::colour_point(gabor_noise, x + 0.25, y + 0.75, out);
                for (int c = 0; c < channels; c++)
                    gabor_values[size_t(c) * plane + size_t(y) * kPanel + size_t(x)] = out[c];
            }
    });
    const double lattice_time = bench::best_time(3, [&] {
        float out[3];
        for (int y = 0; y < kPanel; y++)
            for (int x = 0; x < kPanel; x++) {
                dsn_lattice_point_float(&noise, x, y, out);
                for (int c = 0; c < channels; c++)
                    ours_values[size_t(c) * plane + size_t(y) * kPanel + size_t(x)] = out[c];
            }
    });
    const double continuous_time = bench::best_time(3, [&] {
        float out[3];
        for (int y = 0; y < kPanel; y++)
            for (int x = 0; x < kPanel; x++) {
                dsn_continuous_point_float(&noise, x + 0.25, y + 0.75, out);
                checksum += int64_t(out[0] * 65536);
            }
    });

    const Cross exemplar_spectrum = exemplar_cross(model.spectrum);
    const Cross ours_spectrum = ours_cross(baked->result, width, height);
    const Cross gabor_spectrum = gabor_cross(gabor_noise);
    const int entries = channels * channels;
    const Cross exemplar_smooth = smoothed(exemplar_spectrum, width, height, entries);
    // Gabor's variance per channel against the exemplar's (1 but for the kernels' truncation and the
    // spectrum beyond the bank's reach), from the samples.
    double variance_ratio = 0;
    for (int c = 0; c < channels; c++) {
        double mean = 0, variance = 0, exemplar_variance = 0;
        for (size_t i = 0; i < plane; i++) mean += gabor_values[size_t(c) * plane + i] / samples;
        for (size_t i = 0; i < plane; i++) {
            const double d = gabor_values[size_t(c) * plane + i] - mean;
            variance += d * d / samples;
        }
        const size_t size = model.spectrum.plane_size(); // sum |T_u|^2 = M N variance
        for (size_t i = 0; i < size; i++)
            exemplar_variance +=
                std::norm(std::complex<double>(model.spectrum.values[size_t(c) * size + i])) / double(size);
        variance_ratio += variance / exemplar_variance / channels;
    }
    size_t nonzero = 0, atoms = gabor_noise.bank.atom_count() * size_t(channels);
    int iterations = 0;
    for (int k = 0; k < channels; k++) {
        nonzero += gabor_noise.fits[size_t(k)].nonzero;
        iterations = std::max(iterations, gabor_noise.fits[size_t(k)].iterations);
    }

    // Gabor at the density that gives it our excess kurtosis (which falls as 1 / density).
    const double gabor_exact = gabor_kurtosis(gabor_noise), ours_exact = ours_kurtosis(baked->result);
    const double matched_impacts = kImpacts * gabor_exact / ours_exact;
    gabor::ColourNoise matched = gabor_noise;
    gabor::set_density(matched, matched_impacts, 12345u);
    const double matched_time = bench::best_time(2, [&] {
        float out[3];
        for (int y = 0; y < kPanel; y++)
            for (int x = 0; x < kPanel; x++) {
                gabor::colour_point(matched, x + 0.25, y + 0.75, out);
                checksum += int64_t(out[0] * 65536);
            }
    });
    const double per = 1e9 / samples;
    std::printf("  %-20s %3dx%-3d %s\n", name.c_str(), width, height, channels == 3 ? "RGB" : "grey");
    std::printf("    cost per sample:  Gabor %7.0f ns, ours lattice %4.0f ns (Gabor / lattice %5.1f), ours "
                "continuous %4.0f ns (Gabor / continuous %4.1f)\n",
                gabor_time * per, lattice_time * per, gabor_time / lattice_time, continuous_time * per,
                gabor_time / continuous_time);
    std::printf("    at our kurtosis:  Gabor %7.0f ns at %.1f kernels per point per bandwidth (Gabor / "
                "lattice %5.1f, "
                "Gabor / continuous %4.1f)\n",
                matched_time * per, matched_impacts, matched_time / lattice_time,
                matched_time / continuous_time);
    std::printf("    spectrum error:   Gabor %.3f, ours %.3f; 5x5-averaged: Gabor %.3f, ours %.3f\n",
                spectrum_error(gabor_spectrum, exemplar_spectrum),
                spectrum_error(ours_spectrum, exemplar_spectrum),
                spectrum_error(smoothed(gabor_spectrum, width, height, entries), exemplar_smooth),
                spectrum_error(smoothed(ours_spectrum, width, height, entries), exemplar_smooth));
    std::printf(
        "    excess kurtosis:  Gabor %+.3f, ours %+.3f (exact); sampled on %dx%d: Gabor %+.3f, ours %+.3f\n",
        gabor_exact, ours_exact, kPanel, kPanel, sampled_kurtosis(gabor_values, channels),
        sampled_kurtosis(ours_values, channels));
    std::printf(
        "    Gabor fit:        %zu of %zu kernels kept, %zu bandwidths, <= %d FISTA iterations, %.2f s "
        "(ours: bake %.2f s); variance / exemplar's %.3f",
        nonzero, atoms, gabor_noise.bank.levels.size(), iterations, fit_seconds, bake_seconds,
        variance_ratio);
    if (channels == 3)
        std::printf("; colour decorrelation leaves %.1f%% of the cross-spectral off-diagonal energy",
                    100 * gabor_noise.off_diagonal_after / gabor_noise.off_diagonal_before);
    std::printf("\n");
    add_row(exemplar, ours_values, gabor_values);
    totals.gabor += gabor_time;
    totals.lattice += lattice_time;
    totals.continuous += continuous_time;
    totals.matched += matched_time;
    totals.count++;
}

// A colour Gaussian texture whose spectrum is narrow and oriented (a Gabor-like spot, two colours).
dsn::Image oriented_exemplar(int width, int height, uint32_t seed) {
    dsn::Image spot;
    spot.width = width;
    spot.height = height;
    spot.channels = 3;
    spot.values.assign(size_t(width) * size_t(height) * 3, 0.0);
    const double weights[2][3] = {{1.0, 0.7, 0.3}, {0.2, 0.5, 1.0}};
    for (int dy = -20; dy <= 20; dy++)
        for (int dx = -20; dx <= 20; dx++) {
            const double r2 = dx * dx + dy * dy;
            const double stripes =
                std::exp(-r2 / (2 * 6.0 * 6.0)) * std::cos(2 * gabor::kPi * (0.12 * dx + 0.05 * dy));
            const double blob = std::exp(-r2 / (2 * 2.0 * 2.0));
            for (int c = 0; c < 3; c++)
                spot.at((dx + width) % width, (dy + height) % height, c) =
                    weights[0][c] * stripes + 0.6 * weights[1][c] * blob;
        }
    return bake_fixtures::random_phase_texture(spot, seed);
}

} // namespace

int main(int, char **argv) {
    std::printf(
        "Gabor noise by example (bandwidth-quantized, non-negative basis pursuit fit, decorrelated colour, "
        "%.0f kernels per point per bandwidth) against DSN (r = 15 square texton, 200 iterations, lattice "
        "bake, %.0f impacts per pixel), RGB, one thread, %dx%d points per point:\n",
        kImpacts, kImpacts, kPanel, kPanel);
    std::vector<std::pair<std::string, dsn::Image>> exemplars;
    exemplars.emplace_back("generated spots", bake_fixtures::random_phase_texture(
                                                  bake_fixtures::random_spot(96, 96, 3, 12, 5), 6));
    exemplars.emplace_back("generated oriented", oriented_exemplar(96, 80, 7));
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
    } else {
        std::printf("  (the texture photos are absent: generated exemplars only)\n");
    }
    Totals totals;
    try {
        for (const auto &exemplar : exemplars) compare(exemplar.first, exemplar.second, totals);
    } catch (const std::exception &error) {
        std::printf("gabor_bench: %s\n", error.what());
        return 1;
    }
    std::printf("  over all (summed times): Gabor / ours lattice %.1f, Gabor / ours continuous %.1f; at our "
                "kurtosis: %.1f and %.1f\n",
                totals.gabor / totals.lattice, totals.gabor / totals.continuous,
                totals.matched / totals.lattice, totals.matched / totals.continuous);
    // Beside the program: build/bench/gabor_side_by_side.png.
    std::string path = argv[0];
    path = path.substr(0, path.find_last_of('/') + 1) + "gabor_side_by_side.png";
    dsn::write_file_atomically(
        path, dsn::encode_png(3 * kPanel, int(exemplars.size()) * kPanel, 3, picture.data()));
    std::printf("  side by side (exemplar | ours | Gabor noise by example): %s\n", path.c_str());
    std::printf("  (checksum %lld)\n", static_cast<long long>(checksum));
    return 0;
}
