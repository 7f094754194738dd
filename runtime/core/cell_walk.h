/* runtime/core/cell_walk.h - the cells whose impulses can reach a window, along one axis, periodic or not,
   and where an impulse meets the window. Internal to libdsn; not installed. */
#ifndef DSN_CELL_WALK_H
#define DSN_CELL_WALK_H

#include <stdint.h>

#include "core/shared_inline.h"

/* A window is the run of lattice coordinates [start, start + length) of one axis (a single point has
   length 1). An impulse at axis position p reaches window index j when the texton index
   start + j - p + radius lies in [0, 2 radius]. A span is one group of candidate cells: cells
   first_cell .. first_cell + cell_count - 1 (indices modulo 2^(32 - cell_shift)) whose impulses have
   positions p = (cell << cell_shift) + offset, accepted only when p <= last_position, and reach the
   window with texton index  j + (base - p)  (uint32 arithmetic). Without a period there is one span on
   the whole torus. With a period P, the coordinate is reduced to [0, P), the impulses live on [0, P)
   (cells cut at P, impulses at >= P discarded) and the window meets several copies m of that interval:
   span m has base = start + radius - m P. */
typedef struct dsn_span {
    uint32_t first_cell;
    uint32_t cell_count;
    uint32_t base;
    uint32_t last_position;
} dsn_span;

typedef struct dsn_axis {
    uint32_t radius, shift, period; /* period 0: not periodic */
    uint32_t length;                /* window length */
    uint32_t start;                 /* periodic: window start reduced to [0, P); else the start */
    uint32_t copies_before;         /* periodic: the first copy met is m = -copies_before */
    uint32_t span_count;
} dsn_axis;

/* Window [coordinate, coordinate + length) along one axis. `coordinate` is the int32 lattice
   coordinate (as a uint32 bit pattern); with a period it is reduced by floor modulo. All in 32-bit
   arithmetic (no 64-bit division, which 32-bit targets would call): the copies met are
   m = floor((start - radius) / P) .. floor((start + length - 1 + radius) / P), the first one -1 or
   below only when start < radius. */
DSN_SHARED void dsn_axis_init(dsn_axis *axis, uint32_t coordinate, uint32_t length, uint32_t radius,
                              uint32_t shift, uint32_t period) {
    axis->radius = radius;
    axis->shift = shift;
    axis->period = period;
    axis->length = length;
    axis->start = coordinate;
    axis->copies_before = 0;
    axis->span_count = 1;
    if (period != 0) {
        /* Floor modulo of the int32 coordinate: for c < 0, c mod P = P - 1 - ((-c - 1) mod P), and
           -c - 1 = ~c lies in [0, 2^31). */
        const uint32_t start =
            (coordinate & 0x80000000u) ? period - 1u - ~coordinate % period : coordinate % period;
        /* start + extent may pass 2^32: floor((start + extent) / P) is extent / P, plus 1 when the
           remainders add up to P or more. */
        const uint32_t extent = length - 1u + radius, rest = extent % period;
        axis->start = start;
        axis->copies_before = start >= radius ? 0u : 1u + (radius - 1u - start) / period;
        axis->span_count = axis->copies_before + extent / period + (rest >= period - start ? 1u : 0u) + 1u;
    }
}

/* Span `index` meets copy m = index - copies_before, which starts at m P. Seen from that copy the
   window runs from start - radius - m P to start + length - 1 + radius - m P: the first copy met is the
   only one where the low end is >= 0 and the last the only one where the high end is < P, and there
   both ends lie in [0, P), so arithmetic modulo 2^32 gives them exactly. */
DSN_SHARED dsn_span dsn_axis_span(const dsn_axis *axis, uint32_t index) {
    dsn_span span;
    const uint32_t mask = (1u << axis->shift) - 1u, low = axis->start - axis->radius;
    if (axis->period == 0) {
        span.first_cell = low >> axis->shift;
        span.cell_count = (((low & mask) + axis->length - 1u + 2u * axis->radius) >> axis->shift) + 1u;
        span.base = axis->start + axis->radius;
        span.last_position = 0xFFFFFFFFu;
    } else {
        const uint32_t copy_start = (index - axis->copies_before) * axis->period; /* m P modulo 2^32 */
        const uint32_t first = index == 0 ? low - copy_start : 0u;
        const uint32_t last = index == axis->span_count - 1u
                                  ? axis->start + axis->length - 1u + axis->radius - copy_start
                                  : axis->period - 1u;
        span.first_cell = first >> axis->shift;
        span.cell_count = (last >> axis->shift) - span.first_cell + 1u;
        /* Only differences modulo 2^32 matter (see above). */
        span.base = axis->start + axis->radius - copy_start;
        span.last_position = axis->period - 1u;
    }
    return span;
}

/* Where an impulse at axis position p meets a window of `length` points. With the impulse's end
   e = base - p + length - 1 (uint32, base the span's), some window index reaches it exactly when
   e < length - 1 + diameter (diameter = 2 radius + 1); it then reaches window indices first_index ..
   first_index + count - 1, starting at texton index first_texton. */
typedef struct dsn_reach {
    uint32_t first_index, first_texton, count;
} dsn_reach;

/* The reach of an impulse with end e < length - 1 + diameter. */
DSN_SHARED void dsn_reach_at(uint32_t e, uint32_t length, uint32_t diameter, dsn_reach *reach) {
    const uint32_t last_index =
        (length - 1u + diameter - 1u - e < length - 1u) ? length - 1u + diameter - 1u - e : length - 1u;
    reach->first_index = e < length - 1u ? length - 1u - e : 0u;
    reach->first_texton = reach->first_index + e - (length - 1u);
    reach->count = last_index - reach->first_index + 1u;
}

/* Cell index i of a span, wrapped to the torus of cells. */
static inline uint32_t dsn_span_cell(const dsn_span *span, uint32_t i, uint32_t shift) {
    return (span->first_cell + i) & (0xFFFFFFFFu >> shift);
}

#endif /* DSN_CELL_WALK_H */
