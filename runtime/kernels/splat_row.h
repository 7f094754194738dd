/* runtime/kernels/splat_row.h - the innermost loops of the grid splat (grid_splat.cpp): one
   impulse added to its runs of pixels, one run per row of a block, and the normalization of a row of the
   block's sums, as kernels (kernels.h: each kernel file includes it, so it is built once per instruction
   set). On x86 8-bit textons are read from their cell records (splat_cells.h) on vectors of 64-bit lanes,
   one pixel per lane (2, 4 or 8 by the copy), axis-aligned grids reusing each record's interpolation along
   the row down the runs; 8-bit textons too large for the records take 8 pixels per step with gathers on
   AVX2 and AVX-512; the rest goes pixel by pixel. The same integers every way (add_bilinear's). Internal
   to libdsn; not installed (everything here has internal linkage). */
#ifndef DSN_SPLAT_ROW_H
#define DSN_SPLAT_ROW_H

#include "core/bilinear_texton.h"
#include "core/continuous_internal.h"
#include "kernels/kernels.h"
#include "kernels/splat_cells.h"
#include "simd/simd.h" /* the splat operations; the 256-bit ones (simd_256.h) on AVX2 and AVX-512 */

namespace {

/* One channel of the bilinear texton at (row, column) with the upper weights (down, across), texels
   inside the window: add_bilinear's integer, with one product per step ((65536 - w) a + w b =
   65536 a + w (b - a), the same integers). */
template <uint32_t Bytes, uint32_t Stride>
inline int64_t interior_channel(const unsigned char *top, const unsigned char *bottom, int64_t across,
                                int64_t down) {
    const int64_t top_left = stored_value<Bytes>(top), bottom_left = stored_value<Bytes>(bottom);
    const int64_t upper = top_left * 65536 + across * (stored_value<Bytes>(top + Stride) - top_left);
    const int64_t lower = bottom_left * 65536 + across * (stored_value<Bytes>(bottom + Stride) - bottom_left);
    return upper * 65536 + down * (lower - upper);
}

/* A texel of channel c at (row, column), 0 outside the window (indices are unsigned: -1 is outside). */
template <uint32_t Channels, uint32_t Bytes>
inline int64_t edge_texel(const dsn_splat_texture &texture, uint32_t row, uint32_t column, uint32_t c) {
    if (row >= texture.height || column >= texture.width) return 0;
    return stored_value<Bytes>(texture.values + ((row * texture.stride + column) * Channels + c) * Bytes);
}

/* Adds the impulse to `count` pixels of a row, starting at the offsets (pixel - impulse) given, all in
   reach (-reach < offset < reach on both axes, which the column bounds guarantee): bracket's shifted
   values (offset + reach, divided by 2^level) lie in [0, 2 reach / 2^level), so its lower index and weight
   are read off directly (0 gives index -1 and weight 0: nothing). The sums are planar: channel c of the
   row's first pixel at pixel[c * plane]. */
template <uint32_t Channels, uint32_t Bytes>
void splat_row(const dsn_splat_setup *setup, int64_t offset_x, int64_t offset_y, uint32_t count,
               uint64_t *pixel) {
    const dsn_splat_texture &texture = setup->texture;
    const uint32_t width = texture.width, height = texture.height, level = texture.level;
    const uint32_t row_bytes = texture.stride * Channels * Bytes;
    const size_t plane = setup->plane;
    uint64_t shifted_x = static_cast<uint64_t>(offset_x + setup->reach_x);
    uint64_t shifted_y = static_cast<uint64_t>(offset_y + setup->reach_y);
    for (uint32_t i = 0; i < count; i++, pixel++) {
        const uint64_t level_x = shifted_x >> level, level_y = shifted_y >> level;
        const uint32_t column = static_cast<uint32_t>(level_x >> 32) - 1u;
        const uint32_t row = static_cast<uint32_t>(level_y >> 32) - 1u;
        const int64_t across = static_cast<int64_t>((level_x >> 16) & bilinear_weight_mask);
        const int64_t down = static_cast<int64_t>((level_y >> 16) & bilinear_weight_mask);
        if (row < height - 1u && column < width - 1u) { /* -1 (0xFFFFFFFF) fails too */
            const unsigned char *top = texture.values + (row * texture.stride + column) * Channels * Bytes;
            const unsigned char *bottom = top + row_bytes;
            for (uint32_t c = 0; c < Channels; c++)
                pixel[c * plane] += static_cast<uint64_t>(interior_channel<Bytes, Channels * Bytes>(
                    top + c * Bytes, bottom + c * Bytes, across, down));
        } else { /* at the window's edge: the same integers, texels outside read as 0 */
            for (uint32_t c = 0; c < Channels; c++) {
                const int64_t top_left = edge_texel<Channels, Bytes>(texture, row, column, c);
                const int64_t bottom_left = edge_texel<Channels, Bytes>(texture, row + 1u, column, c);
                const int64_t upper =
                    top_left * 65536 +
                    across * (edge_texel<Channels, Bytes>(texture, row, column + 1u, c) - top_left);
                const int64_t lower =
                    bottom_left * 65536 +
                    across * (edge_texel<Channels, Bytes>(texture, row + 1u, column + 1u, c) - bottom_left);
                pixel[c * plane] += static_cast<uint64_t>(upper * 65536 + down * (lower - upper));
            }
        }
        shifted_x += static_cast<uint64_t>(setup->step_x);
        shifted_y += static_cast<uint64_t>(setup->step_y);
    }
}

#if defined(__AVX2__)
/* ---- 8 pixels at a time on AVX2, 8-bit textons (level 0) without cell records ----
   Each pixel's 2 x 2 texels come from 4 gathers of 32-bit words at the texels' first bytes (the texel
   and, for grey, the next one; for RGB the texel's 3 bytes and one more), each masked to the pixels whose
   texel lies inside the window, so that the others read nothing and give 0. A word read at a texel of
   the last row reaches at most 3 bytes past it: into the asset's 4-byte CRC, which the loader
   guarantees lies in the buffer right after the texton (format.h: total_size). The rows' interpolation
   runs in 32-bit lanes (below 2^25), the column's in 64-bit lanes (multiply_even_32, exact). A row's
   last pixels take a block whose lanes past the row are masked out of the gathers and not added. */

/* The low 32 bits of the 64-bit lanes of a (pixels 0-3) and b (4-7), as 8 lanes in order. */
inline vector_256 splat_low_halves(vector_256 a, vector_256 b) {
    const floats_256 mixed = shuffle<0x88>(as_floats(a), as_floats(b));
    return permute_64<0xD8>(as_integers(mixed));
}

/* Byte `index` of every 32-bit lane, sign-extended. */
template <int Index>
inline vector_256 signed_byte(vector_256 words) {
    return shift_right_arithmetic_32(shift_left_32(words, 24 - 8 * Index), 24);
}

template <uint32_t Channels>
void splat_row_vector(const dsn_splat_setup *setup, int64_t offset_x, int64_t offset_y, uint32_t count,
                      uint64_t *pixel) {
    const dsn_splat_texture &texture = setup->texture;
    const int64_t step_x = setup->step_x, step_y = setup->step_y;
    const size_t plane = setup->plane;
    const uint32_t blocks = (count + 7u) / 8u;
    const vector_256 steps_x = set_4x64(8 * step_x), steps_y = set_4x64(8 * step_y);
    const vector_256 lanes = set_lanes_4x64(0, 1, 2, 3);
    /* bracket's shifted values of pixels 0-3 and 4-7 (modulo 2^64, as the scalar loop steps them) */
    const uint64_t start_x = static_cast<uint64_t>(offset_x + setup->reach_x),
                   start_y = static_cast<uint64_t>(offset_y + setup->reach_y);
    const uint64_t four_x = 4u * static_cast<uint64_t>(step_x), four_y = 4u * static_cast<uint64_t>(step_y);
    vector_256 low_x =
        add_64(set_4x64(static_cast<int64_t>(start_x)), multiply_even_unsigned_32(lanes, set_4x64(step_x)));
    vector_256 low_y =
        add_64(set_4x64(static_cast<int64_t>(start_y)), multiply_even_unsigned_32(lanes, set_4x64(step_y)));
    /* multiply_even_unsigned_32 takes the low 32 bits of the step: add the high part's multiples too */
    low_x = add_64(
        low_x, shift_left_64(multiply_even_unsigned_32(
                                 lanes, set_4x64(static_cast<int64_t>(static_cast<uint64_t>(step_x) >> 32))),
                             32));
    low_y = add_64(
        low_y, shift_left_64(multiply_even_unsigned_32(
                                 lanes, set_4x64(static_cast<int64_t>(static_cast<uint64_t>(step_y) >> 32))),
                             32));
    vector_256 high_x = add_64(low_x, set_4x64(static_cast<int64_t>(four_x)));
    vector_256 high_y = add_64(low_y, set_4x64(static_cast<int64_t>(four_y)));
    const vector_256 width = set_8x32(texture.width), height = set_8x32(texture.height);
    const vector_256 sign = set_8x32(0x80000000u);
    const vector_256 width_sign = bitwise_xor(width, sign), height_sign = bitwise_xor(height, sign);
    const vector_256 ones = set_8x32(1), weight_bits = set_8x32(bilinear_weight_mask),
                     scale = set_8x32(65536);
    const vector_256 row_bytes = set_8x32(texture.stride * Channels);
    const void *texton = texture.values;
    const vector_256 lane_numbers = set_lanes_8x32(0, 1, 2, 3, 4, 5, 6, 7);
    for (uint32_t block = 0; block < blocks; block++, pixel += 8) {
        /* The last block's lanes past the row read nothing and leave their memory alone (masked). */
        const uint32_t remaining = count - 8u * block;
        const bool full = remaining >= 8u;
        const vector_256 present = greater_32(set_8x32(remaining), lane_numbers);
        /* The lower texel indices (column, row: -1 .. size - 1) and the upper weights. */
        const vector_256 column = subtract_32(
            splat_low_halves(shift_right_logical_64(low_x, 32), shift_right_logical_64(high_x, 32)), ones);
        const vector_256 row = subtract_32(
            splat_low_halves(shift_right_logical_64(low_y, 32), shift_right_logical_64(high_y, 32)), ones);
        const vector_256 across = bitwise_and(
            splat_low_halves(shift_right_logical_64(low_x, 16), shift_right_logical_64(high_x, 16)),
            weight_bits);
        const vector_256 down = bitwise_and(
            splat_low_halves(shift_right_logical_64(low_y, 16), shift_right_logical_64(high_y, 16)),
            weight_bits);
        /* index < size as unsigned (-1 fails): signed comparisons of the values flipped by 2^31 */
        const vector_256 left_in = bitwise_and(present, greater_32(width_sign, bitwise_xor(column, sign)));
        const vector_256 right_in =
            bitwise_and(present, greater_32(width_sign, bitwise_xor(add_32(column, ones), sign)));
        const vector_256 top_in = greater_32(height_sign, bitwise_xor(row, sign));
        const vector_256 bottom_in = greater_32(height_sign, bitwise_xor(add_32(row, ones), sign));
        const vector_256 at = add_32(multiply_32(row, row_bytes), multiply_32(column, set_8x32(Channels)));
        const vector_256 right = set_8x32(Channels);
        const vector_256 top_left = gather_masked_32<1>(texton, at, bitwise_and(top_in, left_in));
        const vector_256 top_right =
            gather_masked_32<1>(texton, add_32(at, right), bitwise_and(top_in, right_in));
        const vector_256 below = add_32(at, row_bytes);
        const vector_256 bottom_left = gather_masked_32<1>(texton, below, bitwise_and(bottom_in, left_in));
        const vector_256 bottom_right =
            gather_masked_32<1>(texton, add_32(below, right), bitwise_and(bottom_in, right_in));
        for (uint32_t c = 0; c < Channels; c++) {
            vector_256 a, b, d, e; /* top-left, top-right, bottom-left, bottom-right of channel c */
            if (c == 0)
                a = signed_byte<0>(top_left), b = signed_byte<0>(top_right), d = signed_byte<0>(bottom_left),
                e = signed_byte<0>(bottom_right);
            else if (c == 1)
                a = signed_byte<1>(top_left), b = signed_byte<1>(top_right), d = signed_byte<1>(bottom_left),
                e = signed_byte<1>(bottom_right);
            else
                a = signed_byte<2>(top_left), b = signed_byte<2>(top_right), d = signed_byte<2>(bottom_left),
                e = signed_byte<2>(bottom_right);
            const vector_256 upper = add_32(shift_left_32(a, 16), multiply_32(across, subtract_32(b, a)));
            const vector_256 lower = add_32(shift_left_32(d, 16), multiply_32(across, subtract_32(e, d)));
            const vector_256 difference = subtract_32(lower, upper);
            const vector_256 even =
                add_64(multiply_even_32(upper, scale), multiply_even_32(down, difference));
            const vector_256 odd = add_64(
                multiply_even_32(shift_right_logical_64(upper, 32), scale),
                multiply_even_32(shift_right_logical_64(down, 32), shift_right_logical_64(difference, 32)));
            /* even: pixels 0, 2 | 4, 6; odd: 1, 3 | 5, 7 */
            const vector_256 first = unpack_low_64(even, odd), second = unpack_high_64(even, odd);
            const vector_256 pixels_low = permute_128_of_two<0x20>(first, second);
            const vector_256 pixels_high = permute_128_of_two<0x31>(first, second);
            uint64_t *sums = pixel + c * plane;
            if (full) {
                store_4x64(sums, add_64(load_4x64(sums), pixels_low));
                store_4x64(sums + 4, add_64(load_4x64(sums + 4), pixels_high));
            } else {
                uint64_t values[8];
                store_4x64(values, pixels_low);
                store_4x64(values + 4, pixels_high);
                for (uint32_t i = 0; i < remaining; i++) sums[i] += values[i];
            }
        }
        low_x = add_64(low_x, steps_x), high_x = add_64(high_x, steps_x);
        low_y = add_64(low_y, steps_y), high_y = add_64(high_y, steps_y);
    }
}
#endif

/* One impulse on one run, pixel by pixel but for 8-bit textons (level 0) on AVX2: one copy per channel
   count and value size. */
inline void continuous_splat_row(const dsn_splat_setup *setup, const dsn_splat_run &run) {
    const dsn_splat_texture &texture = setup->texture;
#if defined(__AVX2__)
    if (texture.bits == 8 && texture.level == 0) {
        if (texture.channels == 3)
            splat_row_vector<3>(setup, run.offset_x, run.offset_y, run.count, run.sums);
        else
            splat_row_vector<1>(setup, run.offset_x, run.offset_y, run.count, run.sums);
        return;
    }
#endif
    if (texture.channels == 3)
        texture.bits == 8 ? splat_row<3, 1>(setup, run.offset_x, run.offset_y, run.count, run.sums)
                          : splat_row<3, 2>(setup, run.offset_x, run.offset_y, run.count, run.sums);
    else
        texture.bits == 8 ? splat_row<1, 1>(setup, run.offset_x, run.offset_y, run.count, run.sums)
                          : splat_row<1, 2>(setup, run.offset_x, run.offset_y, run.count, run.sums);
}

#if DSN_SPLAT_CELLS
/* ---- The runs on vectors of 64-bit lanes, 8-bit textons (the x86 kernels: simd.h's splat ops) ----
   Each lane is one pixel of the run: its shifted offsets step as the scalar loop steps them, its cell's
   record of each channel is read from the table (splat_cells.h) at the cell index the lower texel indices
   give, and one multiply-add of 16-bit pairs and two signed 32 x 32-bit products give interior_channel's
   integer, edge cells included (their texels outside the window are 0 in the records). No gathers: the
   records are loaded one by one. Lanes past a run read cell 0 and are not added. A pyramid level
   (Leveled) divides each lane's shifted values by 2^level first. */
/* The records' two integers (splat_rows: upper, lower - upper) and their products: 65536 upper, and
   down (lower - upper) for a down weight in [0, 65536). SSE2 has no signed 32 x 32-bit product
   (splat_signed_times takes several operations), so in its copy the two integers, below 2^25 in
   magnitude (splat_cells.h), are made non-negative dwords first (upper + 2^25, lower - upper + 2^26),
   multiplied unsigned, and the biases' products taken back: the same integers modulo 2^64. */
#if defined(__AVX2__)
inline splat_vector splat_row_integers(splat_vector records, splat_vector across) {
    return splat_rows(records, across);
}
inline splat_vector splat_upper_scaled(splat_vector rows) {
    return splat_signed_times(rows, splat_set(65536));
}
inline splat_vector splat_difference_times(splat_vector difference, splat_vector down) {
    return splat_signed_times(difference, down);
}
#else
inline splat_vector splat_row_integers(splat_vector records, splat_vector across) {
    return add_32(splat_rows(records, across), set_lanes_4x32(1 << 25, 1 << 26, 1 << 25, 1 << 26));
}
inline splat_vector splat_upper_scaled(splat_vector rows) {
    return splat_sub(splat_low_times(rows, splat_set(65536)), splat_set(static_cast<uint64_t>(1) << 41));
}
inline splat_vector splat_difference_times(splat_vector difference, splat_vector down) {
    return splat_sub(splat_low_times(difference, down), shift_left_64(down, 26));
}
#endif

/* The records' bilinear values: 65536 upper + down (lower - upper). */
inline splat_vector splat_bilinear(splat_vector records, splat_vector across, splat_vector down) {
    const splat_vector rows = splat_row_integers(records, across);
    return splat_add(splat_upper_scaled(rows), splat_difference_times(splat_shift_right(rows, 32), down));
}

/* bracket's shifted values of a level: the lanes' (offset + reach) / 2^level. */
template <bool Leveled>
inline splat_vector splat_level(splat_vector shifted, uint32_t level) {
    return Leveled ? splat_shift_right(shifted, level) : shifted;
}

/* First every lane's cell (where its records start: cell[]), then the sums: the loads of the records do not
   wait on the vector stores of their indices. Lanes past a run read cell 0. */
template <uint32_t Channels, bool Leveled>
inline void splat_cell_indices(const dsn_splat_setup *setup, const dsn_splat_run *runs, uint32_t run_count,
                               uint64_t *cell) {
    const uint64_t step_x = static_cast<uint64_t>(setup->step_x),
                   step_y = static_cast<uint64_t>(setup->step_y);
    const splat_vector lanes_x = splat_lane_steps(0, step_x), lanes_y = splat_lane_steps(0, step_y);
    const splat_vector next_x = splat_set(step_x * splat_lanes), next_y = splat_set(step_y * splat_lanes);
    const uint32_t cell_records = Channels == 3 ? 4u : 1u, row_records = setup->cell_row * cell_records;
    const uint32_t level = setup->texture.level;
    uint64_t *at = cell;
    for (uint32_t r = 0; r < run_count; r++) {
        /* bracket's shifted values: the cell is (shifted_y >> 32) rows and (shifted_x >> 32) columns into
           the table, whose row and column 0 are the texel indices -1 */
        splat_vector shifted_x =
            splat_add(splat_set(static_cast<uint64_t>(runs[r].offset_x + setup->reach_x)), lanes_x);
        splat_vector shifted_y =
            splat_add(splat_set(static_cast<uint64_t>(runs[r].offset_y + setup->reach_y)), lanes_y);
        for (uint32_t done = 0; done < runs[r].count; done += splat_lanes, at += splat_lanes) {
            splat_store(
                at, splat_first_lanes(
                        splat_add(splat_whole_times(splat_level<Leveled>(shifted_y, level), row_records),
                                  splat_whole_times(splat_level<Leveled>(shifted_x, level), cell_records)),
                        runs[r].count - done));
            shifted_x = splat_add(shifted_x, next_x);
            shifted_y = splat_add(shifted_y, next_y);
        }
    }
}

/* ---- The gradient's runs: the value and both slopes in one pass ----
   With the texel pieces of each lane's cell record (splat_cells.h: w1 = TR - TL, w3 = TL - TR - BL + BR),
   add_slopes's two integers (bilinear_texton.h), per 2^-16 texel: along y, (65536 - a)(BL - TL) + a (BR -
   TR) = lower - upper, the rows' second dword, already there; along x, (65536 - d)(TR - TL) + d (BR - BL) =
   65536 w1 + d w3 = 256 (256 w1 + d' w3), d = 256 d' the down weight: a multiply-add of the record's words
   with (0, 256, 0, d'). The value planes at `sums`, the slopes along x Channels planes after them, along y
   2 Channels planes after; the runs cover the entry edge too (grid_splat.h), where the value adds 0. The
   records' integers as AVX2 and AVX-512 take them (splat_rows: no biases). */
template <uint32_t Channels>
inline void splat_add_slopes(const splat_vector *records, splat_vector across, splat_vector down,
                             uint64_t *sums, size_t plane, uint32_t remaining, const uint64_t *end) {
    const size_t along_x = Channels * plane, along_y = 2 * Channels * plane;
    const splat_vector slope_weights = splat_or(splat_shift_left(down, 40), splat_set(256u << 16));
    for (uint32_t c = 0; c < Channels; c++) {
        const splat_vector rows = splat_rows(records[c], across);
        const splat_vector difference = splat_shift_right(rows, 32);
        const splat_vector along = splat_rows(records[c], slope_weights);
        uint64_t *value = sums + c * plane;
        splat_accumulate(value, splat_add(splat_upper_scaled(rows), splat_difference_times(difference, down)),
                         remaining, end);
        splat_accumulate(value + along_x,
                         splat_add(splat_signed_times(along, splat_set(256)),
                                   splat_signed_times(splat_shift_right(along, 32), splat_set(256))),
                         remaining, end + along_x);
        splat_accumulate(value + along_y, splat_signed_times(difference, splat_set(1)), remaining,
                         end + along_y);
    }
}

/* The runs of a call, and with Slopes (AVX2 and AVX-512 only: continuous_gradient_runs) both slopes too. */
template <uint32_t Channels, bool Leveled, bool Slopes>
void splat_runs_vector(const dsn_splat_setup *setup, const dsn_splat_run *runs, uint32_t run_count) {
    const uint64_t step_x = static_cast<uint64_t>(setup->step_x),
                   step_y = static_cast<uint64_t>(setup->step_y);
    const splat_vector lanes_x = splat_lane_steps(0, step_x), lanes_y = splat_lane_steps(0, step_y);
    const splat_vector next_x = splat_set(step_x * splat_lanes), next_y = splat_set(step_y * splat_lanes);
    const size_t plane = setup->plane;
    const uint64_t *end = setup->sums_end;
    const uint32_t level = setup->texture.level;
    uint64_t cell[dsn_splat_runs_most * (dsn_splat_run_longest + splat_lanes)];
    splat_cell_indices<Channels, Leveled>(setup, runs, run_count, cell);
    uint64_t *at = cell;
    for (uint32_t r = 0; r < run_count; r++) {
        const dsn_splat_run &run = runs[r];
        splat_vector shifted_x =
            splat_add(splat_set(static_cast<uint64_t>(run.offset_x + setup->reach_x)), lanes_x);
        splat_vector shifted_y =
            splat_add(splat_set(static_cast<uint64_t>(run.offset_y + setup->reach_y)), lanes_y);
        uint64_t *sums = run.sums;
        for (uint32_t done = 0; done < run.count;
             done += splat_lanes, sums += splat_lanes, at += splat_lanes) {
            const uint32_t remaining = run.count - done;
            const splat_vector across = splat_across_weights(splat_level<Leveled>(shifted_x, level)),
                               down = splat_weight(splat_level<Leveled>(shifted_y, level));
            splat_vector records[3];
            splat_load_cells<Channels>(setup->cells, at, records);
            if (Slopes) {
                splat_add_slopes<Channels>(records, across, down, sums, plane, remaining, end);
            } else {
                splat_accumulate(sums, splat_bilinear(records[0], across, down), remaining, end);
                if (Channels == 3) {
                    splat_accumulate(sums + plane, splat_bilinear(records[1], across, down), remaining, end);
                    splat_accumulate(sums + 2 * plane, splat_bilinear(records[2], across, down), remaining,
                                     end);
                }
            }
            shifted_x = splat_add(shifted_x, next_x);
            shifted_y = splat_add(shifted_y, next_y);
        }
    }
}
#endif

#if DSN_SPLAT_CELLS
/* ---- Axis-aligned grids: the runs share their columns (dsn_splat_setup.columns_shared) ----
   A pixel's cell column and across weights then depend on its column alone, its cell row and down weight
   on its row alone. Going down the runs one vector of columns at a time, the interpolation along the row
   (splat_rows: both dwords of each record) stays in registers while the cell row does not change, and
   each pixel adds 65536 upper + down (lower - upper) from it: the same integers. Lanes past the runs read
   the row's first cell and are not added. */
/* One channel of the current cell row, kept in registers: 65536 upper and lower - upper (the value's), and
   with Slopes 65536 w1, w3 and the slope along y (splat_add_slopes's pieces). */
struct AlignedChannel {
    splat_vector scaled, difference, base_x, cross, slope_y;
};

template <bool Slopes>
inline void aligned_channel(splat_vector records, splat_vector across, AlignedChannel *channel) {
    const splat_vector rows = splat_row_integers(records, across);
    channel->scaled = splat_upper_scaled(rows);
    channel->difference = splat_shift_right(rows, 32);
    if (Slopes) {
        /* the words (0, 1, 0, 1): w1 and w3 in the lane's dwords */
        const splat_vector pieces = splat_rows(records, splat_set(0x0001000000010000u));
        channel->base_x = splat_signed_times(pieces, splat_set(65536));
        channel->cross = splat_shift_right(pieces, 32);
        channel->slope_y = splat_signed_times(channel->difference, splat_set(1));
    }
}

/* A pixel's value (and slopes) from its cell row's channel and its down weight. */
template <bool Slopes>
inline void aligned_add(const AlignedChannel &channel, splat_vector weight, uint64_t *sums, size_t along_x,
                        size_t along_y, uint32_t remaining, const uint64_t *end) {
    splat_accumulate(sums, splat_add(channel.scaled, splat_difference_times(channel.difference, weight)),
                     remaining, end);
    if (Slopes) {
        splat_accumulate(sums + along_x, splat_add(channel.base_x, splat_signed_times(channel.cross, weight)),
                         remaining, end + along_x);
        splat_accumulate(sums + along_y, channel.slope_y, remaining, end + along_y);
    }
}

template <uint32_t Channels, bool Leveled, bool Slopes>
void splat_runs_aligned(const dsn_splat_setup *setup, const dsn_splat_run *runs, uint32_t run_count) {
    const uint32_t cell_records = Channels == 3 ? 4u : 1u, row_records = setup->cell_row * cell_records;
    const uint32_t count = runs[0].count;
    const size_t plane = setup->plane, along_x = Channels * plane, along_y = 2 * Channels * plane;
    const uint64_t *end = setup->sums_end;
    const uint32_t level = setup->texture.level;
    /* Each run's first record in the table and down weight. */
    uint64_t row_start[dsn_splat_runs_most], down[dsn_splat_runs_most];
    for (uint32_t r = 0; r < run_count; r++) {
        const uint64_t shifted_y = static_cast<uint64_t>(runs[r].offset_y + setup->reach_y) >> level;
        row_start[r] = (shifted_y >> 32) * row_records;
        down[r] = (shifted_y >> 16) & bilinear_weight_mask;
    }
    const uint64_t step_x = static_cast<uint64_t>(setup->step_x);
    splat_vector shifted_x = splat_add(splat_set(static_cast<uint64_t>(runs[0].offset_x + setup->reach_x)),
                                       splat_lane_steps(0, step_x));
    const splat_vector next_x = splat_set(step_x * splat_lanes);
    for (uint32_t done = 0; done < count; done += splat_lanes) {
        const uint32_t remaining = count - done;
        uint64_t column[splat_lanes]; /* each lane's first record in a row of the table */
        const splat_vector level_x = splat_level<Leveled>(shifted_x, level);
        splat_store(column, splat_first_lanes(splat_whole_times(level_x, cell_records), remaining));
        const splat_vector across = splat_across_weights(level_x);
        const splat_vector zero = splat_set(0);
        AlignedChannel channel_0 = {zero, zero, zero, zero, zero}, channel_1 = channel_0,
                       channel_2 = channel_0;
        uint64_t current = ~static_cast<uint64_t>(0);
        for (uint32_t r = 0; r < run_count; r++) {
            if (row_start[r] != current) {
                current = row_start[r];
                splat_vector records[3];
                splat_load_cells<Channels>(setup->cells + current, column, records);
                aligned_channel<Slopes>(records[0], across, &channel_0);
                if (Channels == 3) {
                    aligned_channel<Slopes>(records[1], across, &channel_1);
                    aligned_channel<Slopes>(records[2], across, &channel_2);
                }
            }
            const splat_vector weight = splat_set(down[r]);
            uint64_t *sums = runs[r].sums + done;
            aligned_add<Slopes>(channel_0, weight, sums, along_x, along_y, remaining, end);
            if (Channels == 3) {
                aligned_add<Slopes>(channel_1, weight, sums + plane, along_x, along_y, remaining, end);
                aligned_add<Slopes>(channel_2, weight, sums + 2 * plane, along_x, along_y, remaining, end);
            }
        }
        shifted_x = splat_add(shifted_x, next_x);
    }
}
#endif

#if DSN_SPLAT_CELLS
/* The runs on vectors of records, axis-aligned grids or not, of a level or of the texton. */
template <uint32_t Channels, bool Leveled>
inline void splat_runs_cells(const dsn_splat_setup *setup, const dsn_splat_run *runs, uint32_t run_count) {
    if (setup->columns_shared)
        splat_runs_aligned<Channels, Leveled, false>(setup, runs, run_count);
    else
        splat_runs_vector<Channels, Leveled, false>(setup, runs, run_count);
}
#endif

#if DSN_SPLAT_CELLS && defined(__AVX2__)
template <uint32_t Channels>
inline void gradient_runs_of(const dsn_splat_setup *setup, const dsn_splat_run *runs, uint32_t run_count,
                             bool leveled) {
    if (setup->columns_shared)
        leveled ? splat_runs_aligned<Channels, true, true>(setup, runs, run_count)
                : splat_runs_aligned<Channels, false, true>(setup, runs, run_count);
    else
        leveled ? splat_runs_vector<Channels, true, true>(setup, runs, run_count)
                : splat_runs_vector<Channels, false, true>(setup, runs, run_count);
}

/* The kernel entry (kernels.h's continuous_gradient_runs): a texture with records, any level. */
inline void continuous_gradient_runs(const dsn_splat_setup *setup, const dsn_splat_run *runs,
                                     uint32_t run_count) {
    const bool leveled = setup->texture.level != 0;
    if (setup->texture.channels == 3)
        gradient_runs_of<3>(setup, runs, run_count, leveled);
    else
        gradient_runs_of<1>(setup, runs, run_count, leveled);
}
#define DSN_SPLAT_GRADIENT_ENTRY continuous_gradient_runs
#else
#define DSN_SPLAT_GRADIENT_ENTRY 0
#endif

/* The kernel entry: the runs on vectors where the texture has records, else pixel by pixel. */
inline void continuous_splat_runs(const dsn_splat_setup *setup, const dsn_splat_run *runs,
                                  uint32_t run_count) {
#if DSN_SPLAT_CELLS
    if (setup->cells != 0) {
        const bool leveled = setup->texture.level != 0;
        if (setup->texture.channels == 3)
            leveled ? splat_runs_cells<3, true>(setup, runs, run_count)
                    : splat_runs_cells<3, false>(setup, runs, run_count);
        else
            leveled ? splat_runs_cells<1, true>(setup, runs, run_count)
                    : splat_runs_cells<1, false>(setup, runs, run_count);
        return;
    }
#endif
    for (uint32_t r = 0; r < run_count; r++) continuous_splat_row(setup, runs[r]);
}

#if DSN_SPLAT_CELLS
/* The high dword of each lane, signed, times the low dword of factor's (below 2^31). SSE2's copy flips
   the dword's sign bit (adding 2^31: non-negative), multiplies unsigned and takes 2^31 factor back. */
inline splat_vector splat_high_times(splat_vector value, splat_vector factor) {
#if defined(__AVX2__)
    return splat_signed_times(splat_shift_right(value, 32), factor);
#else
    return splat_sub(
        splat_low_times(bitwise_xor(splat_shift_right(value, 32), splat_set(0x80000000u)), factor),
        shift_left_64(factor, 31));
#endif
}

/* ---- The normalization on vectors of 64-bit lanes, one pixel each ----
   normalize_q32_unmapped's integers, modulo 2^64 as they never wrap: the offset plus the gains times the
   signed whole parts, plus the floor of the gains times the fractions over 2^32 (the gains' magnitudes
   multiplied, then added or subtracted), then the biased rounding shift; the int32 saturation per value (on
   vectors, interleaved by permutes, where the ops header has splat_store_pixels). Pixels past the last whole
   vector go one by one. */
template <uint32_t Channels>
void splat_normalize_vector(const dsn_noise_state *noise, const int64_t *offset, const uint64_t *sums,
                            size_t plane, uint32_t count, int32_t *out) {
    const uint64_t bias = static_cast<uint64_t>(1) << 63;
    const uint32_t shift = noise->gain_shift;
    const splat_vector rounding = splat_set(bias + ((static_cast<uint64_t>(1) << shift) >> 1));
    const splat_vector rounding_bias = splat_set(bias >> shift), floor_bias = splat_set(bias),
                       floor_unbias = splat_set(bias >> 32);
    uint32_t done = 0;
    for (; done + splat_lanes <= count; done += splat_lanes) {
        splat_vector pixel_sums[Channels];
        for (uint32_t k = 0; k < Channels; k++) pixel_sums[k] = splat_load(sums + k * plane + done);
        splat_vector values[Channels];
        for (uint32_t c = 0; c < Channels; c++) {
            splat_vector accumulated = splat_set(static_cast<uint64_t>(offset[c]));
            splat_vector fractions = splat_set(0);
            for (uint32_t k = 0; k < Channels; k++) {
                const int64_t gain = noise->gain[c * 3 + k];
                const splat_vector size =
                    splat_set(gain < 0 ? 0u - static_cast<uint64_t>(gain) : static_cast<uint64_t>(gain));
                const splat_vector whole = splat_high_times(pixel_sums[k], size),
                                   fraction = splat_low_times(pixel_sums[k], size);
                accumulated = gain < 0 ? splat_sub(accumulated, whole) : splat_add(accumulated, whole);
                fractions = gain < 0 ? splat_sub(fractions, fraction) : splat_add(fractions, fraction);
            }
            /* floor(fractions / 2^32) and the rounding shift, as unsigned shifts of biased values */
            accumulated =
                splat_add(accumulated,
                          splat_sub(splat_shift_right(splat_add(fractions, floor_bias), 32), floor_unbias));
            values[c] = splat_sub(splat_shift_right(splat_add(accumulated, rounding), shift), rounding_bias);
        }
#if defined(DSN_SPLAT_STORE_PIXELS)
        splat_store_pixels<Channels>(out + done * Channels, values);
#else
        uint64_t lanes[Channels][splat_lanes];
        for (uint32_t c = 0; c < Channels; c++) splat_store(lanes[c], values[c]);
        for (uint32_t k = 0; k < splat_lanes; k++)
            for (uint32_t c = 0; c < Channels; c++) {
                const int64_t value = signed_from_bits(lanes[c][k]);
                out[(done + k) * Channels + c] = value > INT32_MAX   ? INT32_MAX
                                                 : value < INT32_MIN ? INT32_MIN
                                                                     : static_cast<int32_t>(value);
            }
#endif
    }
    for (; done < count; done++) {
        uint64_t pixel_sums[Channels];
        for (uint32_t c = 0; c < Channels; c++) pixel_sums[c] = sums[c * plane + done];
        normalize_q32_channels<Channels>(noise, offset, pixel_sums, out + done * Channels);
    }
}
#endif

/* normalize_q32_from of `count` pixels (channel c of pixel p at sums[c plane + p]) with this offset: on
   vectors on x86, else pixel by pixel. */
inline void splat_normalize_from(const dsn_noise_state *noise, const int64_t *offset, const uint64_t *sums,
                                 size_t plane, uint32_t count, int32_t *out) {
#if DSN_SPLAT_CELLS
    if (noise->asset.channels == 3)
        splat_normalize_vector<3>(noise, offset, sums, plane, count, out);
    else
        splat_normalize_vector<1>(noise, offset, sums, plane, count, out);
#else
    const uint32_t channels = noise->asset.channels;
    for (uint32_t p = 0; p < count; p++) {
        uint64_t pixel_sums[DSN_MAX_CHANNELS];
        for (uint32_t c = 0; c < channels; c++) pixel_sums[c] = sums[c * plane + p];
        normalize_q32_from(noise, offset, pixel_sums, out + p * channels);
    }
#endif
}

/* The normalization entry: the values' (the mean's offset). */
inline void continuous_splat_normalize(const dsn_noise_state *noise, const uint64_t *sums, size_t plane,
                                       uint32_t count, int32_t *out) {
    splat_normalize_from(noise, noise->offset, sums, plane, count, out);
}

} // namespace

#endif /* DSN_SPLAT_ROW_H */
