/* runtime/tile_block.h - the fast path for 8-bit textons: a block of the tile accumulated in 16-bit
   sums, one plane per channel, small enough to stay in L1 (SSE2, or AVX2 when compiled for it; plain C
   otherwise). The impulses that reach a rectangle of block_width x walk_height pixels are listed once
   (with where they meet it), then splatted block by block (block_height rows each). When no column of
   the rectangle is reached by more than coverage_limit of them, no pixel is, and no sum can overflow:
   |q| <= 128 for any texton byte and 255 * 128 < 2^15. Otherwise (or when the list is full) the caller
   falls back to the 32-bit splat of tile_walk.h. Internal to tile.cpp. */
#ifndef DSN_TILE_BLOCK_H
#define DSN_TILE_BLOCK_H

#include "noise_internal.h"

#if defined(__AVX2__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace {

#if defined(__AVX2__)
const uint32_t lane = 16; /* 16-bit values per splat vector */
#else
const uint32_t lane = 8;
#endif
const uint32_t block_width = 64, block_height = 32;
const uint32_t walk_height = 2 * block_height;    /* rows walked at once: fewer cells hashed twice */
const uint32_t block_stride = block_width + lane; /* room for the last vector of a clipped row */
const uint32_t coverage_limit = 255;
/* A 64 x 64 rectangle meets lambda (64 + 30)^2 = 276 impulses on average at 30 impacts per pixel with
   a 31 x 31 texton; 384 is 6.5 standard deviations above (a fuller rectangle takes the 32-bit path). */
const uint32_t list_capacity = 384;
/* 16-bit values: room for a 31 x 31 RGB texton (the usual size; larger ones take the 32-bit path). */
const uint32_t planar_texton_capacity = 3 * 31 * ((31 + 2 * lane - 1) / lane * lane);

/* The texton converted to 16 bits, one plane per channel, rows of texton_stride values padded with
   zeros so that a row may be read in whole vectors past its last texel. */
typedef struct planar_texton {
    uint16_t values[planar_texton_capacity];
    uint32_t stride, plane; /* values per row, values per channel plane */
} planar_texton;

uint32_t planar_stride(uint32_t width) { return (width + 2 * lane - 1) / lane * lane; }

int planar_texton_fits(const dsn_asset *asset) {
    return asset->bits == 8 &&
           asset->channels * asset->height * planar_stride(asset->width) <= planar_texton_capacity;
}

void make_planar_texton(const dsn_asset *asset, planar_texton *texton) {
    const uint32_t channels = asset->channels;
    texton->stride = planar_stride(asset->width);
    texton->plane = asset->height * texton->stride;
    for (uint32_t c = 0; c < channels; c++)
        for (uint32_t row = 0; row < asset->height; row++) {
            uint16_t *dst = texton->values + c * texton->plane + row * texton->stride;
            const unsigned char *src = asset->texton + row * asset->width * channels + c;
            uint32_t column = 0;
            for (; column < asset->width; column++)
                dst[column] = uint16_t((uint32_t(src[column * channels]) ^ 0x80u) - 0x80u);
            for (; column < texton->stride; column++) dst[column] = 0;
        }
}

/* Where one impulse meets the walked rectangle (block_width x walk_height at most): texton rows/columns
   and rectangle rows/columns. */
typedef struct block_impulse {
    uint16_t first_index_x, first_texton_x, count_x, first_index_y, first_texton_y, count_y;
} block_impulse;

struct impulse_list {
    block_impulse impulses[list_capacity];
    uint32_t count;                         /* may exceed list_capacity: then only the count is kept */
    int32_t column_change[block_width + 1]; /* impulses starting minus ending at each block column */

    void clear() {
        count = 0;
        for (uint32_t i = 0; i <= block_width; i++) column_change[i] = 0;
    }

    void operator()(const dsn_reach &reach_x, const dsn_reach &reach_y) {
        if (count < list_capacity) {
            block_impulse *impulse = &impulses[count];
            impulse->first_index_x = uint16_t(reach_x.first_index);
            impulse->first_texton_x = uint16_t(reach_x.first_texton);
            impulse->count_x = uint16_t(reach_x.count);
            impulse->first_index_y = uint16_t(reach_y.first_index);
            impulse->first_texton_y = uint16_t(reach_y.first_texton);
            impulse->count_y = uint16_t(reach_y.count);
            column_change[reach_x.first_index]++;
            column_change[reach_x.first_index + reach_x.count]--;
        }
        count++;
    }

    /* Whether every pixel is reached by at most coverage_limit listed impulses (and all are listed). */
    int sums_fit_16_bits() const {
        if (count > list_capacity) return 0;
        int32_t coverage = 0;
        for (uint32_t i = 0; i < block_width; i++) {
            coverage += column_change[i];
            if (coverage > int32_t(coverage_limit)) return 0;
        }
        return 1;
    }
};

#if defined(__AVX2__)
typedef __m256i splat_vector;
inline splat_vector load_vector(const uint16_t *src) {
    return _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(src)));
}
inline void add_vector(uint16_t *dst, splat_vector value) {
    __m256i *out = static_cast<__m256i *>(static_cast<void *>(dst));
    _mm256_storeu_si256(out, _mm256_add_epi16(_mm256_loadu_si256(out), value));
}
#elif defined(__SSE2__)
typedef __m128i splat_vector;
inline splat_vector load_vector(const uint16_t *src) {
    return _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(src)));
}
inline void add_vector(uint16_t *dst, splat_vector value) {
    __m128i *out = static_cast<__m128i *>(static_cast<void *>(dst));
    _mm_storeu_si128(out, _mm_add_epi16(_mm_loadu_si128(out), value));
}
#endif

/* dst[i] += src[i] modulo 2^16 for i < count (with vectors: whole vectors, so up to lane - 1 values past
   count, which land in the block's margin or on zero padding of the texton). */
inline void add_row_16(uint16_t *dst, const uint16_t *src, uint32_t count) {
#if defined(__SSE2__)
    for (uint32_t i = 0; i < count; i += lane) add_vector(dst + i, load_vector(src + i));
#else
    for (uint32_t i = 0; i < count; i++) dst[i] = uint16_t(dst[i] + src[i]);
#endif
}

/* The 16-bit block accumulator: one plane of block_height rows of block_stride values per channel. */
typedef struct block_accumulator {
    uint16_t values[DSN_MAX_CHANNELS * block_height * block_stride];
} block_accumulator;

#if defined(__SSE2__)
/* `rows` texton rows of every channel, `Vectors` whole vectors each: the common short rows get
   straight-line code, with all channels of a row in one pass. */
template <uint32_t Channels, uint32_t Vectors>
inline void add_rows_16(uint16_t *dst, const uint16_t *src, uint32_t rows, const planar_texton *texton) {
    /* Locals: the vector stores may alias anything, so fields read in the loop would be reloaded. */
    const uint32_t plane = block_height * block_stride, texton_stride = texton->stride,
                   texton_plane = texton->plane;
    for (; rows != 0; rows--, dst += block_stride, src += texton_stride)
#pragma GCC unroll 3
        for (uint32_t c = 0; c < Channels; c++)
#pragma GCC unroll 8
            for (uint32_t v = 0; v < Vectors; v++)
                add_vector(dst + c * plane + v * lane, load_vector(src + c * texton_plane + v * lane));
}
#endif

/* The listed impulses (rows relative to the walked rectangle) clipped to its rows [first_row,
   first_row + block_height), into `block`. */
template <uint32_t Channels>
void splat_block(const impulse_list *list, const planar_texton *texton, uint32_t first_row,
                 block_accumulator *block) {
    const uint32_t plane = block_height * block_stride;
    for (uint32_t i = 0; i < Channels * plane; i++) block->values[i] = 0;
    for (uint32_t n = 0; n < list->count; n++) {
        const block_impulse *impulse = &list->impulses[n];
        const uint32_t top = impulse->first_index_y, bottom = top + impulse->count_y;
        const uint32_t first = top > first_row ? top : first_row;
        const uint32_t end = bottom < first_row + block_height ? bottom : first_row + block_height;
        if (first >= end) continue;
        uint16_t *dst = block->values + (first - first_row) * block_stride + impulse->first_index_x;
        const uint16_t *src = texton->values + (impulse->first_texton_y + first - top) * texton->stride +
                              impulse->first_texton_x;
        const uint32_t rows = end - first;
#if defined(__SSE2__)
        switch ((impulse->count_x + lane - 1) / lane) {
        case 1:
            add_rows_16<Channels, 1>(dst, src, rows, texton);
            continue;
        case 2:
            add_rows_16<Channels, 2>(dst, src, rows, texton);
            continue;
        case 3:
            add_rows_16<Channels, 3>(dst, src, rows, texton);
            continue;
        case 4:
            add_rows_16<Channels, 4>(dst, src, rows, texton);
            continue;
        default:
            break;
        }
#endif
        for (uint32_t c = 0; c < Channels; c++)
            for (uint32_t row = 0; row < rows; row++)
                add_row_16(dst + c * plane + row * block_stride,
                           src + c * texton->plane + row * texton->stride, impulse->count_x);
    }
}

} // namespace

#endif /* DSN_TILE_BLOCK_H */
