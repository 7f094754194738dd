// bake_input_test.cpp - load_exemplar: bit depths, channel layouts, and every kind of bad file.
#include <doctest/doctest.h>

#include <filesystem>
#include <stdexcept>

#include "dsn/bake.h"
#include "fixtures/bake_fixtures.h"

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
