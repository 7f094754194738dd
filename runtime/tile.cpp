/* runtime/tile.cpp - tile evaluation on the lattice: splats every impulse that reaches the tile into an
   integer accumulator (one contiguous add of width x channels values per texton row), then normalizes
   each pixel. The sums are the per-point sums (integer addition modulo 2^32 is order-free), so the bits
   equal the per-point path's. */
#include "noise_internal.h"

#if defined(__AVX2__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace {

/* A run of tile indices [offset, offset + length) along one axis whose coordinates are contiguous
   integers. Without a period the whole axis is one run on the torus. With a period the coordinate is
   read as int32 and reduced modulo P, so the run is cut where x0 + i passes from INT32_MAX to
   INT32_MIN (after that cut the reduced coordinates are contiguous again). */
typedef struct tile_run {
    uint32_t start, offset, length;
} tile_run;

uint32_t split_runs(uint32_t start, uint32_t length, uint32_t period, tile_run *runs) {
    uint32_t until_sign_flip = 0x80000000u - start;
    runs[0].start = start;
    runs[0].offset = 0;
    runs[0].length = length;
    if (period == 0 || until_sign_flip == 0 || until_sign_flip >= length) return 1;
    runs[0].length = until_sign_flip;
    runs[1].start = 0x80000000u;
    runs[1].offset = until_sign_flip;
    runs[1].length = length - until_sign_flip;
    return 2;
}

/* dst[i] += texton value i, for `count` interleaved values, modulo 2^32. This is the inner loop of the
   tile path; with SSE2 it runs 16 (8-bit) or 8 (16-bit) values per step (sign extension by unpacking a
   value with itself and shifting arithmetically, which is exact two's-complement in the hardware). */
template <uint32_t Bits>
inline void add_row(uint32_t *dst, const unsigned char *src, uint32_t count) {
    uint32_t i = 0;
#if defined(__SSE2__)
    if (Bits == 8) {
        for (; i + 16 <= count; i += 16) {
            __m128i bytes = _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(src + i)));
            __m128i low16 = _mm_srai_epi16(_mm_unpacklo_epi8(bytes, bytes), 8);
            __m128i high16 = _mm_srai_epi16(_mm_unpackhi_epi8(bytes, bytes), 8);
            __m128i *out = static_cast<__m128i *>(static_cast<void *>(dst + i));
            __m128i values[4] = {_mm_srai_epi32(_mm_unpacklo_epi16(low16, low16), 16),
                                 _mm_srai_epi32(_mm_unpackhi_epi16(low16, low16), 16),
                                 _mm_srai_epi32(_mm_unpacklo_epi16(high16, high16), 16),
                                 _mm_srai_epi32(_mm_unpackhi_epi16(high16, high16), 16)};
            for (int part = 0; part < 4; part++)
                _mm_storeu_si128(out + part, _mm_add_epi32(_mm_loadu_si128(out + part), values[part]));
        }
    } else {
        for (; i + 8 <= count; i += 8) {
            __m128i words =
                _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(src + 2 * i)));
            __m128i *out = static_cast<__m128i *>(static_cast<void *>(dst + i));
            __m128i low = _mm_srai_epi32(_mm_unpacklo_epi16(words, words), 16);
            __m128i high = _mm_srai_epi32(_mm_unpackhi_epi16(words, words), 16);
            _mm_storeu_si128(out, _mm_add_epi32(_mm_loadu_si128(out), low));
            _mm_storeu_si128(out + 1, _mm_add_epi32(_mm_loadu_si128(out + 1), high));
        }
    }
#endif
    if (Bits == 8) {
        for (; i < count; i++) dst[i] += uint32_t(src[i] ^ 0x80u) - 0x80u;
    } else {
        for (; i < count; i++) dst[i] += (uint32_t(src[2 * i] | (src[2 * i + 1] << 8)) ^ 0x8000u) - 0x8000u;
    }
}

/* Calls visit(reach_x, reach_y) for every impulse that reaches the rectangle run_x x run_y (both
   single runs), in the order of the hash stream. This is the only place the tile path walks cells. */
template <typename Visit>
void for_each_reaching_impulse(const dsn_noise *noise, const tile_run *run_x, const tile_run *run_y,
                               Visit &visit) {
    const dsn_asset *asset = &noise->asset;
    const uint32_t shift = noise->cell_shift;
    dsn_axis axis_x, axis_y;
    dsn_axis_init(&axis_x, run_x->start, run_x->length, noise->radius[0], shift, noise->period[0]);
    dsn_axis_init(&axis_y, run_y->start, run_y->length, noise->radius[1], shift, noise->period[1]);
    for (uint32_t span_index_y = 0; span_index_y < axis_y.span_count; span_index_y++) {
        dsn_span span_y = dsn_axis_span(&axis_y, span_index_y);
        for (uint32_t i = 0; i < span_y.cell_count; i++) {
            uint32_t cell_y = dsn_span_cell(&span_y, i, shift), row_key = dsn_row_key(noise, cell_y);
            for (uint32_t span_index_x = 0; span_index_x < axis_x.span_count; span_index_x++) {
                dsn_span span_x = dsn_axis_span(&axis_x, span_index_x);
                for (uint32_t j = 0; j < span_x.cell_count; j++) {
                    uint32_t cell_x = dsn_span_cell(&span_x, j, shift);
                    uint32_t key = dsn_cell_key_in_row(noise, cell_x, row_key);
                    uint32_t count = dsn_cell_impulse_count(noise, key);
                    for (uint32_t k = 0; k < count; k++) {
                        uint32_t hash = dsn_impulse_hash(noise, key, k);
                        uint32_t x = (cell_x << shift) + dsn_impulse_offset(dsn_impulse_bits_x(hash), shift);
                        uint32_t y = (cell_y << shift) + dsn_impulse_offset(dsn_impulse_bits_y(hash), shift);
                        dsn_reach reach_x, reach_y;
                        if (x > span_x.last_position || y > span_y.last_position ||
                            !dsn_reach_window(span_x.base - x, run_x->length, asset->width, &reach_x) ||
                            !dsn_reach_window(span_y.base - y, run_y->length, asset->height, &reach_y))
                            continue;
                        visit(reach_x, reach_y);
                    }
                }
            }
        }
    }
}

/* Adds each reaching impulse's texton into a 32-bit accumulator (rows of row_stride values; the
   rectangle starts at run_x->offset, run_y->offset). */
template <uint32_t Bits>
struct splat_32 {
    const dsn_asset *asset;
    const tile_run *run_x, *run_y;
    uint32_t *accumulator;
    uint32_t row_stride;

    void operator()(const dsn_reach &reach_x, const dsn_reach &reach_y) {
        const uint32_t channels = asset->channels, texton_stride = asset->width * channels * (Bits / 8);
        uint32_t *dst = accumulator + (run_y->offset + reach_y.first_index) * row_stride +
                        (run_x->offset + reach_x.first_index) * channels;
        const unsigned char *src = asset->texton + reach_y.first_texton * texton_stride +
                                   reach_x.first_texton * channels * (Bits / 8);
        for (uint32_t row = 0; row < reach_y.count; row++)
            add_row<Bits>(dst + row * row_stride, src + row * texton_stride, reach_x.count * channels);
    }
};

/* One rectangle of the tile where both axes are single runs. */
void splat_region(const dsn_noise *noise, const tile_run *run_x, const tile_run *run_y, uint32_t *accumulator,
                  uint32_t row_stride) {
    if (noise->asset.bits == 8) {
        splat_32<8> splat = {&noise->asset, run_x, run_y, accumulator, row_stride};
        for_each_reaching_impulse(noise, run_x, run_y, splat);
    } else {
        splat_32<16> splat = {&noise->asset, run_x, run_y, accumulator, row_stride};
        for_each_reaching_impulse(noise, run_x, run_y, splat);
    }
}

/* ---- The blocked 16-bit path (8-bit textons) ----
   The tile is rendered in blocks of block_width x block_height pixels whose accumulators (16-bit,
   one plane per channel) stay in L1. A block first lists the impulses that reach it. When no column
   of the block is reached by more than coverage_limit of them, no pixel is, and no sum can overflow:
   |q| <= 128 for any texton byte and 255 * 128 < 2^15. Otherwise (or when the list is full) the block
   falls back to the 32-bit splat into the tile-sized accumulator. */
#if defined(__AVX2__)
const uint32_t lane = 16; /* 16-bit values per splat vector */
#else
const uint32_t lane = 8;
#endif
const uint32_t block_width = 64, block_height = 32;
const uint32_t block_stride = block_width + lane; /* room for the last vector of a clipped row */
const uint32_t coverage_limit = 255;
const uint32_t list_capacity = 384;
const uint32_t planar_texton_capacity = 4608; /* 16-bit values: a 31 x 31 RGB texton takes 4464 */

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

/* Where one impulse meets a block: texton rows/columns and block rows/columns. */
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

template <uint32_t Channels>
void splat_block(const impulse_list *list, const planar_texton *texton, block_accumulator *block) {
    const uint32_t plane = block_height * block_stride;
    for (uint32_t i = 0; i < Channels * plane; i++) block->values[i] = 0;
    for (uint32_t n = 0; n < list->count; n++) {
        const block_impulse *impulse = &list->impulses[n];
        uint16_t *dst = block->values + impulse->first_index_y * block_stride + impulse->first_index_x;
        const uint16_t *src =
            texton->values + impulse->first_texton_y * texton->stride + impulse->first_texton_x;
        const uint32_t rows = impulse->count_y;
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

/* ---- Normalization of 16-bit sums ----
   dsn_normalize computes round((offset_c + sum_k gain_ck Q_k) / 2^s) in 64 bits. When every |Q_k| <
   2^15 it splits exactly into 32-bit lanes: gain = 2^15 high + low with low in [-2^14, 2^14) (so |high|
   <= 2^14), A = sum high_k Q_k and B = sum low_k Q_k (|A|, |B| < 3 2^29), and P = offset + 2^(s-1) =
   2^s P_q + 2^15 P_m + P_l (P_m < 2^(s-15), P_l < 2^15). Then with B = 2^15 B_h + B_l:
       result = P_q + floor((P_m + A + B_h + ((B_l + P_l) >> 15)) / 2^(s-15))
   where the numerator stays below 2^31 in magnitude. This needs s >= 16, and P_q +- 2^(46-s) inside
   int32 so that the int32 saturation of dsn_normalize can never act. */
typedef struct split_normalization {
    int16_t high[9], low[9];
    int32_t p_q[3], p_m[3], p_l[3];
    uint32_t shift; /* s - 15 */
} split_normalization;

int make_split_normalization(const dsn_noise *noise, split_normalization *split) {
    const uint32_t s = noise->gain_shift, channels = noise->asset.channels;
    if (s < 16 || s > 32) return 0;
    for (uint32_t c = 0; c < channels; c++) {
        for (uint32_t k = 0; k < 3; k++) {
            int64_t gain = k < channels ? noise->gain[c * 3 + k] : 0;
            int64_t low = int64_t(uint64_t(gain) & 0x7FFFu);
            if (low >= 0x4000) low -= 0x8000;
            split->low[c * 3 + k] = int16_t(low);
            split->high[c * 3 + k] = int16_t((gain - low) / 0x8000);
        }
        int64_t p = noise->offset[c] + (int64_t(1) << (s - 1));
        int64_t below = int64_t(uint64_t(p) & ((uint64_t(1) << s) - 1u));
        int64_t p_q = (p - below) / (int64_t(1) << s), margin = int64_t(1) << (46 - s);
        if (p_q - margin < INT32_MIN || p_q + margin > INT32_MAX) return 0;
        split->p_q[c] = int32_t(p_q);
        split->p_m[c] = int32_t(below >> 15);
        split->p_l[c] = int32_t(below & 0x7FFF);
    }
    split->shift = s - 15;
    return 1;
}

/* Q_k of a 16-bit accumulator value, as the uint32 bits dsn_normalize reads. */
inline uint32_t widen_sum(uint16_t value) { return (uint32_t(value) ^ 0x8000u) - 0x8000u; }

/* Output stores: the per-value conversions of the API edge. */
inline void store_value(int32_t *out, int32_t value) { *out = value; }
inline void store_value(float *out, int32_t value) { *out = dsn_fixed_to_float(value); }
inline void store_value(uint8_t *out, int32_t value) { *out = dsn_fixed_to_u8(value); }

/* Row `row` of a block, pixels [first, first + count), normalized one pixel at a time. */
template <typename Value>
void normalize_row_scalar(const dsn_noise *noise, const block_accumulator *block, uint32_t row,
                          uint32_t first, uint32_t count, Value *out) {
    const uint32_t channels = noise->asset.channels, plane = block_height * block_stride;
    for (uint32_t i = first; i < first + count; i++) {
        uint32_t sums[3] = {0, 0, 0};
        int32_t fixed[3];
        for (uint32_t k = 0; k < channels; k++)
            sums[k] = widen_sum(block->values[k * plane + row * block_stride + i]);
        dsn_normalize(noise, sums, fixed);
        for (uint32_t c = 0; c < channels; c++) store_value(out + i * channels + c, fixed[c]);
    }
}

#if defined(__SSE2__)
/* The split normalization as vectors, for 8 pixels at a time. */
typedef struct split_vectors {
    __m128i high_pair[3], high_third[3], low_pair[3], low_third[3], p_q[3], p_m[3], p_l[3], shift;
} split_vectors;

void make_split_vectors(const split_normalization *split, uint32_t channels, split_vectors *v) {
    for (uint32_t c = 0; c < channels; c++) {
        const int16_t *high = split->high + 3 * c, *low = split->low + 3 * c;
        v->high_pair[c] =
            _mm_setr_epi16(high[0], high[1], high[0], high[1], high[0], high[1], high[0], high[1]);
        v->high_third[c] = _mm_setr_epi16(high[2], 0, high[2], 0, high[2], 0, high[2], 0);
        v->low_pair[c] = _mm_setr_epi16(low[0], low[1], low[0], low[1], low[0], low[1], low[0], low[1]);
        v->low_third[c] = _mm_setr_epi16(low[2], 0, low[2], 0, low[2], 0, low[2], 0);
        v->p_q[c] = _mm_set1_epi32(split->p_q[c]);
        v->p_m[c] = _mm_set1_epi32(split->p_m[c]);
        v->p_l[c] = _mm_set1_epi32(split->p_l[c]);
    }
    v->shift = _mm_cvtsi32_si128(int32_t(split->shift));
}

/* Four pixels of output channel c: `pair` holds (Q_0, Q_1) and `third` (Q_2, 0) per pixel. */
inline __m128i normalize_4(const split_vectors *v, uint32_t c, __m128i pair, __m128i third) {
    __m128i a = _mm_add_epi32(_mm_madd_epi16(pair, v->high_pair[c]), _mm_madd_epi16(third, v->high_third[c]));
    __m128i b = _mm_add_epi32(_mm_madd_epi16(pair, v->low_pair[c]), _mm_madd_epi16(third, v->low_third[c]));
    __m128i carry = _mm_srli_epi32(_mm_add_epi32(_mm_and_si128(b, _mm_set1_epi32(0x7FFF)), v->p_l[c]), 15);
    __m128i x = _mm_add_epi32(_mm_add_epi32(v->p_m[c], a), _mm_add_epi32(_mm_srai_epi32(b, 15), carry));
    return _mm_add_epi32(_mm_sra_epi32(x, v->shift), v->p_q[c]);
}

/* (r0 r1 r2 r3), (g0 ..), (b0 ..) -> r0 g0 b0 r1 | g1 b1 r2 g2 | b2 r3 g3 b3. shufps only moves bits
   between lanes (no arithmetic), so reading the integers as floats here is exact. */
inline void interleave_3(__m128i r, __m128i g, __m128i b, __m128i *out) {
    __m128 blue = _mm_castsi128_ps(b);
    __m128 rg_low = _mm_castsi128_ps(_mm_unpacklo_epi32(r, g)),
           rg_high = _mm_castsi128_ps(_mm_unpackhi_epi32(r, g));
    __m128 first = _mm_shuffle_ps(blue, rg_low, _MM_SHUFFLE(3, 2, 0, 0));  /* b0 b0 r1 g1 */
    __m128 second = _mm_shuffle_ps(rg_low, blue, _MM_SHUFFLE(1, 1, 3, 3)); /* g1 g1 b1 b1 */
    __m128 third = _mm_shuffle_ps(blue, rg_high, _MM_SHUFFLE(3, 2, 2, 2)); /* b2 b2 r3 g3 */
    out[0] = _mm_castps_si128(_mm_shuffle_ps(rg_low, first, _MM_SHUFFLE(2, 0, 1, 0)));
    out[1] = _mm_castps_si128(_mm_shuffle_ps(second, rg_high, _MM_SHUFFLE(1, 0, 2, 0)));
    __m128 last = _mm_shuffle_ps(rg_high, blue, _MM_SHUFFLE(3, 3, 3, 3)); /* g3 g3 b3 b3 */
    out[2] = _mm_castps_si128(_mm_shuffle_ps(third, last, _MM_SHUFFLE(2, 0, 2, 0)));
}

/* Stores `vectors` interleaved output vectors (4 values each) of which the first `values` are wanted. */
inline void store_vectors(int32_t *out, const __m128i *v, uint32_t vectors, uint32_t values) {
    if (values == 4 * vectors) {
#pragma GCC unroll 6
        for (uint32_t i = 0; i < vectors; i++)
            _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(out + 4 * i)), v[i]);
        return;
    }
    int32_t buffer[24];
    for (uint32_t i = 0; i < vectors; i++)
        _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(buffer + 4 * i)), v[i]);
    for (uint32_t i = 0; i < values; i++) out[i] = buffer[i];
}

/* float(value) * 2^-16: the conversion rounds once to nearest, like dsn_fixed_to_float. */
inline void store_vectors(float *out, const __m128i *v, uint32_t vectors, uint32_t values) {
    const __m128 scale = _mm_set1_ps(1.0f / 65536.0f);
    float buffer[24];
    float *dst = values == 4 * vectors ? out : buffer;
#pragma GCC unroll 6
    for (uint32_t i = 0; i < vectors; i++)
        _mm_storeu_ps(dst + 4 * i, _mm_mul_ps(_mm_cvtepi32_ps(v[i]), scale));
    if (dst == buffer)
        for (uint32_t i = 0; i < values; i++) out[i] = buffer[i];
}

/* dsn_fixed_to_u8: clamp to [0, 2^16], then (255 v + 2^15) >> 16. */
inline __m128i to_u8_range(__m128i value) {
    const __m128i one = _mm_set1_epi32(DSN_ONE);
    value = _mm_and_si128(value, _mm_cmpgt_epi32(value, _mm_setzero_si128()));
    __m128i above = _mm_cmpgt_epi32(value, one);
    value = _mm_or_si128(_mm_and_si128(above, one), _mm_andnot_si128(above, value));
    return _mm_srli_epi32(
        _mm_add_epi32(_mm_sub_epi32(_mm_slli_epi32(value, 8), value), _mm_set1_epi32(32768)), 16);
}

inline void store_vectors(uint8_t *out, const __m128i *v, uint32_t vectors, uint32_t values) {
    __m128i words[3];
#pragma GCC unroll 3
    for (uint32_t i = 0; i < vectors; i += 2)
        words[i / 2] = _mm_packs_epi32(to_u8_range(v[i]), to_u8_range(v[i + 1]));
    uint8_t buffer[32];
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(buffer)),
                     _mm_packus_epi16(words[0], vectors > 2 ? words[1] : words[0]));
    if (vectors > 2)
        _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(buffer + 16)),
                         _mm_packus_epi16(words[2], words[2]));
    for (uint32_t i = 0; i < values; i++) out[i] = buffer[i];
}

/* Row `row` of a block, `count` pixels, 8 at a time (the accumulator rows have room past the end). */
template <uint32_t channels, typename Value>
void normalize_row_split(const split_vectors *v, const block_accumulator *block, uint32_t row, uint32_t count,
                         Value *out) {
    const uint32_t plane = block_height * block_stride;
    const uint16_t *sums = block->values + row * block_stride;
    const __m128i zero = _mm_setzero_si128();
    for (uint32_t i = 0; i < count; i += 8) {
        const uint32_t pixels = count - i < 8 ? count - i : 8;
        __m128i q0 = _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(sums + i)));
        __m128i q1 = zero, q2 = zero;
        if (channels == 3) {
            q1 = _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(sums + plane + i)));
            q2 = _mm_loadu_si128(
                static_cast<const __m128i *>(static_cast<const void *>(sums + 2 * plane + i)));
        }
        __m128i pair_low = _mm_unpacklo_epi16(q0, q1), pair_high = _mm_unpackhi_epi16(q0, q1);
        __m128i third_low = _mm_unpacklo_epi16(q2, zero), third_high = _mm_unpackhi_epi16(q2, zero);
        __m128i values[6];
        if (channels == 3) {
            interleave_3(normalize_4(v, 0, pair_low, third_low), normalize_4(v, 1, pair_low, third_low),
                         normalize_4(v, 2, pair_low, third_low), values);
            interleave_3(normalize_4(v, 0, pair_high, third_high), normalize_4(v, 1, pair_high, third_high),
                         normalize_4(v, 2, pair_high, third_high), values + 3);
            store_vectors(out + i * 3, values, 6, pixels * 3);
        } else {
            values[0] = normalize_4(v, 0, pair_low, third_low);
            values[1] = normalize_4(v, 0, pair_high, third_high);
            store_vectors(out + i, values, 2, pixels);
        }
    }
}
#endif

/* Everything a tile call prepares once for the blocked path. */
typedef struct block_setup {
    planar_texton texton;
    int split_ok;
#if defined(__SSE2__)
    split_vectors split;
#endif
} block_setup;

void make_block_setup(const dsn_noise *noise, block_setup *setup) {
    make_planar_texton(&noise->asset, &setup->texton);
    split_normalization split;
    setup->split_ok = make_split_normalization(noise, &split);
#if defined(__SSE2__)
    if (setup->split_ok) make_split_vectors(&split, noise->asset.channels, &setup->split);
#else
    setup->split_ok = 0;
#endif
}

/* Where a tile's values go: `out` (width * channels values per row) and the 32-bit accumulator of the
   fallback (`out` itself for fixed output, else the scratch). */
template <typename Value>
struct tile_target {
    Value *out;
    uint32_t *accumulator;
    uint32_t row_values;
};

/* The fallback for a block with too many impulses: 32-bit sums in the tile accumulator. */
template <typename Value>
void render_block_32(const dsn_noise *noise, const tile_run *block_x, const tile_run *block_y,
                     const tile_target<Value> *target) {
    const uint32_t channels = noise->asset.channels, row_values = target->row_values;
    for (uint32_t row = 0; row < block_y->length; row++) {
        uint32_t *sums =
            target->accumulator + (block_y->offset + row) * row_values + block_x->offset * channels;
        for (uint32_t i = 0; i < block_x->length * channels; i++) sums[i] = 0;
    }
    splat_region(noise, block_x, block_y, target->accumulator, row_values);
    for (uint32_t row = 0; row < block_y->length; row++) {
        size_t first = size_t(block_y->offset + row) * row_values + block_x->offset * channels;
        for (uint32_t i = 0; i < block_x->length; i++) {
            const uint32_t *pixel = target->accumulator + first + i * channels;
            uint32_t sums[3] = {pixel[0], channels == 3 ? pixel[1] : 0u, channels == 3 ? pixel[2] : 0u};
            int32_t fixed[3];
            dsn_normalize(noise, sums, fixed); /* sums are copied first: fixed output may overwrite them */
            for (uint32_t c = 0; c < channels; c++)
                store_value(target->out + first + i * channels + c, fixed[c]);
        }
    }
}

template <typename Value>
void render_block(const dsn_noise *noise, const block_setup *setup, const tile_run *block_x,
                  const tile_run *block_y, const tile_target<Value> *target) {
    impulse_list list;
    list.clear();
    for_each_reaching_impulse(noise, block_x, block_y, list);
    if (!list.sums_fit_16_bits()) {
        render_block_32(noise, block_x, block_y, target);
        return;
    }
    const uint32_t channels = noise->asset.channels;
    block_accumulator block;
    if (channels == 3)
        splat_block<3>(&list, &setup->texton, &block);
    else
        splat_block<1>(&list, &setup->texton, &block);
    for (uint32_t row = 0; row < block_y->length; row++) {
        Value *out =
            target->out + size_t(block_y->offset + row) * target->row_values + block_x->offset * channels;
#if defined(__SSE2__)
        if (setup->split_ok) {
            if (channels == 3)
                normalize_row_split<3>(&setup->split, &block, row, block_x->length, out);
            else
                normalize_row_split<1>(&setup->split, &block, row, block_x->length, out);
            continue;
        }
#endif
        normalize_row_scalar(noise, &block, row, 0, block_x->length, out);
    }
}

/* One rectangle of the tile where both axes are single runs, block by block. */
template <typename Value>
void render_region(const dsn_noise *noise, const block_setup *setup, const tile_run *run_x,
                   const tile_run *run_y, const tile_target<Value> *target) {
    for (uint32_t y = 0; y < run_y->length; y += block_height) {
        tile_run block_y = {run_y->start + y, run_y->offset + y,
                            run_y->length - y < block_height ? run_y->length - y : block_height};
        for (uint32_t x = 0; x < run_x->length; x += block_width) {
            tile_run block_x = {run_x->start + x, run_x->offset + x,
                                run_x->length - x < block_width ? run_x->length - x : block_width};
            render_block(noise, setup, &block_x, &block_y, target);
        }
    }
}

/* Largest tile: sides up to DSN_TILE_MAX_SIDE and width * height * channels 32-bit values addressable. */
int tile_values(const dsn_noise *noise, uint32_t width, uint32_t height, size_t *values) {
    if (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE)
        return DSN_ERR_TILE_SIZE;
    uint64_t count = uint64_t(width) * height * noise->asset.channels; /* < 2^34 */
    if (count > (~size_t(0) - 8) / sizeof(uint32_t)) return DSN_ERR_TILE_SIZE;
    *values = size_t(count);
    return DSN_OK;
}

/* The whole tile: blocks of 16-bit sums when the texton allows, else 32-bit sums run by run. */
template <typename Value>
void render_tile(const dsn_noise *noise, uint32_t x0, uint32_t y0, uint32_t width, uint32_t height,
                 Value *out, uint32_t *accumulator) {
    tile_run runs_x[2], runs_y[2];
    uint32_t run_count_x = split_runs(x0, width, noise->period[0], runs_x);
    uint32_t run_count_y = split_runs(y0, height, noise->period[1], runs_y);
    tile_target<Value> target = {out, accumulator, width * noise->asset.channels};
    if (!planar_texton_fits(&noise->asset)) {
        for (uint32_t ry = 0; ry < run_count_y; ry++)
            for (uint32_t rx = 0; rx < run_count_x; rx++)
                render_block_32(noise, &runs_x[rx], &runs_y[ry], &target);
        return;
    }
    block_setup setup;
    make_block_setup(noise, &setup);
    for (uint32_t ry = 0; ry < run_count_y; ry++)
        for (uint32_t rx = 0; rx < run_count_x; rx++)
            render_region(noise, &setup, &runs_x[rx], &runs_y[ry], &target);
}

/* The scratch accumulator: the caller's bytes, aligned up to 4. */
uint32_t *scratch_accumulator(void *scratch, size_t scratch_size, size_t values) {
    if (scratch == 0) return 0;
    size_t misalignment = reinterpret_cast<uintptr_t>(scratch) % sizeof(uint32_t);
    size_t skip = misalignment ? sizeof(uint32_t) - misalignment : 0;
    if (scratch_size < skip || (scratch_size - skip) / sizeof(uint32_t) < values) return 0;
    return static_cast<uint32_t *>(static_cast<void *>(static_cast<unsigned char *>(scratch) + skip));
}

int check_noise(const dsn_noise *noise, const void *out) {
    if (noise == 0 || out == 0) return DSN_ERR_NULL;
    return noise->asset.texton != 0 ? DSN_OK : DSN_ERR_ARGUMENT;
}

/* A tile of converted values; the scratch holds the 32-bit sums of the fallback. */
template <typename Value>
int tile_converted(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                   Value *out, void *scratch, size_t scratch_size) {
    size_t values = 0;
    int err = check_noise(noise, out);
    if (err == DSN_OK) err = tile_values(noise, width, height, &values);
    if (err != DSN_OK) return err;
    uint32_t *accumulator = scratch_accumulator(scratch, scratch_size, values);
    if (accumulator == 0) return DSN_ERR_SCRATCH;
    render_tile(noise, uint32_t(x0), uint32_t(y0), width, height, out, accumulator);
    return DSN_OK;
}

} // namespace

extern "C" size_t dsn_tile_scratch_size(const dsn_noise *noise, uint32_t width, uint32_t height) {
    size_t values = 0;
    if (check_noise(noise, noise) != DSN_OK || tile_values(noise, width, height, &values) != DSN_OK) return 0;
    return values * sizeof(uint32_t) + sizeof(uint32_t) - 1;
}

extern "C" int dsn_tile_fixed(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                              int32_t *out, void *scratch, size_t scratch_size) {
    (void)scratch;
    (void)scratch_size;
    size_t values = 0;
    int err = check_noise(noise, out);
    if (err == DSN_OK) err = tile_values(noise, width, height, &values);
    if (err != DSN_OK) return err;
    /* The output itself is the 32-bit accumulator of the fallback (uint32 may alias int32). */
    render_tile(noise, uint32_t(x0), uint32_t(y0), width, height, out,
                static_cast<uint32_t *>(static_cast<void *>(out)));
    return DSN_OK;
}

extern "C" int dsn_tile_float(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                              float *out, void *scratch, size_t scratch_size) {
    return tile_converted(noise, x0, y0, width, height, out, scratch, scratch_size);
}

extern "C" int dsn_tile_u8(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                           uint8_t *out, void *scratch, size_t scratch_size) {
    return tile_converted(noise, x0, y0, width, height, out, scratch, scratch_size);
}
