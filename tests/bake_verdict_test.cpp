// bake_verdict_test.cpp - the verdict on generated exemplars with known answers: a Gaussian texture is
// held, a weave whose period exceeds the texton's reach gets a larger radius, a two-level pattern gets the
// non-Gaussian-marginal finding, flagstones, facets, stripes and discs get the shape finding and their
// random-phase copies do not, weak but wide correlation gets the structure finding, a small RME is never
// flagged, the noise's moments at the asset's density are those the runtime renders; and the bake's early
// stop and threads leave the result reproducible.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>

#include "dsn/dsn.h"
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

// xorshift32 in [0, 1): the generated exemplars' own deterministic draws.
struct Draws {
    uint32_t state;
    explicit Draws(uint32_t seed) : state(seed * 2654435761u + 1) {}
    double next() {
        state ^= state << 13, state ^= state >> 17, state ^= state << 5;
        return double(state) / 4294967296.0;
    }
};

// A grey size x size exemplar from a function of the pixel, plus light white noise (a photo's grain).
dsn::Image grey_exemplar(int size, uint32_t seed, const std::function<double(int, int)> &value) {
    dsn::Image image;
    image.width = image.height = size, image.channels = 1;
    image.values.resize(size_t(size) * size_t(size));
    const dsn::Image grain = dsn::white_noise(size, size, seed);
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) image.at(x, y, 0) = value(x, y) + 0.01 * grain.at(x, y, 0);
    return image;
}

// Voronoi cells of `count` seed points on the torus: the index of the nearest and the gap between the
// nearest and the second nearest distance (0 on a boundary).
struct Cells {
    std::vector<double> px, py;
    int size;
    Cells(int count, int side, uint32_t seed) : size(side) {
        Draws draws(seed);
        for (int i = 0; i < count; i++) px.push_back(draws.next() * side), py.push_back(draws.next() * side);
    }
    void nearest(int x, int y, int &index, double &gap) const {
        double first = 1e300, second = 1e300;
        for (size_t i = 0; i < px.size(); i++) {
            double dx = std::fabs(x - px[i]), dy = std::fabs(y - py[i]);
            dx = std::min(dx, size - dx), dy = std::min(dy, size - dy);
            const double d = std::sqrt(dx * dx + dy * dy);
            if (d < first)
                second = first, first = d, index = int(i);
            else if (d < second)
                second = d;
        }
        gap = second - first;
    }
};

// The exemplars built to have sharp shapes, each a known material's.
dsn::Image flagstones(int size) { // stones of their own tones, dark mortar joints 2 pixels wide
    const Cells cells(40, size, 21);
    Draws tones(22);
    std::vector<double> tone(cells.px.size());
    for (double &value : tone) value = 0.45 + 0.3 * tones.next();
    return grey_exemplar(size, 23, [&](int x, int y) {
        int index = 0;
        double gap = 0;
        cells.nearest(x, y, index, gap);
        return gap < 2 ? 0.15 : tone[size_t(index)];
    });
}
dsn::Image facets(int size) { // flat facets, each a linear ramp of its own slope, no joints
    const Cells cells(30, size, 31);
    Draws draws(32);
    std::vector<double> base(cells.px.size()), sx(base.size()), sy(base.size());
    for (size_t i = 0; i < base.size(); i++)
        base[i] = 0.3 + 0.4 * draws.next(), sx[i] = 0.01 * (draws.next() - 0.5),
        sy[i] = 0.01 * (draws.next() - 0.5);
    return grey_exemplar(size, 33, [&](int x, int y) {
        int index = 0;
        double gap = 0;
        cells.nearest(x, y, index, gap);
        const size_t i = size_t(index);
        return base[i] + sx[i] * (x - cells.px[i]) + sy[i] * (y - cells.py[i]);
    });
}
dsn::Image stripes(int size) { // horizontal bands of random widths (3 to 10) and random tones
    std::vector<double> row_tone(size_t(size), 0.0);
    Draws draws(41);
    for (int y = 0; y < size;) {
        const int width = 3 + int(draws.next() * 8);
        const double tone = 0.2 + 0.6 * draws.next();
        for (int k = 0; k < width && y < size; k++, y++) row_tone[size_t(y)] = tone;
    }
    return grey_exemplar(size, 43, [&](int, int y) { return row_tone[size_t(y)]; });
}
dsn::Image discs(int size) { // discs of radius 3 to 8, of their own tones, on a mid background
    struct Disc {
        double x, y, r, tone;
    };
    std::vector<Disc> list;
    Draws draws(51);
    for (int i = 0; i < 60; i++)
        list.push_back(
            {draws.next() * size, draws.next() * size, 3 + 5 * draws.next(), 0.2 + 0.6 * draws.next()});
    return grey_exemplar(size, 53, [&](int x, int y) {
        double value = 0.5;
        for (const Disc &disc : list) {
            double dx = std::fabs(x - disc.x), dy = std::fabs(y - disc.y);
            dx = std::min(dx, size - dx), dy = std::min(dy, size - dy);
            if (dx * dx + dy * dy <= disc.r * disc.r) value = disc.tone;
        }
        return value;
    });
}

// The exemplar's random-phase copy: its spectrum's modulus with the phase of a white noise's (the same
// spectrum, hence the same autocorrelation, with no shape), its mean added back.
dsn::Image random_phase_copy(const dsn::Image &exemplar, uint32_t seed) {
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, true);
    dsn::Image copy = dsn::inverse_dft(dsn::random_phase_start(model.spectrum, seed));
    const double scale = std::sqrt(double(exemplar.width) * double(exemplar.height));
    const size_t plane = size_t(exemplar.width) * size_t(exemplar.height);
    for (int c = 0; c < copy.channels; c++)
        for (size_t i = 0; i < plane; i++)
            copy.values[size_t(c) * plane + i] =
                model.mean[size_t(c)] + scale * copy.values[size_t(c) * plane + i];
    return copy;
}

// The sample skewness and excess kurtosis of values.
void sample_moments(const std::vector<double> &values, double &skewness, double &kurtosis) {
    double mean = 0;
    for (double value : values) mean += value;
    mean /= double(values.size());
    double m2 = 0, m3 = 0, m4 = 0;
    for (double value : values) {
        const double d = value - mean;
        m2 += d * d, m3 += d * d * d, m4 += d * d * d * d;
    }
    m2 /= double(values.size()), m3 /= double(values.size()), m4 /= double(values.size());
    skewness = m3 / (m2 * std::sqrt(m2));
    kurtosis = m4 / (m2 * m2) - 3;
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

TEST_CASE(
    "verdict: a Gaussian field's shape signal is 1 within its standard error, and that error is its spread") {
    // Over 16 Gaussian fields of one autocorrelation, the ratios' spread estimates the error the signal
    // states: with 15 degrees of freedom the sample deviation lies within [0.5, 1.6] of the true one with
    // probability above 0.99 (chi-square quantiles).
    const int fields = 16;
    std::vector<double> ratios;
    double stated = 0;
    for (int i = 0; i < fields; i++) {
        const dsn::Image field = bake_fixtures::spot_noise_field(96, 1, uint32_t(100 + i), 0.5, 0.1);
        const dsn::ShapeSignal signal = dsn::shape_signal(dsn::gaussian_model(field, true).t_u, 0);
        ratios.push_back(signal.ratio);
        stated += signal.error / fields;
    }
    double mean = 0, square = 0;
    for (double ratio : ratios) mean += ratio / fields;
    for (double ratio : ratios) square += (ratio - mean) * (ratio - mean);
    const double spread = std::sqrt(square / (fields - 1));
    INFO("mean " << mean << " spread " << spread << " stated error " << stated);
    CHECK(stated > 0);
    CHECK(std::fabs(mean - 1) < 3 * stated / std::sqrt(double(fields)) + 0.01); // the ratio's own bias
    CHECK(spread > 0.5 * stated);
    CHECK(spread < 1.6 * stated);
}

TEST_CASE("verdict: flagstones, facets, stripes and discs get the shape finding, their random-phase copies "
          "do not") {
    const int size = 128;
    const std::vector<std::pair<const char *, dsn::Image>> exemplars = {{"flagstones", flagstones(size)},
                                                                        {"facets", facets(size)},
                                                                        {"stripes", stripes(size)},
                                                                        {"discs", discs(size)}};
    for (const auto &named : exemplars) {
        INFO(named.first);
        const dsn::BakeVerdict shaped = bake_at(named.second, 15).verdict;
        INFO(shaped.summary);
        CHECK(has(shaped, dsn::VerdictFinding::ShapeBeyondSpectrum));
        CHECK(shaped.summary.rfind("good", 0) != 0);
        CHECK(shaped.shape_ratio < dsn::kVerdictShapeRatio);
        CHECK(1 - shaped.shape_ratio > 3 * shaped.shape_error);
        // The report says what it saw: the ratio, to two decimals.
        const auto said =
            std::find_if(shaped.suggestions.begin(), shaped.suggestions.end(), [](const std::string &text) {
                return text.find("sharp shapes") != std::string::npos;
            });
        REQUIRE(said != shaped.suggestions.end());
        char ratio[32];
        std::snprintf(ratio, sizeof ratio, "total variation %.2f", shaped.shape_ratio);
        CHECK(said->find(ratio) != std::string::npos);

        const dsn::BakeVerdict copy = bake_at(random_phase_copy(named.second, 7), 15).verdict;
        INFO(copy.summary);
        CHECK(!has(copy, dsn::VerdictFinding::ShapeBeyondSpectrum));
        CHECK(std::fabs(1 - copy.shape_ratio) < 3 * copy.shape_error + 0.01);
    }
}

TEST_CASE("verdict: skewed tones of a Gaussian field are a tones finding, not a shape one") {
    // exp of a Gaussian field: a monotone change of tones, which --histogram restores exactly.
    dsn::Image skewed = gaussian_exemplar(128, 1, 13);
    for (double &value : skewed.values) value = 0.05 * std::exp(12 * (value - 0.5));
    const dsn::BakeVerdict verdict = bake_at(skewed, 15).verdict;
    INFO(verdict.summary);
    CHECK(has(verdict, dsn::VerdictFinding::NonGaussianMarginal));
    CHECK(!has(verdict, dsn::VerdictFinding::ShapeBeyondSpectrum));
    CHECK(std::fabs(1 - verdict.shape_ratio) < 3 * verdict.shape_error + 0.01);
}

TEST_CASE("verdict: weak correlation beyond the texton's reach is found when it holds a large share") {
    // A white Gaussian grain plus a faint grid of period 40 (0.08 of the grain's variance): every
    // correlation beyond reach stays below 0.2 of the variance, yet most of the autocorrelation energy
    // lies there.
    const int size = 160, period = 40;
    const dsn::Image fine = dsn::white_noise(size, size, 61);
    const double two_pi = 6.283185307179586, amplitude = 2 * std::sqrt(0.08);
    dsn::Image exemplar = fine;
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++)
            exemplar.at(x, y, 0) = 0.5 + 0.1 * (fine.at(x, y, 0) + amplitude * std::sin(two_pi * x / period) *
                                                                       std::sin(two_pi * y / period));
    const dsn::BakeVerdict verdict = bake_at(exemplar, 8).verdict;
    INFO(verdict.summary);
    CHECK(verdict.correlation_beyond_reach < 0.2);
    CHECK(verdict.structure_beyond_reach > dsn::kVerdictStructureShare);
    CHECK((has(verdict, dsn::VerdictFinding::StructureBeyondRadius) ||
           has(verdict, dsn::VerdictFinding::StructureBeyondGaussian)));
    CHECK(verdict.structure_beyond_reach > 3 * verdict.structure_error);
    // Without the grid, what lies beyond reach is sampling noise, within 3 of its standard deviations.
    dsn::Image grain = fine;
    for (double &value : grain.values) value = 0.5 + 0.1 * value;
    const dsn::BakeVerdict plain = bake_at(grain, 8).verdict;
    INFO(plain.summary);
    CHECK(plain.structure_beyond_reach < 3 * plain.structure_error);
    CHECK(!has(plain, dsn::VerdictFinding::StructureBeyondRadius));
    CHECK(!has(plain, dsn::VerdictFinding::StructureBeyondGaussian));
}

TEST_CASE("verdict: a small RME is never flagged; the one judged is what renders") {
    for (int channels : {1, 3}) {
        const dsn::BakeResult result = bake_at(gaussian_exemplar(128, channels, 5), 15);
        const dsn::BakeVerdict &verdict = result.verdict;
        INFO(verdict.summary);
        CHECK(verdict.rme_effective == result.rme_effective);
        CHECK(verdict.rme_effective < dsn::kVerdictModelError);
        CHECK(!has(verdict, dsn::VerdictFinding::HighModelError));
    }
    // Lattice read, 16 bits, no colour transform: what renders is the quantized texton itself.
    dsn::BakeOptions options;
    options.interpolation = DSN_INTERPOLATION_LATTICE;
    options.use_color_transform = false;
    options.bits = 16;
    const dsn::BakeResult lattice = dsn::bake(gaussian_exemplar(128, 3, 5), options);
    CHECK(lattice.rme_effective == doctest::Approx(lattice.rme_quantized).epsilon(1e-5));
    // The bilinear read's spline is applied: the texton aimed at the corrected target renders close to the
    // model, closer than the same texton read without the spline.
    const dsn::BakeResult bilinear = bake_at(gaussian_exemplar(128, 3, 5), 15);
    dsn::Matrix3 stored{};
    for (size_t i = 0; i < stored.size(); i++)
        stored[i] = double(bilinear.fields.color_transform[i]) / double(DSN_Q24_ONE);
    const double without_spline = dsn::effective_model_error(
        bilinear.model.spectrum, bilinear.quantized_texton, stored, DSN_INTERPOLATION_LATTICE);
    CHECK(bilinear.rme_effective ==
          doctest::Approx(dsn::effective_model_error(bilinear.model.spectrum, bilinear.quantized_texton,
                                                     stored, DSN_INTERPOLATION_BILINEAR)));
    CHECK(bilinear.rme_effective < without_spline);
    // A high effective RME is flagged, naming both: a texton of radius 2 for a texture correlated far wider.
    const dsn::BakeVerdict cramped = bake_at(bake_fixtures::spot_noise_field(128, 1, 8, 0.5, 0.1), 1).verdict;
    INFO(cramped.summary);
    CHECK(has(cramped, dsn::VerdictFinding::HighModelError) ==
          (cramped.rme_effective > dsn::kVerdictModelError));
}

TEST_CASE("verdict: the noise's moments by Campbell's theorem, on a one-texel spot") {
    // A spike of one texel at lambda = impacts / |S|: the lattice noise is a Poisson count, skewness
    // 1 / sqrt(lambda) and excess kurtosis 1 / lambda; read bilinearly the spot is the tent, whose n-th
    // power integrates to (2 / (n + 1))^2: skewness (1/4) / (sqrt(lambda) (4/9)^1.5), kurtosis
    // (4/25) / (lambda (4/9)^2). A colour transform mixing two channels of one spike changes neither.
    dsn::Texton spike;
    spike.support = dsn::support_mask(3, DSN_SHAPE_RECTANGLE);
    spike.channels = 2;
    spike.values.assign(size_t(2 * 49), 0.0);
    spike.values[size_t(24)] = 0.5, spike.values[size_t(49 + 24)] = 0.25;
    const dsn::Matrix3 mixing = {1, 1, 0, 2, -1, 0, 0, 0, 1};
    const double impacts = 7, lambda = impacts / 49;
    const dsn::NoiseMoments lattice = dsn::noise_moments(spike, mixing, DSN_INTERPOLATION_LATTICE, impacts);
    const dsn::NoiseMoments bilinear = dsn::noise_moments(spike, mixing, DSN_INTERPOLATION_BILINEAR, impacts);
    for (size_t c = 0; c < 2; c++) {
        CHECK(lattice.skewness[c] == doctest::Approx(1 / std::sqrt(lambda)).epsilon(1e-12));
        CHECK(lattice.excess_kurtosis[c] == doctest::Approx(1 / lambda).epsilon(1e-12));
        CHECK(bilinear.skewness[c] ==
              doctest::Approx(0.25 / (std::sqrt(lambda) * std::pow(4.0 / 9, 1.5))).epsilon(1e-12));
        CHECK(bilinear.excess_kurtosis[c] == doctest::Approx(0.16 / (lambda * (16.0 / 81))).epsilon(1e-12));
    }
}

TEST_CASE("verdict: the noise's skewness and kurtosis are what the runtime renders, and the density it names "
          "brings them under the bounds") {
    // A smooth Gaussian texture (spot of deviation 6) whose texton's noise is skewed at 30 impacts.
    const int size = 128;
    dsn::Image spot;
    spot.width = spot.height = size, spot.channels = 1;
    spot.values.assign(size_t(size) * size, 0.0);
    for (int dy = -30; dy <= 30; dy++)
        for (int dx = -30; dx <= 30; dx++)
            spot.at((dx + size) % size, (dy + size) % size, 0) = std::exp(-(dx * dx + dy * dy) / 72.0);
    dsn::Spectrum spectrum = dsn::forward_dft(spot);
    const dsn::Spectrum white = dsn::forward_dft(dsn::white_noise(size, size, 3));
    for (size_t i = 0; i < spectrum.values.size(); i++) spectrum.values[i] *= white.values[i];
    dsn::Image exemplar = dsn::inverse_dft(spectrum);
    double square = 0;
    for (double value : exemplar.values) square += value * value;
    const double deviation = std::sqrt(square / double(exemplar.values.size()));
    for (double &value : exemplar.values) value = 0.5 + 0.1 * value / deviation;

    for (uint32_t interpolation :
         {uint32_t(DSN_INTERPOLATION_LATTICE), uint32_t(DSN_INTERPOLATION_BILINEAR)}) {
        INFO("interpolation " << interpolation);
        dsn::BakeOptions options;
        options.interpolation = interpolation;
        const dsn::BakeResult result = dsn::bake(exemplar, options);
        const dsn::BakeVerdict &verdict = result.verdict;
        INFO(verdict.summary);
        dsn::Matrix3 stored{};
        for (size_t i = 0; i < stored.size(); i++)
            stored[i] = double(result.fields.color_transform[i]) / double(DSN_Q24_ONE);
        CHECK(verdict.impacts == 30);
        const dsn::NoiseMoments at_30 =
            dsn::noise_moments(result.quantized_texton, stored, interpolation, 30);
        CHECK(verdict.noise_skewness == at_30.skewness);
        CHECK(verdict.noise_excess_kurtosis == at_30.excess_kurtosis);

        // The runtime at 2 impacts per pixel, where the moments are large: four independent 384 x 384
        // renders, whose spread gives the sampling error.
        const double impacts = 2;
        const dsn::NoiseMoments stated =
            dsn::noise_moments(result.quantized_texton, stored, interpolation, impacts);
        std::vector<double> skews, kurtoses;
        for (uint32_t seed = 1; seed <= 4; seed++) {
            dsn_asset asset;
            dsn_noise noise;
            dsn_config config;
            REQUIRE(dsn_asset_load(&asset, result.asset.data(), result.asset.size()) == DSN_OK);
            dsn_config_defaults(&config);
            config.seed = seed;
            config.impacts_q16 = uint32_t(impacts * 65536);
            REQUIRE(dsn_noise_init(&noise, &asset, &config) == DSN_OK);
            const uint32_t side = 384;
            std::vector<float> out(size_t(side) * side);
            int error;
            if (interpolation == DSN_INTERPOLATION_BILINEAR) {
                const int64_t one = int64_t(1) << 32;
                const dsn_grid grid = {
                    int64_t(0.37 * double(one)), int64_t(0.61 * double(one)), one, 0, 0, one};
                std::vector<unsigned char> scratch(
                    std::max<size_t>(1, dsn_continuous_tile_scratch_size(&noise, &grid, side, side)));
                error = dsn_continuous_tile_float(&noise, &grid, side, side, out.data(), scratch.data(),
                                                  scratch.size());
            } else {
                std::vector<unsigned char> scratch(dsn_lattice_tile_scratch_size(&noise, side, side));
                error = dsn_lattice_tile_float(&noise, 0, 0, side, side, out.data(), scratch.data(),
                                               scratch.size());
            }
            REQUIRE(error == DSN_OK);
            double skew = 0, kurtosis = 0;
            sample_moments(std::vector<double>(out.begin(), out.end()), skew, kurtosis);
            skews.push_back(skew), kurtoses.push_back(kurtosis);
        }
        auto mean_and_error = [](const std::vector<double> &values, double &mean, double &error) {
            mean = 0;
            for (double value : values) mean += value / double(values.size());
            double sum = 0;
            for (double value : values) sum += (value - mean) * (value - mean);
            error = std::sqrt(sum / double(values.size() - 1) / double(values.size()));
        };
        double skew = 0, skew_error = 0, kurtosis = 0, kurtosis_error = 0;
        mean_and_error(skews, skew, skew_error);
        mean_and_error(kurtoses, kurtosis, kurtosis_error);
        INFO("rendered skewness " << skew << " +- " << skew_error << ", stated " << stated.skewness[0]);
        INFO("rendered kurtosis " << kurtosis << " +- " << kurtosis_error << ", stated "
                                  << stated.excess_kurtosis[0]);
        // Within 6 standard errors of the mean of four (Student's t with 3 degrees of freedom exceeds 5.84
        // with probability 0.01).
        CHECK(std::fabs(skew - stated.skewness[0]) < 6 * skew_error);
        CHECK(std::fabs(kurtosis - stated.excess_kurtosis[0]) < 6 * kurtosis_error);
        // The stated moments are far from 0 at that density: the comparison has teeth.
        CHECK(std::fabs(stated.skewness[0]) > 6 * skew_error);

        // At 30 impacts the noise is beyond the bounds; the suggested density brings both under them, one
        // impact less does not.
        REQUIRE(has(verdict, dsn::VerdictFinding::SparseNoise));
        REQUIRE(verdict.suggested_impacts > verdict.impacts);
        CHECK(verdict.summary.rfind("fair", 0) == 0);
        const dsn::NoiseMoments at =
            dsn::noise_moments(result.quantized_texton, stored, interpolation, verdict.suggested_impacts);
        CHECK(std::fabs(at.skewness[0]) <= dsn::kVerdictNoiseSkewness);
        CHECK(std::fabs(at.excess_kurtosis[0]) <= dsn::kVerdictNoiseKurtosis);
        const dsn::NoiseMoments below =
            dsn::noise_moments(result.quantized_texton, stored, interpolation, verdict.suggested_impacts - 1);
        CHECK((std::fabs(below.skewness[0]) > dsn::kVerdictNoiseSkewness ||
               std::fabs(below.excess_kurtosis[0]) > dsn::kVerdictNoiseKurtosis));
        char named[64];
        std::snprintf(named, sizeof named, "--impacts %g", verdict.suggested_impacts);
        const auto said =
            std::find_if(verdict.suggestions.begin(), verdict.suggestions.end(),
                         [&](const std::string &text) { return text.find(named) != std::string::npos; });
        CHECK(said != verdict.suggestions.end());
    }
}
