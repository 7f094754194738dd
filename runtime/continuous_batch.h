/* runtime/continuous_batch.h - the continuous mode on a batch of arbitrary points, as a kernel
   (kernels.h): each kernel file includes it, so it is built once per instruction set. Internal to libdsn;
   not installed (everything here has internal linkage).

   The same sums as the per-point evaluator (continuous_point.cpp), reorganized so that the work across
   points runs on vectors. A chunk of points is evaluated in two passes:
     1. per point, its cells are walked and their impulses sifted on the packed lattice fields
        (continuous_sift.h), as per point; every lane of a pair is written to the candidate arrays and
        the count moves only for the lanes that may reach the point (no branch per impulse);
     2. per candidate: the fraction hash, the 16-bit position, the exact reach test and the bilinear
        texton of every channel, read from a table of the 2 x 2 texels at every position of the texton
        bordered by zeros (so that texels outside the window need no test), added to the point's 64-bit
        sums; on AVX2 (the AVX2 and AVX-512 kernels) 8 candidates at a time on vectors, else one by one.
   The sums are then normalized (normalize_q32). The same impulses, offsets, weights and integers as per
   point; integer sums modulo 2^64 do not depend on the order, so the bits are the per-point ones. */
#ifndef DSN_CONTINUOUS_BATCH_H
#define DSN_CONTINUOUS_BATCH_H

#include "continuous_internal.h"
#include "continuous_sift.h"
#include "kernels.h"
#include "simd.h" /* <immintrin.h> on AVX2 and AVX-512 (simd_avx512.h includes it past a GCC 12 false warning) */

namespace {

const uint32_t batch_chunk_points = 32; /* points whose sums are kept at once */
const uint32_t batch_candidates = 1024; /* candidate slots between two visits (passes 2 and 3) */
const uint32_t batch_lane_block = 16;   /* candidates per block of pass 2 */
/* The candidate arrays and the chunk's sums, each array 64 bytes past a multiple of 4 KB from the
   previous one: arrays 4 KB apart would make their loads wait on each other's stores (4K aliasing). */
const uint32_t batch_array_gap = 64;
const uint32_t batch_work_bytes =
    batch_candidates * (3u * 4u + 2u * 8u) + batch_chunk_points * DSN_MAX_CHANNELS * 8u + 6u * batch_array_gap;

/* The texton as the batch reads it, built by continuous_batch.cpp once per call: for every position
   (row, column) of the texton bordered by one zero texel all around, rows and columns 0 .. height and
   0 .. width, and every channel, the 2 x 2 texels that a bilinear read there needs, so that one load
   (8-bit values: the bytes top-left, top-right, bottom-left, bottom-right of one int32) or two (16-bit:
   top-left | top-right << 16, then the bottom row) give them all, with no test at the window's edge. */
inline uint32_t batch_quad_words(uint32_t bits) { return bits == 8 ? 1u : 2u; }
inline size_t batch_quad_count(const dsn_asset *asset) {
    return static_cast<size_t>(asset->height + 1u) * (asset->width + 1u) * asset->channels *
           batch_quad_words(asset->bits);
}

/* The work arrays, carved from 64-byte aligned memory. A slot holds a candidate (an impulse of a pair
   the sift kept, or a lane the count does not keep, overwritten next): its fraction hash input, its
   packed lattice field halves shifted to the top of 16-bit positions (x low, y high), its point, and
   its cell's shifted bases (bracket's shifted value of an impulse at the cell's origin). */
struct BatchArrays {
    uint32_t *stream, *highs, *point;
    uint64_t *base_x, *base_y;
    uint64_t *sums; /* the chunk's points */
};

inline BatchArrays batch_arrays(void *work) {
    BatchArrays arrays;
    unsigned char *bytes = static_cast<unsigned char *>(work);
    arrays.base_x = static_cast<uint64_t *>(static_cast<void *>(bytes));
    arrays.base_y = arrays.base_x + batch_candidates + batch_array_gap / 8u;
    arrays.sums = arrays.base_y + batch_candidates + batch_array_gap / 8u;
    arrays.stream = static_cast<uint32_t *>(static_cast<void *>(
        arrays.sums + batch_chunk_points * DSN_MAX_CHANNELS + batch_array_gap / 8u));
    arrays.highs = arrays.stream + batch_candidates + batch_array_gap / 4u;
    arrays.point = arrays.highs + batch_candidates + batch_array_gap / 4u;
    return arrays;
}

/* What every candidate of a visit shares. */
struct BatchConstants {
    uint32_t half_shift, position_shift;
    uint64_t limit_x, limit_y; /* in reach: 0 < shifted < limit + 1 */
    uint32_t quad_row;         /* quads per row of positions: (width + 1) channels words */
};

inline BatchConstants batch_constants(const dsn_noise_state *noise) {
    BatchConstants constants;
    constants.half_shift = field_lanes(noise->cell_shift).half_bits;
    constants.position_shift = 16u + noise->cell_shift;
    constants.limit_x = static_cast<uint64_t>(2u * noise->radius[0] + 2u) * one_texel - 1u;
    constants.limit_y = static_cast<uint64_t>(2u * noise->radius[1] + 2u) * one_texel - 1u;
    constants.quad_row = (noise->asset.width + 1u) * noise->asset.channels * batch_quad_words(noise->asset.bits);
    return constants;
}

/* A quad's 8-bit value at byte `index` (0 .. 3), sign-extended without implementation-defined shifts. */
inline int32_t quad_byte(uint32_t quad, uint32_t index) {
    return static_cast<int32_t>(((quad >> (8u * index)) & 0xFFu) ^ 0x80u) - 128;
}
inline int32_t quad_half(uint32_t word, uint32_t index) {
    return static_cast<int32_t>(((word >> (16u * index)) & 0xFFFFu) ^ 0x8000u) - 32768;
}

/* Candidates [first, end) one at a time, each in reach adding its bilinear texton to its point's sums
   (kept in registers while the point does not change: a point's candidates are consecutive). */
template <uint32_t Channels, uint32_t Bytes>
void batch_visit_scalar(const uint32_t *quads, const BatchConstants &k, const BatchArrays &arrays, uint32_t first,
                        uint32_t end) {
    uint64_t sums[Channels];
    for (uint32_t c = 0; c < Channels; c++) sums[c] = 0;
    uint32_t point = first < end ? arrays.point[first] : 0u;
    for (uint32_t slot = first; slot < end; slot++) {
        const uint32_t fraction = dsn_mix32(arrays.stream[slot]), highs = arrays.highs[slot];
        /* dsn_impulse_hash's 16-bit positions, then bracket's shifted values */
        const uint32_t bits_x = (highs & 0xFFFFu) | ((fraction & 0xFFFFu) >> k.half_shift);
        const uint32_t bits_y = (highs >> 16) | ((fraction >> 16) >> k.half_shift);
        const uint64_t shifted_x = arrays.base_x[slot] - (static_cast<uint64_t>(bits_x) << k.position_shift);
        const uint64_t shifted_y = arrays.base_y[slot] - (static_cast<uint64_t>(bits_y) << k.position_shift);
        if (shifted_x - 1u > k.limit_x - 1u || shifted_y - 1u > k.limit_y - 1u) continue;
        if (arrays.point[slot] != point) {
            for (uint32_t c = 0; c < Channels; c++) arrays.sums[point * Channels + c] += sums[c], sums[c] = 0;
            point = arrays.point[slot];
        }
        /* The bordered position is the texton's lower index plus 1: bracket's shifted >> 32. */
        const uint32_t at = static_cast<uint32_t>(shifted_y >> 32) * k.quad_row +
                            static_cast<uint32_t>(shifted_x >> 32) * Channels * (Bytes == 1 ? 1u : 2u);
        const int64_t across = static_cast<int64_t>((shifted_x >> 16) & 0xFFFFu);
        const int64_t down = static_cast<int64_t>((shifted_y >> 16) & 0xFFFFu);
        for (uint32_t c = 0; c < Channels; c++) {
            int64_t top_left, top_right, bottom_left, bottom_right;
            if (Bytes == 1) {
                const uint32_t quad = quads[at + c];
                top_left = quad_byte(quad, 0), top_right = quad_byte(quad, 1);
                bottom_left = quad_byte(quad, 2), bottom_right = quad_byte(quad, 3);
            } else {
                const uint32_t top = quads[at + 2u * c], bottom = quads[at + 2u * c + 1u];
                top_left = quad_half(top, 0), top_right = quad_half(top, 1);
                bottom_left = quad_half(bottom, 0), bottom_right = quad_half(bottom, 1);
            }
            /* add_bilinear's integer with one product per step: (65536 - w) a + w b = 65536 a + w (b - a). */
            const int64_t upper = top_left * 65536 + across * (top_right - top_left);
            const int64_t lower = bottom_left * 65536 + across * (bottom_right - bottom_left);
            sums[c] += static_cast<uint64_t>(upper * 65536 + down * (lower - upper));
        }
    }
    for (uint32_t c = 0; c < Channels; c++) arrays.sums[point * Channels + c] += sums[c];
}

#if defined(__AVX2__)
/* ---- Pass 2 on AVX2 vectors (the AVX2 and AVX-512 kernels), 8-bit textons: 8 candidates at a time ----
   The same integers as batch_visit_scalar: the hash in 32-bit lanes, the shifted values in 64-bit lanes,
   the texels by one gather of quads per channel (a lane out of reach reads quad 0, its values zeroed), the rows' interpolation in 32-bit lanes (below 2^25)
   and the column's in 64-bit lanes (_mm256_mul_epi32, signed 32 x 32 -> 64 bits, exact). */

/* The low 32 bits of the 64-bit lanes of a (candidates 0-3) and b (4-7), as 8 lanes in order. */
inline __m256i low_halves(__m256i a, __m256i b) {
    const __m256 mixed = _mm256_shuffle_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), 0x88);
    return _mm256_permute4x64_epi64(_mm256_castps_si256(mixed), 0xD8);
}

/* a < b as unsigned 64-bit lanes (AVX2 compares signed: both flipped by 2^63). */
inline __m256i below_64(__m256i a, __m256i b) {
    const __m256i sign = _mm256_set1_epi64x(static_cast<long long>(0x8000000000000000u));
    return _mm256_cmpgt_epi64(_mm256_xor_si256(b, sign), _mm256_xor_si256(a, sign));
}

inline __m256i load_8(const uint32_t *at) { return _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(at))); }
inline __m256i load_4(const uint64_t *at) { return _mm256_loadu_si256(static_cast<const __m256i *>(static_cast<const void *>(at))); }

/* One axis of 8 candidates: shifted = base - (bits << position_shift) in 64-bit lanes (candidates 0-3,
   4-7), whether 0 < shifted <= limit, and the 32-bit lanes of shifted >> 32 and (shifted >> 16) & 0xFFFF. */
inline void axis_8(__m256i bits, const uint64_t *base, __m128i position_shift, __m256i limit, __m256i *reaches,
                   __m256i *whole, __m256i *weight) {
    const __m256i one = _mm256_set1_epi64x(1);
    const __m256i low = _mm256_sub_epi64(load_4(base), _mm256_sll_epi64(_mm256_cvtepu32_epi64(_mm256_castsi256_si128(bits)), position_shift));
    const __m256i high = _mm256_sub_epi64(load_4(base + 4), _mm256_sll_epi64(_mm256_cvtepu32_epi64(_mm256_extracti128_si256(bits, 1)), position_shift));
    *reaches = low_halves(below_64(_mm256_sub_epi64(low, one), limit), below_64(_mm256_sub_epi64(high, one), limit));
    *whole = low_halves(_mm256_srli_epi64(low, 32), _mm256_srli_epi64(high, 32));
    *weight = _mm256_and_si256(low_halves(_mm256_srli_epi64(low, 16), _mm256_srli_epi64(high, 16)), _mm256_set1_epi32(0xFFFF));
}

inline __m256i mix32_8(__m256i x) {
    x = _mm256_xor_si256(x, _mm256_srli_epi32(x, 16));
    x = _mm256_mullo_epi32(x, _mm256_set1_epi32(0x7FEB352D));
    x = _mm256_xor_si256(x, _mm256_srli_epi32(x, 15));
    x = _mm256_mullo_epi32(x, _mm256_set1_epi32(-0x7B935975 /* 0x846CA68B */));
    return _mm256_xor_si256(x, _mm256_srli_epi32(x, 16));
}

/* The running sums of one point on vectors: the channels' 64-bit values of the even and odd
   candidates, summed lane by lane (modulo 2^64, so in any order). */
struct VectorSums {
    __m256i channel[DSN_MAX_CHANNELS];
    uint32_t point;
};

template <uint32_t Channels>
inline void flush_vector_sums(VectorSums *running, const BatchArrays &arrays) {
    for (uint32_t c = 0; c < Channels; c++) {
        uint64_t lanes[4];
        _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(lanes)), running->channel[c]);
        arrays.sums[running->point * Channels + c] += lanes[0] + lanes[1] + lanes[2] + lanes[3];
        running->channel[c] = _mm256_setzero_si256();
    }
}

/* Candidates first .. first + 7. A lane out of reach reads quad 0 and its values are zeroed. When the 8
   belong to one point (a point's candidates are consecutive, so the first and last tell) they go to the
   running sums; otherwise those are flushed and the lanes added one by one. */
template <uint32_t Channels>
void batch_visit_8(const uint32_t *quads, const BatchConstants &k, const BatchArrays &arrays, uint32_t first,
                   VectorSums *running) {
    const __m256i fraction = mix32_8(load_8(arrays.stream + first)), highs = load_8(arrays.highs + first);
    const __m128i half_shift = _mm_cvtsi32_si128(static_cast<int>(k.half_shift));
    const __m128i position_shift = _mm_cvtsi32_si128(static_cast<int>(k.position_shift));
    const __m256i low_16 = _mm256_set1_epi32(0xFFFF);
    const __m256i bits_x = _mm256_or_si256(_mm256_and_si256(highs, low_16), _mm256_srl_epi32(_mm256_and_si256(fraction, low_16), half_shift));
    const __m256i bits_y = _mm256_or_si256(_mm256_srli_epi32(highs, 16), _mm256_srl_epi32(_mm256_srli_epi32(fraction, 16), half_shift));
    __m256i reaches_x, column, across, reaches_y, row, down;
    axis_8(bits_x, arrays.base_x + first, position_shift, _mm256_set1_epi64x(static_cast<long long>(k.limit_x)), &reaches_x, &column, &across);
    axis_8(bits_y, arrays.base_y + first, position_shift, _mm256_set1_epi64x(static_cast<long long>(k.limit_y)), &reaches_y, &row, &down);
    const __m256i reaches = _mm256_and_si256(reaches_x, reaches_y);
    const __m256i at = _mm256_and_si256(reaches, _mm256_add_epi32(_mm256_mullo_epi32(row, _mm256_set1_epi32(static_cast<int>(k.quad_row))),
                                                                  _mm256_mullo_epi32(column, _mm256_set1_epi32(static_cast<int>(Channels)))));
    /* The reach of the even and odd lanes as 64-bit masks. */
    const __m256i reaches_even = _mm256_shuffle_epi32(reaches, 0xA0), reaches_odd = _mm256_shuffle_epi32(reaches, 0xF5);
    const uint32_t first_point = arrays.point[first], last_point = arrays.point[first + 7u];
    const bool one_point = first_point == last_point;
    if (!one_point || first_point != running->point) {
        flush_vector_sums<Channels>(running, arrays);
        running->point = one_point ? first_point : last_point;
    }
    const __m256i scale = _mm256_set1_epi32(65536);
    for (uint32_t c = 0; c < Channels; c++) {
        const __m256i quad = _mm256_i32gather_epi32(static_cast<const int *>(static_cast<const void *>(quads + c)), at, 4);
        const __m256i top_left = _mm256_srai_epi32(_mm256_slli_epi32(quad, 24), 24), top_right = _mm256_srai_epi32(_mm256_slli_epi32(quad, 16), 24);
        const __m256i bottom_left = _mm256_srai_epi32(_mm256_slli_epi32(quad, 8), 24), bottom_right = _mm256_srai_epi32(quad, 24);
        const __m256i upper = _mm256_add_epi32(_mm256_slli_epi32(top_left, 16), _mm256_mullo_epi32(across, _mm256_sub_epi32(top_right, top_left)));
        const __m256i lower = _mm256_add_epi32(_mm256_slli_epi32(bottom_left, 16), _mm256_mullo_epi32(across, _mm256_sub_epi32(bottom_right, bottom_left)));
        const __m256i difference = _mm256_sub_epi32(lower, upper);
        const __m256i even = _mm256_and_si256(reaches_even, _mm256_add_epi64(_mm256_mul_epi32(upper, scale), _mm256_mul_epi32(down, difference)));
        const __m256i odd = _mm256_and_si256(reaches_odd, _mm256_add_epi64(_mm256_mul_epi32(_mm256_srli_epi64(upper, 32), scale),
                                             _mm256_mul_epi32(_mm256_srli_epi64(down, 32), _mm256_srli_epi64(difference, 32))));
        if (one_point) {
            running->channel[c] = _mm256_add_epi64(running->channel[c], _mm256_add_epi64(even, odd));
            continue;
        }
        uint64_t even_values[4], odd_values[4]; /* candidates 0, 2, 4, 6 and 1, 3, 5, 7 */
        _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(even_values)), even);
        _mm256_storeu_si256(static_cast<__m256i *>(static_cast<void *>(odd_values)), odd);
        for (uint32_t j = 0; j < 4; j++) {
            arrays.sums[arrays.point[first + 2u * j] * Channels + c] += even_values[j];
            arrays.sums[arrays.point[first + 2u * j + 1u] * Channels + c] += odd_values[j];
        }
    }
}
#endif

/* Passes 2 and 3 over candidates [0, count). */
template <uint32_t Channels, uint32_t Bytes>
void batch_visit(const dsn_noise_state *noise, const uint32_t *quads, const BatchArrays &arrays, uint32_t count) {
    const BatchConstants constants = batch_constants(noise);
    uint32_t slot = 0;
#if defined(__AVX2__)
    if (Bytes == 1 && count >= 8u) {
        VectorSums running;
        running.point = arrays.point[0];
        for (uint32_t c = 0; c < Channels; c++) running.channel[c] = _mm256_setzero_si256();
        for (; slot + 8u <= count; slot += 8u) batch_visit_8<Channels>(quads, constants, arrays, slot, &running);
        flush_vector_sums<Channels>(&running, arrays);
    }
#endif
    batch_visit_scalar<Channels, Bytes>(quads, constants, arrays, slot, count);
}

/* What the slots of one pair share. */
struct PairCell {
    uint64_t base_x, base_y;
    uint32_t point;
};

/* Writes every lane of a pair of PerPair fields (8 of 8 bits, or 4 of 16) to the slots from `count`,
   keeping those of `candidates` (bit i: lane i): returns the new count. */
template <uint32_t PerPair>
inline uint32_t batch_emit_pair(const BatchArrays &arrays, uint32_t count, uint64_t pair, uint32_t candidates,
                                uint32_t stream, const PairCell &cell) {
    const uint32_t field_bits = 64u / PerPair, half_bits = field_bits / 2u, half_mask = (1u << half_bits) - 1u;
    uint32_t *stream_slots = arrays.stream, *highs_slots = arrays.highs, *point_slots = arrays.point;
    uint64_t *base_x_slots = arrays.base_x, *base_y_slots = arrays.base_y;
    for (uint32_t in_pair = 0; in_pair < PerPair; in_pair++) {
        const uint32_t field = dsn_pair_bits(pair, in_pair * field_bits);
        stream_slots[count] = stream + in_pair * 0x9E3779B9u;
        /* The field's halves at the top of 16-bit positions: x low, y high. */
        highs_slots[count] = ((field & half_mask) << (16u - half_bits)) |
                             (((field >> half_bits) & half_mask) << (32u - half_bits));
        base_x_slots[count] = cell.base_x;
        base_y_slots[count] = cell.base_y;
        point_slots[count] = cell.point;
        count += (candidates >> in_pair) & 1u;
    }
    return count;
}

/* Pass 1 for one point (index `point` of the chunk): appends its candidates, visiting the arrays first
   whenever a pair might not fit. Returns the new candidate count. */
template <uint32_t Channels, uint32_t Bytes>
uint32_t batch_sift_point(const dsn_noise_state *noise, const uint32_t *quads, const FieldLanes &lanes,
                          const BatchArrays &arrays, uint32_t count, uint32_t point, uint64_t x, uint64_t y) {
    const uint32_t shift = noise->cell_shift;
    const PointAxis px = point_axis(x, noise->radius[0], shift, noise->period[0]);
    const PointAxis py = point_axis(y, noise->radius[1], shift, noise->period[1]);
    for (uint32_t sy = 0; sy < py.axis.span_count; sy++) {
        const dsn_span span_y = dsn_axis_span(&py.axis, sy);
        for (uint32_t j = 0; j < span_y.cell_count; j++) {
            const uint32_t cell_y = dsn_span_cell(&span_y, j, shift);
            CellAxis in_y;
            if (!cell_axis(py, span_y, cell_y, lanes, &in_y)) continue;
            const uint32_t row_key = dsn_row_key(noise, cell_y);
            for (uint32_t sx = 0; sx < px.axis.span_count; sx++) {
                const dsn_span span_x = dsn_axis_span(&px.axis, sx);
                for (uint32_t i = 0; i < span_x.cell_count; i++) {
                    const uint32_t cell_x = dsn_span_cell(&span_x, i, shift);
                    CellAxis in_x;
                    if (!cell_axis(px, span_x, cell_x, lanes, &in_x)) continue;
                    const uint32_t key = dsn_cell_key_in_row(noise, cell_x, row_key);
                    const uint32_t impulses = dsn_cell_impulse_count(noise, key);
                    for (uint32_t first = 0; first < impulses; first += lanes.per_pair) {
                        if (count + lanes.per_pair > batch_candidates) {
                            batch_visit<Channels, Bytes>(noise, quads, arrays, count);
                            count = 0;
                        }
                        const uint64_t pair = dsn_position_pair(key, first >> (6u - lanes.field_shift));
                        uint32_t candidates = gather_lanes(candidate_lanes(pair, lanes, in_x, in_y), lanes);
                        const uint32_t present = impulses - first;
                        if (present < lanes.per_pair) candidates &= (1u << present) - 1u;
                        /* dsn_cell_stream(key, 2^31 + k) of impulse k = first + slot */
                        const uint32_t stream = key + (0x80000000u + first) * 0x9E3779B9u;
                        const PairCell cell = {static_cast<uint64_t>(in_x.shifted_base),
                                               static_cast<uint64_t>(in_y.shifted_base), point};
                        count = lanes.per_pair == 8u
                                    ? batch_emit_pair<8>(arrays, count, pair, candidates, stream, cell)
                                    : batch_emit_pair<4>(arrays, count, pair, candidates, stream, cell);
                    }
                }
            }
        }
    }
    return count;
}

template <uint32_t Channels, uint32_t Bytes>
void batch_points(const dsn_noise_state *noise, const uint32_t *quads, const int64_t *xs, const int64_t *ys,
                  uint32_t count, int32_t *out, void *work) {
    const BatchArrays arrays = batch_arrays(work);
    const FieldLanes lanes = field_lanes(noise->cell_shift);
    for (uint32_t first = 0; first < count; first += batch_chunk_points) {
        const uint32_t points = count - first < batch_chunk_points ? count - first : batch_chunk_points;
        for (uint32_t k = 0; k < batch_chunk_points * Channels; k++) arrays.sums[k] = 0;
        uint32_t candidates = 0;
        for (uint32_t p = 0; p < points; p++)
            candidates = batch_sift_point<Channels, Bytes>(noise, quads, lanes, arrays, candidates, p,
                                                           static_cast<uint64_t>(xs[first + p]),
                                                           static_cast<uint64_t>(ys[first + p]));
        batch_visit<Channels, Bytes>(noise, quads, arrays, candidates);
        for (uint32_t p = 0; p < points; p++)
            normalize_q32(noise, arrays.sums + p * Channels, out + static_cast<size_t>(first + p) * Channels);
    }
}

/* The kernel entry: one copy per channel count and value size. */
inline void continuous_batch(const dsn_noise_state *noise, const uint32_t *quads, const int64_t *xs, const int64_t *ys,
                      uint32_t count, int32_t *out, void *work) {
    const dsn_asset *asset = &noise->asset;
    if (asset->channels == 3)
        asset->bits == 8 ? batch_points<3, 1>(noise, quads, xs, ys, count, out, work)
                         : batch_points<3, 2>(noise, quads, xs, ys, count, out, work);
    else
        asset->bits == 8 ? batch_points<1, 1>(noise, quads, xs, ys, count, out, work)
                         : batch_points<1, 2>(noise, quads, xs, ys, count, out, work);
}

} // namespace

#endif /* DSN_CONTINUOUS_BATCH_H */
