// asset_sections_test.cpp - format 1.1: the loader reads sections and the texton pyramid (format.h steps
// 14 and 15, each failure with its own code), skips unknown kinds, still reads 1.0 files, and a 1.1 file
// read by the 1.0 rules yields the same texton; dsn_asset_level reads every level. Format 1.2: every
// failure of step 16 is DSN_ERR_HISTOGRAM, and the flag and kind 2 count from minor 2 on.
#include <doctest/doctest.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "fixtures/test_assets.h"
#include "runtime/setup/format_bytes.h"

namespace {

using Bytes = std::vector<unsigned char>;

// Two levels (3 x 5 then 1 x 1) of varied values at the extremes of the quantization range.
dsn::AssetFields pyramid_fields(uint32_t channels, uint32_t bits) {
    dsn::AssetFields fields = dsn_test::synthetic_fields(channels, 5, bits, DSN_SHAPE_RECTANGLE, 5);
    const int32_t limit = bits == 8 ? 127 : 32767;
    dsn::PyramidLevel first, second;
    first.width = 3;
    first.height = 5;
    first.exponent = -3;
    for (uint32_t i = 0; i < 3 * 5 * channels; i++) first.values.push_back(int32_t(i * 37 % 255) - 127);
    first.values[0] = limit;
    first.values[1] = -limit;
    second.exponent = 24;
    second.values.assign(channels, -limit);
    fields.pyramid = {first, second};
    return fields;
}

void reseal(Bytes &bytes) {
    const uint32_t total = dsn_read_u32le(bytes.data() + DSN_OFFSET_TOTAL_SIZE);
    dsn_write_u32le(bytes.data() + total - 4, dsn_crc32(0, bytes.data(), total - 4));
}

// A file of the given minor version whose bytes [128, header_size) are exactly `sections`, around the
// texton of a valid 1.0 asset.
Bytes with_sections(const Bytes &sections, uint16_t minor = 1, uint32_t channels = 3, uint32_t bits = 8) {
    Bytes bytes = dsn::encode_asset(dsn_test::synthetic_fields(channels, 5, bits, DSN_SHAPE_RECTANGLE, 5));
    bytes.insert(bytes.begin() + DSN_FORMAT_HEADER_SIZE, sections.begin(), sections.end());
    dsn_write_u16le(&bytes[DSN_OFFSET_VERSION_MINOR], minor);
    dsn_write_u32le(&bytes[DSN_OFFSET_HEADER_SIZE], uint32_t(DSN_FORMAT_HEADER_SIZE + sections.size()));
    dsn_write_u32le(&bytes[DSN_OFFSET_TOTAL_SIZE], uint32_t(bytes.size()));
    reseal(bytes);
    return bytes;
}

// One section: kind, size, payload, and `padding` bytes of value `pad`.
Bytes section(uint32_t kind, const Bytes &payload, size_t padding, unsigned char pad = 0,
              uint32_t size_field = 0xFFFFFFFFu) {
    Bytes bytes(8);
    bytes.reserve(8 + payload.size() + padding);
    dsn_write_u32le(&bytes[0], kind);
    dsn_write_u32le(&bytes[4], size_field == 0xFFFFFFFFu ? uint32_t(payload.size()) : size_field);
    bytes.insert(bytes.end(), payload.begin(), payload.end());
    bytes.insert(bytes.end(), padding, pad);
    return bytes;
}

Bytes operator+(Bytes a, const Bytes &b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

// A pyramid payload for a grey 8-bit asset: one record per (width, height, exponent), values all 1.
Bytes pyramid_payload(const std::vector<int> &records) {
    Bytes payload(4, 0);
    size_t values = 0;
    for (size_t i = 0; i + 2 < records.size(); i += 3) {
        payload[0]++;
        payload.push_back(uint8_t(records[i]));
        payload.push_back(uint8_t(records[i + 1]));
        payload.push_back(uint8_t(records[i + 2] & 0xFF));
        payload.push_back(0);
        values += size_t(records[i]) * size_t(records[i + 1]);
    }
    payload.insert(payload.end(), values, 1);
    return payload;
}

// The padding a payload of `size` bytes needs.
size_t padding_for(size_t size) { return (4 - size % 4) % 4; }

Bytes pyramid_section(const Bytes &payload) {
    return section(DSN_SECTION_PYRAMID, payload, padding_for(payload.size()));
}

int load(const Bytes &bytes) {
    dsn_asset asset;
    std::memset(&asset, 0x5A, sizeof asset);
    const int code = dsn_asset_load(&asset, bytes.data(), bytes.size());
    if (code != DSN_OK) { // a failed load leaves a zeroed asset
        const unsigned char *raw = reinterpret_cast<const unsigned char *>(&asset);
        for (size_t i = 0; i < sizeof asset; i++) REQUIRE(raw[i] == 0);
    }
    return code;
}

// A grey 8-bit file with a pyramid payload edited by `edit` (sizes kept, resealed).
template <typename Edit>
int load_grey_pyramid(Edit edit) {
    Bytes payload = pyramid_payload({3, 3, -2, 1, 1, -5});
    edit(payload);
    return load(with_sections(pyramid_section(payload), 1, 1, 8));
}

} // namespace

TEST_CASE("a 1.1 asset loads with its pyramid, level by level, for every channel count and value size") {
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u}) {
            CAPTURE(channels);
            CAPTURE(bits);
            const dsn::AssetFields fields = pyramid_fields(channels, bits);
            const Bytes bytes = dsn::encode_asset(fields);
            dsn_asset asset;
            REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
            CHECK(asset.version_minor == 1);
            REQUIRE(asset.pyramid_levels == 2);
            CHECK(asset.pyramid == bytes.data() + DSN_FORMAT_HEADER_SIZE + DSN_SECTION_HEADER_SIZE + 4);
            const uint32_t header_size = dsn_read_u32le(bytes.data() + DSN_OFFSET_HEADER_SIZE);
            CHECK(asset.texton == bytes.data() + header_size);
            CHECK(header_size % 4 == 0);
            dsn_level level;
            REQUIRE(dsn_asset_level(&asset, 0, &level) == DSN_OK);
            CHECK(level.values == asset.texton);
            CHECK(level.width == 5);
            CHECK(level.height == 5);
            CHECK(level.exponent == 0);
            for (uint32_t l = 1; l <= 2; l++) {
                const dsn::PyramidLevel &expected = fields.pyramid[l - 1];
                REQUIRE(dsn_asset_level(&asset, l, &level) == DSN_OK);
                CHECK(level.width == expected.width);
                CHECK(level.height == expected.height);
                CHECK(level.exponent == expected.exponent);
                for (size_t i = 0; i < expected.values.size(); i++) {
                    const int32_t value =
                        bits == 8 ? dsn_read_i8(level.values + i) : dsn_read_i16le(level.values + 2 * i);
                    REQUIRE(value == expected.values[i]);
                }
            }
            // The last level's values end where the section's payload (before its padding) does.
            const uint32_t payload_size = dsn_read_u32le(bytes.data() + DSN_FORMAT_HEADER_SIZE + 4);
            CHECK(level.values + channels * bits / 8 ==
                  bytes.data() + DSN_FORMAT_HEADER_SIZE + DSN_SECTION_HEADER_SIZE + payload_size);
            CHECK(dsn_asset_level(&asset, 3, &level) == DSN_ERR_ARGUMENT);
            CHECK(level.values == nullptr);
            CHECK(level.width == 0);
            CHECK(dsn_asset_level(&asset, 0xFFFFFFFFu, &level) == DSN_ERR_ARGUMENT);
            CHECK(dsn_asset_level(nullptr, 0, &level) == DSN_ERR_NULL);
            CHECK(dsn_asset_level(&asset, 0, nullptr) == DSN_ERR_NULL);
            const dsn_asset empty{};
            CHECK(dsn_asset_level(&empty, 0, &level) == DSN_ERR_NULL);
        }
}

TEST_CASE("a 1.0 asset loads without a pyramid, and its level 0 is the texton") {
    const Bytes bytes = dsn::encode_asset(dsn_test::synthetic_fields(3, 7, 8, DSN_SHAPE_DISK, 2));
    CHECK(dsn_read_u16le(bytes.data() + DSN_OFFSET_VERSION_MINOR) == 0);
    dsn_asset asset;
    REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    CHECK(asset.pyramid == nullptr);
    CHECK(asset.pyramid_levels == 0);
    dsn_level level;
    CHECK(dsn_asset_level(&asset, 0, &level) == DSN_OK);
    CHECK(level.values == asset.texton);
    CHECK(dsn_asset_level(&asset, 1, &level) == DSN_ERR_ARGUMENT);
    // A hand-filled asset that claims levels without a pyramid is refused, not read through null.
    dsn_asset claimed = asset;
    claimed.pyramid_levels = 1;
    CHECK(dsn_asset_level(&claimed, 1, &level) == DSN_ERR_ARGUMENT);
}

TEST_CASE("a 1.1 asset read by the 1.0 rules yields the same texton and fields") {
    const dsn::AssetFields fields = pyramid_fields(3, 16);
    const Bytes new_file = dsn::encode_asset(fields);
    dsn::AssetFields plain = fields;
    plain.pyramid.clear();
    const Bytes old_file = dsn::encode_asset(plain);
    // A 1.0 reader: header fields from bytes [0, 128), the texton at header_size, the CRC over the file.
    // Marking the 1.1 file as minor 0 makes this loader apply exactly those rules.
    Bytes as_old = new_file;
    dsn_write_u16le(&as_old[DSN_OFFSET_VERSION_MINOR], 0);
    reseal(as_old);
    dsn_asset read_old, reference;
    REQUIRE(dsn_asset_load(&read_old, as_old.data(), as_old.size()) == DSN_OK);
    REQUIRE(dsn_asset_load(&reference, old_file.data(), old_file.size()) == DSN_OK);
    CHECK(read_old.pyramid_levels == 0);
    CHECK(read_old.pyramid == nullptr);
    const size_t texton_bytes = fields.texton.size() * 2;
    CHECK(std::memcmp(read_old.texton, reference.texton, texton_bytes) == 0);
    // Every 1.0 header byte but the size fields and the minor version is the same in both files.
    for (size_t offset = 0; offset < DSN_FORMAT_HEADER_SIZE; offset++) {
        if (offset >= DSN_OFFSET_VERSION_MINOR && offset < DSN_OFFSET_FLAGS) continue;
        CHECK(new_file[offset] == old_file[offset]);
    }
    CHECK(read_old.width == reference.width);
    CHECK(read_old.scale[2] == reference.scale[2]);
    CHECK(read_old.mean[1] == reference.mean[1]);
    // The 1.1 rules read the same texton.
    dsn_asset read_new;
    REQUIRE(dsn_asset_load(&read_new, new_file.data(), new_file.size()) == DSN_OK);
    CHECK(std::memcmp(read_new.texton, reference.texton, texton_bytes) == 0);
}

TEST_CASE("unknown section kinds are skipped wherever they stand") {
    const Bytes pyramid = pyramid_section(pyramid_payload({3, 3, -2}));
    const Bytes unknown = section(7, Bytes{1, 2, 3, 4, 5}, 3);
    const Bytes empty = section(0, Bytes{}, 0);
    const struct {
        Bytes sections;
        uint32_t levels;
    } cases[] = {{unknown + pyramid, 1}, {pyramid + unknown + empty, 1}, {empty + unknown, 0}, {Bytes{}, 0}};
    for (const auto &c : cases) {
        const Bytes bytes = with_sections(c.sections, 1, 1, 8);
        dsn_asset asset;
        REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
        CHECK(asset.pyramid_levels == c.levels);
    }
    // A later minor version may add kinds: a 1.1 reader skips them the same way.
    CHECK(load(with_sections(unknown + pyramid, 3, 1, 8)) == DSN_OK);
    // A minor-0 file's extra header bytes are not sections: ignored whatever they hold.
    CHECK(load(with_sections(Bytes(12, 0xCC), 0, 1, 8)) == DSN_OK);
}

TEST_CASE("section framing errors are DSN_ERR_SECTION") {
    const Bytes payload = pyramid_payload({3, 3, -2}); // 4 + 4 + 9 = 17 bytes: 3 of padding
    REQUIRE(load(with_sections(pyramid_section(payload), 1, 1, 8)) == DSN_OK);
    // A section header that does not fit in the header's remaining bytes.
    CHECK(load(with_sections(pyramid_section(payload) + Bytes(4, 0), 1, 1, 8)) == DSN_ERR_SECTION);
    CHECK(load(with_sections(Bytes(4, 0), 1, 1, 8)) == DSN_ERR_SECTION);
    // A payload longer than the header, even by its padding only; and sizes near 2^32 (no wrap).
    CHECK(load(with_sections(section(DSN_SECTION_PYRAMID, payload, 3, 0, 21), 1, 1, 8)) == DSN_ERR_SECTION);
    CHECK(load(with_sections(section(DSN_SECTION_PYRAMID, payload, 2), 1, 1, 8)) == DSN_ERR_SECTION);
    CHECK(load(with_sections(section(9, payload, 3, 0, 0xFFFFFFFCu), 1, 1, 8)) == DSN_ERR_SECTION);
    CHECK(load(with_sections(section(9, payload, 3, 0, 0xFFFFFFFFu - 1), 1, 1, 8)) == DSN_ERR_SECTION);
    // Non-zero padding, of a known or an unknown kind.
    CHECK(load(with_sections(section(DSN_SECTION_PYRAMID, payload, 3, 1), 1, 1, 8)) == DSN_ERR_SECTION);
    CHECK(load(with_sections(section(5, Bytes{1}, 3, 0x80), 1, 1, 8)) == DSN_ERR_SECTION);
    // A known kind twice.
    CHECK(load(with_sections(pyramid_section(payload) + pyramid_section(payload), 1, 1, 8)) ==
          DSN_ERR_SECTION);
    // Framing is checked for every section before any pyramid content (step 14 before step 15).
    Bytes bad_levels = payload;
    bad_levels[0] = 0;
    CHECK(load(with_sections(pyramid_section(bad_levels), 1, 1, 8)) == DSN_ERR_PYRAMID);
    CHECK(load(with_sections(pyramid_section(bad_levels) + Bytes(4, 0), 1, 1, 8)) == DSN_ERR_SECTION);
}

TEST_CASE("pyramid content errors are DSN_ERR_PYRAMID") {
    CHECK(load_grey_pyramid([](Bytes &) {}) == DSN_OK);
    CHECK(load_grey_pyramid([](Bytes &p) { p[0] = 0; }) == DSN_ERR_PYRAMID);
    CHECK(load_grey_pyramid([](Bytes &p) { p[0] = 9; }) == DSN_ERR_PYRAMID);
    CHECK(load_grey_pyramid([](Bytes &p) { p[0] = 1; }) == DSN_ERR_PYRAMID); // the size no longer matches
    CHECK(load_grey_pyramid([](Bytes &p) { p[0] = 200; }) == DSN_ERR_PYRAMID);
    for (size_t reserved : {1, 2, 3, 4 + 3, 8 + 3})
        CHECK(load_grey_pyramid([reserved](Bytes &p) { p[reserved] = 1; }) == DSN_ERR_PYRAMID);
    CHECK(load_grey_pyramid([](Bytes &p) { p[4] = 2; }) == DSN_ERR_PYRAMID);  // even width
    CHECK(load_grey_pyramid([](Bytes &p) { p[9] = 0; }) == DSN_ERR_PYRAMID);  // zero height
    CHECK(load_grey_pyramid([](Bytes &p) { p[6] = 25; }) == DSN_ERR_PYRAMID); // exponent above 24
    CHECK(load_grey_pyramid([](Bytes &p) { p[10] = uint8_t(-25 & 0xFF); }) == DSN_ERR_PYRAMID);
    CHECK(load_grey_pyramid([](Bytes &p) { p[6] = 24; }) == DSN_OK);
    CHECK(load_grey_pyramid([](Bytes &p) { p[10] = uint8_t(-24 & 0xFF); }) == DSN_OK);
    CHECK(load_grey_pyramid([](Bytes &p) { p[4] = 1; }) == DSN_ERR_PYRAMID); // 6 values fewer than stored
    CHECK(load_grey_pyramid([](Bytes &p) { p.pop_back(); }) == DSN_ERR_PYRAMID);
    CHECK(load_grey_pyramid([](Bytes &p) { p.push_back(1); }) == DSN_ERR_PYRAMID);
    CHECK(load_grey_pyramid([](Bytes &p) { p.resize(4); }) == DSN_ERR_PYRAMID); // no room for the records
    CHECK(load_grey_pyramid([](Bytes &p) { p.resize(2); }) == DSN_ERR_PYRAMID); // no room for the count
    CHECK(load_grey_pyramid([](Bytes &p) { p.clear(); }) == DSN_ERR_PYRAMID);
    CHECK(load_grey_pyramid([](Bytes &p) { p[12] = 0x80; }) == DSN_ERR_PYRAMID); // reserved value -128
    CHECK(load_grey_pyramid([](Bytes &p) { p.back() = 0x80; }) == DSN_ERR_PYRAMID);
    CHECK(load_grey_pyramid([](Bytes &p) { p.back() = 0x81; }) == DSN_OK); // -127
    // 16 bits: -32768 is reserved, its byte 0x80 alone is not.
    dsn::AssetFields wide = pyramid_fields(1, 16);
    Bytes bytes = dsn::encode_asset(wide);
    const size_t values = DSN_FORMAT_HEADER_SIZE + DSN_SECTION_HEADER_SIZE + 4 + 2 * 4;
    dsn_write_u16le(&bytes[values + 2], 0x0080);
    reseal(bytes);
    CHECK(load(bytes) == DSN_OK);
    dsn_write_u16le(&bytes[values + 2], 0x8000);
    reseal(bytes);
    CHECK(load(bytes) == DSN_ERR_PYRAMID);
    // Pyramid checks come after every 1.0 check (step 15 after step 13).
    Bytes both = with_sections(pyramid_section(Bytes{0, 0, 0, 0}), 1, 1, 8);
    const uint32_t header_size = dsn_read_u32le(both.data() + DSN_OFFSET_HEADER_SIZE);
    both[header_size] = 0x80;
    reseal(both);
    CHECK(load(both) == DSN_ERR_TEXTON);
}

TEST_CASE("the writer refuses pyramids the loader would reject") {
    dsn::AssetFields fields = pyramid_fields(3, 8);
    const auto refuses = [](const dsn::AssetFields &f) {
        CHECK_THROWS_AS(dsn::encode_asset(f), std::invalid_argument);
    };
    dsn::AssetFields f = fields;
    f.pyramid.resize(9, fields.pyramid[1]);
    refuses(f);
    f = fields;
    f.pyramid[0].width = 4;
    refuses(f);
    f = fields;
    f.pyramid[1].height = 257;
    refuses(f);
    f = fields;
    f.pyramid[0].exponent = -25;
    refuses(f);
    f = fields;
    f.pyramid[1].values.pop_back();
    refuses(f);
    f = fields;
    f.pyramid[1].values[0] = -128;
    refuses(f);
    f = fields;
    f.pyramid.resize(8, fields.pyramid[1]);
    const Bytes bytes = dsn::encode_asset(f);
    dsn_asset asset;
    CHECK(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    CHECK(asset.pyramid_levels == 8);
}

namespace {

// A 1.2 file with a 4-entry mapping and no pyramid: its one section starts at byte 128.
Bytes mapped_asset(uint32_t channels) {
    dsn::AssetFields fields = dsn_test::synthetic_fields(channels, 5, 8, DSN_SHAPE_RECTANGLE, 5);
    dsn::HistogramMapping &m = fields.histogram;
    m.entry_count = 4, m.step_shift = 2, m.input_low_q16 = -131072;
    for (uint32_t i = 0; i < 4 * channels; i++) m.tables.push_back(int32_t(i * 3001 % 20000) - 10000);
    if (channels == 1)
        for (int i = 1; i < 9; i++) m.rotation[i] = 0;
    for (uint32_t c = 0; c < channels; c++) m.centre[c] = 1 << 23, m.expected_q16[c] = -100;
    return dsn::encode_asset(fields);
}

const size_t kPayload = DSN_FORMAT_HEADER_SIZE + DSN_SECTION_HEADER_SIZE; // of the one section

int load_code(const Bytes &bytes) {
    dsn_asset asset;
    return dsn_asset_load(&asset, bytes.data(), bytes.size());
}

// `valid` with its histogram payload replaced by `payload` (padded to 4 bytes), resealed.
Bytes with_payload(const Bytes &valid, const Bytes &payload) {
    const uint32_t old_size = dsn_read_u32le(&valid[DSN_FORMAT_HEADER_SIZE + 4]);
    Bytes padded = payload;
    padded.resize((payload.size() + 3) / 4 * 4, 0);
    Bytes bytes(valid.begin(), valid.begin() + long(kPayload));
    bytes.reserve(valid.size() + padded.size());
    dsn_write_u32le(&bytes[DSN_FORMAT_HEADER_SIZE + 4], uint32_t(payload.size()));
    bytes.insert(bytes.end(), padded.begin(), padded.end());
    bytes.insert(bytes.end(), valid.begin() + long(kPayload + (old_size + 3) / 4 * 4), valid.end());
    dsn_write_u32le(&bytes[DSN_OFFSET_HEADER_SIZE], dsn_read_u32le(&valid[DSN_OFFSET_HEADER_SIZE]) +
                                                        uint32_t(padded.size()) - (old_size + 3) / 4 * 4);
    dsn_write_u32le(&bytes[DSN_OFFSET_TOTAL_SIZE], uint32_t(bytes.size()));
    reseal(bytes);
    return bytes;
}

} // namespace

TEST_CASE("1.2: every failure of step 16 is DSN_ERR_HISTOGRAM") {
    for (uint32_t channels : {1u, 3u}) {
        CAPTURE(channels);
        const Bytes valid = mapped_asset(channels);
        REQUIRE(load_code(valid) == DSN_OK);
        const uint32_t size = dsn_read_u32le(&valid[DSN_FORMAT_HEADER_SIZE + 4]);
        REQUIRE(size == DSN_HISTOGRAM_HEADER_SIZE + 2 * 4 * channels);
        const Bytes payload(valid.begin() + long(kPayload), valid.begin() + long(kPayload + size));
        REQUIRE(load_code(with_payload(valid, payload)) == DSN_OK); // the helper itself changes nothing
        const auto patched = [&](size_t offset, uint32_t value, int width) {
            Bytes p = payload;
            for (int i = 0; i < width; i++) p[offset + size_t(i)] = uint8_t(value >> (8 * i));
            return load_code(with_payload(valid, p));
        };
        CHECK(patched(0, 1, 2) == DSN_ERR_HISTOGRAM);    // N = 1
        CHECK(patched(0, 1025, 2) == DSN_ERR_HISTOGRAM); // N above 1024 (size then differs too)
        CHECK(patched(2, 0, 1) == DSN_ERR_HISTOGRAM);    // M = 0
        CHECK(patched(2, 2, 1) == DSN_ERR_HISTOGRAM);    // M above 1 + no pyramid level
        CHECK(patched(3, 17, 1) == DSN_ERR_HISTOGRAM);   // s above 16
        CHECK(patched(3, 16, 1) == DSN_OK);
        CHECK(patched(56, uint32_t(DSN_HISTOGRAM_EXPECTED_LIMIT + 1), 4) == DSN_ERR_HISTOGRAM);
        CHECK(patched(56, uint32_t(-DSN_HISTOGRAM_EXPECTED_LIMIT - 1), 4) == DSN_ERR_HISTOGRAM);
        CHECK(patched(56, uint32_t(-DSN_HISTOGRAM_EXPECTED_LIMIT), 4) == DSN_OK);
        CHECK(patched(DSN_HISTOGRAM_HEADER_SIZE + 2, 0x8000, 2) == DSN_ERR_HISTOGRAM); // -32768
        CHECK(patched(DSN_HISTOGRAM_HEADER_SIZE + 2, 0x8001, 2) == DSN_OK);            // -32767
        if (channels == 1) {
            CHECK(patched(8 + 4 * 5, 1, 4) == DSN_ERR_HISTOGRAM);  // an unused rotation entry
            CHECK(patched(44 + 4 * 2, 1, 4) == DSN_ERR_HISTOGRAM); // an unused centre
            CHECK(patched(56 + 4 * 1, 1, 4) == DSN_ERR_HISTOGRAM); // an unused expected
        } else {
            CHECK(patched(8 + 4 * 5, 1, 4) == DSN_OK);
            CHECK(patched(44 + 4 * 2, 1, 4) == DSN_OK);
        }
        // Sizes that differ from 68 + 2 M N C: one table value more or less, a payload shorter than 68.
        Bytes longer = payload;
        longer.push_back(0), longer.push_back(0);
        CHECK(load_code(with_payload(valid, longer)) == DSN_ERR_HISTOGRAM);
        CHECK(load_code(with_payload(valid, Bytes(payload.begin(), payload.end() - 2))) == DSN_ERR_HISTOGRAM);
        CHECK(load_code(with_payload(valid, Bytes(payload.begin(), payload.begin() + 67))) ==
              DSN_ERR_HISTOGRAM);
        CHECK(load_code(with_payload(valid, Bytes())) == DSN_ERR_HISTOGRAM);
        // The flag without the section (its kind made unknown), the section without the flag.
        Bytes unflagged = valid, unknown_kind = valid;
        dsn_write_u32le(&unflagged[DSN_OFFSET_FLAGS], 0);
        dsn_write_u32le(&unknown_kind[DSN_FORMAT_HEADER_SIZE], 9);
        reseal(unflagged), reseal(unknown_kind);
        CHECK(load_code(unflagged) == DSN_ERR_HISTOGRAM);
        CHECK(load_code(unknown_kind) == DSN_ERR_HISTOGRAM);
    }
}

TEST_CASE("1.2: the flag and the kind-2 section count from minor 2 on; two kind-2 sections are framing") {
    const Bytes valid = mapped_asset(3);
    const uint32_t size = dsn_read_u32le(&valid[DSN_FORMAT_HEADER_SIZE + 4]);
    const Bytes one_section(valid.begin() + DSN_FORMAT_HEADER_SIZE, valid.begin() + long(kPayload + size));
    // Flags: another bit, or the flag in a minor-1 file, are reserved.
    Bytes other_bit = valid, minor_one = valid;
    dsn_write_u32le(&other_bit[DSN_OFFSET_FLAGS], DSN_FLAG_HISTOGRAM | 2u);
    dsn_write_u16le(&minor_one[DSN_OFFSET_VERSION_MINOR], 1);
    reseal(other_bit), reseal(minor_one);
    CHECK(load_code(other_bit) == DSN_ERR_RESERVED);
    CHECK(load_code(minor_one) == DSN_ERR_RESERVED);
    // In a minor-1 file kind 2 is unknown: skipped (even twice, even with bad contents).
    Bytes bad_section = one_section;
    bad_section[DSN_SECTION_HEADER_SIZE] = 0; // N = 0 (low byte of 4)
    Bytes twice = one_section;
    twice.insert(twice.end(), bad_section.begin(), bad_section.end());
    const Bytes skipped = with_sections(twice, 1, 3, 8);
    dsn_asset asset;
    REQUIRE(dsn_asset_load(&asset, skipped.data(), skipped.size()) == DSN_OK);
    CHECK(asset.histogram_table == nullptr);
    // In a minor-2 file, two kind-2 sections are a framing error (step 14, before step 16).
    Bytes duplicated = with_sections(twice, 2, 3, 8);
    dsn_write_u32le(&duplicated[DSN_OFFSET_FLAGS], DSN_FLAG_HISTOGRAM);
    reseal(duplicated);
    CHECK(load_code(duplicated) == DSN_ERR_SECTION);
    // The writer's file with its one section, rebuilt: loads, and its texton is the 1.0 file's.
    Bytes rebuilt = with_sections(one_section, 2, 3, 8);
    dsn_write_u32le(&rebuilt[DSN_OFFSET_FLAGS], DSN_FLAG_HISTOGRAM);
    reseal(rebuilt);
    REQUIRE(dsn_asset_load(&asset, rebuilt.data(), rebuilt.size()) == DSN_OK);
    CHECK(asset.histogram_table == rebuilt.data() + kPayload + DSN_HISTOGRAM_HEADER_SIZE);
    CHECK(asset.histogram_entries == 4);
}
