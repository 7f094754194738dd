/* runtime/evaluators/grid_splat.cpp - splatting a grid's impulses into a block of its pixels (grid_splat.h).
   Each axis gets a frame: an int64 coordinate in which the pixels are base + i a + j b exactly (no wrap) and
   each impulse that may reach the tile has one position per image (one without a period; one per copy of the
   period otherwise). For a block, the cells that can reach its parallelogram are walked once, and each of
   their impulses adds its bilinear texture to the pixels of the block inside its window, found row by row
   as an exact interval of columns. Pixel by pixel these are the per-point sums exactly: the same impulses
   (every impulse within reach of a pixel lies in the block's cells, each image visited once), the same
   offset (the frame difference is the per-point offset for every impulse within reach), the same weights
   (a level divides the offset by 2^level, rounded down, as the filtered walk does), and integer sums do
   not depend on the order. */
#include "evaluators/grid_splat.h"

#include "core/continuous_internal.h"
#include "core/impulse_position.h"
#include "core/poisson_count.h"

#if !DSN_SMALL_CODE

namespace {

/* Frame coordinates stay below 2^62 in magnitude: the tile's extent below 2^61, the reach and the
   frame base below 2^60. */
const uint64_t max_extent = static_cast<uint64_t>(1) << 61;
const uint32_t max_splat_period = 1u << 27;
const uint32_t max_reach_texels = 1u << 27;
/* Sums past a block's row before the next (a cache line of them), where the scratch has room. */
const uint32_t splat_row_padding = 8;

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
typedef dsn_splat_columns ColumnSteps;

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

typedef dsn_splat_axis FrameAxis;

/* The frame of one axis, or false when the grid does not fit one (too large, or a periodic axis whose
   points cross the int32 wrap of the lattice coordinate, where the period breaks). */
bool frame_axis(FrameAxis *axis, int64_t origin, int64_t column, int64_t row, uint32_t width, uint32_t height,
                int64_t reach, uint32_t shift, uint32_t period) {
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
    axis->reach = reach;
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

/* The frame interval of the block's pixels along one axis. */
void block_extent(const FrameAxis &axis, const dsn_splat_block &block, int64_t *low, int64_t *high) {
    const int64_t corner = axis.base + axis.column * static_cast<int64_t>(block.left) +
                           axis.row * static_cast<int64_t>(block.top);
    const int64_t across = axis.column * static_cast<int64_t>(block.columns - 1u);
    const int64_t down = axis.row * static_cast<int64_t>(block.rows - 1u);
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

/* The rows an impulse can reach in a block, from its footprint alone: pixel (i, j) lies at offsets X =
   ox + i column_x + j row_x and Y = oy + i column_y + j row_y from the impulse, reached when |X| < reach_x
   and |Y| < reach_y; eliminating i, j D = (column_x Y - column_y X) - (column_x oy - column_y ox) with
   D = column_x row_y - column_y row_x, whose first term lies within +-(|column_x| reach_y + |column_y|
   reach_x). That bounds the rows (narrow_rows bounds them by each axis over a whole row of the block,
   which on a rotated grid keeps most of them), and the same with i, eliminating j, bounds the columns:
   the impulses that reach none of the block's rows or columns are skipped (the cell walk covers the
   block's extent widened by the reach, much more than its parallelogram widened by the reach there).
   Everything is taken in units of 2^-16 texel (floors) with the truncation errors added to the
   intervals, so only rows and impulses that reach no pixel are ever left out; blocks whose magnitudes
   would overflow int64 this way skip it, as do blocks that are rectangles in the frame. */
struct Footprint {
    bool enabled;
    int64_t column_x, column_y, row_x, row_y; /* the steps in 2^-16 texel, floored */
    int64_t margin_j, margin_i;               /* half widths of the intervals, truncation included */
    int64_t least_j, most_j, least_i, most_i; /* j D / 2^32 for j in [0, rows), i D / 2^32 for i in
                                                 [0, columns), lie within these */
    int64_t sign;                             /* of D; 0: too close to 0 to bound the rows */
    int64_t least_d, most_d;                  /* |D| over 2^32 lies in [least_d, most_d] */
    int64_t inside_i;                         /* (columns - 1) least_d */
};

const int64_t footprint_bound = static_cast<int64_t>(1) << 27;

int64_t absolute(int64_t value) { return value < 0 ? -value : value; }

void footprint_init(Footprint *f, const FrameAxis &x, const FrameAxis &y, const dsn_splat_block &block,
                    int64_t extent_x, int64_t extent_y) {
    f->column_x = floor_shift(x.column, 16);
    f->column_y = floor_shift(y.column, 16);
    f->row_x = floor_shift(x.row, 16);
    f->row_y = floor_shift(y.row, 16);
    const int64_t reach_x = x.reach >> 16, reach_y = y.reach >> 16; /* exact: whole texels */
    /* Offsets of the block's first pixel from an impulse inside the walked box: below extent + reach. */
    const int64_t offset_x = ((extent_x + x.reach) >> 16) + 1, offset_y = ((extent_y + y.reach) >> 16) + 1;
    /* A block that is a rectangle in the frame gains nothing: its box is its parallelogram, and
       narrow_rows bounds its rows exactly. */
    const bool rectangle = (x.row == 0 && y.column == 0) || (x.column == 0 && y.row == 0);
    f->enabled = !rectangle && absolute(f->column_x) < footprint_bound &&
                 absolute(f->column_y) < footprint_bound && absolute(f->row_x) < footprint_bound &&
                 absolute(f->row_y) < footprint_bound && reach_x < footprint_bound &&
                 reach_y < footprint_bound && offset_x < footprint_bound && offset_y < footprint_bound;
    f->margin_j = f->margin_i = f->least_j = f->most_j = f->least_i = f->most_i = 0;
    f->sign = f->least_d = f->most_d = f->inside_i = 0;
    if (!f->enabled) return;
    const int64_t column_sum = absolute(f->column_x) + absolute(f->column_y);
    const int64_t row_sum = absolute(f->row_x) + absolute(f->row_y);
    f->margin_j =
        (absolute(f->column_x) + 1) * reach_y + (absolute(f->column_y) + 1) * reach_x + column_sum + 2;
    f->margin_i = (absolute(f->row_y) + 1) * reach_x + (absolute(f->row_x) + 1) * reach_y + row_sum + 2;
    const int64_t d = f->column_x * f->row_y - f->column_y * f->row_x, error = column_sum + row_sum + 2;
    const int64_t last_row = static_cast<int64_t>(block.rows) - 1,
                  last_column = static_cast<int64_t>(block.columns) - 1;
    f->least_j = last_row * (d - error) < 0 ? last_row * (d - error) : 0;
    f->most_j = last_row * (d + error) > 0 ? last_row * (d + error) : 0;
    f->least_i = last_column * (d - error) < 0 ? last_column * (d - error) : 0;
    f->most_i = last_column * (d + error) > 0 ? last_column * (d + error) : 0;
    if (absolute(d) > error) {
        f->sign = d < 0 ? -1 : 1;
        f->least_d = absolute(d) - error;
        f->most_d = absolute(d) + error;
        f->inside_i = last_column * f->least_d;
    }
}

/* What footprint_rows finds of an impulse. */
enum FootprintReach {
    reaches_nothing,     /* no pixel of the block */
    reaches_rows,        /* rows narrowed */
    reaches_rows_inside, /* rows narrowed, and its footprint lies within the block's columns */
};

/* Narrows [*first_row, *last_row] to the rows the impulse whose offsets from the block's first pixel are
   (offset_x, offset_y) may reach. */
inline FootprintReach footprint_rows(const Footprint &f, int64_t offset_x, int64_t offset_y,
                                     int64_t *first_row, int64_t *last_row) {
    const int64_t a = floor_shift(offset_x, 16), b = floor_shift(offset_y, 16);
    const int64_t spread = absolute(a) + absolute(b);
    const int64_t centre_j = f.column_y * a - f.column_x * b, margin_j = f.margin_j + spread;
    const int64_t centre_i = f.row_x * b - f.row_y * a, margin_i = f.margin_i + spread;
    if (centre_j + margin_j <= f.least_j || centre_j - margin_j >= f.most_j ||
        centre_i + margin_i <= f.least_i || centre_i - margin_i >= f.most_i)
        return reaches_nothing;
    if (f.sign == 0) return reaches_rows;
    /* j |D| / 2^32 lies in (low, high), |D| / 2^32 in [least_d, most_d]. */
    const int64_t low = f.sign * centre_j - margin_j, high = f.sign * centre_j + margin_j;
    const int64_t first = floor_divide(low, low >= 0 ? f.most_d : f.least_d) + 1;
    const int64_t last = floor_divide(high - 1, high >= 0 ? f.least_d : f.most_d);
    if (first > *first_row) *first_row = first;
    if (last < *last_row) *last_row = last;
    /* i |D| / 2^32 lies in (sign centre_i -+ margin_i): within [0, columns) when that lies in [0, columns
       - 1] least_d. */
    const int64_t low_i = f.sign * centre_i - margin_i, high_i = f.sign * centre_i + margin_i;
    return low_i >= 0 && high_i <= f.inside_i ? reaches_rows_inside : reaches_rows;
}

/* Adds the impulse at frame (position_x, position_y) to the block's pixels within its window: one run of
   columns per row, all handed to the kernel at once. The block's sums are its own (row-major, `columns`
   per row, one plane per channel). */
void splat_impulse(const dsn_grid_splat &splat, const dsn_splat_setup *setup, const dsn_splat_block &block,
                   const Footprint &footprint, int64_t position_x, int64_t position_y, uint64_t *sums) {
    const FrameAxis &x = splat.x, &y = splat.y;
    /* Offsets (pixel - impulse) of the block's first pixel. */
    const int64_t row_x = x.base + x.column * static_cast<int64_t>(block.left) +
                          x.row * static_cast<int64_t>(block.top) - position_x;
    const int64_t row_y = y.base + y.column * static_cast<int64_t>(block.left) +
                          y.row * static_cast<int64_t>(block.top) - position_y;
    const int64_t columns = static_cast<int64_t>(block.columns);
    int64_t first_row = 0, last_row = static_cast<int64_t>(block.rows) - 1;
    const FootprintReach reach =
        footprint.enabled ? footprint_rows(footprint, row_x, row_y, &first_row, &last_row) : reaches_rows;
    if (reach == reaches_nothing) return;
    /* A footprint within the block's columns has its rows already: narrow_rows would keep every row it
       meets. (The footprint test is off on axis-aligned grids, whose path below needs narrow_rows.) */
    if (reach != reaches_rows_inside) {
        narrow_rows(row_x, x.column * (columns - 1), x.row, x.reach, &first_row, &last_row);
        narrow_rows(row_y, y.column * (columns - 1), y.row, y.reach, &first_row, &last_row);
    }
    ColumnBounds bounds_x, bounds_y;
    column_bounds_init(&bounds_x, x.columns, row_x + first_row * x.row);
    column_bounds_init(&bounds_y, y.columns, row_y + first_row * y.row);
    dsn_splat_run runs[dsn_splat_block_rows];
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
        if (run_count != 0) splat.runs(setup, runs, run_count);
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
    if (run_count != 0) splat.runs(setup, runs, run_count);
}

void splat_block(const dsn_noise_state *noise, const dsn_grid_splat &splat, const dsn_splat_setup *setup,
                 const dsn_splat_block &block, uint64_t *sums) {
    const FrameAxis &x = splat.x, &y = splat.y;
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
    Footprint footprint;
    footprint_init(&footprint, x, y, block, high_x - low_x, high_y - low_y);
    const dsn_impulse_filter *filter = splat.filter; /* the impulses a mixed tile's material keeps */
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
                        if (filter != 0 && !dsn_filter_keeps(filter, key, k)) continue;
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
                        splat_impulse(splat, setup, block, footprint, position_x, position_y, sums);
                    }
                }
            }
        }
    }
}

} // namespace

int dsn_internal_grid_splat_init(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width,
                                 uint32_t height, const dsn_splat_texture *texture, dsn_grid_splat *splat) {
    const uint32_t shift = noise->cell_shift;
    /* An impulse reaches the offsets (pixel - impulse) whose quotient by 2^level lies within (radius + 1)
       texels of the texture: those in (-reach, reach), reach = (radius + 1) 2^level texels (the few
       below -reach + 2^level read bracket's shifted value 0: nothing). */
    const uint32_t reach_x = ((texture->width - 1u) / 2u + 1u) << texture->level;
    const uint32_t reach_y = ((texture->height - 1u) / 2u + 1u) << texture->level;
    if (reach_x >= max_reach_texels || reach_y >= max_reach_texels) return 0;
    if (!frame_axis(&splat->x, grid->origin_x, grid->column_step_x, grid->row_step_x, width, height,
                    static_cast<int64_t>(reach_x) * static_cast<int64_t>(one_texel), shift,
                    noise->period[0]) ||
        !frame_axis(&splat->y, grid->origin_y, grid->column_step_y, grid->row_step_y, width, height,
                    static_cast<int64_t>(reach_y) * static_cast<int64_t>(one_texel), shift, noise->period[1]))
        return 0;
    /* Steps of 2^14 texels or more make a sparse grid anyway (and keep every offset below 2^53). */
    const uint64_t cx = magnitude(grid->column_step_x) >> 16, cy = magnitude(grid->column_step_y) >> 16;
    const uint64_t rx = magnitude(grid->row_step_x) >> 16, ry = magnitude(grid->row_step_y) >> 16;
    const uint64_t limit = static_cast<uint64_t>(1) << 30;
    if (cx >= limit || cy >= limit || rx >= limit || ry >= limit) return 0;
    /* Per point, a point visits about (2 reach + cell)^2 texels of impulses; a pixel covers |det| of the
       steps, between max(cx ry, cy rx) and twice that (texels^2, 16 fraction bits here). */
    const uint64_t visited_x = 2u * static_cast<uint64_t>(reach_x) + (1u << shift);
    const uint64_t visited_y = 2u * static_cast<uint64_t>(reach_y) + (1u << shift);
    const uint64_t straight = (cx >> 8) * (ry >> 8), crossed = (cy >> 8) * (rx >> 8);
    const uint64_t larger = straight > crossed ? straight : crossed;
    if (larger > (visited_x * visited_y) << 16) return 0;
    dsn_splat_setup *setup = &splat->setup;
    setup->texture = *texture;
    setup->step_x = splat->x.column;
    setup->step_y = splat->y.column;
    setup->reach_x = splat->x.reach;
    setup->reach_y = splat->y.reach;
    setup->plane = 0;
    setup->sums_end = 0;
    setup->cells = 0;
    setup->cell_row = 0;
    setup->columns_shared = splat->x.row == 0 && splat->y.column == 0;
    splat->runs = dsn_kernel_entries_of(noise->tile_kernel)->continuous_splat_runs;
    splat->filter = 0;
    return 1;
}

void dsn_internal_grid_splat_closed(dsn_grid_splat *splat) {
    dsn_splat_axis *axes[2] = {&splat->x, &splat->y};
    for (uint32_t k = 0; k < 2; k++) {
        axes[k]->reach += 1;
        column_steps_init(&axes[k]->columns, axes[k]->column, axes[k]->row, axes[k]->reach);
    }
}

size_t dsn_internal_splat_block_pixels(uint32_t width, uint32_t height) {
    const uint64_t tile = static_cast<uint64_t>(width) * height;
    const uint64_t block = (dsn_splat_block_columns + splat_row_padding) * dsn_splat_block_rows;
    return static_cast<size_t>(tile < block ? tile : block);
}

dsn_splat_block dsn_internal_splat_small_block(uint32_t left, uint32_t top, uint32_t width, uint32_t height,
                                               uint32_t columns, uint32_t rows) {
    dsn_splat_block block;
    block.left = left;
    block.top = top;
    block.columns = width - left < columns ? width - left : columns;
    block.rows = height - top < rows ? height - top : rows;
    block.stride = block.columns;
    block.plane = static_cast<size_t>(block.columns) * block.rows;
    return block;
}

dsn_splat_block dsn_internal_splat_block(uint32_t left, uint32_t top, uint32_t width, uint32_t height) {
    dsn_splat_block block;
    const uint32_t most_columns = dsn_splat_block_columns, most_rows = dsn_splat_block_rows;
    block.left = left;
    block.top = top;
    block.columns = width - left < most_columns ? width - left : most_columns;
    block.rows = height - top < most_rows ? height - top : most_rows;
    /* Rows of 64 sums would lie 512 bytes apart, each column of a block (and each channel's) in the same
       few cache sets: they are spread by a cache line where the scratch has room. */
    const uint32_t padded = block.columns + splat_row_padding;
    block.stride =
        static_cast<uint64_t>(padded) * block.rows <= dsn_internal_splat_block_pixels(width, height)
            ? padded
            : block.columns;
    block.plane = static_cast<size_t>(block.stride) * block.rows;
    return block;
}

void dsn_internal_grid_splat_block(const dsn_noise_state *noise, const dsn_grid_splat *splat,
                                   const dsn_splat_block *block, uint64_t *sums) {
    const size_t count = block->plane * noise->asset.channels;
    for (size_t i = 0; i < count; i++) sums[i] = 0;
    dsn_splat_setup setup = splat->setup;
    setup.plane = block->plane;
    setup.sums_end = sums + count;
    splat_block(noise, *splat, &setup, *block, sums);
}

size_t dsn_internal_splat_sums_size(uint32_t channels, uint32_t width, uint32_t height) {
    return dsn_internal_splat_block_pixels(width, height) * channels * sizeof(uint64_t) +
           (sizeof(uint64_t) - 1u);
}

uint64_t *dsn_internal_aligned_sums(void *scratch) {
    unsigned char *bytes = static_cast<unsigned char *>(scratch);
    const uintptr_t misalignment = reinterpret_cast<uintptr_t>(bytes) % sizeof(uint64_t);
    return static_cast<uint64_t *>(
        static_cast<void *>(bytes + (misalignment ? sizeof(uint64_t) - misalignment : 0u)));
}

#endif /* !DSN_SMALL_CODE */
