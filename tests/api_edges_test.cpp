// api_edges_test.cpp - the runtime API at its edges: null pointers, a noise whose init failed,
// densities out of range, periods 1 and 2^31, NaN / Inf / huge continuous coordinates. Each must give the
// documented error or a defined value (and, under `make sanitize`, no undefined behaviour); on every
// error every evaluator's output is zeroed, exactly as far as the caller said it holds.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <string>

#include "dsn/dsn.h"
#include "fixtures/test_assets.h"
#include "offline/bake_internal.h"

using dsn_test::LoadedNoise;
using dsn_test::make_config;
using dsn_test::synthetic_fields;

TEST_CASE("per-point functions with a null noise zero out[0] alone, and take a null output") {
    LoadedNoise loaded(synthetic_fields(3, 9, 8, DSN_SHAPE_DISK, 1), make_config(5));
    int32_t fixed[3] = {7, 7, 7};
    float real[3] = {7, 7, 7};
    uint8_t bytes[3] = {7, 7, 7};
    dsn_lattice_point_fixed(nullptr, 0, 0, fixed);
    dsn_lattice_point_float(nullptr, 0, 0, real);
    dsn_lattice_point_u8(nullptr, 0, 0, bytes);
    dsn_lattice_point_fixed(&loaded.noise, 0, 0, nullptr);
    dsn_lattice_point_float(&loaded.noise, 0, 0, nullptr);
    dsn_lattice_point_u8(&loaded.noise, 0, 0, nullptr);
    CHECK(fixed[0] == 0);
    CHECK(fixed[1] == 7); // the channel count of a null noise is unknown: only out[0] is known to exist
    CHECK(real[0] == 0.0f);
    CHECK(real[2] == 7.0f);
    CHECK(bytes[0] == 0);
    CHECK(bytes[1] == 7);
    CHECK(dsn_asset_texton_value(nullptr, 0, 0, 0) == 0);
    CHECK(dsn_asset_texton_value(&loaded.asset, 9, 0, 0) == 0);
    CHECK(dsn_asset_texton_value(&loaded.asset, 0, 0, 3) == 0);
    CHECK(dsn_asset_load(nullptr, loaded.bytes.data(), loaded.bytes.size()) == DSN_ERR_NULL);
    CHECK(dsn_asset_load(&loaded.asset, nullptr, 1000) == DSN_ERR_NULL);
}

TEST_CASE("a noise whose init failed evaluates to 0 and refuses tiles") {
    LoadedNoise loaded(synthetic_fields(1, 7, 16, DSN_SHAPE_RECTANGLE, 2), make_config(5));
    dsn_noise failed;
    dsn_config config = make_config(5);
    config.impacts_q16 = uint32_t(-5); // a "negative" density
    REQUIRE(dsn_noise_init(&failed, &loaded.asset, &config) == DSN_ERR_IMPACTS);
    int32_t value = 1234;
    dsn_lattice_point_fixed(&failed, 3, 4, &value);
    CHECK(value == 0);
    int32_t tile[4];
    CHECK(dsn_lattice_tile_fixed(&failed, 0, 0, 2, 2, tile, nullptr, 0) == DSN_ERR_ARGUMENT);
    CHECK(dsn_lattice_tile_scratch_size(&failed, 2, 2) == 0);
    for (uint32_t impacts : {1u, DSN_IMPACTS_MIN_Q16 - 1, DSN_IMPACTS_MAX_Q16 + 1, 0xFFFFFFFFu}) {
        config.impacts_q16 = impacts;
        CHECK(dsn_noise_init(&failed, &loaded.asset, &config) == DSN_ERR_IMPACTS);
    }
}

TEST_CASE("periods 1 and 2^31 are exact: constant rows, and INT32_MIN is 0") {
    const dsn::AssetFields fields = synthetic_fields(3, 11, 8, DSN_SHAPE_DISK, 3);
    LoadedNoise one(fields, make_config(9, 30, 1, 0));
    LoadedNoise half(fields, make_config(9, 30, 0x80000000u, 0x80000000u));
    int32_t a[3], b[3];
    for (int32_t y : {-5, 0, 17, INT32_MAX}) {
        dsn_lattice_point_fixed(&one.noise, INT32_MIN, y, a);
        for (int32_t x : {-1, 0, 1, 12345, INT32_MAX}) {
            dsn_lattice_point_fixed(&one.noise, x, y, b);
            CHECK(std::memcmp(a, b, sizeof a) == 0);
        }
        dsn_lattice_point_fixed(&half.noise, INT32_MIN, y, a);
        dsn_lattice_point_fixed(&half.noise, 0, y, b);
        CHECK(std::memcmp(a, b, sizeof a) == 0);
        dsn_lattice_point_fixed(&half.noise, 5, INT32_MIN, a);
        dsn_lattice_point_fixed(&half.noise, 5, 0, b);
        CHECK(std::memcmp(a, b, sizeof a) == 0);
    }
}

TEST_CASE("continuous coordinates: NaN and Inf are 0, huge values wrap, and the value is defined") {
    dsn::AssetFields fields = synthetic_fields(3, 9, 8, DSN_SHAPE_DISK, 4);
    fields.interpolation = DSN_INTERPOLATION_BILINEAR;
    LoadedNoise loaded(fields, make_config(11));
    const double nan = std::numeric_limits<double>::quiet_NaN(),
                 inf = std::numeric_limits<double>::infinity();
    for (double special : {nan, inf, -inf}) {
        CHECK(dsn_coordinate_from_double(special) == 0);
        CHECK(dsn_coordinate_from_float(float(special)) == 0);
    }
    float at_nan[3], at_zero[3];
    REQUIRE(dsn_continuous_point_float(&loaded.noise, nan, -inf, at_nan) == DSN_OK);
    REQUIRE(dsn_continuous_point_float(&loaded.noise, 0.0, 0.0, at_zero) == DSN_OK);
    CHECK(std::memcmp(at_nan, at_zero, sizeof at_nan) == 0);
    // 2^32 + 0.5 texels is 0.5 texels on the torus; 1e300 is some defined point.
    float wrapped[3], half[3], huge[3];
    REQUIRE(dsn_continuous_point_float(&loaded.noise, 4294967296.5, 3.25, wrapped) == DSN_OK);
    REQUIRE(dsn_continuous_point_float(&loaded.noise, 0.5, 3.25, half) == DSN_OK);
    CHECK(std::memcmp(wrapped, half, sizeof half) == 0);
    REQUIRE(dsn_continuous_point_float(&loaded.noise, 1e300, -1e300, huge) == DSN_OK);
    for (float value : huge) CHECK(std::isfinite(value));
    int32_t out[3] = {1, 1, 1};
    CHECK(dsn_continuous_point_fixed(nullptr, 0, 0, out) == DSN_ERR_NULL);
    CHECK(dsn_continuous_point_fixed(&loaded.noise, 0, 0, nullptr) == DSN_ERR_NULL);
}

TEST_CASE("every error code has its own message; -19 and codes outside the table are unknown") {
    const std::string unknown = dsn_error_message(1);
    CHECK(unknown == "unknown error code");
    CHECK(dsn_error_message(DSN_ERR_LOWEST - 1) == unknown);
    CHECK(dsn_error_message(-19) == unknown); // retired: no error has it
    CHECK(std::string(dsn_error_message(DSN_OK)) == "success");
    std::set<std::string> messages;
    int named = 0;
#define DSN_TEST_ERROR_ENTRY(name, value, message)                                                           \
    CHECK(int(name) == value);                                                                               \
    CHECK(std::string(dsn_error_message(name)) == message);                                                  \
    messages.insert(message);                                                                                \
    named++;
    DSN_LIST_ERRORS(DSN_TEST_ERROR_ENTRY)
#undef DSN_TEST_ERROR_ENTRY
    CHECK(messages.size() == size_t(named));
    CHECK(messages.count(unknown) == 0);
    // The table names every code from 0 down to DSN_ERR_LOWEST but the retired -19.
    int known = 0;
    for (int code = 0; code >= DSN_ERR_LOWEST; code--) known += dsn_error_message(code) != unknown;
    CHECK(known == named);
    CHECK(named == -DSN_ERR_LOWEST);
}

namespace {

// An output array of `size` values plus a few more, all set to a sentinel first: after an erring call,
// zeroed_exactly(n) says that the first n values are 0 and every other value is still the sentinel (the
// call wrote no further than the caller said its output holds).
template <typename Value>
struct Guarded {
    static constexpr size_t spare = 5;
    static Value sentinel() { return Value(90); }
    std::vector<Value> values;
    explicit Guarded(size_t size) : values(size + spare, sentinel()) {}
    Value *data() { return values.data(); }
    bool zeroed_exactly(size_t zeroed) const {
        for (size_t i = 0; i < values.size(); i++)
            if (values[i] != (i < zeroed ? Value(0) : sentinel())) return false;
        return true;
    }
};

// The noises an evaluator must refuse, and one it must accept: each with the values per point it zeroes.
struct Refusals {
    LoadedNoise bilinear, lattice; // lattice: configured without DSN_FLAG_ALLOW_LATTICE_CONTINUOUS
    dsn_noise failed;
    Refusals() : bilinear(bilinear_fields(), make_config(3)), lattice(lattice_fields(), make_config(3)) {
        dsn_config config = make_config(3);
        config.impacts_q16 = 1; // out of range: init fails and zeroes the noise
        REQUIRE(dsn_noise_init(&failed, &bilinear.asset, &config) == DSN_ERR_IMPACTS);
    }
    static dsn::AssetFields lattice_fields() { return synthetic_fields(3, 31, 8, DSN_SHAPE_DISK, 21); }
    static dsn::AssetFields bilinear_fields() {
        dsn::AssetFields fields = lattice_fields();
        fields.interpolation = DSN_INTERPOLATION_BILINEAR;
        fields.pyramid = dsn::texton_pyramid(fields); // so that minified filtered tiles splat
        return fields;
    }
    // (noise, values per point zeroed, the error every continuous evaluator returns for it)
    struct Case {
        const char *name;
        const dsn_noise *noise;
        size_t channels;
        int error;
    };
    std::vector<Case> continuous_cases() const {
        return {{"null noise", nullptr, 1, DSN_ERR_NULL},
                {"failed init", &failed, 1, DSN_ERR_NULL},
                {"lattice asset", &lattice.noise, 3, DSN_ERR_CONTINUOUS_MISMATCH}};
    }
};

dsn_grid unit_grid(double step) {
    dsn_grid grid{};
    grid.origin_x = grid.origin_y = 5 * DSN_COORDINATE_ONE;
    grid.column_step_x = grid.row_step_y = int64_t(step * double(DSN_COORDINATE_ONE));
    return grid;
}

} // namespace

TEST_CASE("every lattice evaluator zeroes its output on every error, and no further") {
    Refusals refusals;
    const uint32_t width = 4, height = 3;
    for (const dsn_noise *noise :
         {static_cast<const dsn_noise *>(nullptr), static_cast<const dsn_noise *>(&refusals.failed)}) {
        CAPTURE(noise == nullptr);
        Guarded<int32_t> fixed(1);
        Guarded<float> real(1);
        Guarded<uint8_t> bytes(1);
        dsn_lattice_point_fixed(noise, 1, 2, fixed.data());
        dsn_lattice_point_float(noise, 1, 2, real.data());
        dsn_lattice_point_u8(noise, 1, 2, bytes.data());
        CHECK(fixed.zeroed_exactly(1));
        CHECK(real.zeroed_exactly(1));
        CHECK(bytes.zeroed_exactly(1));
        // A noise that is not configured: its channel count is unknown, one value per pixel is zeroed.
        const int expected = noise == nullptr ? DSN_ERR_NULL : DSN_ERR_ARGUMENT;
        Guarded<int32_t> fixed_tile(width * height);
        Guarded<float> real_tile(width * height);
        Guarded<uint8_t> byte_tile(width * height);
        unsigned char scratch[1024];
        CHECK(dsn_lattice_tile_fixed(noise, 0, 0, width, height, fixed_tile.data(), nullptr, 0) == expected);
        CHECK(dsn_lattice_tile_float(noise, 0, 0, width, height, real_tile.data(), scratch, sizeof scratch) ==
              expected);
        CHECK(dsn_lattice_tile_u8(noise, 0, 0, width, height, byte_tile.data(), scratch, sizeof scratch) ==
              expected);
        CHECK(fixed_tile.zeroed_exactly(width * height));
        CHECK(real_tile.zeroed_exactly(width * height));
        CHECK(byte_tile.zeroed_exactly(width * height));
    }
    // A configured noise without the scratch: every channel of every pixel.
    const dsn_noise *noise = &refusals.lattice.noise;
    Guarded<float> real_tile(width * height * 3);
    Guarded<uint8_t> byte_tile(width * height * 3);
    CHECK(dsn_lattice_tile_float(noise, 0, 0, width, height, real_tile.data(), nullptr, 0) ==
          DSN_ERR_SCRATCH);
    CHECK(dsn_lattice_tile_u8(noise, 0, 0, width, height, byte_tile.data(), nullptr, 0) == DSN_ERR_SCRATCH);
    CHECK(real_tile.zeroed_exactly(width * height * 3));
    CHECK(byte_tile.zeroed_exactly(width * height * 3));
    // A size refused is no size to write: the output is left as it was.
    Guarded<int32_t> untouched(3);
    CHECK(dsn_lattice_tile_fixed(noise, 0, 0, 0, 1, untouched.data(), nullptr, 0) == DSN_ERR_TILE_SIZE);
    CHECK(dsn_lattice_tile_fixed(noise, 0, 0, 1, DSN_TILE_MAX_SIDE + 1, untouched.data(), nullptr, 0) ==
          DSN_ERR_TILE_SIZE);
    CHECK(untouched.zeroed_exactly(0));
}

TEST_CASE("every continuous and filtered point evaluator zeroes its output on every error, and no further") {
    Refusals refusals;
    dsn_footprint footprint;
    REQUIRE(dsn_footprint_from_float(&footprint, 3, 0, 0, 3, 4) == DSN_OK);
    for (const Refusals::Case &refused : refusals.continuous_cases()) {
        CAPTURE(refused.name);
        Guarded<int32_t> fixed(refused.channels), filtered_fixed(refused.channels);
        Guarded<float> real(refused.channels), sample(refused.channels), filtered_real(refused.channels);
        Guarded<uint8_t> bytes(refused.channels), filtered_bytes(refused.channels);
        CHECK(dsn_continuous_point_fixed(refused.noise, 7, -9, fixed.data()) == refused.error);
        CHECK(dsn_continuous_point_u8(refused.noise, 7, -9, bytes.data()) == refused.error);
        CHECK(dsn_filtered_point_u8(refused.noise, 7, -9, &footprint, filtered_bytes.data()) ==
              refused.error);
        CHECK(dsn_continuous_point_float(refused.noise, 0.5, 2.5, real.data()) == refused.error);
        CHECK(dsn_sample(refused.noise, 0.5f, 2.5f, sample.data()) == refused.error);
        CHECK(dsn_filtered_point_fixed(refused.noise, 7, -9, &footprint, filtered_fixed.data()) ==
              refused.error);
        CHECK(dsn_filtered_point_float(refused.noise, 0.5, 2.5, &footprint, filtered_real.data()) ==
              refused.error);
        CHECK(fixed.zeroed_exactly(refused.channels));
        CHECK(real.zeroed_exactly(refused.channels));
        CHECK(sample.zeroed_exactly(refused.channels));
        CHECK(filtered_fixed.zeroed_exactly(refused.channels));
        CHECK(filtered_real.zeroed_exactly(refused.channels));
        CHECK(bytes.zeroed_exactly(refused.channels));
        CHECK(filtered_bytes.zeroed_exactly(refused.channels));
    }
    // A footprint missing or refused: every channel of a configured noise.
    const dsn_noise *noise = &refusals.bilinear.noise;
    Guarded<int32_t> fixed(3);
    Guarded<float> real(3);
    CHECK(dsn_filtered_point_fixed(noise, 0, 0, nullptr, fixed.data()) == DSN_ERR_NULL);
    footprint.max_taps = 0;
    CHECK(dsn_filtered_point_float(noise, 0, 0, &footprint, real.data()) == DSN_ERR_ARGUMENT);
    CHECK(fixed.zeroed_exactly(3));
    CHECK(real.zeroed_exactly(3));
    // The mean of a noise that is not configured.
    Guarded<float> mean(1);
    CHECK(dsn_noise_mean_float(&refusals.failed, mean.data()) == DSN_ERR_NULL);
    CHECK(mean.zeroed_exactly(1));
}

TEST_CASE(
    "every continuous and filtered tile zeroes its width x height pixels on every error, and no further") {
    Refusals refusals;
    const uint32_t width = 5, height = 4;
    const dsn_grid grid = unit_grid(1.0);
    unsigned char scratch[1 << 16];
    auto check_tiles = [&](const dsn_noise *noise, const dsn_grid *tile_grid, uint32_t max_taps,
                           void *tile_scratch, size_t scratch_size, int expected, size_t zeroed) {
        Guarded<int32_t> fixed(zeroed), filtered_fixed(zeroed);
        Guarded<float> real(zeroed), filtered_real(zeroed);
        Guarded<uint8_t> bytes(zeroed), filtered_bytes(zeroed);
        CHECK(dsn_continuous_tile_fixed(noise, tile_grid, width, height, fixed.data(), tile_scratch,
                                        scratch_size) == expected);
        CHECK(dsn_continuous_tile_float(noise, tile_grid, width, height, real.data(), tile_scratch,
                                        scratch_size) == expected);
        CHECK(dsn_continuous_tile_u8(noise, tile_grid, width, height, bytes.data(), tile_scratch,
                                     scratch_size) == expected);
        CHECK(dsn_filtered_tile_fixed(noise, tile_grid, max_taps, width, height, filtered_fixed.data(),
                                      tile_scratch, scratch_size) == expected);
        CHECK(dsn_filtered_tile_float(noise, tile_grid, max_taps, width, height, filtered_real.data(),
                                      tile_scratch, scratch_size) == expected);
        CHECK(dsn_filtered_tile_u8(noise, tile_grid, max_taps, width, height, filtered_bytes.data(),
                                   tile_scratch, scratch_size) == expected);
        CHECK(fixed.zeroed_exactly(zeroed));
        CHECK(real.zeroed_exactly(zeroed));
        CHECK(bytes.zeroed_exactly(zeroed));
        CHECK(filtered_fixed.zeroed_exactly(zeroed));
        CHECK(filtered_real.zeroed_exactly(zeroed));
        CHECK(filtered_bytes.zeroed_exactly(zeroed));
    };
    for (const Refusals::Case &refused : refusals.continuous_cases()) {
        CAPTURE(refused.name);
        check_tiles(refused.noise, &grid, 4, scratch, sizeof scratch, refused.error,
                    width * height * refused.channels);
    }
    const dsn_noise *noise = &refusals.bilinear.noise;
    {
        INFO("null grid");
        check_tiles(noise, nullptr, 4, scratch, sizeof scratch, DSN_ERR_NULL, width * height * 3);
    }
    Guarded<float> taps(width * height * 3);
    CHECK(dsn_filtered_tile_float(noise, &grid, 0, width, height, taps.data(), scratch, sizeof scratch) ==
          DSN_ERR_ARGUMENT);
    CHECK(taps.zeroed_exactly(width * height * 3));
    // Without the scratch that a splatted grid needs: unit steps (the continuous tile's splat, which the
    // unfiltered filtered tile is) and 1.2 texels per pixel (the filtered splat of pyramid levels 0 and 1).
    for (double step : {1.0, 1.2}) {
        CAPTURE(step);
        const dsn_grid splatted = unit_grid(step);
        REQUIRE(dsn_filtered_tile_scratch_size(noise, &splatted, 1, width, height) > 0);
        Guarded<int32_t> fixed(width * height * 3);
        Guarded<uint8_t> bytes(width * height * 3);
        CHECK(dsn_filtered_tile_fixed(noise, &splatted, 1, width, height, fixed.data(), nullptr, 0) ==
              DSN_ERR_SCRATCH);
        CHECK(dsn_filtered_tile_u8(noise, &splatted, 1, width, height, bytes.data(), scratch, 1) ==
              DSN_ERR_SCRATCH);
        CHECK(fixed.zeroed_exactly(width * height * 3));
        CHECK(bytes.zeroed_exactly(width * height * 3));
    }
    REQUIRE(dsn_continuous_tile_scratch_size(noise, &grid, width, height) > 0);
    Guarded<float> real(width * height * 3);
    CHECK(dsn_continuous_tile_float(noise, &grid, width, height, real.data(), nullptr, 0) == DSN_ERR_SCRATCH);
    CHECK(real.zeroed_exactly(width * height * 3));
    // A size refused is left as it was.
    Guarded<int32_t> untouched(3);
    CHECK(dsn_continuous_tile_fixed(noise, &grid, 0, 2, untouched.data(), scratch, sizeof scratch) ==
          DSN_ERR_TILE_SIZE);
    CHECK(dsn_filtered_tile_fixed(noise, &grid, 4, 2, DSN_TILE_MAX_SIDE + 1, untouched.data(), scratch,
                                  sizeof scratch) == DSN_ERR_TILE_SIZE);
    CHECK(untouched.zeroed_exactly(0));
}

#if DSN_CONTINUOUS_BATCH
TEST_CASE("the batches zero their count points on every error, and no further") {
    Refusals refusals;
    const uint32_t count = 6;
    const int64_t xs[count] = {0, 1, 2, 3, 4, 5}, ys[count] = {5, 4, 3, 2, 1, 0};
    const double real_xs[count] = {0, 1, 2, 3, 4, 5}, real_ys[count] = {5, 4, 3, 2, 1, 0};
    std::vector<unsigned char> scratch(dsn_continuous_batch_scratch_size(&refusals.bilinear.noise));
    REQUIRE(!scratch.empty());
    auto check_batches = [&](const dsn_noise *noise, const int64_t *batch_xs, const double *batch_real_xs,
                             void *batch_scratch, size_t scratch_size, int expected, size_t zeroed) {
        Guarded<int32_t> fixed(zeroed);
        Guarded<float> real(zeroed);
        Guarded<uint8_t> bytes(zeroed);
        CHECK(dsn_continuous_batch_fixed(noise, batch_xs, ys, count, fixed.data(), batch_scratch,
                                         scratch_size) == expected);
        CHECK(dsn_continuous_batch_float(noise, batch_real_xs, real_ys, count, real.data(), batch_scratch,
                                         scratch_size) == expected);
        CHECK(dsn_continuous_batch_u8(noise, batch_xs, ys, count, bytes.data(), batch_scratch,
                                      scratch_size) == expected);
        CHECK(fixed.zeroed_exactly(zeroed));
        CHECK(real.zeroed_exactly(zeroed));
        CHECK(bytes.zeroed_exactly(zeroed));
    };
    for (const Refusals::Case &refused : refusals.continuous_cases()) {
        CAPTURE(refused.name);
        check_batches(refused.noise, xs, real_xs, scratch.data(), scratch.size(), refused.error,
                      count * refused.channels);
    }
    const dsn_noise *noise = &refusals.bilinear.noise;
    {
        INFO("null coordinates");
        check_batches(noise, nullptr, nullptr, scratch.data(), scratch.size(), DSN_ERR_NULL, count * 3);
    }
    {
        INFO("scratch too small");
        check_batches(noise, xs, real_xs, scratch.data(), scratch.size() - 1, DSN_ERR_SCRATCH, count * 3);
    }
}
#endif
