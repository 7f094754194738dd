// bake_exports.cpp - the baker's entry for the page (dsn-bake.wasm, wasm32-wasi): one call turns the
// bytes of an exemplar image (PNG, JPEG, ... as dsn-bake reads them) into the bytes of a .dsnt asset,
// baked for the continuous mode (bilinear) with the largest texton radius up to 15 that the image allows.
// Errors reach the page through exceptions_shim.cpp (the message, then the module stops).
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "dsn/bake.h"

extern "C" {

void *dsn_web_malloc(size_t size) { return std::malloc(size); }

// Bakes `size` bytes at `image`; returns a malloc'd buffer of the asset's bytes and its size in
// *asset_size. `radius` 0 picks the largest radius up to 15 that fits; `iterations` 0 the baker's default.
unsigned char *dsn_web_bake(const unsigned char *image, size_t size, int radius, int iterations,
                            uint32_t seed, size_t *asset_size) {
    std::vector<std::string> warnings;
    const dsn::Image exemplar = dsn::decode_exemplar(image, size, "the image", &warnings);
    dsn::BakeOptions options;
    if (radius <= 0) {
        const int side = exemplar.width < exemplar.height ? exemplar.width : exemplar.height;
        radius = (side - 1) / 4 < 15 ? (side - 1) / 4 : 15;
        if (radius < 1) radius = 1; // too small: the baker says so, with the sizes
    }
    options.radius = radius;
    if (iterations > 0) options.iterations = iterations;
    options.seed = seed;
    options.interpolation = DSN_INTERPOLATION_BILINEAR;
    const dsn::BakeResult result = dsn::bake(exemplar, options);
    unsigned char *bytes = static_cast<unsigned char *>(std::malloc(result.asset.size()));
    if (bytes == nullptr) return nullptr;
    std::memcpy(bytes, result.asset.data(), result.asset.size());
    *asset_size = result.asset.size();
    return bytes;
}

} // extern "C"
