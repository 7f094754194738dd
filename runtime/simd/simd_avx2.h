/* runtime/simd/simd_avx2.h - the vector operations of the strip path for AVX2 (256-bit vectors: 16 pixels per
   strip), and of the continuous splat's runs (splat_row.h: 4 pixels per vector). The same names as
   simd_sse2.h and simd_avx512.h; simd.h picks one. */
#ifndef DSN_SIMD_AVX2_H
#define DSN_SIMD_AVX2_H

#include "simd/simd_256.h"

namespace {

typedef vector_256 simd_vector; /* 16-bit sums, or 32-bit values, of the strip's pixels */
typedef floats_256 simd_floats;
const uint32_t simd_int16_count = 16;

/* ---- Sums ---- */
inline simd_vector load_texels(const uint16_t *src) {
    return _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(src)));
}
inline simd_vector add_16(simd_vector a, simd_vector b) { return _mm256_add_epi16(a, b); }
inline simd_vector zero_vector() { return _mm256_setzero_si256(); }
inline void store_16(uint16_t *dst, simd_vector value) {
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(dst)), value);
}
inline simd_vector subtract_16(simd_vector a, simd_vector b) { return _mm256_sub_epi16(a, b); }
/* Every channel's two rows from one load, as in simd_avx512.h (tile_strips.h): each 16-bit texel of a
   paired plane holds row t in its low byte and row t + 1 in its high byte, both biased by 128
   (unsigned); row_0 adds the texels as they are, row_1 their high bytes shifted down, and finish_pair
   takes row_1 256 times off row_0 once per strip (modulo 2^16, exact: the true sums fit). Three loads
   and nine operations per entry instead of five loads and eight operations (or two more multiplies,
   vpmaddubsw, to widen each byte). */
#define DSN_SIMD_PAIRED_ROWS 1
inline void add_pair(simd_vector texels, simd_vector *row_0, simd_vector *row_1) {
    /* One register for both uses: GCC would fold the load into the add and the shift. */
    __asm__("" : "+x"(texels));
    *row_0 = _mm256_add_epi16(*row_0, texels);
    *row_1 = _mm256_add_epi16(*row_1, _mm256_srli_epi16(texels, 8));
}
inline void finish_pair(simd_vector *row_0, simd_vector row_1) {
    *row_0 = _mm256_sub_epi16(*row_0, _mm256_slli_epi16(row_1, 8));
}

/* ---- Normalization, per 128-bit lane (AVX2 unpacks and shuffles each lane on its own; madd_16, add_32,
   as_floats, as_integers and shuffle: simd_256.h) ---- */
inline simd_vector broadcast_lanes(__m128i value) { return _mm256_broadcastsi128_si256(value); }
inline simd_vector shift_right_15(simd_vector a) { return _mm256_srai_epi32(a, 15); }
inline simd_vector shift_right(simd_vector a, __m128i count) { return _mm256_sra_epi32(a, count); }
inline simd_vector unpack_low_16(simd_vector a, simd_vector b) { return _mm256_unpacklo_epi16(a, b); }
inline simd_vector unpack_high_16(simd_vector a, simd_vector b) { return _mm256_unpackhi_epi16(a, b); }
inline simd_vector unpack_low_32(simd_vector a, simd_vector b) { return _mm256_unpacklo_epi32(a, b); }
inline simd_vector unpack_high_32(simd_vector a, simd_vector b) { return _mm256_unpackhi_epi32(a, b); }
inline simd_vector set_16(int16_t value) { return _mm256_set1_epi16(value); }

/* ---- Output ---- */
/* 128-bit lane `part` of a vector: pixels 8 part .. 8 part + 7 of a normalized strip. */
inline __m128i lane_128(simd_vector v, uint32_t part) {
    return part == 0 ? _mm256_castsi256_si128(v) : _mm256_extracti128_si256(v, 1);
}

/* A whole strip's normalized vectors (4 values per 128-bit lane, see tile_store.h) in output order:
   pixels 0-7 are the low lanes of vectors 0 .. 2 Channels - 1, pixels 8-15 the high lanes, so pairs of
   vectors trade lanes. */
template <uint32_t Channels>
inline void output_order(const simd_vector *values, simd_vector *ordered) {
    for (uint32_t i = 0; i < Channels; i++) {
        ordered[i] = _mm256_permute2x128_si256(values[2 * i], values[2 * i + 1], 0x20);
        ordered[Channels + i] = _mm256_permute2x128_si256(values[2 * i], values[2 * i + 1], 0x31);
    }
}
inline simd_floats to_output_floats(simd_vector fixed) {
    return _mm256_mul_ps(_mm256_cvtepi32_ps(fixed), _mm256_set1_ps(1.0f / 65536.0f));
}
/* 8 output values (streamed strips go out 16 bytes at a time instead, tile_store.h). */
inline void put_vector(int32_t *out, simd_vector values) {
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(out)), values);
}
inline void put_vector(float *out, simd_floats values) { _mm256_storeu_ps(out, values); }
/* to_u8_range (simd_128.h) on 8 values. */
inline __m256i to_u8_range(__m256i value) {
    value = _mm256_min_epi32(_mm256_max_epi32(value, _mm256_setzero_si256()), _mm256_set1_epi32(DSN_ONE));
    return _mm256_srli_epi32(
        _mm256_add_epi32(_mm256_sub_epi32(_mm256_slli_epi32(value, 8), value), _mm256_set1_epi32(32768)), 16);
}

/* 8-bit output of a whole strip (16 pixels), packed like the 128-bit path per lane: 16 + 8 bytes (RGB)
   or 8 bytes (grey) of each lane, brought together by qword permutes. Returns 1. */
template <uint32_t Channels>
inline int store_whole_strip_u8(const simd_vector *values, uint8_t *out) {
    if (Channels == 3) {
        /* first: bytes 0-15 of pixels 0-7 (qwords F0 F1), then of pixels 8-15 (F2 F3); second: bytes
           16-23 of pixels 0-7 (S0) twice, then of pixels 8-15 (S2) twice. Out: F0 F1 S0 F2 | F3 S2. */
        const __m256i first =
            _mm256_packus_epi16(_mm256_packs_epi32(to_u8_range(values[0]), to_u8_range(values[1])),
                                _mm256_packs_epi32(to_u8_range(values[2]), to_u8_range(values[3])));
        const __m256i words = _mm256_packs_epi32(to_u8_range(values[4]), to_u8_range(values[5]));
        const __m256i second = _mm256_packus_epi16(words, words);
        const __m256i low = _mm256_blend_epi32(_mm256_permute4x64_epi64(first, _MM_SHUFFLE(2, 0, 1, 0)),
                                               _mm256_permute4x64_epi64(second, 0), 0x30);
        _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(out)), low);
        _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(out + 32)),
                         _mm256_extracti128_si256(_mm256_unpackhi_epi64(first, second), 1));
    } else {
        const __m256i words = _mm256_packs_epi32(to_u8_range(values[0]), to_u8_range(values[1]));
        const __m256i bytes = _mm256_packus_epi16(words, words);
        _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(out)),
                         _mm256_castsi256_si128(_mm256_permute4x64_epi64(bytes, _MM_SHUFFLE(3, 1, 2, 0))));
    }
    return 1;
}

/* ---- Continuous splat (splat_row.h): 64-bit lanes, one pixel each ---- */
typedef __m256i splat_vector;
const uint32_t splat_lanes = 4;

inline splat_vector splat_set(uint64_t value) { return _mm256_set1_epi64x(static_cast<long long>(value)); }
/* Lane k: first + k step, modulo 2^64. */
inline splat_vector splat_lane_steps(uint64_t first, uint64_t step) {
    return _mm256_set_epi64x(static_cast<long long>(first + 3u * step),
                             static_cast<long long>(first + 2u * step), static_cast<long long>(first + step),
                             static_cast<long long>(first));
}
inline splat_vector splat_add(splat_vector a, splat_vector b) { return _mm256_add_epi64(a, b); }
inline void splat_store(uint64_t *out, splat_vector value) {
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(out)), value);
}
inline splat_vector splat_load(const uint64_t *from) {
    return _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(from)));
}
inline splat_vector splat_sub(splat_vector a, splat_vector b) { return _mm256_sub_epi64(a, b); }
inline splat_vector splat_and(splat_vector a, splat_vector b) { return _mm256_and_si256(a, b); }
inline splat_vector splat_or(splat_vector a, splat_vector b) { return _mm256_or_si256(a, b); }
inline splat_vector splat_shift_right(splat_vector value, uint32_t count) {
    return _mm256_srl_epi64(value, _mm_cvtsi32_si128(static_cast<int>(count)));
}
inline splat_vector splat_shift_left(splat_vector value, uint32_t count) {
    return _mm256_sll_epi64(value, _mm_cvtsi32_si128(static_cast<int>(count)));
}
/* The first `count` lanes (all of them from splat_lanes up), the others 0. */
inline splat_vector splat_first_lanes(splat_vector value, uint32_t count) {
    return _mm256_and_si256(value,
                            _mm256_cmpgt_epi64(_mm256_set1_epi64x(count), _mm256_setr_epi64x(0, 1, 2, 3)));
}
/* The bilinear weight of each lane: its bits 24 to 31, as bits 8 to 15 (continuous_internal.h). */
inline splat_vector splat_weight(splat_vector value) {
    return _mm256_and_si256(_mm256_srli_epi64(value, 16), _mm256_set1_epi64x(0xFF00));
}
/* The words (-32768, a - 32768, -32768, a - 32768) of each lane, a the lane's weight (bits 24 to 31, as 8 to
   15): byte 3 of the lane into the high bytes of words 1 and 3, then the top bit of every word flipped. */
inline splat_vector splat_across_weights(splat_vector value) {
    return _mm256_xor_si256(_mm256_shuffle_epi8(value, _mm256_broadcastsi128_si256(splat_across_order())),
                            _mm256_set1_epi16(-32768));
}
/* (lane >> 32) times factor, modulo 2^64. */
inline splat_vector splat_whole_times(splat_vector value, uint32_t factor) {
    return _mm256_mul_epu32(_mm256_srli_epi64(value, 32), _mm256_set1_epi64x(factor));
}
/* One RGB cell (4 records). */
inline __m256i splat_load_cell(const uint64_t *cell) {
    return _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(cell)));
}
/* The records of `Channels` channels of the cells at cells[index[k]] (splat_cells.h: one record per
   channel, 4 per cell for RGB): records[c] holds channel c of each lane's cell, a 4 x 4 transpose. */
template <uint32_t Channels>
inline void splat_load_cells(const uint64_t *cells, const uint64_t *index, splat_vector *records) {
    if (Channels == 1) {
        records[0] = _mm256_set_epi64x(
            static_cast<long long>(cells[index[3]]), static_cast<long long>(cells[index[2]]),
            static_cast<long long>(cells[index[1]]), static_cast<long long>(cells[index[0]]));
        return;
    }
    const __m256i cell_0 = splat_load_cell(cells + index[0]), cell_1 = splat_load_cell(cells + index[1]);
    const __m256i cell_2 = splat_load_cell(cells + index[2]), cell_3 = splat_load_cell(cells + index[3]);
    const __m256i even_01 = _mm256_unpacklo_epi64(cell_0, cell_1),
                  odd_01 = _mm256_unpackhi_epi64(cell_0, cell_1);
    const __m256i even_23 = _mm256_unpacklo_epi64(cell_2, cell_3),
                  odd_23 = _mm256_unpackhi_epi64(cell_2, cell_3);
    records[0] = _mm256_permute2x128_si256(even_01, even_23, 0x20);
    records[1] = _mm256_permute2x128_si256(odd_01, odd_23, 0x20);
    records[Channels - 1] = _mm256_permute2x128_si256(even_01, even_23, 0x31);
}
/* splat_cells.h's multiply-add: each lane's dwords (low, high) become upper and lower - upper. */
inline splat_vector splat_rows(splat_vector records, splat_vector across) {
    return _mm256_madd_epi16(records, across);
}
/* The low dword of each lane, signed, times the low dword of factor's (below 2^31). */
inline splat_vector splat_signed_times(splat_vector value, splat_vector factor) {
    return _mm256_mul_epi32(value, factor);
}
/* The low dword of each lane, unsigned, times the low dword of factor's (unsigned). */
inline splat_vector splat_low_times(splat_vector value, splat_vector factor) {
    return _mm256_mul_epu32(value, factor);
}
/* Lane k of values[c] saturated to int32 into out[k * Channels + c], for k < splat_lanes: clamped by 64-bit
   comparisons, the low dwords gathered, then interleaved by permutes and blends (no store of lanes read
   back one by one). */
#define DSN_SPLAT_STORE_PIXELS 1
inline __m256i splat_saturated_dwords(__m256i value) { /* dwords 0-3 and again 4-7 */
    const __m256i most = _mm256_set1_epi64x(INT32_MAX), least = _mm256_set1_epi64x(INT32_MIN);
    const __m256i below = _mm256_blendv_epi8(value, most, _mm256_cmpgt_epi64(value, most));
    const __m256i clamped = _mm256_blendv_epi8(below, least, _mm256_cmpgt_epi64(least, below));
    return _mm256_permutevar8x32_epi32(clamped, _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6));
}
template <uint32_t Channels>
inline void splat_store_pixels(int32_t *out, const splat_vector *values) {
    const __m256i first = splat_saturated_dwords(values[0]);
    if (Channels == 1) {
        _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(out)), _mm256_castsi256_si128(first));
        return;
    }
    /* two: channel 0 in dwords 0-3, channel 1 in 4-7; three: channel 2 in 0-3 and 4-7 */
    const __m256i two = _mm256_blend_epi32(first, splat_saturated_dwords(values[1]), 0xF0);
    const __m256i three = splat_saturated_dwords(values[Channels - 1]);
    const __m256i low = _mm256_blend_epi32(
        _mm256_permutevar8x32_epi32(two, _mm256_setr_epi32(0, 4, 0, 1, 5, 0, 2, 6)),
        _mm256_permutevar8x32_epi32(three, _mm256_setr_epi32(0, 0, 0, 0, 0, 1, 0, 0)), 0x24);
    const __m256i high = _mm256_blend_epi32(
        _mm256_permutevar8x32_epi32(two, _mm256_setr_epi32(0, 3, 7, 0, 0, 0, 0, 0)),
        _mm256_permutevar8x32_epi32(three, _mm256_setr_epi32(2, 0, 0, 3, 0, 0, 0, 0)), 0x09);
    _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(out)), low);
    _mm_storeu_si128(static_cast<__m128i *>(static_cast<void *>(out + 8)), _mm256_castsi256_si128(high));
}
/* Adds the first `count` lanes (all of them from splat_lanes up) to sums[0 ..], where sums up to `end`
   may be read and written back. Where a whole vector fits, the other lanes add 0 (a masked store is
   many times slower on AMD's CPUs). */
inline void splat_accumulate(uint64_t *sums, splat_vector values, uint32_t count, const uint64_t *end) {
    long long *at = static_cast<long long *>(static_cast<void *>(sums));
    __m256i *run = static_cast<__m256i *>(static_cast<void *>(sums));
    if (count >= 4) {
        _mm256_storeu_si256(run, _mm256_add_epi64(_mm256_loadu_si256(run), values));
        return;
    }
    const __m256i present = _mm256_cmpgt_epi64(_mm256_set1_epi64x(count), _mm256_setr_epi64x(0, 1, 2, 3));
    if (end - sums >= 4)
        _mm256_storeu_si256(run,
                            _mm256_add_epi64(_mm256_loadu_si256(run), _mm256_and_si256(values, present)));
    else
        _mm256_maskstore_epi64(at, present, _mm256_add_epi64(_mm256_maskload_epi64(at, present), values));
}

} // namespace

#endif /* DSN_SIMD_AVX2_H */
