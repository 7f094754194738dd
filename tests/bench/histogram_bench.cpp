// histogram_bench.cpp - what the histogram-preserving output (dsn-bake --histogram) keeps of real
// textures: for every PNG of the shared texture folder (DSN_TEXTURES, default ../shared/textures), the
// Wasserstein-1 distance between the exemplar's histogram and a 256 x 256 synthesized tile's, per channel,
// for the plain and the histogram-preserving bake of the same options (the ratio is the figure: below 1
// the mapping brings the tones closer), and both bakes' spectrum errors (autocorrelation over the
// texton's reach). Skipped, saying so, when the folder is absent.
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
    double w1 = 0, spectrum = 0; // the channels' mean
};

// The channels' means; a constant channel (a flat colour component) has no autocorrelation and counts
// for W1 alone.
Measured measure(const dsn::Image &exemplar, const dsn::BakeResult &result, int tile) {
    const int reach = int(result.fields.width) - 1; // 2r
    const std::vector<float> out = synthesize(result.asset, tile, 5, 1000, -700);
    Measured measured;
    int varying = 0;
    for (int c = 0; c < exemplar.channels; c++) {
        const std::vector<double> target = channel_of(exemplar, c),
                                  output = channel_of(out, exemplar.channels, c);
        measured.w1 += wasserstein1(output, target) / exemplar.channels;
        if (*std::min_element(target.begin(), target.end()) ==
            *std::max_element(target.begin(), target.end()))
            continue;
        measured.spectrum +=
            spectrum_error(autocorrelation(output, tile, tile, reach, false),
                           autocorrelation(target, exemplar.width, exemplar.height, reach, true));
        varying++;
    }
    measured.spectrum /= std::max(1, varying);
    return measured;
}

} // namespace

int main() {
    const std::string folder = bake_fixtures::textures_folder();
    if (!std::filesystem::is_directory(folder)) {
        std::printf("histogram bench: SKIPPED, no texture folder %s (set DSN_TEXTURES)\n", folder.c_str());
        return 0;
    }
    std::vector<std::string> paths;
    for (const auto &entry : std::filesystem::directory_iterator(folder))
        if (entry.path().extension() == ".png") paths.push_back(entry.path().string());
    std::sort(paths.begin(), paths.end());
    std::printf("%-28s %9s %4s %9s %9s %7s %9s %9s  %s\n", "texture", "size", "r", "W1 plain", "W1 hist",
                "ratio", "spec plain", "spec hist", "marginal (the plain bake's verdict)");
    std::vector<double> ratios, non_gaussian_ratios, spectrum_changes;
    for (const std::string &path : paths) {
        const dsn::Image exemplar = dsn::load_exemplar(path, nullptr);
        dsn::BakeOptions options;
        options.radius = std::min(15, (std::min(exemplar.width, exemplar.height) - 1) / 4);
        if (options.radius < 1) continue;
        const std::string name = std::filesystem::path(path).stem().string();
        Measured plain, mapped;
        bool non_gaussian = false;
        try {
            const dsn::BakeResult plain_bake = dsn::bake(exemplar, options);
            const auto &findings = plain_bake.verdict.findings;
            non_gaussian = std::find(findings.begin(), findings.end(),
                                     dsn::VerdictFinding::NonGaussianMarginal) != findings.end();
            plain = measure(exemplar, plain_bake, 256);
            options.histogram = true;
            mapped = measure(exemplar, dsn::bake(exemplar, options), 256);
        } catch (const std::runtime_error &error) { // a constant picture (its alpha held the pattern)
            std::printf("%-28s refused: %s\n", name.c_str(), error.what());
            continue;
        }
        const double ratio = mapped.w1 / plain.w1;
        ratios.push_back(ratio);
        if (non_gaussian) non_gaussian_ratios.push_back(ratio);
        spectrum_changes.push_back(mapped.spectrum - plain.spectrum);
        std::printf("%-28s %4dx%-4d %4d %9.4f %9.4f %7.3f %9.3f %9.3f  %s\n", name.c_str(), exemplar.width,
                    exemplar.height, options.radius, plain.w1, mapped.w1, ratio, plain.spectrum,
                    mapped.spectrum, non_gaussian ? "non-Gaussian" : "");
    }
    if (ratios.empty()) return 0;
    std::sort(ratios.begin(), ratios.end());
    std::sort(spectrum_changes.begin(), spectrum_changes.end());
    std::printf("W1 ratio (histogram-preserving / plain) over %zu textures: median %.3f, min %.3f, max %.3f; "
                "%zu of them below 1/3\n",
                ratios.size(), ratios[ratios.size() / 2], ratios.front(), ratios.back(),
                size_t(std::count_if(ratios.begin(), ratios.end(), [](double r) { return r <= 1.0 / 3; })));
    if (!non_gaussian_ratios.empty()) {
        std::sort(non_gaussian_ratios.begin(), non_gaussian_ratios.end());
        std::printf(
            "  on the %zu whose marginals the verdict finds non-Gaussian: median %.3f, max %.3f; %zu of "
            "them below 1/3 [target: all]\n",
            non_gaussian_ratios.size(), non_gaussian_ratios[non_gaussian_ratios.size() / 2],
            non_gaussian_ratios.back(),
            size_t(std::count_if(non_gaussian_ratios.begin(), non_gaussian_ratios.end(),
                                 [](double r) { return r <= 1.0 / 3; })));
    }
    std::printf(
        "spectrum error change (histogram-preserving - plain): median %+.3f, min %+.3f, max %+.3f; %zu "
        "of them worse by more than 0.05\n",
        spectrum_changes[spectrum_changes.size() / 2], spectrum_changes.front(), spectrum_changes.back(),
        size_t(std::count_if(spectrum_changes.begin(), spectrum_changes.end(),
                             [](double change) { return change > 0.05; })));
    return 0;
}
