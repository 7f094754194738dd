/* runtime/simd/simd_128.h - the 128-bit operations every x86 copy of the strip path shares (SSE2): the
   output stores that work one 128-bit lane (4 values) at a time, whatever the vector width, the SSE2
   strip path's own operations (simd_sse2.h's vectors are these), the tile walk's widening sums
   (tile_walk.h), a constant of the continuous splat, the bilinear reads and slopes of 8-bit textons, the
   lattice per-point walk's impulse tests (point.cpp), and the 128-bit pieces of the wider kernels.
   Included by the ops headers (simd.h), and on its own where only SSE2 is sure (tile_walk.h,
   bilinear_read.h and point.cpp, built with the runtime's own flags). */
#ifndef DSN_SIMD_128_H
#define DSN_SIMD_128_H

#include <emmintrin.h>
#include <stdint.h>

#include "dsn/dsn.h"

/* The operations are forced inline, as the intrinsics are: through plain inline wrappers GCC sees the
   operations in another order, and allocates registers and schedules differently. For the same reason they
   take and give the instructions' own scalar types where a conversion inside would name a temporary after
   the parameter (the 64-bit broadcasts take int64_t, the top-bit gathers give int). */
#if defined(__GNUC__)
#define DSN_SIMD_INLINE inline __attribute__((always_inline))
#else
#define DSN_SIMD_INLINE inline
#endif

namespace {

typedef __m128i vector_128; /* 4 lanes of 32 bits, 8 of 16 bits or 16 of 8 bits */
typedef __m128 floats_128;

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

/* float(value) * 2^-16: the conversion rounds once to nearest, like dsn_fixed_to_float. */
inline __m128 to_float_4(__m128i fixed) {
    return _mm_mul_ps(_mm_cvtepi32_ps(fixed), _mm_set1_ps(1.0f / 65536.0f));
}

/* dsn_fixed_to_u8 before packing: clamp to [0, 2^16], then (255 v + 2^15) >> 16. */
inline __m128i to_u8_range(__m128i value) {
    const __m128i one = _mm_set1_epi32(DSN_ONE);
    value = _mm_and_si128(value, _mm_cmpgt_epi32(value, _mm_setzero_si128()));
    __m128i above = _mm_cmpgt_epi32(value, one);
    value = _mm_or_si128(_mm_and_si128(above, one), _mm_andnot_si128(above, value));
    return _mm_srli_epi32(
        _mm_add_epi32(_mm_sub_epi32(_mm_slli_epi32(value, 8), value), _mm_set1_epi32(32768)), 16);
}

/* The continuous splat's byte order for the across weights (simd_avx2.h, simd_avx512.h): byte 3 of each
   64-bit lane (the weight's 8 bits) into the high bytes of its words 1 and 3, zeros elsewhere. */
inline __m128i splat_across_order() {
    return _mm_setr_epi8(-128, -128, -128, 3, -128, -128, -128, 3, -128, -128, -128, 11, -128, -128, -128,
                         11);
}

/* ---- The bilinear slopes of 8-bit textons (bilinear_read.h's add_slopes_vector) ---- */

/* right - left of every (left, right) pair of 16-bit lanes, in 32-bit lanes. */
inline __m128i pair_differences(__m128i pairs) { return _mm_madd_epi16(pairs, _mm_set1_epi32(0x0001FFFF)); }

/* a - b in 16-bit lanes (wrapping). */
inline __m128i subtract_16(__m128i a, __m128i b) { return _mm_sub_epi16(a, b); }

/* Pairs of 16-bit lanes (low, high) from the low 16 bits of two vectors of 32-bit lanes. */
inline __m128i pair_up(__m128i low, __m128i high) {
    return _mm_or_si128(_mm_and_si128(low, _mm_set1_epi32(0xFFFF)), _mm_slli_epi32(high, 16));
}

inline __m128i zero_128() { return _mm_setzero_si128(); }

/* The four 32-bit lanes, signed. */
inline void take_32_lanes(__m128i vector, int32_t *lanes) { __builtin_memcpy(lanes, &vector, 16); }

/* ---- The 128-bit operations of the wider kernels (continuous_*.h, filtered_*_vector.h) ---- */

/* A shift count for every lane of a vector (shift_left_32_by). */
DSN_SIMD_INLINE vector_128 shift_count(int count) { return _mm_cvtsi32_si128(count); }
/* value in the low 64 bits, zeros above. */
DSN_SIMD_INLINE vector_128 set_low_64(uint64_t value) {
#if defined(__x86_64__)
    return _mm_cvtsi64_si128(static_cast<long long>(value));
#else
    return _mm_set_epi64x(0, static_cast<long long>(value)); /* 32-bit x86: no 64-bit register to move */
#endif
}
DSN_SIMD_INLINE vector_128 set_2x64(int64_t value) { return _mm_set1_epi64x(value); }
/* The lanes in order, lane 0 first. */
DSN_SIMD_INLINE vector_128 set_lanes_2x64(uint64_t lane_0, uint64_t lane_1) {
    return _mm_set_epi64x(static_cast<long long>(lane_1), static_cast<long long>(lane_0));
}
DSN_SIMD_INLINE vector_128 load_16x8(const uint8_t *at) {
    return _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(at)));
}
DSN_SIMD_INLINE vector_128 load_2x64(const uint64_t *at) {
    return _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(at)));
}
/* The bytes in order, byte 0 first. */
DSN_SIMD_INLINE vector_128 set_lanes_16x8(char lane_0, char lane_1, char lane_2, char lane_3, char lane_4,
                                          char lane_5, char lane_6, char lane_7, char lane_8, char lane_9,
                                          char lane_10, char lane_11, char lane_12, char lane_13,
                                          char lane_14, char lane_15) {
    return _mm_setr_epi8(lane_0, lane_1, lane_2, lane_3, lane_4, lane_5, lane_6, lane_7, lane_8, lane_9,
                         lane_10, lane_11, lane_12, lane_13, lane_14, lane_15);
}
DSN_SIMD_INLINE vector_128 bitwise_and(vector_128 a, vector_128 b) { return _mm_and_si128(a, b); }
DSN_SIMD_INLINE vector_128 bitwise_or(vector_128 a, vector_128 b) { return _mm_or_si128(a, b); }
DSN_SIMD_INLINE vector_128 subtract_64(vector_128 a, vector_128 b) { return _mm_sub_epi64(a, b); }
DSN_SIMD_INLINE vector_128 shift_right_logical_64(vector_128 a, uint32_t count) {
    return _mm_srli_epi64(a, static_cast<int>(count));
}
/* The top bit of byte k in bit k (an int, as the instruction's). */
DSN_SIMD_INLINE int top_bits_of_bytes(vector_128 a) { return _mm_movemask_epi8(a); }

/* ---- The strip path's 128-bit operations (simd_sse2.h's strip vectors are these; tile_normalize.h,
   tile_store.h), and the tile walk's widening sums (tile_walk.h) ---- */

DSN_SIMD_INLINE vector_128 madd_16(vector_128 a, vector_128 b) { return _mm_madd_epi16(a, b); }
DSN_SIMD_INLINE vector_128 add_16(vector_128 a, vector_128 b) { return _mm_add_epi16(a, b); }
DSN_SIMD_INLINE vector_128 add_32(vector_128 a, vector_128 b) { return _mm_add_epi32(a, b); }
DSN_SIMD_INLINE vector_128 subtract_32(vector_128 a, vector_128 b) { return _mm_sub_epi32(a, b); }
DSN_SIMD_INLINE vector_128 unpack_low_16(vector_128 a, vector_128 b) { return _mm_unpacklo_epi16(a, b); }
DSN_SIMD_INLINE vector_128 unpack_high_16(vector_128 a, vector_128 b) { return _mm_unpackhi_epi16(a, b); }
DSN_SIMD_INLINE vector_128 unpack_low_32(vector_128 a, vector_128 b) { return _mm_unpacklo_epi32(a, b); }
DSN_SIMD_INLINE vector_128 unpack_high_32(vector_128 a, vector_128 b) { return _mm_unpackhi_epi32(a, b); }
DSN_SIMD_INLINE floats_128 as_floats(vector_128 a) { return _mm_castsi128_ps(a); }
DSN_SIMD_INLINE vector_128 as_integers(floats_128 a) { return _mm_castps_si128(a); }

DSN_SIMD_INLINE vector_128 load_4x32(const uint32_t *at) {
    return _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(at)));
}
DSN_SIMD_INLINE void store_4x32(uint32_t *at, vector_128 value) {
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(at)), value);
}
DSN_SIMD_INLINE void store_4x32(int32_t *at, vector_128 value) {
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(at)), value);
}
DSN_SIMD_INLINE void store_16x8(uint8_t *at, vector_128 value) {
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(at)), value);
}
/* The low 8 bytes. */
DSN_SIMD_INLINE void store_low_8x8(uint8_t *at, vector_128 value) {
    _mm_storel_epi64(static_cast<__m128i *>(static_cast<void *>(at)), value);
}
/* Orders the streaming (non-temporal) stores before every later store. */
DSN_SIMD_INLINE void store_fence() { _mm_sfence(); }

DSN_SIMD_INLINE vector_128 set_8x16(int16_t value) { return _mm_set1_epi16(value); }
DSN_SIMD_INLINE vector_128 set_4x32(int32_t value) { return _mm_set1_epi32(value); }
/* The lanes in order, lane 0 first. */
DSN_SIMD_INLINE vector_128 set_lanes_8x16(int16_t lane_0, int16_t lane_1, int16_t lane_2, int16_t lane_3,
                                          int16_t lane_4, int16_t lane_5, int16_t lane_6, int16_t lane_7) {
    return _mm_setr_epi16(lane_0, lane_1, lane_2, lane_3, lane_4, lane_5, lane_6, lane_7);
}

DSN_SIMD_INLINE vector_128 unpack_low_8(vector_128 a, vector_128 b) { return _mm_unpacklo_epi8(a, b); }
DSN_SIMD_INLINE vector_128 unpack_high_8(vector_128 a, vector_128 b) { return _mm_unpackhi_epi8(a, b); }
DSN_SIMD_INLINE vector_128 shift_right_arithmetic_16(vector_128 a, uint32_t count) {
    return _mm_srai_epi16(a, static_cast<int>(count));
}
DSN_SIMD_INLINE vector_128 shift_right_arithmetic_32(vector_128 a, uint32_t count) {
    return _mm_srai_epi32(a, static_cast<int>(count));
}
/* 32-bit lanes to 16 bits, and 16-bit lanes to 8 bits unsigned, saturating: a's lanes first, then b's. */
DSN_SIMD_INLINE vector_128 pack_saturated_32x16(vector_128 a, vector_128 b) { return _mm_packs_epi32(a, b); }
DSN_SIMD_INLINE vector_128 pack_saturated_unsigned_16x8(vector_128 a, vector_128 b) {
    return _mm_packus_epi16(a, b);
}

/* ---- The bilinear texton of 8-bit values (bilinear_read.h, filtered_sift.cpp) ---- */

/* The 8 bytes at `at` in the low half, zeros above. */
DSN_SIMD_INLINE vector_128 load_low_8x8(const uint8_t *at) {
    return _mm_loadl_epi64(static_cast<const __m128i *>(static_cast<const void *>(at)));
}
DSN_SIMD_INLINE vector_128 load_low_64(const uint64_t *at) {
    return _mm_loadl_epi64(static_cast<const __m128i *>(static_cast<const void *>(at)));
}
/* value in the low 32 bits, zeros above (an int, as the instruction's). */
DSN_SIMD_INLINE vector_128 set_low_32(int value) { return _mm_cvtsi32_si128(value); }
DSN_SIMD_INLINE vector_128 set_16x8(char value) { return _mm_set1_epi8(value); }
/* The lanes in order, lane 0 first. */
DSN_SIMD_INLINE vector_128 set_lanes_4x32(int32_t lane_0, int32_t lane_1, int32_t lane_2, int32_t lane_3) {
    return _mm_set_epi32(lane_3, lane_2, lane_1, lane_0);
}
DSN_SIMD_INLINE vector_128 bitwise_xor(vector_128 a, vector_128 b) { return _mm_xor_si128(a, b); }
/* The whole vector shifted down by Count bytes, zeros in. */
template <int Count>
DSN_SIMD_INLINE vector_128 shift_right_bytes(vector_128 a) {
    return _mm_srli_si128(a, Count);
}
DSN_SIMD_INLINE vector_128 shift_left_32(vector_128 a, uint32_t count) {
    return _mm_slli_epi32(a, static_cast<int>(count));
}
template <int Order>
DSN_SIMD_INLINE vector_128 shuffle_32(vector_128 a) {
    return _mm_shuffle_epi32(a, Order);
}
DSN_SIMD_INLINE vector_128 add_64(vector_128 a, vector_128 b) { return _mm_add_epi64(a, b); }
DSN_SIMD_INLINE vector_128 shift_left_64(vector_128 a, uint32_t count) {
    return _mm_slli_epi64(a, static_cast<int>(count));
}
/* The unsigned products of the even (low) 32-bit lanes, in 64-bit lanes. */
DSN_SIMD_INLINE vector_128 multiply_even_unsigned_32(vector_128 a, vector_128 b) {
    return _mm_mul_epu32(a, b);
}

/* ---- The lattice per-point walk's 16 impulses a vector (point.cpp) ---- */

DSN_SIMD_INLINE void store_8x16(uint16_t *at, vector_128 value) {
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(at)), value);
}
/* ~a & b. */
DSN_SIMD_INLINE vector_128 and_not(vector_128 a, vector_128 b) { return _mm_andnot_si128(a, b); }
DSN_SIMD_INLINE vector_128 subtract_8(vector_128 a, vector_128 b) { return _mm_sub_epi8(a, b); }
/* The low 16 bits of the products. */
DSN_SIMD_INLINE vector_128 multiply_16(vector_128 a, vector_128 b) { return _mm_mullo_epi16(a, b); }
DSN_SIMD_INLINE vector_128 minimum_unsigned_8(vector_128 a, vector_128 b) { return _mm_min_epu8(a, b); }
/* All ones where equal. */
DSN_SIMD_INLINE vector_128 equal_8(vector_128 a, vector_128 b) { return _mm_cmpeq_epi8(a, b); }
DSN_SIMD_INLINE vector_128 shift_right_logical_16(vector_128 a, uint32_t count) {
    return _mm_srli_epi16(a, static_cast<int>(count));
}
/* 16-bit lane Index, zero-extended (an int, as the instruction's). */
template <int Index>
DSN_SIMD_INLINE int lane_16(vector_128 a) {
    return _mm_extract_epi16(a, Index);
}
/* The low 32-bit lane (an int, as the instruction's). */
DSN_SIMD_INLINE int low_32(vector_128 a) { return _mm_cvtsi128_si32(a); }

} // namespace

#endif /* DSN_SIMD_128_H */
