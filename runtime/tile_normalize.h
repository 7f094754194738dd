/* runtime/tile_normalize.h - the normalization of a block's 16-bit sums into the output (fixed, float
   or 8-bit), bit for bit dsn_normalize and the API-edge conversions: exactly split into 32-bit SIMD
   lanes when the noise allows it (SSE2: 8 pixels per step; AVX2: 16), one pixel at a time otherwise.
   Internal to tile_render.h. */
#ifndef DSN_TILE_NORMALIZE_H
#define DSN_TILE_NORMALIZE_H

#include "tile_block.h"

namespace {

/* ---- Normalization of 16-bit sums ----
   dsn_normalize computes round((offset_c + sum_k gain_ck Q_k) / 2^s) in 64 bits. When every |Q_k| <
   2^15 it splits exactly into 32-bit lanes: gain = 2^15 high + low with low in [-2^14, 2^14) (so |high|
   <= 2^14), A = sum high_k Q_k and B = sum low_k Q_k (|A|, |B| < 3 2^29), and P = offset + 2^(s-1) =
   2^s P_q + 2^15 P_m + P_l (P_m < 2^(s-15), P_l < 2^15). Then
       sum = 2^s P_q + 2^15 (P_m + A + floor((B + P_l) / 2^15)) + ((B + P_l) mod 2^15), so
       result = P_q + floor((P_m + A + floor((B + P_l) / 2^15)) / 2^(s-15))
   where every intermediate stays below 2^31 in magnitude. This needs s >= 16, and P_q +- 2^(46-s) inside
   int32 so that the int32 saturation of dsn_normalize can never act. With vectors, A and B + P_l are
   two pmaddwd each: (Q_0, Q_1) . (high_0, high_1) + (Q_2, 1) . (high_2, 0), and the same with
   (low_0, low_1) and (low_2, P_l). */
typedef struct split_normalization {
    int16_t high[9], low[9];
    int32_t p_q[3], p_m[3], p_l[3];
    uint32_t shift; /* s - 15 */
} split_normalization;

int make_split_normalization(const dsn_noise *noise, split_normalization *split) {
    const uint32_t s = noise->gain_shift, channels = noise->asset.channels;
    if (s < 16 || s > 32) return 0;
    for (uint32_t c = 0; c < channels; c++) {
        const int64_t gain_limit = int64_t(1) << 29, offset_limit = int64_t(1) << 61;
        if (noise->offset[c] <= -offset_limit || noise->offset[c] >= offset_limit) return 0;
        for (uint32_t k = 0; k < 3; k++) {
            int64_t gain = k < channels ? noise->gain[c * 3 + k] : 0;
            if (gain <= -gain_limit || gain >= gain_limit)
                return 0; /* what init guarantees; else per pixel */
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
    __m128i high_pair[3], high_third[3], low_pair[3], low_third[3], p_q[3], p_m[3], shift;
} split_vectors;

void make_split_vectors(const split_normalization *split, uint32_t channels, split_vectors *v) {
    for (uint32_t c = 0; c < channels; c++) {
        const int16_t *high = split->high + 3 * c, *low = split->low + 3 * c;
        v->high_pair[c] =
            _mm_setr_epi16(high[0], high[1], high[0], high[1], high[0], high[1], high[0], high[1]);
        v->high_third[c] = _mm_setr_epi16(high[2], 0, high[2], 0, high[2], 0, high[2], 0);
        v->low_pair[c] = _mm_setr_epi16(low[0], low[1], low[0], low[1], low[0], low[1], low[0], low[1]);
        const int16_t p_l = int16_t(split->p_l[c]);
        v->low_third[c] = _mm_setr_epi16(low[2], p_l, low[2], p_l, low[2], p_l, low[2], p_l);
        v->p_q[c] = _mm_set1_epi32(split->p_q[c]);
        v->p_m[c] = _mm_set1_epi32(split->p_m[c]);
    }
    v->shift = _mm_cvtsi32_si128(int32_t(split->shift));
}

/* Four pixels of output channel c: `pair` holds (Q_0, Q_1) and `third` (Q_2, 1) per pixel. */
inline __m128i normalize_4(const split_vectors *v, uint32_t c, __m128i pair, __m128i third) {
    __m128i a = _mm_add_epi32(_mm_madd_epi16(pair, v->high_pair[c]), _mm_madd_epi16(third, v->high_third[c]));
    __m128i b = _mm_add_epi32(_mm_madd_epi16(pair, v->low_pair[c]), _mm_madd_epi16(third, v->low_third[c]));
    __m128i x = _mm_add_epi32(_mm_add_epi32(v->p_m[c], a), _mm_srai_epi32(b, 15));
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
    /* Zeroed because gcc -Os cannot see that vectors is 2 or 6 (the stores below are free at -O2). */
    __m128i words[3] = {_mm_setzero_si128(), _mm_setzero_si128(), _mm_setzero_si128()};
#pragma GCC unroll 3
    for (uint32_t i = 0; i < vectors; i += 2)
        words[i / 2] = _mm_packs_epi32(to_u8_range(v[i]), to_u8_range(v[i + 1]));
    __m128i first = _mm_packus_epi16(words[0], vectors > 2 ? words[1] : words[0]);
    __m128i second = _mm_packus_epi16(vectors > 2 ? words[2] : words[0], vectors > 2 ? words[2] : words[0]);
    if (values == 4 * vectors) { /* 24 bytes (3 channels) or 8 (1 channel) */
        if (vectors > 2) {
            _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(out)), first);
            _mm_storel_epi64(static_cast<__m128i *>(static_cast<void *>(out + 16)), second);
        } else {
            _mm_storel_epi64(static_cast<__m128i *>(static_cast<void *>(out)), first);
        }
        return;
    }
    uint8_t buffer[32];
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(buffer)), first);
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(buffer + 16)), second);
    for (uint32_t i = 0; i < values; i++) out[i] = buffer[i];
}

#if defined(__AVX2__)
/* normalize_4 on both 128-bit halves at once (the constants repeated in each half). */
inline __m256i normalize_8(const __m256i *constants, __m256i shift, __m256i pair, __m256i third) {
    __m256i a =
        _mm256_add_epi32(_mm256_madd_epi16(pair, constants[0]), _mm256_madd_epi16(third, constants[1]));
    __m256i b =
        _mm256_add_epi32(_mm256_madd_epi16(pair, constants[2]), _mm256_madd_epi16(third, constants[3]));
    __m256i x = _mm256_add_epi32(_mm256_add_epi32(constants[5], a), _mm256_srai_epi32(b, 15));
    return _mm256_add_epi32(_mm256_sra_epi32(x, _mm256_castsi256_si128(shift)), constants[4]);
}

/* interleave_3 on both halves. */
inline void interleave_3x2(__m256i r, __m256i g, __m256i b, __m256i *out) {
    __m256 blue = _mm256_castsi256_ps(b);
    __m256 rg_low = _mm256_castsi256_ps(_mm256_unpacklo_epi32(r, g)),
           rg_high = _mm256_castsi256_ps(_mm256_unpackhi_epi32(r, g));
    __m256 first = _mm256_shuffle_ps(blue, rg_low, _MM_SHUFFLE(3, 2, 0, 0));
    __m256 second = _mm256_shuffle_ps(rg_low, blue, _MM_SHUFFLE(1, 1, 3, 3));
    __m256 third = _mm256_shuffle_ps(blue, rg_high, _MM_SHUFFLE(3, 2, 2, 2));
    out[0] = _mm256_castps_si256(_mm256_shuffle_ps(rg_low, first, _MM_SHUFFLE(2, 0, 1, 0)));
    out[1] = _mm256_castps_si256(_mm256_shuffle_ps(second, rg_high, _MM_SHUFFLE(1, 0, 2, 0)));
    __m256 last = _mm256_shuffle_ps(rg_high, blue, _MM_SHUFFLE(3, 3, 3, 3));
    out[2] = _mm256_castps_si256(_mm256_shuffle_ps(third, last, _MM_SHUFFLE(2, 0, 2, 0)));
}

/* Row `row` of a block, `count` pixels, 16 at a time: 128-bit unpacking works within each half, so the
   low halves hold pixels 0-7 and the high halves pixels 8-15, each stored as the SSE2 code does. */
template <uint32_t channels, typename Value>
void normalize_row_split_avx2(const split_vectors *v, const block_accumulator *block, uint32_t row,
                              uint32_t count, Value *out) {
    const uint32_t plane = block_height * block_stride;
    const uint16_t *sums = block->values + row * block_stride;
    __m256i constants[3][6];
    for (uint32_t c = 0; c < channels; c++) {
        constants[c][0] = _mm256_broadcastsi128_si256(v->high_pair[c]);
        constants[c][1] = _mm256_broadcastsi128_si256(v->high_third[c]);
        constants[c][2] = _mm256_broadcastsi128_si256(v->low_pair[c]);
        constants[c][3] = _mm256_broadcastsi128_si256(v->low_third[c]);
        constants[c][4] = _mm256_broadcastsi128_si256(v->p_q[c]);
        constants[c][5] = _mm256_broadcastsi128_si256(v->p_m[c]);
    }
    const __m256i shift = _mm256_castsi128_si256(v->shift), zero = _mm256_setzero_si256(),
                  ones = _mm256_set1_epi16(1);
    for (uint32_t i = 0; i < count; i += 16) {
        const uint32_t pixels = count - i < 16 ? count - i : 16;
        __m256i q0 = _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(sums + i)));
        __m256i q1 = zero, q2 = zero;
        if (channels == 3) {
            q1 =
                _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(sums + plane + i)));
            q2 = _mm256_loadu_si256(
                static_cast<const __m256i *>(static_cast<const void *>(sums + 2 * plane + i)));
        }
        __m256i pair_low = _mm256_unpacklo_epi16(q0, q1), pair_high = _mm256_unpackhi_epi16(q0, q1);
        __m256i third_low = _mm256_unpacklo_epi16(q2, ones), third_high = _mm256_unpackhi_epi16(q2, ones);
        __m128i halves[2][6];
        if (channels == 3) {
            __m256i low[3], high[3];
            interleave_3x2(normalize_8(constants[0], shift, pair_low, third_low),
                           normalize_8(constants[1], shift, pair_low, third_low),
                           normalize_8(constants[2], shift, pair_low, third_low), low);
            interleave_3x2(normalize_8(constants[0], shift, pair_high, third_high),
                           normalize_8(constants[1], shift, pair_high, third_high),
                           normalize_8(constants[2], shift, pair_high, third_high), high);
            for (uint32_t k = 0; k < 3; k++) {
                halves[0][k] = _mm256_castsi256_si128(low[k]);
                halves[0][k + 3] = _mm256_castsi256_si128(high[k]);
                halves[1][k] = _mm256_extracti128_si256(low[k], 1);
                halves[1][k + 3] = _mm256_extracti128_si256(high[k], 1);
            }
            store_vectors(out + i * 3, halves[0], 6, (pixels < 8 ? pixels : 8) * 3);
            if (pixels > 8) store_vectors(out + (i + 8) * 3, halves[1], 6, (pixels - 8) * 3);
        } else {
            __m256i low = normalize_8(constants[0], shift, pair_low, third_low),
                    high = normalize_8(constants[0], shift, pair_high, third_high);
            halves[0][0] = _mm256_castsi256_si128(low);
            halves[0][1] = _mm256_castsi256_si128(high);
            halves[1][0] = _mm256_extracti128_si256(low, 1);
            halves[1][1] = _mm256_extracti128_si256(high, 1);
            store_vectors(out + i, halves[0], 2, pixels < 8 ? pixels : 8);
            if (pixels > 8) store_vectors(out + i + 8, halves[1], 2, pixels - 8);
        }
    }
}
#endif

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
        const __m128i ones = _mm_set1_epi16(1);
        __m128i third_low = _mm_unpacklo_epi16(q2, ones), third_high = _mm_unpackhi_epi16(q2, ones);
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

/* The row normalization of this build: 16 pixels per step with AVX2, else 8. */
template <uint32_t channels, typename Value>
inline void normalize_row_vectors(const split_vectors *v, const block_accumulator *block, uint32_t row,
                                  uint32_t count, Value *out) {
#if defined(__AVX2__)
    normalize_row_split_avx2<channels>(v, block, row, count, out);
#else
    normalize_row_split<channels>(v, block, row, count, out);
#endif
}
#endif

} // namespace

#endif /* DSN_TILE_NORMALIZE_H */
