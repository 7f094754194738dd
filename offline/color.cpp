// color.cpp - colour covariances, symmetric 3x3 eigen-decomposition and K = B^(1/2) A^(-1/2).
#include "bake_internal.h"

#include <algorithm>
#include <cmath>

namespace dsn {
namespace {

// The cubic B-spline sampled at -1, 0, 1: the autocorrelation of the bilinear hat.
double spline_weight(int offset) { return offset == 0 ? 2.0 / 3 : 1.0 / 6; }

Matrix3 multiply(const Matrix3 &a, const Matrix3 &b) {
    Matrix3 product{};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                product[size_t(i * 3 + j)] += a[size_t(i * 3 + k)] * b[size_t(k * 3 + j)];
    return product;
}

// V diag(f(values)) V^T.
template <typename Function>
Matrix3 spectral_function(const std::array<double, 3> &values, const Matrix3 &vectors, Function function) {
    Matrix3 result{};
    for (int k = 0; k < 3; k++) {
        const double scaled = function(values[size_t(k)]);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                result[size_t(i * 3 + j)] += vectors[size_t(i * 3 + k)] * scaled * vectors[size_t(j * 3 + k)];
    }
    return result;
}

} // namespace

Matrix3 texton_covariance(const Texton &texton, uint32_t interpolation) {
    Matrix3 covariance{};
    const int r = texton.support.radius;
    const int reach = interpolation == DSN_INTERPOLATION_BILINEAR ? 1 : 0;
    for (int k = 0; k < texton.channels; k++)
        for (int l = 0; l < texton.channels; l++) {
            double sum = 0;
            for (int oy = -reach; oy <= reach; oy++)
                for (int ox = -reach; ox <= reach; ox++) {
                    const double weight = reach ? spline_weight(ox) * spline_weight(oy) : 1.0;
                    double lagged = 0;
                    for (int dy = std::max(-r, -r - oy); dy <= std::min(r, r - oy); dy++)
                        for (int dx = std::max(-r, -r - ox); dx <= std::min(r, r - ox); dx++)
                            lagged += texton.at(dx, dy, k) * texton.at(dx + ox, dy + oy, l);
                    sum += weight * lagged;
                }
            covariance[size_t(k * 3 + l)] = sum;
        }
    return covariance;
}

Matrix3 model_covariance(const GaussianModel &model) {
    Matrix3 covariance{};
    const size_t plane = size_t(model.width) * size_t(model.height);
    for (int k = 0; k < model.channels; k++)
        for (int l = 0; l < model.channels; l++) {
            double sum = 0;
            for (size_t i = 0; i < plane; i++)
                sum += model.t_u.values[size_t(k) * plane + i] * model.t_u.values[size_t(l) * plane + i];
            covariance[size_t(k * 3 + l)] = sum;
        }
    return covariance;
}

void symmetric_eigen(const Matrix3 &matrix, std::array<double, 3> &values, Matrix3 &vectors) {
    Matrix3 a = matrix;
    vectors = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int sweep = 0; sweep < 50; sweep++) {
        const double off = a[1] * a[1] + a[2] * a[2] + a[5] * a[5];
        if (off == 0) break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                const double apq = a[size_t(p * 3 + q)];
                if (apq == 0) continue;
                // Rotation that zeroes a[p][q] (Golub & Van Loan, symmetric Schur).
                const double theta = (a[size_t(q * 3 + q)] - a[size_t(p * 3 + p)]) / (2 * apq);
                const double t =
                    (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
                const double c = 1 / std::sqrt(t * t + 1), s = t * c;
                for (int k = 0; k < 3; k++) { // a = a J
                    const double akp = a[size_t(k * 3 + p)], akq = a[size_t(k * 3 + q)];
                    a[size_t(k * 3 + p)] = c * akp - s * akq;
                    a[size_t(k * 3 + q)] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) { // a = J^T a
                    const double apk = a[size_t(p * 3 + k)], aqk = a[size_t(q * 3 + k)];
                    a[size_t(p * 3 + k)] = c * apk - s * aqk;
                    a[size_t(q * 3 + k)] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; k++) { // V = V J
                    const double vkp = vectors[size_t(k * 3 + p)], vkq = vectors[size_t(k * 3 + q)];
                    vectors[size_t(k * 3 + p)] = c * vkp - s * vkq;
                    vectors[size_t(k * 3 + q)] = s * vkp + c * vkq;
                }
            }
    }
    values = {a[0], a[4], a[8]};
}

Matrix3 color_transform(const Matrix3 &a, const Matrix3 &b, int channels) {
    const Matrix3 identity = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    if (channels != 3) { // the same K on 1 x 1 matrices: the gain sqrt(b / a)
        const double gain = a[0] > 0 && std::isfinite(a[0]) ? std::sqrt(std::max(b[0], 0.0) / a[0]) : 1.0;
        return {std::isfinite(gain) ? std::min(gain, kColorTransformLimit) : 1.0, 0, 0, 0, 0, 0, 0, 0, 0};
    }
    std::array<double, 3> a_values, b_values;
    Matrix3 a_vectors, b_vectors;
    symmetric_eigen(a, a_values, a_vectors);
    symmetric_eigen(b, b_values, b_vectors);
    const double a_largest = std::max({a_values[0], a_values[1], a_values[2]});
    if (!(a_largest > 0) || !std::isfinite(a_largest)) return identity;
    const double floor = kColorEigenFloor * a_largest;
    const Matrix3 a_inverse_root = spectral_function(
        a_values, a_vectors, [floor](double value) { return 1 / std::sqrt(std::max(value, floor)); });
    const Matrix3 b_root =
        spectral_function(b_values, b_vectors, [](double value) { return std::sqrt(std::max(value, 0.0)); });
    Matrix3 transform = multiply(b_root, a_inverse_root);
    for (double &entry : transform) {
        if (!std::isfinite(entry)) return identity;
        entry = std::clamp(entry, -kColorTransformLimit, kColorTransformLimit);
    }
    return transform;
}

} // namespace dsn
