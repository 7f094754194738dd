// histogram_bench.cpp - what the histogram-preserving output (dsn-bake --histogram) keeps of real
// textures: for every PNG of the shared texture folder (DSN_TEXTURES, default ../shared/textures), the
// Wasserstein-1 distance between the exemplar's histogram and a 256 x 256 synthesized tile's, per channel,
// for the plain and the histogram-preserving bake of the same options (the ratio is the figure: below 1
// the mapping brings the tones closer), and both bakes' spectrum errors (autocorrelation over the
// texton's reach). W1 is measured in two bases: the exemplar's decorrelated (principal component)
// channels, the ones the mapping maps, and the RGB channels a viewer sees. The two differ where the
// decorrelated channels of the exemplar are dependent (uncorrelated is not independent: a few flat
// colours), which the synthesis, drawing them independently, cannot keep. Skipped, saying so, when the
// folder is absent.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "../fixtures/bake_fixtures.h"
#include "../fixtures/histogram_measures.h"

namespace {

using namespace histogram_measures;

struct Measured {
    double w1_decorrelated = 0, w1_rgb = 0, spectrum = 0; // the channels' means
};

// A constant channel (a flat colour component) has no autocorrelation and counts for W1 alone.
Measured measure(const dsn::Image &exemplar, const dsn::ColourBasis &basis, const dsn::BakeResult &result,
                 int tile) {
    const int reach = int(result.fields.width) - 1; // 2r
    const std::vector<float> out = synthesize(result.asset, tile, 5, 1000, -700);
    std::vector<double> targets[3], outputs[3];
    for (int c = 0; c < exemplar.channels; c++)
        targets[c] = channel_of(exemplar, c), outputs[c] = channel_of(out, exemplar.channels, c);
    Measured measured;
    int varying = 0;
    for (int c = 0; c < exemplar.channels; c++) {
        measured.w1_rgb += wasserstein1(outputs[c], targets[c]) / exemplar.channels;
        measured.w1_decorrelated += wasserstein1(decorrelated_channel(outputs, outputs[0].size(), basis, c),
                                                 decorrelated_channel(targets, targets[0].size(), basis, c)) /
                                    exemplar.channels;
        if (*std::min_element(targets[c].begin(), targets[c].end()) ==
            *std::max_element(targets[c].begin(), targets[c].end()))
            continue;
        measured.spectrum +=
            spectrum_error(autocorrelation(outputs[c], tile, tile, reach, false),
                           autocorrelation(targets[c], exemplar.width, exemplar.height, reach, true));
        varying++;
    }
    measured.spectrum /= std::max(1, varying);
    return measured;
}

struct Ratios {
    std::vector<double> all, non_gaussian;
    void add(double ratio, bool non_gaussian_marginal) {
        all.push_back(ratio);
        if (non_gaussian_marginal) non_gaussian.push_back(ratio);
    }
};

size_t below_third(const std::vector<double> &ratios) {
    return size_t(std::count_if(ratios.begin(), ratios.end(), [](double r) { return r <= 1.0 / 3; }));
}

void summarize(const char *basis, Ratios ratios) {
    std::sort(ratios.all.begin(), ratios.all.end());
    std::printf("W1 ratio (histogram-preserving / plain), %s: over %zu textures median %.3f, min %.3f, max "
                "%.3f, %zu of them below 1/3",
                basis, ratios.all.size(), ratios.all[ratios.all.size() / 2], ratios.all.front(),
                ratios.all.back(), below_third(ratios.all));
    if (!ratios.non_gaussian.empty()) {
        std::sort(ratios.non_gaussian.begin(), ratios.non_gaussian.end());
        std::printf(
            "; over the %zu whose marginals the verdict finds non-Gaussian median %.3f, max %.3f, %zu "
            "of them below 1/3",
            ratios.non_gaussian.size(), ratios.non_gaussian[ratios.non_gaussian.size() / 2],
            ratios.non_gaussian.back(), below_third(ratios.non_gaussian));
    }
    std::printf("\n");
}

} // namespace

int main() {
    const std::vector<std::string> paths = bake_fixtures::texture_paths();
    if (paths.empty()) {
        std::printf("histogram bench: SKIPPED, no texture folder %s (set DSN_TEXTURES)\n",
                    bake_fixtures::textures_folder().c_str());
        return 0;
    }
    std::printf("%-22s %9s %3s | W1 decorrelated: %7s %7s %6s | W1 RGB: %7s %7s %6s | spectrum: %5s %5s\n",
                "texture", "size", "r", "plain", "hist", "ratio", "plain", "hist", "ratio", "plain", "hist");
    Ratios decorrelated, rgb;
    std::vector<double> spectrum_changes;
    for (const std::string &path : paths) {
        const dsn::Image exemplar = dsn::load_exemplar(path, nullptr);
        dsn::BakeOptions options;
        options.radius = std::min(15, (std::min(exemplar.width, exemplar.height) - 1) / 4);
        if (options.radius < 1) continue;
        const std::string name = std::filesystem::path(path).stem().string();
        Measured plain, mapped;
        bool non_gaussian = false;
        try {
            const dsn::ColourBasis basis = dsn::principal_components(exemplar);
            const dsn::BakeResult plain_bake = dsn::bake(exemplar, options);
            const auto &findings = plain_bake.verdict.findings;
            non_gaussian = std::find(findings.begin(), findings.end(),
                                     dsn::VerdictFinding::NonGaussianMarginal) != findings.end();
            plain = measure(exemplar, basis, plain_bake, 256);
            options.histogram = true;
            mapped = measure(exemplar, basis, dsn::bake(exemplar, options), 256);
        } catch (const std::runtime_error &error) { // a constant picture (its alpha held the pattern)
            std::printf("%-22s refused: %s\n", name.c_str(), error.what());
            continue;
        }
        decorrelated.add(mapped.w1_decorrelated / plain.w1_decorrelated, non_gaussian);
        rgb.add(mapped.w1_rgb / plain.w1_rgb, non_gaussian);
        spectrum_changes.push_back(mapped.spectrum - plain.spectrum);
        std::printf("%-22s %4dx%-4d %3d | %24.4f %7.4f %6.3f | %15.4f %7.4f %6.3f | %15.3f %5.3f %s\n",
                    name.c_str(), exemplar.width, exemplar.height, options.radius, plain.w1_decorrelated,
                    mapped.w1_decorrelated, decorrelated.all.back(), plain.w1_rgb, mapped.w1_rgb,
                    rgb.all.back(), plain.spectrum, mapped.spectrum, non_gaussian ? " non-Gaussian" : "");
    }
    if (spectrum_changes.empty()) return 0;
    summarize("decorrelated channels (what the mapping maps) [target: <= 1/3 on the non-Gaussian ones]",
              decorrelated);
    summarize("RGB channels", rgb);
    std::sort(spectrum_changes.begin(), spectrum_changes.end());
    std::printf(
        "spectrum error change (histogram-preserving - plain): median %+.3f, min %+.3f, max %+.3f; %zu "
        "of them worse by more than 0.05\n",
        spectrum_changes[spectrum_changes.size() / 2], spectrum_changes.front(), spectrum_changes.back(),
        size_t(std::count_if(spectrum_changes.begin(), spectrum_changes.end(),
                             [](double change) { return change > 0.05; })));
    return 0;
}
