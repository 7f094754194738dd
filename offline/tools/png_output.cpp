// png_output.cpp - encode_png: 8-bit pixels -> the bytes of a PNG file (stb_image_write); encode_png_16:
// 16-bit pixels -> a PNG file whose zlib stream holds stored (uncompressed) deflate blocks.
#include "png_output.h"

#include <algorithm>
#include <climits>
#include <cstddef>
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

void append_u32_big_endian(std::vector<unsigned char> &bytes, uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8) bytes.push_back(static_cast<unsigned char>(value >> shift));
}

uint32_t crc32(const unsigned char *data, size_t size, uint32_t crc = 0) {
    crc = ~crc;
    for (size_t i = 0; i < size; i++) {
        crc ^= data[i];
        for (int bit = 0; bit < 8; bit++) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

// A chunk: length, type, data, CRC of type and data.
void append_chunk(std::vector<unsigned char> &png, const char *type, const std::vector<unsigned char> &data) {
    append_u32_big_endian(png, static_cast<uint32_t>(data.size()));
    const size_t type_at = png.size();
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), data.begin(), data.end());
    append_u32_big_endian(png, crc32(&png[type_at], png.size() - type_at));
}

} // namespace

std::vector<unsigned char> encode_png_16(int width, int height, int channels, const uint16_t *samples) {
    // A chunk holds at most 2^31 - 1 bytes: the limit below keeps the whole zlib stream (the rows and 5
    // bytes per 65535) under it.
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
        uint64_t(width) * uint64_t(height) * uint64_t(channels) * 2 + uint64_t(height) >
            (uint64_t(1) << 31) - (uint64_t(1) << 26))
        throw std::invalid_argument("encode_png_16: invalid image size");
    // Filter type 0 (none) before every row, samples big-endian.
    const size_t row_bytes = size_t(width) * size_t(channels) * 2;
    std::vector<unsigned char> raw;
    raw.reserve((row_bytes + 1) * size_t(height));
    for (int y = 0; y < height; y++) {
        raw.push_back(0);
        const uint16_t *row = samples + size_t(y) * size_t(width) * size_t(channels);
        for (size_t i = 0; i < size_t(width) * size_t(channels); i++) {
            raw.push_back(static_cast<unsigned char>(row[i] >> 8));
            raw.push_back(static_cast<unsigned char>(row[i] & 0xFF));
        }
    }
    // zlib: header, stored blocks of at most 65535 bytes, Adler-32 of the raw data.
    std::vector<unsigned char> zlib = {0x78, 0x01};
    zlib.reserve(raw.size() + raw.size() / 65535 * 5 + 16);
    uint32_t adler_a = 1, adler_b = 0;
    for (size_t at = 0;;) { // raw is never empty: every row has its filter byte
        const size_t length = std::min<size_t>(65535, raw.size() - at);
        const bool last = at + length == raw.size();
        zlib.push_back(last ? 1 : 0);
        zlib.push_back(static_cast<unsigned char>(length & 0xFF));
        zlib.push_back(static_cast<unsigned char>(length >> 8));
        zlib.push_back(static_cast<unsigned char>(~length & 0xFF));
        zlib.push_back(static_cast<unsigned char>((~length >> 8) & 0xFF));
        zlib.insert(zlib.end(), raw.begin() + static_cast<std::ptrdiff_t>(at),
                    raw.begin() + static_cast<std::ptrdiff_t>(at + length));
        for (size_t i = at; i < at + length; i++) {
            adler_a = (adler_a + raw[i]) % 65521u;
            adler_b = (adler_b + adler_a) % 65521u;
        }
        at += length;
        if (last) break;
    }
    append_u32_big_endian(zlib, (adler_b << 16) | adler_a);

    static const unsigned char kColorTypes[5] = {0, 0, 4, 2, 6}; // grey, grey + alpha, RGB, RGBA
    std::vector<unsigned char> header;
    append_u32_big_endian(header, static_cast<uint32_t>(width));
    append_u32_big_endian(header, static_cast<uint32_t>(height));
    header.insert(header.end(), {16, kColorTypes[channels], 0, 0, 0});
    std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    append_chunk(png, "IHDR", header);
    append_chunk(png, "IDAT", zlib);
    append_chunk(png, "IEND", {});
    return png;
}

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
