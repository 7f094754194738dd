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
   integer. Internal to libdsn; not installed (everything here has internal linkage). */
#ifndef DSN_FILTERED_READS_VECTOR_H
#define DSN_FILTERED_READS_VECTOR_H

#include "core/filtered_internal.h"
#include "kernels/continuous_point_vector.h"
#include "kernels/kernels.h"

#if defined(__AVX2__) && DSN_FILTERING && !DSN_SMALL_CODE
namespace {

/* 4 candidates' values; those of a group's last, partial vector where `present` (zeros elsewhere: no read
   past the list). */
inline __m256i load_64(const int64_t *at, __m256i present, bool whole) {
    const long long *from = static_cast<const long long *>(static_cast<const void *>(at));
    return whole ? _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(at)))
                 : _mm256_maskload_epi64(from, present);
}

/* The reach test of one axis for 4 candidates: u = c + start, in reach when u < limit, and the bracket's
   floor((u + 2^l) / 2^(l + 16)) (below 2^32 where in reach: (2 radius + 2) 2^16). */
inline __m256i axis_offsets(__m256i c, __m256i start, __m256i limit, __m256i bias, __m128i shift,
                            __m256i *in_reach) {
    const __m256i u = _mm256_add_epi64(c, start);
    *in_reach = _mm256_and_si256(*in_reach, below_64(u, limit));
    return _mm256_srl_epi64(_mm256_add_epi64(u, bias), shift);
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* axis_offsets for 8 candidates on 512-bit vectors, all present: the offsets in 32-bit lanes. */
inline __m256i axis_offsets_wide(const int64_t *at, __m512i start, __m512i limit, __m512i bias, __m128i shift,
                                 __mmask8 *in_reach) {
    const __m512i u = _mm512_add_epi64(_mm512_loadu_si512(at), start);
    *in_reach = _mm512_mask_cmplt_epu64_mask(*in_reach, u, limit);
    return _mm512_cvtepi64_epi32(_mm512_srl_epi64(_mm512_add_epi64(u, bias), shift));
}

/* The offsets of candidates first .. first + 15 (all present) in reach, packed from packed_x[packed],
   packed_y[packed] on (16 values stored); returns their count. */
inline uint32_t pack_offsets_16(const int64_t *xs, const int64_t *ys, const __m512i *tests, __m128i shift,
                                uint32_t *packed_x, uint32_t *packed_y) {
    __mmask8 low = 0xFF, high = 0xFF;
    const __m256i x_low = axis_offsets_wide(xs, tests[0], tests[1], tests[4], shift, &low),
                  x_high = axis_offsets_wide(xs + 8, tests[0], tests[1], tests[4], shift, &high),
                  y_low = axis_offsets_wide(ys, tests[2], tests[3], tests[4], shift, &low),
                  y_high = axis_offsets_wide(ys + 8, tests[2], tests[3], tests[4], shift, &high);
    const __mmask16 reach =
        static_cast<__mmask16>(static_cast<uint32_t>(low) | (static_cast<uint32_t>(high) << 8));
    _mm512_storeu_si512(packed_x, _mm512_maskz_compress_epi32(
                                      reach, _mm512_inserti64x4(_mm512_castsi256_si512(x_low), x_high, 1)));
    _mm512_storeu_si512(packed_y, _mm512_maskz_compress_epi32(
                                      reach, _mm512_inserti64x4(_mm512_castsi256_si512(y_low), y_high, 1)));
    return mask_count(reach);
}

/* One row's two texels (3 channels) of 16 candidates by one 8-byte read each, from the pair's column
   clamped into [0, width - 2] (at: its byte offsets) and moved by one texel where it was clamped, the
   texel that left the window zeroed: left and right hold each lane's left and right texel in the low 3
   bytes, as add_window_reads_16's gathers. Lanes outside `rows` read zeros. The reads stay within the
   rows' bytes plus 2 (as the interior's). */
inline void texel_pairs_16(const unsigned char *values, __m512i at, __mmask16 rows, __mmask16 left_out,
                           __mmask16 right_out, __m512i *left, __m512i *right) {
    const __m512i zero = _mm512_setzero_si512(), first_texel = _mm512_set1_epi64(0xFFFFFF);
    const __m512i evens = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    __m512i words[2];
    for (uint32_t half = 0; half < 2; half++) {
        const __mmask8 lanes = static_cast<__mmask8>(rows >> (8u * half)),
                       left_lanes = static_cast<__mmask8>(left_out >> (8u * half)),
                       right_lanes = static_cast<__mmask8>(right_out >> (8u * half));
        const __m256i index = half == 0 ? _mm512_castsi512_si256(at) : _mm512_extracti64x4_epi64(at, 1);
        __m512i word = _mm512_mask_i32gather_epi64(zero, lanes, index, values, 1);
        word = _mm512_mask_slli_epi64(word, left_lanes, word, 24);
        word = _mm512_mask_and_epi64(word, right_lanes, _mm512_srli_epi64(word, 24), first_texel);
        words[half] = word;
    }
    *left = _mm512_permutex2var_epi32(words[0], evens, words[1]);
    *right =
        _mm512_permutex2var_epi32(_mm512_srli_epi64(words[0], 24), evens, _mm512_srli_epi64(words[1], 24));
}

/* add_window_reads_16 for 3-channel levels at least 2 texels wide: each row's two texels by one read
   (texel_pairs_16), half the gathered values; the same values, so the same sums. */
DSN_POINT_INLINE void add_pair_reads_16(const unsigned char *values, uint32_t width, uint32_t height,
                                        uint32_t stride, __m512i s_x, __m512i s_y, __mmask16 reach,
                                        __m512i *sums) {
    const __m512i low_16 = _mm512_set1_epi32(0xFFFF), one = _mm512_set1_epi32(1);
    const __m512i right_column = _mm512_srli_epi32(s_x, 16), lower_row = _mm512_srli_epi32(s_y, 16);
    const __m512i row = _mm512_sub_epi32(lower_row, one);
    const __m512i across = _mm512_and_si512(s_x, low_16), down = _mm512_and_si512(s_y, low_16);
    /* right_column 0: the left texel is out; width: the right one; beyond: both (never in reach). */
    const __mmask16 left_out = _mm512_cmpeq_epi32_mask(right_column, _mm512_setzero_si512()),
                    right_out = _mm512_cmpeq_epi32_mask(right_column, set_16x32(width)),
                    inside = _mm512_mask_cmple_epu32_mask(reach, right_column, set_16x32(width));
    const __mmask16 top = _mm512_mask_cmple_epu32_mask(inside, row, set_16x32(height - 1u)),
                    bottom = _mm512_mask_cmple_epu32_mask(inside, lower_row, set_16x32(height - 1u));
    const __m512i first = _mm512_min_epu32(
        _mm512_max_epi32(_mm512_sub_epi32(right_column, one), _mm512_setzero_si512()), set_16x32(width - 2u));
    const __m512i entry = _mm512_add_epi32(_mm512_mullo_epi32(row, set_16x32(stride)), first);
    const __m512i at = _mm512_add_epi32(_mm512_slli_epi32(entry, 1), entry);
    const __m512i below = _mm512_add_epi32(at, set_16x32(stride * 3u));
    __m512i top_left, top_right, bottom_left, bottom_right;
    texel_pairs_16(values, at, top, left_out, right_out, &top_left, &top_right);
    texel_pairs_16(values, below, bottom, left_out, right_out, &bottom_left, &bottom_right);
    for (uint32_t c = 0; c < 3; c++)
        add_bilinear_16(lane_byte_16(top_left, c), lane_byte_16(top_right, c), lane_byte_16(bottom_left, c),
                        lane_byte_16(bottom_right, c), across, down, &sums[c]);
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
    __m512i differences[Channels][Vectors], corners[Channels][Vectors];
    __m512i last_column, last_row; /* width, height */
};

/* A channel's sums of add_register_reads_16: 64-bit lanes, and the 32-bit lanes of the terms times 2^16
   and 2^31 (the latter with 2 (A - B - D + E) where the product a d, a 32-bit signed lane, went below 0:
   its product then lacks 2^32 (A - B - D + E)), which widen_register_sums adds to the 64-bit ones before
   they could overflow. */
struct RegisterSums {
    __m512i wide, times_16, times_31;
};

/* Byte `index` of each 32-bit lane, sign-extended. */
inline __m512i signed_byte(__m512i words, uint32_t index) {
    return _mm512_srai_epi32(_mm512_sll_epi32(words, _mm_cvtsi32_si128(static_cast<int>(24u - 8u * index))),
                             24);
}

/* Two 16-bit values in a 32-bit lane, low first. */
inline __m512i pair_16(__m512i low, __m512i high) {
    return _mm512_or_si512(_mm512_and_si512(low, _mm512_set1_epi32(0xFFFF)), _mm512_slli_epi32(high, 16));
}

/* The level's texels in 32-bit lanes, texel (R - 1, C - 1) at entry 8 R + C (zero outside the window;
   one gathered read each, as the pair reads'), then each entry's 4 texels by whole-vector shifts of the
   entries (next column: + 1, next row: + 8, both: + 9). */
template <uint32_t Channels, uint32_t Vectors>
inline void register_level(const dsn_walked_level *level, RegisterLevel<Channels, Vectors> *out) {
    const __m512i zero = _mm512_setzero_si512(), one = _mm512_set1_epi32(1);
    const __m512i lanes = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    __m512i texels[Vectors + 1u];
    for (uint32_t v = 0; v < Vectors; v++) {
        const __m512i entry = _mm512_add_epi32(lanes, set_16x32(16u * v));
        const __m512i row = _mm512_sub_epi32(_mm512_srli_epi32(entry, 3), one),
                      column = _mm512_sub_epi32(_mm512_and_si512(entry, _mm512_set1_epi32(7)), one);
        const __mmask16 inside =
            _mm512_mask_cmple_epu32_mask(_mm512_cmple_epu32_mask(row, set_16x32(level->height - 1u)), column,
                                         set_16x32(level->width - 1u));
        const __m512i index = _mm512_add_epi32(_mm512_mullo_epi32(row, set_16x32(level->stride)), column);
        const __m512i at = Channels == 3 ? _mm512_add_epi32(_mm512_slli_epi32(index, 1), index) : index;
        texels[v] = _mm512_mask_i32gather_epi32(zero, inside, at, level->values, 1);
    }
    texels[Vectors] = zero;
    for (uint32_t v = 0; v < Vectors; v++) {
        const __m512i right = _mm512_alignr_epi32(texels[v + 1u], texels[v], 1),
                      below = _mm512_alignr_epi32(texels[v + 1u], texels[v], 8),
                      below_right = _mm512_alignr_epi32(texels[v + 1u], texels[v], 9);
        for (uint32_t c = 0; c < Channels; c++) {
            const __m512i a = signed_byte(texels[v], c), b = signed_byte(right, c), d = signed_byte(below, c),
                          e = signed_byte(below_right, c);
            out->differences[c][v] = pair_16(_mm512_sub_epi32(b, a), _mm512_sub_epi32(d, a));
            out->corners[c][v] = pair_16(_mm512_sub_epi32(_mm512_add_epi32(a, e), _mm512_add_epi32(b, d)),
                                         _mm512_add_epi32(b, d));
        }
    }
    out->last_column = set_16x32(level->width);
    out->last_row = set_16x32(level->height);
}

/* Entry `index` of a table of 64 (4 vectors), zero outside `inside`. */
template <uint32_t Vectors>
inline __m512i table_entry(const __m512i *table, __m512i index, const __mmask16 *part) {
    __m512i entry = _mm512_maskz_permutex2var_epi32(part[0], table[0], index, table[1]);
    for (uint32_t k = 1; k < Vectors / 2u; k++)
        entry = _mm512_or_si512(
            entry, _mm512_maskz_permutex2var_epi32(part[k], table[2u * k], index, table[2u * k + 1u]));
    return entry;
}

/* One channel's part of add_register_reads_16. */
template <uint32_t Vectors>
DSN_POINT_INLINE void add_register_channel(const __m512i *difference_table, const __m512i *corner_table,
                                           __m512i index, const __mmask16 *part, __m512i weights,
                                           __m512i product, __m512i product_odd, __mmask16 negative,
                                           RegisterSums *sums) {
    const __m512i differences = table_entry<Vectors>(difference_table, index, part),
                  corners = table_entry<Vectors>(corner_table, index, part);
    sums->times_16 = _mm512_add_epi32(sums->times_16, _mm512_madd_epi16(weights, differences));
    const __m512i cross = _mm512_srai_epi32(_mm512_slli_epi32(corners, 16), 16);
    sums->times_31 = _mm512_add_epi32(sums->times_31, _mm512_srai_epi32(corners, 16));
    sums->times_31 =
        _mm512_mask_add_epi32(sums->times_31, negative, sums->times_31, _mm512_add_epi32(cross, cross));
    sums->wide = _mm512_add_epi64(
        sums->wide, _mm512_add_epi64(_mm512_mul_epi32(product, cross),
                                     _mm512_mul_epi32(product_odd, _mm512_srli_epi64(cross, 32))));
}

/* add_pair_reads_16's reads (the same integers, so the same sums) from a level in registers. */
template <uint32_t Channels, uint32_t Vectors>
DSN_POINT_INLINE void add_register_reads_16(const RegisterLevel<Channels, Vectors> &level, __m512i s_x,
                                            __m512i s_y, __mmask16 reach, RegisterSums *sums) {
    const __m512i low_16 = _mm512_set1_epi32(0xFFFF), half = _mm512_set1_epi32(0x8000);
    const __m512i right_column = _mm512_srli_epi32(s_x, 16), lower_row = _mm512_srli_epi32(s_y, 16);
    const __m512i across = _mm512_and_si512(s_x, low_16), down = _mm512_and_si512(s_y, low_16);
    const __mmask16 inside = _mm512_mask_cmple_epu32_mask(
        _mm512_mask_cmple_epu32_mask(reach, right_column, level.last_column), lower_row, level.last_row);
    const __m512i index = _mm512_add_epi32(_mm512_slli_epi32(lower_row, 3), right_column);
    /* part k: the lanes (inside) whose entry lies in the table's k-th 32 */
    __mmask16 part[Vectors / 2u];
    const __m512i which = _mm512_srli_epi32(index, 5);
    for (uint32_t k = 0; k < Vectors / 2u; k++)
        part[k] = _mm512_mask_cmpeq_epi32_mask(inside, which, set_16x32(k));
    /* (a - 2^15, d - 2^15) as 16-bit pairs; a d, below 2^32 */
    const __m512i weights = _mm512_xor_si512(_mm512_or_si512(across, _mm512_slli_epi32(down, 16)),
                                             _mm512_or_si512(half, _mm512_slli_epi32(half, 16)));
    const __m512i product = _mm512_mullo_epi32(across, down), product_odd = _mm512_srli_epi64(product, 32);
    const __mmask16 negative = _mm512_cmplt_epi32_mask(product, _mm512_setzero_si512());
    /* the channels written out: the compiler then keeps each one's sums in registers */
    add_register_channel<Vectors>(level.differences[0], level.corners[0], index, part, weights, product,
                                  product_odd, negative, &sums[0]);
    if (Channels == 3) {
        add_register_channel<Vectors>(level.differences[1], level.corners[1], index, part, weights, product,
                                      product_odd, negative, &sums[1]);
        add_register_channel<Vectors>(level.differences[2], level.corners[2], index, part, weights, product,
                                      product_odd, negative, &sums[2]);
    }
}

/* A 32-bit lane sum times 2^shift, as two 64-bit lanes' (modulo 2^64). */
inline __m512i widened(__m512i lanes, uint32_t shift) {
    const __m128i count = _mm_cvtsi32_si128(static_cast<int>(shift));
    return _mm512_add_epi64(
        _mm512_sll_epi64(_mm512_cvtepi32_epi64(_mm512_castsi512_si256(lanes)), count),
        _mm512_sll_epi64(_mm512_cvtepi32_epi64(_mm512_extracti64x4_epi64(lanes, 1)), count));
}

/* The 32-bit sums added to the 64-bit ones and cleared: per 16 reads each grows by less than 2^25 (the
   multiply-add), so every block of packed_block reads or fewer keeps them exact. */
inline void widen_register_sums(RegisterSums *sums) {
    sums->wide = _mm512_add_epi64(sums->wide,
                                  _mm512_add_epi64(widened(sums->times_16, 16), widened(sums->times_31, 31)));
    sums->times_16 = sums->times_31 = _mm512_setzero_si512();
}
#endif

/* pack_offsets_16 for candidates first .. first + 7 of which the first `valid` exist (8 values stored). */
inline uint32_t pack_offsets_8(const int64_t *xs, const int64_t *ys, uint32_t valid, const __m256i *tests,
                               __m128i shift, uint32_t *packed_x, uint32_t *packed_y) {
    const __m256i valid_lanes = _mm256_set1_epi64x(static_cast<long long>(valid));
    __m256i reach_low = _mm256_cmpgt_epi64(valid_lanes, _mm256_setr_epi64x(0, 1, 2, 3)),
            reach_high = _mm256_cmpgt_epi64(valid_lanes, _mm256_setr_epi64x(4, 5, 6, 7));
    const bool whole = valid >= 8u;
    const __m256i s_x = low_halves(
        axis_offsets(load_64(xs, reach_low, whole), tests[0], tests[1], tests[4], shift, &reach_low),
        axis_offsets(load_64(xs + 4, reach_high, whole), tests[0], tests[1], tests[4], shift, &reach_high));
    const __m256i s_y = low_halves(
        axis_offsets(load_64(ys, reach_low, whole), tests[2], tests[3], tests[4], shift, &reach_low),
        axis_offsets(load_64(ys + 4, reach_high, whole), tests[2], tests[3], tests[4], shift, &reach_high));
    const uint32_t reach =
        static_cast<uint32_t>(_mm256_movemask_ps(_mm256_castsi256_ps(low_halves(reach_low, reach_high))));
    const uint32_t entry = packing_table[reach];
    const __m256i order = packing_order(entry);
    store_8x32(packed_x, _mm256_permutevar8x32_epi32(s_x, order));
    store_8x32(packed_y, _mm256_permutevar8x32_epi32(s_y, order));
    return entry >> 24;
}

/* a < b as unsigned 32-bit lanes (AVX2 compares signed: both flipped by 2^31). */
inline __m256i below_32(__m256i a, __m256i b) {
    const __m256i sign = set_8x32(0x80000000u);
    return _mm256_cmpgt_epi32(_mm256_xor_si256(b, sign), _mm256_xor_si256(a, sign));
}

/* The reach test of one axis on narrow offsets (kernels.h, filtered_sift.cpp's narrow_test): in reach
   when c + add < limit, the bracket's value (c + read) >> l. */
#if defined(__AVX512F__) && defined(__AVX512BW__)
inline uint32_t pack_narrow_16(const uint32_t *xs, const uint32_t *ys, __mmask16 present,
                               const __m512i *tests, __m128i shift, uint32_t *packed_x, uint32_t *packed_y) {
    const __m512i c_x = _mm512_maskz_loadu_epi32(present, xs), c_y = _mm512_maskz_loadu_epi32(present, ys);
    const __mmask16 reach = _mm512_mask_cmplt_epu32_mask(
        _mm512_mask_cmplt_epu32_mask(present, _mm512_add_epi32(c_x, tests[0]), tests[1]),
        _mm512_add_epi32(c_y, tests[3]), tests[4]);
    _mm512_storeu_si512(packed_x, _mm512_maskz_compress_epi32(
                                      reach, _mm512_srl_epi32(_mm512_add_epi32(c_x, tests[2]), shift)));
    _mm512_storeu_si512(packed_y, _mm512_maskz_compress_epi32(
                                      reach, _mm512_srl_epi32(_mm512_add_epi32(c_y, tests[5]), shift)));
    return mask_count(reach);
}
#endif

/* pack_narrow_16 for candidates first .. first + 7 of which the first `valid` exist (8 values stored). */
inline uint32_t pack_narrow_8(const uint32_t *xs, const uint32_t *ys, uint32_t valid, const __m256i *tests,
                              __m128i shift, uint32_t *packed_x, uint32_t *packed_y) {
    const __m256i present = _mm256_cmpgt_epi32(set_8x32(valid), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    const int *from_x = static_cast<const int *>(static_cast<const void *>(xs)),
              *from_y = static_cast<const int *>(static_cast<const void *>(ys));
    const __m256i c_x = valid >= 8u ? load_8x32(xs) : _mm256_maskload_epi32(from_x, present),
                  c_y = valid >= 8u ? load_8x32(ys) : _mm256_maskload_epi32(from_y, present);
    const __m256i in_x = below_32(_mm256_add_epi32(c_x, tests[0]), tests[1]),
                  in_y = below_32(_mm256_add_epi32(c_y, tests[3]), tests[4]);
    const uint32_t reach = static_cast<uint32_t>(
        _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_and_si256(present, _mm256_and_si256(in_x, in_y)))));
    const uint32_t entry = packing_table[reach];
    const __m256i order = packing_order(entry);
    store_8x32(packed_x,
               _mm256_permutevar8x32_epi32(_mm256_srl_epi32(_mm256_add_epi32(c_x, tests[2]), shift), order));
    store_8x32(packed_y,
               _mm256_permutevar8x32_epi32(_mm256_srl_epi32(_mm256_add_epi32(c_y, tests[5]), shift), order));
    return entry >> 24;
}

/* Candidates are tested and their offsets packed a block at a time, then read. */
const uint32_t packed_block = 256;

/* Vectors 4 or 6: the level's tables built (the caller checks that it fits them) and its reads taken from
   them, in copies of their own, so that the other calls (Vectors 0) neither make room for them nor clear
   their sums. */
template <uint32_t Channels, uint32_t Vectors>
void filter_level_reads_8(const dsn_walked_level *level, const int64_t *xs, const int64_t *ys,
                          const uint32_t *narrow_xs, const uint32_t *narrow_ys, uint32_t count,
                          const uint64_t *tests, const uint32_t *narrow_tests, uint64_t *out) {
    const __m256i bias = _mm256_set1_epi64x(static_cast<long long>(static_cast<uint64_t>(1) << level->level));
    const __m256i offset_tests_8[5] = {_mm256_set1_epi64x(static_cast<long long>(tests[0])),
                                       _mm256_set1_epi64x(static_cast<long long>(tests[1])),
                                       _mm256_set1_epi64x(static_cast<long long>(tests[2])),
                                       _mm256_set1_epi64x(static_cast<long long>(tests[3])), bias};
    const __m128i shift = _mm_cvtsi32_si128(static_cast<int>(level->level + 16u));
    const __m256i zero = _mm256_setzero_si256();
    __m256i sums[Channels];
    for (uint32_t c = 0; c < Channels; c++) sums[c] = zero;
#if defined(__AVX512F__) && defined(__AVX512BW__)
    const __m512i wide_tests[5] = {
        _mm512_set1_epi64(static_cast<long long>(tests[0])),
        _mm512_set1_epi64(static_cast<long long>(tests[1])),
        _mm512_set1_epi64(static_cast<long long>(tests[2])),
        _mm512_set1_epi64(static_cast<long long>(tests[3])),
        _mm512_set1_epi64(static_cast<long long>(static_cast<uint64_t>(1) << level->level))};
    __m512i wide_sums[Channels];
    for (uint32_t c = 0; c < Channels; c++) wide_sums[c] = _mm512_setzero_si512();
#endif
    __m256i narrow_tests_8[6];
    for (uint32_t i = 0; i < 6; i++) narrow_tests_8[i] = set_8x32(narrow_tests[i]);
    const __m128i narrow_shift = _mm_cvtsi32_si128(static_cast<int>(level->level));
#if defined(__AVX512F__) && defined(__AVX512BW__)
    __m512i narrow_tests_16[6];
    for (uint32_t i = 0; i < 6; i++) narrow_tests_16[i] = set_16x32(narrow_tests[i]);
#endif
#if defined(__AVX512F__) && defined(__AVX512BW__)
    const bool in_registers = Vectors != 0;
    RegisterLevel<Channels, Vectors == 0 ? 4u : Vectors> registers;
    RegisterSums register_sums[Channels];
    for (uint32_t c = 0; c < Channels; c++)
        register_sums[c].wide = register_sums[c].times_16 = register_sums[c].times_31 =
            _mm512_setzero_si512();
    if (in_registers) register_level<Channels, Vectors == 0 ? 4u : Vectors>(level, &registers);
#endif
    uint32_t packed_x[packed_block + 16], packed_y[packed_block + 16];
    for (uint32_t block = 0; block < count; block += packed_block) {
        const uint32_t end = count - block < packed_block ? count : block + packed_block;
        uint32_t packed = 0, first = block;
        if (narrow_xs != 0) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
            for (; first < end; first += 16u) {
                const __mmask16 present =
                    static_cast<__mmask16>(end - first >= 16u ? 0xFFFFu : (1u << (end - first)) - 1u);
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
                const __mmask16 reach = static_cast<__mmask16>(left >= 16u ? 0xFFFFu : (1u << left) - 1u);
                add_register_reads_16<Channels, Vectors == 0 ? 4u : Vectors>(
                    registers, _mm512_loadu_si512(packed_x + next), _mm512_loadu_si512(packed_y + next),
                    reach, register_sums);
            }
            for (uint32_t c = 0; c < Channels; c++) widen_register_sums(&register_sums[c]);
        }
        for (; next + 8u < packed; next += 16u) {
            const uint32_t left = packed - next;
            const __mmask16 reach = static_cast<__mmask16>(left >= 16u ? 0xFFFFu : (1u << left) - 1u);
            const __m512i s_x = _mm512_loadu_si512(packed_x + next),
                          s_y = _mm512_loadu_si512(packed_y + next);
            if (Channels == 3 && level->width >= 2)
                add_pair_reads_16(level->values, level->width, level->height, level->stride, s_x, s_y, reach,
                                  wide_sums);
            else
                add_window_reads_16<Channels>(level->values, level->width, level->height, level->stride, s_x,
                                              s_y, reach, wide_sums);
        }
#endif
        for (; next < packed; next += 8u) {
            const __m256i reach =
                _mm256_cmpgt_epi32(set_8x32(packed - next), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
            add_window_reads_8<Channels>(level->values, level->width, level->height, level->stride,
                                         load_8x32(packed_x + next), load_8x32(packed_y + next), reach, sums);
        }
    }
#if defined(__AVX512F__) && defined(__AVX512BW__)
    if (in_registers)
        for (uint32_t c = 0; c < Channels; c++)
            wide_sums[c] = _mm512_add_epi64(wide_sums[c], register_sums[c].wide);
    for (uint32_t c = 0; c < Channels; c++) /* the 64-bit lanes' sums folded into 4 lanes */
        sums[c] = _mm256_add_epi64(sums[c], _mm256_add_epi64(_mm512_castsi512_si256(wide_sums[c]),
                                                             _mm512_extracti64x4_epi64(wide_sums[c], 1)));
#endif
    for (uint32_t c = 0; c < Channels; c++) {
        uint64_t lanes[4];
        _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(lanes)), sums[c]);
        out[c] += lanes[0] + lanes[1] + lanes[2] + lanes[3];
    }
}

/* kernels.h's filter_level_reads. */
void filter_level_reads(const dsn_walked_level *level, uint32_t channels, const int64_t *xs,
                        const int64_t *ys, const uint32_t *narrow_xs, const uint32_t *narrow_ys,
                        uint32_t count, const uint64_t *tests, const uint32_t *narrow_tests, uint64_t *out) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
    /* the tables cost as much to build as the reads they spare on a few dozen candidates */
    if (level->width <= register_level_side && level->height <= register_level_tallest &&
        count >= register_level_least) {
        const bool tall = level->height > register_level_side;
        if (channels == 3 && tall)
            filter_level_reads_8<3, 6>(level, xs, ys, narrow_xs, narrow_ys, count, tests, narrow_tests, out);
        else if (channels == 3)
            filter_level_reads_8<3, 4>(level, xs, ys, narrow_xs, narrow_ys, count, tests, narrow_tests, out);
        else if (tall)
            filter_level_reads_8<1, 6>(level, xs, ys, narrow_xs, narrow_ys, count, tests, narrow_tests, out);
        else
            filter_level_reads_8<1, 4>(level, xs, ys, narrow_xs, narrow_ys, count, tests, narrow_tests, out);
        return;
    }
#endif
    if (channels == 3)
        filter_level_reads_8<3, 0>(level, xs, ys, narrow_xs, narrow_ys, count, tests, narrow_tests, out);
    else
        filter_level_reads_8<1, 0>(level, xs, ys, narrow_xs, narrow_ys, count, tests, narrow_tests, out);
}

} // namespace
/* The kernel entry (kernels.h): null where there is none. */
#define DSN_FILTER_READS_ENTRY filter_level_reads
#else
#define DSN_FILTER_READS_ENTRY 0
#endif

#endif /* DSN_FILTERED_READS_VECTOR_H */
