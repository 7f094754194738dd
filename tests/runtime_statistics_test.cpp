// runtime_statistics_test.cpp - the runtime's output against theory (fixtures/noise_theory.h) on a
// synthetic texton and a baked-like one (the cropped luminance texton of a random exemplar, made here
// with a direct DFT), at 30 and 5 impacts per pixel: mean, covariances at lags, excess kurtosis,
// radially averaged power spectrum in periodic mode, and the independence of seeds.
#include <doctest/doctest.h>

#include <kiss_fftnd.h>

#include <cmath>
#include <complex>
#include <vector>

#include "fixtures/noise_theory.h"
#include "fixtures/test_assets.h"

namespace {

using dsn_test::LoadedNoise;
using dsn_test::NoiseTheory;

// The cropped luminance texton (see "How it works" in the README) of a 64 x 64 RGB random exemplar: white
// noise filtered by a different anisotropic blur per channel, mixed across channels. Quantized to 8 bits, 31
// x 31.
dsn::AssetFields baked_like_fields() {
    const int n = 64, side = 31, r = 15;
    const double tau = 2 * std::acos(-1.0);
    dsn_test::TestRandom random(77);
    std::vector<double> white(size_t(n) * n);
    for (double &w : white) w = double(random.range(-1000, 1000)) / 1000.0;
    std::vector<std::complex<double>> spectrum[3];
    auto dft = [&](const std::vector<double> &image) {
        std::vector<std::complex<double>> rows(size_t(n) * n), out(size_t(n) * n);
        for (int y = 0; y < n; y++)
            for (int xi = 0; xi < n; xi++)
                for (int x = 0; x < n; x++)
                    rows[size_t(y) * n + xi] += image[size_t(y) * n + x] * std::polar(1.0, -tau * xi * x / n);
        for (int eta = 0; eta < n; eta++)
            for (int xi = 0; xi < n; xi++)
                for (int y = 0; y < n; y++)
                    out[size_t(eta) * n + xi] +=
                        rows[size_t(y) * n + xi] * std::polar(1.0, -tau * eta * y / n);
        return out;
    };
    std::vector<std::complex<double>> noise_spectrum = dft(white);
    const double widths[3][2] = {{2.0, 5.0}, {4.0, 3.0}, {6.0, 1.5}};
    for (int c = 0; c < 3; c++) {
        spectrum[c].resize(size_t(n) * n);
        for (int eta = 0; eta < n; eta++)
            for (int xi = 0; xi < n; xi++) {
                double fx = (xi <= n / 2 ? xi : xi - n) / double(n),
                       fy = (eta <= n / 2 ? eta : eta - n) / double(n);
                double gain =
                    std::exp(-0.5 * tau * tau *
                             (fx * fx * widths[c][0] * widths[c][0] + fy * fy * widths[c][1] * widths[c][1]));
                spectrum[c][size_t(eta) * n + xi] = noise_spectrum[size_t(eta) * n + xi] * gain;
            }
    }
    // Luminance phase, then the inverse DFT at the window points only (direct sum), then 8-bit quantization.
    std::vector<double> texton[3];
    for (int c = 0; c < 3; c++) texton[c].assign(size_t(side) * side, 0.0);
    for (int eta = 0; eta < n; eta++)
        for (int xi = 0; xi < n; xi++) {
            size_t i = size_t(eta) * n + xi;
            std::complex<double> luminance =
                spectrum[0][i] / 3.0 + spectrum[1][i] / 2.0 + spectrum[2][i] / 6.0;
            if (std::abs(luminance) == 0) continue;
            std::complex<double> phase = std::conj(luminance) / std::abs(luminance);
            for (int dy = -r; dy <= r; dy++)
                for (int dx = -r; dx <= r; dx++) {
                    std::complex<double> w = std::polar(1.0, tau * (double(xi) * dx + double(eta) * dy) / n);
                    for (int c = 0; c < 3; c++)
                        texton[c][size_t(dy + r) * side + size_t(dx + r)] +=
                            (spectrum[c][i] * phase * w).real();
                }
        }
    dsn::AssetFields fields;
    fields.channels = 3;
    fields.width = fields.height = side;
    fields.texton.assign(size_t(side) * side * 3, 0);
    for (int c = 0; c < 3; c++) {
        double peak = 0;
        for (double v : texton[c]) peak = std::max(peak, std::abs(v));
        double scale_value = 0.05 / 127.0; // the peak maps to 127 and is worth 0.05
        for (size_t i = 0; i < texton[c].size(); i++)
            fields.texton[i * 3 + size_t(c)] = int32_t(std::lround(texton[c][i] / peak * 127.0));
        fields.scale[c] = uint32_t(std::lround(scale_value * std::ldexp(1.0, 40)));
        fields.mean[c] = int32_t((0.4 + 0.1 * c) * DSN_Q24_ONE);
    }
    const double K[9] = {1.1, -0.1, 0.05, 0.1, 0.9, 0.0, -0.05, 0.2, 1.2};
    for (int i = 0; i < 9; i++) fields.color_transform[i] = int32_t(std::lround(K[i] * DSN_Q24_ONE));
    return fields;
}

dsn::AssetFields synthetic_rgb() { return dsn_test::synthetic_fields(3, 31, 8, DSN_SHAPE_RECTANGLE, 5); }

// n independent blocks of 4 x 3 pixels, 64 apart (more than the texton diameter plus the block): each
// gives the values at lags (0,0), (1,0), (0,1) and (3,2) from its corner. Tile evaluation is exact
// (runtime_tile_test.cpp), so it is used for speed.
struct Samples {
    int channels;
    std::vector<double> values[4][3]; // [lag][channel]
};

const int lags[4][2] = {{0, 0}, {1, 0}, {0, 1}, {3, 2}};

Samples draw_samples(const dsn_noise &noise, int grid, int32_t origin) {
    Samples samples;
    samples.channels = int(dsn_noise_channels(&noise));
    int32_t block[4 * 3 * 3];
    for (int j = 0; j < grid; j++)
        for (int i = 0; i < grid; i++) {
            REQUIRE(dsn_lattice_tile_fixed(&noise, origin + 64 * i, origin + 64 * j, 4, 3, block, nullptr,
                                           0) == DSN_OK);
            for (int lag = 0; lag < 4; lag++)
                for (int c = 0; c < samples.channels; c++)
                    samples.values[lag][c].push_back(
                        block[(lags[lag][1] * 4 + lags[lag][0]) * samples.channels + c] / 65536.0);
        }
    return samples;
}

void check_moments(const dsn::AssetFields &fields, double impacts, uint32_t seed) {
    LoadedNoise loaded(fields, dsn_test::make_config(seed, impacts));
    NoiseTheory theory(loaded.noise);
    const int grid = 1000; // 10^6 independent samples per lag and channel
    Samples samples = draw_samples(loaded.noise, grid, -31999);
    const double n = double(grid) * grid;
    CAPTURE(impacts);
    for (int c = 0; c < samples.channels; c++) {
        const std::vector<double> &x = samples.values[0][c];
        double mean = 0;
        for (double v : x) mean += v;
        mean /= n;
        double variance = theory.covariance(c, c, 0, 0);
        CAPTURE(c);
        CHECK(std::abs(mean - theory.mean[c]) < 4 * std::sqrt(variance / n));
        for (int d = 0; d < samples.channels; d++)
            for (int lag = 0; lag < 4; lag++) {
                const std::vector<double> &y = samples.values[lag][d];
                double sum = 0;
                for (size_t i = 0; i < x.size(); i++)
                    sum += (x[i] - theory.mean[c]) * (y[i] - theory.mean[d]);
                double expected = theory.covariance(c, d, lags[lag][0], lags[lag][1]);
                double scale = std::sqrt(variance * theory.covariance(d, d, 0, 0));
                CAPTURE(d);
                CAPTURE(lag);
                CAPTURE(expected);
                CHECK(std::abs(sum / n - expected) < 0.03 * scale); // 3% of the covariance's scale
            }
        double kurtosis, standard_error;
        dsn_test::kurtosis_with_error(x, &kurtosis, &standard_error);
        CAPTURE(kurtosis);
        CAPTURE(standard_error);
        CHECK(std::abs(kurtosis - theory.excess_kurtosis(c)) < 4 * standard_error);
    }
}

// Radially averaged periodogram of period-512 blocks against the exact expectation P^2 |G(xi)|^2.
// Each periodogram value is near-exponential (relative deviation 1) and I(xi) = I(-xi), so a bin whose
// expected values are e_i averages about n_eff = (sum e)^2 / (2 sum e^2) independent values per seed
// (an anisotropic spectrum concentrates a ring on few frequencies). Rings of integer radius are merged
// until seeds * n_eff >= 10000: the bin's own relative error is then below 1%, and the coherent
// error from the Poisson number of impulses in a block, 1 / sqrt(seeds lambda P^2), stays below 0.5%.
void check_spectrum(const dsn::AssetFields &fields, double impacts) {
    const int period = 512, seeds = 32;
    const size_t size = size_t(period) * period;
    std::vector<double> measured[3];
    std::vector<int32_t> tile(size * fields.channels);
    const int dims[2] = {period, period};
    kiss_fftnd_cfg forward = kiss_fftnd_alloc(dims, 2, 0, nullptr, nullptr);
    std::vector<kiss_fft_cpx> in(size), out(size);
    for (int seed = 0; seed < seeds; seed++) {
        LoadedNoise loaded(fields, dsn_test::make_config(uint32_t(1000 + seed), impacts, period, period));
        REQUIRE(dsn_lattice_tile_fixed(&loaded.noise, -period * 3 + seed, 12345, period, period, tile.data(),
                                       nullptr, 0) == DSN_OK);
        for (uint32_t c = 0; c < fields.channels; c++) {
            double mean = fields.mean[c] / double(DSN_Q24_ONE);
            for (size_t i = 0; i < size; i++) {
                in[i].r = float(tile[i * fields.channels + c] / 65536.0 - mean);
                in[i].i = 0;
            }
            kiss_fftnd(forward, in.data(), out.data());
            measured[c].resize(size);
            for (size_t i = 0; i < size; i++)
                measured[c][i] += (double(out[i].r) * out[i].r + double(out[i].i) * out[i].i) / seeds;
        }
    }
    kiss_fft_free(forward);
    LoadedNoise reference(fields, dsn_test::make_config(0, impacts, period, period));
    NoiseTheory theory(reference.noise);
    for (int c = 0; c < int(fields.channels); c++) {
        std::vector<double> expected = theory.spectrum(c, period);
        const int rings = period / 2 + 1;
        std::vector<double> ring_measured(rings), ring_expected(rings), ring_expected_square(rings);
        std::vector<int> ring_count(rings);
        for (int eta = 0; eta < period; eta++)
            for (int xi = 0; xi < period; xi++) {
                int fx = xi <= period / 2 ? xi : xi - period, fy = eta <= period / 2 ? eta : eta - period;
                int ring = int(std::lround(std::sqrt(double(fx * fx + fy * fy))));
                if (ring >= rings) continue;
                size_t i = size_t(eta) * period + xi;
                double e = double(size) * expected[i];
                ring_measured[ring] += measured[c][i];
                ring_expected[ring] += e;
                ring_expected_square[ring] += e * e;
                ring_count[ring]++;
            }
        double peak = 0;
        for (int ring = 0; ring < rings; ring++)
            peak = std::max(peak, ring_expected[ring] / ring_count[ring]);
        int bins_checked = 0;
        double worst = 0;
        for (int ring = 0; ring < rings;) {
            double sum_measured = 0, sum_expected = 0, sum_square = 0;
            int count = 0;
            double independent = 0;
            for (; ring < rings && independent * seeds < 10000; ring++) {
                sum_measured += ring_measured[ring], sum_expected += ring_expected[ring];
                sum_square += ring_expected_square[ring], count += ring_count[ring];
                independent = sum_expected * sum_expected / (2 * sum_square);
            }
            if (independent * seeds < 10000 || sum_expected / count < 0.01 * peak)
                continue; // negligible band
            worst = std::max(worst, std::abs(sum_measured / sum_expected - 1));
            bins_checked++;
        }
        CAPTURE(c);
        CAPTURE(worst);
        CAPTURE(bins_checked);
        CHECK(bins_checked >= 3);
        CHECK(worst < 0.05);
    }
}

} // namespace

TEST_CASE("statistics: synthetic texton, mean / covariances / kurtosis at 30 and 5 impacts per pixel") {
    check_moments(synthetic_rgb(), 30, 1);
    check_moments(synthetic_rgb(), 5, 2);
}

TEST_CASE("statistics: baked-like texton, mean / covariances / kurtosis at 30 and 5 impacts per pixel") {
    check_moments(baked_like_fields(), 30, 3);
    check_moments(baked_like_fields(), 5, 4);
}

TEST_CASE("statistics: radially averaged power spectrum of periodic 512 x 512 blocks matches |T|^2") {
    check_spectrum(synthetic_rgb(), 30);
    check_spectrum(baked_like_fields(), 5);
}

TEST_CASE("different seeds give uncorrelated fields") {
    auto fields = synthetic_rgb();
    LoadedNoise first(fields, dsn_test::make_config(100)), second(fields, dsn_test::make_config(101));
    const int grid = 300;
    Samples a = draw_samples(first.noise, grid, 5000), b = draw_samples(second.noise, grid, 5000);
    const double n = double(grid) * grid;
    for (int c = 0; c < 3; c++)
        for (int d = 0; d < 3; d++) {
            const std::vector<double> &x = a.values[0][c], &y = b.values[0][d];
            double mx = 0, my = 0;
            for (size_t i = 0; i < x.size(); i++) mx += x[i], my += y[i];
            mx /= n, my /= n;
            double sxy = 0, sxx = 0, syy = 0;
            for (size_t i = 0; i < x.size(); i++)
                sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx),
                    syy += (y[i] - my) * (y[i] - my);
            double correlation = sxy / std::sqrt(sxx * syy);
            CAPTURE(c);
            CAPTURE(d);
            CHECK(std::abs(correlation) < 4 / std::sqrt(n));
        }
}
