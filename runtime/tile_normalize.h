/* runtime/tile_normalize.h - the normalization of a strip row's 16-bit sums (tile_strips.h) into the
   output (fixed, float or 8-bit), bit for bit dsn_normalize and the API-edge conversions: exactly split
   into 32-bit SIMD lanes when the noise allows it (a whole strip, 8 pixels with SSE2 or 16 with AVX2, at
   once), one pixel at a time otherwise. Internal to tile_render.h. */
#ifndef DSN_TILE_NORMALIZE_H
#define DSN_TILE_NORMALIZE_H

#include "tile_strips.h"

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

int make_split_normalization(const dsn_noise_state *noise, split_normalization *split) {
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

/* Q_k of a 16-bit sum, as the uint32 bits dsn_normalize reads. */
inline uint32_t widen_sum(uint16_t value) { return (uint32_t(value) ^ 0x8000u) - 0x8000u; }

/* The vector operations of the split normalization, on the strip's vector width. 128-bit lanes
   compute independently in AVX2 and AVX-512 (unpacking and shuffles too), so their code is the SSE2 code
   run on two or four groups of 8 pixels at once: with AVX2 pixels 0-3 and 8-11 in `low`, 4-7 and 12-15 in
   `high`; with AVX-512 also 16-19 and 24-27 in `low`, 20-23 and 28-31 in `high`. */
#if defined(__AVX512BW__)
typedef __m512 strip_floats;
inline strip_vector broadcast_lanes(__m128i value) { return _mm512_broadcast_i32x4(value); }
inline strip_vector madd_16(strip_vector a, strip_vector b) { return _mm512_madd_epi16(a, b); }
inline strip_vector add_32(strip_vector a, strip_vector b) { return _mm512_add_epi32(a, b); }
inline strip_vector shift_right_15(strip_vector a) { return _mm512_srai_epi32(a, 15); }
inline strip_vector shift_right(strip_vector a, __m128i count) { return _mm512_sra_epi32(a, count); }
inline strip_vector unpack_low_16(strip_vector a, strip_vector b) { return _mm512_unpacklo_epi16(a, b); }
inline strip_vector unpack_high_16(strip_vector a, strip_vector b) { return _mm512_unpackhi_epi16(a, b); }
inline strip_vector unpack_low_32(strip_vector a, strip_vector b) { return _mm512_unpacklo_epi32(a, b); }
inline strip_vector unpack_high_32(strip_vector a, strip_vector b) { return _mm512_unpackhi_epi32(a, b); }
inline strip_vector set_16(int16_t value) { return _mm512_set1_epi16(value); }
inline strip_floats as_floats(strip_vector a) { return _mm512_castsi512_ps(a); }
inline strip_vector as_integers(strip_floats a) { return _mm512_castps_si512(a); }
template <int Order>
inline strip_floats shuffle(strip_floats a, strip_floats b) {
    return _mm512_shuffle_ps(a, b, Order);
}
inline void store_sums(uint16_t *dst, strip_vector value) { _mm512_storeu_si512(dst, value); }
/* 128-bit lane `part` of a vector: pixels 8 part .. 8 part + 7 of a normalized strip. */
inline __m128i lane_128(strip_vector v, uint32_t part) {
    switch (part) {
    case 0:
        return _mm512_castsi512_si128(v);
    case 1:
        return _mm512_extracti32x4_epi32(v, 1);
    case 2:
        return _mm512_extracti32x4_epi32(v, 2);
    default:
        return _mm512_extracti32x4_epi32(v, 3);
    }
}
#elif defined(__AVX2__)
typedef __m256 strip_floats;
inline strip_vector broadcast_lanes(__m128i value) { return _mm256_broadcastsi128_si256(value); }
inline strip_vector madd_16(strip_vector a, strip_vector b) { return _mm256_madd_epi16(a, b); }
inline strip_vector add_32(strip_vector a, strip_vector b) { return _mm256_add_epi32(a, b); }
inline strip_vector shift_right_15(strip_vector a) { return _mm256_srai_epi32(a, 15); }
inline strip_vector shift_right(strip_vector a, __m128i count) { return _mm256_sra_epi32(a, count); }
inline strip_vector unpack_low_16(strip_vector a, strip_vector b) { return _mm256_unpacklo_epi16(a, b); }
inline strip_vector unpack_high_16(strip_vector a, strip_vector b) { return _mm256_unpackhi_epi16(a, b); }
inline strip_vector unpack_low_32(strip_vector a, strip_vector b) { return _mm256_unpacklo_epi32(a, b); }
inline strip_vector unpack_high_32(strip_vector a, strip_vector b) { return _mm256_unpackhi_epi32(a, b); }
inline strip_vector set_16(int16_t value) { return _mm256_set1_epi16(value); }
inline strip_floats as_floats(strip_vector a) { return _mm256_castsi256_ps(a); }
inline strip_vector as_integers(strip_floats a) { return _mm256_castps_si256(a); }
template <int Order>
inline strip_floats shuffle(strip_floats a, strip_floats b) {
    return _mm256_shuffle_ps(a, b, Order);
}
inline void store_sums(uint16_t *dst, strip_vector value) {
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(dst)), value);
}
inline __m128i lane_128(strip_vector v, uint32_t part) {
    return part == 0 ? _mm256_castsi256_si128(v) : _mm256_extracti128_si256(v, 1);
}
#else
typedef __m128 strip_floats;
inline strip_vector broadcast_lanes(__m128i value) { return value; }
inline strip_vector madd_16(strip_vector a, strip_vector b) { return _mm_madd_epi16(a, b); }
inline strip_vector add_32(strip_vector a, strip_vector b) { return _mm_add_epi32(a, b); }
inline strip_vector shift_right_15(strip_vector a) { return _mm_srai_epi32(a, 15); }
inline strip_vector shift_right(strip_vector a, __m128i count) { return _mm_sra_epi32(a, count); }
inline strip_vector unpack_low_16(strip_vector a, strip_vector b) { return _mm_unpacklo_epi16(a, b); }
inline strip_vector unpack_high_16(strip_vector a, strip_vector b) { return _mm_unpackhi_epi16(a, b); }
inline strip_vector unpack_low_32(strip_vector a, strip_vector b) { return _mm_unpacklo_epi32(a, b); }
inline strip_vector unpack_high_32(strip_vector a, strip_vector b) { return _mm_unpackhi_epi32(a, b); }
inline strip_vector set_16(int16_t value) { return _mm_set1_epi16(value); }
inline strip_floats as_floats(strip_vector a) { return _mm_castsi128_ps(a); }
inline strip_vector as_integers(strip_floats a) { return _mm_castps_si128(a); }
template <int Order>
inline strip_floats shuffle(strip_floats a, strip_floats b) {
    return _mm_shuffle_ps(a, b, Order);
}
inline void store_sums(uint16_t *dst, strip_vector value) {
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(dst)), value);
}
inline __m128i lane_128(strip_vector v, uint32_t) { return v; }
#endif

/* The first `pixels` pixels of a strip row, one at a time. */
template <typename Value>
void normalize_strip_scalar(const dsn_noise_state *noise, const strip_vector *sums, uint32_t pixels,
                            Value *out) {
    const uint32_t channels = noise->asset.channels;
    uint16_t values[3][lane];
    for (uint32_t c = 0; c < 3; c++) store_sums(values[c], sums[c]);
    for (uint32_t i = 0; i < pixels; i++) {
        uint32_t q[3] = {0, 0, 0};
        int32_t fixed[3];
        for (uint32_t k = 0; k < channels; k++) q[k] = widen_sum(values[k][i]);
        dsn_normalize(noise, q, fixed);
        for (uint32_t c = 0; c < channels; c++) store_value(out + i * channels + c, fixed[c]);
    }
}

/* The split normalization's constants, repeated in every 128-bit lane. */
typedef struct split_vectors {
    strip_vector high_pair[3], high_third[3], low_pair[3], low_third[3], p_q[3], p_m[3];
    __m128i shift;
} split_vectors;

void make_split_vectors(const split_normalization *split, uint32_t channels, split_vectors *v) {
    for (uint32_t c = 0; c < channels; c++) {
        const int16_t *high = split->high + 3 * c, *low = split->low + 3 * c;
        const int16_t p_l = int16_t(split->p_l[c]);
        v->high_pair[c] = broadcast_lanes(
            _mm_setr_epi16(high[0], high[1], high[0], high[1], high[0], high[1], high[0], high[1]));
        v->high_third[c] = broadcast_lanes(_mm_setr_epi16(high[2], 0, high[2], 0, high[2], 0, high[2], 0));
        v->low_pair[c] =
            broadcast_lanes(_mm_setr_epi16(low[0], low[1], low[0], low[1], low[0], low[1], low[0], low[1]));
        v->low_third[c] = broadcast_lanes(_mm_setr_epi16(low[2], p_l, low[2], p_l, low[2], p_l, low[2], p_l));
        v->p_q[c] = broadcast_lanes(_mm_set1_epi32(split->p_q[c]));
        v->p_m[c] = broadcast_lanes(_mm_set1_epi32(split->p_m[c]));
    }
    v->shift = _mm_cvtsi32_si128(int32_t(split->shift));
}

/* Output channel c of 4 pixels per 128-bit lane: `pair` holds (Q_0, Q_1) and `third` (Q_2, 1) per pixel. */
inline strip_vector normalize_lanes(const split_vectors *v, uint32_t c, strip_vector pair,
                                    strip_vector third) {
    strip_vector a = add_32(madd_16(pair, v->high_pair[c]), madd_16(third, v->high_third[c]));
    strip_vector b = add_32(madd_16(pair, v->low_pair[c]), madd_16(third, v->low_third[c]));
    strip_vector x = add_32(add_32(v->p_m[c], a), shift_right_15(b));
    return add_32(shift_right(x, v->shift), v->p_q[c]);
}

/* Per 128-bit lane: (r0 r1 r2 r3), (g0 ..), (b0 ..) -> r0 g0 b0 r1 | g1 b1 r2 g2 | b2 r3 g3 b3. shufps
   only moves bits between lanes (no arithmetic), so reading the integers as floats here is exact. */
inline void interleave_3(strip_vector r, strip_vector g, strip_vector b, strip_vector *out) {
    strip_floats blue = as_floats(b);
    strip_floats rg_low = as_floats(unpack_low_32(r, g)), rg_high = as_floats(unpack_high_32(r, g));
    strip_floats first = shuffle<_MM_SHUFFLE(3, 2, 0, 0)>(blue, rg_low);  /* b0 b0 r1 g1 */
    strip_floats second = shuffle<_MM_SHUFFLE(1, 1, 3, 3)>(rg_low, blue); /* g1 g1 b1 b1 */
    strip_floats third = shuffle<_MM_SHUFFLE(3, 2, 2, 2)>(blue, rg_high); /* b2 b2 r3 g3 */
    out[0] = as_integers(shuffle<_MM_SHUFFLE(2, 0, 1, 0)>(rg_low, first));
    out[1] = as_integers(shuffle<_MM_SHUFFLE(1, 0, 2, 0)>(second, rg_high));
    strip_floats last = shuffle<_MM_SHUFFLE(3, 3, 3, 3)>(rg_high, blue); /* g3 g3 b3 b3 */
    out[2] = as_integers(shuffle<_MM_SHUFFLE(2, 0, 2, 0)>(third, last));
}

/* 4 output values. `stream` (for outputs far larger than the caches): past the caches, with
   non-temporal stores, where out is 16-byte aligned (the tile call ends with a store fence). */
inline void put_4(int32_t *out, __m128i values, int stream) {
    __m128i *destination = static_cast<__m128i *>(static_cast<void *>(out));
    if (stream && (reinterpret_cast<uintptr_t>(out) & 15u) == 0)
        _mm_stream_si128(destination, values);
    else
        _mm_storeu_si128(destination, values);
}
inline void put_4(float *out, __m128 values, int stream) {
    if (stream && (reinterpret_cast<uintptr_t>(out) & 15u) == 0)
        _mm_stream_ps(out, values);
    else
        _mm_storeu_ps(out, values);
}

/* Stores `vectors` interleaved output vectors (4 values each) of which the first `values` are wanted. */
inline void store_vectors(int32_t *out, const __m128i *v, uint32_t vectors, uint32_t values, int stream) {
    if (values == 4 * vectors) {
#pragma GCC unroll 6
        for (uint32_t i = 0; i < vectors; i++) put_4(out + 4 * i, v[i], stream);
        return;
    }
    int32_t buffer[24];
    for (uint32_t i = 0; i < vectors; i++)
        _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(buffer + 4 * i)), v[i]);
    for (uint32_t i = 0; i < values; i++) out[i] = buffer[i];
}

/* float(value) * 2^-16: the conversion rounds once to nearest, like dsn_fixed_to_float. */
inline void store_vectors(float *out, const __m128i *v, uint32_t vectors, uint32_t values, int stream) {
    const __m128 scale = _mm_set1_ps(1.0f / 65536.0f);
    float buffer[24];
    float *dst = values == 4 * vectors ? out : buffer;
#pragma GCC unroll 6
    for (uint32_t i = 0; i < vectors; i++)
        put_4(dst + 4 * i, _mm_mul_ps(_mm_cvtepi32_ps(v[i]), scale), stream);
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

inline void store_vectors(uint8_t *out, const __m128i *v, uint32_t vectors, uint32_t values, int) {
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

/* Stores the normalized strip: `values` holds, per 128-bit lane, 4 pixels' interleaved values (in the
   order low pair, high pair: 3 vectors each with 3 channels, 1 with 1), of which `pixels` pixels are
   wanted. 128-bit lane j holds pixels 8 j .. 8 j + 7 (lane_128). */
#if defined(__AVX512BW__)
/* The output vectors of a whole strip (32 pixels: 16 output values each, in output order) from its
   normalized vectors, whose 128-bit lane j holds pixels 8 j .. 8 j + 7 (4 values per vector, in the
   order of store_vectors). */
template <uint32_t Channels>
inline void output_order(const __m512i *values, __m512i *out) {
    if (Channels == 3) {
        /* Lanes 0 and 2, and 1 and 3, of each pair of vectors: then lane j of all six is in two. */
        __m512i even[3], odd[3];
        for (uint32_t i = 0; i < 3; i++) {
            even[i] = _mm512_shuffle_i32x4(values[2 * i], values[2 * i + 1], _MM_SHUFFLE(2, 0, 2, 0));
            odd[i] = _mm512_shuffle_i32x4(values[2 * i], values[2 * i + 1], _MM_SHUFFLE(3, 1, 3, 1));
        }
        out[0] = _mm512_shuffle_i32x4(even[0], even[1], _MM_SHUFFLE(2, 0, 2, 0)); /* lane 0 of v0 .. v3 */
        out[1] = _mm512_shuffle_i32x4(even[2], odd[0], _MM_SHUFFLE(2, 0, 2, 0));  /* 0 of v4 v5, 1 of v0 v1 */
        out[2] = _mm512_shuffle_i32x4(odd[1], odd[2], _MM_SHUFFLE(2, 0, 2, 0));   /* lane 1 of v2 .. v5 */
        out[3] = _mm512_shuffle_i32x4(even[0], even[1], _MM_SHUFFLE(3, 1, 3, 1)); /* lane 2 of v0 .. v3 */
        out[4] = _mm512_shuffle_i32x4(even[2], odd[0], _MM_SHUFFLE(3, 1, 3, 1));  /* 2 of v4 v5, 3 of v0 v1 */
        out[5] = _mm512_shuffle_i32x4(odd[1], odd[2], _MM_SHUFFLE(3, 1, 3, 1));   /* lane 3 of v2 .. v5 */
    } else {
        const __m512i first = _mm512_setr_epi64(0, 1, 8, 9, 2, 3, 10, 11);
        const __m512i second = _mm512_setr_epi64(4, 5, 12, 13, 6, 7, 14, 15);
        out[0] = _mm512_permutex2var_epi64(values[0], first, values[1]);
        out[1] = _mm512_permutex2var_epi64(values[0], second, values[1]);
    }
}

inline __m512i output_vector(__m512i fixed, int32_t *) { return fixed; }
inline __m512 output_vector(__m512i fixed, float *) {
    return _mm512_mul_ps(_mm512_cvtepi32_ps(fixed), _mm512_set1_ps(1.0f / 65536.0f));
}

/* 16 output values. `stream`: past the caches (put_4), in one store where out is 64-byte aligned, in four
   where it is 16-byte aligned. */
inline void put_16(int32_t *out, __m512i values, int stream) {
    if (stream && (reinterpret_cast<uintptr_t>(out) & 63u) == 0) {
        _mm512_stream_si512(static_cast<__m512i *>(static_cast<void *>(out)), values);
    } else if (stream && (reinterpret_cast<uintptr_t>(out) & 15u) == 0) {
        __m128i *destination = static_cast<__m128i *>(static_cast<void *>(out));
        _mm_stream_si128(destination, _mm512_castsi512_si128(values));
        _mm_stream_si128(destination + 1, _mm512_extracti32x4_epi32(values, 1));
        _mm_stream_si128(destination + 2, _mm512_extracti32x4_epi32(values, 2));
        _mm_stream_si128(destination + 3, _mm512_extracti32x4_epi32(values, 3));
    } else {
        _mm512_storeu_si512(out, values);
    }
}
inline void put_16(float *out, __m512 values, int stream) {
    put_16(static_cast<int32_t *>(static_cast<void *>(out)), _mm512_castps_si512(values), stream);
}

/* A whole strip (32 pixels) in 64-byte stores (and one of 32 bytes for 8-bit RGB). */
template <uint32_t Channels, typename Value>
inline int store_whole_strip(const strip_vector *values, Value *out, int stream) {
    __m512i ordered[6];
    output_order<Channels>(values, ordered);
    for (uint32_t m = 0; m < 2 * Channels; m++) put_16(out + 16 * m, output_vector(ordered[m], out), stream);
    return 1;
}
/* to_u8_range on 16 values. */
inline __m512i to_u8_range(__m512i value) {
    value = _mm512_min_epi32(_mm512_max_epi32(value, _mm512_setzero_si512()), _mm512_set1_epi32(DSN_ONE));
    return _mm512_srli_epi32(
        _mm512_add_epi32(_mm512_sub_epi32(_mm512_slli_epi32(value, 8), value), _mm512_set1_epi32(32768)), 16);
}

/* 8-bit output packs like store_vectors, per 128-bit lane: 16 + 8 bytes (RGB) or 8 bytes (grey) of each
   lane, brought together by one or two dword permutes. */
template <uint32_t Channels>
inline int store_whole_strip(const strip_vector *values, uint8_t *out, int) {
    if (Channels == 3) {
        const __m512i first =
            _mm512_packus_epi16(_mm512_packs_epi32(to_u8_range(values[0]), to_u8_range(values[1])),
                                _mm512_packs_epi32(to_u8_range(values[2]), to_u8_range(values[3])));
        const __m512i words = _mm512_packs_epi32(to_u8_range(values[4]), to_u8_range(values[5]));
        const __m512i second = _mm512_packus_epi16(words, words);
        const __m512i low = _mm512_setr_epi32(0, 1, 2, 3, 16, 17, 4, 5, 6, 7, 20, 21, 8, 9, 10, 11);
        const __m512i high = _mm512_setr_epi32(24, 25, 12, 13, 14, 15, 28, 29, 0, 0, 0, 0, 0, 0, 0, 0);
        _mm512_storeu_si512(out, _mm512_permutex2var_epi32(first, low, second));
        _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(out + 64)),
                            _mm512_castsi512_si256(_mm512_permutex2var_epi32(first, high, second)));
    } else {
        const __m512i words = _mm512_packs_epi32(to_u8_range(values[0]), to_u8_range(values[1]));
        const __m512i bytes = _mm512_packus_epi16(words, words);
        _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(out)),
                            _mm512_castsi512_si256(
                                _mm512_permutexvar_epi64(_mm512_setr_epi64(0, 2, 4, 6, 0, 0, 0, 0), bytes)));
    }
    return 1;
}

#elif defined(__AVX2__)
/* A whole strip (16 pixels) of fixed or float output; 8-bit output takes the 128-bit path (returns 0).
   Pixels 0-7 are the low 128-bit lanes of values 0 .. 2 Channels - 1, pixels 8-15 the high lanes. When
   streaming (16-byte stores), each lane is stored where it goes; else pairs of lanes are brought together
   for 32-byte stores. */
template <typename Value>
struct output_vectors; /* the 256-bit vector of 8 output values */
template <>
struct output_vectors<int32_t> {
    typedef __m256i type;
};
template <>
struct output_vectors<float> {
    typedef __m256 type;
};
inline __m256i output_vector(__m256i fixed, int32_t *) { return fixed; }
inline __m256 output_vector(__m256i fixed, float *) {
    return _mm256_mul_ps(_mm256_cvtepi32_ps(fixed), _mm256_set1_ps(1.0f / 65536.0f));
}
inline void stream_4(int32_t *out, __m128i values) {
    _mm_stream_si128(static_cast<__m128i *>(static_cast<void *>(out)), values);
}
inline void stream_4(float *out, __m128 values) { _mm_stream_ps(out, values); }
inline __m128i low_lane(__m256i v) { return _mm256_castsi256_si128(v); }
inline __m128 low_lane(__m256 v) { return _mm256_castps256_ps128(v); }
inline __m128i high_lane(__m256i v) { return _mm256_extracti128_si256(v, 1); }
inline __m128 high_lane(__m256 v) { return _mm256_extractf128_ps(v, 1); }
inline void put_8(int32_t *out, __m256i v) {
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(out)), v);
}
inline void put_8(float *out, __m256 v) { _mm256_storeu_ps(out, v); }
inline __m256i join_lanes(__m256i a, __m256i b, int high) {
    return high ? _mm256_permute2x128_si256(a, b, 0x31) : _mm256_permute2x128_si256(a, b, 0x20);
}
inline __m256 join_lanes(__m256 a, __m256 b, int high) {
    return high ? _mm256_permute2f128_ps(a, b, 0x31) : _mm256_permute2f128_ps(a, b, 0x20);
}

template <uint32_t Channels, typename Value>
inline int store_whole_strip(const strip_vector *values, Value *out, int stream) {
    if (stream && (reinterpret_cast<uintptr_t>(out) & 15u) == 0) {
        for (uint32_t i = 0; i < 2 * Channels; i++) {
            const typename output_vectors<Value>::type converted = output_vector(values[i], out);
            stream_4(out + 4 * i, low_lane(converted));
            stream_4(out + 8 * Channels + 4 * i, high_lane(converted));
        }
        return 1;
    }
    for (uint32_t i = 0; i < Channels; i++) {
        const typename output_vectors<Value>::type first = output_vector(values[2 * i], out),
                                                   second = output_vector(values[2 * i + 1], out);
        put_8(out + 8 * i, join_lanes(first, second, 0));
        put_8(out + 8 * (Channels + i), join_lanes(first, second, 1));
    }
    return 1;
}
template <uint32_t Channels>
inline int store_whole_strip(const strip_vector *, uint8_t *, int) {
    return 0;
}
#else
/* SSE2: a strip is one 128-bit lane. */
template <uint32_t Channels, typename Value>
inline int store_whole_strip(const strip_vector *values, Value *out, int stream) {
    store_vectors(out, values, 2 * Channels, lane * Channels, stream);
    return 1;
}
#endif

/* Whole strips as store_whole_strip can; else 8 pixels (a 128-bit lane of each vector) at a time. */
template <uint32_t Channels, typename Value>
inline void store_strip(const strip_vector *values, uint32_t pixels, Value *out, int stream) {
    const uint32_t vectors = 2 * Channels;
    if (pixels == lane && store_whole_strip<Channels>(values, out, stream)) return;
    for (uint32_t part = 0; part * 8 < pixels; part++) {
        __m128i group[6];
        for (uint32_t i = 0; i < vectors; i++) group[i] = lane_128(values[i], part);
        const uint32_t rest = pixels - 8 * part;
        store_vectors(out + 8 * Channels * part, group, vectors, (rest < 8 ? rest : 8) * Channels, stream);
    }
}

/* The first `pixels` pixels of a strip row from its sums (one vector per channel); `stream`: put_4. */
template <uint32_t Channels, typename Value>
inline void normalize_strip(const split_vectors *v, const strip_vector *sums, uint32_t pixels, Value *out,
                            int stream) {
    const strip_vector ones = set_16(1);
    strip_vector pair_low = unpack_low_16(sums[0], sums[1]), pair_high = unpack_high_16(sums[0], sums[1]);
    strip_vector third_low = unpack_low_16(sums[2], ones), third_high = unpack_high_16(sums[2], ones);
    strip_vector values[6];
    if (Channels == 3) {
        interleave_3(normalize_lanes(v, 0, pair_low, third_low), normalize_lanes(v, 1, pair_low, third_low),
                     normalize_lanes(v, 2, pair_low, third_low), values);
        interleave_3(normalize_lanes(v, 0, pair_high, third_high),
                     normalize_lanes(v, 1, pair_high, third_high),
                     normalize_lanes(v, 2, pair_high, third_high), values + 3);
    } else {
        values[0] = normalize_lanes(v, 0, pair_low, third_low);
        values[1] = normalize_lanes(v, 0, pair_high, third_high);
    }
    store_strip<Channels>(values, pixels, out, stream);
}

} // namespace

#endif /* DSN_TILE_NORMALIZE_H */
