/* runtime/kernels/filtered_reads_vector.h - the reads of the filtered sift (filtered_sift.cpp) on AVX2
   vectors, as a kernel (kernels.h: the AVX2 and AVX-512 kernels include it), for 8-bit levels: the buffered
   candidates of one tap and one level, 8 at a time: the exact reach test (on the listing's 32-bit narrow
   offsets where it has them, else in 64-bit lanes), the bracket's offsets in 32-bit lanes, the reads as
   the continuous evaluator's (continuous_point_vector.h's add_window_reads_8, here with the level's
   stride). The same reads and integers as the sift's own, so the same sums modulo 2^64. The AVX-512
   kernel takes 16 candidates at a time (add_window_reads_16; for RGB levels both texels of a row by one
   8-byte read, add_pair_reads_16), the last 15 or fewer 8 at a time; levels of at most 7 texels across and
   11 down (the coarse ones, whose reach holds the most impulses) it holds in registers as tables of the
   reads' texel differences instead (add_register_reads_16), read without gathers by a rearranged, equal,
   integer. The gradient's reads add each read's slopes too (add_slope_lanes), from the gathered texels.
   Internal to libdsn; not installed (everything here has internal linkage). */
#ifndef DSN_FILTERED_READS_VECTOR_H
#define DSN_FILTERED_READS_VECTOR_H

#include "core/filtered_internal.h"
#include "kernels/continuous_point_vector.h"
#include "kernels/kernels.h"

#if defined(__AVX2__) && DSN_FILTERING && !DSN_SMALL_CODE
namespace {

/* 4 candidates' values; those of a group's last, partial vector where `present` (zeros elsewhere: no read
   past the list). */
inline vector_256 load_64(const int64_t *at, vector_256 present, bool whole) {
    return whole ? load_4x64(at) : load_masked_4x64(at, present);
}

/* The reach test of one axis for 4 candidates: u = c + start, in reach when u < limit, and the bracket's
   floor((u + 2^l) / 2^(l + 16)) (below 2^32 where in reach: (2 radius + 2) 2^16). */
inline vector_256 axis_offsets(vector_256 c, vector_256 start, vector_256 limit, vector_256 bias,
                               vector_128 shift, vector_256 *in_reach) {
    const vector_256 u = add_64(c, start);
    *in_reach = bitwise_and(*in_reach, below_64(u, limit));
    return shift_right_logical_64_by(add_64(u, bias), shift);
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* axis_offsets for 8 candidates on 512-bit vectors, all present: the offsets in 32-bit lanes. */
inline vector_256 axis_offsets_wide(const int64_t *at, vector_512 start, vector_512 limit, vector_512 bias,
                                    vector_128 shift, mask_8 *in_reach) {
    const vector_512 u = add_64(load_8x64(at), start);
    *in_reach = less_unsigned_64(*in_reach, u, limit);
    return truncate_64x32(shift_right_logical_64_by(add_64(u, bias), shift));
}

/* The offsets of candidates first .. first + 15 (all present) in reach, packed from packed_x[packed],
   packed_y[packed] on (16 values stored); returns their count. */
inline uint32_t pack_offsets_16(const int64_t *xs, const int64_t *ys, const vector_512 *tests,
                                vector_128 shift, uint32_t *packed_x, uint32_t *packed_y) {
    mask_8 low = 0xFF, high = 0xFF;
    const vector_256 x_low = axis_offsets_wide(xs, tests[0], tests[1], tests[4], shift, &low),
                     x_high = axis_offsets_wide(xs + 8, tests[0], tests[1], tests[4], shift, &high),
                     y_low = axis_offsets_wide(ys, tests[2], tests[3], tests[4], shift, &low),
                     y_high = axis_offsets_wide(ys + 8, tests[2], tests[3], tests[4], shift, &high);
    const mask_16 reach =
        static_cast<mask_16>(static_cast<uint32_t>(low) | (static_cast<uint32_t>(high) << 8));
    store_16x32(packed_x, compress_32(reach, concatenate_256(x_low, x_high)));
    store_16x32(packed_y, compress_32(reach, concatenate_256(y_low, y_high)));
    return mask_count(reach);
}

/* One row's two texels (3 channels) of 16 candidates by one 8-byte read each, from the pair's column
   clamped into [0, width - 2] (at: its byte offsets) and moved by one texel where it was clamped, the
   texel that left the window zeroed: left and right hold each lane's left and right texel in the low 3
   bytes, as add_window_reads_16's gathers. Lanes outside `rows` read zeros. The reads stay within the
   rows' bytes plus 2 (as the interior's). */
inline void texel_pairs_16(const unsigned char *values, vector_512 at, mask_16 rows, mask_16 left_out,
                           mask_16 right_out, vector_512 *left, vector_512 *right) {
    const vector_512 first_texel = set_8x64(0xFFFFFF);
    const vector_512 evens = set_lanes_16x32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    vector_512 words[2];
    for (uint32_t half = 0; half < 2; half++) {
        const mask_8 lanes = static_cast<mask_8>(rows >> (8u * half)),
                     left_lanes = static_cast<mask_8>(left_out >> (8u * half)),
                     right_lanes = static_cast<mask_8>(right_out >> (8u * half));
        const vector_256 index = half == 0 ? low_256(at) : high_256(at);
        vector_512 word = gather_masked_64<1>(values, index, lanes);
        word = shift_left_64_where(left_lanes, word, 24);
        word = and_64_where(word, right_lanes, shift_right_logical_64(word, 24), first_texel);
        words[half] = word;
    }
    *left = permute_32_of_two(words[0], evens, words[1]);
    *right =
        permute_32_of_two(shift_right_logical_64(words[0], 24), evens, shift_right_logical_64(words[1], 24));
}

/* add_window_reads_16 for 3-channel levels at least 2 texels wide: each row's two texels by one read
   (texel_pairs_16), half the gathered values; the same values, so the same sums (and slopes). */
template <bool Slopes>
DSN_POINT_INLINE void add_pair_reads_16(const unsigned char *values, uint32_t width, uint32_t height,
                                        uint32_t stride, vector_512 s_x, vector_512 s_y, mask_16 reach,
                                        vector_512 *sums, vector_512 *slope_x, vector_512 *slope_y) {
    const vector_512 weight_bits = set_16x32(bilinear_weight_mask), one = set_16x32(1);
    const vector_512 right_column = shift_right_logical_32(s_x, 16),
                     lower_row = shift_right_logical_32(s_y, 16);
    const vector_512 row = subtract_32(lower_row, one);
    const vector_512 across = bitwise_and(s_x, weight_bits), down = bitwise_and(s_y, weight_bits);
    /* right_column 0: the left texel is out; width: the right one; beyond: both (never in reach). */
    const mask_16 left_out = equal_32(right_column, zero_512()),
                  right_out = equal_32(right_column, set_16x32(width)),
                  inside = less_equal_unsigned_32(reach, right_column, set_16x32(width));
    const mask_16 top = less_equal_unsigned_32(inside, row, set_16x32(height - 1u)),
                  bottom = less_equal_unsigned_32(inside, lower_row, set_16x32(height - 1u));
    const vector_512 first =
        minimum_unsigned_32(maximum_32(subtract_32(right_column, one), zero_512()), set_16x32(width - 2u));
    const vector_512 entry = add_32(multiply_32(row, set_16x32(stride)), first);
    const vector_512 at = add_32(shift_left_32(entry, 1), entry);
    const vector_512 below = add_32(at, set_16x32(stride * 3u));
    vector_512 top_left, top_right, bottom_left, bottom_right;
    texel_pairs_16(values, at, top, left_out, right_out, &top_left, &top_right);
    texel_pairs_16(values, below, bottom, left_out, right_out, &bottom_left, &bottom_right);
    for (uint32_t c = 0; c < 3; c++) {
        const vector_512 a = lane_byte_16(top_left, c), b = lane_byte_16(top_right, c),
                         d = lane_byte_16(bottom_left, c), e = lane_byte_16(bottom_right, c);
        add_bilinear_16(a, b, d, e, across, down, &sums[c]);
        if (Slopes) add_slope_lanes(a, b, d, e, across, down, &slope_x[c], &slope_y[c]);
    }
}

/* A level of at most 7 texels across and 11 down held in registers, read without gathers: entry 8 R + C
   (R in [0, 11], C in [0, 7]) of a channel describes the texels of the bilinear read whose lower row is R and
   right column C (add_pair_reads_16's): A, B, D, E at (R - 1, C - 1), (R - 1, C), (R, C - 1), (R, C), zero
   outside the window. The read A (2^16 - a)(2^16 - d) + B a (2^16 - d) + D (2^16 - a) d + E a d (a, d: across
   and down) is the same integer as 2^31 (B + D) + 2^16 ((a - 2^15)(B - A) + (d - 2^15)(D - A)) + a d (A - B -
   D + E), so each entry holds the 16-bit pairs (B - A, D - A) and (A - B - D + E, B + D): one multiply-add of
   16-bit pairs, 32-bit sums for all but the last term, and one 64-bit product per lane. Tables of 64
   entries (Vectors 4) for levels up to 7 texels down, else 96 (Vectors 6), looked up by permutes of 32. */
const uint32_t register_level_side = 7, register_level_tallest = 11, register_level_least = 64;

template <uint32_t Channels, uint32_t Vectors>
struct RegisterLevel {
    /* (B - A, D - A), (A - B - D + E, B + D) */
    vector_512 differences[Channels][Vectors], corners[Channels][Vectors];
    vector_512 last_column, last_row; /* width, height */
};

/* A channel's sums of add_register_reads_16: 64-bit lanes, and the 32-bit lanes of the terms times 2^16
   and 2^31 (the latter with 2 (A - B - D + E) where the product a d, a 32-bit signed lane, went below 0:
   its product then lacks 2^32 (A - B - D + E)), which widen_register_sums adds to the 64-bit ones before
   they could overflow. */
struct RegisterSums {
    vector_512 wide, times_16, times_31;
};

/* Byte `index` of each 32-bit lane, sign-extended. */
inline vector_512 signed_byte(vector_512 words, uint32_t index) {
    return shift_right_arithmetic_32(shift_left_32_by(words, shift_count(static_cast<int>(24u - 8u * index))),
                                     24);
}

/* Two 16-bit values in a 32-bit lane, low first. */
inline vector_512 pair_16(vector_512 low, vector_512 high) {
    return bitwise_or(bitwise_and(low, set_16x32(0xFFFF)), shift_left_32(high, 16));
}

/* The level's texels in 32-bit lanes, texel (R - 1, C - 1) at entry 8 R + C (zero outside the window;
   one gathered read each, as the pair reads'), then each entry's 4 texels by whole-vector shifts of the
   entries (next column: + 1, next row: + 8, both: + 9). */
template <uint32_t Channels, uint32_t Vectors>
inline void register_level(const dsn_walked_level *level, RegisterLevel<Channels, Vectors> *out) {
    const vector_512 zero = zero_512(), one = set_16x32(1);
    const vector_512 lanes = set_lanes_16x32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    vector_512 texels[Vectors + 1u];
    for (uint32_t v = 0; v < Vectors; v++) {
        const vector_512 entry = add_32(lanes, set_16x32(16u * v));
        const vector_512 row = subtract_32(shift_right_logical_32(entry, 3), one),
                         column = subtract_32(bitwise_and(entry, set_16x32(7)), one);
        const mask_16 inside = less_equal_unsigned_32(
            less_equal_unsigned_32(row, set_16x32(level->height - 1u)), column, set_16x32(level->width - 1u));
        const vector_512 index = add_32(multiply_32(row, set_16x32(level->stride)), column);
        const vector_512 at = Channels == 3 ? add_32(shift_left_32(index, 1), index) : index;
        texels[v] = gather_masked_32<1>(level->values, at, inside);
    }
    texels[Vectors] = zero;
    for (uint32_t v = 0; v < Vectors; v++) {
        const vector_512 right = combine_shift_right_32<1>(texels[v + 1u], texels[v]),
                         below = combine_shift_right_32<8>(texels[v + 1u], texels[v]),
                         below_right = combine_shift_right_32<9>(texels[v + 1u], texels[v]);
        for (uint32_t c = 0; c < Channels; c++) {
            const vector_512 a = signed_byte(texels[v], c), b = signed_byte(right, c),
                             d = signed_byte(below, c), e = signed_byte(below_right, c);
            out->differences[c][v] = pair_16(subtract_32(b, a), subtract_32(d, a));
            out->corners[c][v] = pair_16(subtract_32(add_32(a, e), add_32(b, d)), add_32(b, d));
        }
    }
    out->last_column = set_16x32(level->width);
    out->last_row = set_16x32(level->height);
}

/* Entry `index` of a table of 64 (4 vectors), zero outside `inside`. */
template <uint32_t Vectors>
inline vector_512 table_entry(const vector_512 *table, vector_512 index, const mask_16 *part) {
    vector_512 entry = permute_32_of_two_or_zero(part[0], table[0], index, table[1]);
    for (uint32_t k = 1; k < Vectors / 2u; k++)
        entry =
            bitwise_or(entry, permute_32_of_two_or_zero(part[k], table[2u * k], index, table[2u * k + 1u]));
    return entry;
}

/* The weights of a read's slopes (Slopes: add_register_reads_16's gradient) and where they go. */
struct RegisterSlopes {
    vector_512 across, down;
    vector_512 *slope_x, *slope_y; /* a channel's 32-bit lanes (add_slope_lanes's) */
};

/* One channel's part of add_register_reads_16; with Slopes its slopes too, 65536 (B - A) + down (A - B - D +
   E) along x and 65536 (D - A) + across (A - B - D + E) along y (add_slope_lanes's integers), from the same
   entries. */
template <uint32_t Vectors, bool Slopes>
DSN_POINT_INLINE void add_register_channel(const vector_512 *difference_table, const vector_512 *corner_table,
                                           vector_512 index, const mask_16 *part, vector_512 weights,
                                           vector_512 product, vector_512 product_odd, mask_16 negative,
                                           RegisterSums *sums, const RegisterSlopes &slopes) {
    const vector_512 differences = table_entry<Vectors>(difference_table, index, part),
                     corners = table_entry<Vectors>(corner_table, index, part);
    sums->times_16 = add_32(sums->times_16, madd_16(weights, differences));
    const vector_512 cross = shift_right_arithmetic_32(shift_left_32(corners, 16), 16);
    if (Slopes) {
        const vector_512 along_x = shift_left_32(differences, 16),
                         along_y = bitwise_and(differences, set_16x32(0xFFFF0000u));
        *slopes.slope_x = add_32(*slopes.slope_x, add_32(along_x, multiply_32(slopes.down, cross)));
        *slopes.slope_y = add_32(*slopes.slope_y, add_32(along_y, multiply_32(slopes.across, cross)));
    }
    sums->times_31 = add_32(sums->times_31, shift_right_arithmetic_32(corners, 16));
    sums->times_31 = add_32_where(negative, sums->times_31, add_32(cross, cross));
    sums->wide = add_64(sums->wide, add_64(multiply_even_32(product, cross),
                                           multiply_even_32(product_odd, shift_right_logical_64(cross, 32))));
}

/* add_pair_reads_16's reads (the same integers, so the same sums, and slopes) from a level in registers. */
template <uint32_t Channels, uint32_t Vectors, bool Slopes>
DSN_POINT_INLINE void add_register_reads_16(const RegisterLevel<Channels, Vectors> &level, vector_512 s_x,
                                            vector_512 s_y, mask_16 reach, RegisterSums *sums,
                                            vector_512 *slope_x, vector_512 *slope_y) {
    const vector_512 weight_bits = set_16x32(bilinear_weight_mask), half = set_16x32(0x8000);
    const vector_512 right_column = shift_right_logical_32(s_x, 16),
                     lower_row = shift_right_logical_32(s_y, 16);
    const vector_512 across = bitwise_and(s_x, weight_bits), down = bitwise_and(s_y, weight_bits);
    const mask_16 inside = less_equal_unsigned_32(
        less_equal_unsigned_32(reach, right_column, level.last_column), lower_row, level.last_row);
    const vector_512 index = add_32(shift_left_32(lower_row, 3), right_column);
    /* part k: the lanes (inside) whose entry lies in the table's k-th 32 */
    mask_16 part[Vectors / 2u];
    const vector_512 which = shift_right_logical_32(index, 5);
    for (uint32_t k = 0; k < Vectors / 2u; k++) part[k] = equal_32(inside, which, set_16x32(k));
    /* (a - 2^15, d - 2^15) as 16-bit pairs; a d, below 2^32 */
    const vector_512 weights =
        bitwise_xor(bitwise_or(across, shift_left_32(down, 16)), bitwise_or(half, shift_left_32(half, 16)));
    const vector_512 product = multiply_32(across, down), product_odd = shift_right_logical_64(product, 32);
    const mask_16 negative = less_32(product, zero_512());
    /* the channels written out: the compiler then keeps each one's sums in registers */
    const RegisterSlopes slopes_0 = {across, down, &slope_x[0], &slope_y[0]};
    add_register_channel<Vectors, Slopes>(level.differences[0], level.corners[0], index, part, weights,
                                          product, product_odd, negative, &sums[0], slopes_0);
    if (Channels == 3) {
        const RegisterSlopes slopes_1 = {across, down, &slope_x[1], &slope_y[1]},
                             slopes_2 = {across, down, &slope_x[2], &slope_y[2]};
        add_register_channel<Vectors, Slopes>(level.differences[1], level.corners[1], index, part, weights,
                                              product, product_odd, negative, &sums[1], slopes_1);
        add_register_channel<Vectors, Slopes>(level.differences[2], level.corners[2], index, part, weights,
                                              product, product_odd, negative, &sums[2], slopes_2);
    }
}

/* A 32-bit lane sum times 2^shift, as two 64-bit lanes' (modulo 2^64). */
inline vector_512 widened(vector_512 lanes, uint32_t shift) {
    const vector_128 count = shift_count(static_cast<int>(shift));
    return add_64(shift_left_64_by(widen_signed_32x64(low_256(lanes)), count),
                  shift_left_64_by(widen_signed_32x64(high_256(lanes)), count));
}

/* The 32-bit sums added to the 64-bit ones and cleared: per 16 reads each grows by less than 2^25 (the
   multiply-add), so every block of packed_block reads or fewer keeps them exact. */
inline void widen_register_sums(RegisterSums *sums) {
    sums->wide = add_64(sums->wide, add_64(widened(sums->times_16, 16), widened(sums->times_31, 31)));
    sums->times_16 = sums->times_31 = zero_512();
}
#endif

/* pack_offsets_16 for candidates first .. first + 7 of which the first `valid` exist (8 values stored). */
inline uint32_t pack_offsets_8(const int64_t *xs, const int64_t *ys, uint32_t valid, const vector_256 *tests,
                               vector_128 shift, uint32_t *packed_x, uint32_t *packed_y) {
    const vector_256 valid_lanes = set_4x64(static_cast<int64_t>(valid));
    vector_256 reach_low = greater_64(valid_lanes, set_lanes_4x64(0, 1, 2, 3)),
               reach_high = greater_64(valid_lanes, set_lanes_4x64(4, 5, 6, 7));
    const bool whole = valid >= 8u;
    const vector_256 s_x = low_halves(
        axis_offsets(load_64(xs, reach_low, whole), tests[0], tests[1], tests[4], shift, &reach_low),
        axis_offsets(load_64(xs + 4, reach_high, whole), tests[0], tests[1], tests[4], shift, &reach_high));
    const vector_256 s_y = low_halves(
        axis_offsets(load_64(ys, reach_low, whole), tests[2], tests[3], tests[4], shift, &reach_low),
        axis_offsets(load_64(ys + 4, reach_high, whole), tests[2], tests[3], tests[4], shift, &reach_high));
    const uint32_t reach = static_cast<uint32_t>(top_bits_of_32(low_halves(reach_low, reach_high)));
    const uint32_t entry = packing_table[reach];
    const vector_256 order = packing_order(entry);
    store_8x32(packed_x, permute_32(s_x, order));
    store_8x32(packed_y, permute_32(s_y, order));
    return entry >> 24;
}

/* a < b as unsigned 32-bit lanes (AVX2 compares signed: both flipped by 2^31). */
inline vector_256 below_32(vector_256 a, vector_256 b) {
    const vector_256 sign = set_8x32(0x80000000u);
    return greater_32(bitwise_xor(b, sign), bitwise_xor(a, sign));
}

/* The reach test of one axis on narrow offsets (kernels.h, filtered_sift.cpp's narrow_test): in reach
   when c + add < limit, the bracket's value (c + read) >> l. */
#if defined(__AVX512F__) && defined(__AVX512BW__)
inline uint32_t pack_narrow_16(const uint32_t *xs, const uint32_t *ys, mask_16 present,
                               const vector_512 *tests, vector_128 shift, uint32_t *packed_x,
                               uint32_t *packed_y) {
    const vector_512 c_x = load_masked_16x32(xs, present), c_y = load_masked_16x32(ys, present);
    const mask_16 reach = less_unsigned_32(less_unsigned_32(present, add_32(c_x, tests[0]), tests[1]),
                                           add_32(c_y, tests[3]), tests[4]);
    store_16x32(packed_x, compress_32(reach, shift_right_logical_32_by(add_32(c_x, tests[2]), shift)));
    store_16x32(packed_y, compress_32(reach, shift_right_logical_32_by(add_32(c_y, tests[5]), shift)));
    return mask_count(reach);
}
#endif

/* pack_narrow_16 for candidates first .. first + 7 of which the first `valid` exist (8 values stored). */
inline uint32_t pack_narrow_8(const uint32_t *xs, const uint32_t *ys, uint32_t valid, const vector_256 *tests,
                              vector_128 shift, uint32_t *packed_x, uint32_t *packed_y) {
    const vector_256 present = greater_32(set_8x32(valid), set_lanes_8x32(0, 1, 2, 3, 4, 5, 6, 7));
    const vector_256 c_x = valid >= 8u ? load_8x32(xs) : load_masked_8x32(xs, present),
                     c_y = valid >= 8u ? load_8x32(ys) : load_masked_8x32(ys, present);
    const vector_256 in_x = below_32(add_32(c_x, tests[0]), tests[1]),
                     in_y = below_32(add_32(c_y, tests[3]), tests[4]);
    const uint32_t reach =
        static_cast<uint32_t>(top_bits_of_32(bitwise_and(present, bitwise_and(in_x, in_y))));
    const uint32_t entry = packing_table[reach];
    const vector_256 order = packing_order(entry);
    store_8x32(packed_x, permute_32(shift_right_logical_32_by(add_32(c_x, tests[2]), shift), order));
    store_8x32(packed_y, permute_32(shift_right_logical_32_by(add_32(c_y, tests[5]), shift), order));
    return entry >> 24;
}

/* Candidates are tested and their offsets packed a block at a time, then read. */
const uint32_t packed_block = 256;

#if DSN_GRADIENTS
/* The 32-bit lanes of a block's slopes (add_slope_lanes: at most 2^5 reads a lane) added to the 64-bit
   lanes and cleared. */
inline void widen_slopes(vector_256 *lanes, vector_256 *sums) {
    *sums = add_widened_32(*sums, *lanes);
    *lanes = zero_256();
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
inline void widen_slopes(vector_512 *lanes, vector_256 *sums) {
    *sums = add_widened_32(add_widened_32(*sums, low_256(*lanes)), high_256(*lanes));
    *lanes = zero_512();
}
#endif

/* widen_slopes of every channel's lanes along x and y. */
template <uint32_t Channels, typename Vector>
inline void widen_channel_slopes(Vector *lanes_x, Vector *lanes_y, vector_256 *slope_x, vector_256 *slope_y) {
    for (uint32_t c = 0; c < Channels; c++) {
        widen_slopes(&lanes_x[c], &slope_x[c]);
        widen_slopes(&lanes_y[c], &slope_y[c]);
    }
}
#endif

/* Vectors 4 or 6: the level's tables built (the caller checks that it fits them) and its reads taken from
   them, in copies of their own, so that the other calls (Vectors 0) neither make room for them nor clear
   their sums. Slopes: the reads' slopes added to slopes[0] (x) and slopes[1] (y) too. */
template <uint32_t Channels, uint32_t Vectors, bool Slopes>
void filter_level_reads_8(const dsn_walked_level *level, const int64_t *xs, const int64_t *ys,
                          const uint32_t *narrow_xs, const uint32_t *narrow_ys, uint32_t count,
                          const uint64_t *tests, const uint32_t *narrow_tests, uint64_t *out,
                          uint64_t (*slopes)[DSN_MAX_CHANNELS]) {
    const vector_256 bias = set_4x64(static_cast<int64_t>(tests[4]));
    const vector_256 offset_tests_8[5] = {
        set_4x64(static_cast<int64_t>(tests[0])), set_4x64(static_cast<int64_t>(tests[1])),
        set_4x64(static_cast<int64_t>(tests[2])), set_4x64(static_cast<int64_t>(tests[3])), bias};
    const vector_128 shift = shift_count(static_cast<int>(level->level + 16u));
    const vector_256 zero = zero_256();
    vector_256 sums[Channels];
    for (uint32_t c = 0; c < Channels; c++) sums[c] = zero;
#if defined(__AVX512F__) && defined(__AVX512BW__)
    const vector_512 wide_tests[5] = {
        set_8x64(static_cast<int64_t>(tests[0])), set_8x64(static_cast<int64_t>(tests[1])),
        set_8x64(static_cast<int64_t>(tests[2])), set_8x64(static_cast<int64_t>(tests[3])),
        set_8x64(static_cast<int64_t>(tests[4]))};
    vector_512 wide_sums[Channels], wide_slope_x[Channels], wide_slope_y[Channels];
    for (uint32_t c = 0; c < Channels; c++) wide_sums[c] = wide_slope_x[c] = wide_slope_y[c] = zero_512();
#endif
    vector_256 slope_x[Channels], slope_y[Channels], slope_lanes_x[Channels], slope_lanes_y[Channels];
    for (uint32_t c = 0; c < Channels; c++)
        slope_x[c] = slope_y[c] = slope_lanes_x[c] = slope_lanes_y[c] = zero;
    vector_256 narrow_tests_8[6];
    for (uint32_t i = 0; i < 6; i++) narrow_tests_8[i] = set_8x32(narrow_tests[i]);
    const vector_128 narrow_shift = shift_count(static_cast<int>(level->level));
#if defined(__AVX512F__) && defined(__AVX512BW__)
    vector_512 narrow_tests_16[6];
    for (uint32_t i = 0; i < 6; i++) narrow_tests_16[i] = set_16x32(narrow_tests[i]);
#endif
#if defined(__AVX512F__) && defined(__AVX512BW__)
    const bool in_registers = Vectors != 0;
    RegisterLevel<Channels, Vectors == 0 ? 4u : Vectors> registers;
    RegisterSums register_sums[Channels];
    for (uint32_t c = 0; c < Channels; c++)
        register_sums[c].wide = register_sums[c].times_16 = register_sums[c].times_31 = zero_512();
    if (in_registers) register_level<Channels, Vectors == 0 ? 4u : Vectors>(level, &registers);
#endif
    uint32_t packed_x[packed_block + 16], packed_y[packed_block + 16];
    for (uint32_t block = 0; block < count; block += packed_block) {
        const uint32_t end = count - block < packed_block ? count : block + packed_block;
        uint32_t packed = 0, first = block;
        if (narrow_xs != 0) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
            for (; first < end; first += 16u) {
                const mask_16 present =
                    static_cast<mask_16>(end - first >= 16u ? 0xFFFFu : (1u << (end - first)) - 1u);
                packed += pack_narrow_16(narrow_xs + first, narrow_ys + first, present, narrow_tests_16,
                                         narrow_shift, packed_x + packed, packed_y + packed);
            }
#endif
            for (; first < end; first += 8u)
                packed += pack_narrow_8(narrow_xs + first, narrow_ys + first, end - first, narrow_tests_8,
                                        narrow_shift, packed_x + packed, packed_y + packed);
        } else {
#if defined(__AVX512F__) && defined(__AVX512BW__)
            for (; first + 16u <= end; first += 16u)
                packed += pack_offsets_16(xs + first, ys + first, wide_tests, shift, packed_x + packed,
                                          packed_y + packed);
#endif
            for (; first < end; first += 8u)
                packed += pack_offsets_8(xs + first, ys + first, end - first, offset_tests_8, shift,
                                         packed_x + packed, packed_y + packed);
        }
        /* The lanes past the last packed offset read zeros (defined values; the masks leave them out). */
        store_8x32(packed_x + packed, zero), store_8x32(packed_x + packed + 8, zero);
        store_8x32(packed_y + packed, zero), store_8x32(packed_y + packed + 8, zero);
        uint32_t next = 0;
#if defined(__AVX512F__) && defined(__AVX512BW__)
        if (in_registers) {
            for (; next < packed; next += 16u) {
                const uint32_t left = packed - next;
                const mask_16 reach = static_cast<mask_16>(left >= 16u ? 0xFFFFu : (1u << left) - 1u);
                add_register_reads_16<Channels, Vectors == 0 ? 4u : Vectors, Slopes>(
                    registers, load_16x32(packed_x + next), load_16x32(packed_y + next), reach, register_sums,
                    wide_slope_x, wide_slope_y);
            }
            for (uint32_t c = 0; c < Channels; c++) widen_register_sums(&register_sums[c]);
        }
        for (; next + 8u < packed; next += 16u) {
            const uint32_t left = packed - next;
            const mask_16 reach = static_cast<mask_16>(left >= 16u ? 0xFFFFu : (1u << left) - 1u);
            const vector_512 s_x = load_16x32(packed_x + next), s_y = load_16x32(packed_y + next);
            if (Channels == 3 && level->width >= 2)
                add_pair_reads_16<Slopes>(level->values, level->width, level->height, level->stride, s_x, s_y,
                                          reach, wide_sums, wide_slope_x, wide_slope_y);
            else
                add_window_reads_16<Channels, Slopes>(level->values, level->width, level->height,
                                                      level->stride, s_x, s_y, reach, wide_sums, wide_slope_x,
                                                      wide_slope_y);
        }
#if DSN_GRADIENTS
        if (Slopes) widen_channel_slopes<Channels>(wide_slope_x, wide_slope_y, slope_x, slope_y);
#endif
#endif
        for (; next < packed; next += 8u) {
            const vector_256 reach =
                greater_32(set_8x32(packed - next), set_lanes_8x32(0, 1, 2, 3, 4, 5, 6, 7));
            add_window_reads_8<Channels, Slopes>(level->values, level->width, level->height, level->stride,
                                                 load_8x32(packed_x + next), load_8x32(packed_y + next),
                                                 reach, sums, slope_lanes_x, slope_lanes_y);
        }
#if DSN_GRADIENTS
        if (Slopes) widen_channel_slopes<Channels>(slope_lanes_x, slope_lanes_y, slope_x, slope_y);
#endif
    }
#if defined(__AVX512F__) && defined(__AVX512BW__)
    if (in_registers)
        for (uint32_t c = 0; c < Channels; c++) wide_sums[c] = add_64(wide_sums[c], register_sums[c].wide);
    for (uint32_t c = 0; c < Channels; c++) /* the 64-bit lanes' sums folded into 4 lanes */
        sums[c] = add_64(sums[c], add_64(low_256(wide_sums[c]), high_256(wide_sums[c])));
#endif
    for (uint32_t c = 0; c < Channels; c++) {
        out[c] += lane_total(sums[c]);
        if (Slopes) slopes[0][c] += lane_total(slope_x[c]), slopes[1][c] += lane_total(slope_y[c]);
    }
}

/* The reads of filter_level_reads with or without the slopes: a level that fits the tables (AVX-512) from
   them. */
template <bool Slopes>
void level_reads(const dsn_walked_level *level, uint32_t channels, const int64_t *xs, const int64_t *ys,
                 const uint32_t *narrow_xs, const uint32_t *narrow_ys, uint32_t count, const uint64_t *tests,
                 const uint32_t *narrow_tests, uint64_t *out, uint64_t (*slopes)[DSN_MAX_CHANNELS]) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
    /* the tables cost as much to build as the reads they spare on a few dozen candidates */
    if (level->width <= register_level_side && level->height <= register_level_tallest &&
        count >= register_level_least) {
        const bool tall = level->height > register_level_side;
        if (channels == 3 && tall)
            filter_level_reads_8<3, 6, Slopes>(level, xs, ys, narrow_xs, narrow_ys, count, tests,
                                               narrow_tests, out, slopes);
        else if (channels == 3)
            filter_level_reads_8<3, 4, Slopes>(level, xs, ys, narrow_xs, narrow_ys, count, tests,
                                               narrow_tests, out, slopes);
        else if (tall)
            filter_level_reads_8<1, 6, Slopes>(level, xs, ys, narrow_xs, narrow_ys, count, tests,
                                               narrow_tests, out, slopes);
        else
            filter_level_reads_8<1, 4, Slopes>(level, xs, ys, narrow_xs, narrow_ys, count, tests,
                                               narrow_tests, out, slopes);
        return;
    }
#endif
    if (channels == 3)
        filter_level_reads_8<3, 0, Slopes>(level, xs, ys, narrow_xs, narrow_ys, count, tests, narrow_tests,
                                           out, slopes);
    else
        filter_level_reads_8<1, 0, Slopes>(level, xs, ys, narrow_xs, narrow_ys, count, tests, narrow_tests,
                                           out, slopes);
}

/* kernels.h's filter_level_reads. */
void filter_level_reads(const dsn_walked_level *level, uint32_t channels, const int64_t *xs,
                        const int64_t *ys, const uint32_t *narrow_xs, const uint32_t *narrow_ys,
                        uint32_t count, const uint64_t *tests, const uint32_t *narrow_tests, uint64_t *out,
                        uint64_t (*slopes)[DSN_MAX_CHANNELS]) {
#if DSN_GRADIENTS
    if (slopes != 0) {
        level_reads<true>(level, channels, xs, ys, narrow_xs, narrow_ys, count, tests, narrow_tests, out,
                          slopes);
        return;
    }
#else
    (void)slopes;
#endif
    level_reads<false>(level, channels, xs, ys, narrow_xs, narrow_ys, count, tests, narrow_tests, out, 0);
}

} // namespace
/* The kernel entry (kernels.h): null where there is none. */
#define DSN_FILTER_READS_ENTRY filter_level_reads
#else
#define DSN_FILTER_READS_ENTRY 0
#endif

#endif /* DSN_FILTERED_READS_VECTOR_H */
