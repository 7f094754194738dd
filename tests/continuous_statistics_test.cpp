// continuous_statistics_test.cpp - the continuous noise against its theory, at 30 and 5 impacts per pixel.
//
// Theory. With impulses of a Poisson process of intensity lambda on the plane and the bilinear texton
// t~_k(y) = sum_a t_k[a] L(y - a) (L the 2-D tent), the output out_c = m_c + sum_k K_ck (F_k - E F_k) /
// sqrt(lambda) has mean m_c and covariance
//     Cov(out_c(x), out_d(x + h)) = sum_kl K_ck K_dl integral t~_k(y) t~_l(y + h) dy
//                                 = sum_kl K_ck K_dl sum_a sum_b t_k[a] t_l[b] B(b - a - h),
// B the separable cubic B-spline (the tent's autocorrelation), for any real lag h. Channel c is a shot
// noise with the single spot u_c = sum_k K_ck t~_k, so its excess kurtosis is
//     integral u_c^4 / (lambda (integral u_c^2)^2),
// the quartic integral computed exactly by 3-point Gauss-Legendre per unit square (u_c^4 has degree 4
// per axis there).
// Samples: sites 24 texels apart (farther than the spot's reach 2r + 2 plus the largest lag) at random
// real positions, so sites are independent. Mean and kurtosis are estimated from all samples pooled, with
// standard errors from the sample (the kurtosis' by the delta method); covariances from 20 batches.
// Tolerances are 4 standard errors.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "fixtures/continuous_fixtures.h"
#include "fixtures/noise_theory.h"

using namespace continuous_fixtures;

namespace {

const int kRadius = 5, kSide = 2 * kRadius + 1;
const double kLags[][2] = {{0, 0}, {1, 0}, {0, 1}, {3, 2}, {0.5, 0.25}};
const int kLagCount = 5, kBatches = 20;

// The bilinear spot of a texton (side x side values) at a real offset (x, y).
double bilinear_at(const std::vector<double> &t, double x, double y) {
    const double fx = std::floor(x), fy = std::floor(y);
    double sum = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            const int column = int(fx) + i + kRadius, row = int(fy) + j + kRadius;
            if (column < 0 || column >= kSide || row < 0 || row >= kSide) continue;
            sum +=
                t[size_t(row * kSide + column)] * (1 - std::fabs(x - fx - i)) * (1 - std::fabs(y - fy - j));
        }
    return sum;
}

double quartic_integral(const std::vector<double> &u) {
    const double nodes[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
    const double weights[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
    double sum = 0;
    for (int cy = -kRadius - 1; cy <= kRadius; cy++)
        for (int cx = -kRadius - 1; cx <= kRadius; cx++)
            for (int j = 0; j < 3; j++)
                for (int i = 0; i < 3; i++) {
                    const double value = bilinear_at(u, cx + nodes[i], cy + nodes[j]);
                    sum += weights[i] * weights[j] * value * value * value * value;
                }
    return sum;
}

struct Theory {
    std::array<double, 3> mean{};
    double covariance[kLagCount][3][3] = {};
    std::array<double, 3> kurtosis{};
};

Theory theory(const dsn::AssetFields &fields, double lambda) {
    Theory result;
    const auto t = texton_values(fields);
    const uint32_t channels = fields.channels;
    auto transform = [&](uint32_t c, uint32_t k) { return fields.color_transform[c * 3 + k] / 16777216.0; };
    for (uint32_t c = 0; c < channels; c++) result.mean[size_t(c)] = fields.mean[c] / 16777216.0;
    for (int h = 0; h < kLagCount; h++)
        for (uint32_t k = 0; k < channels; k++)
            for (uint32_t l = 0; l < channels; l++) {
                const double a = bilinear_correlation(t[k], t[l], kSide, kLags[h][0], kLags[h][1]);
                for (uint32_t c = 0; c < channels; c++)
                    for (uint32_t d = 0; d < channels; d++)
                        result.covariance[h][c][d] += transform(c, k) * transform(d, l) * a;
            }
    for (uint32_t c = 0; c < channels; c++) {
        std::vector<double> u(t[0].size(), 0.0);
        for (uint32_t k = 0; k < channels; k++)
            for (size_t i = 0; i < u.size(); i++) u[i] += transform(c, k) * t[k][i];
        const double square = bilinear_correlation(u, u, kSide, 0, 0);
        result.kurtosis[c] = quartic_integral(u) / (lambda * square * square);
    }
    return result;
}

// Per batch: means, lagged covariances and excess kurtosis; then mean and standard error over batches.
struct Estimate {
    double value = 0, standard_error = 0;
};

Estimate batch_estimate(const std::vector<double> &per_batch) {
    double mean = 0, square = 0;
    for (double v : per_batch) mean += v;
    mean /= double(per_batch.size());
    for (double v : per_batch) square += (v - mean) * (v - mean);
    return {mean, std::sqrt(square / double(per_batch.size() - 1) / double(per_batch.size()))};
}

void check_against_theory(const dsn::AssetFields &fields, uint32_t impacts, int sites_per_batch) {
    auto noise = make_noise(fields, 1000 + impacts, impacts << 16);
    const uint32_t channels = fields.channels;
    const Theory expected = theory(fields, double(impacts) / double(kSide * kSide));
    std::vector<double> samples[3], covariances[kLagCount][3][3];
    std::mt19937_64 random(impacts);
    const int64_t one = int64_t(1) << 32;
    for (int batch = 0; batch < kBatches; batch++) {
        std::vector<std::array<double, 3>> values[kLagCount];
        for (int s = 0; s < sites_per_batch; s++) {
            const int64_t site = int64_t(batch) * sites_per_batch + s;
            const int64_t x = (site % 2000) * 24 * one + int64_t(random() >> 32);
            const int64_t y = (site / 2000) * 24 * one + int64_t(random() >> 32);
            for (int h = 0; h < kLagCount; h++) {
                int32_t out[3];
                dsn_continuous_point_fixed(&noise->noise, x + int64_t(kLags[h][0] * double(one)),
                                           y + int64_t(kLags[h][1] * double(one)), out);
                std::array<double, 3> v{};
                for (uint32_t c = 0; c < channels; c++) v[c] = out[c] / 65536.0;
                values[h].push_back(v);
            }
        }
        const double n = sites_per_batch;
        for (uint32_t c = 0; c < channels; c++)
            for (const auto &v : values[0]) samples[c].push_back(v[c]);
        for (int h = 0; h < kLagCount; h++)
            for (uint32_t c = 0; c < channels; c++)
                for (uint32_t d = 0; d < channels; d++) {
                    double sum = 0, mean_c = 0, mean_d = 0;
                    for (int s = 0; s < sites_per_batch; s++) {
                        mean_c += values[0][size_t(s)][c];
                        mean_d += values[h][size_t(s)][d];
                    }
                    mean_c /= n, mean_d /= n;
                    for (int s = 0; s < sites_per_batch; s++)
                        sum += (values[0][size_t(s)][c] - mean_c) * (values[h][size_t(s)][d] - mean_d);
                    covariances[h][c][d].push_back(sum / (n - 1));
                }
    }
    for (uint32_t c = 0; c < channels; c++) {
        double mean, mean_error, kurtosis, kurtosis_error;
        dsn_test::mean_with_error(samples[c], &mean, &mean_error);
        dsn_test::kurtosis_with_error(samples[c], &kurtosis, &kurtosis_error);
        CAPTURE(impacts);
        CAPTURE(c);
        CHECK(std::fabs(mean - expected.mean[c]) <= 4 * mean_error);
        CHECK(std::fabs(kurtosis - expected.kurtosis[c]) <= 4 * kurtosis_error);
        MESSAGE("impacts " << impacts << " channel " << c << ": excess kurtosis " << kurtosis << " +- "
                           << kurtosis_error << " (theory " << expected.kurtosis[c] << ")");
    }
    for (int h = 0; h < kLagCount; h++)
        for (uint32_t c = 0; c < channels; c++)
            for (uint32_t d = 0; d < channels; d++) {
                const Estimate covariance = batch_estimate(covariances[h][c][d]);
                CAPTURE(impacts);
                CAPTURE(h);
                CAPTURE(c);
                CAPTURE(d);
                CAPTURE(covariance.value);
                CAPTURE(expected.covariance[h][c][d]);
                CHECK(std::fabs(covariance.value - expected.covariance[h][c][d]) <=
                      4 * covariance.standard_error);
                // The standard errors are small: the check above is within 3% of the channel variances.
                CHECK(4 * covariance.standard_error <=
                      0.03 * std::sqrt(expected.covariance[0][c][c] * expected.covariance[0][d][d]));
            }
}

} // namespace

TEST_CASE("continuous statistics: mean, covariance at real lags and kurtosis match the bilinear theory") {
    // RGB with a non-trivial colour transform, 8 bits; and grey 16 bits. 20 batches of sites each.
    const dsn::AssetFields rgb = random_texton_asset(3, kRadius, 8, 42);
    const dsn::AssetFields grey = random_texton_asset(1, kRadius, 16, 43);
    // At 5 impacts the marginal is further from Gaussian (excess kurtosis ~2), so the covariance estimates
    // vary more (Var s^2 ~ (2 + kurtosis) sigma^4 / n): twice the samples keep their error within 3%.
    check_against_theory(rgb, 30, 5000);
    check_against_theory(rgb, 5, 10000);
    check_against_theory(grey, 30, 5000);
    check_against_theory(grey, 5, 10000);
}
