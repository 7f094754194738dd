/* runtime/evaluators/grid_splat.h - a grid's pixels (dsn_grid: any affine map, periodic noises too) evaluated
   by splatting: the impulses near a block of its pixels each add their bilinear texture (the texton, or a
   level of its pyramid) to the block's 64-bit sums, pixel by pixel the per-point sums. The fast path of
   the continuous tile (continuous_tile.cpp) and of the filtered tile (filtered_tile.cpp); the small build
   (DSN_SMALL_CODE) evaluates grids point by point and has none of it. Internal to libdsn; not
   installed. */
#ifndef DSN_GRID_SPLAT_H
#define DSN_GRID_SPLAT_H

#include <stddef.h>
#include <stdint.h>

#include "kernels/kernels.h"

#if !DSN_SMALL_CODE

/* The columns an impulse reaches along one axis, row by row (grid_splat.cpp's column bounds): what
   depends on the grid alone. */
typedef struct dsn_splat_columns {
    int64_t denominator;                     /* |column step|; 0: the axis is constant along a row */
    int64_t sign;                            /* low numerator = sign offset - reach: -1 for column > 0 */
    int64_t step_quotient, step_remainder;   /* sign row over the denominator */
    int64_t width_quotient, width_remainder; /* 2 reach - 1 over the denominator */
    int64_t row, reach;
} dsn_splat_columns;

/* One axis of the grid in its frame: an int64 coordinate in which the pixels are base + i column + j
   row exactly (no wrap) and each impulse that may reach the tile has one position per image (one without
   a period, one per copy of the period otherwise). */
typedef struct dsn_splat_axis {
    int64_t base;           /* frame coordinate of pixel (0, 0) */
    int64_t column, row;    /* steps per column and per row */
    uint32_t lattice_base;  /* without a period: the lattice coordinate of frame 0 */
    uint32_t period, shift; /* period 0: none */
    int64_t reach;          /* an impulse reaches the offsets in (-reach, reach) */
    dsn_splat_columns columns;
} dsn_splat_axis;

/* A grid ready to splat one texture: both frames, what the kernel's runs share, and which impulses it
   splats (every one where `filter` is null, as init leaves it; a mixed tile's material sets it). */
typedef struct dsn_grid_splat {
    dsn_splat_axis x, y;
    dsn_splat_setup setup; /* its cells, plane and sums_end are set by whoever fills a block */
    dsn_splat_runs_entry *runs;
    const dsn_impulse_filter *filter;
} dsn_grid_splat;

/* Blocks of the tile: at most this many columns and rows (one run per row, as long as a row). */
enum { dsn_splat_block_columns = dsn_splat_run_longest, dsn_splat_block_rows = dsn_splat_runs_most };

/* A block: columns [left, left + columns), rows [top, top + rows); its sums planar, channel c of its
   pixel (i, j) at sums[c * plane + j * stride + i]. */
typedef struct dsn_splat_block {
    uint32_t left, top, columns, rows, stride;
    size_t plane;
} dsn_splat_block;

/* Prepares `splat` to read `texture` over the grid's width x height pixels. Returns 0 when the grid is
   evaluated point by point instead: it does not fit a frame (too large, or a periodic axis whose points
   cross the int32 wrap of the lattice coordinate), or it is so sparse that per point is cheaper. */
int dsn_internal_grid_splat_init(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width,
                                 uint32_t height, const dsn_splat_texture *texture, dsn_grid_splat *splat);

/* Widens the offsets an impulse reaches from (-reach, reach) to [-reach, reach] on both axes (the kernel
   reads them as before): the gradient's runs (kernels.h's continuous_gradient_runs), whose slopes are
   one-sided toward +x and +y, so that an impulse exactly at the edge where it enters the reach adds its
   slope (its value is 0), as per point; at the other edge both are 0. The texture's records then need a
   margin (splat_cells.h). */
void dsn_internal_grid_splat_closed(dsn_grid_splat *splat);

/* The pixels whose sums a block of the tile takes at most: the tile's, or one block's with its rows
   padded by a cache line, whichever is fewer (at most 72 x 32). */
size_t dsn_internal_splat_block_pixels(uint32_t width, uint32_t height);

/* The block of the tile whose top-left pixel is (left, top) (multiples of the block sides), its rows
   padded where dsn_internal_splat_block_pixels leaves room. */
dsn_splat_block dsn_internal_splat_block(uint32_t left, uint32_t top, uint32_t width, uint32_t height);

/* The block of the tile at (left, top) of at most `columns` x `rows` pixels, its rows unpadded: the
   gradient tiles' smaller blocks, whose sums live on the stack. */
dsn_splat_block dsn_internal_splat_small_block(uint32_t left, uint32_t top, uint32_t width, uint32_t height,
                                               uint32_t columns, uint32_t rows);

/* Zeroes the block's sums (sums[0 .. channels plane)) and adds every impulse within reach. */
void dsn_internal_grid_splat_block(const dsn_noise_state *noise, const dsn_grid_splat *splat,
                                   const dsn_splat_block *block, uint64_t *sums);

/* Bytes of scratch that hold the 64-bit sums of dsn_internal_splat_block_pixels pixels at any
   alignment: every block's, one at a time. */
size_t dsn_internal_splat_sums_size(uint32_t channels, uint32_t width, uint32_t height);

/* The scratch as an array of uint64, aligned (the caller's buffer needs no alignment). */
uint64_t *dsn_internal_aligned_sums(void *scratch);

#endif /* !DSN_SMALL_CODE */

#endif /* DSN_GRID_SPLAT_H */
