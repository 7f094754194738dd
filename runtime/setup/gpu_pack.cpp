/* runtime/setup/gpu_pack.cpp - dsn_gpu_pack: a configured noise as the 32-bit words that dsn/dsn.glsl reads
   (the layout is documented in dsn/gpu.h). */
#include <stddef.h>

#include "dsn/gpu.h"
#include "setup/noise_state.h"
#if DSN_SURFACE
#include "core/surface_walk.h"
#include "setup/wide_arithmetic.h"
#endif

namespace {

const uint32_t cdf_words = 96, guide_words = 64;
const uint32_t cdf_first = 48, guide_first = cdf_first + cdf_words;
const uint32_t surface_first = guide_first + guide_words, surface_words = 8;

static_assert(sizeof(dsn_noise_state::poisson_cdf) == cdf_words * sizeof(uint32_t),
              "the layout holds the whole Poisson table");
static_assert(sizeof(dsn_noise_state::poisson_guide) == guide_words,
              "the layout holds the whole Poisson guide");
static_assert(surface_first + surface_words == DSN_GPU_HEADER_WORDS, "the texton follows the surface words");

/* Words 3 .. 16 of the layout: where each is in the configured noise (every one a uint32_t field), in
   words from its start. A table and one loop rather than fourteen assignments: the runtime's whole code
   must stay small on microcontrollers (the cross test's footprint counts this file too). */
#define DSN_ASSET_FIELD(name) (offsetof(dsn_noise_state, asset) + offsetof(dsn_asset, name)) / 4
#define DSN_STATE_FIELD(name) offsetof(dsn_noise_state, name) / 4
const unsigned char header_fields[14] = {
    DSN_ASSET_FIELD(channels),      DSN_ASSET_FIELD(bits),        DSN_ASSET_FIELD(width),
    DSN_ASSET_FIELD(height),        DSN_STATE_FIELD(radius[0]),   DSN_STATE_FIELD(radius[1]),
    DSN_STATE_FIELD(cell_shift),    DSN_STATE_FIELD(period[0]),   DSN_STATE_FIELD(period[1]),
    DSN_STATE_FIELD(seed_column),   DSN_STATE_FIELD(seed_row),    DSN_STATE_FIELD(gain_shift),
    DSN_STATE_FIELD(poisson_parts), DSN_STATE_FIELD(poisson_size)};
#undef DSN_ASSET_FIELD
#undef DSN_STATE_FIELD
static_assert(offsetof(dsn_noise_state, poisson_size) / 4 <= 255,
              "header_fields holds word indexes in bytes");
static_assert(offsetof(dsn_noise_state, poisson_size) % 4 == 0 && offsetof(dsn_asset, height) % 4 == 0,
              "the header fields are whole words");

/* A configured noise has a texton; dsn_noise_init zeroes the noise when it fails. */
const dsn_noise_state *configured(const dsn_noise *handle) {
    const dsn_noise_state *noise = dsn_state(handle);
    return dsn_configured(noise) ? noise : 0;
}

/* Values of a texton of `asset`'s channels: width * height * channels. */
size_t texton_words(const dsn_asset *asset, uint32_t width, uint32_t height) {
    return size_t(width) * height * asset->channels;
}

/* The texton's quads (dsn/gpu.h): two words per texel and channel, with a row and a column more. */
size_t quad_words(const dsn_asset *asset) {
    return 2u * texton_words(asset, asset->width + 1u, asset->height + 1u);
}

/* The textons' values before the quads. */
size_t value_words(const dsn_asset *asset) {
    return texton_words(asset, asset->width, asset->height) +
           (asset->lattice_texton != 0 ? texton_words(asset, asset->lattice_width, asset->lattice_height)
                                       : 0u);
}

} // namespace

extern "C" size_t dsn_gpu_word_count(const dsn_noise *handle) {
    const dsn_noise_state *noise = configured(handle);
    if (noise == 0) return 0;
    return DSN_GPU_HEADER_WORDS + value_words(&noise->asset) + quad_words(&noise->asset);
}

namespace {

/* The texton's quads (dsn/gpu.h): the 2 x 2 texels whose lower right is (r, q), 16 bits each (two's
   complement), two to a word. */
void put_quads(uint32_t *words, const dsn_asset *asset) {
    const uint32_t width = asset->width, height = asset->height, channels = asset->channels;
    for (uint32_t r = 0; r <= height; r++)
        for (uint32_t q = 0; q <= width; q++)
            for (uint32_t c = 0; c < channels; c++)
                for (uint32_t pair = 0; pair < 2; pair++) {
                    uint32_t word = 0;
                    for (uint32_t half = 0; half < 2; half++) {
                        /* unsigned: r - 1 and q - 1 wrap past the texton for r, q = 0 */
                        const uint32_t row = r - 1u + pair, column = q - 1u + half;
                        if (row < height && column < width)
                            word |= (static_cast<uint32_t>(dsn_asset_texton_value(asset, row, column, c)) &
                                     0xFFFFu)
                                    << (16u * half);
                    }
                    *words++ = word;
                }
}

/* A texton's values, sign-extended to whole words in uint32 arithmetic: the asset stores them in the
   layout's order (format.h: row-major, channels interleaved, 8-bit or 16-bit little-endian two's
   complement). */
void put_texton(uint32_t *words, const unsigned char *texton, size_t count, uint32_t bits) {
    const uint32_t bytes = bits / 8, sign = bytes == 1 ? 0x80u : 0x8000u;
    for (size_t v = 0; v < count; v++, texton += bytes)
        words[v] = ((texton[0] | (bytes == 2 ? uint32_t(texton[1]) << 8 : 0u)) ^ sign) - sign;
}

/* int64 values as pairs of words, low first (the conversion to uint64 is modulo 2^64). */
void put_pairs(uint32_t *words, const int64_t *values, uint32_t count) {
    for (uint32_t i = 0; i < count; i++) {
        const uint64_t bits = static_cast<uint64_t>(values[i]);
        words[2 * i] = static_cast<uint32_t>(bits);
        words[2 * i + 1] = static_cast<uint32_t>(bits >> 32);
    }
}

/* Words 208 .. 215: the surface noise's offset and the largest walk it evaluates (dsn/gpu.h); zeros in a
   runtime built without it. The walk's cost test (surface_walk.h's walk_too_costly) compares its cubes
   times c^2 impacts with the support times DSN_MAX_POINT_IMPULSES: for whole cubes, the same as comparing
   them with the quotient. */
void put_surface(const dsn_noise_state *noise, uint32_t *words) {
    for (uint32_t i = 0; i < surface_words; i++) words[i] = 0;
#if DSN_SURFACE
    int64_t offset[DSN_MAX_CHANNELS] = {0, 0, 0};
    surface_offset(noise, noise->offset, offset);
    put_pairs(words, offset, 3);
    const uint64_t side = static_cast<uint64_t>(1) << noise->cell_shift;
    const uint64_t cost = side * side * noise->impacts_q16,
                   budget = (static_cast<uint64_t>(noise->asset.support_size) * DSN_MAX_POINT_IMPULSES) << 16;
    const uint64_t cubes = cost == 0 ? DSN_MAX_POINT_IMPULSES : dsn_divide(budget, cost);
    words[6] = static_cast<uint32_t>(cubes < DSN_MAX_POINT_IMPULSES ? cubes : DSN_MAX_POINT_IMPULSES);
#else
    (void)noise;
#endif
}

} // namespace

extern "C" int dsn_gpu_pack(const dsn_noise *handle, uint32_t *words, size_t capacity) {
    if (handle == 0 || words == 0) return DSN_ERR_NULL;
    const size_t count = dsn_gpu_word_count(handle);
    if (count == 0 || capacity < count) return DSN_ERR_ARGUMENT;
    const dsn_noise_state *noise = dsn_state(handle);
    const dsn_asset *asset = &noise->asset;
    /* dsn.glsl evaluates the Gaussian-space noise only (a noise made with DSN_FLAG_NO_HISTOGRAM has no
       mapping left). */
    if (asset->histogram_table != 0) return DSN_ERR_UNSUPPORTED;
    const unsigned char *state = static_cast<const unsigned char *>(static_cast<const void *>(noise));
    uint32_t i;
    words[0] = DSN_GPU_MAGIC;
    words[1] = DSN_GPU_LAYOUT_VERSION;
    words[2] = static_cast<uint32_t>(count);
    for (i = 0; i < 14; i++)
        words[3 + i] =
            *static_cast<const uint32_t *>(static_cast<const void *>(state + 4u * header_fields[i]));
    words[17] = dsn_continuous_check(handle) == DSN_OK ? 1u : 0u;
    put_pairs(words + 18, noise->gain, 9);
    put_pairs(words + 36, noise->offset, 3);
    /* The lattice evaluators' texton (dsn_lattice_view): the lattice texton after the texton, or the
       texton itself. */
    const size_t texton_count = texton_words(asset, asset->width, asset->height);
    const int separate = asset->lattice_texton != 0;
    words[42] = separate ? asset->lattice_width : asset->width;
    words[43] = separate ? asset->lattice_height : asset->height;
    words[44] = (words[42] - 1u) / 2u;
    words[45] = (words[43] - 1u) / 2u;
    words[46] = static_cast<uint32_t>(DSN_GPU_HEADER_WORDS + (separate ? texton_count : 0u));
    words[47] = static_cast<uint32_t>(DSN_GPU_HEADER_WORDS + value_words(asset));
    for (i = 48; i < cdf_first; i++) words[i] = 0;
    for (i = 0; i < cdf_words; i++) words[cdf_first + i] = noise->poisson_cdf[i];
    for (i = 0; i < guide_words; i++) words[guide_first + i] = noise->poisson_guide[i];
    put_surface(noise, words + surface_first);
    put_texton(words + DSN_GPU_HEADER_WORDS, asset->texton, texton_count, asset->bits);
    if (separate)
        put_texton(words + DSN_GPU_HEADER_WORDS + texton_count, asset->lattice_texton,
                   value_words(asset) - texton_count, asset->bits);
    put_quads(words + DSN_GPU_HEADER_WORDS + value_words(asset), asset);
    return DSN_OK;
}
