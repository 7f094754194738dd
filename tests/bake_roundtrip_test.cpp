// bake_roundtrip_test.cpp - what the runtime loader reads from a baked asset is what was baked, and the
// bilinear bake corrects the interpolation's spectral loss.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include <stb_image.h>

#include "dsn/dsn.h"
#include "fixtures/bake_fixtures.h"
#include "offline/bake_internal.h"
#include "offline/label.h"

using namespace bake_fixtures;

TEST_CASE("the runtime loader reads back the baked texton to the quantization step, and every field") {
    for (int bits : {8, 16}) {
        CAPTURE(bits);
        dsn::BakeOptions options;
        options.radius = 9;
        options.shape = DSN_SHAPE_DISK;
        options.iterations = 40;
        options.bits = bits;
        options.seed = 1234;
        const dsn::Image exemplar = random_phase_exemplar(48, 44, 3, 71);
        const dsn::BakeResult result = dsn::bake(exemplar, options);
        dsn_asset asset;
        REQUIRE(dsn_asset_load(&asset, result.asset.data(), result.asset.size()) == DSN_OK);
        CHECK(asset.channels == 3);
        CHECK(asset.bits == uint32_t(bits));
        CHECK(asset.shape == DSN_SHAPE_DISK);
        CHECK(asset.width == 19);
        CHECK(asset.bake_seed == 1234);
        CHECK(asset.bake_iterations == 40);
        CHECK(asset.exemplar_width == 48);
        CHECK(asset.exemplar_height == 44);
        for (int c = 0; c < 3; c++) {
            CHECK(std::fabs(asset.mean[c] / 16777216.0 - result.model.mean[size_t(c)]) <= 0.5 / 16777216.0);
            for (int k = 0; k < 3; k++)
                CHECK(std::fabs(asset.color_transform[c * 3 + k] / 16777216.0 -
                                result.color_transform[size_t(c * 3 + k)]) <= 0.5 / 16777216.0);
        }
        for (uint32_t c = 0; c < 3; c++) {
            const double step = asset.scale[c] / 1099511627776.0;
            for (int dy = -9; dy <= 9; dy++)
                for (int dx = -9; dx <= 9; dx++) {
                    const double read =
                        dsn_asset_texton_value(&asset, uint32_t(dy + 9), uint32_t(dx + 9), c) * step;
                    CHECK(read == result.quantized_texton.at(dx, dy, int(c)));
                    CHECK(std::fabs(read - result.sot.texton.at(dx, dy, int(c))) <= step / 2 * (1 + 1e-9));
                }
        }
    }
}

TEST_CASE("bilinear bake: the texton's spectrum times the B-spline factor is closer to the model") {
    // A sharp texture (white noise plus a little of its right neighbour): much energy at high frequencies,
    // where bilinear interpolation loses most.
    const dsn::Image noise = dsn::white_noise(64, 64, 81);
    dsn::Image exemplar = noise;
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++)
            exemplar.at(x, y, 0) = 0.5 + 0.05 * (noise.at(x, y, 0) + 0.5 * noise.at((x + 1) % 64, y, 0));
    dsn::BakeOptions options;
    options.iterations = 200;
    options.periodic = false;
    options.interpolation = DSN_INTERPOLATION_LATTICE;
    const dsn::BakeResult lattice = dsn::bake(exemplar, options);
    options.interpolation = DSN_INTERPOLATION_BILINEAR;
    const dsn::BakeResult bilinear = dsn::bake(exemplar, options);
    // What the continuous noise sampled on the lattice has: |T|^2 b, i.e. the modulus times sqrt(b).
    auto sampled = [](const dsn::Texton &texton) {
        dsn::Spectrum spectrum = dsn::texton_spectrum(texton, 64, 64);
        for (int xi2 = 0; xi2 < 64; xi2++)
            for (int xi1 = 0; xi1 < 64; xi1++) {
                const double b = (2.0 / 3 + std::cos(2 * M_PI * xi1 / 64) / 3) *
                                 (2.0 / 3 + std::cos(2 * M_PI * xi2 / 64) / 3);
                spectrum.values[size_t(xi2) * 64 + size_t(xi1)] *= float(std::sqrt(b));
            }
        return spectrum;
    };
    // Relative model errors over every frequency (the paper's, like BakeResult's rme).
    const double corrected = dsn::relative_model_error(bilinear.model.spectrum, sampled(bilinear.sot.texton));
    const double uncorrected = dsn::relative_model_error(lattice.model.spectrum, sampled(lattice.sot.texton));
    MESSAGE("RME of the bilinear-sampled noise: corrected texton " << corrected << ", lattice texton "
                                                                   << uncorrected);
    CHECK(corrected < uncorrected);
    // The corrected texton reaches the model about as well as the lattice texton reaches it without
    // interpolation.
    CHECK(corrected < lattice.rme + 0.05);
}

TEST_CASE("preview_png: four labelled exemplar-sized panels, the first one the exemplar itself, and the "
          "verdict below") {
    const dsn::Image noise = dsn::white_noise(61, 64, 5);
    dsn::Image exemplar = noise;
    for (double &value : exemplar.values)
        value = std::round(std::clamp(0.5 + 0.15 * value, 0.0, 1.0) * 255) / 255;
    dsn::BakeOptions options;
    options.iterations = 20;
    const dsn::BakeResult result = dsn::bake(exemplar, options);
    const std::vector<unsigned char> png = dsn::preview_png(exemplar, result, 3);
    int width = 0, height = 0, channels = 0;
    unsigned char *pixels = stbi_load_from_memory(png.data(), int(png.size()), &width, &height, &channels, 3);
    REQUIRE(pixels != nullptr);
    // The layout of preview.cpp at this size: labels one 12-pixel line high (scale 1), a 4-pixel gap, the
    // panels in columns as wide as the panel or the label (plus a gap), 4 pixels apart, then the verdict.
    const char *const labels[4] = {"exemplar", "Gaussian reference", "texton (SOT)", "runtime synthesis"};
    int columns[4], expected_width = 3 * 4;
    for (int i = 0; i < 4; i++) {
        columns[i] = std::max(61, dsn::label_width(labels[i], 1) + 4);
        expected_width += columns[i];
    }
    const int top = 12 + 4, exemplar_left = (columns[0] - 61) / 2;
    const int synthesis_left = columns[0] + columns[1] + columns[2] + 3 * 4 + (columns[3] - 61) / 2;
    CHECK(width == expected_width);
    REQUIRE(height > top + 64 + 4);
    auto pixel = [&](int x, int y) { return pixels[(size_t(y) * size_t(width) + size_t(x)) * 3]; };
    int mismatches = 0;
    double sum = 0, square_sum = 0;
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 61; x++) {
            for (int c = 0; c < 3; c++)
                mismatches +=
                    pixels[(size_t(top + y) * size_t(width) + size_t(exemplar_left + x)) * 3 + size_t(c)] !=
                    (unsigned char)std::lround(exemplar.at(x, y, 0) * 255);
            const double synthesized = pixel(synthesis_left + x, top + y);
            sum += synthesized, square_sum += synthesized * synthesized;
        }
    // Text (light grey on the dark background) in the label row and under the panels.
    int label_pixels = 0, verdict_pixels = 0;
    for (int x = 0; x < width; x++) {
        for (int y = 0; y < 12; y++) label_pixels += pixel(x, y) == 225;
        for (int y = top + 64 + 4; y < height; y++) verdict_pixels += pixel(x, y) == 225;
    }
    stbi_image_free(pixels);
    CHECK(mismatches == 0);
    CHECK(label_pixels > 100);
    CHECK(verdict_pixels > 100);
    CHECK(!result.verdict.summary.empty());
    const double mean = sum / (61 * 64), variance = square_sum / (61 * 64) - mean * mean;
    CHECK(variance > 1); // the runtime synthesis is a texture, not a flat panel
}
