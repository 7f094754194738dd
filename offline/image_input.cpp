// image_input.cpp - load_exemplar: a PNG, JPEG or binary PGM/PPM file -> planar grey or RGB doubles in
// [0, 1]. Every other format is refused by name.
//
// PNG and JPEG are decoded by stb_image (Debian's libstb-dev header), compiled here with only those two
// decoders: the others (HDR, TGA, BMP, PSD, GIF, PIC, and stb's PNM reader) do not reject truncated
// files or ignore the declared value range. Every allocation stb makes is bounded by what the declared
// size needs, so a small file cannot inflate to gigabytes. PGM/PPM is read here: a short file is an
// error and samples are divided by the file's own maxval.
#include "dsn/bake.h"
#include "file_input.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace dsn {
namespace {

// The largest single allocation stb_image may make while decoding the current image (set per decode from
// the declared size), and whether it asked for more.
thread_local size_t allocation_limit = 0;
thread_local bool allocation_refused = false;

// What stb_image holds while it decodes, so that a decode abandoned by a failed check (below) frees it.
// A fixed table (a decode holds a few blocks; more is refused like an oversized one), which keeps the
// thread_local trivially destructible (the wasm32-wasi build has no thread-exit destructors).
constexpr size_t kMaxLiveAllocations = 64;
thread_local void *live_allocations[kMaxLiveAllocations];
thread_local size_t live_count = 0;

void forget(void *pointer) {
    for (size_t i = 0; i < live_count; i++)
        if (live_allocations[i] == pointer) {
            live_allocations[i] = live_allocations[--live_count];
            return;
        }
}

void *limited_malloc(size_t size) {
    if (size > allocation_limit || live_count == kMaxLiveAllocations) {
        allocation_refused = true;
        return nullptr;
    }
    // Zeroed: stb_image 2.27 decodes a JPEG scan with a Huffman table that no DHT segment defined from
    // whatever its allocation held (found by make fuzz); zeros make that decode defined and repeatable.
    void *pointer = std::calloc(size, 1);
    if (pointer) live_allocations[live_count++] = pointer;
    return pointer;
}

void *limited_realloc(void *pointer, size_t size) {
    if (size > allocation_limit || (pointer == nullptr && live_count == kMaxLiveAllocations)) {
        allocation_refused = true;
        return nullptr;
    }
    forget(pointer);
    void *moved = std::realloc(pointer, size);
    if (moved)
        live_allocations[live_count++] = moved;
    else if (pointer)
        live_allocations[live_count++] = pointer; // still stb's: a failed realloc keeps it
    return moved;
}

void limited_free(void *pointer) {
    forget(pointer);
    std::free(pointer);
}

// stb_image 2.27 checks its JPEG Huffman decoding with an assert that corrupt data can fail (after the
// fuzzer found it): aborting the tool is no answer to a bad file, so a failed check abandons the decode
// (DecoderCheckFailed) and every allocation of it is freed.
struct DecoderCheckFailed {};
[[noreturn]] void decoder_check_failed() { throw DecoderCheckFailed(); }

} // namespace
} // namespace dsn

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#define STBI_MAX_DIMENSIONS 65535
#define STBI_MALLOC(size) dsn::limited_malloc(size)
#define STBI_REALLOC(pointer, size) dsn::limited_realloc(pointer, size)
#define STBI_FREE(pointer) dsn::limited_free(pointer)
#define STBI_ASSERT(condition) ((condition) ? (void)0 : dsn::decoder_check_failed())
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#pragma GCC diagnostic ignored "-Wtype-limits"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#endif
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace dsn {
namespace {

struct StbFree {
    void operator()(void *pixels) const { limited_free(pixels); }
};

[[noreturn]] void fail(const std::string &name, const std::string &problem) {
    throw std::runtime_error(name + ": " + problem);
}

enum class Format { png, jpeg, pnm, unknown };

bool starts_with(const unsigned char *bytes, size_t size, const char *signature, size_t length) {
    return size >= length && std::memcmp(bytes, signature, length) == 0;
}

// The format from the file's first bytes; the formats refused are named in the error.
Format detect_format(const unsigned char *bytes, size_t size, const std::string &name) {
    if (starts_with(bytes, size, "\x89PNG\r\n\x1a\n", 8)) return Format::png;
    if (starts_with(bytes, size, "\xff\xd8\xff", 3)) return Format::jpeg;
    if (starts_with(bytes, size, "P5", 2) || starts_with(bytes, size, "P6", 2)) return Format::pnm;
    const char *refused = nullptr;
    if (starts_with(bytes, size, "BM", 2))
        refused = "BMP";
    else if (starts_with(bytes, size, "GIF8", 4))
        refused = "GIF";
    else if (starts_with(bytes, size, "8BPS", 4))
        refused = "PSD";
    else if (starts_with(bytes, size, "#?RADIANCE", 10) || starts_with(bytes, size, "#?RGBE", 6))
        refused = "Radiance HDR";
    else if (starts_with(bytes, size, "\x53\x80\xf6\x34", 4))
        refused = "Softimage PIC";
    else if (size >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '4')
        refused = "plain-text or 1-bit PNM (P1-P4)";
    else if (starts_with(bytes, size, "RIFF", 4) && size >= 12 && std::memcmp(bytes + 8, "WEBP", 4) == 0)
        refused = "WebP";
    else if (starts_with(bytes, size, "II*\0", 4) || starts_with(bytes, size, "MM\0*", 4))
        refused = "TIFF";
    if (refused)
        fail(name, std::string(refused) + " images are not accepted (the baker reads PNG, JPEG and binary "
                                          "PGM/PPM)");
    return Format::unknown;
}

uint32_t big_endian_u32(const unsigned char *bytes) {
    return uint32_t(bytes[0]) << 24 | uint32_t(bytes[1]) << 16 | uint32_t(bytes[2]) << 8 | bytes[3];
}

void check_size(const std::string &name, uint64_t width, uint64_t height) {
    if (width == 0 || height == 0) fail(name, "image has zero size");
    if (width > uint64_t(kMaxExemplarSide) || height > uint64_t(kMaxExemplarSide))
        fail(name,
             "image is " + std::to_string(width) + "x" + std::to_string(height) +
                 ", larger than the limit of " + std::to_string(kMaxExemplarSide) +
                 " per side; crop it (keeps the texture's scale), e.g. convert IN -gravity center -crop " +
                 std::to_string(kMaxExemplarSide) + "x" + std::to_string(kMaxExemplarSide) +
                 "+0+0 +repage OUT.png, or downscale it, e.g. convert IN -resize " +
                 std::to_string(kMaxExemplarSide) + "x" + std::to_string(kMaxExemplarSide) +
                 " OUT.png (ImageMagick)");
}

// Channels kept: grey (+alpha) -> 1, RGB(A) -> 3.
int kept_channels(int stored_channels) { return stored_channels <= 2 ? 1 : 3; }

// Samples interleaved, `stored_channels` per pixel, each within [0, maximum]. Appends a warning when an
// alpha channel is dropped that is not fully opaque (an opaque one loses nothing).
template <typename Sample>
Image to_planar(const Sample *pixels, int width, int height, int stored_channels, double maximum,
                const std::string &name, std::vector<std::string> *warnings) {
    Image image;
    image.width = width;
    image.height = height;
    image.channels = kept_channels(stored_channels);
    image.values.resize(size_t(width) * size_t(height) * size_t(image.channels));
    bool translucent = false;
    const bool has_alpha = stored_channels == 2 || stored_channels == 4;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const Sample *pixel = pixels + (size_t(y) * size_t(width) + size_t(x)) * size_t(stored_channels);
            for (int c = 0; c < image.channels; c++) image.at(x, y, c) = pixel[c] / maximum;
            if (has_alpha && double(pixel[stored_channels - 1]) != maximum) translucent = true;
        }
    if (translucent && warnings) warnings->push_back(name + ": alpha channel ignored");
    return image;
}

// ---- PNG and JPEG through stb_image ----

// The largest allocation a decode of a width x height image may need: 4 channels of 16 bits plus the
// PNG filter bytes, or the compressed data itself (at most the file), and room for the decoder's tables.
size_t allocation_bound(uint64_t width, uint64_t height, size_t file_size) {
    const uint64_t pixels = width * height * 8 + height;
    return size_t((pixels > file_size ? pixels : file_size) + (uint64_t(1) << 20));
}

// stb_image 2.27 builds a JPEG Huffman table from the 16 code counts of a DHT segment without checking
// that they total at most 256: larger totals write past its tables. Every DHT segment is checked here
// first, found as stb finds them: segments skipped by their length, entropy-coded data (after SOS) scanned
// for the next marker, a byte past the end read as 0.
bool jpeg_huffman_tables_fit(const unsigned char *bytes, size_t size) {
    const auto byte = [bytes, size](size_t at) { return at < size ? unsigned(bytes[at]) : 0u; };
    size_t at = 2; // after SOI
    while (at + 1 < size) {
        if (bytes[at] != 0xFF) {
            at++;
            continue;
        }
        const unsigned marker = bytes[at + 1];
        if (marker == 0xFF) {
            at++;
            continue;
        }
        if (marker == 0x00 || (marker >= 0xD0 && marker <= 0xD8) || marker == 0x01) {
            at += 2; // stuffed 0xFF, restart marker or a stray SOI: no segment follows
            continue;
        }
        if (marker == 0xD9) return true; // EOI
        const size_t length = byte(at + 2) << 8 | byte(at + 3);
        if (marker == 0xC4) {
            long remaining = long(length) - 2;
            size_t table = at + 4;
            while (remaining > 0) {
                unsigned codes = 0;
                for (size_t i = 0; i < 16; i++) codes += byte(table + 1 + i);
                if (codes > 256) return false;
                table += 17 + codes;
                remaining -= long(17 + codes);
            }
        }
        at += 2 + length;
    }
    return true;
}

// stb_image 2.27 copies a PNG chunk of length 0 from a buffer it has not allocated yet (memcpy from
// null, undefined even for 0 bytes) when that chunk is the first IDAT. Empty IDAT chunks carry nothing:
// the copy returned, made only when there is one, leaves them out.
std::vector<unsigned char> without_empty_idat_chunks(const unsigned char *bytes, size_t size) {
    std::vector<unsigned char> kept;
    size_t at = 8, copied = 0;
    // A chunk's header (length and type) is enough to drop it: a truncated file may end before the CRC.
    while (at + 8 <= size) {
        const uint64_t length = big_endian_u32(bytes + at);
        if (length == 0 && std::memcmp(bytes + at + 4, "IDAT", 4) == 0) {
            kept.insert(kept.end(), bytes + copied, bytes + at);
            copied = std::min(at + 12, size);
        }
        if (at + 12 > size || length > size - at - 12) break;
        at += 12 + size_t(length);
    }
    if (copied == 0) return kept;
    kept.insert(kept.end(), bytes + copied, bytes + size);
    return kept;
}

// stb_image's reason for the last failure, as " (reason)", or nothing when it gave none.
std::string reason() {
    const char *text = stbi_failure_reason();
    return text && *text ? std::string(" (") + text + ")" : std::string();
}

Image decode_with_stb(const unsigned char *bytes, size_t size, Format format, const std::string &name,
                      std::vector<std::string> *warnings) {
    std::vector<unsigned char> cleaned;
    if (format == Format::png && !(cleaned = without_empty_idat_chunks(bytes, size)).empty()) {
        bytes = cleaned.data();
        size = cleaned.size();
    }
    const char *format_name = format == Format::png ? "PNG" : "JPEG";
    const int length = int(size);
    int width = 0, height = 0, stored_channels = 0;
    // The size is read from the PNG header itself, so that one too large is refused as such (stb_image
    // reports it only as an unknown image type).
    if (format == Format::png) {
        if (size < 24 || std::memcmp(bytes + 12, "IHDR", 4) != 0)
            fail(name, "truncated or corrupt PNG (no IHDR header)");
        check_size(name, big_endian_u32(bytes + 16), big_endian_u32(bytes + 20));
    }
    if (format == Format::jpeg && !jpeg_huffman_tables_fit(bytes, size))
        fail(name, "corrupt JPEG (a Huffman table with more than 256 codes)");
    allocation_limit = size_t(1) << 20;
    allocation_refused = false;
    if (!stbi_info_from_memory(bytes, length, &width, &height, &stored_channels))
        fail(name, std::string("truncated or corrupt ") + format_name + " header" + reason());
    check_size(name, uint64_t(width), uint64_t(height));
    allocation_limit = allocation_bound(uint64_t(width), uint64_t(height), size);
    allocation_refused = false;
    const bool sixteen_bits = stbi_is_16_bit_from_memory(bytes, length) != 0;
    std::unique_ptr<void, StbFree> pixels;
    live_count = 0;
    try {
        pixels.reset(sixteen_bits ? static_cast<void *>(stbi_load_16_from_memory(
                                        bytes, length, &width, &height, &stored_channels, 0))
                                  : static_cast<void *>(stbi_load_from_memory(bytes, length, &width, &height,
                                                                              &stored_channels, 0)));
    } catch (const DecoderCheckFailed &) {
        for (size_t i = 0; i < live_count; i++) std::free(live_allocations[i]);
        live_count = 0;
        allocation_limit = 0;
        fail(name, std::string("cannot decode ") + format_name + ": corrupt compressed data");
    }
    const bool refused = allocation_refused;
    allocation_limit = 0;
    if (refused)
        fail(name, std::string("cannot decode ") + format_name +
                       ": its compressed data expands beyond what a " + std::to_string(width) + "x" +
                       std::to_string(height) + " image needs");
    if (!pixels)
        fail(name, std::string("cannot decode ") + format_name + ", truncated or corrupt" + reason());
    if (sixteen_bits)
        return to_planar(static_cast<const stbi_us *>(pixels.get()), width, height, stored_channels, 65535.0,
                         name, warnings);
    return to_planar(static_cast<const stbi_uc *>(pixels.get()), width, height, stored_channels, 255.0, name,
                     warnings);
}

// ---- Binary PGM (P5) and PPM (P6) ----

// Reads the header's next whole number (after whitespace and # comments); false if there is none.
bool pnm_number(const unsigned char *bytes, size_t size, size_t &at, uint64_t &value) {
    for (;;) {
        while (at < size && std::strchr(" \t\r\n\v\f", bytes[at]) && bytes[at]) at++;
        if (at < size && bytes[at] == '#') {
            while (at < size && bytes[at] != '\n' && bytes[at] != '\r') at++;
            continue;
        }
        break;
    }
    if (at >= size || bytes[at] < '0' || bytes[at] > '9') return false;
    value = 0;
    for (int digits = 0; at < size && bytes[at] >= '0' && bytes[at] <= '9'; digits++, at++) {
        if (digits == 9) return false; // beyond any size or maxval accepted
        value = value * 10 + uint64_t(bytes[at] - '0');
    }
    return true;
}

Image decode_pnm(const unsigned char *bytes, size_t size, const std::string &name,
                 std::vector<std::string> *warnings) {
    const int stored_channels = bytes[1] == '5' ? 1 : 3;
    const char *format_name = stored_channels == 1 ? "PGM" : "PPM";
    size_t at = 2;
    uint64_t width = 0, height = 0, maximum = 0;
    if (!pnm_number(bytes, size, at, width) || !pnm_number(bytes, size, at, height) ||
        !pnm_number(bytes, size, at, maximum) || at >= size || !std::strchr(" \t\r\n\v\f", bytes[at]) ||
        !bytes[at])
        fail(name, std::string("truncated or corrupt ") + format_name + " header");
    at++; // the single whitespace byte before the samples
    check_size(name, width, height);
    if (maximum < 1 || maximum > 65535)
        fail(name,
             std::string(format_name) + " maxval " + std::to_string(maximum) + " is not within 1..65535");
    const size_t sample_bytes = maximum > 255 ? 2 : 1;
    const size_t count = size_t(width * height) * size_t(stored_channels);
    const size_t needed = count * sample_bytes;
    if (size - at < needed)
        fail(name, std::string("truncated ") + format_name + ": " + std::to_string(size - at) + " of the " +
                       std::to_string(needed) + " bytes of pixel data");
    std::vector<uint16_t> samples(count);
    for (size_t i = 0; i < count; i++) {
        const unsigned char *sample = bytes + at + i * sample_bytes;
        samples[i] = sample_bytes == 2 ? uint16_t(sample[0] << 8 | sample[1]) : sample[0];
        if (samples[i] > maximum)
            fail(name, std::string(format_name) + " sample " + std::to_string(samples[i]) +
                           " is above the maxval " + std::to_string(maximum));
    }
    return to_planar(samples.data(), int(width), int(height), stored_channels, double(maximum), name,
                     warnings);
}

} // namespace

Image decode_exemplar(const unsigned char *bytes, size_t size, const std::string &name,
                      std::vector<std::string> *warnings) {
    if (size > kMaxExemplarFileBytes) fail(name, "file is too large");
    const Format format = detect_format(bytes, size, name);
    if (format == Format::unknown)
        fail(name, size == 0 ? "not a readable image (the file is empty)"
                             : "not a readable image (not PNG, JPEG or binary PGM/PPM)");
    if (format == Format::pnm) return decode_pnm(bytes, size, name, warnings);
    return decode_with_stb(bytes, size, format, name, warnings);
}

Image load_exemplar(const std::string &path, std::vector<std::string> *warnings) {
    const std::vector<unsigned char> bytes = read_input_file(path, kMaxExemplarFileBytes, "an image");
    return decode_exemplar(bytes.data(), bytes.size(), path, warnings);
}

} // namespace dsn
