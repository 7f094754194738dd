// asset_corruption_test.cpp - every single-bit flip and every truncation of small valid assets (1.0, 1.1
// with a pyramid, and 1.2 with a histogram mapping) is rejected with the code the format.h validation order
// prescribes; hostile edits with a recomputed CRC are rejected by a field check or load into a noise whose
// points and tiles are defined and agree.
#include <doctest/doctest.h>

#include <cstring>
#include <vector>

#include "dsn/asset_writer.h"
#include "dsn/dsn.h"
#include "runtime/setup/format_bytes.h"

namespace {

std::vector<unsigned char> small_asset(uint32_t channels, uint32_t bits, uint32_t shape, bool pyramid,
                                       bool histogram) {
    dsn::AssetFields fields;
    fields.channels = channels;
    fields.bits = bits;
    fields.shape = shape;
    fields.width = fields.height = 5;
    fields.default_impacts_q16 = 20u << 16;
    for (uint32_t c = 0; c < channels; c++) {
        fields.scale[c] = (1u << 30) + c;
        fields.mean[c] = int32_t(c + 1) << 22;
    }
    dsn::set_identity_color_transform(fields);
    const int32_t limit = bits == 8 ? 127 : 32767;
    for (uint32_t row = 0; row < 5; row++)
        for (uint32_t column = 0; column < 5; column++)
            for (uint32_t c = 0; c < channels; c++) {
                int32_t value = int32_t((row * 37 + column * 11 + c * 5) % 19) * limit / 19 - limit / 3;
                fields.texton.push_back(dsn_in_support(shape, 5, row, column) ? value : 0);
            }
    if (pyramid) { // format 1.1: a 3 x 3 level and a 1 x 1 level
        dsn::PyramidLevel first, second;
        first.width = first.height = 3;
        first.exponent = -2;
        for (uint32_t i = 0; i < 9 * channels; i++) first.values.push_back(int32_t(i * 29 % 41) - 20);
        second.exponent = -5;
        second.values.assign(channels, limit);
        fields.pyramid = {first, second};
    }
    if (histogram) { // format 1.2: 5 entries per table, a table per level
        dsn::HistogramMapping &mapping = fields.histogram;
        mapping.entry_count = 5;
        mapping.level_count = uint32_t(1 + fields.pyramid.size());
        mapping.step_shift = 1;
        mapping.input_low_q16 = -65536;
        for (uint32_t i = 0; i < mapping.level_count * channels * 5; i++)
            mapping.tables.push_back(int32_t(i * 4099 % 16001) - 8000);
        for (uint32_t c = 0; c < channels; c++) {
            mapping.centre[c] = int32_t(c + 2) << 21;
            mapping.expected_q16[c] = int32_t(c * 1000) - 700;
        }
        for (uint32_t i = 0; i < 9; i++)
            mapping.rotation[i] = channels == 3 || i == 0 ? int32_t(i * 977 % 31) << 19 : 0;
    }
    return dsn::encode_asset(fields);
}

// The code format.h's validation order gives for a valid asset with one header byte changed, before any
// field check (the CRC still being the original one).
int expected_code_for_damaged(const std::vector<unsigned char> &damaged, size_t offset) {
    static const unsigned char magic[] = DSN_FORMAT_MAGIC;
    if (offset < 4) return DSN_ERR_BAD_MAGIC;
    if (offset < 8) return damaged[offset] == magic[offset] ? DSN_OK : DSN_ERR_TEXT_MODE;
    if (offset == 8 || offset == 9) return DSN_ERR_VERSION;
    const uint64_t header = dsn_read_u32le(damaged.data() + DSN_OFFSET_HEADER_SIZE);
    const uint64_t total = dsn_read_u32le(damaged.data() + DSN_OFFSET_TOTAL_SIZE);
    if (header < DSN_FORMAT_HEADER_SIZE || header + 4 > total) return DSN_ERR_HEADER_SIZE;
    if (total > damaged.size()) return DSN_ERR_TRUNCATED;
    return DSN_ERR_CRC;
}

bool is_field_check(int code) {
    switch (code) {
    case DSN_ERR_RESERVED:
    case DSN_ERR_CHANNELS:
    case DSN_ERR_BITS:
    case DSN_ERR_SHAPE:
    case DSN_ERR_INTERPOLATION:
    case DSN_ERR_DIMENSIONS:
    case DSN_ERR_TOTAL_SIZE:
    case DSN_ERR_SCALE:
    case DSN_ERR_IMPACTS:
    case DSN_ERR_COLOR_TRANSFORM:
    case DSN_ERR_TEXTON:
    case DSN_ERR_SECTION:
    case DSN_ERR_PYRAMID:
    case DSN_ERR_HISTOGRAM:
        return true;
    default:
        return false;
    }
}

void recompute_crc(std::vector<unsigned char> &bytes) {
    const size_t body = bytes.size() - DSN_FORMAT_CRC_SIZE;
    dsn_write_u32le(bytes.data() + body, dsn_crc32(0, bytes.data(), body));
}

// Evaluates an accepted hostile asset: points at extreme coordinates and a tile straddling the 32-bit
// wrap must agree (and, under `make sanitize`, be free of undefined behaviour).
void evaluate_everywhere(const dsn_asset &asset) {
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = 7;
    dsn_noise noise;
    if (dsn_noise_init(&noise, &asset, &config) != DSN_OK) return;
    const int32_t x0 = 2147483646, y0 = -2147483647 - 1;
    const uint32_t width = 4, height = 3, channels = asset.channels;
    std::vector<int32_t> tile(width * height * channels);
    std::vector<unsigned char> scratch(dsn_lattice_tile_scratch_size(&noise, width, height));
    REQUIRE(dsn_lattice_tile_fixed(&noise, x0, y0, width, height, tile.data(), scratch.data(),
                                   scratch.size()) == DSN_OK);
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            int32_t value[DSN_MAX_CHANNELS];
            dsn_lattice_point_fixed(&noise, int32_t(uint32_t(x0) + i), int32_t(uint32_t(y0) + j), value);
            for (uint32_t c = 0; c < channels; c++) REQUIRE(value[c] == tile[(j * width + i) * channels + c]);
        }
}

const struct {
    uint32_t channels, bits, shape;
    bool pyramid, histogram;
} kAssets[] = {{3, 8, DSN_SHAPE_DISK, false, false}, {1, 16, DSN_SHAPE_RECTANGLE, false, false},
               {3, 8, DSN_SHAPE_DISK, true, false},  {1, 16, DSN_SHAPE_RECTANGLE, true, false},
               {3, 8, DSN_SHAPE_DISK, true, true},   {1, 16, DSN_SHAPE_RECTANGLE, false, true}};

} // namespace

TEST_CASE("every single-bit flip of a valid asset is rejected with the code of the validation order") {
    for (const auto &kind : kAssets) {
        const std::vector<unsigned char> valid =
            small_asset(kind.channels, kind.bits, kind.shape, kind.pyramid, kind.histogram);
        dsn_asset asset;
        REQUIRE(dsn_asset_load(&asset, valid.data(), valid.size()) == DSN_OK);
        size_t checked = 0;
        for (size_t offset = 0; offset < valid.size(); offset++)
            for (int bit = 0; bit < 8; bit++) {
                std::vector<unsigned char> damaged = valid;
                damaged[offset] = static_cast<unsigned char>(damaged[offset] ^ (1u << bit));
                const int expected = expected_code_for_damaged(damaged, offset);
                const int code = dsn_asset_load(&asset, damaged.data(), damaged.size());
                if (code != expected) {
                    CAPTURE(offset);
                    CAPTURE(bit);
                    CHECK(code == expected);
                }
                checked++;
            }
        CHECK(checked == valid.size() * 8);
    }
}

TEST_CASE("every truncation of a valid asset is rejected as truncated") {
    for (const auto &kind : kAssets) {
        const std::vector<unsigned char> valid =
            small_asset(kind.channels, kind.bits, kind.shape, kind.pyramid, kind.histogram);
        dsn_asset asset;
        for (size_t size = 0; size < valid.size(); size++) {
            // A fresh copy of exactly `size` bytes, so a read past the end is a sanitizer error.
            std::vector<unsigned char> prefix(valid.begin(), valid.begin() + long(size));
            const int code = dsn_asset_load(&asset, prefix.empty() ? nullptr : prefix.data(), size);
            if (size == 0 && code == DSN_ERR_NULL) continue; // a null buffer may be reported as such
            if (code != DSN_ERR_TRUNCATED) {
                CAPTURE(size);
                CHECK(code == DSN_ERR_TRUNCATED);
            }
        }
    }
}

TEST_CASE("hostile fields with a recomputed CRC are refused by a field check or evaluate consistently") {
    for (const auto &kind : kAssets) {
        const std::vector<unsigned char> valid =
            small_asset(kind.channels, kind.bits, kind.shape, kind.pyramid, kind.histogram);
        size_t accepted = 0, refused = 0;
        for (size_t offset = DSN_OFFSET_FLAGS; offset < valid.size() - DSN_FORMAT_CRC_SIZE; offset++)
            for (int variant = 0; variant < 10; variant++) {
                std::vector<unsigned char> hostile = valid;
                hostile[offset] = variant < 8 ? static_cast<unsigned char>(hostile[offset] ^ (1u << variant))
                                              : static_cast<unsigned char>(variant == 8 ? 0x00 : 0xFF);
                if (hostile == valid) continue;
                recompute_crc(hostile);
                dsn_asset asset;
                const int code = dsn_asset_load(&asset, hostile.data(), hostile.size());
                if (code == DSN_OK) {
                    accepted++;
                    evaluate_everywhere(asset);
                } else {
                    refused++;
                    if (!is_field_check(code)) {
                        CAPTURE(offset);
                        CAPTURE(variant);
                        CHECK(is_field_check(code));
                    }
                }
            }
        // Metadata, means, transforms and texton values change freely; structure bytes do not.
        CHECK(accepted > 0);
        CHECK(refused > 0);
    }
}
