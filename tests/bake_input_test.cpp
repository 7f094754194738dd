// bake_input_test.cpp - load_exemplar: bit depths, channel layouts, and every kind of bad file.
#include <doctest/doctest.h>

#include <filesystem>
#include <stdexcept>

#include "dsn/bake.h"
#include "fixtures/bake_fixtures.h"

#include <stb_image_write.h>

using namespace bake_fixtures;

namespace {

std::string error_of(const std::string &path) {
    try {
        std::vector<std::string> warnings;
        dsn::load_exemplar(path, &warnings);
    } catch (const std::runtime_error &error) {
        return error.what();
    }
    return "";
}

} // namespace

TEST_CASE("load_exemplar reads 8- and 16-bit grey, grey+alpha, RGB and RGBA PNGs into [0, 1]") {
    const std::string folder = temporary_folder();
    struct Case {
        int depth, colour_type, expected_channels;
        bool warns;
    };
    const Case cases[] = {{8, 0, 1, false},  {8, 4, 1, true},  {8, 2, 3, false},  {8, 6, 3, true},
                          {16, 0, 1, false}, {16, 4, 1, true}, {16, 2, 3, false}, {16, 6, 3, true}};
    for (const Case &test : cases) {
        CAPTURE(test.depth);
        CAPTURE(test.colour_type);
        const int width = 5, height = 3;
        const int per_pixel = test.colour_type == 0   ? 1
                              : test.colour_type == 2 ? 3
                              : test.colour_type == 4 ? 2
                                                      : 4;
        const unsigned maximum = test.depth == 16 ? 65535u : 255u;
        std::vector<unsigned> samples;
        for (int i = 0; i < width * height * per_pixel; i++)
            samples.push_back(unsigned(i * 7919) % (maximum + 1));
        const std::string path = folder + "/image.png";
        write_bytes(path, encode_png(width, height, test.depth, test.colour_type, samples));
        std::vector<std::string> warnings;
        const dsn::Image image = dsn::load_exemplar(path, &warnings);
        REQUIRE(image.width == width);
        REQUIRE(image.height == height);
        REQUIRE(image.channels == test.expected_channels);
        CHECK(warnings.size() == (test.warns ? 1u : 0u));
        for (int y = 0; y < height; y++)
            for (int x = 0; x < width; x++)
                for (int c = 0; c < image.channels; c++) {
                    const unsigned sample = samples[size_t((y * width + x) * per_pixel + c)];
                    CHECK(image.at(x, y, c) == double(sample) / maximum); // exact: both are the same division
                }
    }
    std::filesystem::remove_all(folder);
}

TEST_CASE("load_exemplar refuses bad files with a message naming the problem") {
    const std::string folder = temporary_folder();
    std::vector<unsigned> samples(64 * 64, 100);
    const std::vector<unsigned char> png = encode_png(64, 64, 8, 0, samples);

    write_bytes(folder + "/text.png", std::vector<unsigned char>{'h', 'e', 'l', 'l', 'o', '\n'});
    write_bytes(folder + "/truncated.png",
                std::vector<unsigned char>(png.begin(), png.begin() + long(png.size() / 2)));
    write_bytes(folder + "/empty.png", {});
    // A valid header claiming 5000 x 5000: refused from stbi_info, before any decoding.
    std::vector<unsigned char> huge = encode_png(1, 1, 8, 0, {0});
    huge[16 + 2] = 0x13, huge[16 + 3] = 0x88, huge[20 + 2] = 0x13, huge[20 + 3] = 0x88;
    write_bytes(folder + "/huge.png", huge);

    CHECK(error_of(folder + "/missing.png").find("No such file") != std::string::npos);
    CHECK(error_of(folder).find("not a regular file") != std::string::npos);
    CHECK(error_of(folder + "/text.png").find("not a readable image") != std::string::npos);
    CHECK(error_of(folder + "/empty.png").find("not a readable image") != std::string::npos);
    CHECK(error_of(folder + "/huge.png").find("larger than the limit") != std::string::npos);
    const std::string truncated = error_of(folder + "/truncated.png");
    CHECK(truncated.find("cannot decode") != std::string::npos);
    CHECK(truncated.find('\n') == std::string::npos);
    std::filesystem::remove_all(folder);
}

namespace {

std::string decode_error(const std::vector<unsigned char> &bytes,
                         std::vector<std::string> *warnings = nullptr) {
    try {
        dsn::decode_exemplar(bytes.data(), bytes.size(), "input", warnings);
    } catch (const std::runtime_error &error) {
        return error.what();
    }
    return "";
}

std::vector<unsigned char> bytes_of(const std::string &text) {
    return std::vector<unsigned char>(text.begin(), text.end());
}

// A binary PGM/PPM: header, then the samples (1 byte each up to maxval 255, else 2 bytes big-endian).
std::vector<unsigned char> pnm(char kind, int width, int height, unsigned maximum,
                               const std::vector<unsigned> &samples) {
    std::vector<unsigned char> bytes =
        bytes_of(std::string("P") + kind + "\n# made by the test\n" + std::to_string(width) + " " +
                 std::to_string(height) + "\n" + std::to_string(maximum) + "\n");
    for (unsigned sample : samples) {
        if (maximum > 255) bytes.push_back((unsigned char)(sample >> 8));
        bytes.push_back((unsigned char)(sample & 0xFFu));
    }
    return bytes;
}

// A PNG chunk (CRC left 0: stb_image does not check it).
void append_chunk(std::vector<unsigned char> &png, const char *type, const std::vector<unsigned char> &data) {
    for (int shift = 24; shift >= 0; shift -= 8) png.push_back((unsigned char)(data.size() >> shift));
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), data.begin(), data.end());
    png.insert(png.end(), 4, 0);
}

// A 64x64 grey PNG whose zlib stream inflates to about `expanded` bytes: one literal 0, then matches of
// length 258 at distance 1 (a fixed-Huffman block: 13 bits per 258 bytes).
std::vector<unsigned char> deflate_bomb_png(size_t expanded) {
    std::vector<unsigned char> stream = {0x78, 0x01};
    uint32_t bits = 0;
    int count = 0;
    auto put = [&](uint32_t value, int length) { // LSB first
        bits |= value << count;
        count += length;
        while (count >= 8) {
            stream.push_back((unsigned char)(bits & 0xFF));
            bits >>= 8;
            count -= 8;
        }
    };
    auto put_code = [&](uint32_t code, int length) { // Huffman codes go MSB first
        for (int i = length - 1; i >= 0; i--) put((code >> i) & 1u, 1);
    };
    put(1, 1);         // final block
    put(1, 2);         // fixed Huffman
    put_code(0x30, 8); // literal 0
    size_t done = 1;
    for (; done + 258 <= expanded; done += 258) {
        put_code(0xC5, 8); // length code 285: 258
        put_code(0, 5);    // distance code 0: 1
    }
    for (; done < expanded; done++) put_code(0x30, 8);
    put_code(0, 7); // end of block
    put(0, 7);
    std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    append_chunk(png, "IHDR", {0, 0, 0, 64, 0, 0, 0, 64, 8, 0, 0, 0, 0});
    append_chunk(png, "IDAT", stream);
    append_chunk(png, "IEND", {});
    return png;
}

} // namespace

TEST_CASE("decode_exemplar reads binary PGM and PPM by their own maxval and refuses truncated ones") {
    for (unsigned maximum : {1u, 15u, 255u, 4095u, 65535u}) {
        CAPTURE(maximum);
        std::vector<unsigned> samples;
        for (unsigned i = 0; i < 6 * 4 * 3; i++) samples.push_back(i * 7919u % (maximum + 1));
        const dsn::Image grey = dsn::decode_exemplar(
            pnm('5', 6, 4, maximum, {samples.begin(), samples.begin() + 24}).data(),
            pnm('5', 6, 4, maximum, {samples.begin(), samples.begin() + 24}).size(), "grey", nullptr);
        REQUIRE(grey.channels == 1);
        for (int y = 0; y < 4; y++)
            for (int x = 0; x < 6; x++)
                CHECK(grey.at(x, y, 0) == double(samples[size_t(y * 6 + x)]) / maximum);
        const std::vector<unsigned char> ppm = pnm('6', 6, 4, maximum, samples);
        const dsn::Image rgb = dsn::decode_exemplar(ppm.data(), ppm.size(), "rgb", nullptr);
        REQUIRE(rgb.channels == 3);
        for (int y = 0; y < 4; y++)
            for (int x = 0; x < 6; x++)
                for (int c = 0; c < 3; c++)
                    CHECK(rgb.at(x, y, c) == double(samples[size_t((y * 6 + x) * 3 + c)]) / maximum);
        // Every length short of the whole is refused, never read past its end.
        for (size_t cut = 3; cut < ppm.size(); cut += 7) {
            CAPTURE(cut);
            const std::string error =
                decode_error(std::vector<unsigned char>(ppm.begin(), ppm.begin() + long(cut)));
            CHECK(error.find("truncated") != std::string::npos);
        }
    }
    // 64x64 RGB with 6000 of its 12288 bytes: refused, naming how much is there.
    std::vector<unsigned char> short_ppm = pnm('6', 64, 64, 255, std::vector<unsigned>(64 * 64 * 3, 9));
    short_ppm.resize(short_ppm.size() - (12288 - 6000));
    CHECK(decode_error(short_ppm).find("truncated PPM: 6000 of the 12288 bytes") != std::string::npos);
    CHECK(decode_error(pnm('5', 2, 2, 15, {1, 2, 16, 3})).find("sample 16 is above the maxval 15") !=
          std::string::npos);
    CHECK(decode_error(pnm('5', 2, 2, 0, {0, 0, 0, 0})).find("maxval 0") != std::string::npos);
    CHECK(decode_error(pnm('5', 2, 2, 70000, {0, 0, 0, 0})).find("maxval 70000") != std::string::npos);
}

TEST_CASE("decode_exemplar refuses the formats it does not read by name, before decoding anything") {
    const std::string hdr =
        std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 64 +X 64\n") + "\002\002\000\100";
    CHECK(decode_error(bytes_of(hdr)).find("Radiance HDR images are not accepted") != std::string::npos);
    CHECK(decode_error(bytes_of("BM\066\0\0\0\0\0\0\0\066\0\0\0")).find("BMP images are not accepted") !=
          std::string::npos);
    CHECK(decode_error(bytes_of("GIF89a\4\0\4\0")).find("GIF images are not accepted") != std::string::npos);
    CHECK(decode_error(bytes_of("8BPS\0\1")).find("PSD images are not accepted") != std::string::npos);
    CHECK(decode_error(bytes_of("P2\n2 2\n255\n1 2 3 4\n")).find("P1-P4") != std::string::npos);
    // A TGA has no signature: it is not a readable image, and the message lists what is.
    const std::vector<unsigned char> tga = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 4, 0, 24, 0, 1, 2, 3};
    CHECK(decode_error(tga).find("not PNG, JPEG or binary PGM/PPM") != std::string::npos);
}

TEST_CASE("decode_exemplar bounds a PNG's decompression by its declared size") {
    // 64x64 grey needs 4160 bytes; this stream inflates to 64 MiB.
    const std::vector<unsigned char> bomb = deflate_bomb_png(size_t(64) << 20);
    CHECK(bomb.size() < 500000);
    CHECK(decode_error(bomb).find("expands beyond what a 64x64 image needs") != std::string::npos);
    // The same construction, expanding to exactly the rows it needs, decodes.
    const dsn::Image image = dsn::decode_exemplar(deflate_bomb_png(64 * 65).data(),
                                                  deflate_bomb_png(64 * 65).size(), "fits", nullptr);
    CHECK(image.width == 64);
}

TEST_CASE("decode_exemplar's messages name the real problem") {
    std::vector<unsigned> samples(30 * 30 * 4, 255);
    for (size_t i = 0; i < samples.size(); i += 4) samples[i] = unsigned(i * 31 % 256);
    std::vector<std::string> warnings;
    // An opaque alpha channel loses nothing when dropped: no warning.
    dsn::decode_exemplar(encode_png(30, 30, 8, 6, samples).data(), encode_png(30, 30, 8, 6, samples).size(),
                         "opaque", &warnings);
    CHECK(warnings.empty());
    // A PNG declaring 30000 x 30000 is refused as too large (not as an unknown type).
    std::vector<unsigned char> huge = encode_png(1, 1, 8, 0, {0});
    huge[16 + 2] = 0x75, huge[16 + 3] = 0x30, huge[20 + 2] = 0x75, huge[20 + 3] = 0x30;
    CHECK(decode_error(huge).find("30000x30000, larger than the limit of 2048") != std::string::npos);
    CHECK(decode_error(huge).find(
              "crop it (keeps the texture's scale), e.g. convert IN -gravity center -crop 2048x2048") !=
          std::string::npos);
    // A truncated JPEG is called a JPEG.
    const unsigned char jpeg_start[] = {0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x10, 'J', 'F', 'I', 'F',
                                        0,    1,    1,    0,    0,    1,    0,   1,   0,   0};
    const std::string jpeg_error =
        decode_error(std::vector<unsigned char>(std::begin(jpeg_start), std::end(jpeg_start)));
    CHECK(jpeg_error.find("JPEG") != std::string::npos);
    CHECK(jpeg_error.find("png") == std::string::npos);
}

namespace {

void append_bytes(void *context, void *data, int size) {
    auto *bytes = static_cast<std::vector<unsigned char> *>(context);
    bytes->insert(bytes->end(), static_cast<unsigned char *>(data),
                  static_cast<unsigned char *>(data) + size);
}

} // namespace

// Run under valgrind by tests/scripts/image-input-valgrind: every prefix of a file of each accepted format
// is either refused or decoded from initialised bytes only (the sum below branches on every value).
TEST_CASE("decode_exemplar on every truncation of a PNG, JPEG, PGM and PPM") {
    const int width = 24, height = 20;
    std::vector<unsigned> grey, rgb;
    std::vector<unsigned char> rgb_bytes;
    for (int i = 0; i < width * height; i++) grey.push_back(unsigned(i * 37 % 256));
    for (int i = 0; i < width * height * 3; i++) {
        rgb.push_back(unsigned(i * 53 % 4096));
        rgb_bytes.push_back((unsigned char)(i * 53 % 256));
    }
    std::vector<unsigned char> jpeg;
    REQUIRE(stbi_write_jpg_to_func(append_bytes, &jpeg, width, height, 3, rgb_bytes.data(), 90) != 0);
    const std::vector<std::pair<const char *, std::vector<unsigned char>>> files = {
        {"png", encode_png(width, height, 8, 0, grey)},
        {"png16", encode_png(width, height, 16, 2, rgb)},
        {"jpeg", jpeg},
        {"pgm", pnm('5', width, height, 255, grey)},
        {"ppm16", pnm('6', width, height, 4095, rgb)},
    };
    const auto sum_of = [](const dsn::Image &image) { // branches on every value: valgrind sees each
        double sum = 0;
        for (double value : image.values) sum += value > 0.5 ? value : -value;
        return sum;
    };
    for (const auto &file : files) {
        CAPTURE(file.first);
        for (size_t cut = 0; cut < file.second.size(); cut += cut < 64 ? 1 : 5) {
            const std::vector<unsigned char> prefix(file.second.begin(), file.second.begin() + long(cut));
            double sum = 0;
            try {
                sum = sum_of(dsn::decode_exemplar(prefix.data(), prefix.size(), "cut", nullptr));
            } catch (const std::runtime_error &) {
            }
            CHECK(sum > -1e9);
        }
        const dsn::Image whole =
            dsn::decode_exemplar(file.second.data(), file.second.size(), "whole", nullptr);
        CHECK(whole.width == width);
        CHECK(sum_of(whole) > -1e9);
    }
}

TEST_CASE("decode_exemplar refuses a JPEG Huffman table of more than 256 codes before stb_image builds it") {
    std::vector<unsigned char> pixels(16 * 16 * 3);
    for (size_t i = 0; i < pixels.size(); i++) pixels[i] = (unsigned char)(i * 29);
    std::vector<unsigned char> jpeg;
    REQUIRE(stbi_write_jpg_to_func(append_bytes, &jpeg, 16, 16, 3, pixels.data(), 90) != 0);
    const dsn::Image image = dsn::decode_exemplar(jpeg.data(), jpeg.size(), "good", nullptr);
    CHECK(image.channels == 3);
    size_t table = 0;
    for (size_t i = 2; i + 1 < jpeg.size() && table == 0; i++)
        if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xC4) table = i + 5; // the first table's 16 counts
    REQUIRE(table != 0);
    // Counts totalling 16 x 255 codes: stb_image 2.27 would write them past its 257-entry tables.
    for (size_t i = 0; i < 16; i++) jpeg[table + i] = 0xFF;
    CHECK(decode_error(jpeg).find("Huffman table with more than 256 codes") != std::string::npos);
}

TEST_CASE("decode_exemplar reads a PNG with an empty IDAT chunk first (stb_image copied it from null)") {
    std::vector<unsigned> samples;
    for (unsigned i = 0; i < 9 * 7; i++) samples.push_back(i * 13 % 256);
    const std::vector<unsigned char> png = encode_png(9, 7, 8, 0, samples);
    std::vector<unsigned char> with_empty(png.begin(), png.begin() + 33); // signature + IHDR
    append_chunk(with_empty, "IDAT", {});
    with_empty.insert(with_empty.end(), png.begin() + 33, png.end());
    const dsn::Image plain = dsn::decode_exemplar(png.data(), png.size(), "plain", nullptr);
    const dsn::Image image =
        dsn::decode_exemplar(with_empty.data(), with_empty.size(), "empty IDAT", nullptr);
    CHECK(image.values == plain.values);
}
