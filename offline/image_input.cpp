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

struct StbFree {
    void operator()(void *pixels) const { stbi_image_free(pixels); }
};

[[noreturn]] void fail(const std::string &name, const std::string &problem) {
    throw std::runtime_error(name + ": " + problem);
}

// Reads the whole file, refusing what is not a regular file or is larger than any image we accept.
std::vector<unsigned char> read_regular_file(const std::string &path) {
    struct stat status;
    if (stat(path.c_str(), &status) != 0) fail(path, std::strerror(errno));
    if (!S_ISREG(status.st_mode)) fail(path, "not a regular file");
    if (uint64_t(status.st_size) > kMaxExemplarFileBytes)
        fail(path,
             "file is larger than the limit of " + std::to_string(kMaxExemplarFileBytes >> 20) + " MiB");
    FILE *file = std::fopen(path.c_str(), "rb");
    if (!file) fail(path, std::strerror(errno));
    std::vector<unsigned char> bytes(size_t(status.st_size));
    const size_t read = std::fread(bytes.data(), 1, bytes.size(), file);
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed || read != bytes.size()) fail(path, "read error");
    return bytes;
}

// A PNG whose header says 0 x 0: stb_image reports it only as an unknown image type.
bool is_zero_size_png(const unsigned char *bytes, size_t size) {
    const unsigned char signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (size < 24 || std::memcmp(bytes, signature, 8) != 0 || std::memcmp(bytes + 12, "IHDR", 4) != 0)
        return false;
    const auto zero = [](const unsigned char *field) {
        return (field[0] | field[1] | field[2] | field[3]) == 0;
    };
    return zero(bytes + 16) || zero(bytes + 20);
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

Image decode_exemplar(const unsigned char *bytes, size_t size, const std::string &name,
                      std::vector<std::string> *warnings) {
    if (size > kMaxExemplarFileBytes) fail(name, "file is too large");
    const int length = int(size);
    int width = 0, height = 0, stored_channels = 0;
    if (is_zero_size_png(bytes, size)) fail(name, "image has zero size");
    if (!stbi_info_from_memory(bytes, length, &width, &height, &stored_channels))
        fail(name, std::string("not a readable image (") + stbi_failure_reason() + ")");
    if (width <= 0 || height <= 0) fail(name, "image has zero size");
    if (width > kMaxExemplarSide || height > kMaxExemplarSide)
        fail(name, "image is " + std::to_string(width) + "x" + std::to_string(height) +
                       ", larger than the limit of " + std::to_string(kMaxExemplarSide) + " per side");
    Image image;
    if (stbi_is_16_bit_from_memory(bytes, length)) {
        std::unique_ptr<stbi_us, StbFree> pixels(
            stbi_load_16_from_memory(bytes, length, &width, &height, &stored_channels, 0));
        if (!pixels) fail(name, std::string("cannot decode image (") + stbi_failure_reason() + ")");
        image = to_planar(pixels.get(), width, height, stored_channels, 65535.0);
    } else {
        std::unique_ptr<stbi_uc, StbFree> pixels(
            stbi_load_from_memory(bytes, length, &width, &height, &stored_channels, 0));
        if (!pixels) fail(name, std::string("cannot decode image (") + stbi_failure_reason() + ")");
        image = to_planar(pixels.get(), width, height, stored_channels, 255.0);
    }
    if ((stored_channels == 2 || stored_channels == 4) && warnings)
        warnings->push_back(name + ": alpha channel ignored");
    return image;
}

Image load_exemplar(const std::string &path, std::vector<std::string> *warnings) {
    const std::vector<unsigned char> bytes = read_regular_file(path);
    return decode_exemplar(bytes.data(), bytes.size(), path, warnings);
}

} // namespace dsn
