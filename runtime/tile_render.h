/* runtime/tile_render.h - a whole tile on the lattice, computed in this translation unit: the tile is
   cut into runs of contiguous coordinates (tile_walk.h), each run into blocks; a block's impulses are
   splatted into 16-bit sums that stay in L1 (tile_block.h) and normalized straight into the output
   (tile_normalize.h), or, when 16 bits cannot hold the sums (16-bit textons, large textons, extreme
   densities), splatted into a 32-bit accumulator and normalized one pixel at a time. Either way the sums
   are the per-point sums (integer addition modulo 2^32 is order-free, and the 16-bit sums provably never
   wrap), so the bits equal the per-point path's. Included by tile.cpp and, built for AVX2, by
   tile_avx2.cpp (everything here has internal linkage, so the two copies never mix). */
#ifndef DSN_TILE_RENDER_H
#define DSN_TILE_RENDER_H

/* The blocked path keeps about 27 KB on the stack (the 16-bit block, the planar texton, the impulse list)
   and pays off only with vector instructions; without them, the 32-bit path keeps a tile call's stack
   under 1 KB, which microcontrollers need. Both give the same bits. Define DSN_TILE_BLOCKS to 0 or 1 to
   choose. */
#ifndef DSN_TILE_BLOCKS
#if defined(__SSE2__)
#define DSN_TILE_BLOCKS 1
#else
#define DSN_TILE_BLOCKS 0
#endif
#endif

#include "tile_walk.h"

#if DSN_TILE_BLOCKS
namespace {
/* Output stores of the blocked path, typed (declared before its templates use them). */
inline void store_value(int32_t *out, int32_t value) { *out = value; }
inline void store_value(float *out, int32_t value) { *out = dsn_fixed_to_float(value); }
inline void store_value(uint8_t *out, int32_t value) { *out = dsn_fixed_to_u8(value); }
} // namespace

#include "tile_block.h"
#include "tile_normalize.h"
#endif

namespace {

/* The 32-bit path converts pixel by pixel (dsn_store_pixel) rather than with one copy of the tile code
   per output type; the blocked path (SSE2), whose inner loop is the row normalization, keeps one copy per
   type, chosen once per tile. */

#if DSN_TILE_BLOCKS
/* Everything a tile call prepares once for the blocked path. */
typedef struct block_setup {
    planar_texton texton;
    int split_ok;
#if defined(__SSE2__)
    split_vectors split;
#endif
} block_setup;

void make_block_setup(const dsn_noise *noise, block_setup *setup) {
    make_planar_texton(&noise->asset, &setup->texton);
    split_normalization split;
    setup->split_ok = make_split_normalization(noise, &split);
#if defined(__SSE2__)
    if (setup->split_ok) make_split_vectors(&split, noise->asset.channels, &setup->split);
#else
    setup->split_ok = 0;
#endif
}
#endif /* DSN_TILE_BLOCKS */

/* Where a tile's values go: `out` (width * channels values of type `kind` per row) and the 32-bit
   accumulator of the fallback (`out` itself for fixed output, else the scratch). */
typedef struct tile_target {
    void *out;
    dsn_output_kind kind;
    uint32_t *accumulator;
    uint32_t row_values;
} tile_target;

/* The 32-bit path for a rectangle of single runs (a block with too many impulses, or a whole run when
   the texton does not fit the 16-bit path): 32-bit sums in the tile accumulator, then each pixel. */
void render_block_32(const dsn_noise *noise, const tile_run *block_x, const tile_run *block_y,
                     const tile_target *target) {
    const uint32_t channels = noise->asset.channels, row_values = target->row_values;
    for (uint32_t row = 0; row < block_y->length; row++) {
        uint32_t *sums =
            target->accumulator + size_t(block_y->offset + row) * row_values + block_x->offset * channels;
        for (uint32_t i = 0; i < block_x->length * channels; i++) sums[i] = 0;
    }
    splat_region(noise, block_x, block_y, target->accumulator, row_values);
    for (uint32_t row = 0; row < block_y->length; row++) {
        size_t first = size_t(block_y->offset + row) * row_values + block_x->offset * channels;
        for (uint32_t i = 0; i < block_x->length; i++) {
            const uint32_t *pixel = target->accumulator + first + i * channels;
            uint32_t sums[3] = {pixel[0], channels == 3 ? pixel[1] : 0u, channels == 3 ? pixel[2] : 0u};
            int32_t fixed[3];
            dsn_normalize(noise, sums, fixed); /* sums are copied first: fixed output may overwrite them */
            dsn_store_pixel(target->out, target->kind, first + i * channels, fixed, channels);
        }
    }
}

#if DSN_TILE_BLOCKS
/* A rectangle of the tile, block_width x walk_height at most: its impulses are listed once, then
   splatted block by block (blocks of block_height rows). One copy per output type (`target->kind`):
   the row normalization is the blocked path's inner loop. */
template <typename Value>
void render_blocks(const dsn_noise *noise, const block_setup *setup, const tile_run *walk_x,
                   const tile_run *walk_y, const tile_target *target) {
    impulse_list list;
    list.clear();
    for_each_reaching_impulse(noise, walk_x, walk_y, list);
    if (!list.sums_fit_16_bits()) {
        render_block_32(noise, walk_x, walk_y, target);
        return;
    }
    const uint32_t channels = noise->asset.channels;
    block_accumulator block;
    for (uint32_t first_row = 0; first_row < walk_y->length; first_row += block_height) {
        if (channels == 3)
            splat_block<3>(&list, &setup->texton, first_row, &block);
        else
            splat_block<1>(&list, &setup->texton, first_row, &block);
        const uint32_t rows =
            walk_y->length - first_row < block_height ? walk_y->length - first_row : block_height;
        for (uint32_t row = 0; row < rows; row++) {
            Value *out = static_cast<Value *>(target->out) +
                         size_t(walk_y->offset + first_row + row) * target->row_values +
                         walk_x->offset * channels;
#if defined(__SSE2__)
            if (setup->split_ok) {
                if (channels == 3)
                    normalize_row_vectors<3>(&setup->split, &block, row, walk_x->length, out);
                else
                    normalize_row_vectors<1>(&setup->split, &block, row, walk_x->length, out);
                continue;
            }
#endif
            normalize_row_scalar(noise, &block, row, 0, walk_x->length, out);
        }
    }
}

/* One rectangle of the tile where both axes are single runs, in rectangles of block_width x walk_height. */
template <typename Value>
void render_region(const dsn_noise *noise, const block_setup *setup, const tile_run *run_x,
                   const tile_run *run_y, const tile_target *target) {
    for (uint32_t y = 0; y < run_y->length; y += walk_height) {
        tile_run walk_y = {run_y->start + y, run_y->offset + y,
                           run_y->length - y < walk_height ? run_y->length - y : walk_height};
        for (uint32_t x = 0; x < run_x->length; x += block_width) {
            tile_run walk_x = {run_x->start + x, run_x->offset + x,
                               run_x->length - x < block_width ? run_x->length - x : block_width};
            render_blocks<Value>(noise, setup, &walk_x, &walk_y, target);
        }
    }
}

/* The whole tile in blocks, with the output type's copy of the blocked path. */
template <typename Value>
void render_blocked_tile(const dsn_noise *noise, const tile_run *runs_x, uint32_t run_count_x,
                         const tile_run *runs_y, uint32_t run_count_y, const tile_target *target) {
    block_setup setup;
    make_block_setup(noise, &setup);
    for (uint32_t ry = 0; ry < run_count_y; ry++)
        for (uint32_t rx = 0; rx < run_count_x; rx++)
            render_region<Value>(noise, &setup, &runs_x[rx], &runs_y[ry], target);
}
#endif /* DSN_TILE_BLOCKS */

/* The whole tile: blocks of 16-bit sums when the texton allows, else 32-bit sums run by run. */
void render_tile(const dsn_noise *noise, uint32_t x0, uint32_t y0, uint32_t width, uint32_t height, void *out,
                 dsn_output_kind kind, uint32_t *accumulator) {
    tile_run runs_x[2], runs_y[2];
    uint32_t run_count_x = split_runs(x0, width, noise->period[0], runs_x);
    uint32_t run_count_y = split_runs(y0, height, noise->period[1], runs_y);
    tile_target target = {out, kind, accumulator, width * noise->asset.channels};
#if DSN_TILE_BLOCKS
    /* A single point (how the small build evaluates per point) takes the 32-bit path: no planar copy of
       the texton and no block on the stack for one pixel. */
    if ((width > 1 || height > 1) && planar_texton_fits(&noise->asset)) {
        if (kind == dsn_output_float)
            render_blocked_tile<float>(noise, runs_x, run_count_x, runs_y, run_count_y, &target);
        else if (kind == dsn_output_u8)
            render_blocked_tile<uint8_t>(noise, runs_x, run_count_x, runs_y, run_count_y, &target);
        else
            render_blocked_tile<int32_t>(noise, runs_x, run_count_x, runs_y, run_count_y, &target);
        return;
    }
#endif
    for (uint32_t ry = 0; ry < run_count_y; ry++)
        for (uint32_t rx = 0; rx < run_count_x; rx++)
            render_block_32(noise, &runs_x[rx], &runs_y[ry], &target);
}

} // namespace

#endif /* DSN_TILE_RENDER_H */
