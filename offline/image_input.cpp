// image_input.cpp - load_exemplar: any image stb_image reads -> planar grey or RGB doubles in [0, 1].
#include "dsn/bake.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <sys/stat.h>

#include <stb_image.h>

namespace dsn {
namespace {

struct FileCloser {
    void operator()(FILE *file) const { std::fclose(file); }
};
struct StbFree {
    void operator()(void *pixels) const { stbi_image_free(pixels); }
};

[[noreturn]] void fail(const std::string &path, const std::string &problem) {
    throw std::runtime_error(path + ": " + problem);
}

std::unique_ptr<FILE, FileCloser> open_regular_file(const std::string &path) {
    struct stat status;
    if (stat(path.c_str(), &status) != 0) fail(path, std::strerror(errno));
    if (!S_ISREG(status.st_mode)) fail(path, "not a regular file");
    std::unique_ptr<FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file) fail(path, std::strerror(errno));
    return file;
}

// A PNG whose header says 0 x 0: stb_image reports it only as an unknown image type.
bool is_zero_size_png(FILE *file) {
    unsigned char header[24];
    const bool read = std::fread(header, 1, sizeof header, file) == sizeof header;
    std::rewind(file);
    const unsigned char signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (!read || std::memcmp(header, signature, 8) != 0 || std::memcmp(header + 12, "IHDR", 4) != 0)
        return false;
    const auto zero = [](const unsigned char *field) {
        return (field[0] | field[1] | field[2] | field[3]) == 0;
    };
    return zero(header + 16) || zero(header + 20);
}

// Channels kept: grey (+alpha) -> 1, RGB(A) -> 3.
int kept_channels(int stored_channels) { return stored_channels <= 2 ? 1 : 3; }

template <typename Sample>
Image to_planar(const Sample *pixels, int width, int height, int stored_channels, double maximum) {
    Image image;
    image.width = width;
    image.height = height;
    image.channels = kept_channels(stored_channels);
    image.values.resize(size_t(width) * size_t(height) * size_t(image.channels));
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            for (int c = 0; c < image.channels; c++)
                image.at(x, y, c) =
                    pixels[(size_t(y) * size_t(width) + size_t(x)) * size_t(stored_channels) + size_t(c)] /
                    maximum;
    return image;
}

} // namespace

Image load_exemplar(const std::string &path, std::vector<std::string> *warnings) {
    auto file = open_regular_file(path);
    int width = 0, height = 0, stored_channels = 0;
    if (is_zero_size_png(file.get())) fail(path, "image has zero size");
    if (!stbi_info_from_file(file.get(), &width, &height, &stored_channels))
        fail(path, std::string("not a readable image (") + stbi_failure_reason() + ")");
    if (width <= 0 || height <= 0) fail(path, "image has zero size");
    if (width > kMaxExemplarSide || height > kMaxExemplarSide)
        fail(path, "image is " + std::to_string(width) + "x" + std::to_string(height) +
                       ", larger than the limit of " + std::to_string(kMaxExemplarSide) + " per side");
    const bool sixteen_bit = stbi_is_16_bit_from_file(file.get()) != 0;
    Image image;
    if (sixteen_bit) {
        std::unique_ptr<stbi_us, StbFree> pixels(
            stbi_load_from_file_16(file.get(), &width, &height, &stored_channels, 0));
        if (!pixels) fail(path, std::string("cannot decode image (") + stbi_failure_reason() + ")");
        image = to_planar(pixels.get(), width, height, stored_channels, 65535.0);
    } else {
        std::unique_ptr<stbi_uc, StbFree> pixels(
            stbi_load_from_file(file.get(), &width, &height, &stored_channels, 0));
        if (!pixels) fail(path, std::string("cannot decode image (") + stbi_failure_reason() + ")");
        image = to_planar(pixels.get(), width, height, stored_channels, 255.0);
    }
    if ((stored_channels == 2 || stored_channels == 4) && warnings)
        warnings->push_back(path + ": alpha channel ignored");
    return image;
}

} // namespace dsn
