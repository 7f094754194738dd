/* runtime/simd/simd_256.h - the 256-bit operations the AVX2 and the AVX-512 copies share: the strip path's
   AVX2 vectors (simd_avx2.h), and the 8 lanes of the vector continuous and filtered kernels
   (continuous_lanes.h, continuous_point_vector.h, continuous_batch*.h, filtered_*_vector.h), which the
   AVX-512 copy runs too, for the last 8 candidates of a visit and where its algorithm keeps 256-bit steps,
   and the gathered splat rows of both copies (splat_row.h).
   Included by simd_avx2.h and simd_avx512.h. */
#ifndef DSN_SIMD_256_H
#define DSN_SIMD_256_H

#include <immintrin.h>

#include "simd/simd_128.h"

namespace {

typedef __m256i vector_256; /* 8 lanes of 32 bits, 4 of 64 bits or 16 of 16 bits */
typedef __m256 floats_256;

/* ---- Memory ---- */
/* load_8x32, store_8x32 and set_8x32 are plain inline, as the kernels' helpers they replaced were: forced,
   GCC allocates some of the filtered reads' registers differently. */
inline vector_256 load_8x32(const uint32_t *at) {
    return _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(at)));
}
inline void store_8x32(uint32_t *at, vector_256 value) {
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(at)), value);
}
/* The lanes whose mask lane has its top bit set, the others 0 (and not read). */
DSN_SIMD_INLINE vector_256 load_masked_8x32(const uint32_t *at, vector_256 mask) {
    return _mm256_maskload_epi32(static_cast<const int *>(static_cast<const void *>(at)), mask);
}
DSN_SIMD_INLINE vector_256 load_4x64(const int64_t *at) {
    return _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(at)));
}
DSN_SIMD_INLINE vector_256 load_4x64(const uint64_t *at) {
    return _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(at)));
}
/* The lanes whose mask lane has its top bit set, the others 0 (and not read). */
DSN_SIMD_INLINE vector_256 load_masked_4x64(const int64_t *at, vector_256 mask) {
    return _mm256_maskload_epi64(static_cast<const long long *>(static_cast<const void *>(at)), mask);
}
DSN_SIMD_INLINE void store_4x64(int64_t *at, vector_256 value) {
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(at)), value);
}
DSN_SIMD_INLINE void store_4x64(uint64_t *at, vector_256 value) {
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(at)), value);
}
/* 128-bit sign-extending loads (SSE4.1, which both copies have), for the lattice point's texel sums:
   the 8 signed bytes at `at` as 16-bit lanes, and the 4 at `at` as 32-bit lanes. */
DSN_SIMD_INLINE vector_128 load_signed_8x8_to_16(const unsigned char *at) {
    return _mm_cvtepi8_epi16(_mm_loadl_epi64(static_cast<const __m128i *>(static_cast<const void *>(at))));
}
DSN_SIMD_INLINE vector_128 load_signed_8x4_to_32(const unsigned char *at) {
    int32_t bytes;
    __builtin_memcpy(&bytes, at, sizeof bytes);
    return _mm_cvtepi8_epi32(_mm_cvtsi32_si128(bytes));
}
/* The low 8 bytes of a, signed, as 16-bit lanes. */
DSN_SIMD_INLINE vector_128 widen_signed_8_to_16(vector_128 a) { return _mm_cvtepi8_epi16(a); }
/* Lane k: the 32 bits at base + Scale offsets[k] bytes where mask's lane k has its top bit set, else 0. */
template <int Scale>
DSN_SIMD_INLINE vector_256 gather_masked_32(const void *base, vector_256 offsets, vector_256 mask) {
    return _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), static_cast<const int *>(base), offsets, mask,
                                       Scale);
}

/* Lane k: the 32 bits at base + Scale offsets[k] bytes. */
template <int Scale>
DSN_SIMD_INLINE vector_256 gather_32(const void *base, vector_256 offsets) {
    return _mm256_i32gather_epi32(static_cast<const int *>(base), offsets, Scale);
}
/* 64-bit lane k: the 64 bits at base + Scale offsets[k] bytes (4 32-bit offsets). */
template <int Scale>
DSN_SIMD_INLINE vector_256 gather_64(const void *base, vector_128 offsets) {
    return _mm256_i32gather_epi64(static_cast<const long long *>(base), offsets, Scale);
}

/* 64-bit lane k: the 64 bits at base + Scale offsets[k] bytes where mask's lane k has its top bit set, else
   0 (and not read). */
template <int Scale>
DSN_SIMD_INLINE vector_256 gather_masked_64(const void *base, vector_128 offsets, vector_256 mask) {
    return _mm256_mask_i32gather_epi64(_mm256_setzero_si256(), static_cast<const long long *>(base), offsets,
                                       mask, Scale);
}

/* ---- Constants ---- */
DSN_SIMD_INLINE vector_256 zero_256() { return _mm256_setzero_si256(); }
inline vector_256 set_8x32(uint32_t value) { return _mm256_set1_epi32(static_cast<int>(value)); }
DSN_SIMD_INLINE vector_256 set_4x64(int64_t value) { return _mm256_set1_epi64x(value); }
/* The lanes in order, lane 0 first. */
DSN_SIMD_INLINE vector_256 set_lanes_8x32(int32_t lane_0, int32_t lane_1, int32_t lane_2, int32_t lane_3,
                                          int32_t lane_4, int32_t lane_5, int32_t lane_6, int32_t lane_7) {
    return _mm256_setr_epi32(lane_0, lane_1, lane_2, lane_3, lane_4, lane_5, lane_6, lane_7);
}
DSN_SIMD_INLINE vector_256 set_lanes_32x8(char lane_0, char lane_1, char lane_2, char lane_3, char lane_4,
                                          char lane_5, char lane_6, char lane_7, char lane_8, char lane_9,
                                          char lane_10, char lane_11, char lane_12, char lane_13,
                                          char lane_14, char lane_15, char lane_16, char lane_17,
                                          char lane_18, char lane_19, char lane_20, char lane_21,
                                          char lane_22, char lane_23, char lane_24, char lane_25,
                                          char lane_26, char lane_27, char lane_28, char lane_29,
                                          char lane_30, char lane_31) {
    return _mm256_setr_epi8(lane_0, lane_1, lane_2, lane_3, lane_4, lane_5, lane_6, lane_7, lane_8, lane_9,
                            lane_10, lane_11, lane_12, lane_13, lane_14, lane_15, lane_16, lane_17, lane_18,
                            lane_19, lane_20, lane_21, lane_22, lane_23, lane_24, lane_25, lane_26, lane_27,
                            lane_28, lane_29, lane_30, lane_31);
}
DSN_SIMD_INLINE vector_256 set_lanes_4x64(int64_t lane_0, int64_t lane_1, int64_t lane_2, int64_t lane_3) {
    return _mm256_setr_epi64x(lane_0, lane_1, lane_2, lane_3);
}

/* ---- Bits ---- */
DSN_SIMD_INLINE vector_256 bitwise_and(vector_256 a, vector_256 b) { return _mm256_and_si256(a, b); }
DSN_SIMD_INLINE vector_256 bitwise_or(vector_256 a, vector_256 b) { return _mm256_or_si256(a, b); }
DSN_SIMD_INLINE vector_256 bitwise_xor(vector_256 a, vector_256 b) { return _mm256_xor_si256(a, b); }
/* ~a & b. */
DSN_SIMD_INLINE vector_256 and_not(vector_256 a, vector_256 b) { return _mm256_andnot_si256(a, b); }
DSN_SIMD_INLINE vector_256 shift_left_32(vector_256 a, uint32_t count) {
    return _mm256_slli_epi32(a, static_cast<int>(count));
}
/* Every lane by the same count, the low 64 bits of `count` (shift_count). */
DSN_SIMD_INLINE vector_256 shift_left_32_by(vector_256 a, vector_128 count) {
    return _mm256_sll_epi32(a, count);
}
DSN_SIMD_INLINE vector_256 shift_right_logical_32(vector_256 a, uint32_t count) {
    return _mm256_srli_epi32(a, static_cast<int>(count));
}
DSN_SIMD_INLINE vector_256 shift_right_logical_32_by(vector_256 a, vector_128 count) {
    return _mm256_srl_epi32(a, count);
}
/* Lane k by counts' lane k. */
DSN_SIMD_INLINE vector_256 shift_right_logical_32_per_lane(vector_256 a, vector_256 counts) {
    return _mm256_srlv_epi32(a, counts);
}
DSN_SIMD_INLINE vector_256 shift_right_arithmetic_32(vector_256 a, uint32_t count) {
    return _mm256_srai_epi32(a, static_cast<int>(count));
}
DSN_SIMD_INLINE vector_256 shift_left_64(vector_256 a, uint32_t count) {
    return _mm256_slli_epi64(a, static_cast<int>(count));
}
DSN_SIMD_INLINE vector_256 shift_left_64_by(vector_256 a, vector_128 count) {
    return _mm256_sll_epi64(a, count);
}
DSN_SIMD_INLINE vector_256 shift_right_logical_64(vector_256 a, uint32_t count) {
    return _mm256_srli_epi64(a, static_cast<int>(count));
}
DSN_SIMD_INLINE vector_256 shift_right_logical_64_by(vector_256 a, vector_128 count) {
    return _mm256_srl_epi64(a, count);
}

/* ---- Arithmetic (modulo 2^32 or 2^64) ---- */
DSN_SIMD_INLINE vector_256 add_32(vector_256 a, vector_256 b) { return _mm256_add_epi32(a, b); }
DSN_SIMD_INLINE vector_256 subtract_32(vector_256 a, vector_256 b) { return _mm256_sub_epi32(a, b); }
DSN_SIMD_INLINE vector_256 multiply_32(vector_256 a, vector_256 b) { return _mm256_mullo_epi32(a, b); }
DSN_SIMD_INLINE vector_256 add_64(vector_256 a, vector_256 b) { return _mm256_add_epi64(a, b); }
DSN_SIMD_INLINE vector_256 subtract_64(vector_256 a, vector_256 b) { return _mm256_sub_epi64(a, b); }
/* The low 32 bits of each 64-bit lane, signed, multiplied into the 64-bit lane (exact). */
DSN_SIMD_INLINE vector_256 multiply_even_32(vector_256 a, vector_256 b) { return _mm256_mul_epi32(a, b); }
/* Pairs of 16-bit lanes multiplied (signed) and summed into 32-bit lanes. */
DSN_SIMD_INLINE vector_256 madd_16(vector_256 a, vector_256 b) { return _mm256_madd_epi16(a, b); }
/* The low 32 bits of each 64-bit lane, unsigned, multiplied into the 64-bit lane (exact). */
DSN_SIMD_INLINE vector_256 multiply_even_unsigned_32(vector_256 a, vector_256 b) {
    return _mm256_mul_epu32(a, b);
}
DSN_SIMD_INLINE vector_256 minimum_32(vector_256 a, vector_256 b) { return _mm256_min_epi32(a, b); }
DSN_SIMD_INLINE vector_256 maximum_32(vector_256 a, vector_256 b) { return _mm256_max_epi32(a, b); }
DSN_SIMD_INLINE vector_256 minimum_unsigned_32(vector_256 a, vector_256 b) { return _mm256_min_epu32(a, b); }

/* ---- Comparisons: all ones where true ---- */
DSN_SIMD_INLINE vector_256 equal_32(vector_256 a, vector_256 b) { return _mm256_cmpeq_epi32(a, b); }
DSN_SIMD_INLINE vector_256 greater_8(vector_256 a, vector_256 b) { return _mm256_cmpgt_epi8(a, b); }
DSN_SIMD_INLINE vector_256 greater_32(vector_256 a, vector_256 b) { return _mm256_cmpgt_epi32(a, b); }
DSN_SIMD_INLINE vector_256 greater_64(vector_256 a, vector_256 b) { return _mm256_cmpgt_epi64(a, b); }
/* The top bit of 32-bit lane k in bit k (an int, as the instruction's). */
DSN_SIMD_INLINE int top_bits_of_32(vector_256 a) { return _mm256_movemask_ps(_mm256_castsi256_ps(a)); }
/* Bit k: lane k of a below lane k of b, unsigned (no unsigned comparison before AVX-512: a < b exactly when
   min(a, b) is not b). */
DSN_SIMD_INLINE uint32_t less_unsigned_32_bits(vector_256 a, vector_256 b) {
    return ~static_cast<uint32_t>(top_bits_of_32(equal_32(minimum_unsigned_32(a, b), b))) & 0xFFu;
}
/* Bit k: the top bit of 64-bit lane k. */
DSN_SIMD_INLINE int top_bits_of_64(vector_256 a) { return _mm256_movemask_pd(_mm256_castsi256_pd(a)); }

/* The top bit of byte k in bit k (an int, as the instruction's). */
DSN_SIMD_INLINE int top_bits_of_bytes(vector_256 a) { return _mm256_movemask_epi8(a); }

/* ---- Lanes ---- */
/* b's bytes where mask's byte has its top bit set, a's elsewhere. */
DSN_SIMD_INLINE vector_256 blend_bytes(vector_256 a, vector_256 b, vector_256 mask) {
    return _mm256_blendv_epi8(a, b, mask);
}
/* The even 16-bit lanes of a, the odd ones of b. */
DSN_SIMD_INLINE vector_256 blend_odd_16(vector_256 a, vector_256 b) { return _mm256_blend_epi16(a, b, 0xAA); }
/* Lane k: lane order[k] (its low 3 bits) of a, across the whole vector. */
DSN_SIMD_INLINE vector_256 permute_32(vector_256 a, vector_256 order) {
    return _mm256_permutevar8x32_epi32(a, order);
}
/* 64-bit lane k: lane (Order >> 2 k) & 3 of a. */
template <int Order>
DSN_SIMD_INLINE vector_256 permute_64(vector_256 a) {
    return _mm256_permute4x64_epi64(a, Order);
}
/* Per 128-bit lane: byte k is byte order[k] (its low 4 bits) of the lane, or 0 where order[k]'s top bit is
 * set. */
DSN_SIMD_INLINE vector_256 shuffle_bytes(vector_256 a, vector_256 order) {
    return _mm256_shuffle_epi8(a, order);
}
/* Per 128-bit lane: the low (high) 64-bit lane of a, then of b. */
DSN_SIMD_INLINE vector_256 unpack_low_64(vector_256 a, vector_256 b) { return _mm256_unpacklo_epi64(a, b); }
DSN_SIMD_INLINE vector_256 unpack_high_64(vector_256 a, vector_256 b) { return _mm256_unpackhi_epi64(a, b); }
/* The low 128 bits: 128-bit lane Order & 3 of (a, b); the high ones: lane (Order >> 4) & 3. */
template <int Order>
DSN_SIMD_INLINE vector_256 permute_128_of_two(vector_256 a, vector_256 b) {
    return _mm256_permute2x128_si256(a, b, Order);
}
DSN_SIMD_INLINE vector_128 low_128(vector_256 a) { return _mm256_castsi256_si128(a); }
DSN_SIMD_INLINE vector_128 high_128(vector_256 a) { return _mm256_extracti128_si256(a, 1); }
/* Per 128-bit lane: 32-bit lane k is lane (Order >> 2 k) & 3 of the lane. */
template <int Order>
DSN_SIMD_INLINE vector_256 shuffle_32(vector_256 a) {
    return _mm256_shuffle_epi32(a, Order);
}
/* 4 32-bit lanes, unsigned, widened into 64-bit lanes. */
DSN_SIMD_INLINE vector_256 widen_unsigned_32x64(vector_128 a) { return _mm256_cvtepu32_epi64(a); }
/* 8 bytes (the low 64 bits of bytes), unsigned, widened into 32-bit lanes. */
DSN_SIMD_INLINE vector_256 widen_bytes_8x32(vector_128 bytes) { return _mm256_cvtepu8_epi32(bytes); }
DSN_SIMD_INLINE floats_256 as_floats(vector_256 a) { return _mm256_castsi256_ps(a); }
DSN_SIMD_INLINE vector_256 as_integers(floats_256 a) { return _mm256_castps_si256(a); }
/* Per 128-bit lane: two 32-bit lanes of a, then two of b, by Order as _MM_SHUFFLE's. */
template <int Order>
DSN_SIMD_INLINE floats_256 shuffle(floats_256 a, floats_256 b) {
    return _mm256_shuffle_ps(a, b, Order);
}

} // namespace

#endif /* DSN_SIMD_256_H */
