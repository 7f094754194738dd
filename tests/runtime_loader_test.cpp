// runtime_loader_test.cpp - dsn_asset_load: a valid asset loads in place, and every field check of the
// format's validation order produces exactly its own error code; argument checks of the runtime API.
#include <doctest/doctest.h>

#include <cstring>
#include <vector>

#include "fixtures/test_assets.h"
#include "runtime/setup/format_bytes.h"
#include "runtime/setup/noise_state.h"

namespace {

using Bytes = std::vector<unsigned char>;

Bytes valid_bytes(uint32_t channels = 3, uint32_t shape = DSN_SHAPE_RECTANGLE, uint32_t bits = 8) {
    return dsn::encode_asset(dsn_test::synthetic_fields(channels, 5, bits, shape, 11));
}

// Rewrites the CRC after an edit, so that the check under test is the one that fails.
void reseal(Bytes &bytes) {
    uint32_t total = dsn_read_u32le(bytes.data() + DSN_OFFSET_TOTAL_SIZE);
    dsn_write_u32le(bytes.data() + total - 4, dsn_crc32(0, bytes.data(), total - 4));
}

int load(const Bytes &bytes, size_t size) {
    dsn_asset asset;
    std::memset(&asset, 0x5A, sizeof asset);
    int code = dsn_asset_load(&asset, bytes.data(), size);
    if (code != DSN_OK) { // a failed load leaves a zeroed asset
        const unsigned char *raw = reinterpret_cast<const unsigned char *>(&asset);
        for (size_t i = 0; i < sizeof asset; i++) REQUIRE(raw[i] == 0);
    }
    return code;
}

int load(const Bytes &bytes) { return load(bytes, bytes.size()); }

template <typename Edit>
int load_edited(Edit edit, bool seal = true, Bytes bytes = valid_bytes()) {
    edit(bytes);
    if (seal) reseal(bytes);
    return load(bytes);
}

} // namespace

TEST_CASE("a valid asset loads in place with every field") {
    auto fields = dsn_test::synthetic_fields(3, 7, 16, DSN_SHAPE_DISK, 3);
    fields.default_impacts_q16 = 12u << 16;
    fields.bake_seed = 99;
    Bytes bytes = dsn::encode_asset(fields);
    bytes.push_back(0xEE); // trailing bytes are ignored
    dsn_asset asset;
    REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    CHECK(asset.texton == bytes.data() + DSN_FORMAT_HEADER_SIZE); // zero-copy view
    CHECK(asset.channels == 3);
    CHECK(asset.bits == 16);
    CHECK(asset.shape == DSN_SHAPE_DISK);
    CHECK(asset.width == 7);
    CHECK(asset.support_size == dsn_support_size(DSN_SHAPE_DISK, 7, 7));
    CHECK(asset.default_impacts_q16 == (12u << 16));
    CHECK(asset.bake_seed == 99);
    CHECK(asset.mean[1] == fields.mean[1]);
    CHECK(asset.color_transform[3] == fields.color_transform[3]);
    for (uint32_t row = 0; row < 7; row++)
        for (uint32_t column = 0; column < 7; column++)
            for (uint32_t c = 0; c < 3; c++)
                CHECK(dsn_asset_texton_value(&asset, row, column, c) ==
                      fields.texton[(row * 7 + column) * 3 + c]);
    CHECK(dsn_asset_texton_value(&asset, 7, 0, 0) == 0);
    CHECK(dsn_asset_texton_value(&asset, 0, 0, 3) == 0);
    CHECK(dsn_asset_texton_value(nullptr, 0, 0, 0) == 0);
}

TEST_CASE("every validation step has its own error code, in the documented order") {
    const Bytes good = valid_bytes();
    CHECK(load(good) == DSN_OK);
    dsn_asset asset;
    CHECK(dsn_asset_load(nullptr, good.data(), good.size()) == DSN_ERR_NULL);
    CHECK(dsn_asset_load(&asset, nullptr, good.size()) == DSN_ERR_NULL);
    // 1, 3, 6: truncation at each stage.
    CHECK(load(good, 0) == DSN_ERR_TRUNCATED);
    CHECK(load(good, 7) == DSN_ERR_TRUNCATED);
    CHECK(load(good, 131) == DSN_ERR_TRUNCATED);
    CHECK(load(good, good.size() - 1) == DSN_ERR_TRUNCATED);
    // 2: magic; damage to CR, LF or SUB only is reported as a text-mode transfer.
    CHECK(load_edited([](Bytes &b) { b[1] = 'X'; }, false) == DSN_ERR_BAD_MAGIC);
    CHECK(load_edited([](Bytes &b) { b[0] = 0x09; }, false) == DSN_ERR_BAD_MAGIC);
    CHECK(load_edited([](Bytes &b) { b[4] = 0x0A; }, false) == DSN_ERR_TEXT_MODE);
    CHECK(load_edited([](Bytes &b) { b.erase(b.begin() + 4); }, false) == DSN_ERR_TEXT_MODE); // CRLF -> LF
    // 4, 5: version and header size.
    CHECK(load_edited([](Bytes &b) { dsn_write_u16le(&b[DSN_OFFSET_VERSION_MAJOR], 2); }) == DSN_ERR_VERSION);
    CHECK(load_edited([](Bytes &b) { dsn_write_u32le(&b[DSN_OFFSET_HEADER_SIZE], 127); }, false) ==
          DSN_ERR_HEADER_SIZE);
    CHECK(load_edited([](Bytes &b) { dsn_write_u32le(&b[DSN_OFFSET_HEADER_SIZE], 0xFFFFFFF0u); }, false) ==
          DSN_ERR_HEADER_SIZE);
    CHECK(load_edited([](Bytes &b) { dsn_write_u32le(&b[DSN_OFFSET_TOTAL_SIZE], 3); }, false) ==
          DSN_ERR_HEADER_SIZE);
    CHECK(load_edited([](Bytes &b) { dsn_write_u32le(&b[DSN_OFFSET_TOTAL_SIZE], 0xFFFFFFFFu); }, false) ==
          DSN_ERR_TRUNCATED);
    // 7: checksum (any flipped bit).
    CHECK(load_edited([](Bytes &b) { b[DSN_FORMAT_HEADER_SIZE + 3] ^= 0x10; }, false) == DSN_ERR_CRC);
    CHECK(load_edited([](Bytes &b) { b[b.size() - 1] ^= 1; }, false) == DSN_ERR_CRC);
    // 8: flags and reserved bytes.
    CHECK(load_edited([](Bytes &b) { b[DSN_OFFSET_FLAGS + 2] = 1; }) == DSN_ERR_RESERVED);
    CHECK(load_edited([](Bytes &b) { b[DSN_OFFSET_RESERVED + 15] = 1; }) == DSN_ERR_RESERVED);
    // 9: the geometry fields, each with its code.
    CHECK(load_edited([](Bytes &b) { b[DSN_OFFSET_CHANNELS] = 2; }) == DSN_ERR_CHANNELS);
    CHECK(load_edited([](Bytes &b) { b[DSN_OFFSET_CHANNELS] = 0; }) == DSN_ERR_CHANNELS);
    CHECK(load_edited([](Bytes &b) { b[DSN_OFFSET_BITS] = 12; }) == DSN_ERR_BITS);
    CHECK(load_edited([](Bytes &b) { b[DSN_OFFSET_SHAPE] = 2; }) == DSN_ERR_SHAPE);
    CHECK(load_edited([](Bytes &b) { b[DSN_OFFSET_INTERPOLATION] = 2; }) == DSN_ERR_INTERPOLATION);
    CHECK(load_edited([](Bytes &b) { dsn_write_u16le(&b[DSN_OFFSET_WIDTH], 4); }) == DSN_ERR_DIMENSIONS);
    CHECK(load_edited([](Bytes &b) { dsn_write_u16le(&b[DSN_OFFSET_HEIGHT], 0); }) == DSN_ERR_DIMENSIONS);
    CHECK(load_edited([](Bytes &b) { dsn_write_u16le(&b[DSN_OFFSET_WIDTH], 257); }) == DSN_ERR_DIMENSIONS);
    // A disk that is not square (the rectangle 5 x 3 is well-formed apart from its size).
    CHECK(load_edited([](Bytes &b) {
              b[DSN_OFFSET_SHAPE] = DSN_SHAPE_DISK;
              dsn_write_u16le(&b[DSN_OFFSET_HEIGHT], 3);
          }) == DSN_ERR_SHAPE);
    // 10: total size against the texton size.
    CHECK(load_edited([](Bytes &b) { dsn_write_u16le(&b[DSN_OFFSET_WIDTH], 3); }) == DSN_ERR_TOTAL_SIZE);
    CHECK(load_edited([](Bytes &b) { b[DSN_OFFSET_BITS] = 16; }) == DSN_ERR_TOTAL_SIZE);
    // 11: scale, impacts, unused channel fields.
    CHECK(load_edited([](Bytes &b) { dsn_write_u32le(&b[DSN_OFFSET_SCALE + 4], 0); }) == DSN_ERR_SCALE);
    CHECK(load_edited([](Bytes &b) { dsn_write_u32le(&b[DSN_OFFSET_DEFAULT_IMPACTS], 1); }) ==
          DSN_ERR_IMPACTS);
    CHECK(load_edited([](Bytes &b) {
              dsn_write_u32le(&b[DSN_OFFSET_DEFAULT_IMPACTS], DSN_IMPACTS_MAX_Q16 + 1);
          }) == DSN_ERR_IMPACTS);
    Bytes grey = valid_bytes(1);
    CHECK(load(grey) == DSN_OK);
    CHECK(load_edited([](Bytes &b) { dsn_write_u32le(&b[DSN_OFFSET_SCALE + 8], 5); }, true, grey) ==
          DSN_ERR_RESERVED);
    CHECK(load_edited([](Bytes &b) { dsn_write_i32le(&b[DSN_OFFSET_MEAN + 4], -1); }, true, grey) ==
          DSN_ERR_RESERVED);
    // 12: grey colour transform.
    CHECK(load_edited([](Bytes &b) { dsn_write_i32le(&b[DSN_OFFSET_COLOR_TRANSFORM + 8], 7); }, true, grey) ==
          DSN_ERR_COLOR_TRANSFORM);
    // 13: texton values.
    CHECK(load_edited([](Bytes &b) { b[DSN_FORMAT_HEADER_SIZE + 7] = 0x80; }) == DSN_ERR_TEXTON);
    Bytes wide = valid_bytes(1, DSN_SHAPE_RECTANGLE, 16);
    CHECK(load_edited([](Bytes &b) { dsn_write_u16le(&b[DSN_FORMAT_HEADER_SIZE + 2], 0x8000); }, true,
                      wide) == DSN_ERR_TEXTON);
    Bytes disk = valid_bytes(1, DSN_SHAPE_DISK);
    CHECK(load(disk) == DSN_OK);
    CHECK(load_edited([](Bytes &b) { b[DSN_FORMAT_HEADER_SIZE + 0] = 1; }, true, disk) == DSN_ERR_TEXTON);
    // A later minor version with a longer header loads when its extra bytes are sections (here one of an
    // unknown kind, skipped); other bytes there break the framing (steps 14 and 15: asset_sections_test).
    for (unsigned char fill : {0xCC, 0x00}) {
        const int code = load_edited([fill](Bytes &b) {
            b.insert(b.begin() + DSN_FORMAT_HEADER_SIZE, 8, fill);
            if (fill == 0) dsn_write_u32le(&b[DSN_FORMAT_HEADER_SIZE], 0xCCCCCCCCu); // kind, size 0
            dsn_write_u16le(&b[DSN_OFFSET_VERSION_MINOR], 3);
            dsn_write_u32le(&b[DSN_OFFSET_HEADER_SIZE], DSN_FORMAT_HEADER_SIZE + 8);
            dsn_write_u32le(&b[DSN_OFFSET_TOTAL_SIZE], uint32_t(b.size()));
        });
        CHECK(code == (fill == 0 ? DSN_OK : DSN_ERR_SECTION));
    }
}

TEST_CASE("error messages are distinct, static and never null") {
    std::vector<std::string> seen;
    for (int code = DSN_OK; code >= DSN_ERR_LOWEST; code--) {
        const char *message = dsn_error_message(code);
        REQUIRE(message != nullptr);
        for (const auto &other : seen) CHECK(other != message);
        seen.push_back(message);
    }
    CHECK(std::string(dsn_error_message(12345)) == "unknown error code");
}

TEST_CASE("configuration and evaluation arguments are checked") {
    Bytes bytes = valid_bytes();
    dsn_asset asset, empty{};
    REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    dsn_config config;
    dsn_config_defaults(&config);
    dsn_noise noise;
    CHECK(dsn_noise_init(nullptr, &asset, &config) == DSN_ERR_NULL);
    CHECK(dsn_noise_init(&noise, nullptr, &config) == DSN_ERR_NULL);
    CHECK(dsn_noise_init(&noise, &asset, nullptr) == DSN_ERR_NULL);
    CHECK(dsn_noise_init(&noise, &empty, &config) == DSN_ERR_ARGUMENT);
    // An asset altered after loading: init runs the loader's geometry checks again.
    dsn_asset altered = asset;
    altered.shape = DSN_SHAPE_DISK + 1;
    CHECK(dsn_noise_init(&noise, &altered, &config) == DSN_ERR_ARGUMENT);
    altered = asset;
    altered.support_size += 1;
    CHECK(dsn_noise_init(&noise, &altered, &config) == DSN_ERR_ARGUMENT);
    altered = asset;
    altered.width += 1;
    CHECK(dsn_noise_init(&noise, &altered, &config) == DSN_ERR_ARGUMENT);
    config.flags = DSN_FLAGS_ALL + 1; // the lowest unknown bit
    CHECK(dsn_noise_init(&noise, &asset, &config) == DSN_ERR_ARGUMENT);
    config.flags = 0;
    config.impacts_q16 = DSN_IMPACTS_MIN_Q16 - 1;
    CHECK(dsn_noise_init(&noise, &asset, &config) == DSN_ERR_IMPACTS);
    config.impacts_q16 = DSN_IMPACTS_MAX_Q16 + 1;
    CHECK(dsn_noise_init(&noise, &asset, &config) == DSN_ERR_IMPACTS);
    config.impacts_q16 = 0; // the asset's default, 30 when it has none
    REQUIRE(dsn_noise_init(&noise, &asset, &config) == DSN_OK);
    CHECK(dsn_state(&noise)->impacts_q16 == DSN_IMPACTS_DEFAULT_Q16);
    // Extremes of the density still give a valid table and normalization.
    for (uint32_t impacts : {DSN_IMPACTS_MIN_Q16, DSN_IMPACTS_MAX_Q16}) {
        config.impacts_q16 = impacts;
        REQUIRE(dsn_noise_init(&noise, &asset, &config) == DSN_OK);
        CHECK(dsn_state(&noise)->poisson_size > 0);
        int32_t point[3], tile[3];
        dsn_lattice_point_fixed(&noise, INT32_MIN, INT32_MAX, point);
        REQUIRE(dsn_lattice_tile_fixed(&noise, INT32_MIN, INT32_MAX, 1, 1, tile, nullptr, 0) == DSN_OK);
        CHECK(std::memcmp(point, tile, sizeof point) == 0);
    }
    int32_t out[3];
    CHECK(dsn_lattice_tile_fixed(&noise, 0, 0, 0, 4, out, nullptr, 0) == DSN_ERR_TILE_SIZE);
    CHECK(dsn_lattice_tile_fixed(&noise, 0, 0, DSN_TILE_MAX_SIDE + 1, 1, out, nullptr, 0) ==
          DSN_ERR_TILE_SIZE);
    CHECK(dsn_lattice_tile_fixed(nullptr, 0, 0, 1, 1, out, nullptr, 0) == DSN_ERR_NULL);
    CHECK(dsn_lattice_tile_fixed(&noise, 0, 0, 1, 1, nullptr, nullptr, 0) == DSN_ERR_NULL);
    float values[3];
    CHECK(dsn_lattice_tile_float(&noise, 0, 0, 1, 1, values, nullptr, 0) == DSN_ERR_SCRATCH);
    std::vector<unsigned char> scratch(dsn_lattice_tile_scratch_size(&noise, 1, 1));
    CHECK(dsn_lattice_tile_float(&noise, 0, 0, 1, 1, values, scratch.data(), scratch.size() - 4) ==
          DSN_ERR_SCRATCH);
    CHECK(dsn_lattice_tile_float(&noise, 0, 0, 1, 1, values, scratch.data(), scratch.size()) == DSN_OK);
    CHECK(dsn_lattice_tile_scratch_size(&noise, 0, 1) == 0);
    CHECK(dsn_lattice_tile_scratch_size(nullptr, 1, 1) == 0);
}
