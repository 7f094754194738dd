/* runtime/kernels/continuous_point_vector.h - the continuous mode at one point on AVX2 or AVX-512 vectors, as
   a kernel (kernels.h: the AVX2 and AVX-512 kernels include it), for 8-bit textons and cells of side <= 16
   (pairs of 8 impulses). The cells are walked and their pairs sifted as by continuous_point.cpp's
   evaluator (continuous_sift.h), the keys and counts of all the cells first; each pair's candidates are
   packed into arrays, their cell by its column and row index (AVX-512: a cell's first two pairs at once,
   compressed), then visited 8 (AVX-512: 16)
   at a time: the fraction hash, the 16-bit positions, the exact reach test and the bilinear texton, all
   in 32-bit lanes (64-bit for the column's interpolation), the texels gathered straight from the texton,
   each where it lies inside the window (no branch at the window's edge; AVX-512: both texels of a row by
   one 8-byte read). The same impulses, offsets,
   weights and integers as the evaluator, so the same bits. Internal to libdsn; not installed (everything
   here has internal linkage). */
#ifndef DSN_CONTINUOUS_POINT_VECTOR_H
#define DSN_CONTINUOUS_POINT_VECTOR_H

#include "core/continuous_internal.h"
#include "core/continuous_sift.h"
#include "kernels/continuous_lanes.h"

namespace {
/* The noises the vector evaluator takes (continuous_batch.cpp asks too, built without AVX2): 8-bit
   textons, cells of side <= 16 (pairs of 8 impulses), radii below 2^12. */
inline bool point_vector_takes(const dsn_noise_state *noise) {
    return noise->asset.bits == 8 && dsn_field_shift(noise->cell_shift) == 3 && noise->radius[0] < 4096u &&
           noise->radius[1] < 4096u;
}
} // namespace

#if defined(__AVX2__)
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
   S & 0xFFFF. bracket keeps 0 < shifted < (2 radius + 2) 2^32, that is 0 <= S <= (2 radius + 2) 2^16 - 1
   except shifted = 0 (S = 0 with low bits zero), which the test below keeps too: its texels are those of
   rows -1 and 0 with weight 0 on row 0, so it adds exactly zero. For a cell that passes cell_axis,
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

inline __m256i broadcast_8(uint32_t value) { return _mm256_set1_epi32(static_cast<int>(value)); }

inline void store_8(uint32_t *at, __m256i value) {
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(at)), value);
}

/* a <= limit as unsigned 32-bit lanes. */
inline __m256i at_most(__m256i a, __m256i limit) { return _mm256_cmpeq_epi32(_mm256_min_epu32(a, limit), a); }

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
    __m128i shift;
    /* floor(shifted_base / 2^16) of the point's column and row cells (AxisCells's base) */
    __m256i column_bases, row_bases;
    __m256i sums[Channels];
#if defined(__AVX512F__) && defined(__AVX512BW__)
    __m512i wide_sums[Channels];
#endif
};

/* Byte `index` of every 32-bit lane, sign-extended. */
inline __m256i lane_byte(__m256i words, int index) {
    return _mm256_srai_epi32(_mm256_sll_epi32(words, _mm_cvtsi32_si128(24 - 8 * index)), 24);
}

/* The bilinear reads of 8 candidates in reach (`reach`) of a window of width x height 8-bit texels,
   `stride` texels a row, added to sums (64-bit lanes, one per channel): bracket's floor(shifted / 2^16)
   of each axis in 32-bit lanes, the lower index (S >> 16) - 1 and the weight S & 0xFFFF. Each texel is
   read where it lies inside the window (index -1, 0xFFFFFFFF, fails the tests) and is zero elsewhere, as
   add_bilinear's, without a branch: one gather per texel column and row, 4 bytes from each texel (its
   channels first). Reads reach at most 3 bytes past the window's last texel: into the asset's 4-byte CRC
   (format.h: total_size), which the loader guarantees lies in the buffer after the texton and the
   pyramid. */
template <uint32_t Channels>
DSN_POINT_INLINE void add_window_reads_8(const unsigned char *values, uint32_t width, uint32_t height,
                                         uint32_t stride, __m256i s_x, __m256i s_y, __m256i reach,
                                         __m256i *sums) {
    const __m256i low_16 = _mm256_set1_epi32(0xFFFF), one = _mm256_set1_epi32(1);
    const __m256i column = _mm256_sub_epi32(_mm256_srli_epi32(s_x, 16), one),
                  row = _mm256_sub_epi32(_mm256_srli_epi32(s_y, 16), one);
    const __m256i across = _mm256_and_si256(s_x, low_16), down = _mm256_and_si256(s_y, low_16);
    const __m256i last_column = broadcast_8(width - 1u), last_row = broadcast_8(height - 1u);
    const __m256i left = at_most(column, last_column),
                  right = at_most(_mm256_add_epi32(column, one), last_column);
    const __m256i top = _mm256_and_si256(reach, at_most(row, last_row)),
                  bottom = _mm256_and_si256(reach, at_most(_mm256_add_epi32(row, one), last_row));
    /* Byte offset of the top-left texel (unread where it is outside). */
    const __m256i entry = _mm256_add_epi32(_mm256_mullo_epi32(row, broadcast_8(stride)), column);
    const __m256i at = Channels == 3 ? _mm256_add_epi32(_mm256_slli_epi32(entry, 1), entry) : entry;
    const __m256i below = _mm256_add_epi32(at, broadcast_8(stride * Channels));
    const int *texels = static_cast<const int *>(static_cast<const void *>(values));
    const int *next = static_cast<const int *>(static_cast<const void *>(values + Channels));
    const __m256i zero = _mm256_setzero_si256();
    const __m256i top_left = _mm256_mask_i32gather_epi32(zero, texels, at, _mm256_and_si256(top, left), 1),
                  top_right = _mm256_mask_i32gather_epi32(zero, next, at, _mm256_and_si256(top, right), 1),
                  bottom_left =
                      _mm256_mask_i32gather_epi32(zero, texels, below, _mm256_and_si256(bottom, left), 1),
                  bottom_right =
                      _mm256_mask_i32gather_epi32(zero, next, below, _mm256_and_si256(bottom, right), 1);
    for (uint32_t c = 0; c < Channels; c++) {
        const int byte = static_cast<int>(c);
        __m256i even, odd;
        bilinear_8(lane_byte(top_left, byte), lane_byte(top_right, byte), lane_byte(bottom_left, byte),
                   lane_byte(bottom_right, byte), across, down, &even, &odd);
        sums[c] = _mm256_add_epi64(sums[c], _mm256_add_epi64(even, odd));
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
DSN_POINT_INLINE void add_quad_reads_8(const uint32_t *quads, uint32_t quad_row, __m256i s_x, __m256i s_y,
                                       __m256i reach, __m256i *sums) {
    const __m256i low_16 = _mm256_set1_epi32(0xFFFF);
    const __m256i across = _mm256_and_si256(s_x, low_16), down = _mm256_and_si256(s_y, low_16);
    const __m256i at = _mm256_madd_epi16(_mm256_blend_epi16(_mm256_srli_epi32(s_x, 16), s_y, 0xAA),
                                         broadcast_8(quad_index_factors(quad_row, Channels)));
    for (uint32_t c = 0; c < Channels; c++) {
        const int *table = static_cast<const int *>(static_cast<const void *>(quads + c));
        const __m256i quad = _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), table, at, reach, 4);
        __m256i even, odd;
        bilinear_8(lane_byte(quad, 0), lane_byte(quad, 1), lane_byte(quad, 2), lane_byte(quad, 3), across,
                   down, &even, &odd);
        sums[c] = _mm256_add_epi64(sums[c], _mm256_add_epi64(even, odd));
    }
}

/* Candidates first .. first + 7 of which the first `valid` exist. */
template <uint32_t Channels>
inline void visit_point_8(PointVisit<Channels> *visit, const PointCandidates &candidates, uint32_t first,
                          uint32_t valid) {
    const __m256i fraction = mix32_8(load_8(candidates.stream + first)),
                  packed = load_8(candidates.field + first);
    __m256i bits_x, bits_y;
    impulse_bits_8(_mm256_and_si256(packed, broadcast_8(0xFF)), fraction, &bits_x, &bits_y);
    /* the cells' bases by their indices (the permutes read the low 3 bits) */
    const __m256i base_x = _mm256_permutevar8x32_epi32(visit->column_bases, _mm256_srli_epi32(packed, 8)),
                  base_y = _mm256_permutevar8x32_epi32(visit->row_bases, _mm256_srli_epi32(packed, 11));
    const __m256i s_x = _mm256_sub_epi32(base_x, _mm256_sll_epi32(bits_x, visit->shift));
    const __m256i s_y = _mm256_sub_epi32(base_y, _mm256_sll_epi32(bits_y, visit->shift));
    const __m256i exists = _mm256_cmpgt_epi32(broadcast_8(valid), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    const __m256i reach =
        _mm256_and_si256(exists, _mm256_and_si256(at_most(s_x, broadcast_8(visit->last_x)),
                                                  at_most(s_y, broadcast_8(visit->last_y))));
    if (visit->quads != 0)
        add_quad_reads_8<Channels>(visit->quads, visit->quad_row, s_x, s_y, reach, visit->sums);
    else
        add_window_reads_8<Channels>(visit->texton, visit->width, visit->height, visit->width, s_x, s_y,
                                     reach, visit->sums);
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* visit_point_8 on 512-bit vectors: candidates first .. first + 15 of which the first `valid` exist. */
inline __m512i load_16(const uint32_t *at) { return _mm512_loadu_si512(at); }
inline __m512i broadcast_16(uint32_t value) { return _mm512_set1_epi32(static_cast<int>(value)); }
inline __m512i lane_byte_16(__m512i words, unsigned int index) {
    return _mm512_srai_epi32(_mm512_slli_epi32(words, 24 - 8 * index), 24);
}

/* dsn_mix32 of every lane. */
inline __m512i mix32_16(__m512i x) {
    x = _mm512_xor_si512(x, _mm512_srli_epi32(x, 16));
    x = _mm512_mullo_epi32(x, _mm512_set1_epi32(0x7FEB352D));
    x = _mm512_xor_si512(x, _mm512_srli_epi32(x, 15));
    x = _mm512_mullo_epi32(x, _mm512_set1_epi32(-0x7B935975 /* 0x846CA68B */));
    return _mm512_xor_si512(x, _mm512_srli_epi32(x, 16));
}

/* impulse_bits_8 on 16 lanes. */
inline void impulse_bits_16(__m512i fields, __m512i fraction, __m512i *bits_x, __m512i *bits_y) {
    *bits_x = _mm512_or_si512(_mm512_slli_epi32(_mm512_and_si512(fields, _mm512_set1_epi32(15)), 12),
                              _mm512_srli_epi32(_mm512_and_si512(fraction, _mm512_set1_epi32(0xFFFF)), 4));
    *bits_y =
        _mm512_or_si512(_mm512_slli_epi32(_mm512_srli_epi32(fields, 4), 12), _mm512_srli_epi32(fraction, 20));
}

/* candidate_lanes of two pairs of 8-bit fields at once in one 128-bit vector (the first pair low), their
   top bits gathered by one movemask: bit i for impulse i of the first pair, 8 + i of the second. */
inline uint32_t sift_two_pairs(__m128i pairs, const FieldLanes &lanes, const CellAxis &x, const CellAxis &y) {
    const __m128i halves = _mm_set1_epi64x(static_cast<long long>(lanes.halves)),
                  tops = _mm_set1_epi64x(static_cast<long long>(lanes.tops));
    const __m128i halves_x = _mm_and_si128(pairs, halves),
                  halves_y = _mm_and_si128(_mm_srli_epi64(pairs, 4), halves);
    const __m128i in_x = _mm_and_si128(
        _mm_sub_epi64(_mm_or_si128(halves_x, tops), _mm_set1_epi64x(static_cast<long long>(x.low_lanes))),
        _mm_sub_epi64(_mm_set1_epi64x(static_cast<long long>(x.high_lanes)), halves_x));
    const __m128i in_y = _mm_and_si128(
        _mm_sub_epi64(_mm_or_si128(halves_y, tops), _mm_set1_epi64x(static_cast<long long>(y.low_lanes))),
        _mm_sub_epi64(_mm_set1_epi64x(static_cast<long long>(y.high_lanes)), halves_y));
    return static_cast<uint32_t>(_mm_movemask_epi8(_mm_and_si128(in_x, in_y)));
}

/* bilinear_8 on 16 lanes, the 16 values added to sum's 64-bit lanes. */
/* The rows' interpolations upper and lower (32-bit lanes) interpolated down the column, added to sum. */
DSN_POINT_INLINE void add_column_16(__m512i upper, __m512i lower, __m512i down, __m512i *sum) {
    const __m512i scale = _mm512_set1_epi32(65536);
    const __m512i difference = _mm512_sub_epi32(lower, upper);
    const __m512i even = _mm512_add_epi64(_mm512_mul_epi32(upper, scale), _mm512_mul_epi32(down, difference));
    const __m512i odd =
        _mm512_add_epi64(_mm512_mul_epi32(_mm512_srli_epi64(upper, 32), scale),
                         _mm512_mul_epi32(_mm512_srli_epi64(down, 32), _mm512_srli_epi64(difference, 32)));
    *sum = _mm512_add_epi64(*sum, _mm512_add_epi64(even, odd));
}

DSN_POINT_INLINE void add_bilinear_16(__m512i a, __m512i b, __m512i d, __m512i e, __m512i across,
                                      __m512i down, __m512i *sum) {
    add_column_16(
        _mm512_add_epi32(_mm512_slli_epi32(a, 16), _mm512_mullo_epi32(across, _mm512_sub_epi32(b, a))),
        _mm512_add_epi32(_mm512_slli_epi32(d, 16), _mm512_mullo_epi32(across, _mm512_sub_epi32(e, d))), down,
        sum);
}

/* add_bilinear_16 of quads (bytes a, b, d, e), the bytes taken and the rows' steps made in 16-bit halves:
   a and d, b and e sign-extended, then b - a and e - d (within int16). */
DSN_POINT_INLINE void add_quad_bilinear_16(__m512i quad, __m512i across, __m512i down, __m512i *sum) {
    const __m512i left = _mm512_srai_epi16(_mm512_slli_epi16(quad, 8), 8), right = _mm512_srai_epi16(quad, 8);
    const __m512i step = _mm512_sub_epi16(right, left);
    const __m512i upper =
        _mm512_add_epi32(_mm512_slli_epi32(left, 16),
                         _mm512_mullo_epi32(across, _mm512_srai_epi32(_mm512_slli_epi32(step, 16), 16)));
    const __m512i lower = _mm512_add_epi32(_mm512_and_si512(left, broadcast_16(0xFFFF0000u)),
                                           _mm512_mullo_epi32(across, _mm512_srai_epi32(step, 16)));
    add_column_16(upper, lower, down, sum);
}

/* add_quad_reads_8 on 16 lanes; 3 channels: channels 0 and 1 by 8-byte reads, 8 lanes a gather, the
   words' halves taken by permutes, and channel 2 by one gather of 16 words. */
template <uint32_t Channels>
DSN_POINT_INLINE void add_quad_reads_16(const uint32_t *quads, uint32_t quad_row, __m512i s_x, __m512i s_y,
                                        __mmask16 reach, __m512i *sums) {
    const __m512i low_16 = _mm512_set1_epi32(0xFFFF);
    const __m512i across = _mm512_and_si512(s_x, low_16), down = _mm512_and_si512(s_y, low_16);
    const __m512i at =
        _mm512_madd_epi16(_mm512_mask_blend_epi16(0xAAAAAAAAu, _mm512_srli_epi32(s_x, 16), s_y),
                          broadcast_16(quad_index_factors(quad_row, Channels)));
    const __m512i zero = _mm512_setzero_si512();
    __m512i quad[Channels];
    if (Channels == 3) {
        const __m512i lows = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30),
                      highs = _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
        /* channels 0 and 1 of candidates 0 .. 7 and 8 .. 15 */
        const __m512i low_words = _mm512_mask_i32gather_epi64(zero, static_cast<__mmask8>(reach),
                                                              _mm512_castsi512_si256(at), quads, 4);
        const __m512i high_words = _mm512_mask_i32gather_epi64(zero, static_cast<__mmask8>(reach >> 8),
                                                               _mm512_extracti64x4_epi64(at, 1), quads, 4);
        quad[Channels - 1] = _mm512_mask_i32gather_epi32(zero, reach, at, quads + 2, 4);
        quad[0] = _mm512_permutex2var_epi32(low_words, lows, high_words);
        quad[Channels - 2] = _mm512_permutex2var_epi32(low_words, highs, high_words);
    } else {
        quad[0] = _mm512_mask_i32gather_epi32(zero, reach, at, quads, 4);
    }
    for (uint32_t c = 0; c < Channels; c++) add_quad_bilinear_16(quad[c], across, down, &sums[c]);
}

/* add_window_reads_8 on 512-bit vectors: 16 candidates, those of `reach`. */
template <uint32_t Channels>
DSN_POINT_INLINE void add_window_reads_16(const unsigned char *values, uint32_t width, uint32_t height,
                                          uint32_t stride, __m512i s_x, __m512i s_y, __mmask16 reach,
                                          __m512i *sums) {
    const __m512i low_16 = _mm512_set1_epi32(0xFFFF);
    /* the texton indices of the right column and the lower row, and of the left column and upper row */
    const __m512i right_column = _mm512_srli_epi32(s_x, 16), lower_row = _mm512_srli_epi32(s_y, 16);
    const __m512i column = _mm512_sub_epi32(right_column, _mm512_set1_epi32(1)),
                  row = _mm512_sub_epi32(lower_row, _mm512_set1_epi32(1));
    const __m512i across = _mm512_and_si512(s_x, low_16), down = _mm512_and_si512(s_y, low_16);
    const __m512i last_column = broadcast_16(width - 1u), last_row = broadcast_16(height - 1u);
    const __mmask16 left = _mm512_cmple_epu32_mask(column, last_column),
                    right = _mm512_cmple_epu32_mask(right_column, last_column);
    const __mmask16 top = _mm512_mask_cmple_epu32_mask(reach, row, last_row),
                    bottom = _mm512_mask_cmple_epu32_mask(reach, lower_row, last_row);
    const __m512i entry = _mm512_add_epi32(_mm512_mullo_epi32(row, broadcast_16(stride)), column);
    const __m512i at = Channels == 3 ? _mm512_add_epi32(_mm512_slli_epi32(entry, 1), entry) : entry;
    const __m512i below = _mm512_add_epi32(at, broadcast_16(stride * Channels));
    const void *texton = values, *next = values + Channels;
    const __m512i zero = _mm512_setzero_si512();
    const __m512i top_left = _mm512_mask_i32gather_epi32(zero, top & left, at, texton, 1),
                  top_right = _mm512_mask_i32gather_epi32(zero, top & right, at, next, 1),
                  bottom_left = _mm512_mask_i32gather_epi32(zero, bottom & left, below, texton, 1),
                  bottom_right = _mm512_mask_i32gather_epi32(zero, bottom & right, below, next, 1);
    for (uint32_t c = 0; c < Channels; c++)
        add_bilinear_16(lane_byte_16(top_left, c), lane_byte_16(top_right, c), lane_byte_16(bottom_left, c),
                        lane_byte_16(bottom_right, c), across, down, &sums[c]);
}

/* add_window_reads_16 on the whole texton (the per-point visit's window): each row's two texels by one
   8-byte read from 4 bytes before the right texel, 8 lanes a gather, half the values gathered. The left
   texel's channels end at byte 3 of the read and the right one's start at byte 4: the gathered words'
   low and high halves, each zeroed where its texel is outside. The reads reach at most 4 bytes before
   the texton and 4 past it: into the asset's header (format.h: header_size >= 128) and 4-byte CRC, in the
   buffer that the loader checked (asset.cpp sets the texton there only). */
template <uint32_t Channels>
DSN_POINT_INLINE void add_texton_pairs_16(const unsigned char *texton, uint32_t width, uint32_t height,
                                          __m512i s_x, __m512i s_y, __mmask16 reach, __m512i *sums) {
    const __m512i low_16 = _mm512_set1_epi32(0xFFFF), one = _mm512_set1_epi32(1);
    const __m512i right_column = _mm512_srli_epi32(s_x, 16), lower_row = _mm512_srli_epi32(s_y, 16);
    const __m512i row = _mm512_sub_epi32(lower_row, one);
    const __m512i across = _mm512_and_si512(s_x, low_16), down = _mm512_and_si512(s_y, low_16);
    const __m512i last_column = broadcast_16(width - 1u), last_row = broadcast_16(height - 1u);
    const __mmask16 left = _mm512_cmple_epu32_mask(_mm512_sub_epi32(right_column, one), last_column),
                    right = _mm512_cmple_epu32_mask(right_column, last_column);
    /* a row is read where one of its texels is inside */
    const __mmask16 top = _mm512_mask_cmple_epu32_mask(reach & (left | right), row, last_row),
                    bottom = _mm512_mask_cmple_epu32_mask(reach & (left | right), lower_row, last_row);
    const __m512i entry = _mm512_add_epi32(_mm512_mullo_epi32(row, broadcast_16(width)), right_column);
    const __m512i at = _mm512_sub_epi32(
        Channels == 3 ? _mm512_add_epi32(_mm512_slli_epi32(entry, 1), entry) : entry, _mm512_set1_epi32(4));
    const __m512i below = _mm512_add_epi32(at, broadcast_16(width * Channels));
    const __m512i zero = _mm512_setzero_si512();
    const __m512i lows = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30),
                  highs = _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
    __m512i texels[4]; /* top left, top right, bottom left, bottom right */
    for (uint32_t pass = 0; pass < 2; pass++) {
        const __mmask16 rows = pass == 0 ? top : bottom;
        const __m512i from = pass == 0 ? at : below;
        const __m512i first = _mm512_mask_i32gather_epi64(zero, static_cast<__mmask8>(rows),
                                                          _mm512_castsi512_si256(from), texton, 1),
                      second = _mm512_mask_i32gather_epi64(zero, static_cast<__mmask8>(rows >> 8),
                                                           _mm512_extracti64x4_epi64(from, 1), texton, 1);
        texels[2 * pass] = _mm512_maskz_permutex2var_epi32(left, first, lows, second);
        texels[2 * pass + 1] = _mm512_maskz_permutex2var_epi32(right, first, highs, second);
    }
    for (uint32_t c = 0; c < Channels; c++)
        add_bilinear_16(lane_byte_16(texels[0], 4u - Channels + c), lane_byte_16(texels[1], c),
                        lane_byte_16(texels[2], 4u - Channels + c), lane_byte_16(texels[3], c), across, down,
                        &sums[c]);
}

template <uint32_t Channels>
DSN_POINT_INLINE void visit_point_16(PointVisit<Channels> *visit, const PointCandidates &candidates,
                                     uint32_t first, uint32_t valid) {
    const __m512i fraction = mix32_16(load_16(candidates.stream + first));
    const __m512i packed = load_16(candidates.field + first);
    /* impulse_bits_16, each axis's field bits selected into bits 12 .. 15 (0xEC: A & C | B) */
    const __m512i field_bits = broadcast_16(0xF000);
    const __m512i bits_x =
        _mm512_ternarylogic_epi32(_mm512_slli_epi32(packed, 12),
                                  _mm512_srli_epi32(_mm512_slli_epi32(fraction, 16), 20), field_bits, 0xEC);
    const __m512i bits_y = _mm512_ternarylogic_epi32(_mm512_slli_epi32(packed, 8),
                                                     _mm512_srli_epi32(fraction, 20), field_bits, 0xEC);
    /* the cells' bases by their indices (the permutes read the low 4 bits: the bases twice) */
    const __m512i column_bases = _mm512_broadcast_i64x4(visit->column_bases),
                  row_bases = _mm512_broadcast_i64x4(visit->row_bases);
    const __m512i base_x = _mm512_permutexvar_epi32(_mm512_srli_epi32(packed, 8), column_bases),
                  base_y = _mm512_permutexvar_epi32(_mm512_srli_epi32(packed, 11), row_bases);
    const __m512i s_x = _mm512_sub_epi32(base_x, _mm512_sll_epi32(bits_x, visit->shift));
    const __m512i s_y = _mm512_sub_epi32(base_y, _mm512_sll_epi32(bits_y, visit->shift));
    const __mmask16 exists = static_cast<__mmask16>(valid >= 16u ? 0xFFFFu : (1u << valid) - 1u);
    const __mmask16 reach =
        _mm512_mask_cmple_epu32_mask(_mm512_mask_cmple_epu32_mask(exists, s_x, broadcast_16(visit->last_x)),
                                     s_y, broadcast_16(visit->last_y));
    if (visit->quads != 0)
        add_quad_reads_16<Channels>(visit->quads, visit->quad_row, s_x, s_y, reach, visit->wide_sums);
    else
        add_texton_pairs_16<Channels>(visit->texton, visit->width, visit->height, s_x, s_y, reach,
                                      visit->wide_sums);
}
#endif

/* Visits the buffered candidates and empties the buffer. */
template <uint32_t Channels>
inline void visit_point_candidates(PointVisit<Channels> *visit, PointCandidates *candidates) {
    const uint32_t count = candidates->count;
    /* The lanes past the last candidate hold zeros (defined values; the count leaves them out). */
    const __m256i zero = _mm256_setzero_si256();
    for (uint32_t pad = count; pad < count + point_vector_lanes; pad += 8u) {
        store_8(candidates->stream + pad, zero), store_8(candidates->field + pad, zero);
    }
    uint32_t first = 0;
#if defined(__AVX512F__) && defined(__AVX512BW__)
    for (; first + 8u < count; first += 16u)
        visit_point_16<Channels>(visit, *candidates, first, count - first);
#endif
    for (; first < count; first += 8u) visit_point_8<Channels>(visit, *candidates, first, count - first);
    candidates->count = 0;
}

/* Buffers the candidates `sifted` (bit i: lane i) of the pair `pair` that holds impulses first .. first + 7
   of the cell with this key; indices: the cell's (cell_indices). */
inline void add_sifted_pair(PointCandidates *candidates, uint32_t key, uint32_t first, uint64_t pair,
                            uint32_t sifted, uint32_t indices) {
    __m256i streams, fields;
    /* dsn_cell_stream(key, 2^31 + k) of impulse k = first + lane */
    const uint32_t packed =
        pack_pair_8(pair, sifted, key + (0x80000000u + first) * 0x9E3779B9u, &streams, &fields);
    const uint32_t slot = candidates->count;
    store_8(candidates->stream + slot, streams);
    store_8(candidates->field + slot, _mm256_or_si256(fields, broadcast_8(indices)));
    candidates->count = slot + packed;
}

/* Buffers the candidates of the pair that holds impulses first .. first + 7 of the cell with this key,
   whose impulses are `count` (none when count <= first); indices: the cell's (cell_indices). */
inline void add_pair(PointCandidates *candidates, uint32_t key, uint32_t first, uint32_t count,
                     const FieldLanes &lanes, const CellAxis &x, const CellAxis &y, uint32_t indices) {
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
    __m512i guide[4], cdf[2];
};

inline bool count_tables_fit(const dsn_noise_state *noise) {
    return noise->poisson_parts == 1 && noise->poisson_guide[63] <= 29u &&
           sizeof noise->poisson_cdf / sizeof noise->poisson_cdf[0] >= 32u;
}

inline void count_tables(const dsn_noise_state *noise, CountTables *tables) {
    for (uint32_t q = 0; q < 4; q++)
        tables->guide[q] = _mm512_cvtepu8_epi32(_mm_loadu_si128(
            static_cast<const __m128i *>(static_cast<const void *>(noise->poisson_guide + 16 * q))));
    tables->cdf[0] = _mm512_loadu_si512(noise->poisson_cdf);
    tables->cdf[1] = _mm512_loadu_si512(noise->poisson_cdf + 16);
}

/* dsn_poisson_count_two_steps of 16 keys (count_tables_fit), the guide and thresholds read by permutes;
   the rare lanes that need the exact search take dsn_poisson_draw. */
inline __m512i counts_16(const dsn_noise_state *noise, const CountTables &tables, __m512i keys) {
    const __m512i bucket = _mm512_srli_epi32(keys, 26), one = _mm512_set1_epi32(1);
    __m512i n = _mm512_mask_blend_epi32(_mm512_cmpge_epu32_mask(bucket, _mm512_set1_epi32(32)),
                                        _mm512_permutex2var_epi32(tables.guide[0], bucket, tables.guide[1]),
                                        _mm512_permutex2var_epi32(tables.guide[2], bucket, tables.guide[3]));
    for (uint32_t step = 0; step < 2; step++)
        n = _mm512_mask_add_epi32(
            n, _mm512_cmpge_epu32_mask(keys, _mm512_permutex2var_epi32(tables.cdf[0], n, tables.cdf[1])), n,
            one);
    const __m512i size = broadcast_16(noise->poisson_size);
    const __mmask16 search =
        _mm512_cmpgt_epu32_mask(n, size) |
        _mm512_mask_cmpge_epu32_mask(_mm512_cmplt_epu32_mask(n, size), keys,
                                     _mm512_permutex2var_epi32(tables.cdf[0], n, tables.cdf[1]));
    if (search == 0) return n;
    uint32_t lanes[16], uniforms[16];
    _mm512_storeu_si512(lanes, n), _mm512_storeu_si512(uniforms, keys);
    for (uint32_t k = 0; k < 16; k++)
        if ((search >> k) & 1u) lanes[k] = dsn_poisson_draw(noise, uniforms[k]);
    return _mm512_loadu_si512(lanes);
}

/* The candidates `sifted` (bit k: impulse k) of a cell's first two pairs (`pairs`, the first low)
   compressed into place; indices: the cell's (cell_indices). */
inline void add_sifted_pairs(PointCandidates *candidates, uint32_t key, __m128i pairs, uint32_t sifted,
                             uint32_t indices) {
    /* dsn_cell_stream(key, 2^31 + k) of impulse k */
    const __m512i streams = _mm512_add_epi32(
        _mm512_set1_epi32(static_cast<int>(key + 0x80000000u * 0x9E3779B9u)),
        _mm512_mullo_epi32(_mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
                           _mm512_set1_epi32(-0x61C88647 /* 0x9E3779B9 */)));
    const __mmask16 keep = static_cast<__mmask16>(sifted);
    const uint32_t slot = candidates->count;
    _mm512_storeu_si512(candidates->stream + slot, _mm512_maskz_compress_epi32(keep, streams));
    _mm512_storeu_si512(candidates->field + slot,
                        _mm512_maskz_compress_epi32(
                            keep, _mm512_or_si512(_mm512_cvtepu8_epi32(pairs), broadcast_16(indices))));
    candidates->count = slot + mask_count(sifted);
}

/* add_pair for the cell's first two pairs at once (impulses 0 .. 15): the sifting of both pairs in one
   128-bit vector (candidate_lanes), their top bits gathered by one movemask, and the candidates
   compressed into place. */
inline void add_first_pairs(PointCandidates *candidates, uint32_t key, uint32_t count,
                            const FieldLanes &lanes, const CellAxis &x, const CellAxis &y, uint32_t indices) {
    const __m128i pairs = _mm_set_epi64x(static_cast<long long>(dsn_position_pair(key, 1)),
                                         static_cast<long long>(dsn_position_pair(key, 0)));
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

/* False when there are more than point_vector_cells. */
DSN_POINT_INLINE bool axis_cells(const PointAxis &point, const FieldLanes &lanes, AxisCells *cells) {
    cells->count = 0;
    for (uint32_t s = 0; s < point.axis.span_count; s++) {
        const dsn_span span = dsn_axis_span(&point.axis, s);
        for (uint32_t i = 0; i < span.cell_count; i++) {
            const uint32_t cell = dsn_span_cell(&span, i, point.axis.shift), at = cells->count;
            CellAxis axis;
            if (!cell_axis(point, span, cell, lanes, &axis)) continue;
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
DSN_POINT_INLINE bool point_cells(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                  const FieldLanes &lanes, AxisCells *columns, AxisCells *rows) {
    const uint32_t shift = noise->cell_shift;
    return axis_cells(point_axis(x, noise->radius[0], shift, noise->period[0]), lanes, columns) &&
           axis_cells(point_axis(y, noise->radius[1], shift, noise->period[1]), lanes, rows);
}

/* The visit of a point, its sums zero, given the bases of its column and row cells by their indices
   (AxisCells's base); quads: the batch's table (PointVisit), or null. */
template <uint32_t Channels>
DSN_POINT_INLINE void point_visit_begin(const dsn_noise_state *noise, __m256i column_bases, __m256i row_bases,
                                        const uint32_t *quads, PointVisit<Channels> *visit) {
    visit->texton = noise->asset.texton;
    visit->quads = quads;
    visit->width = noise->asset.width, visit->height = noise->asset.height;
    visit->quad_row = (noise->asset.width + 1u) * Channels;
    visit->last_x = ((2u * noise->radius[0] + 2u) << 16) - 1u;
    visit->last_y = ((2u * noise->radius[1] + 2u) << 16) - 1u;
    visit->shift = _mm_cvtsi32_si128(static_cast<int>(noise->cell_shift));
    visit->column_bases = column_bases, visit->row_bases = row_bases;
    for (uint32_t c = 0; c < Channels; c++) {
        visit->sums[c] = _mm256_setzero_si256();
#if defined(__AVX512F__) && defined(__AVX512BW__)
        visit->wide_sums[c] = _mm512_setzero_si512();
#endif
    }
}

/* point_visit_begin for the point whose cells are columns x rows. */
template <uint32_t Channels>
DSN_POINT_INLINE void point_visit_start(const dsn_noise_state *noise, const AxisCells &columns,
                                        const AxisCells &rows, const uint32_t *quads,
                                        PointVisit<Channels> *visit) {
    /* the bases past the axes' cells are not read (masked: defined values) */
    const __m256i indices = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    point_visit_begin<Channels>(
        noise,
        _mm256_maskload_epi32(static_cast<const int *>(static_cast<const void *>(columns.base)),
                              _mm256_cmpgt_epi32(broadcast_8(columns.count), indices)),
        _mm256_maskload_epi32(static_cast<const int *>(static_cast<const void *>(rows.base)),
                              _mm256_cmpgt_epi32(broadcast_8(rows.count), indices)),
        quads, visit);
}

/* Buffers the candidates of a cell's pairs from impulse 16 on (cells of more than 16 impulses), visiting
   the buffer whenever a pair might not fit. */
template <uint32_t Channels>
DSN_POINT_INLINE void add_later_pairs(PointVisit<Channels> *visit, PointCandidates *candidates, uint32_t key,
                                      uint32_t count, const FieldLanes &lanes, const CellAxis &x,
                                      const CellAxis &y, uint32_t indices) {
    for (uint32_t first = 16; first < count; first += 8u) {
        if (candidates->count > point_vector_slots - 8u) visit_point_candidates<Channels>(visit, candidates);
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

/* Visits the candidates left and writes the point's values. */
template <uint32_t Channels>
DSN_POINT_INLINE void point_visit_finish(const dsn_noise_state *noise, PointVisit<Channels> *visit,
                                         PointCandidates *candidates, int32_t *out) {
    uint64_t sums[Channels];
    point_visit_sums<Channels>(visit, candidates, sums, 1);
    normalize_q32(noise, sums, out);
}

/* The point's values from its cells, with the key and impulse count of the cell (columns i, rows j) at
   index j row_step + i column_step of keys and counts; quads: the batch's table (PointVisit), or null. */
template <uint32_t Channels>
DSN_POINT_INLINE void point_vector_sum(const dsn_noise_state *noise, const FieldLanes &lanes,
                                       const AxisCells &columns, const AxisCells &rows, const uint32_t *keys,
                                       const uint32_t *counts, uint32_t row_step, uint32_t column_step,
                                       const uint32_t *quads, int32_t *out) {
    PointVisit<Channels> visit;
    point_visit_start<Channels>(noise, columns, rows, quads, &visit);
    PointCandidates candidates;
    candidates.count = 0;
    for (uint32_t j = 0; j < rows.count; j++) {
        for (uint32_t i = 0; i < columns.count; i++) {
            const uint32_t key = keys[j * row_step + i * column_step],
                           count = counts[j * row_step + i * column_step];
            /* The first two pairs whether the cell has impulses there or not: a branch on the count
               would often be mispredicted. The rest (cells of more than 16 impulses) one by one. */
            if (candidates.count > point_vector_slots - 16u)
                visit_point_candidates<Channels>(&visit, &candidates);
#if defined(__AVX512F__) && defined(__AVX512BW__)
            add_first_pairs(&candidates, key, count, lanes, columns.axis[i], rows.axis[j],
                            cell_indices(i, j));
#else
            add_pair(&candidates, key, 0, count, lanes, columns.axis[i], rows.axis[j], cell_indices(i, j));
            add_pair(&candidates, key, 8, count, lanes, columns.axis[i], rows.axis[j], cell_indices(i, j));
#endif
            add_later_pairs<Channels>(&visit, &candidates, key, count, lanes, columns.axis[i], rows.axis[j],
                                      cell_indices(i, j));
        }
    }
    point_visit_finish<Channels>(noise, &visit, &candidates, out);
}

template <uint32_t Channels>
int point_vector(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out) {
    const FieldLanes lanes = field_lanes(noise->cell_shift);
    AxisCells columns, rows;
    if (!point_cells(noise, x, y, lanes, &columns, &rows)) return 0;
    /* The keys and counts of all the cells first: the counts' chains of dependent loads then overlap. */
    uint32_t keys[point_vector_cells * point_vector_cells], counts[point_vector_cells * point_vector_cells];
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
    point_vector_sum<Channels>(noise, lanes, columns, rows, keys, counts, columns.count, 1, 0, out);
    return 1;
}

/* The kernel entry, one copy per channel count; 0 for a noise it does not take, or a point with more
   than point_vector_cells cells along an axis. */
inline int continuous_point_vector(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out) {
    if (!point_vector_takes(noise)) return 0;
    return noise->asset.channels == 3 ? point_vector<3>(noise, x, y, out) : point_vector<1>(noise, x, y, out);
}

} // namespace
#endif /* __AVX2__ */

#endif /* DSN_CONTINUOUS_POINT_VECTOR_H */
