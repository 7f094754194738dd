/* runtime/kernels/tile_gradient.h - a lattice tile with its forward differences (dsn.h, "Gradients"): the
   value at (x, y) and the differences to (x + 1, y) and (x, y + 1), which are the spot noise of the
   differenced texton, from the sums of one more column and row than the tile has. Each rectangle's sums
   are summed strip by strip as the value tile's are (tile_strips.h), kept three rows at a time in 16-bit
   rows, and every output row's value and both differences are normalized from them in lanes
   (difference_lanes); where the strips cannot take a rectangle (too dense, a period's cut inside it, a
   texton they do not hold), its sums are splatted in 32 bits (tile_walk.h) and normalized point by point.
   Either way the sums are the per-point sums, so the bits are the per-point path's. Internal to
   tile_render.h. */
#ifndef DSN_TILE_GRADIENT_H
#define DSN_TILE_GRADIENT_H

#if DSN_GRADIENTS
#include "core/gradient_output.h"

namespace {

/* Where a gradient tile's values go: three outputs of `kind`, `tile_width` points a row. */
typedef struct gradient_target {
    void *out, *dx, *dy;
    dsn_output_kind kind;
    uint32_t channels, tile_width;
} gradient_target;

/* The 32-bit path works in blocks whose sums, one more column and row, stay on the stack (about 7 KB). */
const uint32_t gradient_block_width = 32, gradient_block_height = 16;

/* The sums of the (width + 1) x (height + 1) points from (x, y) (coordinates modulo 2^32, as a lattice
   tile's pixels: the point right of x is x + 1 even where a period's reduction cuts the run at INT32_MAX,
   split_runs), into `sums`, row-major, channels interleaved. */
void extended_sums(const dsn_noise_state *noise, uint32_t x, uint32_t y, uint32_t width, uint32_t height,
                   uint32_t *sums) {
    const uint32_t row_stride = (width + 1u) * noise->asset.channels;
    for (uint32_t i = 0; i < row_stride * (height + 1u); i++) sums[i] = 0;
    tile_run runs_x[2], runs_y[2];
    const uint32_t count_x = split_runs(x, width + 1u, noise->period[0], runs_x);
    const uint32_t count_y = split_runs(y, height + 1u, noise->period[1], runs_y);
    for (uint32_t j = 0; j < count_y; j++)
        for (uint32_t i = 0; i < count_x; i++)
            splat_region(noise, &runs_x[i], &runs_y[j], sums, row_stride, 0);
}

/* One point's value and differences from its sums and its neighbours', normalized and mapped, stored at
   point `index` of the target. */
void store_gradient_point(const dsn_noise_state *noise, const uint32_t *here, const uint32_t *east,
                          const uint32_t *south, const gradient_target *target, size_t index) {
    int32_t values[3 * DSN_MAX_CHANNELS];
    dsn_lattice_gradient_values(noise, here, east, south, values);
    dsn_store_gradient(target->out, target->dx, target->dy, target->kind, index * target->channels, values,
                       target->channels);
}

/* The 32-bit path for the width x height points of the tile from point (left, top), at (x, y). */
void gradient_rectangle_32(const dsn_noise_state *noise, uint32_t x, uint32_t y, uint32_t left, uint32_t top,
                           uint32_t width, uint32_t height, const gradient_target *target) {
    const uint32_t channels = target->channels;
    for (uint32_t block_y = 0; block_y < height; block_y += gradient_block_height)
        for (uint32_t block_x = 0; block_x < width; block_x += gradient_block_width) {
            const uint32_t block_w =
                width - block_x < gradient_block_width ? width - block_x : gradient_block_width;
            const uint32_t block_h =
                height - block_y < gradient_block_height ? height - block_y : gradient_block_height;
            uint32_t sums[(gradient_block_width + 1) * (gradient_block_height + 1) * DSN_MAX_CHANNELS];
            extended_sums(noise, x + block_x, y + block_y, block_w, block_h, sums);
            const uint32_t row_stride = (block_w + 1u) * channels;
            for (uint32_t j = 0; j < block_h; j++)
                for (uint32_t i = 0; i < block_w; i++) {
                    const uint32_t *here = sums + j * row_stride + i * channels;
                    const size_t index = size_t(top + block_y + j) * target->tile_width + left + block_x + i;
                    store_gradient_point(noise, here, here + channels, here + row_stride, target, index);
                }
        }
}

#if DSN_TILE_BLOCKS
/* ---- Differences of 16-bit sums in lanes ----
   A difference of sums has no mean: its normalization is round(sum_k gain_ck (Q'_k - Q_k) / 2^s). With
   the value's split (tile_normalize.h), gain = 2^15 high + low, it is floor((A + 2^(s-16) + floor(B /
   2^15)) / 2^(s-15)) where A = sum_k high_k (Q'_k - Q_k) and B likewise with low: A is the difference of
   the two sums' A, exact modulo 2^32 as long as the true A fits; floor(B / 2^15) is taken from the two B
   (each within int32, the value's bound), floor(B' / 2^15) - floor(B / 2^15) + floor(((B' mod 2^15) -
   (B mod 2^15)) / 2^15), the last term -1 or 0. Every |Q| < 2^15, so |Q' - Q| < 2^16, and with H_c and L_c
   the sums of |high_ck| and |low_ck| the result stays in int32 where 2^16 H_c + 2 L_c + 1 + 2^(s-16) <
   2^31 (difference_fits), which holds for the gains init makes unless a texton is almost all zeros. */
typedef struct difference_vectors {
    simd_vector half, low_mask; /* 2^(s-16), 2^15 - 1 */
} difference_vectors;

int difference_fits(const split_normalization *split, uint32_t channels) {
    for (uint32_t c = 0; c < channels; c++) {
        int64_t high = 0, low = 0;
        for (uint32_t k = 0; k < 3; k++) {
            high += split->high[3 * c + k] < 0 ? -split->high[3 * c + k] : split->high[3 * c + k];
            low += split->low[3 * c + k] < 0 ? -split->low[3 * c + k] : split->low[3 * c + k];
        }
        if ((high << 16) + 2 * low + 1 + (int64_t(1) << (split->shift - 1)) >= (int64_t(1) << 31)) return 0;
    }
    return 1;
}

/* The difference's normalization from its A (a) and the B of both sums (b_to, b_from). */
inline simd_vector difference_lanes(const split_vectors *v, const difference_vectors *d, simd_vector a,
                                    simd_vector b_to, simd_vector b_from) {
    const simd_vector below =
        shift_right_15(subtract_32(bitwise_and(b_to, d->low_mask), bitwise_and(b_from, d->low_mask)));
    const simd_vector b = add_32(subtract_32(shift_right_15(b_to), shift_right_15(b_from)), below);
    return shift_right(add_32(add_32(d->half, a), b), v->shift);
}

/* The parts of a strip row's sums (one vector per channel) for each output channel c: parts[2 h][c] = A
   and parts[2 h + 1][c] = B + P_l (tile_normalize.h) of half h (the pixels of unpack_low_16, then
   unpack_high_16). */
template <uint32_t Channels>
DSN_SIMD_INLINE void sum_parts(const split_vectors *v, const simd_vector *sums, simd_vector (*parts)[3]) {
    const simd_vector ones = set_16(1);
#pragma GCC unroll 2
    for (uint32_t h = 0; h < 2; h++) {
        const simd_vector pair = h ? unpack_high_16(sums[0], sums[1]) : unpack_low_16(sums[0], sums[1]);
        const simd_vector third = h ? unpack_high_16(sums[2], ones) : unpack_low_16(sums[2], ones);
#pragma GCC unroll 3
        for (uint32_t c = 0; c < Channels; c++) {
            parts[2 * h][c] = high_part(v, c, pair, third);
            parts[2 * h + 1][c] = low_part(v, c, pair, third);
        }
    }
}

/* A strip row's value and both differences, normalized from the sums of its points, of the points right
   of them and of those below (one vector per channel each), each output stored as soon as it is made:
   the point's own parts are computed once for all three. */
template <uint32_t Channels, typename Value>
DSN_SIMD_INLINE void store_gradient_strip(const split_vectors *v, const difference_vectors *d,
                                          const simd_vector *here, const simd_vector *east,
                                          const simd_vector *south, uint32_t pixels, Value *out, Value *dx,
                                          Value *dy) {
    simd_vector own[4][3], lanes[2][3];
    sum_parts<Channels>(v, here, own);
#pragma GCC unroll 2
    for (uint32_t h = 0; h < 2; h++)
#pragma GCC unroll 3
        for (uint32_t c = 0; c < Channels; c++)
            lanes[h][c] = value_lanes(v, c, own[2 * h][c], own[2 * h + 1][c]);
    store_lanes<Channels>(lanes, pixels, out);
#pragma GCC unroll 2
    for (uint32_t k = 0; k < 2; k++) {
        simd_vector moved[4][3];
        sum_parts<Channels>(v, k ? south : east, moved);
#pragma GCC unroll 2
        for (uint32_t h = 0; h < 2; h++)
#pragma GCC unroll 3
            for (uint32_t c = 0; c < Channels; c++)
                lanes[h][c] = difference_lanes(v, d, subtract_32(moved[2 * h][c], own[2 * h][c]),
                                               moved[2 * h + 1][c], own[2 * h + 1][c]);
        store_lanes<Channels>(lanes, pixels, k ? dy : dx);
    }
}

/* Three rows of a rectangle's 16-bit sums (row r in rows[r % 3]), a plane per channel: up to
   strip_capacity strips. */
typedef struct sum_rows {
    alignas(64) strip_texel rows[3][3][rectangle_width + lane];
} sum_rows;

/* Everything a gradient tile prepares once for the strip path. */
typedef struct gradient_setup {
    strip_setup strips;
    difference_vectors difference;
    int lanes; /* value and differences normalized in lanes (else point by point) */
} gradient_setup;

/* The sums of one channel of a strip of row `row`, starting `shift` points to the right. */
inline void load_sums(const sum_rows *sums, uint32_t row, uint32_t first, uint32_t shift, simd_vector *out) {
    for (uint32_t c = 0; c < 3; c++) out[c] = load_texels(sums->rows[row % 3][c] + first + shift);
}

/* Output row `row` of a rectangle `width` points wide from its sums and the next row's. */
template <uint32_t Channels, typename Value>
void gradient_row(const dsn_noise_state *noise, const gradient_setup *setup, const sum_rows *sums,
                  uint32_t row, uint32_t width, const gradient_target *target, size_t first_index) {
    for (uint32_t s = 0; s * lane < width; s++) {
        const uint32_t pixels = width - s * lane < lane ? width - s * lane : lane;
        const size_t index = first_index + s * lane;
        if (!setup->lanes) {
            for (uint32_t i = 0; i < pixels; i++) {
                uint32_t here[3] = {0, 0, 0}, east[3] = {0, 0, 0}, south[3] = {0, 0, 0};
                for (uint32_t c = 0; c < Channels; c++) {
                    here[c] = widen_sum(sums->rows[row % 3][c][s * lane + i]);
                    east[c] = widen_sum(sums->rows[row % 3][c][s * lane + i + 1]);
                    south[c] = widen_sum(sums->rows[(row + 1) % 3][c][s * lane + i]);
                }
                store_gradient_point(noise, here, east, south, target, index + i);
            }
            continue;
        }
        simd_vector here[3], east[3], south[3];
        load_sums(sums, row, s * lane, 0, here);
        load_sums(sums, row, s * lane, 1, east);
        load_sums(sums, row + 1, s * lane, 0, south);
        store_gradient_strip<Channels>(&setup->strips.split, &setup->difference, here, east, south, pixels,
                                       static_cast<Value *>(target->out) + index * Channels,
                                       static_cast<Value *>(target->dx) + index * Channels,
                                       static_cast<Value *>(target->dy) + index * Channels);
    }
}

/* The width x height points of the tile from point (left, top), whose sums are the rectangle sums_x x
   sums_y (single runs, one more column and row): its impulses listed and filed under the strips once, then
   two rows at a time summed, kept, and every output row whose next row is kept normalized. */
template <uint32_t Channels, typename Value>
void gradient_rectangle(const dsn_noise_state *noise, const gradient_setup *setup, const tile_run *sums_x,
                        const tile_run *sums_y, uint32_t left, uint32_t top, const gradient_target *target) {
    const uint32_t width = sums_x->length - 1u, height = sums_y->length - 1u;
    impulse_list list;
    list.clear(sums_x->length, sums_y->length);
    for_each_nearby_impulse(noise, sums_x, sums_y, list, keep_every());
    if (!list.prepare(setup->strips.texton.width, setup->strips.texton.height)) {
        gradient_rectangle_32(noise, sums_x->start, sums_y->start, left, top, width, height, target);
        return;
    }
    strip_entries entries;
    const strip_texton *texton = &setup->strips.texton;
    file_strip_entries(&list, texton, sums_x->length, sums_y->length, &entries);
    const strip_texel *row_zero = texton->values + (strip_rows - 1) * texton->stride;
    sum_rows sums; /* zeroed: the loads of the last strip read past the sums */
    for (uint32_t k = 0; k < 3; k++)
        for (uint32_t c = 0; c < 3; c++)
            for (uint32_t i = 0; i < rectangle_width + lane; i++) sums.rows[k][c][i] = 0;
    for (uint32_t y = 0; y < sums_y->length; y += strip_rows) {
        const uint32_t last_key_end = y + strip_rows - 1 + texton->height;
        for (uint32_t s = 0; s * lane < sums_x->length; s++) {
            simd_vector strip[3 * strip_rows];
            const uint32_t first = entries.key_start[s][y], end = entries.key_start[s][last_key_end];
            add_strip_rows<Channels>(row_zero + y * texton->stride, entries.base + first, end - first,
                                     texton->plane, texton->stride, strip);
            for (uint32_t r = 0; r < strip_rows; r++)
                for (uint32_t c = 0; c < Channels; c++)
                    store_16(sums.rows[(y + r) % 3][c] + s * lane, strip[3 * r + c]);
        }
        for (uint32_t row = y == 0 ? 0 : y - 1; row <= y && row < height; row++)
            gradient_row<Channels, Value>(noise, setup, &sums, row, width, target,
                                          size_t(top + row) * target->tile_width + left);
    }
}

/* The tile in rectangles as wide as the strips' (their sums take one strip more) and one row shorter
   (their sums take the strips' rows), each by the strips where its sums are single runs, else by the
   32-bit path. */
template <uint32_t Channels, typename Value>
void gradient_strip_tile(const dsn_noise_state *noise, const gradient_setup *setup, uint32_t x0, uint32_t y0,
                         uint32_t width, uint32_t height, const gradient_target *target) {
    const uint32_t step_x = setup->strips.rectangle.width, step_y = setup->strips.rectangle.height - 1u;
    for (uint32_t top = 0; top < height; top += step_y)
        for (uint32_t left = 0; left < width; left += step_x) {
            const uint32_t part_w = width - left < step_x ? width - left : step_x;
            const uint32_t part_h = height - top < step_y ? height - top : step_y;
            tile_run runs_x[2], runs_y[2];
            if (split_runs(x0 + left, part_w + 1u, noise->period[0], runs_x) == 1 &&
                split_runs(y0 + top, part_h + 1u, noise->period[1], runs_y) == 1)
                gradient_rectangle<Channels, Value>(noise, setup, &runs_x[0], &runs_y[0], left, top, target);
            else
                gradient_rectangle_32(noise, x0 + left, y0 + top, left, top, part_w, part_h, target);
        }
}
#endif /* DSN_TILE_BLOCKS */

/* A whole gradient tile of `kind` (fixed or float): by the strips when they hold the texton, else by the
   32-bit path. */
void render_gradient_tile(const dsn_noise_state *noise, uint32_t x0, uint32_t y0, uint32_t width,
                          uint32_t height, void *out, void *dx, void *dy, dsn_output_kind kind) {
    const gradient_target target = {out, dx, dy, kind, noise->asset.channels, width};
#if DSN_TILE_BLOCKS
    const uint64_t pixels = uint64_t(width) * height;
    const rectangle_size rectangle =
        pixels > 1 && lattice_strips_take(noise) ? choose_rectangle(noise) : rectangle_size{0, 0};
    if (rectangle.width != 0 && kind != dsn_output_u8) {
        gradient_setup setup;
        make_strip_setup(noise, rectangle, pixels, 4, &setup.strips);
        split_normalization split;
        setup.lanes =
            make_split_normalization(noise, &split) && difference_fits(&split, noise->asset.channels);
        if (dsn_has_mapping(noise)) setup.lanes = 0; /* the chain rule, point by point */
        if (setup.lanes) {
            setup.difference.half = broadcast_lanes(set_4x32(int32_t(1) << (split.shift - 1u)));
            setup.difference.low_mask = broadcast_lanes(set_4x32(0x7FFF));
        }
        const int rgb = noise->asset.channels == 3;
        if (kind == dsn_output_float) {
            if (rgb)
                gradient_strip_tile<3, float>(noise, &setup, x0, y0, width, height, &target);
            else
                gradient_strip_tile<1, float>(noise, &setup, x0, y0, width, height, &target);
        } else {
            if (rgb)
                gradient_strip_tile<3, int32_t>(noise, &setup, x0, y0, width, height, &target);
            else
                gradient_strip_tile<1, int32_t>(noise, &setup, x0, y0, width, height, &target);
        }
        return;
    }
#endif
    gradient_rectangle_32(noise, x0, y0, 0, 0, width, height, &target);
}

} // namespace

#endif /* DSN_GRADIENTS */
#endif /* DSN_TILE_GRADIENT_H */
