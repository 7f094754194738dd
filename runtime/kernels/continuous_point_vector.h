/* runtime/kernels/continuous_point_vector.h - the continuous mode at one point on AVX2 or AVX-512 vectors, as
   a kernel (kernels.h: the AVX2 and AVX-512 kernels include it), for 8-bit textons and cells of side <= 16
   (pairs of 8 impulses). The cells are walked and their pairs sifted as by continuous_point.cpp's
   evaluator (continuous_sift.h), the keys and counts of all the cells first; each pair's candidates are
   packed into arrays, their cell by its column and row index (AVX-512: a cell's first two pairs at once,
   compressed), then visited 8 (AVX-512: 16)
   at a time: the fraction hash, the 16-bit positions, the exact reach test and the bilinear texton, all
   in 32-bit lanes (64-bit for the column's interpolation), the texels gathered straight from the texton,
   each where it lies inside the window (no branch at the window's edge; AVX-512: both texels of a row by
   one 8-byte read). The same impulses, offsets, weights and integers as the evaluator, so the same bits.
   The gradient's sums (the value and both slopes, continuous_internal.h) take the same walk with the
   entry edge in its sifting, the texels read as the value's (AVX-512: 16 candidates at a time), the
   slopes summed beside the values. Internal to libdsn; not installed (everything here has internal
   linkage). */
#ifndef DSN_CONTINUOUS_POINT_VECTOR_H
#define DSN_CONTINUOUS_POINT_VECTOR_H

#include "core/continuous_internal.h"
#include "core/continuous_sift.h"
#include "kernels/continuous_lanes.h"
#include "kernels/mix_pick_lanes.h"

namespace {
/* The noises the vector evaluator takes (continuous_batch.cpp asks too, built without AVX2): 8-bit
   textons, cells of side <= 16 (pairs of 8 impulses), radii below 2^12. */
inline bool point_vector_takes(const dsn_noise_state *noise) {
    return noise->asset.bits == 8 && dsn_field_shift(noise->cell_shift) == 3 && noise->radius[0] < 4096u &&
           noise->radius[1] < 4096u;
}
} // namespace

#if defined(__AVX2__) && !DSN_SMALL_CODE /* the small build evaluates point by point */
/* Forced into the walk (the compiler left them out of line, measurably slower). */
#if defined(__GNUC__)
#define DSN_POINT_INLINE inline __attribute__((always_inline))
#else
#define DSN_POINT_INLINE inline
#endif

namespace {

/* The offsets in 32-bit lanes. Write S = floor(shifted / 2^16) for bracket's shifted value (CellAxis's
   shifted_base less b 2^(16 + shift) for the 16-bit position b): S = floor(shifted_base / 2^16) - b 2^shift
   exactly, as b 2^(16 + shift) is a multiple of 2^16. The lower index is (S >> 16) - 1 and the weight
   S & bilinear_weight_mask. bracket keeps 0 < shifted < (2 radius + 2) 2^32, that is 0 <= S <= (2 radius + 2)
   2^16 - 1 except shifted = 0 (S = 0 with low bits zero), which the test below keeps too: its texels are
   those of rows -1 and 0 with weight 0 on row 0, so it adds exactly zero. For a cell that passes cell_axis,
   0 < shifted_base < (2 radius + 2) 2^32 + 2^(32 + shift), so S lies within (-2^20, 2^30) for the radii
   taken (continuous_point_vector). */
const uint32_t point_vector_slots = 64; /* candidates visited at once (a usual point has about 35) */
const uint32_t point_vector_cells = 8;  /* cells of a point along each axis, at most (a usual point has 3) */

#if defined(__AVX512F__) && defined(__AVX512BW__)
const uint32_t point_vector_lanes = 16; /* candidates per visit: 512-bit vectors (the last 8 or fewer: 256) */
#else
const uint32_t point_vector_lanes = 8;
#endif

/* The packed candidates: fraction hash input, and the 8-bit field with the cell's column i and row j
   among the point's cells (AxisCells) above it: field | i << 8 | j << 11. The slots past the end take
   the last pair's store and the padding. */
struct PointCandidates {
    uint32_t stream[point_vector_slots + 16], field[point_vector_slots + 16];
    uint32_t count;
};

/* A candidate's column and row index above its field (PointCandidates). */
inline uint32_t cell_indices(uint32_t i, uint32_t j) { return i << 8 | j << 11; }

/* a <= limit as unsigned 32-bit lanes. */
inline vector_256 at_most(vector_256 a, vector_256 limit) {
    return equal_32(minimum_unsigned_32(a, limit), a);
}

/* What the visits of one point share, and its sums (64-bit lanes per channel). */
template <uint32_t Channels>
struct PointVisit {
    const unsigned char *texton;
    /* The batch's 2 x 2 texel table of the bordered texton (continuous_batch.h's quads; null per point):
       one read per channel, no test at the window's edge. */
    const uint32_t *quads;
    uint32_t width, height;
    uint32_t quad_row;       /* quads per row of the table: (width + 1) Channels */
    uint32_t last_x, last_y; /* the largest S in reach */
    vector_128 shift;
    /* floor(shifted_base / 2^16) of the point's column and row cells (AxisCells's base) */
    vector_256 column_bases, row_bases;
    vector_256 sums[Channels];
#if defined(__AVX512F__) && defined(__AVX512BW__)
    vector_512 wide_sums[Channels];
#endif
};

/* Byte `index` of every 32-bit lane, sign-extended. */
inline vector_256 lane_byte(vector_256 words, int index) {
    return shift_right_arithmetic_32(shift_left_32_by(words, shift_count(24 - 8 * index)), 24);
}

/* The bilinear reads of 8 candidates in reach (`reach`) of a window of width x height 8-bit texels,
   `stride` texels a row, added to sums (64-bit lanes, one per channel): bracket's floor(shifted / 2^16)
   of each axis in 32-bit lanes, the lower index (S >> 16) - 1 and the weight S & bilinear_weight_mask. Each
   texel is read where it lies inside the window (index -1, 0xFFFFFFFF, fails the tests) and is zero
   elsewhere, as add_bilinear's, without a branch: one gather per texel column and row, 4 bytes from each
   texel (its channels first). Reads reach at most 3 bytes past the window's last texel: into the asset's
   4-byte CRC (format.h: total_size), which the loader guarantees lies in the buffer after the texton and the
   pyramid. `moved` adds a byte offset per lane: a mixed point's lane reads its own material's texton
   (MixedVisit), whose asset's CRC follows it alike. */
struct WindowTexels {
    vector_256 top_left, top_right, bottom_left, bottom_right; /* 4 bytes each, channels first */
    vector_256 across, down;
};

template <uint32_t Channels>
DSN_POINT_INLINE void window_texels_8(const unsigned char *values, uint32_t width, uint32_t height,
                                      uint32_t stride, vector_256 s_x, vector_256 s_y, vector_256 reach,
                                      WindowTexels *texels, vector_256 moved = zero_256()) {
    const vector_256 weight_bits = set_8x32(bilinear_weight_mask), one = set_8x32(1);
    const vector_256 column = subtract_32(shift_right_logical_32(s_x, 16), one),
                     row = subtract_32(shift_right_logical_32(s_y, 16), one);
    texels->across = bitwise_and(s_x, weight_bits), texels->down = bitwise_and(s_y, weight_bits);
    const vector_256 last_column = set_8x32(width - 1u), last_row = set_8x32(height - 1u);
    const vector_256 left = at_most(column, last_column), right = at_most(add_32(column, one), last_column);
    const vector_256 top = bitwise_and(reach, at_most(row, last_row)),
                     bottom = bitwise_and(reach, at_most(add_32(row, one), last_row));
    /* Byte offset of the top-left texel (unread where it is outside). */
    const vector_256 entry = add_32(multiply_32(row, set_8x32(stride)), column);
    const vector_256 at = add_32(Channels == 3 ? add_32(shift_left_32(entry, 1), entry) : entry, moved);
    const vector_256 below = add_32(at, set_8x32(stride * Channels));
    const unsigned char *next = values + Channels;
    texels->top_left = gather_masked_32<1>(values, at, bitwise_and(top, left));
    texels->top_right = gather_masked_32<1>(next, at, bitwise_and(top, right));
    texels->bottom_left = gather_masked_32<1>(values, below, bitwise_and(bottom, left));
    texels->bottom_right = gather_masked_32<1>(next, below, bitwise_and(bottom, right));
}

/* bilinear_texton.h's add_slopes of reads with texels a, b (upper row), d, e (lower row), sign-extended
   8-bit values in 32-bit lanes: along x (65536 - down) (b - a) + down (e - d), along y
   (65536 - across) (d - a) + across (e - b), written with one product each around the cross difference
   a - b - d + e (the same integers: each below 2^24 in magnitude, every step below 2^26), added to the
   32-bit lanes slope_x and slope_y, which the caller widens before 2^7 reads could overflow a lane. */
template <typename Vector>
DSN_POINT_INLINE void add_slope_lanes(Vector a, Vector b, Vector d, Vector e, Vector across, Vector down,
                                      Vector *slope_x, Vector *slope_y) {
    const Vector cross = add_32(subtract_32(a, b), subtract_32(e, d));
    *slope_x = add_32(*slope_x, add_32(shift_left_32(subtract_32(b, a), 16), multiply_32(down, cross)));
    *slope_y = add_32(*slope_y, add_32(shift_left_32(subtract_32(d, a), 16), multiply_32(across, cross)));
}

/* With Slopes, each read's slopes added to slope_x[c] and slope_y[c] too (add_slope_lanes). */
template <uint32_t Channels, bool Slopes = false>
DSN_POINT_INLINE void add_window_reads_8(const unsigned char *values, uint32_t width, uint32_t height,
                                         uint32_t stride, vector_256 s_x, vector_256 s_y, vector_256 reach,
                                         vector_256 *sums, vector_256 *slope_x = 0, vector_256 *slope_y = 0) {
    WindowTexels texels;
    window_texels_8<Channels>(values, width, height, stride, s_x, s_y, reach, &texels);
    for (uint32_t c = 0; c < Channels; c++) {
        const int byte = static_cast<int>(c);
        const vector_256 a = lane_byte(texels.top_left, byte), b = lane_byte(texels.top_right, byte),
                         d = lane_byte(texels.bottom_left, byte), e = lane_byte(texels.bottom_right, byte);
        vector_256 even, odd;
        bilinear_8(a, b, d, e, texels.across, texels.down, &even, &odd);
        sums[c] = add_64(sums[c], add_64(even, odd));
        if (Slopes) add_slope_lanes(a, b, d, e, texels.across, texels.down, &slope_x[c], &slope_y[c]);
    }
}

/* The multipliers of a quad's index (S_y >> 16) quad_row + (S_x >> 16) Channels as 16-bit halves, for
   a product-sum of the 16-bit halves (S_x >> 16, S_y >> 16) of each lane: in reach, S >> 16 is at most
   2 radius + 1 < 2^13, and quad_row = (width + 1) Channels <= (2 radius + 3) 3 < 2^15 (the radii the
   vector evaluator takes), so that every factor is a non-negative int16 and the index an int32. */
inline uint32_t quad_index_factors(uint32_t quad_row, uint32_t channels) { return quad_row << 16 | channels; }

/* add_window_reads_8 from the quad table: the bordered position of the top-left texel is the lower index
   plus 1, (S >> 16) along each axis; a lane out of reach reads nothing and adds zero. */
template <uint32_t Channels>
DSN_POINT_INLINE void add_quad_reads_8(const uint32_t *quads, uint32_t quad_row, vector_256 s_x,
                                       vector_256 s_y, vector_256 reach, vector_256 *sums) {
    const vector_256 weight_bits = set_8x32(bilinear_weight_mask);
    const vector_256 across = bitwise_and(s_x, weight_bits), down = bitwise_and(s_y, weight_bits);
    const vector_256 at = madd_16(blend_odd_16(shift_right_logical_32(s_x, 16), s_y),
                                  set_8x32(quad_index_factors(quad_row, Channels)));
    for (uint32_t c = 0; c < Channels; c++) {
        const vector_256 quad = gather_masked_32<4>(quads + c, at, reach);
        vector_256 even, odd;
        bilinear_8(lane_byte(quad, 0), lane_byte(quad, 1), lane_byte(quad, 2), lane_byte(quad, 3), across,
                   down, &even, &odd);
        sums[c] = add_64(sums[c], add_64(even, odd));
    }
}

/* The offsets S (bracket's floor(shifted / 2^16)) of candidates first .. first + 7, of which the first
   `valid` exist; returns the lanes in reach. */
template <uint32_t Channels>
DSN_POINT_INLINE vector_256 candidate_offsets_8(const PointVisit<Channels> *visit,
                                                const PointCandidates &candidates, uint32_t first,
                                                uint32_t valid, vector_256 *offset_x, vector_256 *offset_y) {
    const vector_256 fraction = mix32_lanes(load_8x32(candidates.stream + first)),
                     packed = load_8x32(candidates.field + first);
    vector_256 bits_x, bits_y;
    impulse_bits_8(bitwise_and(packed, set_8x32(0xFF)), fraction, &bits_x, &bits_y);
    /* the cells' bases by their indices (the permutes read the low 3 bits) */
    const vector_256 base_x = permute_32(visit->column_bases, shift_right_logical_32(packed, 8)),
                     base_y = permute_32(visit->row_bases, shift_right_logical_32(packed, 11));
    const vector_256 s_x = subtract_32(base_x, shift_left_32_by(bits_x, visit->shift));
    const vector_256 s_y = subtract_32(base_y, shift_left_32_by(bits_y, visit->shift));
    const vector_256 exists = greater_32(set_8x32(valid), set_lanes_8x32(0, 1, 2, 3, 4, 5, 6, 7));
    *offset_x = s_x, *offset_y = s_y;
    return bitwise_and(
        exists, bitwise_and(at_most(s_x, set_8x32(visit->last_x)), at_most(s_y, set_8x32(visit->last_y))));
}

/* Candidates first .. first + 7 of which the first `valid` exist. */
template <uint32_t Channels>
inline void visit_point_8(PointVisit<Channels> *visit, const PointCandidates &candidates, uint32_t first,
                          uint32_t valid) {
    vector_256 s_x, s_y;
    const vector_256 reach = candidate_offsets_8(visit, candidates, first, valid, &s_x, &s_y);
    if (visit->quads != 0)
        add_quad_reads_8<Channels>(visit->quads, visit->quad_row, s_x, s_y, reach, visit->sums);
    else
        add_window_reads_8<Channels>(visit->texton, visit->width, visit->height, visit->width, s_x, s_y,
                                     reach, visit->sums);
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* visit_point_8 on 512-bit vectors: candidates first .. first + 15 of which the first `valid` exist. */
inline vector_512 lane_byte_16(vector_512 words, unsigned int index) {
    return shift_right_arithmetic_32(shift_left_32(words, 24 - 8 * index), 24);
}

/* impulse_bits_8 on 16 lanes. */
inline void impulse_bits_16(vector_512 fields, vector_512 fraction, vector_512 *bits_x, vector_512 *bits_y) {
    *bits_x = bitwise_or(shift_left_32(bitwise_and(fields, set_16x32(15)), 12),
                         shift_right_logical_32(bitwise_and(fraction, set_16x32(0xFFFF)), 4));
    *bits_y = bitwise_or(shift_left_32(shift_right_logical_32(fields, 4), 12),
                         shift_right_logical_32(fraction, 20));
}

/* candidate_lanes of two pairs of 8-bit fields at once in one 128-bit vector (the first pair low), their
   top bits gathered by one movemask: bit i for impulse i of the first pair, 8 + i of the second. */
inline uint32_t sift_two_pairs(vector_128 pairs, const FieldLanes &lanes, const CellAxis &x,
                               const CellAxis &y) {
    const vector_128 halves = set_2x64(static_cast<int64_t>(lanes.halves)),
                     tops = set_2x64(static_cast<int64_t>(lanes.tops));
    const vector_128 halves_x = bitwise_and(pairs, halves),
                     halves_y = bitwise_and(shift_right_logical_64(pairs, 4), halves);
    const vector_128 in_x =
        bitwise_and(subtract_64(bitwise_or(halves_x, tops), set_2x64(static_cast<int64_t>(x.low_lanes))),
                    subtract_64(set_2x64(static_cast<int64_t>(x.high_lanes)), halves_x));
    const vector_128 in_y =
        bitwise_and(subtract_64(bitwise_or(halves_y, tops), set_2x64(static_cast<int64_t>(y.low_lanes))),
                    subtract_64(set_2x64(static_cast<int64_t>(y.high_lanes)), halves_y));
    return static_cast<uint32_t>(top_bits_of_bytes(bitwise_and(in_x, in_y)));
}

/* bilinear_8 on 16 lanes, the 16 values added to sum's 64-bit lanes. */
/* The rows' interpolations upper and lower (32-bit lanes) interpolated down the column: the even lanes'
   values in even's 64-bit lanes, the odd lanes' in odd's. */
DSN_POINT_INLINE void column_16(vector_512 upper, vector_512 lower, vector_512 down, vector_512 *even,
                                vector_512 *odd) {
    const vector_512 scale = set_16x32(65536);
    const vector_512 difference = subtract_32(lower, upper);
    *even = add_64(multiply_even_32(upper, scale), multiply_even_32(down, difference));
    *odd = add_64(multiply_even_32(shift_right_logical_64(upper, 32), scale),
                  multiply_even_32(shift_right_logical_64(down, 32), shift_right_logical_64(difference, 32)));
}

DSN_POINT_INLINE void add_column_16(vector_512 upper, vector_512 lower, vector_512 down, vector_512 *sum) {
    vector_512 even, odd;
    column_16(upper, lower, down, &even, &odd);
    *sum = add_64(*sum, add_64(even, odd));
}

DSN_POINT_INLINE void bilinear_16(vector_512 a, vector_512 b, vector_512 d, vector_512 e, vector_512 across,
                                  vector_512 down, vector_512 *even, vector_512 *odd) {
    column_16(add_32(shift_left_32(a, 16), multiply_32(across, subtract_32(b, a))),
              add_32(shift_left_32(d, 16), multiply_32(across, subtract_32(e, d))), down, even, odd);
}

DSN_POINT_INLINE void add_bilinear_16(vector_512 a, vector_512 b, vector_512 d, vector_512 e,
                                      vector_512 across, vector_512 down, vector_512 *sum) {
    add_column_16(add_32(shift_left_32(a, 16), multiply_32(across, subtract_32(b, a))),
                  add_32(shift_left_32(d, 16), multiply_32(across, subtract_32(e, d))), down, sum);
}

/* add_bilinear_16 of quads (bytes a, b, d, e), the bytes taken and the rows' steps made in 16-bit halves:
   a and d, b and e sign-extended, then b - a and e - d (within int16). */
DSN_POINT_INLINE void add_quad_bilinear_16(vector_512 quad, vector_512 across, vector_512 down,
                                           vector_512 *sum) {
    const vector_512 left = shift_right_arithmetic_16<8>(shift_left_16<8>(quad)),
                     right = shift_right_arithmetic_16<8>(quad);
    const vector_512 step = subtract_16(right, left);
    const vector_512 upper = add_32(
        shift_left_32(left, 16), multiply_32(across, shift_right_arithmetic_32(shift_left_32(step, 16), 16)));
    const vector_512 lower = add_32(bitwise_and(left, set_16x32(0xFFFF0000u)),
                                    multiply_32(across, shift_right_arithmetic_32(step, 16)));
    add_column_16(upper, lower, down, sum);
}

/* add_quad_reads_8 on 16 lanes; 3 channels: channels 0 and 1 by 8-byte reads, 8 lanes a gather, the
   words' halves taken by permutes, and channel 2 by one gather of 16 words. */
template <uint32_t Channels>
DSN_POINT_INLINE void add_quad_reads_16(const uint32_t *quads, uint32_t quad_row, vector_512 s_x,
                                        vector_512 s_y, mask_16 reach, vector_512 *sums) {
    const vector_512 weight_bits = set_16x32(bilinear_weight_mask);
    const vector_512 across = bitwise_and(s_x, weight_bits), down = bitwise_and(s_y, weight_bits);
    const vector_512 at = madd_16(blend_odd_16(shift_right_logical_32(s_x, 16), s_y),
                                  set_16x32(quad_index_factors(quad_row, Channels)));
    vector_512 quad[Channels];
    if (Channels == 3) {
        const vector_512 lows = set_lanes_16x32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30),
                         highs = set_lanes_16x32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
        /* channels 0 and 1 of candidates 0 .. 7 and 8 .. 15 */
        const vector_512 low_words = gather_masked_64<4>(quads, low_256(at), static_cast<mask_8>(reach));
        const vector_512 high_words =
            gather_masked_64<4>(quads, high_256(at), static_cast<mask_8>(reach >> 8));
        quad[Channels - 1] = gather_masked_32<4>(quads + 2, at, reach);
        quad[0] = permute_32_of_two(low_words, lows, high_words);
        quad[Channels - 2] = permute_32_of_two(low_words, highs, high_words);
    } else {
        quad[0] = gather_masked_32<4>(quads, at, reach);
    }
    for (uint32_t c = 0; c < Channels; c++) add_quad_bilinear_16(quad[c], across, down, &sums[c]);
}

/* add_window_reads_8 on 512-bit vectors: 16 candidates, those of `reach`. */
template <uint32_t Channels, bool Slopes = false>
DSN_POINT_INLINE void add_window_reads_16(const unsigned char *values, uint32_t width, uint32_t height,
                                          uint32_t stride, vector_512 s_x, vector_512 s_y, mask_16 reach,
                                          vector_512 *sums, vector_512 *slope_x = 0,
                                          vector_512 *slope_y = 0) {
    const vector_512 weight_bits = set_16x32(bilinear_weight_mask);
    /* the texton indices of the right column and the lower row, and of the left column and upper row */
    const vector_512 right_column = shift_right_logical_32(s_x, 16),
                     lower_row = shift_right_logical_32(s_y, 16);
    const vector_512 column = subtract_32(right_column, set_16x32(1)),
                     row = subtract_32(lower_row, set_16x32(1));
    const vector_512 across = bitwise_and(s_x, weight_bits), down = bitwise_and(s_y, weight_bits);
    const vector_512 last_column = set_16x32(width - 1u), last_row = set_16x32(height - 1u);
    const mask_16 left = less_equal_unsigned_32(column, last_column),
                  right = less_equal_unsigned_32(right_column, last_column);
    const mask_16 top = less_equal_unsigned_32(reach, row, last_row),
                  bottom = less_equal_unsigned_32(reach, lower_row, last_row);
    const vector_512 entry = add_32(multiply_32(row, set_16x32(stride)), column);
    const vector_512 at = Channels == 3 ? add_32(shift_left_32(entry, 1), entry) : entry;
    const vector_512 below = add_32(at, set_16x32(stride * Channels));
    const unsigned char *next = values + Channels;
    const vector_512 top_left = gather_masked_32<1>(values, at, top & left),
                     top_right = gather_masked_32<1>(next, at, top & right),
                     bottom_left = gather_masked_32<1>(values, below, bottom & left),
                     bottom_right = gather_masked_32<1>(next, below, bottom & right);
    for (uint32_t c = 0; c < Channels; c++) {
        const vector_512 a = lane_byte_16(top_left, c), b = lane_byte_16(top_right, c),
                         d = lane_byte_16(bottom_left, c), e = lane_byte_16(bottom_right, c);
        add_bilinear_16(a, b, d, e, across, down, &sums[c]);
        if (Slopes) add_slope_lanes(a, b, d, e, across, down, &slope_x[c], &slope_y[c]);
    }
}

/* add_window_reads_16 on the whole texton (the per-point visit's window): each row's two texels by one
   8-byte read from 4 bytes before the right texel, 8 lanes a gather, half the values gathered. The left
   texel's channels end at byte 3 of the read and the right one's start at byte 4: the gathered words'
   low and high halves, each zeroed where its texel is outside. The reads reach at most 4 bytes before
   the texton and 4 past it: into the asset's header (format.h: header_size >= 128) and 4-byte CRC, in the
   buffer that the loader checked (asset.cpp sets the texton there only). texton_pairs_16 reads the
   texels (top left, top right, bottom left, bottom right: the left ones' channels end at byte 3 of a
   lane, the right ones' start at byte 0) and the weights, add_texton_pairs_16 adds their values. */
struct TextonTexels16 {
    vector_512 texel[4];
    vector_512 across, down;
};

template <uint32_t Channels>
DSN_POINT_INLINE void texton_pairs_16(const unsigned char *texton, uint32_t width, uint32_t height,
                                      vector_512 s_x, vector_512 s_y, mask_16 reach, TextonTexels16 *texels,
                                      vector_512 moved = zero_512()) {
    const vector_512 weight_bits = set_16x32(bilinear_weight_mask), one = set_16x32(1);
    const vector_512 right_column = shift_right_logical_32(s_x, 16),
                     lower_row = shift_right_logical_32(s_y, 16);
    const vector_512 row = subtract_32(lower_row, one);
    texels->across = bitwise_and(s_x, weight_bits), texels->down = bitwise_and(s_y, weight_bits);
    const vector_512 last_column = set_16x32(width - 1u), last_row = set_16x32(height - 1u);
    const mask_16 left = less_equal_unsigned_32(subtract_32(right_column, one), last_column),
                  right = less_equal_unsigned_32(right_column, last_column);
    /* a row is read where one of its texels is inside */
    const mask_16 top = less_equal_unsigned_32(reach & (left | right), row, last_row),
                  bottom = less_equal_unsigned_32(reach & (left | right), lower_row, last_row);
    const vector_512 entry = add_32(multiply_32(row, set_16x32(width)), right_column);
    const vector_512 at = add_32(
        subtract_32(Channels == 3 ? add_32(shift_left_32(entry, 1), entry) : entry, set_16x32(4)), moved);
    const vector_512 below = add_32(at, set_16x32(width * Channels));
    const vector_512 lows = set_lanes_16x32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30),
                     highs = set_lanes_16x32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
    for (uint32_t pass = 0; pass < 2; pass++) {
        const mask_16 rows = pass == 0 ? top : bottom;
        const vector_512 from = pass == 0 ? at : below;
        const vector_512 first = gather_masked_64<1>(texton, low_256(from), static_cast<mask_8>(rows)),
                         second = gather_masked_64<1>(texton, high_256(from), static_cast<mask_8>(rows >> 8));
        texels->texel[2 * pass] = permute_32_of_two_or_zero(left, first, lows, second);
        texels->texel[2 * pass + 1] = permute_32_of_two_or_zero(right, first, highs, second);
    }
}

template <uint32_t Channels>
DSN_POINT_INLINE void add_texton_pairs_16(const unsigned char *texton, uint32_t width, uint32_t height,
                                          vector_512 s_x, vector_512 s_y, mask_16 reach, vector_512 *sums) {
    TextonTexels16 texels;
    texton_pairs_16<Channels>(texton, width, height, s_x, s_y, reach, &texels);
    for (uint32_t c = 0; c < Channels; c++)
        add_bilinear_16(lane_byte_16(texels.texel[0], 4u - Channels + c), lane_byte_16(texels.texel[1], c),
                        lane_byte_16(texels.texel[2], 4u - Channels + c), lane_byte_16(texels.texel[3], c),
                        texels.across, texels.down, &sums[c]);
}

/* candidate_offsets_8 on 16 lanes: candidates first .. first + 15 of which the first `valid` exist. */
template <uint32_t Channels>
DSN_POINT_INLINE mask_16 candidate_offsets_16(const PointVisit<Channels> *visit,
                                              const PointCandidates &candidates, uint32_t first,
                                              uint32_t valid, vector_512 *offset_x, vector_512 *offset_y) {
    const vector_512 fraction = mix32_lanes(load_16x32(candidates.stream + first));
    const vector_512 packed = load_16x32(candidates.field + first);
    /* impulse_bits_16, each axis's field bits selected into bits 12 .. 15 */
    const vector_512 field_bits = set_16x32(0xF000);
    const vector_512 bits_x = masked_or(shift_left_32(packed, 12),
                                        shift_right_logical_32(shift_left_32(fraction, 16), 20), field_bits);
    const vector_512 bits_y =
        masked_or(shift_left_32(packed, 8), shift_right_logical_32(fraction, 20), field_bits);
    /* the cells' bases by their indices (the permutes read the low 4 bits: the bases twice) */
    const vector_512 column_bases = broadcast_256(visit->column_bases),
                     row_bases = broadcast_256(visit->row_bases);
    const vector_512 base_x = permute_32(column_bases, shift_right_logical_32(packed, 8)),
                     base_y = permute_32(row_bases, shift_right_logical_32(packed, 11));
    const vector_512 s_x = subtract_32(base_x, shift_left_32_by(bits_x, visit->shift));
    const vector_512 s_y = subtract_32(base_y, shift_left_32_by(bits_y, visit->shift));
    const mask_16 exists = static_cast<mask_16>(valid >= 16u ? 0xFFFFu : (1u << valid) - 1u);
    *offset_x = s_x, *offset_y = s_y;
    return less_equal_unsigned_32(less_equal_unsigned_32(exists, s_x, set_16x32(visit->last_x)), s_y,
                                  set_16x32(visit->last_y));
}

template <uint32_t Channels>
DSN_POINT_INLINE void visit_point_16(PointVisit<Channels> *visit, const PointCandidates &candidates,
                                     uint32_t first, uint32_t valid) {
    vector_512 s_x, s_y;
    const mask_16 reach = candidate_offsets_16(visit, candidates, first, valid, &s_x, &s_y);
    if (visit->quads != 0)
        add_quad_reads_16<Channels>(visit->quads, visit->quad_row, s_x, s_y, reach, visit->wide_sums);
    else
        add_texton_pairs_16<Channels>(visit->texton, visit->width, visit->height, s_x, s_y, reach,
                                      visit->wide_sums);
}
#endif

/* The lanes past the last candidate set to zeros (defined values; the count leaves them out). */
inline void clear_past_candidates(PointCandidates *candidates) {
    const uint32_t count = candidates->count;
    const vector_256 zero = zero_256();
    for (uint32_t pad = count; pad < count + point_vector_lanes; pad += 8u) {
        store_8x32(candidates->stream + pad, zero), store_8x32(candidates->field + pad, zero);
    }
}

/* Visits the buffered candidates and empties the buffer. */
template <uint32_t Channels>
inline void visit_point_candidates(PointVisit<Channels> *visit, PointCandidates *candidates) {
    const uint32_t count = candidates->count;
    clear_past_candidates(candidates);
    uint32_t first = 0;
#if defined(__AVX512F__) && defined(__AVX512BW__)
    for (; first + 8u < count; first += 16u)
        visit_point_16<Channels>(visit, *candidates, first, count - first);
#endif
    for (; first < count; first += 8u) visit_point_8<Channels>(visit, *candidates, first, count - first);
    candidates->count = 0;
}

#if DSN_GRADIENTS
/* A visit that sums the slopes too (the gradient, dsn.h "Gradients"): 64-bit lanes per channel and axis,
   beside the values' sums (AVX-512: those of 16 candidates at a time in wide_slope_x and wide_slope_y). */
template <uint32_t Channels>
struct SlopeVisit {
    PointVisit<Channels> values;
    vector_256 slope_x[Channels], slope_y[Channels];
#if defined(__AVX512F__) && defined(__AVX512BW__)
    vector_512 wide_slope_x[Channels], wide_slope_y[Channels];
#endif
};

/* Sign-extended 32-bit lanes added to 64-bit lanes: the even lanes, then the odd ones. */
DSN_POINT_INLINE vector_256 add_widened_32(vector_256 sums, vector_256 values) {
    const vector_256 one = set_8x32(1);
    return add_64(sums, add_64(multiply_even_32(values, one),
                               multiply_even_32(shift_right_logical_64(values, 32), one)));
}

/* add_window_reads_8 with each candidate's slopes (add_slope_lanes), added to the slopes' 64-bit lanes. */
template <uint32_t Channels>
DSN_POINT_INLINE void add_window_slopes_8(const unsigned char *values, uint32_t width, uint32_t height,
                                          vector_256 s_x, vector_256 s_y, vector_256 reach,
                                          SlopeVisit<Channels> *visit) {
    vector_256 along_x[Channels], along_y[Channels];
    for (uint32_t c = 0; c < Channels; c++) along_x[c] = along_y[c] = zero_256();
    add_window_reads_8<Channels, true>(values, width, height, width, s_x, s_y, reach, visit->values.sums,
                                       along_x, along_y);
    for (uint32_t c = 0; c < Channels; c++) {
        visit->slope_x[c] = add_widened_32(visit->slope_x[c], along_x[c]);
        visit->slope_y[c] = add_widened_32(visit->slope_y[c], along_y[c]);
    }
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* Sign-extended 32-bit lanes added to 64-bit lanes, 16 of them. */
DSN_POINT_INLINE vector_512 add_widened_32(vector_512 sums, vector_512 values) {
    const vector_512 one = set_16x32(1);
    return add_64(sums, add_64(multiply_even_32(values, one),
                               multiply_even_32(shift_right_logical_64(values, 32), one)));
}

/* add_window_slopes_8 on 16 lanes, the texels read as add_texton_pairs_16 reads them. */
template <uint32_t Channels>
DSN_POINT_INLINE void add_texton_slopes_16(const unsigned char *texton, uint32_t width, uint32_t height,
                                           vector_512 s_x, vector_512 s_y, mask_16 reach,
                                           SlopeVisit<Channels> *visit) {
    TextonTexels16 texels;
    texton_pairs_16<Channels>(texton, width, height, s_x, s_y, reach, &texels);
    for (uint32_t c = 0; c < Channels; c++) {
        const vector_512 a = lane_byte_16(texels.texel[0], 4u - Channels + c),
                         b = lane_byte_16(texels.texel[1], c),
                         d = lane_byte_16(texels.texel[2], 4u - Channels + c),
                         e = lane_byte_16(texels.texel[3], c);
        add_bilinear_16(a, b, d, e, texels.across, texels.down, &visit->values.wide_sums[c]);
        vector_512 along_x = zero_512(), along_y = zero_512();
        add_slope_lanes(a, b, d, e, texels.across, texels.down, &along_x, &along_y);
        visit->wide_slope_x[c] = add_widened_32(visit->wide_slope_x[c], along_x);
        visit->wide_slope_y[c] = add_widened_32(visit->wide_slope_y[c], along_y);
    }
}
#endif

/* Visits the buffered candidates with their slopes and empties the buffer. */
template <uint32_t Channels>
inline void visit_candidates(SlopeVisit<Channels> *visit, PointCandidates *candidates) {
    const uint32_t count = candidates->count;
    /* The lanes past the last candidate hold zeros (defined values; the count leaves them out). */
    const vector_256 zero = zero_256();
    for (uint32_t pad = count; pad < count + point_vector_lanes; pad += 8u)
        store_8x32(candidates->stream + pad, zero), store_8x32(candidates->field + pad, zero);
    const PointVisit<Channels> &values = visit->values;
    uint32_t first = 0;
#if defined(__AVX512F__) && defined(__AVX512BW__)
    for (; first + 8u < count; first += 16u) {
        vector_512 s_x, s_y;
        const mask_16 reach = candidate_offsets_16(&values, *candidates, first, count - first, &s_x, &s_y);
        add_texton_slopes_16<Channels>(values.texton, values.width, values.height, s_x, s_y, reach, visit);
    }
#endif
    for (; first < count; first += 8u) {
        vector_256 s_x, s_y;
        const vector_256 reach = candidate_offsets_8(&values, *candidates, first, count - first, &s_x, &s_y);
        add_window_slopes_8<Channels>(values.texton, values.width, values.height, s_x, s_y, reach, visit);
    }
    candidates->count = 0;
}
#endif

/* The visit of the value alone (visit_point_candidates), by the name the walks below call. */
template <uint32_t Channels>
DSN_POINT_INLINE void visit_candidates(PointVisit<Channels> *visit, PointCandidates *candidates) {
    visit_point_candidates<Channels>(visit, candidates);
}

/* Buffers the candidates `sifted` (bit i: lane i) of the pair `pair` that holds impulses first .. first + 7
   of the cell with this key; indices: the cell's (cell_indices). */
inline void add_sifted_pair(PointCandidates *candidates, uint32_t key, uint32_t first, uint64_t pair,
                            uint32_t sifted, uint32_t indices) {
    vector_256 streams, fields;
    /* dsn_cell_stream(key, 2^31 + k) of impulse k = first + lane */
    const uint32_t packed =
        pack_pair_8(pair, sifted, key + (0x80000000u + first) * 0x9E3779B9u, &streams, &fields);
    const uint32_t slot = candidates->count;
    store_8x32(candidates->stream + slot, streams);
    store_8x32(candidates->field + slot, bitwise_or(fields, set_8x32(indices)));
    candidates->count = slot + packed;
}

/* Buffers the candidates of the pair that holds impulses first .. first + 7 of the cell with this key,
   whose impulses are `count` (none when count <= first); indices: the cell's (cell_indices). */
DSN_POINT_INLINE void add_pair(PointCandidates *candidates, uint32_t key, uint32_t first, uint32_t count,
                               const FieldLanes &lanes, const CellAxis &x, const CellAxis &y,
                               uint32_t indices) {
    const uint64_t pair = dsn_position_pair(key, first >> 3);
    const uint32_t present = count <= first ? 0u : count - first < 8u ? count - first : 8u;
    const uint32_t sifted = gather_lanes(candidate_lanes(pair, lanes, x, y), lanes) & ((1u << present) - 1u);
    add_sifted_pair(candidates, key, first, pair, sifted, indices);
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* Number of set bits of a 16-bit mask. */
inline uint32_t mask_count(uint32_t mask) {
#if defined(__POPCNT__)
    return static_cast<uint32_t>(__builtin_popcount(mask));
#else
    mask -= (mask >> 1) & 0x5555u;
    mask = (mask & 0x3333u) + ((mask >> 2) & 0x3333u);
    mask = (mask + (mask >> 4)) & 0x0F0Fu;
    return (mask + (mask >> 8)) & 0x1Fu;
#endif
}

/* The Poisson table of a noise whose cell counts are one draw, in vectors: the guide widened to 32 bits
   and cdf[0 .. 31]. dsn_poisson_count_two_steps then reads no threshold past cdf[31] when the guide's
   counts are at most 29 (count_tables_fit). */
struct CountTables {
    vector_512 guide[4], cdf[2];
};

inline bool count_tables_fit(const dsn_noise_state *noise) {
    return noise->poisson_parts == 1 && noise->poisson_guide[63] <= 29u &&
           sizeof noise->poisson_cdf / sizeof noise->poisson_cdf[0] >= 32u;
}

inline void count_tables(const dsn_noise_state *noise, CountTables *tables) {
    for (uint32_t q = 0; q < 4; q++)
        tables->guide[q] = widen_bytes_16x32(load_16x8(noise->poisson_guide + 16 * q));
    tables->cdf[0] = load_16x32(noise->poisson_cdf);
    tables->cdf[1] = load_16x32(noise->poisson_cdf + 16);
}

/* dsn_poisson_count_two_steps of 16 keys (count_tables_fit), the guide and thresholds read by permutes;
   the rare lanes that need the exact search take dsn_poisson_draw. */
inline vector_512 counts_16(const dsn_noise_state *noise, const CountTables &tables, vector_512 keys) {
    const vector_512 bucket = shift_right_logical_32(keys, 26), one = set_16x32(1);
    vector_512 n = blend_32(greater_equal_unsigned_32(bucket, set_16x32(32)),
                            permute_32_of_two(tables.guide[0], bucket, tables.guide[1]),
                            permute_32_of_two(tables.guide[2], bucket, tables.guide[3]));
    for (uint32_t step = 0; step < 2; step++)
        n = add_32_where(greater_equal_unsigned_32(keys, permute_32_of_two(tables.cdf[0], n, tables.cdf[1])),
                         n, one);
    const vector_512 size = set_16x32(noise->poisson_size);
    const mask_16 search = greater_unsigned_32(n, size) |
                           greater_equal_unsigned_32(less_unsigned_32(n, size), keys,
                                                     permute_32_of_two(tables.cdf[0], n, tables.cdf[1]));
    if (search == 0) return n;
    uint32_t lanes[16], uniforms[16];
    store_16x32(lanes, n), store_16x32(uniforms, keys);
    for (uint32_t k = 0; k < 16; k++)
        if ((search >> k) & 1u) lanes[k] = dsn_poisson_draw(noise, uniforms[k]);
    return load_16x32(lanes);
}

/* The candidates `sifted` (bit k: impulse k) of a cell's first two pairs (`pairs`, the first low)
   compressed into place; indices: the cell's (cell_indices). */
inline void add_sifted_pairs(PointCandidates *candidates, uint32_t key, vector_128 pairs, uint32_t sifted,
                             uint32_t indices) {
    /* dsn_cell_stream(key, 2^31 + k) of impulse k */
    const vector_512 streams =
        add_32(set_16x32(key + 0x80000000u * 0x9E3779B9u),
               multiply_32(set_lanes_16x32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
                           set_16x32(0x9E3779B9u)));
    const mask_16 keep = static_cast<mask_16>(sifted);
    const uint32_t slot = candidates->count;
    store_16x32(candidates->stream + slot, compress_32(keep, streams));
    store_16x32(candidates->field + slot,
                compress_32(keep, bitwise_or(widen_bytes_16x32(pairs), set_16x32(indices))));
    candidates->count = slot + mask_count(sifted);
}

/* add_pair for the cell's first two pairs at once (impulses 0 .. 15): the sifting of both pairs in one
   128-bit vector (candidate_lanes), their top bits gathered by one movemask, and the candidates
   compressed into place. */
inline void add_first_pairs(PointCandidates *candidates, uint32_t key, uint32_t count,
                            const FieldLanes &lanes, const CellAxis &x, const CellAxis &y, uint32_t indices) {
    const uint64_t first = dsn_position_pair(key, 0), second = dsn_position_pair(key, 1);
    const vector_128 pairs = set_lanes_2x64(first, second);
    uint32_t sifted = sift_two_pairs(pairs, lanes, x, y);
    if (count < 16u) sifted &= (1u << count) - 1u; /* impulses that do not exist */
    add_sifted_pairs(candidates, key, pairs, sifted, indices);
}
#endif

/* floor(value / 2^16) as an int32 bit pattern (the value far from the int64 limits). */
inline uint32_t shifted_16(int64_t value) {
    return static_cast<uint32_t>(static_cast<uint64_t>(floor_shift(value, 16)));
}

/* The cells of one axis that may reach the point (cell_axis), with their floor(shifted_base / 2^16). */
struct AxisCells {
    uint32_t cell[point_vector_cells], base[point_vector_cells];
    CellAxis axis[point_vector_cells];
    uint32_t count;
};

/* False when there are more than point_vector_cells. EntryEdge: the gradient's sifting
   (cell_axis_with_entry_edge). */
template <bool EntryEdge = false>
DSN_POINT_INLINE bool axis_cells(const PointAxis &point, const FieldLanes &lanes, AxisCells *cells) {
    cells->count = 0;
    for (uint32_t s = 0; s < point.axis.span_count; s++) {
        const dsn_span span = dsn_axis_span(&point.axis, s);
        for (uint32_t i = 0; i < span.cell_count; i++) {
            const uint32_t cell = dsn_span_cell(&span, i, point.axis.shift), at = cells->count;
            CellAxis axis;
            if (!(EntryEdge ? cell_axis_with_entry_edge(point, span, cell, lanes, &axis)
                            : cell_axis(point, span, cell, lanes, &axis)))
                continue;
            if (at == point_vector_cells) return false;
            cells->axis[at] = axis;
            cells->cell[at] = cell;
            cells->base[at] = shifted_16(axis.shifted_base);
            cells->count = at + 1u;
        }
    }
    return true;
}

/* The cells of the point (x, y) along both axes; false when an axis has more than point_vector_cells. */
template <bool EntryEdge>
DSN_POINT_INLINE bool point_cells(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                  const FieldLanes &lanes, AxisCells *columns, AxisCells *rows) {
    const uint32_t shift = noise->cell_shift;
    return axis_cells<EntryEdge>(point_axis(x, noise->radius[0], shift, noise->period[0]), lanes, columns) &&
           axis_cells<EntryEdge>(point_axis(y, noise->radius[1], shift, noise->period[1]), lanes, rows);
}

/* The visit of a point, its sums zero, given the bases of its column and row cells by their indices
   (AxisCells's base); quads: the batch's table (PointVisit), or null. */
template <uint32_t Channels>
DSN_POINT_INLINE void point_visit_begin(const dsn_noise_state *noise, vector_256 column_bases,
                                        vector_256 row_bases, const uint32_t *quads,
                                        PointVisit<Channels> *visit) {
    visit->texton = noise->asset.texton;
    visit->quads = quads;
    visit->width = noise->asset.width, visit->height = noise->asset.height;
    visit->quad_row = (noise->asset.width + 1u) * Channels;
    visit->last_x = ((2u * noise->radius[0] + 2u) << 16) - 1u;
    visit->last_y = ((2u * noise->radius[1] + 2u) << 16) - 1u;
    visit->shift = shift_count(static_cast<int>(noise->cell_shift));
    visit->column_bases = column_bases, visit->row_bases = row_bases;
    for (uint32_t c = 0; c < Channels; c++) {
        visit->sums[c] = zero_256();
#if defined(__AVX512F__) && defined(__AVX512BW__)
        visit->wide_sums[c] = zero_512();
#endif
    }
}

/* The bases of an axis's cells by their indices (the lanes past its cells are not read: masked, defined
   values). */
DSN_POINT_INLINE vector_256 cell_bases(const AxisCells &cells) {
    return load_masked_8x32(cells.base,
                            greater_32(set_8x32(cells.count), set_lanes_8x32(0, 1, 2, 3, 4, 5, 6, 7)));
}

/* point_visit_begin for the point whose cells are columns x rows. */
template <uint32_t Channels>
DSN_POINT_INLINE void point_visit_start(const dsn_noise_state *noise, const AxisCells &columns,
                                        const AxisCells &rows, const uint32_t *quads,
                                        PointVisit<Channels> *visit) {
    point_visit_begin<Channels>(noise, cell_bases(columns), cell_bases(rows), quads, visit);
}

#if DSN_GRADIENTS
/* A slope visit with zero sums (point_visit_begin's, then the slopes'). */
template <uint32_t Channels>
DSN_POINT_INLINE void slope_visit_begin(const dsn_noise_state *noise, vector_256 column_bases,
                                        vector_256 row_bases, SlopeVisit<Channels> *visit) {
    point_visit_begin<Channels>(noise, column_bases, row_bases, 0, &visit->values);
    for (uint32_t c = 0; c < Channels; c++) {
        visit->slope_x[c] = visit->slope_y[c] = zero_256();
#if defined(__AVX512F__) && defined(__AVX512BW__)
        visit->wide_slope_x[c] = visit->wide_slope_y[c] = zero_512();
#endif
    }
}
#endif

/* Buffers the candidates of a cell's pairs from impulse 16 on (cells of more than 16 impulses), visiting
   the buffer whenever a pair might not fit. */
template <class Visit>
DSN_POINT_INLINE void add_later_pairs(Visit *visit, PointCandidates *candidates, uint32_t key, uint32_t count,
                                      const FieldLanes &lanes, const CellAxis &x, const CellAxis &y,
                                      uint32_t indices) {
    for (uint32_t first = 16; first < count; first += 8u) {
        if (candidates->count > point_vector_slots - 8u) visit_candidates(visit, candidates);
        add_pair(candidates, key, first, count, lanes, x, y, indices);
    }
}

/* Visits the candidates left and writes the point's sums, channel c at sums[c stride]. */
template <uint32_t Channels>
DSN_POINT_INLINE void point_visit_sums(PointVisit<Channels> *visit, PointCandidates *candidates,
                                       uint64_t *sums, uint32_t stride) {
    visit_point_candidates<Channels>(visit, candidates);
    for (uint32_t c = 0; c < Channels; c++) {
        uint64_t lanes_64[12] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
        __builtin_memcpy(lanes_64, &visit->sums[c], 32);
#if defined(__AVX512F__) && defined(__AVX512BW__)
        __builtin_memcpy(lanes_64 + 4, &visit->wide_sums[c], 64);
#endif
        uint64_t sum = 0;
        for (uint32_t k = 0; k < 12; k++) sum += lanes_64[k];
        sums[c * stride] = sum;
    }
}

/* Buffers the candidates of the point's cells, visiting the buffer whenever it might not hold a cell's
   next pairs (the last visit is the caller's): the key and impulse count of the cell (columns i, rows j)
   at index j row_step + i column_step of keys and counts. */
template <class Visit>
DSN_POINT_INLINE void visit_cells(const FieldLanes &lanes, const AxisCells &columns, const AxisCells &rows,
                                  const uint32_t *keys, const uint32_t *counts, uint32_t row_step,
                                  uint32_t column_step, Visit *visit, PointCandidates *candidates) {
    for (uint32_t j = 0; j < rows.count; j++) {
        for (uint32_t i = 0; i < columns.count; i++) {
            const uint32_t key = keys[j * row_step + i * column_step],
                           count = counts[j * row_step + i * column_step];
            /* The first two pairs whether the cell has impulses there or not: a branch on the count
               would often be mispredicted. The rest (cells of more than 16 impulses) one by one. */
            if (candidates->count > point_vector_slots - 16u) visit_candidates(visit, candidates);
#if defined(__AVX512F__) && defined(__AVX512BW__)
            add_first_pairs(candidates, key, count, lanes, columns.axis[i], rows.axis[j], cell_indices(i, j));
#else
            add_pair(candidates, key, 0, count, lanes, columns.axis[i], rows.axis[j], cell_indices(i, j));
            add_pair(candidates, key, 8, count, lanes, columns.axis[i], rows.axis[j], cell_indices(i, j));
#endif
            add_later_pairs(visit, candidates, key, count, lanes, columns.axis[i], rows.axis[j],
                            cell_indices(i, j));
        }
    }
}

/* The point's sums from its cells (visit_cells), channel c at value[c] (0 past the channels); quads: the
   batch's table (PointVisit), or null. */
template <uint32_t Channels>
DSN_POINT_INLINE void point_vector_sum(const dsn_noise_state *noise, const FieldLanes &lanes,
                                       const AxisCells &columns, const AxisCells &rows, const uint32_t *keys,
                                       const uint32_t *counts, uint32_t row_step, uint32_t column_step,
                                       const uint32_t *quads, uint64_t *value) {
    PointVisit<Channels> visit;
    point_visit_start<Channels>(noise, columns, rows, quads, &visit);
    PointCandidates candidates;
    candidates.count = 0;
    visit_cells(lanes, columns, rows, keys, counts, row_step, column_step, &visit, &candidates);
    point_visit_sums<Channels>(&visit, &candidates, value, 1);
    for (uint32_t c = Channels; c < DSN_MAX_CHANNELS; c++) value[c] = 0;
}

/* The keys and impulse counts of the point's cells, row by row, all of them first: the counts' chains of
   dependent loads then overlap. */
DSN_POINT_INLINE void cell_keys_and_counts(const dsn_noise_state *noise, const AxisCells &columns,
                                           const AxisCells &rows, uint32_t *keys, uint32_t *counts) {
    const uint32_t cells = rows.count * columns.count;
    for (uint32_t j = 0, k = 0; j < rows.count; j++) {
        const uint32_t row_key = dsn_row_key(noise, rows.cell[j]);
        for (uint32_t i = 0; i < columns.count; i++, k++)
            keys[k] = dsn_cell_key_in_row(noise, columns.cell[i], row_key);
    }
    if (dsn_poisson_two_steps_fit(noise))
        for (uint32_t k = 0; k < cells; k++) counts[k] = dsn_poisson_count_two_steps(noise, keys[k]);
    else
        for (uint32_t k = 0; k < cells; k++) counts[k] = dsn_cell_impulse_count(noise, keys[k]);
}

/* The point's sums (what dsn_internal_continuous_point normalizes); 0 for a point with more than
   point_vector_cells cells along an axis. */
template <uint32_t Channels>
int point_vector(const dsn_noise_state *noise, uint64_t x, uint64_t y, uint64_t *value) {
    const FieldLanes lanes = field_lanes(noise->cell_shift);
    AxisCells columns, rows;
    if (!point_cells<false>(noise, x, y, lanes, &columns, &rows)) return 0;
    uint32_t keys[point_vector_cells * point_vector_cells], counts[point_vector_cells * point_vector_cells];
    cell_keys_and_counts(noise, columns, rows, keys, counts);
    point_vector_sum<Channels>(noise, lanes, columns, rows, keys, counts, columns.count, 1, 0, value);
    return 1;
}

/* The sum of a vector's 64-bit lanes, modulo 2^64. */
inline uint64_t lane_total(vector_256 lanes) {
    uint64_t values[4];
    __builtin_memcpy(values, &lanes, sizeof values);
    return values[0] + values[1] + values[2] + values[3];
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
inline uint64_t lane_total(vector_512 lanes) {
    return lane_total(low_256(lanes)) + lane_total(high_256(lanes));
}
#endif

#if DSN_GRADIENTS

/* A slope visit's sums, channel c at value[c], slope_x[c], slope_y[c] (0 past the channels). */
template <uint32_t Channels>
inline void slope_visit_sums(const SlopeVisit<Channels> &visit, uint64_t *value, uint64_t *slope_x,
                             uint64_t *slope_y) {
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) value[c] = slope_x[c] = slope_y[c] = 0;
    for (uint32_t c = 0; c < Channels; c++) {
        value[c] = lane_total(visit.values.sums[c]);
        slope_x[c] = lane_total(visit.slope_x[c]);
        slope_y[c] = lane_total(visit.slope_y[c]);
#if defined(__AVX512F__) && defined(__AVX512BW__)
        value[c] += lane_total(visit.values.wide_sums[c]);
        slope_x[c] += lane_total(visit.wide_slope_x[c]);
        slope_y[c] += lane_total(visit.wide_slope_y[c]);
#endif
    }
}

/* dsn_internal_continuous_slopes's sums (continuous_internal.h), the impulses at the entry edge included;
   0 for a point with more than point_vector_cells cells along an axis. */
template <uint32_t Channels>
int point_slopes(const dsn_noise_state *noise, uint64_t x, uint64_t y, uint64_t *value, uint64_t *slope_x,
                 uint64_t *slope_y) {
    const FieldLanes lanes = field_lanes(noise->cell_shift);
    AxisCells columns, rows;
    if (!point_cells<true>(noise, x, y, lanes, &columns, &rows)) return 0;
    uint32_t keys[point_vector_cells * point_vector_cells], counts[point_vector_cells * point_vector_cells];
    cell_keys_and_counts(noise, columns, rows, keys, counts);
    SlopeVisit<Channels> visit;
    slope_visit_begin<Channels>(noise, cell_bases(columns), cell_bases(rows), &visit);
    PointCandidates candidates;
    candidates.count = 0;
    visit_cells(lanes, columns, rows, keys, counts, columns.count, 1, &visit, &candidates);
    visit_candidates(&visit, &candidates);
    slope_visit_sums(visit, value, slope_x, slope_y);
    return 1;
}
#endif

/* ---- A mix's point (mix_point.cpp): each candidate reads its material's texton (kernels.h's
   dsn_point_materials), the materials' textons of one size, channels and bits ---- */

#if defined(__AVX512F__) && defined(__AVX512BW__)
typedef vector_512 mixed_sums;
inline vector_512 zero_sums() { return zero_512(); }
#else
typedef vector_256 mixed_sums;
inline vector_256 zero_sums() { return zero_256(); }
#endif

/* The visit of a mixed point: the point's (material 0's texton, window, cell bases), the materials as
   lanes (the thresholds their hashes meet, or the pick and its axes; where each texton lies from material
   0's, in bytes, which the gathers' 32-bit offsets add), and each material's sums. Picked: the weights
   vary, and the pick gives the materials (its call kept out of the copy that compares the thresholds), or
   where the lanes take the control around the point (mix_pick_lanes.h), the lanes. */
template <uint32_t Channels, bool Picked>
struct MixedVisit {
    PointVisit<Channels> point;
    uint32_t count;
    uint32_t threshold[3], moved[3]; /* level l: material l + 1 or a later one (broadcast where used) */
    uint32_t reached[3];             /* all ones, or 0 where no hash meets the level's threshold */
    uint32_t (*pick)(const void *context, uint32_t hash, uint32_t x, uint32_t y); /* or null */
    const void *context;
    PickAxis pick_x, pick_y;
#if DSN_MIXING
    bool lanes_pick;
    PickWindow window;
#endif
    /* sums[0]: every candidate's read (material 0's sums once the others' are taken away, exactly, modulo
       2^64); sums[m], m > 0: material m's */
    mixed_sums sums[dsn_point_materials_most][Channels];
};

/* The materials as lanes for the point (x, y) of the lead `noise`, the sums zero; false where a texton lies
   2^30 bytes or more from material 0's. */
template <uint32_t Channels, bool Picked>
inline bool mixed_visit_begin(const dsn_noise_state *noise, const dsn_point_materials *materials, uint64_t x,
                              uint64_t y, MixedVisit<Channels, Picked> *visit) {
    const uint64_t lead = reinterpret_cast<uintptr_t>(materials->values[0]);
    visit->count = materials->count;
    visit->pick = materials->pick, visit->context = materials->context;
    visit->pick_x = pick_axis(x, noise->radius[0]), visit->pick_y = pick_axis(y, noise->radius[1]);
#if DSN_MIXING
    visit->lanes_pick = false;
    if (Picked) {
        const PickWindow unread = {}; /* (written whatever pick_window answers: no warning in any build) */
        visit->window = unread;
        visit->lanes_pick =
            materials->control != 0 &&
            pick_window(materials->control, materials->count, visit->pick_x.whole, visit->pick_y.whole,
                        noise->radius[0] + 2u, noise->radius[1] + 2u, &visit->window);
    }
#endif
    for (uint32_t level = 0; level < 3; level++) {
        const uint32_t m = level + 1u < materials->count ? level + 1u : 0u;
        const uint64_t moved = uint64_t(reinterpret_cast<uintptr_t>(materials->values[m])) - lead;
        if (moved + (uint64_t(1) << 30) >= (uint64_t(1) << 31)) return false;
        visit->moved[level] = uint32_t(moved);
        visit->threshold[level] = uint32_t(materials->thresholds[level]);
        visit->reached[level] = materials->thresholds[level] >> 32 ? 0u : 0xFFFFFFFFu;
    }
    for (uint32_t m = 0; m < dsn_point_materials_most; m++)
        for (uint32_t c = 0; c < Channels; c++) visit->sums[m][c] = zero_sums();
    return true;
}

/* The candidates' material hashes dsn_cell_stream(key, 2^31 + 2^30 + k): the fraction's stream moved by
   2^30 0x9E3779B9 (2^30 modulo 2^32). */
const uint32_t material_stream_step = 0x40000000u;

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* Bits 0, 2, .. 14 of a lane mask as bits 0 .. 7: the candidates of bilinear_16's even 64-bit lanes. */
inline mask_8 even_bits(uint32_t lanes) {
    lanes &= 0x5555u;
    lanes = (lanes | lanes >> 1) & 0x3333u;
    lanes = (lanes | lanes >> 2) & 0x0F0Fu;
    return static_cast<mask_8>(lanes | lanes >> 4);
}

/* Candidates first .. first + 15 of which the first `valid` exist: each one's material from its hash, its
   texels read from that material's texton, and its read (bilinear_16's even and odd 64-bit lanes) added
   to that material's sums under that material's lanes. */
template <uint32_t Channels, bool Picked>
DSN_POINT_INLINE void visit_mixed(MixedVisit<Channels, Picked> *visit, const PointCandidates &candidates,
                                  uint32_t first, uint32_t valid) {
    vector_512 s_x, s_y;
    const mask_16 reach = candidate_offsets_16(&visit->point, candidates, first, valid, &s_x, &s_y);
    const vector_512 hashes =
        mix32_lanes(add_32(load_16x32(candidates.stream + first), set_16x32(material_stream_step)));
    uint32_t at_least[4] = {0, 0, 0, 0};
    if (Picked) {
#if DSN_MIXING
        if (visit->lanes_pick) {
            picked_level_bits(visit->window, hashes, impulse_wholes(visit->pick_x, s_x),
                              impulse_wholes(visit->pick_y, s_y), at_least);
            for (uint32_t level = 0; level < 3; level++) at_least[level] &= reach;
        } else
#endif
        {
            uint32_t hash_lanes[16], x_lanes[16], y_lanes[16];
            store_16x32(hash_lanes, hashes), store_16x32(x_lanes, s_x), store_16x32(y_lanes, s_y);
            picked_levels(visit, hash_lanes, x_lanes, y_lanes, reach, at_least);
        }
    } else {
        for (uint32_t level = 0; level < 3 && level + 1u < visit->count; level++)
            at_least[level] =
                greater_equal_unsigned_32(hashes, set_16x32(visit->threshold[level])) & visit->reached[level];
    }
    vector_512 moved = zero_512();
    for (uint32_t level = 0; level < 3 && level + 1u < visit->count; level++)
        moved = blend_32(static_cast<mask_16>(at_least[level]), moved, set_16x32(visit->moved[level]));
    TextonTexels16 texels;
    texton_pairs_16<Channels>(visit->point.texton, visit->point.width, visit->point.height, s_x, s_y, reach,
                              &texels, moved);
    /* The count read once: the sums' vector stores may alias it as far as the compiler knows, and a
       second read would leave lanes it cannot prove set. */
    const uint32_t count = visit->count;
    mask_8 even_lanes[dsn_point_materials_most], odd_lanes[dsn_point_materials_most];
    for (uint32_t m = 1; m < dsn_point_materials_most && m < count; m++) {
        const uint32_t lanes = at_least[m - 1] & ~at_least[m];
        even_lanes[m] = even_bits(lanes), odd_lanes[m] = even_bits(lanes >> 1);
    }
    for (uint32_t c = 0; c < Channels; c++) {
        vector_512 even, odd;
        bilinear_16(lane_byte_16(texels.texel[0], 4u - Channels + c), lane_byte_16(texels.texel[1], c),
                    lane_byte_16(texels.texel[2], 4u - Channels + c), lane_byte_16(texels.texel[3], c),
                    texels.across, texels.down, &even, &odd);
        visit->sums[0][c] = add_64(visit->sums[0][c], add_64(even, odd));
        for (uint32_t m = 1; m < dsn_point_materials_most && m < count; m++)
            visit->sums[m][c] =
                add_64_where(odd_lanes[m], add_64_where(even_lanes[m], visit->sums[m][c], even), odd);
    }
}
const uint32_t mixed_lanes = 16;
#else
/* The AVX2 copy: candidates first .. first + 7 of which the first `valid` exist, each read once from its
   material's texton (window_texels_8's moved gathers); the read's 64-bit halves (bilinear_8's even and
   odd lanes) added to each material's sums under that material's lanes. */
template <uint32_t Channels, bool Picked>
DSN_POINT_INLINE void visit_mixed(MixedVisit<Channels, Picked> *visit, const PointCandidates &candidates,
                                  uint32_t first, uint32_t valid) {
    const PointVisit<Channels> &point = visit->point;
    vector_256 s_x, s_y;
    const vector_256 reach = candidate_offsets_8(&point, candidates, first, valid, &s_x, &s_y);
    const vector_256 hashes =
        mix32_lanes(add_32(load_8x32(candidates.stream + first), set_8x32(material_stream_step)));
    vector_256 at_least[4] = {zero_256(), zero_256(), zero_256(), zero_256()};
    if (Picked) {
#if DSN_MIXING
        if (visit->lanes_pick) {
            picked_level_lanes(visit->window, hashes, impulse_wholes(visit->pick_x, s_x),
                               impulse_wholes(visit->pick_y, s_y), at_least);
            for (uint32_t level = 0; level < 3; level++)
                at_least[level] = bitwise_and(at_least[level], reach);
        } else
#endif
        {
            uint32_t hash_lanes[8], x_lanes[8], y_lanes[8], picked[3] = {0, 0, 0};
            store_8x32(hash_lanes, hashes), store_8x32(x_lanes, s_x), store_8x32(y_lanes, s_y);
            picked_levels(visit, hash_lanes, x_lanes, y_lanes, static_cast<uint32_t>(top_bits_of_32(reach)),
                          picked);
            const vector_256 lane_bits = set_lanes_8x32(1, 2, 4, 8, 16, 32, 64, 128);
            for (uint32_t level = 0; level < 3; level++)
                at_least[level] = equal_32(bitwise_and(set_8x32(picked[level]), lane_bits), lane_bits);
        }
    } else {
        for (uint32_t level = 0; level < 3 && level + 1u < visit->count; level++)
            at_least[level] = bitwise_and(at_most(set_8x32(visit->threshold[level]), hashes),
                                          set_8x32(visit->reached[level]));
    }
    vector_256 moved = zero_256();
    for (uint32_t level = 0; level < 3 && level + 1u < visit->count; level++)
        moved = blend_bytes(moved, set_8x32(visit->moved[level]), at_least[level]);
    WindowTexels texels;
    window_texels_8<Channels>(point.texton, point.width, point.height, point.width, s_x, s_y, reach, &texels,
                              moved);
    const uint32_t count = visit->count; // read once, as in the AVX-512 copy
    vector_256 even_lanes[dsn_point_materials_most], odd_lanes[dsn_point_materials_most];
    for (uint32_t m = 1; m < dsn_point_materials_most && m < count; m++) {
        const vector_256 lanes = and_not(at_least[m], at_least[m - 1]);
        even_lanes[m] = shuffle_32<0xA0>(lanes), odd_lanes[m] = shuffle_32<0xF5>(lanes);
    }
    for (uint32_t c = 0; c < Channels; c++) {
        const int byte = static_cast<int>(c);
        vector_256 even, odd;
        bilinear_8(lane_byte(texels.top_left, byte), lane_byte(texels.top_right, byte),
                   lane_byte(texels.bottom_left, byte), lane_byte(texels.bottom_right, byte), texels.across,
                   texels.down, &even, &odd);
        visit->sums[0][c] = add_64(visit->sums[0][c], add_64(even, odd));
        for (uint32_t m = 1; m < dsn_point_materials_most && m < count; m++)
            visit->sums[m][c] = add_64(
                visit->sums[m][c], add_64(bitwise_and(even, even_lanes[m]), bitwise_and(odd, odd_lanes[m])));
    }
}
const uint32_t mixed_lanes = 8;
#endif

template <uint32_t Channels, bool Picked>
DSN_POINT_INLINE void visit_candidates(MixedVisit<Channels, Picked> *visit, PointCandidates *candidates) {
    clear_past_candidates(candidates);
    for (uint32_t first = 0; first < candidates->count; first += mixed_lanes)
        visit_mixed<Channels, Picked>(visit, *candidates, first, candidates->count - first);
    candidates->count = 0;
}

/* Each material's sums at the point, material m's channel c at value[3 m + c] (0 past the channels); 0
   where mixed_visit_begin is false, or for a point with more than point_vector_cells cells along an axis. A
   pick's materials are those of the candidates in reach (the others read nothing). */
template <uint32_t Channels, bool Picked>
int point_mixed(const dsn_noise_state *noise, const dsn_point_materials *materials, uint64_t x, uint64_t y,
                uint64_t *value) {
    MixedVisit<Channels, Picked> visit;
    const FieldLanes lanes = field_lanes(noise->cell_shift);
    AxisCells columns, rows;
    if (!mixed_visit_begin<Channels, Picked>(noise, materials, x, y, &visit) ||
        !point_cells<false>(noise, x, y, lanes, &columns, &rows))
        return 0;
    uint32_t keys[point_vector_cells * point_vector_cells], counts[point_vector_cells * point_vector_cells];
    cell_keys_and_counts(noise, columns, rows, keys, counts);
    point_visit_start<Channels>(noise, columns, rows, 0, &visit.point);
    PointCandidates candidates;
    candidates.count = 0;
    visit_cells(lanes, columns, rows, keys, counts, columns.count, 1, &visit, &candidates);
    visit_candidates(&visit, &candidates);
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) {
        uint64_t others = 0;
        for (uint32_t m = 1; m < materials->count; m++) {
            value[DSN_MAX_CHANNELS * m + c] = c < Channels ? lane_total(visit.sums[m][c]) : 0u;
            others += value[DSN_MAX_CHANNELS * m + c];
        }
        value[c] = c < Channels ? lane_total(visit.sums[0][c]) - others : 0u;
    }
    return 1;
}

/* The kernel entry (kernels.h's dsn_continuous_point_entry), one copy per channel count: the point's sums,
   and where slope_x is not null its derivative's (point_slopes), or where materials is not null each
   material's (point_mixed); 0 for a noise it does not take, or a
   point with more than point_vector_cells cells along an axis. */
inline int continuous_point_sums(const dsn_noise_state *noise, uint64_t x, uint64_t y, uint64_t *value,
                                 uint64_t *slope_x, uint64_t *slope_y, const dsn_point_materials *materials) {
    if (!point_vector_takes(noise)) return 0;
    const bool rgb = noise->asset.channels == 3;
    if (materials != 0) {
        if (slope_x != 0 || materials->count > dsn_point_materials_most) return 0;
        if (materials->pick != 0)
            return rgb ? point_mixed<3, true>(noise, materials, x, y, value)
                       : point_mixed<1, true>(noise, materials, x, y, value);
        return rgb ? point_mixed<3, false>(noise, materials, x, y, value)
                   : point_mixed<1, false>(noise, materials, x, y, value);
    }
#if DSN_GRADIENTS
    if (slope_x != 0)
        return rgb ? point_slopes<3>(noise, x, y, value, slope_x, slope_y)
                   : point_slopes<1>(noise, x, y, value, slope_x, slope_y);
#else
    (void)slope_x, (void)slope_y;
#endif
    return rgb ? point_vector<3>(noise, x, y, value) : point_vector<1>(noise, x, y, value);
}

/* The continuous point entry of the x86 kernel copies (kernel_avx2.cpp, kernel_avx512.cpp): this
   evaluator where it takes the noise, else Fallback's (the default kernel's sifting walk,
   continuous_point_sift.h, whose copy built for the baseline runs faster than one built for AVX2 or
   AVX-512). */
template <const dsn_kernel_entries *Fallback>
int continuous_point_or(const dsn_noise_state *noise, uint64_t x, uint64_t y, uint64_t *value,
                        uint64_t *slope_x, uint64_t *slope_y, const dsn_point_materials *materials) {
    if (materials != 0) return continuous_point_sums(noise, x, y, value, slope_x, slope_y, materials);
    return continuous_point_sums(noise, x, y, value, slope_x, slope_y, 0) ||
           Fallback->continuous_point(noise, x, y, value, slope_x, slope_y, 0);
}

/* The point's values (normalize_q32 of its sums), as dsn_internal_continuous_point gives them; 0 where
   continuous_point_sums is. */
inline int continuous_point_vector(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out) {
    uint64_t value[DSN_MAX_CHANNELS];
    if (!continuous_point_sums(noise, x, y, value, 0, 0, 0)) return 0;
    normalize_q32(noise, value, out);
    return 1;
}

} // namespace
#endif /* __AVX2__ */

#endif /* DSN_CONTINUOUS_POINT_VECTOR_H */
