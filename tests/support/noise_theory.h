// tests/support/noise_theory.h - what the DSN output should be, from a loaded asset and its
// configuration: mean, covariance K (t * t~) K^T at any lag, excess kurtosis and the power spectrum on a
// P x P torus. With g_c = sum_k K_ck t_k (t_k = q_k scale_k / 2^40):
//   E out_c = mean_c,  Cov(out_c(x), out_d(x + h)) = sum_u g_c(u) g_d(u + h),
//   excess kurtosis of out_c = sum g_c^4 / (lambda (sum g_c^2)^2)   (compound Poisson cumulants),
//   E |DFT_P(out_c - mean_c)|^2 (xi) = P^2 |DFT_P(g_c)(xi)|^2       (exactly, in periodic mode).
#ifndef DSN_TEST_NOISE_THEORY_H
#define DSN_TEST_NOISE_THEORY_H

#include <cmath>
#include <complex>
#include <vector>

#include "dsn/dsn.h"

namespace dsn_test {

struct NoiseTheory {
    int channels = 0, width = 0, height = 0;
    double lambda = 0;
    double mean[3] = {0, 0, 0};
    std::vector<double> spot[3]; // g_c, row-major over the texton window

    explicit NoiseTheory(const dsn_noise &noise) {
        const dsn_asset &asset = noise.asset;
        channels = int(asset.channels);
        width = int(asset.width);
        height = int(asset.height);
        lambda = double(noise.impacts_q16) / 65536.0 / double(asset.support_size);
        for (int c = 0; c < channels; c++) {
            mean[c] = double(asset.mean[c]) / double(DSN_Q24_ONE);
            spot[c].assign(size_t(width) * height, 0.0);
        }
        for (int c = 0; c < channels; c++)
            for (int k = 0; k < channels; k++) {
                double K = (noise.flags & DSN_FLAG_NO_COLOR_TRANSFORM)
                               ? (c == k ? 1.0 : 0.0)
                               : asset.color_transform[c * 3 + k] / double(DSN_Q24_ONE);
                double scale = double(asset.scale[k]) / std::ldexp(1.0, 40);
                for (int row = 0; row < height; row++)
                    for (int column = 0; column < width; column++)
                        spot[c][size_t(row) * width + column] +=
                            K * scale *
                            dsn_asset_texton_value(&asset, uint32_t(row), uint32_t(column), uint32_t(k));
            }
    }

    double at(int c, int column, int row) const {
        if (column < 0 || row < 0 || column >= width || row >= height) return 0.0;
        return spot[c][size_t(row) * width + column];
    }

    // Cov(out_c(x), out_d(x + (hx, hy))).
    double covariance(int c, int d, int hx, int hy) const {
        double sum = 0;
        for (int row = 0; row < height; row++)
            for (int column = 0; column < width; column++)
                sum += at(c, column, row) * at(d, column + hx, row + hy);
        return sum;
    }

    double excess_kurtosis(int c) const {
        double second = 0, fourth = 0;
        for (double g : spot[c]) second += g * g, fourth += g * g * g * g;
        return fourth / (lambda * second * second);
    }

    // |DFT_P(g_c)(xi)|^2 on the period x period torus (the spot wraps around the origin).
    std::vector<double> spectrum(int c, int period) const {
        std::vector<std::complex<double>> rows(size_t(period) * height);
        const double tau = 2 * std::acos(-1.0);
        const int rx = (width - 1) / 2, ry = (height - 1) / 2;
        for (int row = 0; row < height; row++)
            for (int xi = 0; xi < period; xi++) {
                std::complex<double> sum = 0;
                for (int column = 0; column < width; column++)
                    sum += at(c, column, row) * std::polar(1.0, -tau * double(xi) * (column - rx) / period);
                rows[size_t(row) * period + xi] = sum;
            }
        std::vector<double> power(size_t(period) * period);
        for (int eta = 0; eta < period; eta++)
            for (int xi = 0; xi < period; xi++) {
                std::complex<double> sum = 0;
                for (int row = 0; row < height; row++)
                    sum += rows[size_t(row) * period + xi] *
                           std::polar(1.0, -tau * double(eta) * (row - ry) / period);
                power[size_t(eta) * period + xi] = std::norm(sum);
            }
        return power;
    }
};

// Sample excess kurtosis and its standard error by the delta method: the influence function of
// m4 / m2^2 - 3 (mean estimated too) is IF = (d^4 - m4 - 4 m3 d) / m2^2 - 2 m4 (d^2 - m2) / m2^3, and
// the estimator's variance is Var(IF) / n.
inline void kurtosis_with_error(const std::vector<double> &x, double *kurtosis, double *standard_error) {
    const double n = double(x.size());
    double mean = 0;
    for (double v : x) mean += v;
    mean /= n;
    double m2 = 0, m3 = 0, m4 = 0;
    for (double v : x) {
        double d = v - mean;
        m2 += d * d, m3 += d * d * d, m4 += d * d * d * d;
    }
    m2 /= n, m3 /= n, m4 /= n;
    double if_mean = 0, if_square = 0;
    for (double v : x) {
        double d = v - mean;
        double influence =
            (d * d * d * d - m4 - 4 * m3 * d) / (m2 * m2) - 2 * m4 * (d * d - m2) / (m2 * m2 * m2);
        if_mean += influence, if_square += influence * influence;
    }
    if_mean /= n;
    *kurtosis = m4 / (m2 * m2) - 3;
    *standard_error = std::sqrt((if_square / n - if_mean * if_mean) / n);
}

// Sample mean and its standard error.
inline void mean_with_error(const std::vector<double> &x, double *mean, double *standard_error) {
    const double n = double(x.size());
    double sum = 0, square = 0;
    for (double v : x) sum += v;
    *mean = sum / n;
    for (double v : x) square += (v - *mean) * (v - *mean);
    *standard_error = std::sqrt(square / (n - 1) / n);
}

} // namespace dsn_test

#endif
