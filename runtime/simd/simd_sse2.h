/* runtime/simd/simd_sse2.h - the vector operations of the strip path for SSE2 (128-bit vectors: 8 pixels per
   strip), and of the continuous splat's runs (splat_row.h: 2 pixels per vector). simd_avx2.h and
   simd_avx512.h define the same names for their widths; simd.h picks one. */
#ifndef DSN_SIMD_SSE2_H
#define DSN_SIMD_SSE2_H

#include "simd/simd_128.h"

namespace {

typedef vector_128 simd_vector; /* 16-bit sums, or 32-bit values, of the strip's pixels */
typedef floats_128 simd_floats;
const uint32_t simd_int16_count = 8;

/* ---- Sums (add_16: simd_128.h) ---- */
inline simd_vector load_texels(const uint16_t *src) {
    return _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(src)));
}
inline simd_vector zero_vector() { return _mm_setzero_si128(); }
inline void store_16(uint16_t *dst, simd_vector value) {
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(dst)), value);
}

/* ---- Normalization, per 128-bit lane (madd_16, add_32, the unpacks, as_floats and as_integers:
   simd_128.h) ---- */
inline simd_vector broadcast_lanes(__m128i value) { return value; }
inline simd_vector shift_right_15(simd_vector a) { return _mm_srai_epi32(a, 15); }
inline simd_vector shift_right(simd_vector a, __m128i count) { return _mm_sra_epi32(a, count); }
inline simd_vector set_16(int16_t value) { return _mm_set1_epi16(value); }
template <int Order>
inline simd_floats shuffle(simd_floats a, simd_floats b) {
    return _mm_shuffle_ps(a, b, Order);
}

/* ---- Output ---- */
/* 128-bit lane `part` of a vector: pixels 8 part .. 8 part + 7 of a normalized strip. */
inline __m128i lane_128(simd_vector v, uint32_t) { return v; }

/* A whole strip's normalized vectors (4 values each, see tile_store.h) in output order: one lane, so
   they already are. */
template <uint32_t Channels>
inline void output_order(const simd_vector *values, simd_vector *ordered) {
    for (uint32_t i = 0; i < 2 * Channels; i++) ordered[i] = values[i];
}
inline simd_floats to_output_floats(simd_vector fixed) { return to_float_4(fixed); }
/* 4 output values (streamed strips go out through put_4 instead, tile_store.h). */
inline void put_vector(int32_t *out, simd_vector values) { put_4(out, values, 0); }
inline void put_vector(float *out, simd_floats values) { put_4(out, values, 0); }
/* 8-bit output of a whole strip in one go: none wider than the 128-bit path (returns 0). */
template <uint32_t Channels>
inline int store_whole_strip_u8(const simd_vector *, uint8_t *) {
    return 0;
}

/* ---- Continuous splat (splat_row.h): 64-bit lanes, one pixel each ---- */
typedef __m128i splat_vector;
const uint32_t splat_lanes = 2;

inline splat_vector splat_set(uint64_t value) { return _mm_set1_epi64x(static_cast<long long>(value)); }
/* Lane k: first + k step, modulo 2^64. */
inline splat_vector splat_lane_steps(uint64_t first, uint64_t step) {
    return _mm_set_epi64x(static_cast<long long>(first + step), static_cast<long long>(first));
}
inline splat_vector splat_add(splat_vector a, splat_vector b) { return _mm_add_epi64(a, b); }
inline void splat_store(uint64_t *out, splat_vector value) {
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(out)), value);
}
inline splat_vector splat_load(const uint64_t *from) {
    return _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(from)));
}
inline splat_vector splat_sub(splat_vector a, splat_vector b) { return _mm_sub_epi64(a, b); }
inline splat_vector splat_and(splat_vector a, splat_vector b) { return _mm_and_si128(a, b); }
inline splat_vector splat_or(splat_vector a, splat_vector b) { return _mm_or_si128(a, b); }
inline splat_vector splat_shift_right(splat_vector value, uint32_t count) {
    return _mm_srl_epi64(value, _mm_cvtsi32_si128(static_cast<int>(count)));
}
inline splat_vector splat_shift_left(splat_vector value, uint32_t count) {
    return _mm_sll_epi64(value, _mm_cvtsi32_si128(static_cast<int>(count)));
}
/* The first `count` lanes (all of them from splat_lanes up), the others 0. */
inline splat_vector splat_first_lanes(splat_vector value, uint32_t count) {
    return count >= 2 ? value : _mm_move_epi64(value);
}
/* The bilinear weight of each lane: its bits 24 to 31, as bits 8 to 15 (continuous_internal.h). */
inline splat_vector splat_weight(splat_vector value) {
    return _mm_and_si128(_mm_srli_epi64(value, 16), _mm_set1_epi64x(0xFF00));
}
/* The words (-32768, a - 32768, -32768, a - 32768) of each lane, a the lane's weight (bits 24 to 31, as 8 to
 * 15). */
inline splat_vector splat_across_weights(splat_vector value) {
    const splat_vector spread = _mm_shufflehi_epi16(_mm_shufflelo_epi16(value, 0x55), 0x55); /* word 1 */
    return _mm_xor_si128(_mm_and_si128(spread, _mm_set1_epi32(-16777216)) /* bits 24-31 */,
                         _mm_set1_epi16(-32768));
}
/* (lane >> 32) times factor, modulo 2^64. */
inline splat_vector splat_whole_times(splat_vector value, uint32_t factor) {
    return _mm_mul_epu32(_mm_srli_epi64(value, 32), _mm_set1_epi64x(factor));
}
/* The records of `Channels` channels of the cells at cells[index[k]] (splat_cells.h: one record per
   channel, 4 per cell for RGB): records[c] holds channel c of each lane's cell. */
template <uint32_t Channels>
inline void splat_load_cells(const uint64_t *cells, const uint64_t *index, splat_vector *records) {
    const __m128i *first = static_cast<const __m128i *>(static_cast<const void *>(cells + index[0]));
    const __m128i *second = static_cast<const __m128i *>(static_cast<const void *>(cells + index[1]));
    if (Channels == 1) {
        records[0] = _mm_unpacklo_epi64(_mm_loadl_epi64(first), _mm_loadl_epi64(second));
        return;
    }
    const __m128i first_01 = _mm_loadu_si128(first), second_01 = _mm_loadu_si128(second);
    records[0] = _mm_unpacklo_epi64(first_01, second_01);
    records[1] = _mm_unpackhi_epi64(first_01, second_01);
    records[Channels - 1] = _mm_unpacklo_epi64(_mm_loadl_epi64(first + 1), _mm_loadl_epi64(second + 1));
}
/* splat_cells.h's multiply-add: each lane's dwords (low, high) become upper and lower - upper. */
inline splat_vector splat_rows(splat_vector records, splat_vector across) {
    return _mm_madd_epi16(records, across);
}
/* The low dword of each lane, signed, times the low dword of factor's (below 2^31). SSE2 multiplies
   unsigned only: a negative dword s reads as s + 2^32, so its product is 2^32 times the factor too much. */
inline splat_vector splat_signed_times(splat_vector value, splat_vector factor) {
    const splat_vector negative = _mm_shuffle_epi32(_mm_srai_epi32(value, 31), _MM_SHUFFLE(2, 2, 0, 0));
    return _mm_sub_epi64(_mm_mul_epu32(value, factor), _mm_and_si128(negative, _mm_slli_epi64(factor, 32)));
}
/* The low dword of each lane, unsigned, times the low dword of factor's (unsigned). */
inline splat_vector splat_low_times(splat_vector value, splat_vector factor) {
    return _mm_mul_epu32(value, factor);
}
/* Adds the first `count` lanes (all of them from splat_lanes up) to sums[0 ..] (and no further: the end
   of the sums is not needed). */
inline void splat_accumulate(uint64_t *sums, splat_vector values, uint32_t count, const uint64_t *) {
    __m128i *at = static_cast<__m128i *>(static_cast<void *>(sums));
    if (count >= 2)
        _mm_storeu_si128(at, _mm_add_epi64(_mm_loadu_si128(at), values));
    else
        _mm_storel_epi64(at, _mm_add_epi64(_mm_loadl_epi64(at), values));
}

} // namespace

#endif /* DSN_SIMD_SSE2_H */
