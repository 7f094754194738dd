// bake_verdict_test.cpp - the verdict on generated exemplars with known answers: a Gaussian texture is
// held, a weave whose period exceeds the texton's reach gets a larger radius, a two-level pattern gets the
// non-Gaussian-marginal finding; and the bake's early stop and threads leave the result reproducible.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "fixtures/bake_fixtures.h"
#include "offline/bake_internal.h"
#include <doctest/doctest.h>

namespace {

// Asymptotic discrete spot noise of the known spot (bake_fixtures::spot_noise_field), so the exemplar has
// the sampling fluctuations of a photo of a Gaussian texture; mean 0.5, standard deviation 0.1.
dsn::Image gaussian_exemplar(int size, int channels, uint32_t seed) {
    return bake_fixtures::spot_noise_field(size, channels, seed, 0.5, 0.1);
}

dsn::BakeResult bake_at(const dsn::Image &exemplar, int radius) {
    dsn::BakeOptions options;
    options.radius = radius;
    return dsn::bake(exemplar, options);
}

bool has(const dsn::BakeVerdict &verdict, dsn::VerdictFinding finding) {
    return std::find(verdict.findings.begin(), verdict.findings.end(), finding) != verdict.findings.end();
}

} // namespace

TEST_CASE("verdict: a Gaussian exemplar is held") {
    for (int channels : {1, 3}) {
        const dsn::BakeResult result = bake_at(gaussian_exemplar(128, channels, 5), 15);
        const dsn::BakeVerdict &verdict = result.verdict;
        INFO(verdict.summary);
        CHECK(verdict.findings.empty());
        CHECK(verdict.summary.rfind("good", 0) == 0);
        CHECK(verdict.suggestions.empty());
        REQUIRE(verdict.channels.size() == size_t(channels));
        // The moments of a Gaussian field stay within 3 of their standard errors.
        CHECK(std::fabs(verdict.channels[0].skewness) < 3 * verdict.channels[0].skewness_error);
        CHECK(std::fabs(verdict.channels[0].excess_kurtosis) < 3 * verdict.channels[0].kurtosis_error);
        CHECK(verdict.structure_beyond_reach < dsn::kVerdictStructureShare);
    }
}

TEST_CASE("verdict: a weave whose period exceeds the texton's reach gets a larger radius") {
    // Period 24 in both directions, alternating orientation every 12 pixels, light noise; r = 8 reaches
    // lags up to 16 only.
    const int size = 128, period = 24;
    dsn::Image weave;
    weave.width = weave.height = size, weave.channels = 1;
    weave.values.resize(size_t(size) * size);
    const dsn::Image noise = dsn::white_noise(size, size, 3);
    const double two_pi = 6.283185307179586;
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            const double across = std::sin(two_pi * x / period), along = std::sin(two_pi * y / period);
            weave.at(x, y, 0) =
                0.5 + 0.2 * (((x / 12 + y / 12) % 2) ? across : along) + 0.03 * noise.at(x, y, 0);
        }
    const dsn::BakeResult result = bake_at(weave, 8);
    const dsn::BakeVerdict &verdict = result.verdict;
    INFO(verdict.summary);
    CHECK(has(verdict, dsn::VerdictFinding::StructureBeyondRadius));
    CHECK(!has(verdict, dsn::VerdictFinding::NonGaussianMarginal));
    CHECK(verdict.structure_beyond_reach > dsn::kVerdictStructureShare);
    CHECK(verdict.suggested_radius == period); // the strongest correlation beyond reach: one period
    REQUIRE(!verdict.suggestions.empty());
    CHECK(verdict.suggestions[0].find("--radius 24") != std::string::npos);
    CHECK(verdict.suggestions[0].find("bytes instead of " + std::to_string(result.asset.size())) !=
          std::string::npos);
    // The asset size the suggestion names is the one a bake at that radius writes.
    dsn::BakeOptions options;
    options.radius = 24;
    options.iterations = 2;
    const size_t larger = dsn::bake(weave, options).asset.size();
    CHECK(verdict.suggestions[0].find("asset " + std::to_string(larger) + " bytes") != std::string::npos);
}

TEST_CASE("verdict: a two-level pattern gets the non-Gaussian-marginal finding") {
    dsn::Image binary = gaussian_exemplar(128, 1, 9);
    for (double &value : binary.values) value = value > 0.5 ? 0.7 : 0.3;
    const dsn::BakeVerdict verdict = bake_at(binary, 15).verdict;
    INFO(verdict.summary);
    CHECK(has(verdict, dsn::VerdictFinding::NonGaussianMarginal));
    CHECK(!has(verdict, dsn::VerdictFinding::StructureBeyondRadius));
    // A symmetric two-level marginal has excess kurtosis -2 exactly (less sampling error).
    CHECK(verdict.channels[0].excess_kurtosis == doctest::Approx(-2).epsilon(0.05));
    CHECK(verdict.summary.rfind("limited", 0) == 0);
}

TEST_CASE("verdict: a two-level pattern gets --histogram suggested, and not once it is on") {
    for (int channels : {1, 3}) {
        dsn::Image binary = gaussian_exemplar(128, channels, 9);
        for (double &value : binary.values) value = value > 0.5 ? 0.7 : 0.3;
        dsn::BakeOptions options;
        const dsn::BakeResult plain = dsn::bake(binary, options);
        REQUIRE(has(plain.verdict, dsn::VerdictFinding::NonGaussianMarginal));
        const auto suggestion =
            std::find_if(plain.verdict.suggestions.begin(), plain.verdict.suggestions.end(),
                         [](const std::string &text) { return text.find("tones") != std::string::npos; });
        REQUIRE(suggestion != plain.verdict.suggestions.end());
        INFO(*suggestion);
        CHECK(suggestion->find("try --histogram") != std::string::npos);
        // It names the bytes the mapping adds: header, 1 + levels tables of 129 Q3.12 entries per channel.
        const size_t tables = 2 * 129 * size_t(channels) * (1 + plain.fields.pyramid.size());
        CHECK(suggestion->find(std::to_string(8 + 68 + tables) + " bytes") != std::string::npos);

        options.histogram = true;
        const dsn::BakeVerdict mapped = dsn::bake(binary, options).verdict;
        INFO(mapped.summary);
        CHECK(!has(mapped, dsn::VerdictFinding::NonGaussianMarginal));
        CHECK(mapped.summary.find("non-Gaussian tones kept by the histogram mapping") != std::string::npos);
        for (const std::string &text : mapped.suggestions)
            CHECK(text.find("--histogram") == std::string::npos);
        // The signals still describe the exemplar's tones, and its structure as the plain bake saw it.
        CHECK(mapped.channels[0].excess_kurtosis ==
              doctest::Approx(plain.verdict.channels[0].excess_kurtosis));
        CHECK(!has(mapped, dsn::VerdictFinding::StructureBeyondRadius));
        CHECK(mapped.structure_beyond_reach < dsn::kVerdictStructureShare);
    }
}

TEST_CASE("bake: the early stop reports why it stopped, and threads change no bit") {
    const dsn::Image exemplar = gaussian_exemplar(128, 3, 11);
    dsn::BakeOptions options; // default early stop
    const dsn::BakeResult stopped = dsn::bake(exemplar, options);
    const size_t runs = stopped.sot.rme_per_iteration.size();
    CHECK(stopped.sot.stop == dsn::SotStop::Converged);
    CHECK(runs >= size_t(dsn::early_stop_minimum_iterations(128, 128)));
    CHECK(runs < size_t(options.iterations));
    const auto &rme = stopped.sot.rme_per_iteration;
    CHECK(rme[runs - 51] - rme.back() < dsn::kDefaultStopTolerance);
    options.stop_tolerance = 0;
    options.iterations = int(runs);
    CHECK(dsn::bake(exemplar, options).sot.stop == dsn::SotStop::IterationLimit);

    options = dsn::BakeOptions();
    setenv("DSN_BAKE_THREADS", "1", 1);
    const dsn::BakeResult one_thread = dsn::bake(exemplar, options);
    setenv("DSN_BAKE_THREADS", "3", 1);
    const dsn::BakeResult three_threads = dsn::bake(exemplar, options);
    unsetenv("DSN_BAKE_THREADS");
    CHECK(one_thread.asset == stopped.asset);
    CHECK(three_threads.asset == stopped.asset);
    CHECK(one_thread.sot.rme_per_iteration == three_threads.sot.rme_per_iteration);
}
