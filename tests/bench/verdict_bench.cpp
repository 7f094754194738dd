// verdict_bench.cpp - what the bake verdict says of real textures: for every PNG of the shared texture
// folder (DSN_TEXTURES, default ../shared/textures), a default bake's RME (the texton's) and effective RME
// (what renders: quantized texton, stored colour transform, bilinear read), the shape signal (total
// variation over a random-phase copy's, on the Gaussianized exemplar, with its standard error), the share
// of autocorrelation energy beyond the texton's reach and the largest correlation there, the noise's
// skewness and excess kurtosis at the asset's density (worst output channel) with the density the verdict
// suggests, and the verdict with its findings. Skipped, saying so, when the folder is absent.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixtures/bake_fixtures.h"

int main() {
    const std::vector<std::string> paths = bake_fixtures::texture_paths();
    if (paths.empty()) {
        std::printf("verdict_bench: skipped (no PNG in %s; set DSN_TEXTURES)\n",
                    bake_fixtures::textures_folder().c_str());
        return 0;
    }
    std::printf("%-22s %8s %6s %6s %11s %6s %5s %6s %6s %5s  %s\n", "texture", "size", "RME", "effRME",
                "shape(err)  ", "beyond(err)", "corr", "skew", "kurt", "imp", "verdict: findings");
    int good = 0, fair = 0, limited = 0, failed = 0;
    double largest_gap = 0;
    for (const std::string &path : paths) {
        const std::string name = std::filesystem::path(path).stem().string();
        dsn::BakeOptions options;
        dsn::BakeResult result;
        dsn::Image exemplar;
        try {
            std::vector<std::string> warnings;
            exemplar = dsn::load_exemplar(path, &warnings);
            options.radius = std::min(options.radius, (std::min(exemplar.width, exemplar.height) - 1) / 4);
            result = dsn::bake(exemplar, options);
        } catch (const std::exception &error) {
            std::printf("%-22s refused: %s\n", name.c_str(), error.what());
            failed++;
            continue;
        }
        const dsn::BakeVerdict &verdict = result.verdict;
        size_t worst = 0;
        for (size_t c = 1; c < verdict.noise_skewness.size(); c++)
            if (std::fabs(verdict.noise_skewness[c]) > std::fabs(verdict.noise_skewness[worst])) worst = c;
        std::string findings;
        for (dsn::VerdictFinding finding : verdict.findings)
            findings += std::string(findings.empty() ? "" : ", ") + dsn::verdict_finding_name(finding);
        const std::string word = verdict.summary.substr(0, verdict.summary.find(':'));
        good += word == "good", fair += word == "fair", limited += word == "limited";
        largest_gap = std::max(largest_gap, verdict.rme_effective - verdict.rme);
        char size[32];
        std::snprintf(size, sizeof size, "%dx%d", exemplar.width, exemplar.height);
        std::printf("%-22s %8s %6.3f %6.3f %5.3f(%.3f) %4.2f(%.2f) %5.2f %6.2f %6.2f %5.0f  %s%s%s (r=%d)\n",
                    name.c_str(), size, verdict.rme, verdict.rme_effective, verdict.shape_ratio,
                    verdict.shape_error, verdict.structure_beyond_reach, verdict.structure_error,
                    verdict.correlation_beyond_reach, verdict.noise_skewness[worst],
                    verdict.noise_excess_kurtosis[worst],
                    verdict.suggested_impacts > 0 ? verdict.suggested_impacts : verdict.impacts, word.c_str(),
                    findings.empty() ? "" : ": ", findings.c_str(), options.radius);
    }
    std::printf(
        "verdict_bench: %zu textures: %d good, %d fair, %d limited, %d refused; effective RME at most "
        "%.3f above the texton's\n",
        paths.size(), good, fair, limited, failed, largest_gap);
    return 0;
}
