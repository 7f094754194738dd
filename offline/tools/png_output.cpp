// png_output.cpp - encode_png: 8-bit pixels -> the bytes of a PNG file (stb_image_write).
#include "png_output.h"

#include <climits>
#include <cstdint>
#include <stdexcept>

#include <stb_image_write.h>

namespace dsn {
namespace {

void append_bytes(void *context, void *data, int size) {
    auto *bytes = static_cast<std::vector<unsigned char> *>(context);
    const auto *begin = static_cast<const unsigned char *>(data);
    bytes->insert(bytes->end(), begin, begin + size);
}

} // namespace

std::vector<unsigned char> encode_png(int width, int height, int channels, const unsigned char *pixels) {
    // stb_image_write holds the filtered rows, (width * channels + 1) * height bytes, in an int.
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 || width > (1 << 24) / channels ||
        (uint64_t(width) * uint64_t(channels) + 1) * uint64_t(height) > uint64_t(INT_MAX))
        throw std::invalid_argument("encode_png: image too large for a PNG of stb_image_write");
    std::vector<unsigned char> png;
    if (!stbi_write_png_to_func(append_bytes, &png, width, height, channels, pixels, width * channels))
        throw std::runtime_error("PNG encoding failed");
    return png;
}

} // namespace dsn
