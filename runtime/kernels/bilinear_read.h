/* runtime/kernels/bilinear_read.h - the fast build's bilinear texton reads of a window's interior, without
   bounds checks (8-bit values on SSE2 vectors), and of its border, texel by texel: the integers of
   add_bilinear (bilinear_texton.h). Shared by the continuous per-point evaluator (continuous_point.cpp)
   and the filtered one (filtered_sift.cpp). Internal to libdsn; not installed (everything here has
   internal linkage). */
#ifndef DSN_BILINEAR_READ_H
#define DSN_BILINEAR_READ_H

#include <stdint.h>

#include "core/continuous_internal.h"

#if !DSN_SMALL_CODE

#if defined(__SSE2__)
#include "simd/simd_128.h"
#endif

namespace {

/* Stored value (8- or 16-bit) plus 2^(8 Bytes - 1), as an unsigned number: flipping the sign bit of a
   two's-complement value (one operation; sign-extending it takes more). */
template <uint32_t Bytes>
inline int64_t biased_value(const unsigned char *at) {
    if (Bytes == 1) return static_cast<int64_t>(at[0] ^ 0x80u);
    return static_cast<int64_t>((at[0] | (static_cast<uint32_t>(at[1]) << 8)) ^ 0x8000u);
}

/* One channel of the bilinear texton (as add_bilinear) of the biased values, with its top-left texel at
   `top`, the texel right of it Stride bytes further, the row below at `bottom`: the weights add up to
   2^32, so it is the texton's plus 2^(32 + 8 Bytes - 1) exactly (the caller takes that off). The
   interpolation is rewritten with one product per step, (65536 - w) a + w b = 65536 a + w (b - a): the
   same integers. */
template <uint32_t Bytes, uint32_t Stride>
inline uint64_t bilinear_channel(const unsigned char *top, const unsigned char *bottom, int64_t across,
                                 int64_t down) {
    const int64_t top_left = biased_value<Bytes>(top), bottom_left = biased_value<Bytes>(bottom);
    const int64_t upper = top_left * 65536 + across * (biased_value<Bytes>(top + Stride) - top_left);
    const int64_t lower = bottom_left * 65536 + across * (biased_value<Bytes>(bottom + Stride) - bottom_left);
    return static_cast<uint64_t>(upper * 65536 + down * (lower - upper));
}

/* The 2 x 2 texels of every channel with their top-left at (row, column), for texels that may leave the
   window of width x height values (rows `stride` values apart; zero outside): each texel read with its
   own bounds test, corners[corner][channel] with corner = 2 (down) + (right). */
template <uint32_t Channels, uint32_t Bytes>
inline void read_corners(const unsigned char *texton, uint32_t width, uint32_t height, uint32_t stride,
                         uint32_t row, uint32_t column, int64_t corners[4][DSN_MAX_CHANNELS]) {
    for (uint32_t corner = 0; corner < 4; corner++) {
        const uint32_t at_row = row + (corner >> 1), at_column = column + (corner & 1u);
        const bool inside = at_row < height && at_column < width; /* -1 (0xFFFFFFFF) is outside too */
        const unsigned char *at = texton + (inside ? (at_row * stride + at_column) * Channels * Bytes : 0u);
        for (uint32_t c = 0; c < Channels; c++)
            corners[corner][c] =
                inside ? biased_value<Bytes>(at + c * Bytes) - (static_cast<int64_t>(1) << (8u * Bytes - 1u))
                       : 0;
    }
}

/* The bilinear texton of every channel, as add_bilinear computes it, for 2 x 2 texels that may leave the
   window (read_corners): the same integers. */
template <uint32_t Channels, uint32_t Bytes>
inline void add_border(const unsigned char *texton, uint32_t width, uint32_t height, uint32_t stride,
                       uint32_t row, uint32_t column, int64_t across, int64_t down, uint64_t *sums) {
    int64_t corners[4][DSN_MAX_CHANNELS];
    read_corners<Channels, Bytes>(texton, width, height, stride, row, column, corners);
    for (uint32_t c = 0; c < Channels; c++) {
        const int64_t upper = (65536 - across) * corners[0][c] + across * corners[1][c];
        const int64_t lower = (65536 - across) * corners[2][c] + across * corners[3][c];
        sums[c] += static_cast<uint64_t>((65536 - down) * upper + down * lower);
    }
}

#if defined(__SSE2__)
/* ---- The bilinear texton of 8-bit values on SSE2 vectors ----
   The same integers as bilinear_channel, exactly, with every channel at once. The biased values v
   (0..255) of the two texels of a row sit in 16-bit lanes as pairs (left, right), one pair per
   channel; the row's interpolation (65536 - across) left + across right is a dot product with the
   weight pair, each weight w split as 128 (w >> 7) + (w & 127) so that both parts fit signed 16-bit
   lanes (w >> 7 <= 512): two madd_16, exact in 32 bits (below 2^24). The column's interpolation
   (65536 - down) upper + down lower, below 2^41, takes 64-bit lanes (multiply_even_unsigned_32: every
   term is non-negative). Reads: 8 bytes from a row's first texel (RGB: the 6 needed and 2 more) or 4
   (grey: 2 and 2 more); past the texton's last row they reach at most 2 bytes into the asset's 4-byte
   CRC, which the loader guarantees lies in the buffer right after the texton (format.h: total_size). */
struct BilinearSums {
    vector_128 even, odd; /* 64-bit lanes: channels 0 and 2; channel 1 (RGB) or the lower row (grey) */
};

/* The bytes of a row's two texels, from its first: 8 of them (RGB: the 6 needed and 2 more) or 4 (grey:
   2 and 2 more). */
template <uint32_t Channels>
inline vector_128 row_bytes(const unsigned char *row) {
    if (Channels == 3) return load_low_8x8(row);
    uint32_t word;
    __builtin_memcpy(&word, row, sizeof word);
    return set_low_32(static_cast<int>(word)); /* the bits unchanged */
}

/* A row's texels (its bytes as row_bytes loads them) as (left, right) 16-bit pairs of biased values, one
   pair per channel (lanes past the channels hold garbage, never used). */
template <uint32_t Channels>
inline vector_128 row_pairs(vector_128 bytes) {
    const vector_128 values = unpack_low_8(bitwise_xor(bytes, set_16x8(-128)), zero_128());
    /* grey: (left, right) already; RGB: left channels in lanes 0-2, right ones in lanes 3-5 */
    return Channels == 3 ? unpack_low_16(values, shift_right_bytes<6>(values)) : values;
}

/* A weight pair (65536 - w, w) as its two parts: high parts (w >> 7) and low parts (w & 127), each
   broadcast as a (left, right) pair of 16-bit lanes. */
inline void weight_parts(uint32_t weight, vector_128 *high, vector_128 *low) {
    const uint32_t left = 65536u - weight;
    *high = set_4x32(static_cast<int32_t>((left >> 7) | ((weight >> 7) << 16)));
    *low = set_4x32(static_cast<int32_t>((left & 127u) | ((weight & 127u) << 16)));
}

/* (65536 - w) left + w right of every pair, in 32-bit lanes. */
inline vector_128 interpolate_pairs(vector_128 pairs, vector_128 high, vector_128 low) {
    return add_32(shift_left_32(madd_16(pairs, high), 7), madd_16(pairs, low));
}

/* The bilinear texton of the two rows' texels (their bytes as row_bytes loads them). */
template <uint32_t Channels>
inline void add_bilinear_bytes(vector_128 top, vector_128 bottom, uint32_t across, uint32_t down,
                               BilinearSums *sums) {
    vector_128 high, low;
    weight_parts(across, &high, &low);
    const vector_128 down_weights =
        set_lanes_4x32(static_cast<int32_t>(65536u - down), 0, static_cast<int32_t>(down), 0);
    if (Channels == 3) {
        const vector_128 upper = interpolate_pairs(row_pairs<3>(top), high, low);
        const vector_128 lower = interpolate_pairs(row_pairs<3>(bottom), high, low);
        const vector_128 up_weight = shuffle_32<0x00>(down_weights),
                         down_weight = shuffle_32<0xAA>(down_weights);
        sums->even = add_64(sums->even, add_64(multiply_even_unsigned_32(upper, up_weight),
                                               multiply_even_unsigned_32(lower, down_weight)));
        sums->odd = add_64(sums->odd,
                           add_64(multiply_even_unsigned_32(shift_right_logical_64(upper, 32), up_weight),
                                  multiply_even_unsigned_32(shift_right_logical_64(lower, 32), down_weight)));
    } else {
        /* lanes: upper, lower; spread to 64-bit lanes, each times its weight */
        const vector_128 rows =
            interpolate_pairs(unpack_low_32(row_pairs<1>(top), row_pairs<1>(bottom)), high, low);
        sums->even = add_64(sums->even, multiply_even_unsigned_32(shuffle_32<0x10>(rows), down_weights));
    }
}

template <uint32_t Channels>
inline void add_bilinear_vector(const unsigned char *top, const unsigned char *bottom, uint32_t across,
                                uint32_t down, BilinearSums *sums) {
    add_bilinear_bytes<Channels>(row_bytes<Channels>(top), row_bytes<Channels>(bottom), across, down, sums);
}

/* The slopes of add_slopes (bilinear_texton.h) for every channel at once, 8-bit values: the vertical
   differences (c - a, d - b) are the rows' pairs subtracted, interpolated across like a row; the
   horizontal ones (b - a, d - c) are each row's pair difference, paired and interpolated down. Every lane
   stays below 65536 255 < 2^24 in magnitude, so a visit's sums of up to 128 candidates fit 32-bit lanes
   exactly (SlopeRead widens them when it takes them). Lane c is channel c. */
struct SlopeLanes {
    vector_128 along_x, along_y;
};

template <uint32_t Channels>
inline void add_slopes_vector(const unsigned char *top, const unsigned char *bottom, uint32_t across,
                              uint32_t down, SlopeLanes *sums) {
    const vector_128 upper = row_pairs<Channels>(row_bytes<Channels>(top));
    const vector_128 lower = row_pairs<Channels>(row_bytes<Channels>(bottom));
    vector_128 high, low;
    weight_parts(across, &high, &low);
    sums->along_y = add_32(sums->along_y, interpolate_pairs(subtract_16(lower, upper), high, low));
    weight_parts(down, &high, &low);
    const vector_128 rows = pair_up(pair_differences(upper), pair_differences(lower));
    sums->along_x = add_32(sums->along_x, interpolate_pairs(rows, high, low));
}

/* The channel sums of the vector's lanes (modulo 2^64). */
template <uint32_t Channels>
inline void take_bilinear_sums(const BilinearSums &sums, uint64_t *out) {
    uint64_t even[2], odd[2];
    __builtin_memcpy(even, &sums.even, sizeof even);
    __builtin_memcpy(odd, &sums.odd, sizeof odd);
    if (Channels == 3) {
        out[0] = even[0], out[1] = odd[0], out[2] = even[1];
    } else {
        out[0] = even[0] + even[1];
    }
}
#endif

} // namespace

#endif /* !DSN_SMALL_CODE */

#endif /* DSN_BILINEAR_READ_H */
