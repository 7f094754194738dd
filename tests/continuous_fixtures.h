// continuous_fixtures.h - what the continuous-mode tests share: assets built from fixed integers, a
// configured noise that keeps its asset bytes alive, and the bilinear-spot theory (cubic B-spline).
#ifndef DSN_TESTS_CONTINUOUS_FIXTURES_H
#define DSN_TESTS_CONTINUOUS_FIXTURES_H

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "dsn/asset_writer.h"
#include "dsn/dsn.h"

namespace continuous_fixtures {

// A noise and the bytes its asset view points into.
struct Noise {
    std::vector<unsigned char> bytes;
    dsn_asset asset;
    dsn_noise noise;
};

inline std::unique_ptr<Noise> make_noise(const dsn::AssetFields &fields, uint32_t seed,
                                         uint32_t impacts_q16 = 0, uint32_t period_x = 0,
                                         uint32_t period_y = 0, uint32_t flags = 0) {
    auto made = std::make_unique<Noise>();
    made->bytes = dsn::encode_asset(fields);
    if (dsn_asset_load(&made->asset, made->bytes.data(), made->bytes.size()) != DSN_OK)
        throw std::runtime_error("test asset does not load");
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = seed;
    config.impacts_q16 = impacts_q16;
    config.period_x = period_x;
    config.period_y = period_y;
    config.flags = flags;
    if (dsn_noise_init(&made->noise, &made->asset, &config) != DSN_OK)
        throw std::runtime_error("test noise does not initialize");
    return made;
}

// A random texton (fixed mt19937 seed, raw outputs only, so identical everywhere) under a tent envelope,
// bilinear, with a non-trivial colour transform.
inline dsn::AssetFields random_texton_asset(uint32_t channels, uint32_t radius, uint32_t bits,
                                            uint32_t seed) {
    dsn::AssetFields fields;
    fields.channels = channels;
    fields.bits = bits;
    fields.interpolation = DSN_INTERPOLATION_BILINEAR;
    fields.width = fields.height = 2 * radius + 1;
    dsn::set_identity_color_transform(fields);
    const int32_t peak = bits == 8 ? 127 : 32767, r = int32_t(radius);
    std::mt19937 random(seed);
    for (int32_t dy = -r; dy <= r; dy++)
        for (int32_t dx = -r; dx <= r; dx++)
            for (uint32_t c = 0; c < channels; c++) {
                const int64_t envelope = int64_t(r + 1 - std::abs(dx)) * (r + 1 - std::abs(dy));
                const int64_t raw = int64_t(random() % uint32_t(2 * peak + 1)) - peak;
                fields.texton.push_back(int32_t(raw * envelope / ((r + 1) * (r + 1))));
            }
    const int32_t means[3] = {1 << 23, 1 << 22, -(1 << 21)}; // 0.5, 0.25, -0.125
    const int32_t transform[9] = {1 << 24, 1 << 22, 0, -(1 << 21), 1 << 24, 1 << 23, 0, 1 << 22, 3 << 22};
    for (uint32_t c = 0; c < channels; c++) {
        fields.mean[c] = means[c];
        fields.scale[c] = (bits == 8 ? 1u << 31 : 1u << 24) + 977u * c; // values of a few hundredths
    }
    if (channels == 3)
        for (int i = 0; i < 9; i++) fields.color_transform[i] = transform[i];
    return fields;
}

// The texton of `fields` in value units: t[c][row][column].
inline std::vector<std::vector<double>> texton_values(const dsn::AssetFields &fields) {
    std::vector<std::vector<double>> t(fields.channels, std::vector<double>(fields.width * fields.height));
    for (uint32_t i = 0; i < fields.width * fields.height; i++)
        for (uint32_t c = 0; c < fields.channels; c++)
            t[c][i] = fields.texton[i * fields.channels + c] * std::ldexp(double(fields.scale[c]), -40);
    return t;
}

// The autocorrelation of the tent (the bilinear kernel): the cubic B-spline.
inline double cubic_bspline(double s) {
    s = std::fabs(s);
    if (s < 1) return 2.0 / 3.0 - s * s + s * s * s / 2;
    if (s < 2) return (2 - s) * (2 - s) * (2 - s) / 6;
    return 0;
}

// Integral over the plane of u(y) v(y + h) for the bilinear interpolants of two textons (side x side,
// values row-major): sum_a sum_b u[a] v[b] B(b - a - h), B the separable cubic B-spline.
inline double bilinear_correlation(const std::vector<double> &u, const std::vector<double> &v, int side,
                                   double hx, double hy) {
    double sum = 0;
    for (int ay = 0; ay < side; ay++)
        for (int ax = 0; ax < side; ax++) {
            const double ua = u[size_t(ay * side + ax)];
            if (ua == 0) continue;
            for (int by = 0; by < side; by++) {
                const double wy = cubic_bspline(by - ay - hy);
                if (wy == 0) continue;
                for (int bx = 0; bx < side; bx++)
                    sum += ua * v[size_t(by * side + bx)] * wy * cubic_bspline(bx - ax - hx);
            }
        }
    return sum;
}

} // namespace continuous_fixtures

#endif // DSN_TESTS_CONTINUOUS_FIXTURES_H
