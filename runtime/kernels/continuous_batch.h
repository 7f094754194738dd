/* runtime/kernels/continuous_batch.h - the continuous mode on a batch of arbitrary points, as a kernel
   (kernels.h): each kernel file includes it, so it is built once per instruction set. Internal to libdsn;
   not installed (everything here has internal linkage).

   With AVX2, the noises that the kernel's vector per-point evaluator takes (continuous_point_vector.h:
   8-bit textons, the usual densities) go through its code 8 points at a time (continuous_batch_group.h),
   which is faster there, reading the texton from the quad table below. The others:
   the same sums as the per-point evaluator (continuous_point.cpp), reorganized so that the work across
   points runs on vectors. A chunk of points is evaluated in two passes:
     1. per point, its cells are walked and their impulses sifted on the packed lattice fields
        (continuous_sift.h), as per point; every lane of a pair is written to the candidate arrays and
        the count moves only for the lanes that may reach the point (no branch per impulse);
     2. per candidate: the fraction hash, the 16-bit position, the exact reach test and the bilinear
        texton of every channel, read from a table of the 2 x 2 texels at every position of the texton
        bordered by zeros (so that texels outside the window need no test), added to the point's 64-bit
        sums; 8 candidates at a time on AVX2 vectors (8-bit textons), else one by one.
   The sums are then normalized (normalize_q32). The same impulses, offsets, weights and integers as per
   point; integer sums modulo 2^64 do not depend on the order, so the bits are the per-point ones.
   The batch's gradients (batch_gradients) take the groups where the values do, else go point by point. */
#ifndef DSN_CONTINUOUS_BATCH_H
#define DSN_CONTINUOUS_BATCH_H

#include "core/continuous_internal.h"
#include "core/continuous_sift.h"
#include "kernels/continuous_batch_group.h"
#include "kernels/continuous_lanes.h"
#include "kernels/continuous_point_vector.h"
#include "kernels/kernels.h"
#include "simd/simd.h" /* <immintrin.h> on AVX2 and AVX-512 (simd_avx512.h includes it past a GCC 12 false warning) */

namespace {

const uint32_t batch_chunk_points = 32; /* points whose sums are kept at once */
const uint32_t batch_candidates = 1024; /* candidate slots between two visits (pass 2) */
const uint32_t batch_cells = 512;       /* cells between two visits */
/* The arrays (candidates, cells, the chunk's sums), each 64 bytes past a multiple of 4 KB from the
   previous one: arrays 4 KB apart would make their loads wait on each other's stores (4K aliasing). */
const uint32_t batch_array_gap = 64;
const uint32_t batch_work_bytes = batch_candidates * 2u * 4u + batch_cells * (2u * 8u + 4u) +
                                  batch_chunk_points * DSN_MAX_CHANNELS * 8u + 6u * batch_array_gap;

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
   the sift kept, or a lane the count does not keep, overwritten next): its fraction hash input and its
   packed lattice field (16 bits) with its cell's index in the cell arrays (16 bits above). A cell holds
   its point and its shifted bases (bracket's shifted value of an impulse at the cell's origin). */
struct BatchArrays {
    uint32_t *stream, *packed;
    uint64_t *base_x, *base_y;
    uint32_t *point;
    uint64_t *sums; /* the chunk's points */
};

inline BatchArrays batch_arrays(void *work) {
    BatchArrays arrays;
    unsigned char *bytes = static_cast<unsigned char *>(work);
    const uint32_t gap_64 = batch_array_gap / 8u, gap_32 = batch_array_gap / 4u;
    arrays.base_x = static_cast<uint64_t *>(static_cast<void *>(bytes));
    arrays.base_y = arrays.base_x + batch_cells + gap_64;
    arrays.sums = arrays.base_y + batch_cells + gap_64;
    arrays.stream = static_cast<uint32_t *>(
        static_cast<void *>(arrays.sums + batch_chunk_points * DSN_MAX_CHANNELS + gap_64));
    arrays.packed = arrays.stream + batch_candidates + gap_32;
    arrays.point = arrays.packed + batch_candidates + gap_32;
    return arrays;
}

/* How full the arrays are. */
struct BatchFill {
    uint32_t slots, cells;
};

/* What every candidate of a visit shares. */
struct BatchConstants {
    uint32_t half_shift, half_mask, high_shift, position_shift;
    uint64_t limit_x, limit_y; /* in reach: 0 < shifted < limit + 1 */
    uint32_t quad_row;         /* quads per row of positions: (width + 1) channels words */
};

inline BatchConstants batch_constants(const dsn_noise_state *noise) {
    BatchConstants constants;
    constants.half_shift = field_lanes(noise->cell_shift).half_bits;
    constants.half_mask = (1u << constants.half_shift) - 1u;
    constants.high_shift = 16u - constants.half_shift;
    constants.position_shift = 16u + noise->cell_shift;
    constants.limit_x = static_cast<uint64_t>(2u * noise->radius[0] + 2u) * one_texel - 1u;
    constants.limit_y = static_cast<uint64_t>(2u * noise->radius[1] + 2u) * one_texel - 1u;
    constants.quad_row =
        (noise->asset.width + 1u) * noise->asset.channels * batch_quad_words(noise->asset.bits);
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
void batch_visit_scalar(const uint32_t *quads, const BatchConstants &k, const BatchArrays &arrays,
                        uint32_t first, uint32_t end) {
    uint64_t sums[Channels];
    for (uint32_t c = 0; c < Channels; c++) sums[c] = 0;
    uint32_t point = first < end ? arrays.point[arrays.packed[first] >> 16] : 0u;
    for (uint32_t slot = first; slot < end; slot++) {
        const uint32_t fraction = dsn_mix32(arrays.stream[slot]), packed = arrays.packed[slot];
        const uint32_t cell = packed >> 16;
        /* dsn_impulse_hash's 16-bit positions, then bracket's shifted values */
        const uint32_t bits_x =
            ((packed & k.half_mask) << k.high_shift) | ((fraction & 0xFFFFu) >> k.half_shift);
        const uint32_t bits_y =
            (((packed >> k.half_shift) & k.half_mask) << k.high_shift) | ((fraction >> 16) >> k.half_shift);
        const uint64_t shifted_x = arrays.base_x[cell] - (static_cast<uint64_t>(bits_x) << k.position_shift);
        const uint64_t shifted_y = arrays.base_y[cell] - (static_cast<uint64_t>(bits_y) << k.position_shift);
        if (shifted_x - 1u > k.limit_x - 1u || shifted_y - 1u > k.limit_y - 1u) continue;
        if (arrays.point[cell] != point) {
            for (uint32_t c = 0; c < Channels; c++) arrays.sums[point * Channels + c] += sums[c], sums[c] = 0;
            point = arrays.point[cell];
        }
        /* The bordered position is the texton's lower index plus 1: bracket's shifted >> 32. */
        const uint32_t at = static_cast<uint32_t>(shifted_y >> 32) * k.quad_row +
                            static_cast<uint32_t>(shifted_x >> 32) * Channels * (Bytes == 1 ? 1u : 2u);
        const int64_t across = static_cast<int64_t>((shifted_x >> 16) & bilinear_weight_mask);
        const int64_t down = static_cast<int64_t>((shifted_y >> 16) & bilinear_weight_mask);
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
   the texels by one gather of quads per channel (a lane out of reach reads quad 0, its values zeroed), the
   rows' interpolation in 32-bit lanes (below 2^25) and the column's in 64-bit lanes (multiply_even_32, signed
   32 x 32 -> 64 bits, exact). */

/* One axis of 8 candidates: shifted = base - (bits << position_shift) in 64-bit lanes (candidates 0-3,
   4-7), whether 0 < shifted <= limit, and the 32-bit lanes of shifted >> 32 and the bilinear weight (shifted
   >> 16) & bilinear_weight_mask. */
inline void axis_8(vector_256 bits, const uint64_t *bases, vector_256 cells, vector_128 position_shift,
                   vector_256 limit, vector_256 *reaches, vector_256 *whole, vector_256 *weight) {
    const vector_256 one = set_4x64(1);
    const vector_256 low = subtract_64(gather_64<8>(bases, low_128(cells)),
                                       shift_left_64_by(widen_unsigned_32x64(low_128(bits)), position_shift));
    const vector_256 high =
        subtract_64(gather_64<8>(bases, high_128(cells)),
                    shift_left_64_by(widen_unsigned_32x64(high_128(bits)), position_shift));
    *reaches = low_halves(below_64(subtract_64(low, one), limit), below_64(subtract_64(high, one), limit));
    *whole = low_halves(shift_right_logical_64(low, 32), shift_right_logical_64(high, 32));
    *weight = bitwise_and(low_halves(shift_right_logical_64(low, 16), shift_right_logical_64(high, 16)),
                          set_8x32(bilinear_weight_mask));
}

/* The running sums of one point on vectors: the channels' 64-bit values of the even and odd
   candidates, summed lane by lane (modulo 2^64, so in any order). */
struct VectorSums {
    vector_256 channel[DSN_MAX_CHANNELS];
    uint32_t point;
};

template <uint32_t Channels>
inline void flush_vector_sums(VectorSums *running, const BatchArrays &arrays) {
    for (uint32_t c = 0; c < Channels; c++) {
        uint64_t lanes[4];
        store_4x64(lanes, running->channel[c]);
        arrays.sums[running->point * Channels + c] += lanes[0] + lanes[1] + lanes[2] + lanes[3];
        running->channel[c] = zero_256();
    }
}

/* Candidates first .. first + 7. A lane out of reach reads quad 0 and its values are zeroed. When the 8
   belong to one point (a point's candidates are consecutive, so the first and last tell) they go to the
   running sums; otherwise those are flushed and the lanes added one by one. */
template <uint32_t Channels>
void batch_visit_8(const uint32_t *quads, const BatchConstants &k, const BatchArrays &arrays, uint32_t first,
                   VectorSums *running) {
    const vector_256 fraction = mix32_lanes(load_8x32(arrays.stream + first)),
                     packed = load_8x32(arrays.packed + first);
    const vector_256 cells = shift_right_logical_32(packed, 16);
    const vector_128 half_shift = shift_count(static_cast<int>(k.half_shift));
    const vector_128 high_shift = shift_count(static_cast<int>(k.high_shift));
    const vector_128 position_shift = shift_count(static_cast<int>(k.position_shift));
    const vector_256 low_16 = set_8x32(0xFFFF), half_mask = set_8x32(k.half_mask);
    const vector_256 high_x = shift_left_32_by(bitwise_and(packed, half_mask), high_shift);
    const vector_256 high_y =
        shift_left_32_by(bitwise_and(shift_right_logical_32_by(packed, half_shift), half_mask), high_shift);
    const vector_256 bits_x =
        bitwise_or(high_x, shift_right_logical_32_by(bitwise_and(fraction, low_16), half_shift));
    const vector_256 bits_y =
        bitwise_or(high_y, shift_right_logical_32_by(shift_right_logical_32(fraction, 16), half_shift));
    vector_256 reaches_x, column, across, reaches_y, row, down;
    axis_8(bits_x, arrays.base_x, cells, position_shift, set_4x64(static_cast<int64_t>(k.limit_x)),
           &reaches_x, &column, &across);
    axis_8(bits_y, arrays.base_y, cells, position_shift, set_4x64(static_cast<int64_t>(k.limit_y)),
           &reaches_y, &row, &down);
    const vector_256 reaches = bitwise_and(reaches_x, reaches_y);
    const vector_256 at = bitwise_and(
        reaches, add_32(multiply_32(row, set_8x32(k.quad_row)), multiply_32(column, set_8x32(Channels))));
    /* The reach of the even and odd lanes as 64-bit masks. */
    const vector_256 reaches_even = shuffle_32<0xA0>(reaches), reaches_odd = shuffle_32<0xF5>(reaches);
    const uint32_t first_point = arrays.point[arrays.packed[first] >> 16];
    const uint32_t last_point = arrays.point[arrays.packed[first + 7u] >> 16];
    const bool one_point = first_point == last_point;
    if (!one_point || first_point != running->point) {
        flush_vector_sums<Channels>(running, arrays);
        running->point = one_point ? first_point : last_point;
    }
    for (uint32_t c = 0; c < Channels; c++) {
        const vector_256 quad = gather_32<4>(quads + c, at);
        vector_256 even, odd;
        bilinear_8(shift_right_arithmetic_32(shift_left_32(quad, 24), 24),
                   shift_right_arithmetic_32(shift_left_32(quad, 16), 24),
                   shift_right_arithmetic_32(shift_left_32(quad, 8), 24), shift_right_arithmetic_32(quad, 24),
                   across, down, &even, &odd);
        even = bitwise_and(reaches_even, even);
        odd = bitwise_and(reaches_odd, odd);
        if (one_point) {
            running->channel[c] = add_64(running->channel[c], add_64(even, odd));
            continue;
        }
        uint64_t even_values[4], odd_values[4]; /* candidates 0, 2, 4, 6 and 1, 3, 5, 7 */
        store_4x64(even_values, even);
        store_4x64(odd_values, odd);
        for (uint32_t j = 0; j < 4; j++) {
            arrays.sums[arrays.point[arrays.packed[first + 2u * j] >> 16] * Channels + c] += even_values[j];
            arrays.sums[arrays.point[arrays.packed[first + 2u * j + 1u] >> 16] * Channels + c] +=
                odd_values[j];
        }
    }
}
#endif

/* Passes 2 and 3 over candidates [0, count). */
template <uint32_t Channels, uint32_t Bytes>
void batch_visit(const dsn_noise_state *noise, const uint32_t *quads, const BatchArrays &arrays,
                 uint32_t count) {
    const BatchConstants constants = batch_constants(noise);
    uint32_t slot = 0;
#if defined(__AVX2__)
    if (Bytes == 1 && count >= 8u) {
        VectorSums running;
        running.point = arrays.point[arrays.packed[0] >> 16];
        for (uint32_t c = 0; c < Channels; c++) running.channel[c] = zero_256();
        for (; slot + 8u <= count; slot += 8u)
            batch_visit_8<Channels>(quads, constants, arrays, slot, &running);
        flush_vector_sums<Channels>(&running, arrays);
    }
#endif
    batch_visit_scalar<Channels, Bytes>(quads, constants, arrays, slot, count);
}

/* Writes every lane of a pair of PerPair fields (8 of 8 bits, or 4 of 16) to the slots from fill->slots,
   keeping those of `candidates` (bit i: lane i). */
template <uint32_t PerPair>
inline void batch_emit_pair(const BatchArrays &arrays, BatchFill *fill, uint64_t pair, uint32_t candidates,
                            uint32_t stream) {
    const uint32_t field_bits = 64u / PerPair, cell = (fill->cells - 1u) << 16;
    uint32_t *stream_slots = arrays.stream, *packed_slots = arrays.packed, slots = fill->slots;
    for (uint32_t in_pair = 0; in_pair < PerPair; in_pair++) {
        stream_slots[slots] = stream + in_pair * 0x9E3779B9u;
        packed_slots[slots] =
            (dsn_pair_bits(pair, in_pair * field_bits) & 0xFFFFu >> (16u - field_bits)) | cell;
        slots += (candidates >> in_pair) & 1u;
    }
    fill->slots = slots;
}

#if defined(__AVX2__)
/* batch_emit_pair<8> on vectors: the 8 lanes' values are packed (candidates first) and stored at once. */
inline void batch_emit_pair_8(const BatchArrays &arrays, BatchFill *fill, uint64_t pair, uint32_t candidates,
                              uint32_t stream) {
    vector_256 streams, fields;
    const uint32_t count = pack_pair_8(pair, candidates, stream, &streams, &fields);
    store_8x32(arrays.stream + fill->slots, streams);
    store_8x32(arrays.packed + fill->slots, bitwise_or(fields, set_8x32((fill->cells - 1u) << 16)));
    fill->slots += count;
}
#endif

/* Records a cell of the point (the last of the arrays, which its slots refer to). */
inline void batch_add_cell(const BatchArrays &arrays, BatchFill *fill, const CellAxis &x, const CellAxis &y,
                           uint32_t point) {
    arrays.base_x[fill->cells] = static_cast<uint64_t>(x.shifted_base);
    arrays.base_y[fill->cells] = static_cast<uint64_t>(y.shifted_base);
    arrays.point[fill->cells] = point;
    fill->cells++;
}

/* Pass 1 for one point (index `point` of the chunk): appends its cells and candidates, visiting the
   arrays first whenever a cell or a pair might not fit. */
template <uint32_t Channels, uint32_t Bytes>
void batch_sift_point(const dsn_noise_state *noise, const uint32_t *quads, const FieldLanes &lanes,
                      const BatchArrays &arrays, BatchFill *fill, uint32_t point, uint64_t x, uint64_t y) {
    const uint32_t shift = noise->cell_shift;
    const bool two_steps = dsn_poisson_two_steps_fit(noise);
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
                    const uint32_t impulses = two_steps ? dsn_poisson_count_two_steps(noise, key)
                                                        : dsn_cell_impulse_count(noise, key);
                    if (impulses == 0) continue;
                    if (fill->cells == batch_cells) {
                        batch_visit<Channels, Bytes>(noise, quads, arrays, fill->slots);
                        fill->slots = fill->cells = 0;
                    }
                    batch_add_cell(arrays, fill, in_x, in_y, point);
                    for (uint32_t first = 0; first < impulses; first += lanes.per_pair) {
                        if (fill->slots + lanes.per_pair > batch_candidates) {
                            batch_visit<Channels, Bytes>(noise, quads, arrays, fill->slots);
                            fill->slots = fill->cells = 0;
                            batch_add_cell(arrays, fill, in_x, in_y, point);
                        }
                        const uint64_t pair = dsn_position_pair(key, first >> (6u - lanes.field_shift));
                        uint32_t candidates = gather_lanes(candidate_lanes(pair, lanes, in_x, in_y), lanes);
                        const uint32_t present = impulses - first;
                        if (present < lanes.per_pair) candidates &= (1u << present) - 1u;
                        /* dsn_cell_stream(key, 2^31 + k) of impulse k = first + slot */
                        const uint32_t stream = key + (0x80000000u + first) * 0x9E3779B9u;
                        if (lanes.per_pair == 8u)
#if defined(__AVX2__)
                            batch_emit_pair_8(arrays, fill, pair, candidates, stream);
#else
                            batch_emit_pair<8>(arrays, fill, pair, candidates, stream);
#endif
                        else
                            batch_emit_pair<4>(arrays, fill, pair, candidates, stream);
                    }
                }
            }
        }
    }
}

template <uint32_t Channels, uint32_t Bytes>
void batch_points(const dsn_noise_state *noise, const uint32_t *quads, const int64_t *xs, const int64_t *ys,
                  uint32_t count, int32_t *out, void *work) {
    const BatchArrays arrays = batch_arrays(work);
    const FieldLanes lanes = field_lanes(noise->cell_shift);
    for (uint32_t first = 0; first < count; first += batch_chunk_points) {
        const uint32_t points = count - first < batch_chunk_points ? count - first : batch_chunk_points;
        for (uint32_t k = 0; k < batch_chunk_points * Channels; k++) arrays.sums[k] = 0;
        BatchFill fill = {0, 0};
        for (uint32_t p = 0; p < points; p++)
            batch_sift_point<Channels, Bytes>(noise, quads, lanes, arrays, &fill, p,
                                              static_cast<uint64_t>(xs[first + p]),
                                              static_cast<uint64_t>(ys[first + p]));
        batch_visit<Channels, Bytes>(noise, quads, arrays, fill.slots);
        for (uint32_t p = 0; p < points; p++)
            normalize_q32(noise, arrays.sums + p * Channels, out + static_cast<size_t>(first + p) * Channels);
    }
}

#if DSN_GRADIENTS
/* The batch's gradients (the entry's dx): with AVX2, the groups of continuous_batch_group.h for the noises
   the vector per-point evaluator takes; else point by point. */
inline void batch_gradients(const dsn_noise_state *noise, const int64_t *xs, const int64_t *ys,
                            uint32_t count, int32_t *out, int32_t *dx, int32_t *dy) {
    const uint32_t channels = noise->asset.channels;
#if defined(__AVX2__)
    if (point_vector_takes(noise)) {
        channels == 3 ? batch_group_gradients<3>(noise, xs, ys, count, out, dx, dy)
                      : batch_group_gradients<1>(noise, xs, ys, count, out, dx, dy);
        return;
    }
#endif
    for (uint32_t k = 0; k < count; k++) {
        int32_t values[3 * DSN_MAX_CHANNELS];
        dsn_internal_continuous_gradient(noise, static_cast<uint64_t>(xs[k]), static_cast<uint64_t>(ys[k]),
                                         values);
        store_gradient_point(values, channels, static_cast<size_t>(k) * channels, out, dx, dy);
    }
}
#endif

/* The kernel entry. With AVX2 (the AVX2 and AVX-512 kernels, or a default kernel built for AVX2) the
   groups of continuous_batch_group.h for the noises the vector per-point evaluator takes (faster than the
   passes above there), else the passes above, one copy per channel count and value size. Without,
   those (pass 2 one candidate at a time) measured slower than the per-point evaluator with its SSE2 bilinear
   reads, which the entry then calls point by point (work and quads unused). */
inline void continuous_batch(const dsn_noise_state *noise, const uint32_t *quads, const int64_t *xs,
                             const int64_t *ys, uint32_t count, int32_t *out, int32_t *dx, int32_t *dy,
                             void *work) {
#if DSN_GRADIENTS
    if (dx != 0) {
        batch_gradients(noise, xs, ys, count, out, dx, dy);
        return;
    }
#else
    (void)dx, (void)dy;
#endif
#if defined(__AVX2__)
    if (point_vector_takes(noise)) { /* faster there */
        noise->asset.channels == 3 ? batch_groups<3>(noise, quads, xs, ys, count, out)
                                   : batch_groups<1>(noise, quads, xs, ys, count, out);
        return;
    }
    const dsn_asset *asset = &noise->asset;
    if (asset->channels == 3)
        asset->bits == 8 ? batch_points<3, 1>(noise, quads, xs, ys, count, out, work)
                         : batch_points<3, 2>(noise, quads, xs, ys, count, out, work);
    else
        asset->bits == 8 ? batch_points<1, 1>(noise, quads, xs, ys, count, out, work)
                         : batch_points<1, 2>(noise, quads, xs, ys, count, out, work);
#else
    (void)quads, (void)work;
    for (uint32_t k = 0; k < count; k++)
        dsn_internal_continuous_point(noise, static_cast<uint64_t>(xs[k]), static_cast<uint64_t>(ys[k]),
                                      out + static_cast<size_t>(k) * noise->asset.channels);
#endif
}

} // namespace

#endif /* DSN_CONTINUOUS_BATCH_H */
