// pyramid.cpp - the texton pyramid of format 1.1 (dsn/format.h): level l is the L2 projection of the
// bilinear texton convolved with a Gaussian of standard deviation 2^(l-1) texels onto the bilinear tents
// at spacing 2^l, quantized with one exponent per level.
//
// The projection solves the normal equations on the level's grid. The tents' Gram matrix is
// 4^l (M (x) M), M the tridiagonal [1/6 2/3 1/6]; the right side is <t0 * G, h_k>, which separates per
// axis into kappa(2^l k - j) with kappa = hat_1 * g_sigma * hat_(2^l): the texton's tent, the Gaussian and
// the level's tent. g_sigma * hat_(2^l) has a closed form (erf), so kappa is one short integral over the
// texton's tent, done by Simpson's rule.
#include "bake_internal.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dsn {
namespace {

constexpr int kSimpsonIntervals =
    64; // per half of the texton's tent: m is smooth, so this is exact to ~1e-12
constexpr double kPi = 3.14159265358979323846;

// Second antiderivative of the Gaussian density: integral of (s - z)_+ g_sigma(z) dz.
double gaussian_ramp(double s, double sigma) {
    const double density = std::exp(-s * s / (2 * sigma * sigma)) / (sigma * std::sqrt(2 * kPi));
    const double cumulative = 0.5 * std::erfc(-s / (sigma * std::sqrt(2.0)));
    return s * cumulative + sigma * sigma * density;
}

// (g_sigma * hat_spacing)(x): hat_w(y) = (1/w) [(y + w)_+ - 2 y_+ + (y - w)_+].
double gaussian_tent(double x, double sigma, double spacing) {
    return (gaussian_ramp(x + spacing, sigma) - 2 * gaussian_ramp(x, sigma) +
            gaussian_ramp(x - spacing, sigma)) /
           spacing;
}

// Solves M x = right (in place), M = tridiagonal [1/6 2/3 1/6] of size n, by the Thomas algorithm (M is
// strictly diagonally dominant: no pivoting needed).
void solve_tent_gram(std::vector<double> &right, size_t first, size_t stride, int n,
                     std::vector<double> &work) {
    const double off = 1.0 / 6, diagonal = 2.0 / 3;
    work.assign(size_t(n), 0);
    double denominator = diagonal;
    work[0] = off / denominator;
    right[first] /= denominator;
    for (int i = 1; i < n; i++) {
        denominator = diagonal - off * work[size_t(i - 1)];
        work[size_t(i)] = off / denominator;
        double &value = right[first + size_t(i) * stride];
        value = (value - off * right[first + size_t(i - 1) * stride]) / denominator;
    }
    for (int i = n - 2; i >= 0; i--)
        right[first + size_t(i) * stride] -= work[size_t(i)] * right[first + size_t(i + 1) * stride];
}

// The texton's values as the runtime reads them, q * scale / 2^40, channels interleaved.
std::vector<double> texton_values(const AssetFields &fields) {
    std::vector<double> values(fields.texton.size());
    for (size_t i = 0; i < values.size(); i++)
        values[i] = std::ldexp(double(fields.texton[i]) * double(fields.scale[i % fields.channels]), -40);
    return values;
}

} // namespace

int pyramid_level_count(int radius_x, int radius_y) {
    const int radius = std::max(radius_x, radius_y);
    int count = 0;
    while (count < int(DSN_PYRAMID_MAX_LEVELS) && (radius >> count) > 0) count++;
    return count; // floor(log2(radius)) + 1, 0 for radius 0
}

int pyramid_level_radius(int radius, int level) {
    // ceil((radius + 1 + 3 sigma) / 2^level) with sigma = 2^level / 2, in integers.
    const int spacing = 1 << level;
    return (2 * radius + 2 + 3 * spacing + 2 * spacing - 1) / (2 * spacing);
}

double pyramid_kappa(int level, double u) {
    const double spacing = std::ldexp(1.0, level), sigma = spacing / 2;
    // Simpson's rule on each half of the texton's tent [-1, 0] and [0, 1], where the tent is linear.
    const double h = 1.0 / kSimpsonIntervals;
    double sum = 0;
    for (int half = -1; half <= 0; half++)
        for (int i = 0; i <= kSimpsonIntervals; i++) {
            const double w = half + i * h;
            const double weight = (i == 0 || i == kSimpsonIntervals) ? 1 : (i % 2 ? 4 : 2);
            sum += weight * (1 - std::abs(w)) * gaussian_tent(u - w, sigma, spacing);
        }
    return sum * h / 3;
}

PrefilteredLevel prefiltered_level(const AssetFields &fields, int level) {
    if (level < 1 || level > int(DSN_PYRAMID_MAX_LEVELS))
        throw std::invalid_argument("pyramid level out of range");
    const int channels = int(fields.channels);
    const int radius_x = int(fields.width - 1) / 2, radius_y = int(fields.height - 1) / 2;
    const int spacing = 1 << level;
    PrefilteredLevel result;
    result.level = level;
    const int level_radius_x = pyramid_level_radius(radius_x, level);
    const int level_radius_y = pyramid_level_radius(radius_y, level);
    result.width = 2 * level_radius_x + 1;
    result.height = 2 * level_radius_y + 1;
    if (result.width > int(DSN_FORMAT_MAX_SIDE) || result.height > int(DSN_FORMAT_MAX_SIDE))
        throw std::invalid_argument("pyramid level wider than 255 values");

    // kappa at every integer offset a level node may have from a texel.
    const int extent = spacing * std::max(level_radius_x, level_radius_y) + std::max(radius_x, radius_y);
    std::vector<double> kappa(size_t(2 * extent + 1));
    for (int u = -extent; u <= extent; u++) kappa[size_t(u + extent)] = pyramid_kappa(level, u);
    const auto kappa_at = [&](int u) { return kappa[size_t(u + extent)]; };

    // Right side, separably: along x per texton row, then along y.
    const std::vector<double> texton = texton_values(fields);
    const int width = int(fields.width), height = int(fields.height);
    std::vector<double> along_x(size_t(height) * size_t(result.width) * size_t(channels), 0);
    for (int row = 0; row < height; row++)
        for (int k = 0; k < result.width; k++)
            for (int column = 0; column < width; column++) {
                const double weight = kappa_at(spacing * (k - level_radius_x) - (column - radius_x));
                for (int c = 0; c < channels; c++)
                    along_x[(size_t(row) * size_t(result.width) + size_t(k)) * size_t(channels) +
                            size_t(c)] +=
                        weight *
                        texton[(size_t(row) * size_t(width) + size_t(column)) * size_t(channels) + size_t(c)];
            }
    result.values.assign(size_t(result.height) * size_t(result.width) * size_t(channels), 0);
    for (int k = 0; k < result.height; k++)
        for (int row = 0; row < height; row++) {
            const double weight = kappa_at(spacing * (k - level_radius_y) - (row - radius_y));
            for (size_t i = 0; i < size_t(result.width) * size_t(channels); i++)
                result.values[size_t(k) * size_t(result.width) * size_t(channels) + i] +=
                    weight * along_x[size_t(row) * size_t(result.width) * size_t(channels) + i];
        }

    // (M (x) M) s = b / 4^l: along rows, then along columns, per channel.
    std::vector<double> work;
    const size_t row_stride = size_t(result.width) * size_t(channels);
    for (int c = 0; c < channels; c++) {
        for (int k = 0; k < result.height; k++)
            solve_tent_gram(result.values, size_t(k) * row_stride + size_t(c), size_t(channels), result.width,
                            work);
        for (int k = 0; k < result.width; k++)
            solve_tent_gram(result.values, size_t(k) * size_t(channels) + size_t(c), row_stride,
                            result.height, work);
    }
    const double area = std::ldexp(1.0, 2 * level);
    for (double &value : result.values) value /= area;
    return result;
}

PyramidLevel quantize_level(const PrefilteredLevel &level, const AssetFields &fields) {
    const double limit = fields.bits == 8 ? 127 : 32767;
    const uint32_t channels = fields.channels;
    // q = s 2^40 / (scale[c] 2^e): the smallest e that keeps every |q| within the range.
    double largest = 0; // max |s| 2^40 / scale[c]
    for (size_t i = 0; i < level.values.size(); i++)
        largest =
            std::max(largest, std::abs(std::ldexp(level.values[i], 40) / double(fields.scale[i % channels])));
    int exponent = DSN_PYRAMID_EXPONENT_MIN;
    while (exponent < DSN_PYRAMID_EXPONENT_MAX && largest > std::ldexp(limit, exponent)) exponent++;
    PyramidLevel quantized;
    quantized.width = uint32_t(level.width);
    quantized.height = uint32_t(level.height);
    quantized.exponent = exponent;
    quantized.values.resize(level.values.size());
    for (size_t i = 0; i < level.values.size(); i++) {
        const double q = std::ldexp(level.values[i], 40 - exponent) / double(fields.scale[i % channels]);
        quantized.values[i] = int32_t(std::clamp(std::round(q), -limit, limit));
    }
    return quantized;
}

std::vector<PyramidLevel> texton_pyramid(const AssetFields &fields) {
    std::vector<PyramidLevel> levels;
    const int count = pyramid_level_count(int(fields.width - 1) / 2, int(fields.height - 1) / 2);
    for (int level = 1; level <= count; level++)
        levels.push_back(quantize_level(prefiltered_level(fields, level), fields));
    return levels;
}

} // namespace dsn
