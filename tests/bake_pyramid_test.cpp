// bake_pyramid_test.cpp - the texton pyramid of format 1.1 (offline/pyramid.cpp) against an independent
// numerical reference: each level is the L2 projection of t0 * G_l onto the level's tents (its residual
// is orthogonal to every tent, it beats sampling; its relative error is reported), keeps the integral,
// loses < 1% of the energy to its window, turns a delta into a Gaussian; quantization, level sizes, the
// 6 KB bound and the bake step.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "fixtures/bake_fixtures.h"
#include "fixtures/test_assets.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

// a(x) = (hat_1 * g_sigma)(x) by the midpoint rule (fine: g is smooth and hat is linear on each half);
// computed here independently of pyramid.cpp's closed form.
double blurred_tent(double x, double sigma) {
    const int steps = 400;
    double sum = 0;
    for (int i = 0; i < steps; i++) {
        const double w = -1 + (i + 0.5) * 2.0 / steps;
        const double z = x - w;
        sum += (1 - std::abs(w)) * std::exp(-z * z / (2 * sigma * sigma));
    }
    return sum * (2.0 / steps) / (sigma * std::sqrt(2 * kPi));
}

// One channel of a texton and its level on a fine grid: the reference f = t0 * G_l and the level's
// continuous texton t_l, both sampled at step h over [-extent, extent]^2.
struct Sampled {
    int count = 0; // samples per axis
    double step = 0, extent = 0;
    std::vector<double> reference, level, sampled_level; // sampled_level: tents through f at the nodes
    double at(const std::vector<double> &image, int ix, int iy) const {
        return image[size_t(iy) * size_t(count) + size_t(ix)];
    }
    double position(int i) const { return -extent + i * step; }
};

double texton_value(const dsn::AssetFields &fields, int row, int column, int channel) {
    return std::ldexp(double(fields.texton[(size_t(row) * fields.width + size_t(column)) * fields.channels +
                                           size_t(channel)]) *
                          double(fields.scale[channel]),
                      -40);
}

double tent(double u) { return std::max(0.0, 1 - std::abs(u)); }

Sampled sample(const dsn::AssetFields &fields, const dsn::PrefilteredLevel &level, int channel, double step) {
    const int spacing = 1 << level.level, radius = int(fields.width - 1) / 2;
    const double sigma = spacing / 2.0;
    const int level_radius = (level.width - 1) / 2;
    Sampled s;
    s.step = step;
    s.extent = std::max(radius + 1 + 8 * sigma, double(spacing * (level_radius + 1)));
    s.extent = std::ceil(s.extent / spacing) * spacing;
    s.count = int(std::lround(2 * s.extent / step)) + 1;
    // f = sum_j t[j] a(x - jx) a(y - jy): along x per texton row, then along y.
    std::vector<double> a_x(size_t(fields.width) * size_t(s.count));
    for (int j = 0; j < int(fields.width); j++)
        for (int i = 0; i < s.count; i++)
            a_x[size_t(j) * size_t(s.count) + size_t(i)] = blurred_tent(s.position(i) - (j - radius), sigma);
    std::vector<double> rows(size_t(fields.height) * size_t(s.count), 0);
    for (int row = 0; row < int(fields.height); row++)
        for (int column = 0; column < int(fields.width); column++) {
            const double t = texton_value(fields, row, column, channel);
            if (t == 0) continue;
            for (int i = 0; i < s.count; i++)
                rows[size_t(row) * size_t(s.count) + size_t(i)] +=
                    t * a_x[size_t(column) * size_t(s.count) + size_t(i)];
        }
    s.reference.assign(size_t(s.count) * size_t(s.count), 0);
    for (int row = 0; row < int(fields.height); row++)
        for (int iy = 0; iy < s.count; iy++) {
            const double weight = a_x[size_t(row) * size_t(s.count) + size_t(iy)];
            for (int ix = 0; ix < s.count; ix++)
                s.reference[size_t(iy) * size_t(s.count) + size_t(ix)] +=
                    weight * rows[size_t(row) * size_t(s.count) + size_t(ix)];
        }
    // t_l(x) = sum s[i, j] hat(x / D - (i - r_l)) hat(y / D - (j - r_l)), and the same through f's values
    // at the nodes (interpolation instead of projection).
    const auto node_value = [&](int i, int j) {
        const double x = spacing * (i - level_radius), y = spacing * (j - level_radius);
        const int ix = int(std::lround((x + s.extent) / step)), iy = int(std::lround((y + s.extent) / step));
        return s.at(s.reference, ix, iy);
    };
    s.level.assign(s.reference.size(), 0);
    s.sampled_level.assign(s.reference.size(), 0);
    const int channels = int(fields.channels);
    for (int iy = 0; iy < s.count; iy++)
        for (int ix = 0; ix < s.count; ix++) {
            const double x = s.position(ix) / spacing + level_radius,
                         y = s.position(iy) / spacing + level_radius;
            const int i0 = int(std::floor(x)), j0 = int(std::floor(y));
            double value = 0, through_samples = 0;
            for (int j = j0; j <= j0 + 1; j++)
                for (int i = i0; i <= i0 + 1; i++) {
                    if (i < 0 || j < 0 || i >= level.width || j >= level.height) continue;
                    const double weight = tent(x - i) * tent(y - j);
                    value += weight *
                             level.values[(size_t(j) * size_t(level.width) + size_t(i)) * size_t(channels) +
                                          size_t(channel)];
                    through_samples += weight * node_value(i, j);
                }
            s.level[size_t(iy) * size_t(s.count) + size_t(ix)] = value;
            s.sampled_level[size_t(iy) * size_t(s.count) + size_t(ix)] = through_samples;
        }
    return s;
}

double relative_error(const std::vector<double> &approximation, const std::vector<double> &reference) {
    double error = 0, energy = 0;
    for (size_t i = 0; i < reference.size(); i++) {
        error += (approximation[i] - reference[i]) * (approximation[i] - reference[i]);
        energy += reference[i] * reference[i];
    }
    return std::sqrt(error / energy);
}

// A 31 x 31 grey texton with a non-zero sum: the test assets' bump-times-wave plus a positive bump.
dsn::AssetFields test_texton(uint32_t channels = 1, uint32_t side = 31) {
    dsn::AssetFields fields = dsn_test::synthetic_fields(channels, side, 8, DSN_SHAPE_RECTANGLE, 21);
    const int r = int(side - 1) / 2;
    for (int row = 0; row < int(side); row++)
        for (int column = 0; column < int(side); column++)
            for (uint32_t c = 0; c < channels; c++) {
                int32_t &value = fields.texton[(size_t(row) * side + size_t(column)) * channels + c];
                const double bump =
                    40 * std::exp(-double((row - r) * (row - r) + (column - r) * (column - r)) / 30);
                value = std::max(-127, std::min(127, value + int32_t(std::lround(bump))));
            }
    return fields;
}

} // namespace

TEST_CASE("pyramid level counts and sizes follow the format's rule") {
    CHECK(dsn::pyramid_level_count(0, 0) == 0);
    CHECK(dsn::pyramid_level_count(1, 0) == 1);
    CHECK(dsn::pyramid_level_count(15, 15) == 4);
    CHECK(dsn::pyramid_level_count(16, 3) == 5);
    CHECK(dsn::pyramid_level_count(127, 127) == 7);
    // ceil((r + 1 + 3 sigma_l) / 2^l): 31 x 31 gives sides 21, 13, 9, 7.
    const int sides[] = {21, 13, 9, 7};
    for (int l = 1; l <= 4; l++) CHECK(2 * dsn::pyramid_level_radius(15, l) + 1 == sides[l - 1]);
    for (int r = 0; r <= 127; r++)
        for (int l = 1; l <= 8; l++) {
            const int level_radius = dsn::pyramid_level_radius(r, l), spacing = 1 << l;
            const double wanted = (r + 1 + 1.5 * spacing) / spacing;
            CHECK(level_radius >= wanted);
            CHECK(level_radius < wanted + 1);
            CHECK(2 * level_radius + 1 <= int(DSN_FORMAT_MAX_SIDE));
        }
}

TEST_CASE(
    "kappa is the blurred texel tent against a level tent: symmetric, integral 2^l, matching quadrature") {
    for (int l = 1; l <= 8; l++) {
        const int spacing = 1 << l;
        double integral = 0;
        for (int u = -4 * spacing; u <= 4 * spacing; u++) integral += dsn::pyramid_kappa(l, u);
        CHECK(integral == doctest::Approx(spacing).epsilon(1e-9)); // sum over integers = integral (smooth)
        for (int u : {0, 1, spacing / 2, spacing, 3 * spacing}) {
            CHECK(dsn::pyramid_kappa(l, u) == doctest::Approx(dsn::pyramid_kappa(l, -u)).epsilon(1e-12));
            // kappa(u) = integral of (hat_1 * g)(x) hat_D(x - u): the midpoint rule over x.
            double reference = 0;
            const double dx = 1.0 / 16;
            for (double x = u - spacing + dx / 2; x < u + spacing; x += dx)
                reference += blurred_tent(x, spacing / 2.0) * (1 - std::abs(x - u) / spacing) * dx;
            CHECK(dsn::pyramid_kappa(l, u) == doctest::Approx(reference).epsilon(1e-4));
        }
    }
}

TEST_CASE("each level is the L2 projection of t0 * G_l: orthogonal residual, better than sampling, its error "
          "stated") {
    const dsn::AssetFields fields = test_texton();
    double texton_sum = 0, texton_magnitude = 0;
    for (int row = 0; row < 31; row++)
        for (int column = 0; column < 31; column++) {
            texton_sum += texton_value(fields, row, column, 0);
            texton_magnitude += std::abs(texton_value(fields, row, column, 0));
        }
    REQUIRE(std::abs(texton_sum) > 0.1 * texton_magnitude);
    for (int l = 1; l <= 4; l++) {
        CAPTURE(l);
        const dsn::PrefilteredLevel level = dsn::prefiltered_level(fields, l);
        const int spacing = 1 << l, level_radius = (level.width - 1) / 2;
        const double step = 0.125;
        const Sampled s = sample(fields, level, 0, step);
        const double area = step * step;

        // Orthogonality: <f - t_l, h_k> = 0 for every tent h_k of the level (the normal equations),
        // measured by quadrature, relative to the largest <f, h_k>. The quadrature's own error on these
        // smooth-times-tent integrands is O(step^2) relative.
        double largest = 0, worst = 0;
        for (int j = 0; j < level.height; j++)
            for (int i = 0; i < level.width; i++) {
                double with_reference = 0, with_residual = 0;
                const double cx = spacing * (i - level_radius), cy = spacing * (j - level_radius);
                const int x0 = int(std::lround((cx - spacing + s.extent) / step));
                const int y0 = int(std::lround((cy - spacing + s.extent) / step));
                for (int iy = std::max(0, y0); iy <= std::min(s.count - 1, y0 + 2 * spacing * 8); iy++)
                    for (int ix = std::max(0, x0); ix <= std::min(s.count - 1, x0 + 2 * spacing * 8); ix++) {
                        const double weight =
                            tent((s.position(ix) - cx) / spacing) * tent((s.position(iy) - cy) / spacing);
                        with_reference += weight * s.at(s.reference, ix, iy) * area;
                        with_residual += weight * (s.at(s.reference, ix, iy) - s.at(s.level, ix, iy)) * area;
                    }
                largest = std::max(largest, std::abs(with_reference));
                worst = std::max(worst, std::abs(with_residual));
            }
        CHECK(worst < 1e-3 * largest);

        // Optimality: no element of the span is closer (the orthogonality above), in particular not the
        // tents through f's samples at the nodes. The error itself is the price of the prefilter's form
        // (bilinear at spacing 2^l = 4 sigma_l) and depends on the texton's spectrum: this texton's wave
        // (0.7 radians per texel) sits near level 2's Nyquist frequency. Measured: 0.09, 0.27, 0.16, 0.11
        // for levels 1-4 (sampling: 0.17, 0.35, 0.19, 0.21).
        const double projection_error = relative_error(s.level, s.reference);
        const double sampling_error = relative_error(s.sampled_level, s.reference);
        MESSAGE("level " << l << ": relative L2 error " << projection_error
                         << " (tents through the samples: " << sampling_error << ")");
        CHECK(projection_error < sampling_error);

        // Truncation: the energy of t0 * G_l outside the level's nodes' window [-2^l r_l, 2^l r_l]^2.
        double outside = 0, total = 0;
        const double window = spacing * level_radius;
        for (int iy = 0; iy < s.count; iy++)
            for (int ix = 0; ix < s.count; ix++) {
                const double energy = s.at(s.reference, ix, iy) * s.at(s.reference, ix, iy);
                total += energy;
                if (std::abs(s.position(ix)) > window || std::abs(s.position(iy)) > window) outside += energy;
            }
        MESSAGE("level " << l << ": energy outside the window " << outside / total);
        CHECK(outside < 0.01 * total);

        // The integral: integral t_l = 4^l sum s_l ~ integral t0 * G_l = integral t0 = sum t.
        double level_sum = 0;
        for (double value : level.values) level_sum += value;
        MESSAGE("level " << l << ": 4^l sum s_l = " << std::ldexp(level_sum, 2 * l)
                         << ", sum t = " << texton_sum);
        CHECK(std::abs(std::ldexp(level_sum, 2 * l) - texton_sum) < 1e-3 * texton_magnitude);
    }
}

TEST_CASE("a delta texton gives Gaussian-like levels of variance sigma_l^2 + 1/6") {
    dsn::AssetFields fields = dsn_test::synthetic_fields(1, 15, 8, DSN_SHAPE_RECTANGLE, 1);
    std::fill(fields.texton.begin(), fields.texton.end(), 0);
    fields.texton[7 * 15 + 7] = 127;
    const double total = texton_value(fields, 7, 7, 0);
    for (int l = 1; l <= 3; l++) {
        CAPTURE(l);
        const dsn::PrefilteredLevel level = dsn::prefiltered_level(fields, l);
        const int r = (level.width - 1) / 2, spacing = 1 << l;
        const auto at = [&](int i, int j) {
            return level.values[size_t(j + r) * size_t(level.width) + size_t(i + r)];
        };
        double sum = 0, second_moment = 0, largest = 0;
        for (int j = -r; j <= r; j++)
            for (int i = -r; i <= r; i++) {
                // Symmetric under every reflection and the diagonal swap, separable, peaked at the centre.
                CHECK(at(i, j) == doctest::Approx(at(-i, j)).epsilon(1e-9).scale(total));
                CHECK(at(i, j) == doctest::Approx(at(j, i)).epsilon(1e-9).scale(total));
                CHECK(at(i, j) * at(0, 0) ==
                      doctest::Approx(at(i, 0) * at(0, j)).epsilon(1e-9).scale(total * total));
                CHECK(at(i, j) <= at(0, 0));
                sum += at(i, j);
                second_moment += at(i, j) * double(spacing * i) * double(spacing * i);
                largest = std::max(largest, std::abs(at(i, j)));
            }
        // Decreasing away from the centre while the values matter (the projection rings slightly at the
        // tails: at most a few percent of the peak).
        for (int i = 0; i < r; i++)
            if (at(i + 1, 0) > 0.05 * largest) CHECK(at(i + 1, 0) < at(i, 0));
        for (int i = 0; i <= r; i++) CHECK(at(i, 0) > -0.05 * largest);
        // The continuous level's variance per axis: the nodes' plus the level tent's own (2^l)^2 / 6.
        // t0 * G_l has sigma_l^2 + 1/6 (the texel tent's variance is 1/6). The projection keeps the
        // integral (to the truncation) but not the second moment exactly: the Gaussian is only 2 nodes wide
        // per standard deviation. Measured: 0.5%, 3% and 6% off for levels 1-3.
        const double variance = second_moment / sum + double(spacing * spacing) / 6;
        const double expected = double(spacing * spacing) / 4 + 1.0 / 6;
        MESSAGE("level " << l << ": variance " << variance << " for sigma_l^2 + 1/6 = " << expected);
        CHECK(variance == doctest::Approx(expected).epsilon(0.1));
        CHECK(std::ldexp(sum, 2 * l) == doctest::Approx(total).epsilon(1e-3));
    }
}

TEST_CASE("levels are quantized with the smallest exponent that fits, to half a step") {
    for (uint32_t bits : {8u, 16u}) {
        dsn::AssetFields fields = dsn_test::synthetic_fields(3, 15, bits, DSN_SHAPE_DISK, 4);
        const double limit = bits == 8 ? 127 : 32767;
        for (int l = 1; l <= 3; l++) {
            const dsn::PrefilteredLevel level = dsn::prefiltered_level(fields, l);
            const dsn::PyramidLevel quantized = dsn::quantize_level(level, fields);
            REQUIRE(quantized.values.size() == level.values.size());
            bool needs_exponent = false; // would exponent - 1 overflow the range?
            for (size_t i = 0; i < level.values.size(); i++) {
                const double unit = std::ldexp(double(fields.scale[i % 3]), quantized.exponent - 40);
                CHECK(std::abs(quantized.values[i]) <= limit);
                CHECK(std::abs(quantized.values[i] * unit - level.values[i]) <= 0.5 * unit * (1 + 1e-9));
                needs_exponent |= std::abs(level.values[i]) / (unit / 2) > limit;
            }
            CHECK((needs_exponent || quantized.exponent == DSN_PYRAMID_EXPONENT_MIN));
        }
    }
    // A zero texton: every exponent fits, the smallest is taken.
    dsn::AssetFields zero = dsn_test::synthetic_fields(1, 5, 8, DSN_SHAPE_RECTANGLE, 4);
    std::fill(zero.texton.begin(), zero.texton.end(), 0);
    const dsn::PyramidLevel level = dsn::quantize_level(dsn::prefiltered_level(zero, 1), zero);
    CHECK(level.exponent == DSN_PYRAMID_EXPONENT_MIN);
    for (int32_t value : level.values) CHECK(value == 0);
}

TEST_CASE("an RGB pyramid is the pyramid of each channel") {
    const dsn::AssetFields rgb = test_texton(3, 9);
    const std::vector<dsn::PyramidLevel> levels = dsn::texton_pyramid(rgb);
    REQUIRE(levels.size() == 3);
    for (uint32_t c = 0; c < 3; c++) {
        dsn::AssetFields grey = rgb;
        grey.channels = 1;
        grey.scale[0] = rgb.scale[c];
        grey.texton.clear();
        for (size_t i = c; i < rgb.texton.size(); i += 3) grey.texton.push_back(rgb.texton[i]);
        for (int l = 1; l <= 3; l++) {
            const dsn::PrefilteredLevel both = dsn::prefiltered_level(rgb, l),
                                        one = dsn::prefiltered_level(grey, l);
            for (size_t i = 0; i < one.values.size(); i++)
                CHECK(both.values[i * 3 + c] == doctest::Approx(one.values[i]).epsilon(1e-12));
        }
    }
}

TEST_CASE("a 31x31 RGB 8-bit asset with its pyramid fits in 6 KB and loads with 4 levels") {
    dsn::AssetFields fields = test_texton(3, 31);
    fields.pyramid = dsn::texton_pyramid(fields);
    const std::vector<unsigned char> bytes = dsn::encode_asset(fields);
    dsn::AssetFields plain = fields;
    plain.pyramid.clear();
    const size_t without = dsn::encode_asset(plain).size();
    MESSAGE("31x31 RGB 8-bit: " << bytes.size() << " bytes with the pyramid, " << without << " without");
    CHECK(without == 128 + 31 * 31 * 3 + 4);
    CHECK(bytes.size() <= 6 * 1024);
    dsn_asset asset;
    REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    CHECK(asset.pyramid_levels == 4);
    const uint32_t sides[] = {21, 13, 9, 7};
    for (uint32_t l = 1; l <= 4; l++) {
        dsn_level level;
        REQUIRE(dsn_asset_level(&asset, l, &level) == DSN_OK);
        CHECK(level.width == sides[l - 1]);
        CHECK(level.height == sides[l - 1]);
        CHECK(level.exponent == fields.pyramid[l - 1].exponent);
    }
}

TEST_CASE("the bake writes the pyramid by default; without it, the 1.0 file of the same bake") {
    const dsn::Image exemplar = bake_fixtures::random_phase_exemplar(40, 36, 3, 5);
    dsn::BakeOptions options;
    options.radius = 7;
    options.iterations = 20;
    options.periodic = false;
    options.interpolation = DSN_INTERPOLATION_LATTICE; // no lattice texton: the pyramid is the only section
    const dsn::BakeResult with = dsn::bake(exemplar, options);
    options.pyramid = false;
    const dsn::BakeResult without = dsn::bake(exemplar, options);
    REQUIRE(with.fields.pyramid.size() == 3);
    CHECK(without.fields.pyramid.empty());
    dsn_asset asset;
    REQUIRE(dsn_asset_load(&asset, with.asset.data(), with.asset.size()) == DSN_OK);
    CHECK(asset.version_minor == 1);
    CHECK(asset.pyramid_levels == 3);
    REQUIRE(dsn_asset_load(&asset, without.asset.data(), without.asset.size()) == DSN_OK);
    CHECK(asset.version_minor == 0);
    CHECK(asset.pyramid_levels == 0);
    // The pyramid is purely additive: the 1.1 file with its section removed (minor 0, header 128, total
    // size and CRC adjusted) is the --no-pyramid file, byte for byte.
    const uint32_t header_size = dsn_read_u32le(with.asset.data() + DSN_OFFSET_HEADER_SIZE);
    std::vector<unsigned char> stripped(with.asset.begin(), with.asset.begin() + DSN_FORMAT_HEADER_SIZE);
    stripped.insert(stripped.end(), with.asset.begin() + header_size, with.asset.end());
    dsn_write_u16le(&stripped[DSN_OFFSET_VERSION_MINOR], 0);
    dsn_write_u32le(&stripped[DSN_OFFSET_HEADER_SIZE], DSN_FORMAT_HEADER_SIZE);
    dsn_write_u32le(&stripped[DSN_OFFSET_TOTAL_SIZE], uint32_t(stripped.size()));
    dsn_write_u32le(&stripped[stripped.size() - 4], dsn_crc32(0, stripped.data(), stripped.size() - 4));
    CHECK(stripped == without.asset);
    // The pyramid is the one of the stored texton.
    const std::vector<dsn::PyramidLevel> again = dsn::texton_pyramid(without.fields);
    REQUIRE(again.size() == 3);
    for (size_t l = 0; l < 3; l++) {
        CHECK(again[l].exponent == with.fields.pyramid[l].exponent);
        CHECK(again[l].values == with.fields.pyramid[l].values);
    }
}
