/* runtime/simd/simd_mix64.h - the cell hashes (core/cell_hash.h) on every lane of a vector, written once for
   every width against its operations (their overloads by vector type): dsn_mix64 on 64-bit lanes (the cell
   walks that hash impulse pairs on vectors: the lattice point's on 128 bits, the continuous batch's on 256
   or 512) and dsn_mix32 on 32-bit lanes (keys, fractions' and materials' streams, on 256 or 512 bits).
   Included after the ops header of the translation unit's width (simd.h), so that each width's overloads
   are declared before these templates; empty where simd.h has no ops header. */
#ifndef DSN_SIMD_MIX64_H
#define DSN_SIMD_MIX64_H

#include "simd/simd.h"

#if DSN_SIMD
namespace {

/* Every 64-bit lane set to `value` (the bits unchanged): set_2x64, set_4x64 or set_8x64 by type. */
template <typename Vector>
Vector all_lanes_64(uint64_t value);
template <>
DSN_SIMD_INLINE vector_128 all_lanes_64<vector_128>(uint64_t value) {
    return set_2x64(static_cast<int64_t>(value));
}
#if defined(__AVX2__)
template <>
DSN_SIMD_INLINE vector_256 all_lanes_64<vector_256>(uint64_t value) {
    return set_4x64(static_cast<int64_t>(value));
}
#endif
#if defined(__AVX512F__) && defined(__AVX512BW__)
template <>
DSN_SIMD_INLINE vector_512 all_lanes_64<vector_512>(uint64_t value) {
    return set_8x64(static_cast<int64_t>(value));
}
#endif

/* x * factor modulo 2^64 in every 64-bit lane, by three 32 x 32 -> 64-bit products (no 64-bit multiply
   below AVX512DQ): x_lo f_lo + 2^32 (x_hi f_lo + x_lo f_hi); the high halves' product only reaches bits 64
   and up. */
template <typename Vector>
DSN_SIMD_INLINE Vector multiply_64(Vector x, uint64_t factor) {
    const Vector low = all_lanes_64<Vector>(factor & 0xFFFFFFFFu), high = all_lanes_64<Vector>(factor >> 32);
    const Vector cross = add_64(multiply_even_unsigned_32(shift_right_logical_64(x, 32), low),
                                multiply_even_unsigned_32(x, high));
    return add_64(multiply_even_unsigned_32(x, low), shift_left_64(cross, 32));
}

/* dsn_mix64 of every 64-bit lane. */
template <typename Vector>
DSN_SIMD_INLINE Vector mix64_lanes(Vector x) {
    x = multiply_64(bitwise_xor(x, shift_right_logical_64(x, 30)), 0xBF58476D1CE4E5B9u);
    x = multiply_64(bitwise_xor(x, shift_right_logical_64(x, 27)), 0x94D049BB133111EBu);
    return bitwise_xor(x, shift_right_logical_64(x, 31));
}

/* Every 32-bit lane set to `value`: set_8x32 or set_16x32 by type (a 32-bit multiply needs AVX2). */
template <typename Vector>
Vector all_lanes_32(uint32_t value);
#if defined(__AVX2__)
template <>
DSN_SIMD_INLINE vector_256 all_lanes_32<vector_256>(uint32_t value) {
    return set_8x32(value);
}
#endif
#if defined(__AVX512F__) && defined(__AVX512BW__)
template <>
DSN_SIMD_INLINE vector_512 all_lanes_32<vector_512>(uint32_t value) {
    return set_16x32(value);
}
#endif

/* dsn_mix32 of every 32-bit lane. */
template <typename Vector>
DSN_SIMD_INLINE Vector mix32_lanes(Vector x) {
    x = bitwise_xor(x, shift_right_logical_32(x, 16));
    x = multiply_32(x, all_lanes_32<Vector>(0x7FEB352Du));
    x = bitwise_xor(x, shift_right_logical_32(x, 15));
    x = multiply_32(x, all_lanes_32<Vector>(0x846CA68Bu));
    return bitwise_xor(x, shift_right_logical_32(x, 16));
}

} // namespace
#endif /* DSN_SIMD */

#endif /* DSN_SIMD_MIX64_H */
