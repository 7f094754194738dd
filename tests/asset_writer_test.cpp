// asset_writer_test.cpp - the .dsnt writer: byte layout, refusal of invalid fields, atomic file writes.
#include <doctest/doctest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "dsn/asset_writer.h"
#include "offline/tools/file_output.h"
#include "runtime/setup/format_bytes.h"

namespace {

dsn::AssetFields rgb_disk_asset() {
    dsn::AssetFields fields;
    fields.channels = 3;
    fields.bits = 16;
    fields.shape = DSN_SHAPE_DISK;
    fields.width = fields.height = 5;
    fields.default_impacts_q16 = 30u << 16;
    for (int c = 0; c < 3; c++) {
        fields.scale[c] = 1000u + uint32_t(c);
        fields.mean[c] = -5 - c;
    }
    fields.color_transform[1] = -7;
    fields.bake_iterations = 1000;
    fields.bake_seed = 0xDEADBEEFu;
    fields.exemplar_width = 640;
    fields.texton.assign(5 * 5 * 3, 0);
    fields.texton[(2 * 5 + 2) * 3 + 1] = -32767; // centre, green
    fields.texton[(0 * 5 + 2) * 3 + 2] = 32767;  // top of the disk, blue
    return fields;
}

std::string read_file(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

} // namespace

TEST_CASE("encode_asset lays out every field at its format.h offset, little-endian, with the CRC") {
    std::vector<unsigned char> bytes = dsn::encode_asset(rgb_disk_asset());
    const unsigned char *p = bytes.data();
    REQUIRE(bytes.size() == DSN_FORMAT_HEADER_SIZE + 5 * 5 * 3 * 2 + 4);
    CHECK(std::string(bytes.begin(), bytes.begin() + 8) == std::string(DSN_FORMAT_MAGIC, 8));
    CHECK(dsn_read_u16le(p + DSN_OFFSET_VERSION_MAJOR) == 1);
    CHECK(dsn_read_u32le(p + DSN_OFFSET_HEADER_SIZE) == DSN_FORMAT_HEADER_SIZE);
    CHECK(dsn_read_u32le(p + DSN_OFFSET_TOTAL_SIZE) == bytes.size());
    CHECK(p[DSN_OFFSET_CHANNELS] == 3);
    CHECK(p[DSN_OFFSET_BITS] == 16);
    CHECK(p[DSN_OFFSET_SHAPE] == DSN_SHAPE_DISK);
    CHECK(dsn_read_u16le(p + DSN_OFFSET_WIDTH) == 5);
    CHECK(dsn_read_u32le(p + DSN_OFFSET_DEFAULT_IMPACTS) == (30u << 16));
    CHECK(dsn_read_u32le(p + DSN_OFFSET_SCALE + 8) == 1002u);
    CHECK(dsn_read_i32le(p + DSN_OFFSET_MEAN + 4) == -6);
    CHECK(dsn_read_i32le(p + DSN_OFFSET_COLOR_TRANSFORM) == DSN_Q24_ONE);
    CHECK(dsn_read_i32le(p + DSN_OFFSET_COLOR_TRANSFORM + 4) == -7);
    CHECK(dsn_read_u32le(p + DSN_OFFSET_BAKE_SEED) == 0xDEADBEEFu);
    CHECK(dsn_read_u16le(p + DSN_OFFSET_EXEMPLAR_WIDTH) == 640);
    for (unsigned i = DSN_OFFSET_RESERVED; i < DSN_FORMAT_HEADER_SIZE; i++) CHECK(p[i] == 0);
    CHECK(dsn_read_i16le(p + DSN_FORMAT_HEADER_SIZE + 2 * ((2 * 5 + 2) * 3 + 1)) == -32767);
    CHECK(dsn_read_i16le(p + DSN_FORMAT_HEADER_SIZE + 2 * ((0 * 5 + 2) * 3 + 2)) == 32767);
    size_t body = bytes.size() - 4;
    CHECK(dsn_read_u32le(p + body) == dsn_crc32(0, p, body));
}

TEST_CASE("encode_asset refuses every field the loader would reject") {
    struct Case {
        const char *name;
        void (*spoil)(dsn::AssetFields &);
    };
    const Case cases[] = {
        {"channels 2", [](dsn::AssetFields &f) { f.channels = 2; }},
        {"bits 12", [](dsn::AssetFields &f) { f.bits = 12; }},
        {"shape 2", [](dsn::AssetFields &f) { f.shape = 2; }},
        {"interpolation 2", [](dsn::AssetFields &f) { f.interpolation = 2; }},
        {"even width",
         [](dsn::AssetFields &f) {
             f.width = 4;
             f.shape = DSN_SHAPE_RECTANGLE;
         }},
        {"width 257",
         [](dsn::AssetFields &f) {
             f.width = 257;
             f.shape = DSN_SHAPE_RECTANGLE;
         }},
        {"non-square disk", [](dsn::AssetFields &f) { f.height = 3; }},
        {"impacts too small", [](dsn::AssetFields &f) { f.default_impacts_q16 = 1; }},
        {"impacts too large", [](dsn::AssetFields &f) { f.default_impacts_q16 = DSN_IMPACTS_MAX_Q16 + 1; }},
        {"zero scale", [](dsn::AssetFields &f) { f.scale[1] = 0; }},
        {"short texton", [](dsn::AssetFields &f) { f.texton.pop_back(); }},
        {"value -32768", [](dsn::AssetFields &f) { f.texton[0 + 2 * 3] = -32768; }},
        {"outside the disk", [](dsn::AssetFields &f) { f.texton[0] = 1; }},
        {"unused channel mean",
         [](dsn::AssetFields &f) {
             f.channels = 1;
             f.scale[1] = f.scale[2] = 0;
             f.texton.resize(25);
             f.mean[2] = 0;
             f.mean[1] = 3;
             dsn::set_identity_color_transform(f);
         }},
        {"grey off-diagonal",
         [](dsn::AssetFields &f) {
             f.channels = 1;
             f.scale[1] = f.scale[2] = 0;
             f.mean[1] = f.mean[2] = 0;
             f.texton.resize(25);
             dsn::set_identity_color_transform(f);
             f.color_transform[4] = 1;
         }},
    };
    CHECK_NOTHROW(dsn::encode_asset(rgb_disk_asset()));
    for (const Case &c : cases) {
        CAPTURE(c.name);
        dsn::AssetFields fields = rgb_disk_asset();
        c.spoil(fields);
        CHECK_THROWS_AS(dsn::encode_asset(fields), std::invalid_argument);
    }
}

TEST_CASE("write_file_atomically replaces the file whole and leaves it untouched on failure") {
    char folder_template[] = "/tmp/dsn-writer-XXXXXX";
    REQUIRE(mkdtemp(folder_template) != nullptr);
    const std::string folder = folder_template, path = folder + "/a.dsnt";
    dsn::write_file_atomically(path, {1, 2, 3});
    dsn::write_file_atomically(path, {4, 5});
    CHECK(read_file(path) == std::string("\x04\x05", 2));

    CHECK_THROWS_AS(dsn::write_file_atomically(folder + "/missing/b.dsnt", {1}), std::runtime_error);
    CHECK_THROWS_AS(dsn::write_file_atomically(folder, {1}), std::runtime_error);
    CHECK_THROWS_AS(dsn::write_file_atomically("/dev/full", {1}), std::runtime_error);
    CHECK(read_file(path) == std::string("\x04\x05", 2));
    // Only a.dsnt is left: no temporary file survives.
    CHECK(std::remove(path.c_str()) == 0);
    CHECK(rmdir(folder.c_str()) == 0);
}

TEST_CASE("write_files_atomically writes every file or none, and same_file sees through path spellings") {
    char folder_template[] = "/tmp/dsn-writer-XXXXXX";
    REQUIRE(mkdtemp(folder_template) != nullptr);
    const std::string folder = folder_template;
    const std::string a = folder + "/a.dsnt", b = folder + "/b.json";
    dsn::write_files_atomically({{a, {1}}, {b, {2}}});
    CHECK(read_file(a) == "\x01");
    CHECK(read_file(b) == "\x02");

    // The second destination is refused: the first is not replaced either, and no temporary remains.
    CHECK_THROWS_AS(dsn::write_files_atomically({{a, {9}}, {"/dev/full", {9}}}), std::runtime_error);
    CHECK_THROWS_AS(dsn::write_files_atomically({{a, {9}}, {folder + "/missing/c", {9}}}),
                    std::runtime_error);
    CHECK_THROWS_AS(dsn::write_files_atomically({{a, {9}}, {folder + "/./a.dsnt", {9}}}), std::runtime_error);
    CHECK(read_file(a) == "\x01");

    CHECK(dsn::same_file(a, folder + "/../" + folder.substr(folder.rfind('/') + 1) + "/a.dsnt"));
    CHECK(dsn::same_file(folder + "/new.png", folder + "/./new.png"));
    CHECK_FALSE(dsn::same_file(a, b));
    CHECK_FALSE(dsn::same_file(a, folder + "/new.png"));

    CHECK(std::remove(a.c_str()) == 0);
    CHECK(std::remove(b.c_str()) == 0);
    CHECK(rmdir(folder.c_str()) == 0); // fails if a temporary file was left behind
}
