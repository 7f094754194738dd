/* runtime/filtered_internal.h - what the files of the filtered evaluation share: the plan of one
   footprint (level of detail, taps and their spacing, computed in filter_footprint.cpp) and the
   filtered point evaluator (filtered_point.cpp) that the tile calls at each grid point. The mathematics
   is documented in dsn.h ("Filtered evaluation"). Compiled only with DSN_FILTERING. Internal to libdsn;
   not installed. */
#ifndef DSN_FILTERED_INTERNAL_H
#define DSN_FILTERED_INTERNAL_H

#include <stdint.h>

#include "noise_state.h"

#if DSN_FILTERING

/* How a footprint is evaluated: level of detail in 1/256 levels, clamped to [0, 256 (levels + 1)];
   taps (a power of two, 1 .. 16) with tap k at the point plus offset_x/y[k] (Q32.32, modulo 2^64). */
typedef struct dsn_filter_plan {
    int32_t lod_q8;
    uint32_t taps;
    int64_t offset_x[DSN_FILTER_MAX_TAPS], offset_y[DSN_FILTER_MAX_TAPS];
} dsn_filter_plan;

/* The plan of `footprint` for a pyramid of `levels` levels: DSN_OK, DSN_ERR_NULL (null footprint) or
   DSN_ERR_ARGUMENT (max_taps 0 or above DSN_FILTER_MAX_TAPS). Integer arithmetic only
   (filter_footprint.cpp). */
int dsn_internal_filter_plan(const dsn_footprint *footprint, uint32_t levels, dsn_filter_plan *plan);

/* DSN_OK when the filtered functions may evaluate `noise` (the continuous mode's check). */
int dsn_internal_filtered_check(const dsn_noise_state *noise);

/* The Q16.16 values of the filtered point (x, y) under `plan`, on a noise that passed the check
   (filtered_point.cpp). */
void dsn_internal_filtered_point(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                 const dsn_filter_plan *plan, int32_t *out);

#endif /* DSN_FILTERING */

#endif /* DSN_FILTERED_INTERNAL_H */
