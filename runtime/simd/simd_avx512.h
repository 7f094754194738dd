/* runtime/simd/simd_avx512.h - the vector operations of the strip path for AVX-512 F and BW (512-bit vectors:
   32 pixels per strip), and of the continuous splat's runs (splat_row.h: 8 pixels per vector). The same names
   as simd_sse2.h and simd_avx2.h; simd.h picks one. */
#ifndef DSN_SIMD_AVX512_H
#define DSN_SIMD_AVX512_H

#if defined(__GNUC__) && !defined(__clang__)
/* GCC 12's AVX-512 intrinsics start some results from a deliberately undefined vector and then warn
   -Wmaybe-uninitialized, or -Wuninitialized where a caller's constants reach them, on their own lines
   (GCC bug 105593, fixed in GCC 13). */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#else
#include <immintrin.h>
#endif

#include "simd/simd_256.h"

namespace {

typedef __m512i vector_512; /* 16 lanes of 32 bits, 8 of 64 bits, 32 of 16 bits or 64 of 8 bits */
typedef __mmask8 mask_8;    /* a bit per lane of a comparison's result */
typedef __mmask16 mask_16;
typedef __mmask64 mask_64;

typedef vector_512 simd_vector; /* 16-bit sums, or 32-bit values, of the strip's pixels */
typedef __m512 simd_floats;
const uint32_t simd_int16_count = 32;

/* ---- Sums ---- */
inline simd_vector load_texels(const uint16_t *src) { return _mm512_loadu_si512(src); }
/* Every channel's two rows from one load (tile_strips.h): each 16-bit texel of a paired plane holds row
   t in its low byte and row t + 1 in its high byte, both biased by 128 (unsigned). Widening the bytes
   (a shuffle per 32 of them, which bound the strips here: two of the four vector pipes of AMD's Zen 4
   run shuffles, at half rate on 512 bits) is left out: row_0 adds the texels as they are, their high
   bytes 256 times over, row_1 the high bytes shifted down, and finish_pair takes row_1 256 times off
   row_0 once per strip (all modulo 2^16, exact: the true sums fit). */
#define DSN_SIMD_PAIRED_ROWS 1
inline void add_pair(simd_vector texels, simd_vector *row_0, simd_vector *row_1) {
    /* One register for both uses: GCC would fold the load into the add and the shift, reading the
       vector (which crosses a cache line wherever it does not start one) twice. */
    __asm__("" : "+v"(texels));
    *row_0 = _mm512_add_epi16(*row_0, texels);
    *row_1 = _mm512_add_epi16(*row_1, _mm512_srli_epi16(texels, 8));
}
inline void finish_pair(simd_vector *row_0, simd_vector row_1) {
    *row_0 = _mm512_sub_epi16(*row_0, _mm512_slli_epi16(row_1, 8));
}
inline simd_vector add_16(simd_vector a, simd_vector b) { return _mm512_add_epi16(a, b); }
inline simd_vector zero_vector() { return _mm512_setzero_si512(); }
inline void store_16(uint16_t *dst, simd_vector value) { _mm512_storeu_si512(dst, value); }

/* ---- Normalization, per 128-bit lane (AVX-512 unpacks and shuffles each lane on its own) ---- */
inline simd_vector broadcast_lanes(__m128i value) { return _mm512_broadcast_i32x4(value); }
inline simd_vector madd_16(simd_vector a, simd_vector b) { return _mm512_madd_epi16(a, b); }
DSN_SIMD_INLINE simd_vector add_32(simd_vector a, simd_vector b) { return _mm512_add_epi32(a, b); }
inline simd_vector shift_right_15(simd_vector a) { return _mm512_srai_epi32(a, 15); }
inline simd_vector shift_right(simd_vector a, __m128i count) { return _mm512_sra_epi32(a, count); }
inline simd_vector unpack_low_16(simd_vector a, simd_vector b) { return _mm512_unpacklo_epi16(a, b); }
inline simd_vector unpack_high_16(simd_vector a, simd_vector b) { return _mm512_unpackhi_epi16(a, b); }
inline simd_vector unpack_low_32(simd_vector a, simd_vector b) { return _mm512_unpacklo_epi32(a, b); }
inline simd_vector unpack_high_32(simd_vector a, simd_vector b) { return _mm512_unpackhi_epi32(a, b); }
inline simd_vector set_16(int16_t value) { return _mm512_set1_epi16(value); }
inline simd_floats as_floats(simd_vector a) { return _mm512_castsi512_ps(a); }
inline simd_vector as_integers(simd_floats a) { return _mm512_castps_si512(a); }
template <int Order>
inline simd_floats shuffle(simd_floats a, simd_floats b) {
    return _mm512_shuffle_ps(a, b, Order);
}

/* ---- Output ---- */
/* 128-bit lane `part` of a vector: pixels 8 part .. 8 part + 7 of a normalized strip. */
inline __m128i lane_128(simd_vector v, uint32_t part) {
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

/* A whole strip's normalized vectors (4 values per 128-bit lane, lane j holding pixels 8 j .. 8 j + 7,
   see tile_store.h) in output order: 16 values per vector. */
template <uint32_t Channels>
inline void output_order(const simd_vector *values, simd_vector *ordered) {
    if (Channels == 3) {
        /* Lanes 0 and 2, and 1 and 3, of each pair of vectors: then lane j of all six is in two. */
        __m512i even[3], odd[3];
        for (uint32_t i = 0; i < 3; i++) {
            even[i] = _mm512_shuffle_i32x4(values[2 * i], values[2 * i + 1], _MM_SHUFFLE(2, 0, 2, 0));
            odd[i] = _mm512_shuffle_i32x4(values[2 * i], values[2 * i + 1], _MM_SHUFFLE(3, 1, 3, 1));
        }
        ordered[0] = _mm512_shuffle_i32x4(even[0], even[1], _MM_SHUFFLE(2, 0, 2, 0)); /* lane 0 of v0 .. v3 */
        ordered[1] =
            _mm512_shuffle_i32x4(even[2], odd[0], _MM_SHUFFLE(2, 0, 2, 0)); /* 0 of v4 v5, 1 of v0 v1 */
        ordered[2] = _mm512_shuffle_i32x4(odd[1], odd[2], _MM_SHUFFLE(2, 0, 2, 0));   /* lane 1 of v2 .. v5 */
        ordered[3] = _mm512_shuffle_i32x4(even[0], even[1], _MM_SHUFFLE(3, 1, 3, 1)); /* lane 2 of v0 .. v3 */
        ordered[4] =
            _mm512_shuffle_i32x4(even[2], odd[0], _MM_SHUFFLE(3, 1, 3, 1)); /* 2 of v4 v5, 3 of v0 v1 */
        ordered[5] = _mm512_shuffle_i32x4(odd[1], odd[2], _MM_SHUFFLE(3, 1, 3, 1)); /* lane 3 of v2 .. v5 */
    } else {
        const __m512i first = _mm512_setr_epi64(0, 1, 8, 9, 2, 3, 10, 11);
        const __m512i second = _mm512_setr_epi64(4, 5, 12, 13, 6, 7, 14, 15);
        ordered[0] = _mm512_permutex2var_epi64(values[0], first, values[1]);
        ordered[1] = _mm512_permutex2var_epi64(values[0], second, values[1]);
    }
}
inline simd_floats to_output_floats(simd_vector fixed) {
    return _mm512_mul_ps(_mm512_cvtepi32_ps(fixed), _mm512_set1_ps(1.0f / 65536.0f));
}
/* 16 output values. Never past the caches here: streamed rows go through stream_line instead
   (DSN_SIMD_STREAM_LINES). */
inline void put_vector(int32_t *out, simd_vector values) { _mm512_storeu_si512(out, values); }
inline void put_vector(float *out, simd_floats values) { _mm512_storeu_ps(out, values); }

/* Streamed rows are staged and written a 64-byte cache line per store (tile_render.h): 16-byte streaming
   stores of a strip that starts inside a line cost more here than the staging. */
#define DSN_SIMD_STREAM_LINES 1
/* A 64-byte cache line from 64-byte aligned `line` to 64-byte aligned `out`, past the caches. */
inline void stream_line(void *out, const void *line) {
    _mm512_stream_si512(static_cast<__m512i *>(out), _mm512_load_si512(line));
}

/* to_u8_range (simd_128.h) on 16 values. */
inline __m512i to_u8_range(__m512i value) {
    value = _mm512_min_epi32(_mm512_max_epi32(value, _mm512_setzero_si512()), _mm512_set1_epi32(DSN_ONE));
    return _mm512_srli_epi32(
        _mm512_add_epi32(_mm512_sub_epi32(_mm512_slli_epi32(value, 8), value), _mm512_set1_epi32(32768)), 16);
}

/* 8-bit output of a whole strip (32 pixels), packed like the 128-bit path per lane: 16 + 8 bytes (RGB)
   or 8 bytes (grey) of each lane, brought together by one or two dword permutes. Returns 1. */
template <uint32_t Channels>
inline int store_whole_strip_u8(const simd_vector *values, uint8_t *out) {
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

/* ---- Continuous splat (splat_row.h): 64-bit lanes, one pixel each ---- */
typedef __m512i splat_vector;
const uint32_t splat_lanes = 8;

inline splat_vector splat_set(uint64_t value) { return _mm512_set1_epi64(static_cast<long long>(value)); }
/* Lane k: first + k step, modulo 2^64. */
inline splat_vector splat_lane_steps(uint64_t first, uint64_t step) {
    return _mm512_add_epi64(_mm512_set1_epi64(static_cast<long long>(first)),
                            _mm512_mullox_epi64(_mm512_set1_epi64(static_cast<long long>(step)),
                                                _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7)));
}
inline splat_vector splat_add(splat_vector a, splat_vector b) { return _mm512_add_epi64(a, b); }
inline void splat_store(uint64_t *out, splat_vector value) { _mm512_storeu_si512(out, value); }
inline splat_vector splat_load(const uint64_t *from) { return _mm512_loadu_si512(from); }
inline splat_vector splat_sub(splat_vector a, splat_vector b) { return _mm512_sub_epi64(a, b); }
inline splat_vector splat_and(splat_vector a, splat_vector b) { return _mm512_and_si512(a, b); }
inline splat_vector splat_or(splat_vector a, splat_vector b) { return _mm512_or_si512(a, b); }
inline splat_vector splat_shift_right(splat_vector value, uint32_t count) {
    return _mm512_srl_epi64(value, _mm_cvtsi32_si128(static_cast<int>(count)));
}
inline splat_vector splat_shift_left(splat_vector value, uint32_t count) {
    return _mm512_sll_epi64(value, _mm_cvtsi32_si128(static_cast<int>(count)));
}
/* The first `count` lanes (all of them from splat_lanes up), the others 0. */
inline splat_vector splat_first_lanes(splat_vector value, uint32_t count) {
    return _mm512_maskz_mov_epi64(
        count >= 8 ? static_cast<__mmask8>(0xFF) : static_cast<__mmask8>((1u << count) - 1u), value);
}
/* The bilinear weight of each lane: its bits 24 to 31, as bits 8 to 15 (continuous_internal.h). */
inline splat_vector splat_weight(splat_vector value) {
    return _mm512_and_si512(_mm512_srli_epi64(value, 16), _mm512_set1_epi64(0xFF00));
}
/* The words (-32768, a - 32768, -32768, a - 32768) of each lane, a the lane's weight (bits 24 to 31, as 8 to
   15): byte 3 of the lane into the high bytes of words 1 and 3, then the top bit of every word flipped. */
inline splat_vector splat_across_weights(splat_vector value) {
    return _mm512_xor_si512(_mm512_shuffle_epi8(value, _mm512_broadcast_i32x4(splat_across_order())),
                            _mm512_set1_epi16(-32768));
}
/* (lane >> 32) times factor, modulo 2^64. */
inline splat_vector splat_whole_times(splat_vector value, uint32_t factor) {
    return _mm512_mul_epu32(_mm512_srli_epi64(value, 32), _mm512_set1_epi64(factor));
}
/* Two RGB cells (4 records each) in one vector. */
inline __m512i splat_cell_pair(const uint64_t *first, const uint64_t *second) {
    return _mm512_inserti64x4(
        _mm512_castsi256_si512(
            _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(first)))),
        _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(second))), 1);
}
/* The records of `Channels` channels of the cells at cells[index[k]] (splat_cells.h: one record per
   channel, 4 per cell for RGB): records[c] holds channel c of each lane's cell. RGB cells are loaded in
   pairs and transposed by two-source permutes. */
template <uint32_t Channels>
inline void splat_load_cells(const uint64_t *cells, const uint64_t *index, splat_vector *records) {
    if (Channels == 1) {
        records[0] = _mm512_set_epi64(
            static_cast<long long>(cells[index[7]]), static_cast<long long>(cells[index[6]]),
            static_cast<long long>(cells[index[5]]), static_cast<long long>(cells[index[4]]),
            static_cast<long long>(cells[index[3]]), static_cast<long long>(cells[index[2]]),
            static_cast<long long>(cells[index[1]]), static_cast<long long>(cells[index[0]]));
        return;
    }
    const __m512i pair_0 = splat_cell_pair(cells + index[0], cells + index[1]);
    const __m512i pair_1 = splat_cell_pair(cells + index[2], cells + index[3]);
    const __m512i pair_2 = splat_cell_pair(cells + index[4], cells + index[5]);
    const __m512i pair_3 = splat_cell_pair(cells + index[6], cells + index[7]);
    const __m512i channels_01 = _mm512_setr_epi64(0, 4, 8, 12, 1, 5, 9, 13),
                  channel_2 = _mm512_setr_epi64(2, 6, 10, 14, 2, 6, 10, 14);
    const __m512i low_01 = _mm512_permutex2var_epi64(pair_0, channels_01, pair_1);
    const __m512i high_01 = _mm512_permutex2var_epi64(pair_2, channels_01, pair_3);
    records[0] = _mm512_shuffle_i64x2(low_01, high_01, _MM_SHUFFLE(1, 0, 1, 0));
    records[1] = _mm512_shuffle_i64x2(low_01, high_01, _MM_SHUFFLE(3, 2, 3, 2));
    records[Channels - 1] =
        _mm512_shuffle_i64x2(_mm512_permutex2var_epi64(pair_0, channel_2, pair_1),
                             _mm512_permutex2var_epi64(pair_2, channel_2, pair_3), _MM_SHUFFLE(1, 0, 1, 0));
}
/* splat_cells.h's multiply-add: each lane's dwords (low, high) become upper and lower - upper. */
inline splat_vector splat_rows(splat_vector records, splat_vector across) {
    return _mm512_madd_epi16(records, across);
}
/* The low dword of each lane, signed, times the low dword of factor's (below 2^31). */
inline splat_vector splat_signed_times(splat_vector value, splat_vector factor) {
    return _mm512_mul_epi32(value, factor);
}
/* The low dword of each lane, unsigned, times the low dword of factor's (unsigned). */
inline splat_vector splat_low_times(splat_vector value, splat_vector factor) {
    return _mm512_mul_epu32(value, factor);
}
/* Lane k of values[c] saturated to int32 into out[k * Channels + c], for k < splat_lanes: narrowed with
   saturation, then interleaved by two-source permutes (no store of lanes read back one by one). */
#define DSN_SPLAT_STORE_PIXELS 1
template <uint32_t Channels>
inline void splat_store_pixels(int32_t *out, const splat_vector *values) {
    const __m256i first = _mm512_cvtsepi64_epi32(values[0]);
    if (Channels == 1) {
        _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(out)), first);
        return;
    }
    /* dwords 0-7: channel 0, 8-15: channel 1, 16-23: channel 2 (the second source) */
    const __m512i two =
        _mm512_inserti64x4(_mm512_castsi256_si512(first), _mm512_cvtsepi64_epi32(values[1]), 1);
    const __m512i three = _mm512_castsi256_si512(_mm512_cvtsepi64_epi32(values[Channels - 1]));
    const __m512i low = _mm512_setr_epi32(0, 8, 16, 1, 9, 17, 2, 10, 18, 3, 11, 19, 4, 12, 20, 5),
                  high = _mm512_setr_epi32(13, 21, 6, 14, 22, 7, 15, 23, 0, 0, 0, 0, 0, 0, 0, 0);
    _mm512_storeu_si512(out, _mm512_permutex2var_epi32(two, low, three));
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(out + 16)),
                        _mm512_castsi512_si256(_mm512_permutex2var_epi32(two, high, three)));
}
/* Adds the first `count` lanes (all of them from splat_lanes up) to sums[0 ..] (and no further: the end
   of the sums is not needed). */
inline void splat_accumulate(uint64_t *sums, splat_vector values, uint32_t count, const uint64_t *) {
    if (count >= 8) {
        _mm512_storeu_si512(sums, _mm512_add_epi64(_mm512_loadu_si512(sums), values));
        return;
    }
    const __mmask8 present =
        count >= 8 ? static_cast<__mmask8>(0xFF) : static_cast<__mmask8>((1u << count) - 1u);
    _mm512_mask_storeu_epi64(sums, present,
                             _mm512_add_epi64(_mm512_maskz_loadu_epi64(present, sums), values));
}

/* ---- The 512-bit operations of the continuous and filtered kernels (continuous_*.h, filtered_*_vector.h):
   16 lanes of 32 bits, 8 of 64 bits or 32 of 16 bits; the comparisons give one mask bit per lane ---- */

inline vector_512 load_16x32(const uint32_t *at) { return _mm512_loadu_si512(at); }
/* load_16x32 and set_16x32 are plain inline, as the kernels' helpers they replaced were (simd_256.h). */
DSN_SIMD_INLINE vector_512 load_8x64(const int64_t *at) { return _mm512_loadu_si512(at); }
DSN_SIMD_INLINE void store_8x64(uint64_t *at, vector_512 value) { _mm512_storeu_si512(at, value); }
DSN_SIMD_INLINE void store_8x64(int64_t *at, vector_512 value) { _mm512_storeu_si512(at, value); }
DSN_SIMD_INLINE void store_16x32(uint32_t *at, vector_512 value) { _mm512_storeu_si512(at, value); }
/* The lanes of mask, the others 0 (and not read). */
DSN_SIMD_INLINE vector_512 load_masked_16x32(const uint32_t *at, mask_16 mask) {
    return _mm512_maskz_loadu_epi32(mask, at);
}
/* The 64-bit lanes of mask, the others 0 (and not read). */
DSN_SIMD_INLINE vector_512 load_masked_8x64(const int64_t *at, mask_8 mask) {
    return _mm512_maskz_loadu_epi64(mask, at);
}
/* The masked gathers: unoptimized, GCC makes them macros that hand the mask to a builtin taking a signed
   integer, which -Wsign-conversion reports at the call; the bits are the same either way. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wsign-conversion"
#endif
/* Lane k: the 32 bits at base + Scale offsets[k] bytes where mask bit k is set, else 0. */
template <int Scale>
DSN_SIMD_INLINE vector_512 gather_masked_32(const void *base, vector_512 offsets, mask_16 mask) {
    return _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), mask, offsets, base, Scale);
}
/* 64-bit lane k: the 64 bits at base + Scale offsets[k] bytes where mask bit k is set, else 0. */
template <int Scale>
DSN_SIMD_INLINE vector_512 gather_masked_64(const void *base, vector_256 offsets, mask_8 mask) {
    return _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), mask, offsets, base, Scale);
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

DSN_SIMD_INLINE vector_512 zero_512() { return _mm512_setzero_si512(); }
inline vector_512 set_16x32(uint32_t value) { return _mm512_set1_epi32(static_cast<int>(value)); }
DSN_SIMD_INLINE vector_512 set_8x64(int64_t value) { return _mm512_set1_epi64(value); }
/* The lanes in order, lane 0 first. */
DSN_SIMD_INLINE vector_512 set_lanes_8x64(int64_t lane_0, int64_t lane_1, int64_t lane_2, int64_t lane_3,
                                          int64_t lane_4, int64_t lane_5, int64_t lane_6, int64_t lane_7) {
    return _mm512_setr_epi64(lane_0, lane_1, lane_2, lane_3, lane_4, lane_5, lane_6, lane_7);
}
/* The lanes in order, lane 0 first. */
DSN_SIMD_INLINE vector_512 set_lanes_16x32(int32_t lane_0, int32_t lane_1, int32_t lane_2, int32_t lane_3,
                                           int32_t lane_4, int32_t lane_5, int32_t lane_6, int32_t lane_7,
                                           int32_t lane_8, int32_t lane_9, int32_t lane_10, int32_t lane_11,
                                           int32_t lane_12, int32_t lane_13, int32_t lane_14,
                                           int32_t lane_15) {
    return _mm512_setr_epi32(lane_0, lane_1, lane_2, lane_3, lane_4, lane_5, lane_6, lane_7, lane_8, lane_9,
                             lane_10, lane_11, lane_12, lane_13, lane_14, lane_15);
}
/* The 256 bits in both halves. */
DSN_SIMD_INLINE vector_512 broadcast_256(vector_256 value) { return _mm512_broadcast_i64x4(value); }
DSN_SIMD_INLINE vector_256 low_256(vector_512 a) { return _mm512_castsi512_si256(a); }
DSN_SIMD_INLINE vector_256 high_256(vector_512 a) { return _mm512_extracti64x4_epi64(a, 1); }
/* a in the low half, the high half undefined. */
DSN_SIMD_INLINE vector_512 cast_to_512(vector_256 a) { return _mm512_castsi256_si512(a); }
/* low in the low half, high in the high half. */
DSN_SIMD_INLINE vector_512 concatenate_256(vector_256 low, vector_256 high) {
    return _mm512_inserti64x4(_mm512_castsi256_si512(low), high, 1);
}
/* Lanes Count .. 15 of low, then lanes 0 .. Count - 1 of high. */
template <int Count>
DSN_SIMD_INLINE vector_512 combine_shift_right_32(vector_512 high, vector_512 low) {
    return _mm512_alignr_epi32(high, low, Count);
}

DSN_SIMD_INLINE vector_512 bitwise_and(vector_512 a, vector_512 b) { return _mm512_and_si512(a, b); }
DSN_SIMD_INLINE vector_512 bitwise_or(vector_512 a, vector_512 b) { return _mm512_or_si512(a, b); }
DSN_SIMD_INLINE vector_512 bitwise_xor(vector_512 a, vector_512 b) { return _mm512_xor_si512(a, b); }
/* (a & mask) | b, in one instruction. */
DSN_SIMD_INLINE vector_512 masked_or(vector_512 a, vector_512 b, vector_512 mask) {
    return _mm512_ternarylogic_epi32(a, b, mask, 0xEC);
}
/* The 16-bit shifts take their count as a constant (GCC and Clang disagree on the count's signedness). */
template <int Count>
DSN_SIMD_INLINE vector_512 shift_left_16(vector_512 a) {
    return _mm512_slli_epi16(a, Count);
}
template <int Count>
DSN_SIMD_INLINE vector_512 shift_right_arithmetic_16(vector_512 a) {
    return _mm512_srai_epi16(a, Count);
}
DSN_SIMD_INLINE vector_512 shift_left_32(vector_512 a, uint32_t count) { return _mm512_slli_epi32(a, count); }
/* Every lane by the same count, the low 64 bits of `count` (shift_count). */
DSN_SIMD_INLINE vector_512 shift_left_32_by(vector_512 a, vector_128 count) {
    return _mm512_sll_epi32(a, count);
}
DSN_SIMD_INLINE vector_512 shift_right_logical_32(vector_512 a, uint32_t count) {
    return _mm512_srli_epi32(a, count);
}
DSN_SIMD_INLINE vector_512 shift_right_logical_32_by(vector_512 a, vector_128 count) {
    return _mm512_srl_epi32(a, count);
}
DSN_SIMD_INLINE vector_512 shift_right_arithmetic_32(vector_512 a, uint32_t count) {
    return _mm512_srai_epi32(a, count);
}
DSN_SIMD_INLINE vector_512 shift_left_64(vector_512 a, uint32_t count) { return _mm512_slli_epi64(a, count); }
DSN_SIMD_INLINE vector_512 shift_right_logical_64(vector_512 a, uint32_t count) {
    return _mm512_srli_epi64(a, count);
}
DSN_SIMD_INLINE vector_512 shift_right_logical_64_by(vector_512 a, vector_128 count) {
    return _mm512_srl_epi64(a, count);
}
DSN_SIMD_INLINE vector_512 shift_left_64_by(vector_512 a, vector_128 count) {
    return _mm512_sll_epi64(a, count);
}
DSN_SIMD_INLINE vector_512 shift_right_arithmetic_64(vector_512 a, uint32_t count) {
    return _mm512_srai_epi64(a, count);
}
/* a << count in the 64-bit lanes of mask, a in the others. */
DSN_SIMD_INLINE vector_512 shift_left_64_where(mask_8 mask, vector_512 a, uint32_t count) {
    return _mm512_mask_slli_epi64(a, mask, a, count);
}
/* a & b in the 64-bit lanes of mask, otherwise's lanes in the others. */
DSN_SIMD_INLINE vector_512 and_64_where(vector_512 otherwise, mask_8 mask, vector_512 a, vector_512 b) {
    return _mm512_mask_and_epi64(otherwise, mask, a, b);
}

/* Arithmetic modulo 2^16, 2^32 or 2^64. */
DSN_SIMD_INLINE vector_512 subtract_16(vector_512 a, vector_512 b) { return _mm512_sub_epi16(a, b); }
DSN_SIMD_INLINE vector_512 subtract_32(vector_512 a, vector_512 b) { return _mm512_sub_epi32(a, b); }
DSN_SIMD_INLINE vector_512 multiply_32(vector_512 a, vector_512 b) { return _mm512_mullo_epi32(a, b); }
/* a + b in the lanes of mask, a in the others. */
DSN_SIMD_INLINE vector_512 add_32_where(mask_16 mask, vector_512 a, vector_512 b) {
    return _mm512_mask_add_epi32(a, mask, a, b);
}
DSN_SIMD_INLINE vector_512 add_64(vector_512 a, vector_512 b) { return _mm512_add_epi64(a, b); }
/* a + b in the 64-bit lanes of mask, a in the others. */
DSN_SIMD_INLINE vector_512 add_64_where(mask_8 mask, vector_512 a, vector_512 b) {
    return _mm512_mask_add_epi64(a, mask, a, b);
}
#if defined(__AVX512DQ__)
/* x * factor modulo 2^64 in every 64-bit lane: one instruction with AVX512DQ (simd_mix64.h's multiply_64
   otherwise). */
DSN_SIMD_INLINE vector_512 multiply_64(vector_512 x, uint64_t factor) {
    return _mm512_mullo_epi64(x, _mm512_set1_epi64(static_cast<long long>(factor)));
}
#endif
#if defined(__AVX512DQ__) && defined(__AVX512VL__)
/* The same on 128 bits (the lattice point's pair hashes). */
DSN_SIMD_INLINE vector_128 multiply_64(vector_128 x, uint64_t factor) {
    return _mm_mullo_epi64(x, _mm_set1_epi64x(static_cast<long long>(factor)));
}
#endif
DSN_SIMD_INLINE vector_512 subtract_64(vector_512 a, vector_512 b) { return _mm512_sub_epi64(a, b); }
/* The low 32 bits of each 64-bit lane, signed, multiplied into the 64-bit lane (exact). */
DSN_SIMD_INLINE vector_512 multiply_even_32(vector_512 a, vector_512 b) { return _mm512_mul_epi32(a, b); }
/* The low 32 bits of each 64-bit lane, unsigned, multiplied into the 64-bit lane (exact). */
DSN_SIMD_INLINE vector_512 multiply_even_unsigned_32(vector_512 a, vector_512 b) {
    return _mm512_mul_epu32(a, b);
}
DSN_SIMD_INLINE vector_512 maximum_32(vector_512 a, vector_512 b) { return _mm512_max_epi32(a, b); }
DSN_SIMD_INLINE vector_512 maximum_64(vector_512 a, vector_512 b) { return _mm512_max_epi64(a, b); }
DSN_SIMD_INLINE vector_512 minimum_64(vector_512 a, vector_512 b) { return _mm512_min_epi64(a, b); }
DSN_SIMD_INLINE vector_512 minimum_unsigned_32(vector_512 a, vector_512 b) { return _mm512_min_epu32(a, b); }
DSN_SIMD_INLINE vector_512 minimum_32(vector_512 a, vector_512 b) { return _mm512_min_epi32(a, b); }
/* Lane k by counts' lane k. */
DSN_SIMD_INLINE vector_512 shift_right_logical_32_per_lane(vector_512 a, vector_512 counts) {
    return _mm512_srlv_epi32(a, counts);
}
/* 8 32-bit lanes, signed, widened into 64-bit lanes. */
DSN_SIMD_INLINE vector_512 widen_signed_32x64(vector_256 a) { return _mm512_cvtepi32_epi64(a); }
/* The low 32 bits of each 64-bit lane. */
DSN_SIMD_INLINE vector_256 truncate_64x32(vector_512 a) { return _mm512_cvtepi64_epi32(a); }

/* Comparisons; `within`: only the lanes of that mask, the others 0. */
DSN_SIMD_INLINE mask_16 equal_32(vector_512 a, vector_512 b) { return _mm512_cmpeq_epi32_mask(a, b); }
DSN_SIMD_INLINE mask_16 equal_32(mask_16 within, vector_512 a, vector_512 b) {
    return _mm512_mask_cmpeq_epi32_mask(within, a, b);
}
DSN_SIMD_INLINE mask_64 greater_unsigned_8(vector_512 a, vector_512 b) {
    return _mm512_cmpgt_epu8_mask(a, b);
}
/* The top bit of byte k in bit k. */
DSN_SIMD_INLINE mask_64 top_bits_of_bytes(vector_512 a) { return _mm512_movepi8_mask(a); }
DSN_SIMD_INLINE uint64_t mask_bits(mask_64 mask) { return _cvtmask64_u64(mask); }
DSN_SIMD_INLINE mask_16 less_32(vector_512 a, vector_512 b) { return _mm512_cmplt_epi32_mask(a, b); }
DSN_SIMD_INLINE mask_16 greater_32(vector_512 a, vector_512 b) { return _mm512_cmpgt_epi32_mask(a, b); }
DSN_SIMD_INLINE mask_8 less_unsigned_64(mask_8 within, vector_512 a, vector_512 b) {
    return _mm512_mask_cmplt_epu64_mask(within, a, b);
}
DSN_SIMD_INLINE mask_16 less_unsigned_32(mask_16 within, vector_512 a, vector_512 b) {
    return _mm512_mask_cmplt_epu32_mask(within, a, b);
}
/* Comparisons of unsigned 32-bit lanes; `within`: only the lanes of that mask, the others 0. */
DSN_SIMD_INLINE mask_16 less_unsigned_32(vector_512 a, vector_512 b) { return _mm512_cmplt_epu32_mask(a, b); }
/* less_unsigned_32 as bits, as simd_256.h's for 8 lanes. */
DSN_SIMD_INLINE uint32_t less_unsigned_32_bits(vector_512 a, vector_512 b) { return less_unsigned_32(a, b); }
DSN_SIMD_INLINE mask_16 less_equal_unsigned_32(vector_512 a, vector_512 b) {
    return _mm512_cmple_epu32_mask(a, b);
}
DSN_SIMD_INLINE mask_16 less_equal_unsigned_32(mask_16 within, vector_512 a, vector_512 b) {
    return _mm512_mask_cmple_epu32_mask(within, a, b);
}
DSN_SIMD_INLINE mask_16 greater_unsigned_32(vector_512 a, vector_512 b) {
    return _mm512_cmpgt_epu32_mask(a, b);
}
DSN_SIMD_INLINE mask_16 greater_equal_unsigned_32(vector_512 a, vector_512 b) {
    return _mm512_cmpge_epu32_mask(a, b);
}
DSN_SIMD_INLINE mask_16 greater_equal_unsigned_32(mask_16 within, vector_512 a, vector_512 b) {
    return _mm512_mask_cmpge_epu32_mask(within, a, b);
}

/* b in the 32-bit lanes of mask, a in the others. */
DSN_SIMD_INLINE vector_512 blend_32(mask_16 mask, vector_512 a, vector_512 b) {
    return _mm512_mask_blend_epi32(mask, a, b);
}
/* Each 128-bit quarter's 32-bit lanes reordered by Order (two bits a lane, as _mm_shuffle_epi32). */
template <int Order>
DSN_SIMD_INLINE vector_512 shuffle_32(vector_512 a) {
    return _mm512_shuffle_epi32(a, static_cast<_MM_PERM_ENUM>(Order));
}
/* The even 16-bit lanes of a, the odd ones of b. */
DSN_SIMD_INLINE vector_512 blend_odd_16(vector_512 a, vector_512 b) {
    return _mm512_mask_blend_epi16(0xAAAAAAAAu, a, b);
}
/* Lane k: lane order[k] (its low 4 bits) of a. */
DSN_SIMD_INLINE vector_512 permute_32(vector_512 a, vector_512 order) {
    return _mm512_permutexvar_epi32(order, a);
}
/* Lane k: lane order[k] (its low 5 bits) of first's lanes followed by second's. */
DSN_SIMD_INLINE vector_512 permute_32_of_two(vector_512 first, vector_512 order, vector_512 second) {
    return _mm512_permutex2var_epi32(first, order, second);
}
/* permute_32_of_two in the lanes of mask, 0 in the others. */
DSN_SIMD_INLINE vector_512 permute_32_of_two_or_zero(mask_16 mask, vector_512 first, vector_512 order,
                                                     vector_512 second) {
    return _mm512_maskz_permutex2var_epi32(mask, first, order, second);
}
/* The lanes of mask packed to the front, in order, zeros after. */
DSN_SIMD_INLINE vector_512 compress_32(mask_16 mask, vector_512 a) {
    return _mm512_maskz_compress_epi32(mask, a);
}
/* Per 128-bit lane: byte k is byte order[k] (its low 4 bits) of the lane, or 0 where order[k]'s top bit is
 * set. */
DSN_SIMD_INLINE vector_512 shuffle_bytes(vector_512 a, vector_512 order) {
    return _mm512_shuffle_epi8(a, order);
}
/* The 64-bit lanes of mask packed to the front, in order, zeros after (in a register: the compressing
   store to memory is microcoded on AMD Zen 4). */
DSN_SIMD_INLINE vector_512 compress_64(mask_8 mask, vector_512 a) {
    return _mm512_maskz_compress_epi64(mask, a);
}
/* 8 32-bit lanes, unsigned, widened into 64-bit lanes. */
DSN_SIMD_INLINE vector_512 widen_unsigned_32x64(vector_256 a) { return _mm512_cvtepu32_epi64(a); }
/* 16 bytes, unsigned, widened into 32-bit lanes. */
DSN_SIMD_INLINE vector_512 widen_bytes_16x32(vector_128 bytes) { return _mm512_cvtepu8_epi32(bytes); }

} // namespace

#endif /* DSN_SIMD_AVX512_H */
