/* runtime/simd_sse2.h - the vector operations of the strip path for SSE2 (128-bit vectors: 8 pixels per
   strip). simd_avx2.h and simd_avx512.h define the same names for their widths; simd.h picks one. */
#ifndef DSN_SIMD_SSE2_H
#define DSN_SIMD_SSE2_H

#include "simd_128.h"

namespace {

typedef __m128i simd_vector; /* 16-bit sums, or 32-bit values, of the strip's pixels */
typedef __m128 simd_floats;
typedef uint16_t simd_texel; /* the texton as the sums read it: sign-extended to 16 bits once */
const uint32_t simd_int16_count = 8;

/* ---- Sums ---- */
inline simd_vector load_texels(const simd_texel *src) {
    return _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(src)));
}
inline simd_vector add_16(simd_vector a, simd_vector b) { return _mm_add_epi16(a, b); }
inline simd_vector zero_vector() { return _mm_setzero_si128(); }
inline void store_16(uint16_t *dst, simd_vector value) {
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(dst)), value);
}

/* ---- Normalization, per 128-bit lane ---- */
inline simd_vector broadcast_lanes(__m128i value) { return value; }
inline simd_vector madd_16(simd_vector a, simd_vector b) { return _mm_madd_epi16(a, b); }
inline simd_vector add_32(simd_vector a, simd_vector b) { return _mm_add_epi32(a, b); }
inline simd_vector shift_right_15(simd_vector a) { return _mm_srai_epi32(a, 15); }
inline simd_vector shift_right(simd_vector a, __m128i count) { return _mm_sra_epi32(a, count); }
inline simd_vector unpack_low_16(simd_vector a, simd_vector b) { return _mm_unpacklo_epi16(a, b); }
inline simd_vector unpack_high_16(simd_vector a, simd_vector b) { return _mm_unpackhi_epi16(a, b); }
inline simd_vector unpack_low_32(simd_vector a, simd_vector b) { return _mm_unpacklo_epi32(a, b); }
inline simd_vector unpack_high_32(simd_vector a, simd_vector b) { return _mm_unpackhi_epi32(a, b); }
inline simd_vector set_16(int16_t value) { return _mm_set1_epi16(value); }
inline simd_floats as_floats(simd_vector a) { return _mm_castsi128_ps(a); }
inline simd_vector as_integers(simd_floats a) { return _mm_castps_si128(a); }
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
/* 4 output values; `stream_aligned` (out is then 16-byte aligned): past the caches (put_4). */
inline void put_vector(int32_t *out, simd_vector values, int stream_aligned) {
    put_4(out, values, stream_aligned);
}
inline void put_vector(float *out, simd_floats values, int stream_aligned) {
    put_4(out, values, stream_aligned);
}
/* 8-bit output of a whole strip in one go: none wider than the 128-bit path (returns 0). */
template <uint32_t Channels>
inline int store_whole_strip_u8(const simd_vector *, uint8_t *) {
    return 0;
}

} // namespace

#endif /* DSN_SIMD_SSE2_H */
