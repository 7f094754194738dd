/* runtime/kernels/filtered_candidates_vector.h - the listing of the filtered sift's candidates
   (filtered_sift.cpp) on AVX2 vectors, as a kernel (kernels.h: the AVX2 and AVX-512 kernels include it), for
   cells of side
   <= 16 (pairs of 8 impulses): each pair sifted on its packed lattice fields against the taps' box
   (continuous_sift.h) and its candidates packed to the front of a vector (continuous_lanes.h, as the
   continuous evaluator's), then their fraction hash and 16-bit positions in 32-bit lanes, their shifted
   offsets in 64-bit lanes (where the caller reads them) and those offsets / 2^16 in 32-bit lanes, 8
   stored at once (AVX-512: two pairs at once, hashed and placed on all 16 lanes while the sift runs, and
   only what is stored compressed). Only the
   sift bounds them: a candidate may lie up to a texel beyond the box, which the level tests, exact for any
   offset of that size, leave out as the walk does. Internal to libdsn; not installed (everything here has
   internal linkage). */
#ifndef DSN_FILTERED_CANDIDATES_VECTOR_H
#define DSN_FILTERED_CANDIDATES_VECTOR_H

#include "core/cell_hash.h"
#include "core/continuous_sift.h"
#include "kernels/continuous_lanes.h"
#include "kernels/continuous_point_vector.h"
#include "kernels/kernels.h"

#if defined(__AVX2__) && DSN_FILTERING && !DSN_SMALL_CODE
namespace {

/* A shifted_base / 2^16 modulo 2^32, as a lane: the narrow offsets are it less the 16-bit positions times
   2^cell_shift (the offset's low 16 bits are the same for every impulse of an axis: its shifted_base's). */
inline int narrow_base(int64_t shifted_base) {
    return static_cast<int>(static_cast<uint32_t>(static_cast<uint64_t>(shifted_base) >> 16));
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* shifted_base - bits 2^position_shift for the 16 candidates of `bits` (32-bit lanes), in order. */
inline void store_shifted_16(int64_t *at, __m512i base, __m512i bits, __m128i position_shift) {
    const __m512i low = _mm512_sll_epi64(_mm512_cvtepu32_epi64(_mm512_castsi512_si256(bits)), position_shift),
                  high = _mm512_sll_epi64(_mm512_cvtepu32_epi64(_mm512_extracti64x4_epi64(bits, 1)),
                                          position_shift);
    _mm512_storeu_si512(at, _mm512_sub_epi64(base, low));
    _mm512_storeu_si512(at + 8, _mm512_sub_epi64(base, high));
}

/* kernels.h's filter_candidates, two pairs at a time (impulses first .. first + 15 of a cell), on 512-bit
   vectors: both sifted in one 128-bit vector (sift_two_pairs) and their candidates compressed to the front.
   Wide: xs, ys are written (a loop of its own without them: fewer live registers). */
template <bool Wide>
uint32_t listed_candidates(const dsn_filter_cell *cells, uint32_t cell_count, uint32_t cell_shift,
                           uint32_t count, int64_t *xs, int64_t *ys, uint32_t *narrow_xs, uint32_t *narrow_ys,
                           uint32_t *ends) {
    const FieldLanes lanes = field_lanes(cell_shift);
    const __m128i position_shift = _mm_cvtsi32_si128(static_cast<int>(16u + cell_shift)),
                  cell_shift_vector = _mm_cvtsi32_si128(static_cast<int>(cell_shift));
    /* lane * 0x9E3779B9 modulo 2^32 */
    const __m512i weyl =
        _mm512_mullo_epi32(_mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
                           _mm512_set1_epi32(-0x61C88647 /* 0x9E3779B9 */));
    for (uint32_t k = 0; k < cell_count; k++) {
        const dsn_filter_cell &cell = cells[k];
        const __m512i base_x = _mm512_set1_epi64(static_cast<long long>(cell.x.shifted_base)),
                      base_y = _mm512_set1_epi64(static_cast<long long>(cell.y.shifted_base));
        const __m512i narrow_base_x = _mm512_set1_epi32(narrow_base(cell.x.shifted_base)),
                      narrow_base_y = _mm512_set1_epi32(narrow_base(cell.y.shifted_base));
        for (uint32_t first = 0; first < cell.count; first += 16u) {
            const __m128i pairs =
                _mm_set_epi64x(static_cast<long long>(dsn_position_pair(cell.key, (first >> 3) + 1u)),
                               static_cast<long long>(dsn_position_pair(cell.key, first >> 3)));
            uint32_t sifted = sift_two_pairs(pairs, lanes, cell.x, cell.y);
            if (cell.count - first < 16u)
                sifted &= (1u << (cell.count - first)) - 1u; /* impulses that do not exist */
            const __mmask16 keep = static_cast<__mmask16>(sifted);
            /* dsn_cell_stream(key, 2^31 + k) of impulse k = first + lane */
            const __m512i streams = _mm512_add_epi32(
                _mm512_set1_epi32(static_cast<int>(cell.key + (0x80000000u + first) * 0x9E3779B9u)), weyl);
            /* hashed and placed before the sift's mask is known (lanewise: the same values), off its
               chain; then only what is stored is compressed */
            __m512i bits_x, bits_y;
            impulse_bits_16(_mm512_cvtepu8_epi32(pairs), mix32_16(streams), &bits_x, &bits_y);
            const __m512i narrow_x =
                              _mm512_sub_epi32(narrow_base_x, _mm512_sll_epi32(bits_x, cell_shift_vector)),
                          narrow_y =
                              _mm512_sub_epi32(narrow_base_y, _mm512_sll_epi32(bits_y, cell_shift_vector));
            if (Wide) {
                store_shifted_16(xs + count, base_x, _mm512_maskz_compress_epi32(keep, bits_x),
                                 position_shift);
                store_shifted_16(ys + count, base_y, _mm512_maskz_compress_epi32(keep, bits_y),
                                 position_shift);
            }
            _mm512_storeu_si512(narrow_xs + count, _mm512_maskz_compress_epi32(keep, narrow_x));
            _mm512_storeu_si512(narrow_ys + count, _mm512_maskz_compress_epi32(keep, narrow_y));
            count += mask_count(sifted);
        }
        ends[k] = count;
    }
    return count;
}

uint32_t filter_candidates(const dsn_filter_cell *cells, uint32_t cell_count, uint32_t cell_shift,
                           uint32_t count, int64_t *xs, int64_t *ys, uint32_t *narrow_xs, uint32_t *narrow_ys,
                           uint32_t *ends) {
    return xs != 0 ? listed_candidates<true>(cells, cell_count, cell_shift, count, xs, ys, narrow_xs,
                                             narrow_ys, ends)
                   : listed_candidates<false>(cells, cell_count, cell_shift, count, xs, ys, narrow_xs,
                                              narrow_ys, ends);
}
#else
/* shifted_base - bits 2^position_shift for the 8 candidates of `bits` (32-bit lanes), in order. */
inline void store_shifted(int64_t *at, __m256i base, __m256i bits, __m128i position_shift) {
    const __m256i low = _mm256_sll_epi64(_mm256_cvtepu32_epi64(_mm256_castsi256_si128(bits)), position_shift),
                  high = _mm256_sll_epi64(_mm256_cvtepu32_epi64(_mm256_extracti128_si256(bits, 1)),
                                          position_shift);
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(at)), _mm256_sub_epi64(base, low));
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(at + 4)), _mm256_sub_epi64(base, high));
}

/* kernels.h's filter_candidates, a pair at a time. */
uint32_t filter_candidates(const dsn_filter_cell *cells, uint32_t cell_count, uint32_t cell_shift,
                           uint32_t count, int64_t *xs, int64_t *ys, uint32_t *narrow_xs, uint32_t *narrow_ys,
                           uint32_t *ends) {
    const FieldLanes lanes = field_lanes(cell_shift);
    const __m128i position_shift = _mm_cvtsi32_si128(static_cast<int>(16u + cell_shift)),
                  cell_shift_vector = _mm_cvtsi32_si128(static_cast<int>(cell_shift));
    for (uint32_t k = 0; k < cell_count; k++) {
        const dsn_filter_cell &cell = cells[k];
        const __m256i base_x = _mm256_set1_epi64x(static_cast<long long>(cell.x.shifted_base)),
                      base_y = _mm256_set1_epi64x(static_cast<long long>(cell.y.shifted_base));
        const __m256i narrow_base_x = _mm256_set1_epi32(narrow_base(cell.x.shifted_base)),
                      narrow_base_y = _mm256_set1_epi32(narrow_base(cell.y.shifted_base));
        for (uint32_t first = 0; first < cell.count; first += 8u) {
            const uint64_t pair = dsn_position_pair(cell.key, first >> 3);
            const uint32_t present = cell.count - first < 8u ? cell.count - first : 8u;
            const uint32_t sifted =
                gather_lanes(candidate_lanes(pair, lanes, cell.x, cell.y), lanes) & ((1u << present) - 1u);
            __m256i streams, fields;
            /* dsn_cell_stream(key, 2^31 + k) of impulse k = first + lane */
            const uint32_t packed =
                pack_pair_8(pair, sifted, cell.key + (0x80000000u + first) * 0x9E3779B9u, &streams, &fields);
            const __m256i fraction = mix32_8(streams);
            __m256i bits_x, bits_y;
            impulse_bits_8(fields, fraction, &bits_x, &bits_y);
            if (xs != 0) {
                store_shifted(xs + count, base_x, bits_x, position_shift);
                store_shifted(ys + count, base_y, bits_y, position_shift);
            }
            store_8x32(narrow_xs + count,
                       _mm256_sub_epi32(narrow_base_x, _mm256_sll_epi32(bits_x, cell_shift_vector)));
            store_8x32(narrow_ys + count,
                       _mm256_sub_epi32(narrow_base_y, _mm256_sll_epi32(bits_y, cell_shift_vector)));
            count += packed;
        }
        ends[k] = count;
    }
    return count;
}

#endif

} // namespace
/* The kernel entry (kernels.h): null where there is none. */
#define DSN_FILTER_CANDIDATES_ENTRY filter_candidates
#else
#define DSN_FILTER_CANDIDATES_ENTRY 0
#endif

#endif /* DSN_FILTERED_CANDIDATES_VECTOR_H */
