// api_edges_test.cpp - the runtime API at its edges: null pointers, a noise whose init failed,
// densities out of range, periods 1 and 2^31, NaN / Inf / huge continuous coordinates. Each must give the
// documented error or a defined value (and, under `make sanitize`, no undefined behaviour).
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <string>

#include "dsn/dsn.h"
#include "fixtures/test_assets.h"

using dsn_test::LoadedNoise;
using dsn_test::make_config;
using dsn_test::synthetic_fields;

TEST_CASE("per-point functions with a null noise or output write nothing and do not crash") {
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
    CHECK(fixed[0] == 7);
    CHECK(real[2] == 7.0f);
    CHECK(bytes[1] == 7);
    CHECK(dsn_asset_texton_value(nullptr, 0, 0, 0) == 0);
    CHECK(dsn_asset_texton_value(&loaded.asset, 9, 0, 0) == 0);
    CHECK(dsn_asset_texton_value(&loaded.asset, 0, 0, 3) == 0);
    CHECK(dsn_asset_load(nullptr, loaded.bytes.data(), loaded.bytes.size()) == DSN_ERR_NULL);
    CHECK(dsn_asset_load(&loaded.asset, nullptr, 1000) == DSN_ERR_NULL);
}

TEST_CASE("a noise whose init failed evaluates to nothing and refuses tiles") {
    LoadedNoise loaded(synthetic_fields(1, 7, 16, DSN_SHAPE_RECTANGLE, 2), make_config(5));
    dsn_noise failed;
    dsn_config config = make_config(5);
    config.impacts_q16 = uint32_t(-5); // a "negative" density
    REQUIRE(dsn_noise_init(&failed, &loaded.asset, &config) == DSN_ERR_IMPACTS);
    int32_t value = 1234;
    dsn_lattice_point_fixed(&failed, 3, 4, &value);
    CHECK(value == 1234);
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
