/* runtime/continuous_tile.cpp - the continuous mode on a regular grid (dsn_grid): a grid under any affine
   map (zoom, rotation, shear, mirror; periodic or not) is splatted, each impulse adding its bilinear
   texton to the pixels it reaches, into sums kept in the caller's scratch; grids too sparse or too large
   for that, and every grid in the small build (DSN_SMALL_CODE, dsn.h), are evaluated point by point. Both
   give the per-point bits. */
#include "bilinear_texton.h"
#include "cell_walk.h"
#include "continuous_internal.h"
#include "impulse_position.h"
#include "kernels.h"
#include "normalize_fixed.h"
#include "poisson_count.h"
#include "splat_cells.h"

namespace {

int check_tile(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
               const void *out) {
    const int err = dsn_internal_continuous_check(noise);
    if (err != DSN_OK) return err;
    if (grid == 0 || out == 0) return DSN_ERR_NULL;
    if (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE)
        return DSN_ERR_TILE_SIZE;
    return DSN_OK;
}

#if !DSN_SMALL_CODE
/* ---- Fast path: splatting the impulses onto the tile, under any affine grid ----
   Pixel (i, j) is the point origin + i column_step + j row_step. Each axis gets a frame: an int64
   coordinate in which the pixels are base + i a + j b exactly (no wrap) and each impulse that may reach
   the tile has one position per image (one without a period; one per copy of the period otherwise).
   The tile is cut into square blocks; for each block the cells that can reach its parallelogram are
   walked once, and each of their impulses adds its bilinear texton to the pixels of the block inside its
   window, found row by row as an exact interval of columns. Pixel by pixel these are the per-point sums
   exactly: the same impulses (every impulse within reach of a pixel lies in the block's cells, each
   image visited once), the same offset (the frame difference is the per-point offset for every impulse
   within reach), the same weights, and integer sums do not depend on the order. */

/* Pixels per row and rows of a block: a run per row at most, as long as a row. */
const uint32_t block_columns = dsn_splat_run_longest, block_rows = dsn_splat_runs_most;
/* Frame coordinates stay below 2^62 in magnitude: the tile's extent below 2^61, the reach and the
   frame base below 2^60. */
const uint64_t max_extent = static_cast<uint64_t>(1) << 61;
const uint32_t max_splat_period = 1u << 27;

/* Floor of value / 2^shift (shift < 63) without shifting a negative number. */
int64_t floor_shift(int64_t value, uint32_t shift) {
    const uint64_t bias = static_cast<uint64_t>(1) << 63;
    return static_cast<int64_t>((static_cast<uint64_t>(value) + bias) >> shift) -
           static_cast<int64_t>(bias >> shift);
}

int64_t floor_divide(int64_t numerator, int64_t denominator) { /* denominator > 0 */
    const int64_t quotient = numerator / denominator;
    return (quotient * denominator > numerator) ? quotient - 1 : quotient;
}

uint64_t magnitude(int64_t value) {
    return value < 0 ? ~static_cast<uint64_t>(value) + 1u : static_cast<uint64_t>(value);
}

/* The columns i with -reach < offset + i column < reach along one axis, the offset moving by `row` per
   row: first <= i <= last, with first - 1 and last the floors of two numerators over |column| that differ
   by 2 reach - 1 and step by a constant per row. The low one is kept as a quotient and a remainder in
   [0, |column|), moved without dividing, and the high one follows from it with one comparison; what
   depends on the grid alone (ColumnSteps) is computed once, so an impulse costs one division per axis.
   With column 0 the condition does not depend on i and is tested per row. */
struct ColumnSteps {
    int64_t denominator;                     /* |column|; 0: the axis is constant along a row */
    int64_t sign;                            /* low numerator = sign offset - reach: -1 for column > 0 */
    int64_t step_quotient, step_remainder;   /* sign row over the denominator */
    int64_t width_quotient, width_remainder; /* 2 reach - 1 over the denominator */
    int64_t row, reach;
};

void column_steps_init(ColumnSteps *s, int64_t column, int64_t row, int64_t reach) {
    s->row = row;
    s->reach = reach;
    s->denominator = column < 0 ? -column : column;
    s->sign = column > 0 ? -1 : 1;
    s->step_quotient = s->step_remainder = s->width_quotient = s->width_remainder = 0;
    if (column == 0) return;
    s->step_quotient = floor_divide(s->sign * row, s->denominator);
    s->step_remainder = s->sign * row - s->step_quotient * s->denominator;
    s->width_quotient = floor_divide(2 * reach - 1, s->denominator);
    s->width_remainder = 2 * reach - 1 - s->width_quotient * s->denominator;
}

/* One axis of the grid in its frame. */
struct FrameAxis {
    int64_t base;           /* frame coordinate of pixel (0, 0) */
    int64_t column, row;    /* steps per column and per row */
    uint32_t lattice_base;  /* without a period: the lattice coordinate of frame 0 */
    uint32_t period, shift; /* period 0: none */
    uint32_t radius;
    int64_t reach;       /* (radius + 1) texels: an impulse reaches the offsets in (-reach, reach) */
    ColumnSteps columns; /* the runs of columns an impulse reaches (splat_impulse) */
};

/* The frame of one axis, or false when the grid does not fit one (too large, or a periodic axis whose
   points cross the int32 wrap of the lattice coordinate, where the period breaks). */
bool frame_axis(FrameAxis *axis, int64_t origin, int64_t column, int64_t row, uint32_t width, uint32_t height,
                uint32_t radius, uint32_t shift, uint32_t period) {
    if (magnitude(column) > max_extent / width || magnitude(row) > max_extent / height) return false;
    /* Offsets of the tile's pixels from pixel (0, 0): in [low, high], |.| < 2^62. */
    const int64_t across = column * static_cast<int64_t>(width - 1u),
                  down = row * static_cast<int64_t>(height - 1u);
    const int64_t low = (across < 0 ? across : 0) + (down < 0 ? down : 0);
    const int64_t high = (across > 0 ? across : 0) + (down > 0 ? down : 0);
    axis->column = column;
    axis->row = row;
    axis->period = period;
    axis->shift = shift;
    axis->radius = radius;
    axis->reach = static_cast<int64_t>(radius + 1u) * static_cast<int64_t>(one_texel);
    column_steps_init(&axis->columns, column, row, axis->reach);
    const uint64_t point = static_cast<uint64_t>(origin);
    if (period == 0) {
        /* The lattice is a torus of 2^32 texels: frame = point - (lattice_base << 32). */
        axis->lattice_base = static_cast<uint32_t>(point >> 32);
        axis->base = static_cast<int64_t>(point & 0xFFFFFFFFu);
        return true;
    }
    if (period >= max_splat_period) return false;
    /* Per point, the coordinate u = int32(X - 1) 2^32 + fraction (X the integer part) is reduced modulo
       the period; across the tile u is affine only when no pixel leaves the int64 range. */
    const int64_t u = signed_from_bits(point - one_texel);
    if ((u < 0 && low < INT64_MIN - u) || (u > 0 && high > INT64_MAX - u)) return false;
    const uint32_t whole = static_cast<uint32_t>(point >> 32) - 1u; /* int32 bits of X - 1 */
    const uint32_t start = (whole & 0x80000000u) ? period - 1u - ~whole % period : whole % period;
    /* The reduced point plus one texel, as per point: impulses then sit at their own positions. */
    axis->lattice_base = 0;
    axis->base = static_cast<int64_t>(start + 1u) * static_cast<int64_t>(one_texel) +
                 static_cast<int64_t>(point & 0xFFFFFFFFu);
    return true;
}

/* The cells of one axis that may reach the frame interval [low, high] (already widened by the reach),
   as spans: one without a period, one per copy of the period met otherwise. */
struct FrameSpans {
    int64_t first_lattice, last_lattice; /* the lattice window, frame units */
    int64_t first_copy;
    uint32_t span_count;
};

struct FrameSpan {
    uint32_t first_cell, cell_count; /* cell indices (wrapped) */
    uint32_t last_position;          /* impulses at lattice positions beyond are discarded */
    int64_t first_origin;            /* frame coordinate of the first cell's origin */
};

void frame_spans(const FrameAxis &axis, int64_t low, int64_t high, FrameSpans *spans) {
    spans->first_lattice = floor_shift(low, 32);
    spans->last_lattice = floor_shift(high, 32);
    spans->first_copy = 0;
    spans->span_count = 1;
    if (axis.period != 0) {
        const int64_t period = static_cast<int64_t>(axis.period);
        spans->first_copy = floor_divide(spans->first_lattice, period);
        spans->span_count =
            static_cast<uint32_t>(floor_divide(spans->last_lattice, period) - spans->first_copy + 1);
    }
}

FrameSpan frame_span(const FrameAxis &axis, const FrameSpans &spans, uint32_t index) {
    FrameSpan span;
    const uint32_t mask = (1u << axis.shift) - 1u;
    if (axis.period == 0) {
        const uint32_t low = axis.lattice_base + static_cast<uint32_t>(spans.first_lattice);
        span.first_cell = low >> axis.shift;
        span.cell_count =
            (((low & mask) + static_cast<uint32_t>(spans.last_lattice - spans.first_lattice)) >> axis.shift) +
            1u;
        span.last_position = 0xFFFFFFFFu;
        span.first_origin =
            (spans.first_lattice - static_cast<int64_t>(low & mask)) * static_cast<int64_t>(one_texel);
        return span;
    }
    const int64_t period = static_cast<int64_t>(axis.period);
    const int64_t copy_start = (spans.first_copy + static_cast<int64_t>(index)) * period;
    int64_t first = spans.first_lattice - copy_start, last = spans.last_lattice - copy_start;
    if (first < 0) first = 0;
    if (last > period - 1) last = period - 1;
    span.first_cell = static_cast<uint32_t>(first) >> axis.shift;
    span.cell_count = (static_cast<uint32_t>(last) >> axis.shift) - span.first_cell + 1u;
    span.last_position = axis.period - 1u;
    span.first_origin =
        (copy_start + static_cast<int64_t>(span.first_cell << axis.shift)) * static_cast<int64_t>(one_texel);
    return span;
}

struct ColumnBounds {
    int64_t quotient, remainder; /* the low floor: first = quotient + 1 */
    int64_t offset;              /* the row's offset */
};

inline void column_bounds_init(ColumnBounds *b, const ColumnSteps &s, int64_t offset) {
    b->offset = offset;
    b->quotient = b->remainder = 0;
    if (s.denominator == 0) return;
    const int64_t numerator = s.sign * offset - s.reach;
    b->quotient = floor_divide(numerator, s.denominator);
    b->remainder = numerator - b->quotient * s.denominator;
}

/* Narrows [*first, *last] to this axis' columns in the current row. */
inline void column_bounds_apply(const ColumnBounds &b, const ColumnSteps &s, int64_t *first, int64_t *last) {
    if (s.denominator == 0) {
        if (b.offset <= -s.reach || b.offset >= s.reach) *last = *first - 1;
        return;
    }
    const int64_t low = b.quotient + 1;
    const int64_t high =
        b.quotient + s.width_quotient + (b.remainder + s.width_remainder >= s.denominator ? 1 : 0);
    if (low > *first) *first = low;
    if (high < *last) *last = high;
}

inline void column_bounds_next(ColumnBounds *b, const ColumnSteps &s) {
    b->offset += s.row;
    b->remainder += s.step_remainder;
    const int64_t carry = b->remainder >= s.denominator ? 1 : 0;
    b->quotient += s.step_quotient + carry;
    b->remainder -= carry * s.denominator;
}

/* A block of the tile: columns [first_column, end_column), rows [first_row, end_row). */
struct Block {
    uint32_t first_column, end_column, first_row, end_row;
    uint32_t stride; /* sums from one row of the block to the next */
};

/* The frame interval of the block's pixels along one axis. */
void block_extent(const FrameAxis &axis, const Block &block, int64_t *low, int64_t *high) {
    const int64_t corner = axis.base + axis.column * static_cast<int64_t>(block.first_column) +
                           axis.row * static_cast<int64_t>(block.first_row);
    const int64_t across = axis.column * static_cast<int64_t>(block.end_column - 1u - block.first_column);
    const int64_t down = axis.row * static_cast<int64_t>(block.end_row - 1u - block.first_row);
    *low = corner + (across < 0 ? across : 0) + (down < 0 ? down : 0);
    *high = corner + (across > 0 ? across : 0) + (down > 0 ? down : 0);
}

/* Narrows the rows [*first, *last] of a block to those where one axis can be within reach: the row's
   offsets (pixel - impulse) span offset + j row + [min(0, across), max(0, across)] (across: from the
   row's first column to its last), which must meet (-reach, reach). Rows outside have no run. */
void narrow_rows(int64_t offset, int64_t across, int64_t row, int64_t reach, int64_t *first, int64_t *last) {
    const int64_t least = offset + (across < 0 ? across : 0), most = offset + (across > 0 ? across : 0);
    int64_t low, high; /* the rows low .. high */
    if (row == 0) return;
    if (row > 0) {
        low = floor_divide(-reach - most, row) + 1;  /* j row > -reach - most */
        high = floor_divide(reach - least - 1, row); /* j row < reach - least */
    } else {
        low = floor_divide(least - reach, -row) + 1; /* j (-row) > least - reach */
        high = floor_divide(reach + most - 1, -row); /* j (-row) < reach + most */
    }
    if (low > *first) *first = low;
    if (high < *last) *last = high;
}

/* Adds the impulse at frame (position_x, position_y) to the block's pixels within its window: one run of
   columns per row, all handed to the kernel at once. The block's sums are its own (row-major, `columns`
   per row, one plane per channel). */
void splat_impulse(const FrameAxis &x, const FrameAxis &y, const Block &block, int64_t position_x,
                   int64_t position_y, uint64_t *sums, const dsn_splat_setup *setup,
                   dsn_splat_runs_entry *splat_runs) {
    /* Offsets (pixel - impulse) of the block's first pixel. */
    const int64_t row_x = x.base + x.column * static_cast<int64_t>(block.first_column) +
                          x.row * static_cast<int64_t>(block.first_row) - position_x;
    const int64_t row_y = y.base + y.column * static_cast<int64_t>(block.first_column) +
                          y.row * static_cast<int64_t>(block.first_row) - position_y;
    const int64_t columns = static_cast<int64_t>(block.end_column - block.first_column);
    int64_t first_row = 0, last_row = static_cast<int64_t>(block.end_row - block.first_row) - 1;
    narrow_rows(row_x, x.column * (columns - 1), x.row, x.reach, &first_row, &last_row);
    narrow_rows(row_y, y.column * (columns - 1), y.row, y.reach, &first_row, &last_row);
    ColumnBounds bounds_x, bounds_y;
    column_bounds_init(&bounds_x, x.columns, row_x + first_row * x.row);
    column_bounds_init(&bounds_y, y.columns, row_y + first_row * y.row);
    dsn_splat_run runs[block_rows];
    uint32_t run_count = 0;
    if (x.row == 0 && y.column == 0) {
        /* Axis-aligned: x does not move down the rows nor y along them, so every row has the first row's
           run (the rows narrow_rows kept have y within reach; with y.row 0, y is the same on every row). */
        int64_t first = 0, last = columns - 1;
        column_bounds_apply(bounds_x, x.columns, &first, &last);
        column_bounds_apply(bounds_y, y.columns, &first, &last);
        if (first > last) return;
        for (int64_t j = first_row; j <= last_row; j++) {
            dsn_splat_run *run = &runs[run_count++];
            run->offset_x = bounds_x.offset + x.column * first;
            run->offset_y = row_y + j * y.row;
            run->sums = sums + static_cast<size_t>(j * static_cast<int64_t>(block.stride) + first);
            run->count = static_cast<uint32_t>(last - first + 1);
        }
        if (run_count != 0) splat_runs(setup, runs, run_count);
        return;
    }
    for (int64_t j = first_row; j <= last_row; j++) {
        int64_t first = 0, last = columns - 1;
        column_bounds_apply(bounds_x, x.columns, &first, &last);
        column_bounds_apply(bounds_y, y.columns, &first, &last);
        if (first <= last) {
            dsn_splat_run *run = &runs[run_count++];
            run->offset_x = bounds_x.offset + x.column * first;
            run->offset_y = bounds_y.offset + y.column * first;
            run->sums = sums + static_cast<size_t>(j * static_cast<int64_t>(block.stride) + first);
            run->count = static_cast<uint32_t>(last - first + 1);
        }
        column_bounds_next(&bounds_x, x.columns);
        column_bounds_next(&bounds_y, y.columns);
    }
    if (run_count != 0) splat_runs(setup, runs, run_count);
}

void splat_block(const dsn_noise_state *noise, const FrameAxis &x, const FrameAxis &y, const Block &block,
                 uint64_t *sums, const dsn_splat_setup *setup, dsn_splat_runs_entry *splat_runs) {
    const uint32_t shift = noise->cell_shift, cell_mask = 0xFFFFFFFFu >> shift;
    const uint32_t position_shift = 16u + shift, lattice_shift = 16u - shift;
    int64_t low_x, high_x, low_y, high_y;
    block_extent(x, block, &low_x, &high_x);
    block_extent(y, block, &low_y, &high_y);
    /* Impulses at p reach pixels at offsets in (-reach, reach): p in (low - reach, high + reach). */
    FrameSpans spans_x, spans_y;
    frame_spans(x, low_x - x.reach, high_x + x.reach, &spans_x);
    frame_spans(y, low_y - y.reach, high_y + y.reach, &spans_y);
    const int64_t cell_step = static_cast<int64_t>(one_texel) << shift;
    for (uint32_t sy = 0; sy < spans_y.span_count; sy++) {
        const FrameSpan span_y = frame_span(y, spans_y, sy);
        for (uint32_t sx = 0; sx < spans_x.span_count; sx++) {
            const FrameSpan span_x = frame_span(x, spans_x, sx);
            for (uint32_t cy = 0; cy < span_y.cell_count; cy++) {
                const uint32_t cell_y = (span_y.first_cell + cy) & cell_mask;
                const int64_t origin_y = span_y.first_origin + static_cast<int64_t>(cy) * cell_step;
                const uint32_t row_key = dsn_row_key(noise, cell_y);
                for (uint32_t cx = 0; cx < span_x.cell_count; cx++) {
                    const uint32_t cell_x = (span_x.first_cell + cx) & cell_mask;
                    const int64_t origin_x = span_x.first_origin + static_cast<int64_t>(cx) * cell_step;
                    const uint32_t key = dsn_cell_key_in_row(noise, cell_x, row_key);
                    const uint32_t count = dsn_cell_impulse_count(noise, key);
                    for (uint32_t k = 0; k < count; k++) {
                        const uint32_t hash = dsn_impulse_hash(noise, key, k);
                        const uint32_t bits_x = dsn_impulse_bits_x(hash), bits_y = dsn_impulse_bits_y(hash);
                        /* The period: impulses past its end are discarded, as per point. */
                        if ((cell_x << shift) + (bits_x >> lattice_shift) > span_x.last_position ||
                            (cell_y << shift) + (bits_y >> lattice_shift) > span_y.last_position)
                            continue;
                        const int64_t position_x =
                            origin_x + static_cast<int64_t>(static_cast<uint64_t>(bits_x) << position_shift);
                        const int64_t position_y =
                            origin_y + static_cast<int64_t>(static_cast<uint64_t>(bits_y) << position_shift);
                        if (position_x <= low_x - x.reach || position_x >= high_x + x.reach ||
                            position_y <= low_y - y.reach || position_y >= high_y + y.reach)
                            continue;
                        splat_impulse(x, y, block, position_x, position_y, sums, setup, splat_runs);
                    }
                }
            }
        }
    }
}

/* Both frames, or false when the grid is evaluated point by point: it does not fit a frame, or it is so
   sparse that per point is cheaper (one pixel covering more area than the cells a point visits). */
bool splat_frames(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                  FrameAxis *x, FrameAxis *y) {
    const uint32_t shift = noise->cell_shift;
    if (!frame_axis(x, grid->origin_x, grid->column_step_x, grid->row_step_x, width, height, noise->radius[0],
                    shift, noise->period[0]) ||
        !frame_axis(y, grid->origin_y, grid->column_step_y, grid->row_step_y, width, height, noise->radius[1],
                    shift, noise->period[1]))
        return false;
    /* Steps of 2^14 texels or more make a sparse grid anyway (and keep every offset below 2^53). */
    const uint64_t cx = magnitude(grid->column_step_x) >> 16, cy = magnitude(grid->column_step_y) >> 16;
    const uint64_t rx = magnitude(grid->row_step_x) >> 16, ry = magnitude(grid->row_step_y) >> 16;
    const uint64_t limit = static_cast<uint64_t>(1) << 30;
    if (cx >= limit || cy >= limit || rx >= limit || ry >= limit) return false;
    /* Per point, a point visits about (2r + 2 + cell)^2 texels of impulses; a pixel covers |det| of the
       steps, between max(cx ry, cy rx) and twice that (texels^2, 16 fraction bits here). */
    const uint64_t visited_x = 2u * noise->radius[0] + 2u + (1u << shift);
    const uint64_t visited_y = 2u * noise->radius[1] + 2u + (1u << shift);
    const uint64_t straight = (cx >> 8) * (ry >> 8), crossed = (cy >> 8) * (rx >> 8);
    const uint64_t larger = straight > crossed ? straight : crossed;
    return larger <= (visited_x * visited_y) << 16;
}

size_t splat_scratch_size(const dsn_noise_state *noise, uint32_t width, uint32_t height) {
    const uint64_t bytes = static_cast<uint64_t>(width) * height * noise->asset.channels * sizeof(uint64_t);
    const uint64_t alignment_slack = sizeof(uint64_t) - 1u;
    if (bytes + alignment_slack > static_cast<size_t>(-1)) return 0; /* too large here: per point */
    return static_cast<size_t>(bytes + alignment_slack);
}

/* The scratch as an array of uint64, aligned (the caller's buffer needs no alignment). */
uint64_t *aligned_sums(void *scratch) {
    unsigned char *bytes = static_cast<unsigned char *>(scratch);
    const uintptr_t misalignment = reinterpret_cast<uintptr_t>(bytes) % sizeof(uint64_t);
    return static_cast<uint64_t *>(
        static_cast<void *>(bytes + (misalignment ? sizeof(uint64_t) - misalignment : 0u)));
}

/* The tile block by block: each block's sums are splatted into the start of the scratch (planar, channel
   c of the block's pixel (i, j) at sums[c * plane + j * stride + i], so the vector kernels add runs of
   pixels of one channel), then normalized a row at a time by the kernel (on vectors of pixels too) and mapped
   and stored into `out` pixel by pixel; a block's sums stay in the caches. 8-bit textons are read from their
   cell records (splat_cells.h) where the kernels take them, kept on the stack for the call. */
void splat_grid(const dsn_noise_state *noise, const FrameAxis &x, const FrameAxis &y, uint32_t width,
                uint32_t height, uint64_t *sums, void *out, dsn_output_kind kind) {
    const dsn_kernel_entries *kernel = dsn_kernel_entries_of(noise->tile_kernel);
    dsn_splat_runs_entry *splat_runs = kernel->continuous_splat_runs;
    const uint32_t channels = noise->asset.channels;
    dsn_splat_setup setup;
    setup.asset = &noise->asset;
    setup.step_x = x.column;
    setup.step_y = y.column;
    setup.reach_x = x.reach;
    setup.reach_y = y.reach;
    setup.cells = 0;
    setup.cell_row = 0;
    setup.columns_shared = x.row == 0 && y.column == 0;
    setup.sums_end = sums + static_cast<size_t>(width) * height * channels;
#if DSN_SPLAT_CELLS
    alignas(64) uint64_t cells[splat_cell_capacity]; /* RGB cells on 32-byte boundaries */
    if (make_splat_cells(&noise->asset, cells, &setup.cell_row)) setup.cells = cells;
#endif
    for (uint32_t top = 0; top < height; top += block_rows)
        for (uint32_t left = 0; left < width; left += block_columns) {
            Block block;
            block.first_column = left;
            block.end_column = width - left < block_columns ? width : left + block_columns;
            block.first_row = top;
            block.end_row = height - top < block_rows ? height : top + block_rows;
            const uint32_t columns = block.end_column - left, rows = block.end_row - top;
            /* Rows of 64 sums would lie 512 bytes apart, each column of a block (and each channel's)
               in the same few cache sets: they are spread by a cache line where the scratch has room. */
            const uint32_t padded = columns + 8u;
            block.stride = static_cast<uint64_t>(padded) * rows <= static_cast<uint64_t>(width) * height
                               ? padded
                               : columns;
            const size_t plane = static_cast<size_t>(block.stride) * rows;
            setup.plane = plane;
            for (size_t i = 0; i < plane * channels; i++) sums[i] = 0;
            splat_block(noise, x, y, block, sums, &setup, splat_runs);
            for (uint32_t j = 0; j < rows; j++) {
                int32_t values[block_columns * DSN_MAX_CHANNELS];
                kernel->continuous_splat_normalize(noise, sums + static_cast<size_t>(j) * block.stride, plane,
                                                   columns, values);
                const size_t first = (static_cast<size_t>(top + j) * width + left) * channels;
                for (uint32_t i = 0; i < columns; i++) dsn_map_output(noise, values + i * channels);
                if (kind == dsn_output_fixed)
                    for (uint32_t i = 0; i < columns * channels; i++)
                        static_cast<int32_t *>(out)[first + i] = values[i];
                else
                    for (uint32_t i = 0; i < columns; i++)
                        dsn_store_pixel(out, kind, first + i * channels, values + i * channels, channels);
            }
        }
}

#endif /* !DSN_SMALL_CODE */

/* Evaluates every grid point in order into `out`: by splatting when the grid qualifies (not in the
   small build), else point by point. */
int evaluate_grid(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                  void *out, dsn_output_kind kind, void *scratch, size_t scratch_size) {
    const int err = check_tile(noise, grid, width, height, out);
    if (err != DSN_OK) return err;
#if !DSN_SMALL_CODE
    FrameAxis x, y;
    const size_t needed =
        splat_frames(noise, grid, width, height, &x, &y) ? splat_scratch_size(noise, width, height) : 0;
    if (needed != 0) {
        if (scratch == 0 || scratch_size < needed) return DSN_ERR_SCRATCH;
        splat_grid(noise, x, y, width, height, aligned_sums(scratch), out, kind);
        return DSN_OK;
    }
#else
    (void)scratch;
    (void)scratch_size;
#endif
    /* Pixel (i, j) is origin + i column_step + j row_step modulo 2^64: stepping adds the same values. */
    const uint32_t channels = noise->asset.channels;
    int32_t pixel[DSN_MAX_CHANNELS];
    uint64_t row_x = static_cast<uint64_t>(grid->origin_x), row_y = static_cast<uint64_t>(grid->origin_y);
    size_t index = 0;
    for (uint32_t j = 0; j < height; j++) {
        uint64_t point_x = row_x, point_y = row_y;
        for (uint32_t i = 0; i < width; i++, index += channels) {
            dsn_internal_continuous_point(noise, point_x, point_y, pixel);
            dsn_store_pixel(out, kind, index, pixel, channels);
            point_x += static_cast<uint64_t>(grid->column_step_x);
            point_y += static_cast<uint64_t>(grid->column_step_y);
        }
        row_x += static_cast<uint64_t>(grid->row_step_x);
        row_y += static_cast<uint64_t>(grid->row_step_y);
    }
    return DSN_OK;
}

} // namespace

extern "C" {

size_t dsn_continuous_tile_scratch_size(const dsn_noise *handle, const dsn_grid *grid, uint32_t width,
                                        uint32_t height) {
    const dsn_noise_state *noise = dsn_state(handle);
#if DSN_SMALL_CODE
    (void)noise, (void)grid, (void)width, (void)height;
    return 0; /* point by point: no scratch */
#else
    FrameAxis x, y;
    if (check_tile(noise, grid, width, height, grid) != DSN_OK) return 0;
    return splat_frames(noise, grid, width, height, &x, &y) ? splat_scratch_size(noise, width, height) : 0;
#endif
}

int dsn_continuous_tile_fixed(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height,
                              int32_t *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return evaluate_grid(noise, grid, width, height, out, dsn_output_fixed, scratch, scratch_size);
}

int dsn_continuous_tile_float(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height,
                              float *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return evaluate_grid(noise, grid, width, height, out, dsn_output_float, scratch, scratch_size);
}

int dsn_continuous_tile_u8(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height,
                           uint8_t *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return evaluate_grid(noise, grid, width, height, out, dsn_output_u8, scratch, scratch_size);
}

} // extern "C"
