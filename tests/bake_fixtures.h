// bake_fixtures.h - shared helpers of the baker tests: the real-texture folder, a synthetic exemplar with
// a known answer, and a minimal PNG encoder (8- and 16-bit, any colour type) for the input tests.
#ifndef DSN_TESTS_BAKE_FIXTURES_H
#define DSN_TESTS_BAKE_FIXTURES_H

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "dsn/bake.h"

namespace bake_fixtures {

// ../shared/textures relative to the repo root (tests run from there); DSN_TEXTURES overrides it.
inline std::string textures_folder() {
    const char *override_folder = std::getenv("DSN_TEXTURES");
    return override_folder ? override_folder : "../shared/textures";
}

inline bool textures_available() {
    FILE *probe = std::fopen((textures_folder() + "/animal_leather.png").c_str(), "rb");
    if (!probe) return false;
    std::fclose(probe);
    return true;
}

inline const std::vector<std::string> &named_textures() {
    static const std::vector<std::string> names = {"animal_leather", "stone_granite1", "paper_crinklepaper",
                                                   "wood_walnut",    "stone_slate",    "wood_bark",
                                                   "stone_ground1",  "wood_burlwood"};
    return names;
}

// The known compact spot: an anisotropic, channel-dependent Gaussian bump of radius <= 9 (inside the r = 15
// support), placed around the origin of the torus.
inline dsn::Image known_spot(int width, int height, int channels) {
    dsn::Image spot;
    spot.width = width;
    spot.height = height;
    spot.channels = channels;
    spot.values.assign(size_t(width) * size_t(height) * size_t(channels), 0.0);
    for (int c = 0; c < channels; c++)
        for (int dy = -9; dy <= 9; dy++)
            for (int dx = -9; dx <= 9; dx++) {
                if (dx * dx + dy * dy > 81) continue;
                const double sx = 2.5 + c, sy = 4.0 - c * 0.5;
                const double value = (1.0 - 0.2 * c) *
                                     std::exp(-0.5 * (dx * dx / (sx * sx) + dy * dy / (sy * sy))) *
                                     (1 + 0.3 * std::sin(0.7 * dx + 0.4 * c));
                spot.at((dx + width) % width, (dy + height) % height, c) = value;
            }
    return spot;
}

// Random-phase texture of the known spot: the modulus of the spot's spectrum with a random phase, plus a
// mean; exactly periodic, so bake it with periodic = false. The spot itself is an exact answer (RME 0).
inline dsn::Image random_phase_exemplar(int width, int height, int channels, uint32_t seed) {
    const dsn::Spectrum spot = dsn::forward_dft(known_spot(width, height, channels));
    dsn::Spectrum modulus = spot;
    for (auto &value : modulus.values) value = std::abs(value);
    dsn::Image texture = dsn::inverse_dft(dsn::random_phase_start(modulus, seed));
    for (int c = 0; c < channels; c++) {
        double energy = 0;
        const size_t plane = size_t(width) * size_t(height);
        for (size_t i = 0; i < plane; i++)
            energy += texture.values[size_t(c) * plane + i] * texture.values[size_t(c) * plane + i];
        const double gain = 0.1 / std::sqrt(energy / double(plane)); // standard deviation 0.1 around 0.5
        for (size_t i = 0; i < plane; i++)
            texture.values[size_t(c) * plane + i] = 0.5 + gain * texture.values[size_t(c) * plane + i];
    }
    return texture;
}

// A PNG with stored (uncompressed) deflate blocks. colour_type: 0 grey, 2 RGB, 4 grey+alpha, 6 RGBA;
// samples row-major, interleaved, each in 0..2^depth - 1.
inline std::vector<unsigned char> encode_png(int width, int height, int depth, int colour_type,
                                             const std::vector<unsigned> &samples) {
    const int per_pixel = colour_type == 0 ? 1 : colour_type == 2 ? 3 : colour_type == 4 ? 2 : 4;
    std::vector<unsigned char> raw;
    for (int y = 0; y < height; y++) {
        raw.push_back(0); // filter: none
        for (int i = 0; i < width * per_pixel; i++) {
            const unsigned sample = samples[size_t(y) * size_t(width * per_pixel) + size_t(i)];
            if (depth == 16) raw.push_back((unsigned char)(sample >> 8));
            raw.push_back((unsigned char)(sample & 0xFFu));
        }
    }
    std::vector<unsigned char> zlib = {0x78, 0x01};
    for (size_t start = 0; start < raw.size(); start += 65535) {
        const size_t length = std::min<size_t>(65535, raw.size() - start);
        zlib.push_back(start + length >= raw.size() ? 1 : 0);
        zlib.push_back((unsigned char)(length & 0xFF));
        zlib.push_back((unsigned char)(length >> 8));
        zlib.push_back((unsigned char)(~length & 0xFF));
        zlib.push_back((unsigned char)((~length >> 8) & 0xFF));
        zlib.insert(zlib.end(), raw.begin() + long(start), raw.begin() + long(start + length));
    }
    uint32_t a = 1, b = 0;
    for (unsigned char byte : raw) {
        a = (a + byte) % 65521;
        b = (b + a) % 65521;
    }
    const uint32_t adler = (b << 16) | a;
    for (int shift = 24; shift >= 0; shift -= 8) zlib.push_back((unsigned char)(adler >> shift));

    std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    auto chunk = [&png](const char *type, const std::vector<unsigned char> &data) {
        const uint32_t length = uint32_t(data.size());
        for (int shift = 24; shift >= 0; shift -= 8) png.push_back((unsigned char)(length >> shift));
        std::vector<unsigned char> body(type, type + 4);
        body.insert(body.end(), data.begin(), data.end());
        png.insert(png.end(), body.begin(), body.end());
        const uint32_t crc = dsn_crc32(0, body.data(), body.size());
        for (int shift = 24; shift >= 0; shift -= 8) png.push_back((unsigned char)(crc >> shift));
    };
    std::vector<unsigned char> header;
    for (int value : {width, height})
        for (int shift = 24; shift >= 0; shift -= 8)
            header.push_back((unsigned char)(uint32_t(value) >> shift));
    header.insert(header.end(), {(unsigned char)depth, (unsigned char)colour_type, 0, 0, 0});
    chunk("IHDR", header);
    chunk("IDAT", zlib);
    chunk("IEND", {});
    return png;
}

inline void write_bytes(const std::string &path, const std::vector<unsigned char> &bytes) {
    FILE *file = std::fopen(path.c_str(), "wb");
    if (!file) return;
    std::fwrite(bytes.data(), 1, bytes.size(), file);
    std::fclose(file);
}

// A fresh temporary folder for files a test writes.
inline std::string temporary_folder() {
    char pattern[] = "/tmp/dsn-bake-test-XXXXXX";
    const char *folder = mkdtemp(pattern);
    return folder ? folder : "/tmp";
}

} // namespace bake_fixtures

#endif // DSN_TESTS_BAKE_FIXTURES_H
