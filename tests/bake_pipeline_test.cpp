// bake_pipeline_test.cpp - bake(): input checks, quantization effect, asset size and fields, reproducibility
// (the real-texture case is skipped when the texture folder is absent).
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

#include "dsn/bake.h"
#include "fixtures/bake_fixtures.h"
#include "runtime/setup/format_bytes.h"

using namespace bake_fixtures;

namespace {

std::string bake_error(const dsn::Image &exemplar, const dsn::BakeOptions &options) {
    try {
        dsn::check_bake_input(exemplar, options);
    } catch (const std::exception &error) {
        return error.what();
    }
    return "";
}

dsn::Image blank(int width, int height) {
    dsn::Image image;
    image.width = width, image.height = height, image.channels = 1;
    image.values.assign(size_t(width) * size_t(height), 0.5);
    return image;
}

} // namespace

TEST_CASE("bake refuses options out of range and exemplars smaller than S - S, naming a radius that fits") {
    dsn::BakeOptions options;
    CHECK(bake_error(blank(61, 61), options) == "");
    CHECK(bake_error(blank(61, 60), options) ==
          "image 61x60 is too small for radius 15 (both sides must be at least 61); radius 14 would fit");
    CHECK(bake_error(blank(4, 100), options).find("no radius fits") != std::string::npos);
    for (int radius : {0, -3, 128}) {
        options.radius = radius;
        CHECK(bake_error(blank(600, 600), options).find("out of range") != std::string::npos);
    }
    options = dsn::BakeOptions();
    options.bits = 12;
    CHECK(bake_error(blank(61, 61), options).find("bits") != std::string::npos);
    options = dsn::BakeOptions();
    options.iterations = 0;
    CHECK(bake_error(blank(61, 61), options).find("iterations") != std::string::npos);
    options = dsn::BakeOptions();
    CHECK_THROWS_WITH(dsn::bake(blank(61, 61), options), doctest::Contains("constant image"));
}

namespace {

// Bakes an exemplar at r = 15 (8 bits, 100 iterations) and checks the asset: quantization moves the RME by
// no more than the rounding allows (and by < 0.001 when `small_change`), size and recorded fields.
void check_quantized_bake(const std::string &name, const dsn::Image &exemplar, bool periodic,
                          bool small_change) {
    CAPTURE(name);
    dsn::BakeOptions options;
    options.iterations = 100;
    options.periodic = periodic;
    const dsn::BakeResult result = dsn::bake(exemplar, options);
    MESSAGE(name << ": RME " << result.rme << ", quantized " << result.rme_quantized << ", "
                 << result.asset.size() << " bytes");
    // The RME (every frequency, the paper's; so is rme_quantized) is a distance: rounding the texton moves
    // it by at most ||Q - T|| / ||T_u|| (Minkowski over the frequencies, Parseval for ||Q - T||). On the
    // known compact spot the SOT is nearly exact (RME ~0.015) and that rounding
    // (~1% of the texton) shows in full; on textures whose texton spreads over the support it is far below
    // the 0.001 asked.
    double rounding = 0, model_energy = 0;
    for (size_t i = 0; i < result.sot.texton.values.size(); i++) {
        const double difference = result.quantized_texton.values[i] - result.sot.texton.values[i];
        rounding += difference * difference;
    }
    for (const auto &value : result.target.values) model_energy += std::norm(std::complex<double>(value));
    const double bound = std::sqrt(rounding * result.target.plane_size() / model_energy);
    CHECK(std::fabs(result.rme_quantized - result.rme) <= bound * (1 + 1e-9));
    if (small_change) CHECK(std::fabs(result.rme_quantized - result.rme) < 0.001);
    // rme (every frequency) is rme_without_zero_frequency (the per-iteration figure) plus the zero
    // frequency's |T(0)|^2 = (sum of the texton)^2 per channel.
    CHECK(result.rme_without_zero_frequency ==
          doctest::Approx(result.sot.rme_per_iteration.back()).epsilon(1e-5));
    const size_t points = result.sot.texton.support.mask.size();
    double zero_frequency = 0;
    for (int c = 0; c < exemplar.channels; c++) {
        double sum = 0;
        for (size_t i = 0; i < points; i++) sum += result.sot.texton.values[size_t(c) * points + i];
        zero_frequency += sum * sum;
    }
    CHECK(result.rme * result.rme ==
          doctest::Approx(result.rme_without_zero_frequency * result.rme_without_zero_frequency +
                          zero_frequency / model_energy)
              .epsilon(1e-6));
    dsn::AssetFields plain = result.fields; // the 1.0 asset (dsn-bake --no-pyramid --interpolation lattice)
    plain.pyramid.clear();
    plain.lattice_texton.clear();
    CHECK(dsn::encode_asset(plain).size() == 128 + 31 * 31 * size_t(exemplar.channels) + 4);
    CHECK(dsn::encode_asset(plain).size() <= 3200);
    CHECK(result.fields.pyramid.size() == 4);
    // The default (bilinear) bake adds its lattice texton, 33 x 33, in a section of its own.
    const size_t lattice_bytes = 8 + 4 + 33 * 33 * size_t(exemplar.channels);
    CHECK(result.fields.lattice_texton.size() == 33 * 33 * size_t(exemplar.channels));
    CHECK(result.asset.size() <= 6 * 1024 + lattice_bytes + 3);
    CHECK(result.fields.bake_iterations == 100);
    CHECK(result.fields.exemplar_width == uint32_t(exemplar.width));
    CHECK(result.fields.bake_rme_q24 == uint32_t(std::lround(result.rme_quantized * (1 << 24))));
    for (int c = 0; c < exemplar.channels; c++)
        CHECK(result.fields.mean[c] == int32_t(std::lround(result.model.mean[size_t(c)] * (1 << 24))));
}

} // namespace

TEST_CASE(
    "bake: 8-bit quantization changes the RME by < 0.001 on a generated spread-out texture, a 31x31 RGB "
    "asset is <= 3.2 KB, <= 6 KB with its pyramid") {
    check_quantized_bake("known compact spot", random_phase_exemplar(64, 64, 3, 41), false, false);
    check_quantized_bake("spread-out spot", random_phase_texture(random_spot(80, 72, 3, 15, 23), 24), false,
                         true);
}

TEST_CASE("bake: 8-bit quantization changes the RME by < 0.001 on real textures" *
          doctest::skip(!textures_available())) {
    for (const char *name : {"stone_granite1", "wood_walnut"}) {
        std::vector<std::string> warnings;
        check_quantized_bake(name, dsn::load_exemplar(textures_folder() + "/" + name + ".png", &warnings),
                             true, true);
    }
}

TEST_CASE("bake is reproducible: same input, options and seed give a byte-identical asset") {
    const dsn::Image exemplar = random_phase_exemplar(48, 48, 3, 51);
    dsn::BakeOptions options;
    options.radius = 10;
    options.iterations = 60;
    options.seed = 77;
    options.shape = DSN_SHAPE_DISK;
    const std::vector<unsigned char> first = dsn::bake(exemplar, options).asset;
    CHECK(dsn::bake(exemplar, options).asset == first);
    options.seed = 78;
    CHECK(dsn::bake(exemplar, options).asset != first);
}

TEST_CASE("bake records its options: bits, shape, interpolation, identity transform on request") {
    const dsn::Image exemplar = random_phase_exemplar(48, 48, 3, 61);
    dsn::BakeOptions options;
    options.radius = 8;
    options.iterations = 30;
    options.bits = 16;
    options.interpolation = DSN_INTERPOLATION_BILINEAR;
    options.use_color_transform = false;
    const dsn::BakeResult result = dsn::bake(exemplar, options);
    CHECK(result.asset.size() == dsn_read_u32le(&result.asset[DSN_OFFSET_HEADER_SIZE]) + 17 * 17 * 3 * 2 +
                                     4); // texton after the pyramid
    CHECK(result.asset[DSN_OFFSET_BITS] == 16);
    CHECK(result.asset[DSN_OFFSET_INTERPOLATION] == DSN_INTERPOLATION_BILINEAR);
    CHECK(result.asset[DSN_OFFSET_SHAPE] == DSN_SHAPE_RECTANGLE);
    for (int i = 0; i < 9; i++)
        CHECK(dsn_read_i32le(&result.asset[DSN_OFFSET_COLOR_TRANSFORM + 4u * unsigned(i)]) ==
              (i % 4 == 0 ? DSN_Q24_ONE : 0));
    // The bilinear target carries more high-frequency energy than the model: its texton does too.
    options.interpolation = DSN_INTERPOLATION_LATTICE;
    const dsn::BakeResult lattice = dsn::bake(exemplar, options);
    double bilinear_energy = 0, lattice_energy = 0;
    for (double value : result.sot.texton.values) bilinear_energy += value * value;
    for (double value : lattice.sot.texton.values) lattice_energy += value * value;
    CHECK(bilinear_energy > lattice_energy);
}
