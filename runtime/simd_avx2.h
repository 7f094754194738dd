/* runtime/simd_avx2.h - the vector operations of the strip path for AVX2 (256-bit vectors: 16 pixels per
   strip). The same names as simd_sse2.h and simd_avx512.h; simd.h picks one. */
#ifndef DSN_SIMD_AVX2_H
#define DSN_SIMD_AVX2_H

#include <immintrin.h>

#include "simd_128.h"

namespace {

typedef __m256i simd_vector; /* 16-bit sums, or 32-bit values, of the strip's pixels */
typedef __m256 simd_floats;
typedef uint16_t simd_texel; /* the texton as the sums read it: sign-extended to 16 bits once */
const uint32_t simd_int16_count = 16;

/* ---- Sums ---- */
inline simd_vector load_texels(const simd_texel *src) {
    return _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(src)));
}
inline simd_vector add_16(simd_vector a, simd_vector b) { return _mm256_add_epi16(a, b); }
inline simd_vector zero_vector() { return _mm256_setzero_si256(); }
inline void store_16(uint16_t *dst, simd_vector value) {
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(dst)), value);
}

/* ---- Normalization, per 128-bit lane (AVX2 unpacks and shuffles each lane on its own) ---- */
inline simd_vector broadcast_lanes(__m128i value) { return _mm256_broadcastsi128_si256(value); }
inline simd_vector madd_16(simd_vector a, simd_vector b) { return _mm256_madd_epi16(a, b); }
inline simd_vector add_32(simd_vector a, simd_vector b) { return _mm256_add_epi32(a, b); }
inline simd_vector shift_right_15(simd_vector a) { return _mm256_srai_epi32(a, 15); }
inline simd_vector shift_right(simd_vector a, __m128i count) { return _mm256_sra_epi32(a, count); }
inline simd_vector unpack_low_16(simd_vector a, simd_vector b) { return _mm256_unpacklo_epi16(a, b); }
inline simd_vector unpack_high_16(simd_vector a, simd_vector b) { return _mm256_unpackhi_epi16(a, b); }
inline simd_vector unpack_low_32(simd_vector a, simd_vector b) { return _mm256_unpacklo_epi32(a, b); }
inline simd_vector unpack_high_32(simd_vector a, simd_vector b) { return _mm256_unpackhi_epi32(a, b); }
inline simd_vector set_16(int16_t value) { return _mm256_set1_epi16(value); }
inline simd_floats as_floats(simd_vector a) { return _mm256_castsi256_ps(a); }
inline simd_vector as_integers(simd_floats a) { return _mm256_castps_si256(a); }
template <int Order>
inline simd_floats shuffle(simd_floats a, simd_floats b) {
    return _mm256_shuffle_ps(a, b, Order);
}

/* ---- Output ---- */
/* 128-bit lane `part` of a vector: pixels 8 part .. 8 part + 7 of a normalized strip. */
inline __m128i lane_128(simd_vector v, uint32_t part) {
    return part == 0 ? _mm256_castsi256_si128(v) : _mm256_extracti128_si256(v, 1);
}

/* A whole strip's normalized vectors (4 values per 128-bit lane, see tile_store.h) in output order:
   pixels 0-7 are the low lanes of vectors 0 .. 2 Channels - 1, pixels 8-15 the high lanes, so pairs of
   vectors trade lanes. */
template <uint32_t Channels>
inline void output_order(const simd_vector *values, simd_vector *ordered) {
    for (uint32_t i = 0; i < Channels; i++) {
        ordered[i] = _mm256_permute2x128_si256(values[2 * i], values[2 * i + 1], 0x20);
        ordered[Channels + i] = _mm256_permute2x128_si256(values[2 * i], values[2 * i + 1], 0x31);
    }
}
inline simd_floats to_output_floats(simd_vector fixed) {
    return _mm256_mul_ps(_mm256_cvtepi32_ps(fixed), _mm256_set1_ps(1.0f / 65536.0f));
}
/* 8 output values. `stream_aligned` (out is then 16-byte aligned): past the caches (put_4), in two
   16-byte stores. */
inline void put_vector(int32_t *out, simd_vector values, int stream_aligned) {
    if (stream_aligned) {
        __m128i *destination = static_cast<__m128i *>(static_cast<void *>(out));
        _mm_stream_si128(destination, _mm256_castsi256_si128(values));
        _mm_stream_si128(destination + 1, _mm256_extracti128_si256(values, 1));
    } else {
        _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(out)), values);
    }
}
inline void put_vector(float *out, simd_floats values, int stream_aligned) {
    if (stream_aligned) {
        _mm_stream_ps(out, _mm256_castps256_ps128(values));
        _mm_stream_ps(out + 4, _mm256_extractf128_ps(values, 1));
    } else {
        _mm256_storeu_ps(out, values);
    }
}
/* 8-bit output of a whole strip in one go: none wider than the 128-bit path (returns 0). */
template <uint32_t Channels>
inline int store_whole_strip_u8(const simd_vector *, uint8_t *) {
    return 0;
}

} // namespace

#endif /* DSN_SIMD_AVX2_H */
