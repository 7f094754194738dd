/* runtime/kernels/tile_walk.h - the impulses that reach a rectangle of a tile (the walk over the cells of
   cell_walk.h, the only source of impulses), and the 32-bit splat of their texton into a
   tile-sized accumulator: the general path, for every texton and density. Internal to tile_render.h. */
#ifndef DSN_TILE_WALK_H
#define DSN_TILE_WALK_H

#include "core/cell_walk.h"
#include "core/impulse_position.h"
#include "core/poisson_count.h"
#include "kernels/kernels.h"

#if defined(__SSE2__)
#include "simd/simd_128.h"
#endif

namespace {

/* A run of tile indices [offset, offset + length) along one axis whose coordinates are contiguous
   integers. Without a period the whole axis is one run on the torus. With a period the coordinate is
   read as int32 and reduced modulo P, so the run is cut where x0 + i passes from INT32_MAX to
   INT32_MIN (after that cut the reduced coordinates are contiguous again). */
typedef struct tile_run {
    uint32_t start, offset, length;
} tile_run;

uint32_t split_runs(uint32_t start, uint32_t length, uint32_t period, tile_run *runs) {
    uint32_t until_sign_flip = 0x80000000u - start;
    runs[0].start = start;
    runs[0].offset = 0;
    runs[0].length = length;
    if (period == 0 || until_sign_flip == 0 || until_sign_flip >= length) return 1;
    runs[0].length = until_sign_flip;
    runs[1].start = 0x80000000u;
    runs[1].offset = until_sign_flip;
    runs[1].length = length - until_sign_flip;
    return 2;
}

/* dst[i] += texton value i, for `count` interleaved values, modulo 2^32. This is the inner loop of the
   tile path; with SSE2 it runs 16 (8-bit) or 8 (16-bit) values per step (sign extension by unpacking a
   value with itself and shifting arithmetically, which is exact two's-complement in the hardware). */
template <uint32_t Bits>
inline void add_row(uint32_t *dst, const unsigned char *src, uint32_t count) {
    uint32_t i = 0;
#if defined(__SSE2__)
    if (Bits == 8) {
        for (; i + 16 <= count; i += 16) {
            vector_128 bytes = load_16x8(src + i);
            vector_128 low16 = shift_right_arithmetic_16(unpack_low_8(bytes, bytes), 8);
            vector_128 high16 = shift_right_arithmetic_16(unpack_high_8(bytes, bytes), 8);
            uint32_t *out = dst + i;
            vector_128 values[4] = {shift_right_arithmetic_32(unpack_low_16(low16, low16), 16),
                                    shift_right_arithmetic_32(unpack_high_16(low16, low16), 16),
                                    shift_right_arithmetic_32(unpack_low_16(high16, high16), 16),
                                    shift_right_arithmetic_32(unpack_high_16(high16, high16), 16)};
            /* A size_t offset, as a vector pointer's steps were: an int one changes GCC's code. */
            for (int part = 0; part < 4; part++)
                store_4x32(out + size_t(part) * 4, add_32(load_4x32(out + size_t(part) * 4), values[part]));
        }
    } else {
        for (; i + 8 <= count; i += 8) {
            vector_128 words = load_16x8(src + 2 * i);
            uint32_t *out = dst + i;
            vector_128 low = shift_right_arithmetic_32(unpack_low_16(words, words), 16);
            vector_128 high = shift_right_arithmetic_32(unpack_high_16(words, words), 16);
            store_4x32(out, add_32(load_4x32(out), low));
            store_4x32(out + 4, add_32(load_4x32(out + 4), high));
        }
    }
#endif
    if (Bits == 8) {
        for (; i < count; i++) dst[i] += uint32_t(src[i] ^ 0x80u) - 0x80u;
    } else {
        for (; i < count; i++) dst[i] += (uint32_t(src[2 * i] | (src[2 * i + 1] << 8)) ^ 0x8000u) - 0x8000u;
    }
}

/* add_row for the asset's value width. The small build has one generic loop instead of a copy per
   width; the fast build picks the specialized copy (once per texton row, a predictable branch). */
inline void add_row_of_width(uint32_t *dst, const unsigned char *src, uint32_t count, uint32_t bits) {
#if DSN_SMALL_CODE
    for (uint32_t i = 0; i < count; i++)
        dst[i] += uint32_t(bits == 8 ? dsn_read_i8(src + i) : dsn_read_i16le(src + 2 * i));
#else
    if (bits == 8)
        add_row<8>(dst, src, count);
    else
        add_row<16>(dst, src, count);
#endif
}

#if DSN_MIXING
/* The kernel entry (kernels.h's dsn_lattice_rows_entry): add_row_of_width row by row. */
inline void add_texton_rows(const unsigned char *values, size_t stride, uint32_t bits, uint32_t rows,
                            uint32_t count, uint32_t *sums, size_t sums_stride) {
    for (uint32_t row = 0; row < rows; row++)
        add_row_of_width(sums + row * sums_stride, values + row * stride, count, bits);
}
#define DSN_LATTICE_ROWS_ENTRY add_texton_rows
#else
#define DSN_LATTICE_ROWS_ENTRY 0
#endif

/* One candidate cell along one axis: the end e (dsn_reach_at) of an impulse at in-cell offset 0 (one
   at offset t has e = end - t), and the last in-cell offset before the period's cut (the impulses past it
   are discarded). */
typedef struct walk_cell {
    uint32_t end, last_offset;
} walk_cell;

inline walk_cell walk_cell_of(const dsn_span *span, uint32_t cell, uint32_t shift, uint32_t length) {
    const uint32_t origin = cell << shift;
    const walk_cell result = {span->base - origin + length - 1u, span->last_position - origin};
    return result;
}

/* Which impulses a walk keeps (1) or passes over (0): every one, or, for a mixed tile, those of one
   material (kernels.h's dsn_impulse_filter: a hash in [low, low + span)). */
struct keep_every {
    uint32_t operator()(uint32_t, uint32_t) const { return 1u; }
};
#if DSN_MIXING
struct keep_material {
    uint64_t low, span;
    uint32_t operator()(uint32_t key, uint32_t k) const {
        return uint32_t(uint64_t(dsn_material_hash(key, k)) - low < span);
    }
};
#endif

/* Calls visit(end_x, end_y, reaches) for every impulse of the cells near the rectangle run_x x run_y
   (both single runs), in the order of the hash stream: its ends (dsn_reach_at) on both axes, and what
   `keep` says of it (1 for an impulse it keeps; a mixed tile's bits, one per material) where it reaches
   the rectangle, else 0 (computed without a branch: the caller may store every impulse and count only
   those that reach). This is the only place the tile path walks cells. The
   impulses' packed offsets are read as in dsn_impulse_field, one position pair per pair's impulses. */
template <typename Visit, typename Keep>
void for_each_nearby_impulse(const dsn_noise_state *noise, const tile_run *run_x, const tile_run *run_y,
                             Visit &visit, const Keep &keep) {
    const dsn_asset *asset = &noise->asset;
    const uint32_t shift = noise->cell_shift, field_shift = dsn_field_shift(shift);
    const uint32_t per_pair_mask = (1u << (6u - field_shift)) - 1u, half_bits = 1u << (field_shift - 1u);
    const uint32_t half_mask = (1u << half_bits) - 1u, drop = half_bits - shift;
    const uint32_t limit_x = run_x->length - 1u + asset->width, limit_y = run_y->length - 1u + asset->height;
    dsn_axis axis_x, axis_y;
    dsn_axis_init(&axis_x, run_x->start, run_x->length, noise->radius[0], shift, noise->period[0]);
    dsn_axis_init(&axis_y, run_y->start, run_y->length, noise->radius[1], shift, noise->period[1]);
    for (uint32_t span_index_y = 0; span_index_y < axis_y.span_count; span_index_y++) {
        const dsn_span span_y = dsn_axis_span(&axis_y, span_index_y);
        for (uint32_t i = 0; i < span_y.cell_count; i++) {
            const uint32_t cell_y = dsn_span_cell(&span_y, i, shift), row_key = dsn_row_key(noise, cell_y);
            const walk_cell in_y = walk_cell_of(&span_y, cell_y, shift, run_y->length);
            for (uint32_t span_index_x = 0; span_index_x < axis_x.span_count; span_index_x++) {
                const dsn_span span_x = dsn_axis_span(&axis_x, span_index_x);
                for (uint32_t j = 0; j < span_x.cell_count; j++) {
                    const uint32_t cell_x = dsn_span_cell(&span_x, j, shift);
                    const walk_cell in_x = walk_cell_of(&span_x, cell_x, shift, run_x->length);
                    const uint32_t key = dsn_cell_key_in_row(noise, cell_x, row_key);
                    const uint32_t count = dsn_cell_impulse_count(noise, key);
                    uint64_t pair = 0;
                    for (uint32_t k = 0; k < count; k++) {
                        if ((k & per_pair_mask) == 0) pair = dsn_impulse_pair(noise, key, k);
                        const uint32_t field = dsn_pair_bits(pair, (k & per_pair_mask) << field_shift);
                        const uint32_t offset_x = (field & half_mask) >> drop,
                                       offset_y = ((field >> half_bits) & half_mask) >> drop;
                        const uint32_t end_x = in_x.end - offset_x, end_y = in_y.end - offset_y;
                        const uint32_t reaches = uint32_t(offset_x <= in_x.last_offset) &
                                                 uint32_t(offset_y <= in_y.last_offset) &
                                                 uint32_t(end_x < limit_x) & uint32_t(end_y < limit_y);
                        visit(end_x, end_y, (0u - reaches) & keep(key, k));
                    }
                }
            }
        }
    }
}

/* Calls visit(reach_x, reach_y) for every impulse that reaches the rectangle run_x x run_y (both single
   runs), in the order of the hash stream. */
template <typename Visit>
struct reaching_filter {
    Visit &visit;
    uint32_t length_x, length_y, width, height;

    void operator()(uint32_t end_x, uint32_t end_y, uint32_t reaches) {
        if (!reaches) return;
        dsn_reach reach_x, reach_y;
        dsn_reach_at(end_x, length_x, width, &reach_x);
        dsn_reach_at(end_y, length_y, height, &reach_y);
        visit(reach_x, reach_y);
    }
};

/* for_each_nearby_impulse over the impulses `filter` keeps: every one where it is null. */
template <typename Visit>
void for_each_kept_impulse(const dsn_noise_state *noise, const tile_run *run_x, const tile_run *run_y,
                           Visit &visit, const dsn_impulse_filter *filter) {
#if DSN_MIXING
    if (filter != 0) {
        const keep_material keep = {filter->low, filter->high - filter->low};
        for_each_nearby_impulse(noise, run_x, run_y, visit, keep);
        return;
    }
#else
    (void)filter;
#endif
    for_each_nearby_impulse(noise, run_x, run_y, visit, keep_every());
}

template <typename Visit>
void for_each_reaching_impulse(const dsn_noise_state *noise, const tile_run *run_x, const tile_run *run_y,
                               Visit &visit, const dsn_impulse_filter *filter) {
    reaching_filter<Visit> reaching = {visit, run_x->length, run_y->length, noise->asset.width,
                                       noise->asset.height};
    for_each_kept_impulse(noise, run_x, run_y, reaching, filter);
}

/* Adds each reaching impulse's texton into a 32-bit accumulator: `corner` is the rectangle's first
   value, rows are row_stride values apart. What does not change between impulses is set once. */
struct splat_32 {
    const unsigned char *texton;
    uint32_t *corner;
    uint32_t row_stride, channels, bits, texel_bytes, texton_stride;

    void operator()(const dsn_reach &reach_x, const dsn_reach &reach_y) {
        uint32_t *dst = corner + size_t(reach_y.first_index) * row_stride + reach_x.first_index * channels;
        const unsigned char *src =
            texton + reach_y.first_texton * texton_stride + reach_x.first_texton * texel_bytes;
        for (uint32_t row = 0; row < reach_y.count; row++)
            add_row_of_width(dst + size_t(row) * row_stride, src + row * texton_stride,
                             reach_x.count * channels, bits);
    }
};

/* One rectangle of the tile where both axes are single runs: the impulses `filter` keeps (every one where
   it is null). */
void splat_region(const dsn_noise_state *noise, const tile_run *run_x, const tile_run *run_y,
                  uint32_t *accumulator, uint32_t row_stride, const dsn_impulse_filter *filter) {
    const dsn_asset *asset = &noise->asset;
    const uint32_t texel_bytes = asset->channels * (asset->bits / 8);
    splat_32 splat = {asset->texton,
                      accumulator + size_t(run_y->offset) * row_stride + run_x->offset * asset->channels,
                      row_stride,
                      asset->channels,
                      asset->bits,
                      texel_bytes,
                      asset->width * texel_bytes};
    for_each_reaching_impulse(noise, run_x, run_y, splat, filter);
}

} // namespace

#endif /* DSN_TILE_WALK_H */
