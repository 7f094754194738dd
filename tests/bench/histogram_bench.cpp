// histogram_bench.cpp - what the histogram-preserving output (dsn-bake --histogram) keeps of real
// textures against the plain bake of the same options: for every PNG of the shared texture folder
// (DSN_TEXTURES, default ../shared/textures; an argument keeps the names that contain it), a 512 x 512
// continuous-mode render of each bake (tests/fixtures/histogram_measures.h) and, per texture:
//   - spectrum: the log-spectrum error of the render against the exemplar (tests/fixtures/
//     spectrum_measures.h), the mean over the RGB channels that vary;
//   - high: the power above 0.25 cycles per pixel over the exemplar's (each with the 8-bit rounding floor
//     at every frequency), the largest over the RGB channels and in the exemplar's strongest principal
//     component (a fine pixel noise added to a smooth material);
//   - RME: the bake's relative model error (each bake against its own model: the plain one in RGB, the
//     histogram-preserving one in the Gaussianized decorrelated channels);
//   - W1: the Wasserstein-1 distance of the render's histogram to the exemplar's, the mean over the RGB
//     channels, the ratio histogram / plain, and the worst channel's ratio (above 1: a channel worse);
//     and in the decorrelated channels (the ones the mapping maps; they differ where those channels are
//     dependent, a few flat colours, which the synthesis draws independently).
// The summary checks the goals: spectrum error and RME within +0.03 of the plain bake's on every texture,
// no high-frequency excess above 1.5x, RGB W1 at most 0.5x the plain bake's (median) and never worse per
// channel. Skipped, saying so, when the folder is absent.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixtures/bake_fixtures.h"
#include "fixtures/histogram_measures.h"
#include "fixtures/spectrum_measures.h"

namespace {

using namespace histogram_measures;

constexpr int kTile = 512;

struct Measured {
    double spectrum = 0, high = 0, high_principal = 0, rme = 0;
    double w1_decorrelated = 0, w1_rgb = 0; // the channels' means
    std::vector<double> w1_channels;
};

double high_ratio(const std::vector<double> &output, int width, const std::vector<double> &exemplar,
                  const dsn::Image &image) {
    using namespace spectrum_measures;
    return high_frequency_ratio(welch_spectrum(output, width, width),
                                welch_spectrum(exemplar, image.width, image.height));
}

// A constant channel (a flat colour component) has no spectrum and counts for W1 alone.
Measured measure(const dsn::Image &exemplar, const dsn::ColourBasis &basis, const dsn::BakeResult &result) {
    using namespace spectrum_measures;
    const std::vector<float> out = synthesize(result.asset, kTile, 5, 1000, -700);
    std::vector<double> targets[3], outputs[3];
    for (int c = 0; c < exemplar.channels; c++)
        targets[c] = channel_of(exemplar, c), outputs[c] = channel_of(out, exemplar.channels, c);
    Measured measured;
    measured.rme = result.rme;
    int varying = 0;
    for (int c = 0; c < exemplar.channels; c++) {
        measured.w1_channels.push_back(wasserstein1(outputs[c], targets[c]));
        measured.w1_rgb += measured.w1_channels.back() / exemplar.channels;
        measured.w1_decorrelated += wasserstein1(decorrelated_channel(outputs, outputs[0].size(), basis, c),
                                                 decorrelated_channel(targets, targets[0].size(), basis, c)) /
                                    exemplar.channels;
        if (*std::min_element(targets[c].begin(), targets[c].end()) ==
            *std::max_element(targets[c].begin(), targets[c].end()))
            continue;
        measured.spectrum += log_spectrum_error(welch_spectrum(outputs[c], kTile, kTile),
                                                welch_spectrum(targets[c], exemplar.width, exemplar.height));
        measured.high = std::max(measured.high, high_ratio(outputs[c], kTile, targets[c], exemplar));
        varying++;
    }
    measured.spectrum /= std::max(1, varying);
    if (basis.variances[0] > 0)
        measured.high_principal =
            high_ratio(decorrelated_channel(outputs, outputs[0].size(), basis, 0), kTile,
                       decorrelated_channel(targets, targets[0].size(), basis, 0), exemplar);
    return measured;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0 : values[values.size() / 2];
}

} // namespace

int main(int argc, char **argv) {
    const std::vector<std::string> paths = bake_fixtures::texture_paths();
    if (paths.empty()) {
        std::printf("histogram bench: SKIPPED, no texture folder %s (set DSN_TEXTURES)\n",
                    bake_fixtures::textures_folder().c_str());
        return 0;
    }
    const std::string only = argc > 1 ? argv[1] : "";
    std::printf("%-20s %7s %2s | spectrum: %5s %5s | high: %6s %6s %6s %6s | RME: %5s %5s | W1 RGB: %6s %6s "
                "%5s %5s | W1 decorr. %5s\n",
                "texture", "size", "r", "plain", "hist", "plain", "hist", "pc1 p", "pc1 h", "plain", "hist",
                "plain", "hist", "ratio", "worst", "ratio");
    std::vector<double> rgb_ratios, spectrum_changes, rme_changes, high_ratios;
    size_t worse_channel = 0;
    for (const std::string &path : paths) {
        const std::string name = std::filesystem::path(path).stem().string();
        if (name.find(only) == std::string::npos) continue;
        const dsn::Image exemplar = dsn::load_exemplar(path, nullptr);
        dsn::BakeOptions options;
        options.radius = std::min(15, (std::min(exemplar.width, exemplar.height) - 1) / 4);
        if (options.radius < 1) continue;
        Measured plain, mapped;
        try {
            const dsn::ColourBasis basis = dsn::principal_components(exemplar);
            plain = measure(exemplar, basis, dsn::bake(exemplar, options));
            options.histogram = true;
            mapped = measure(exemplar, basis, dsn::bake(exemplar, options));
        } catch (const std::runtime_error &error) { // a constant picture (its alpha held the pattern)
            std::printf("%-20s refused: %s\n", name.c_str(), error.what());
            continue;
        }
        double worst = 0;
        for (size_t c = 0; c < plain.w1_channels.size(); c++)
            worst =
                std::max(worst, plain.w1_channels[c] > 0 ? mapped.w1_channels[c] / plain.w1_channels[c] : 1);
        // A channel counts as worse beyond a thousandth of the range (the sampling noise of equal ones).
        for (size_t c = 0; c < plain.w1_channels.size(); c++)
            if (mapped.w1_channels[c] > plain.w1_channels[c] + 1e-3) {
                worse_channel++;
                break;
            }
        rgb_ratios.push_back(mapped.w1_rgb / plain.w1_rgb);
        spectrum_changes.push_back(mapped.spectrum - plain.spectrum);
        rme_changes.push_back(mapped.rme - plain.rme);
        high_ratios.push_back(std::max(mapped.high, mapped.high_principal));
        std::printf(
            "%-20s %3dx%-3d %2d | %15.3f %5.3f | %12.2f %6.2f %6.2f %6.2f | %10.3f %5.3f | %14.4f %6.4f "
            "%5.3f %5.2f | %16.3f\n",
            name.c_str(), exemplar.width, exemplar.height, options.radius, plain.spectrum, mapped.spectrum,
            plain.high, mapped.high, plain.high_principal, mapped.high_principal, plain.rme, mapped.rme,
            plain.w1_rgb, mapped.w1_rgb, rgb_ratios.back(), worst,
            mapped.w1_decorrelated / plain.w1_decorrelated);
        std::fflush(stdout);
    }
    if (rgb_ratios.empty()) return 0;
    const auto count_above = [](const std::vector<double> &values, double limit) {
        return size_t(std::count_if(values.begin(), values.end(), [limit](double v) { return v > limit; }));
    };
    const size_t n = rgb_ratios.size();
    std::printf("over %zu textures (goal in brackets):\n", n);
    std::printf("  spectrum error, histogram - plain: median %+.3f, max %+.3f; %zu above +0.03 [0]\n",
                median(spectrum_changes), *std::max_element(spectrum_changes.begin(), spectrum_changes.end()),
                count_above(spectrum_changes, 0.03));
    std::printf(
        "  high-frequency power over the exemplar's (histogram, worst of RGB and pc1): median %.2f, max "
        "%.2f; %zu above 1.5 [0]\n",
        median(high_ratios), *std::max_element(high_ratios.begin(), high_ratios.end()),
        count_above(high_ratios, 1.5));
    std::printf("  RME, histogram - plain: median %+.3f, max %+.3f; %zu above +0.03 [0]\n",
                median(rme_changes), *std::max_element(rme_changes.begin(), rme_changes.end()),
                count_above(rme_changes, 0.03));
    std::printf(
        "  RGB W1 ratio histogram / plain: median %.3f [<= 0.5], max %.3f; %zu textures with a channel "
        "worse by more than 0.001 [0]\n",
        median(rgb_ratios), *std::max_element(rgb_ratios.begin(), rgb_ratios.end()), worse_channel);
    return 0;
}
