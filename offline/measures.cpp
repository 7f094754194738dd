// measures.cpp - relative model error (OT distance between Gaussian models, over every frequency as
// Galerne, Leclaire and Moisan define it, or without the zero frequency), that of what renders, the DSN
// moments by Campbell's theorem and the shape signal (total variation against a random-phase copy's).
#include "bake_internal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace dsn {

namespace {

// sqrt(sum (|T_u|^2 + |T|^2 - 2 |sum_c conj(T_u,c) T_c|) / sum |T_u|^2) over the frequencies from `first`
// (0: every frequency; 1: all but xi = 0, the first value of each plane).
double model_error_from(const Spectrum &model, const Spectrum &texton, size_t first) {
    if (model.width != texton.width || model.height != texton.height || model.channels != texton.channels)
        throw std::invalid_argument("relative_model_error: spectra of different shapes");
    const size_t plane = model.plane_size();
    double model_energy = 0, texton_energy = 0, cross = 0;
    for (size_t i = first; i < plane; i++) {
        std::complex<double> inner = 0;
        for (int c = 0; c < model.channels; c++) {
            const std::complex<double> u = model.values[size_t(c) * plane + i];
            const std::complex<double> t = texton.values[size_t(c) * plane + i];
            model_energy += std::norm(u);
            texton_energy += std::norm(t);
            inner += std::conj(u) * t;
        }
        cross += std::abs(inner);
    }
    if (!(model_energy > 0)) return 0;
    return std::sqrt(std::max(0.0, model_energy + texton_energy - 2 * cross) / model_energy);
}

} // namespace

double relative_model_error(const Spectrum &model, const Spectrum &texton) {
    return model_error_from(model, texton, 0);
}

double relative_model_error_without_zero_frequency(const Spectrum &model, const Spectrum &texton) {
    return model_error_from(model, texton, 1);
}

double relative_model_error(const Spectrum &model, const Texton &texton) {
    return relative_model_error(model, texton_spectrum(texton, model.width, model.height));
}

double relative_model_error_without_zero_frequency(const Spectrum &model, const Texton &texton) {
    return relative_model_error_without_zero_frequency(model,
                                                       texton_spectrum(texton, model.width, model.height));
}

std::vector<double> excess_kurtosis(const Texton &texton, double impacts_per_pixel) {
    if (!(impacts_per_pixel > 0)) throw std::invalid_argument("impacts per pixel must be positive");
    const double lambda = impacts_per_pixel / texton.support.size();
    const size_t plane = texton.support.mask.size();
    std::vector<double> kurtosis(size_t(texton.channels), 0.0);
    for (int c = 0; c < texton.channels; c++) {
        double square_sum = 0, fourth_sum = 0;
        for (size_t i = 0; i < plane; i++) {
            const double square = texton.values[size_t(c) * plane + i] * texton.values[size_t(c) * plane + i];
            square_sum += square;
            fourth_sum += square * square;
        }
        if (square_sum > 0) kurtosis[size_t(c)] = fourth_sum / (lambda * square_sum * square_sum);
    }
    return kurtosis;
}

double effective_model_error(const Spectrum &model, const Texton &texton, const Matrix3 &color_transform,
                             uint32_t interpolation) {
    Spectrum rendered = texton_spectrum(texton, model.width, model.height);
    const Spectrum read = rendered;
    const size_t plane = rendered.plane_size();
    const int channels = rendered.channels;
    const double two_pi = 6.283185307179586;
    for (int xi2 = 0; xi2 < rendered.height; xi2++)
        for (int xi1 = 0; xi1 < rendered.width; xi1++) {
            const size_t i = size_t(xi2) * size_t(rendered.width) + size_t(xi1);
            double spline = 1;
            if (interpolation == DSN_INTERPOLATION_BILINEAR)
                spline = (2.0 / 3 + std::cos(two_pi * xi1 / rendered.width) / 3) *
                         (2.0 / 3 + std::cos(two_pi * xi2 / rendered.height) / 3);
            const double amplitude = std::sqrt(spline);
            for (int c = 0; c < channels; c++) {
                std::complex<double> sum = 0;
                for (int k = 0; k < channels; k++)
                    sum += color_transform[size_t(c * 3 + k)] *
                           std::complex<double>(read.values[size_t(k) * plane + i]);
                rendered.values[size_t(c) * plane + i] = std::complex<float>(amplitude * sum);
            }
        }
    return relative_model_error(model, rendered);
}

NoiseMoments noise_moments(const Texton &texton, const Matrix3 &color_transform, uint32_t interpolation,
                           double impacts_per_pixel) {
    if (!(impacts_per_pixel > 0)) throw std::invalid_argument("impacts per pixel must be positive");
    const double lambda = impacts_per_pixel / texton.support.size();
    const int r = texton.support.radius, channels = texton.channels;
    // The spot channel c sees at texel (dx, dy), zero outside the window.
    auto spot = [&](int c, int dx, int dy) {
        if (dx < -r || dx > r || dy < -r || dy > r) return 0.0;
        double sum = 0;
        for (int k = 0; k < channels; k++) sum += color_transform[size_t(c * 3 + k)] * texton.at(dx, dy, k);
        return sum;
    };
    // Three-point Gauss-Legendre on [0, 1] per axis: exact for the bilinear interpolant's fourth power
    // (degree 4 in each variable).
    const double offset = std::sqrt(0.6) / 2;
    const std::array<double, 3> nodes = {0.5 - offset, 0.5, 0.5 + offset};
    const std::array<double, 3> weights = {5.0 / 18, 8.0 / 18, 5.0 / 18};
    NoiseMoments moments;
    for (int c = 0; c < channels; c++) {
        double i2 = 0, i3 = 0, i4 = 0;
        auto add = [&](double value, double weight) {
            const double square = value * value;
            i2 += weight * square, i3 += weight * square * value, i4 += weight * square * square;
        };
        if (interpolation == DSN_INTERPOLATION_BILINEAR) {
            for (int y = -r - 1; y <= r; y++)
                for (int x = -r - 1; x <= r; x++) {
                    const double v00 = spot(c, x, y), v10 = spot(c, x + 1, y), v01 = spot(c, x, y + 1),
                                 v11 = spot(c, x + 1, y + 1);
                    if (v00 == 0 && v10 == 0 && v01 == 0 && v11 == 0) continue;
                    for (int j = 0; j < 3; j++)
                        for (int i = 0; i < 3; i++) {
                            const double fx = nodes[size_t(i)], fy = nodes[size_t(j)];
                            add((1 - fy) * ((1 - fx) * v00 + fx * v10) + fy * ((1 - fx) * v01 + fx * v11),
                                weights[size_t(i)] * weights[size_t(j)]);
                        }
                }
        } else {
            for (int y = -r; y <= r; y++)
                for (int x = -r; x <= r; x++) add(spot(c, x, y), 1);
        }
        const bool varies = i2 > 0;
        moments.skewness.push_back(varies ? i3 / (std::sqrt(lambda) * i2 * std::sqrt(i2)) : 0);
        moments.excess_kurtosis.push_back(varies ? i4 / (lambda * i2 * i2) : 0);
    }
    return moments;
}

ShapeSignal shape_signal(const Image &image, int channel) {
    const int width = image.width, height = image.height;
    const size_t plane = size_t(width) * size_t(height);
    Image one;
    one.width = width, one.height = height, one.channels = 1;
    one.values.assign(image.values.begin() + std::ptrdiff_t(size_t(channel) * plane),
                      image.values.begin() + std::ptrdiff_t(size_t(channel + 1) * plane));
    double mean = 0;
    for (double value : one.values) mean += value;
    mean /= double(plane);
    for (double &value : one.values) value -= mean;
    // Coordinates within one period of the torus (-width..2 width - 1): wrapped without a division.
    auto at = [&](const Image &field, int x, int y) {
        x = x < 0 ? x + width : (x >= width ? x - width : x);
        y = y < 0 ? y + height : (y >= height ? y - height : y);
        return field.values[size_t(y) * size_t(width) + size_t(x)];
    };
    double absolute[2] = {0, 0};
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            absolute[0] += std::fabs(at(one, x + 1, y) - at(one, x, y));
            absolute[1] += std::fabs(at(one, x, y + 1) - at(one, x, y));
        }
    // The autocorrelation G(z) = sum_p u(p) u(p + z) (even in z), and from it the covariances of the
    // differences d_x, d_y at every lag.
    Spectrum power = forward_dft(one);
    for (std::complex<float> &value : power.values) value = std::norm(value);
    const Image g = inverse_dft(power);
    auto gamma = [&](int x, int y) { return at(g, x, y); };
    auto cxx = [&](int x, int y) { return 2 * gamma(x, y) - gamma(x + 1, y) - gamma(x - 1, y); };
    auto cyy = [&](int x, int y) { return 2 * gamma(x, y) - gamma(x, y + 1) - gamma(x, y - 1); };
    auto cxy = [&](int x, int y) {
        return gamma(x - 1, y + 1) - gamma(x - 1, y) - gamma(x, y + 1) + gamma(x, y);
    };
    const double vx = std::max(0.0, cxx(0, 0)), vy = std::max(0.0, cyy(0, 0));
    const double sx = std::sqrt(vx / double(plane)), sy = std::sqrt(vy / double(plane));
    ShapeSignal signal;
    if (!(sx + sy > 0)) return signal;
    const double gaussian_mean = 0.7978845608028654; // sqrt(2 / pi)
    signal.ratio = (absolute[0] + absolute[1]) / (gaussian_mean * double(plane) * (sx + sy));
    const double wx = sx / (sx + sy), wy = sy / (sx + sy);
    auto h = [](double c) {
        c = std::clamp(c, -1.0, 1.0);
        return c * std::asin(c) + std::sqrt(1 - c * c) - 1 - c * c / 2;
    };
    double variance = 0;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            if (vx > 0) variance += wx * wx * h(cxx(x, y) / vx);
            if (vy > 0) variance += wy * wy * h(cyy(x, y) / vy);
            if (vx > 0 && vy > 0) variance += 2 * wx * wy * h(cxy(x, y) / std::sqrt(vx * vy));
        }
    signal.error = std::sqrt(std::max(0.0, variance) / double(plane));
    return signal;
}

} // namespace dsn
