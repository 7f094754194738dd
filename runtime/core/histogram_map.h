/* runtime/core/histogram_map.h - the histogram-preserving output of format 1.2 (format.h, "Meaning of the
   mapping"): a point's Gaussian-space Q16.16 values to its colours, through one level's tables (or the
   blend of two, for the filtered evaluation) and the rotation. Every evaluator applies it to its values
   as the last step, where its noise has a mapping. Compiled only with DSN_HISTOGRAM. Internal to libdsn;
   not installed. */
#ifndef DSN_HISTOGRAM_MAP_H
#define DSN_HISTOGRAM_MAP_H

#include <stdint.h>

#include "dsn/dsn.h"

#if DSN_HISTOGRAM

/* values[channels]: the Gaussian-space values g_k in, the colours out_c out (in place). The tables of
   `level` blended with those of level + 1 with weight blend / 256 (blend 0..255; 0 and level 0 for the
   unfiltered evaluations); a level at or above the asset's histogram_levels is the constant `expected`.
   The asset has a mapping whose fields passed the loader's checks (histogram_map.cpp). */
void dsn_internal_histogram_map(const dsn_asset *asset, int32_t *values, uint32_t level, uint32_t blend);

#if DSN_GRADIENTS
/* The chain rule of the mapping of `level` blended with level + 1 (as dsn_internal_histogram_map): dx and
   dy, a point's Gaussian-space derivatives at its Gaussian-space values `values` (before the mapping),
   become the derivatives of its colours, in place (dsn.h, "Gradients"). */
void dsn_internal_histogram_map_gradient(const dsn_asset *asset, const int32_t *values, uint32_t level,
                                         uint32_t blend, int32_t *dx, int32_t *dy);
#endif

/* out[channels]: the colour the mapping gives where every table is `expected` (levels at or above
   histogram_levels): what the filtered evaluation fades to. */
void dsn_internal_histogram_fade(const dsn_asset *asset, int32_t *out);

/* The fields of a mapping the evaluators can read without overflow or out-of-range shifts (the ranges of
   format.h step 16 that do not need the file): dsn_noise_init refuses an asset that fails them. */
int dsn_internal_histogram_usable(const dsn_asset *asset);

#endif

#endif /* DSN_HISTOGRAM_MAP_H */
