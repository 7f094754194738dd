/* runtime/kernels/continuous_lanes.h - the AVX2 pieces that the vector continuous evaluators (one point:
   continuous_point_vector.h; a batch of points: continuous_batch.h) share: a pair's candidates packed
   into lanes, the fraction hash and the bilinear texton of 8 candidates, 64-bit lanes packed and compared
   (also filtered_reads_vector.h's). Internal to libdsn; not
   installed (everything here has internal linkage). */
#ifndef DSN_CONTINUOUS_LANES_H
#define DSN_CONTINUOUS_LANES_H

#include <stdint.h>

#include "simd/simd.h" /* the 256-bit operations (simd_256.h) on AVX2 and AVX-512 */
#include "simd/simd_mix64.h"

#if defined(__AVX2__)
namespace {

/* The low 32 bits of the 64-bit lanes of a (candidates 0-3) and b (4-7), as 8 lanes in order. */
inline vector_256 low_halves(vector_256 a, vector_256 b) {
    return permute_64<0xD8>(as_integers(shuffle<0x88>(as_floats(a), as_floats(b))));
}

/* a < b as unsigned 64-bit lanes (AVX2 compares signed: both flipped by 2^63). */
inline vector_256 below_64(vector_256 a, vector_256 b) {
    const vector_256 sign = set_4x64(INT64_MIN);
    return greater_64(bitwise_xor(b, sign), bitwise_xor(a, sign));
}

/* dsn_impulse_hash's 16-bit positions of 8 impulses with 8-bit fields (cells of side <= 16): each 4-bit
   half of the field above 12 bits of the impulse's fraction hash. */
inline void impulse_bits_8(vector_256 fields, vector_256 fraction, vector_256 *bits_x, vector_256 *bits_y) {
    *bits_x = bitwise_or(shift_left_32(bitwise_and(fields, set_8x32(15)), 12),
                         shift_right_logical_32(bitwise_and(fraction, set_8x32(0xFFFF)), 4));
    *bits_y = bitwise_or(shift_left_32(shift_right_logical_32(fields, 4), 12),
                         shift_right_logical_32(fraction, 20));
}

/* The bilinear texton of 8 candidates from their texels' values (32-bit lanes) and weights (0 .. 65280,
   multiples of 2^8):
   add_bilinear's integer with one product per step, (65536 - w) a + w b = 65536 a + w (b - a), the rows
   in 32-bit lanes (below 2^25), the column in 64-bit lanes (multiply_even_32, signed 32 x 32 -> 64 bits,
   exact): candidates 0, 2, 4, 6 in `even`, 1, 3, 5, 7 in `odd`. */
inline void bilinear_8(vector_256 top_left, vector_256 top_right, vector_256 bottom_left,
                       vector_256 bottom_right, vector_256 across, vector_256 down, vector_256 *even,
                       vector_256 *odd) {
    const vector_256 scale = set_8x32(65536);
    const vector_256 upper =
        add_32(shift_left_32(top_left, 16), multiply_32(across, subtract_32(top_right, top_left)));
    const vector_256 lower =
        add_32(shift_left_32(bottom_left, 16), multiply_32(across, subtract_32(bottom_right, bottom_left)));
    const vector_256 difference = subtract_32(lower, upper);
    *even = add_64(multiply_even_32(upper, scale), multiply_even_32(down, difference));
    *odd = add_64(multiply_even_32(shift_right_logical_64(upper, 32), scale),
                  multiply_even_32(shift_right_logical_64(down, 32), shift_right_logical_64(difference, 32)));
}

/* For each set of lanes (bit i: lane i) the lanes in order, 3 bits each from bit 0, and their count at
   bit 24: the permutation that packs a pair's candidates to the front of a vector. */
/* clang-format off */
const uint32_t packing_table[256] = {
    0x00000000u, 0x01000000u, 0x01000001u, 0x02000008u, 0x01000002u, 0x02000010u, 0x02000011u, 0x03000088u,
    0x01000003u, 0x02000018u, 0x02000019u, 0x030000C8u, 0x0200001Au, 0x030000D0u, 0x030000D1u, 0x04000688u,
    0x01000004u, 0x02000020u, 0x02000021u, 0x03000108u, 0x02000022u, 0x03000110u, 0x03000111u, 0x04000888u,
    0x02000023u, 0x03000118u, 0x03000119u, 0x040008C8u, 0x0300011Au, 0x040008D0u, 0x040008D1u, 0x05004688u,
    0x01000005u, 0x02000028u, 0x02000029u, 0x03000148u, 0x0200002Au, 0x03000150u, 0x03000151u, 0x04000A88u,
    0x0200002Bu, 0x03000158u, 0x03000159u, 0x04000AC8u, 0x0300015Au, 0x04000AD0u, 0x04000AD1u, 0x05005688u,
    0x0200002Cu, 0x03000160u, 0x03000161u, 0x04000B08u, 0x03000162u, 0x04000B10u, 0x04000B11u, 0x05005888u,
    0x03000163u, 0x04000B18u, 0x04000B19u, 0x050058C8u, 0x04000B1Au, 0x050058D0u, 0x050058D1u, 0x0602C688u,
    0x01000006u, 0x02000030u, 0x02000031u, 0x03000188u, 0x02000032u, 0x03000190u, 0x03000191u, 0x04000C88u,
    0x02000033u, 0x03000198u, 0x03000199u, 0x04000CC8u, 0x0300019Au, 0x04000CD0u, 0x04000CD1u, 0x05006688u,
    0x02000034u, 0x030001A0u, 0x030001A1u, 0x04000D08u, 0x030001A2u, 0x04000D10u, 0x04000D11u, 0x05006888u,
    0x030001A3u, 0x04000D18u, 0x04000D19u, 0x050068C8u, 0x04000D1Au, 0x050068D0u, 0x050068D1u, 0x06034688u,
    0x02000035u, 0x030001A8u, 0x030001A9u, 0x04000D48u, 0x030001AAu, 0x04000D50u, 0x04000D51u, 0x05006A88u,
    0x030001ABu, 0x04000D58u, 0x04000D59u, 0x05006AC8u, 0x04000D5Au, 0x05006AD0u, 0x05006AD1u, 0x06035688u,
    0x030001ACu, 0x04000D60u, 0x04000D61u, 0x05006B08u, 0x04000D62u, 0x05006B10u, 0x05006B11u, 0x06035888u,
    0x04000D63u, 0x05006B18u, 0x05006B19u, 0x060358C8u, 0x05006B1Au, 0x060358D0u, 0x060358D1u, 0x071AC688u,
    0x01000007u, 0x02000038u, 0x02000039u, 0x030001C8u, 0x0200003Au, 0x030001D0u, 0x030001D1u, 0x04000E88u,
    0x0200003Bu, 0x030001D8u, 0x030001D9u, 0x04000EC8u, 0x030001DAu, 0x04000ED0u, 0x04000ED1u, 0x05007688u,
    0x0200003Cu, 0x030001E0u, 0x030001E1u, 0x04000F08u, 0x030001E2u, 0x04000F10u, 0x04000F11u, 0x05007888u,
    0x030001E3u, 0x04000F18u, 0x04000F19u, 0x050078C8u, 0x04000F1Au, 0x050078D0u, 0x050078D1u, 0x0603C688u,
    0x0200003Du, 0x030001E8u, 0x030001E9u, 0x04000F48u, 0x030001EAu, 0x04000F50u, 0x04000F51u, 0x05007A88u,
    0x030001EBu, 0x04000F58u, 0x04000F59u, 0x05007AC8u, 0x04000F5Au, 0x05007AD0u, 0x05007AD1u, 0x0603D688u,
    0x030001ECu, 0x04000F60u, 0x04000F61u, 0x05007B08u, 0x04000F62u, 0x05007B10u, 0x05007B11u, 0x0603D888u,
    0x04000F63u, 0x05007B18u, 0x05007B19u, 0x0603D8C8u, 0x05007B1Au, 0x0603D8D0u, 0x0603D8D1u, 0x071EC688u,
    0x0200003Eu, 0x030001F0u, 0x030001F1u, 0x04000F88u, 0x030001F2u, 0x04000F90u, 0x04000F91u, 0x05007C88u,
    0x030001F3u, 0x04000F98u, 0x04000F99u, 0x05007CC8u, 0x04000F9Au, 0x05007CD0u, 0x05007CD1u, 0x0603E688u,
    0x030001F4u, 0x04000FA0u, 0x04000FA1u, 0x05007D08u, 0x04000FA2u, 0x05007D10u, 0x05007D11u, 0x0603E888u,
    0x04000FA3u, 0x05007D18u, 0x05007D19u, 0x0603E8C8u, 0x05007D1Au, 0x0603E8D0u, 0x0603E8D1u, 0x071F4688u,
    0x030001F5u, 0x04000FA8u, 0x04000FA9u, 0x05007D48u, 0x04000FAAu, 0x05007D50u, 0x05007D51u, 0x0603EA88u,
    0x04000FABu, 0x05007D58u, 0x05007D59u, 0x0603EAC8u, 0x05007D5Au, 0x0603EAD0u, 0x0603EAD1u, 0x071F5688u,
    0x04000FACu, 0x05007D60u, 0x05007D61u, 0x0603EB08u, 0x05007D62u, 0x0603EB10u, 0x0603EB11u, 0x071F5888u,
    0x05007D63u, 0x0603EB18u, 0x0603EB19u, 0x071F58C8u, 0x0603EB1Au, 0x071F58D0u, 0x071F58D1u, 0x08FAC688u,
};
/* clang-format on */

/* The lane indices of a packing_table entry, in 32-bit lanes (for permute_32). */
inline vector_256 packing_order(uint32_t entry) {
    return bitwise_and(
        shift_right_logical_32_per_lane(set_8x32(entry), set_lanes_8x32(0, 3, 6, 9, 12, 15, 18, 21)),
        set_8x32(7));
}

/* The 8 lanes of a pair of 8-bit fields packed, candidates first (bit i of `candidates`: lane i): their
   fraction hash inputs (stream + lane G) and their fields, in 32-bit lanes. Returns the candidates'
   count. */
inline uint32_t pack_pair_8(uint64_t pair, uint32_t candidates, uint32_t stream, vector_256 *streams,
                            vector_256 *fields) {
    const uint32_t entry = packing_table[candidates & 0xFFu];
    const vector_256 order = packing_order(entry);
    /* lane * 0x9E3779B9 modulo 2^32, as int32 bit patterns */
    const vector_256 weyl = set_lanes_8x32(0, -0x61C88647, 0x3C6EF372, -0x255992D5, 0x78DDE6E4, 0x1715609D,
                                           -0x4AB325AA, 0x5384540F);
    *streams = permute_32(add_32(set_8x32(stream), weyl), order);
    *fields = permute_32(widen_bytes_8x32(set_low_64(pair)), order);
    return entry >> 24;
}

} // namespace
#endif /* __AVX2__ */

#endif /* DSN_CONTINUOUS_LANES_H */
