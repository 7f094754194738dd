/* runtime/setup/init_internal.h - the steps of dsn_noise_init that live in their own files, and the asset
   geometry check it shares with the loader. Internal. */
#ifndef DSN_INIT_INTERNAL_H
#define DSN_INIT_INTERNAL_H

#include "setup/noise_state.h"

/* Largest mean of one Poisson draw: keeps the table short (<= ~50 entries) and exp(-mean) far above
   the 2^-62 resolution of the fixed-point computation. Denser cells sum several draws. */
#define DSN_POISSON_MEAN_MAX 16u

/* Fills poisson_parts, poisson_size, poisson_cdf and poisson_guide for cells whose mean count is
   cell_mean_q32 / 2^32 (> 0). */
void dsn_internal_build_poisson_table(dsn_noise_state *noise, uint64_t cell_mean_q32);

/* Fills gain_shift, gain and offset from the asset, impacts_q16 and flags. */
void dsn_internal_compute_normalization(dsn_noise_state *noise);

/* Whether dsn_noise_init bounds the work of a point (evaluation_cost.cpp): every build but the small one,
   whose unfiltered walks its 8 KB leave unchecked (dsn.h, DSN_MAX_POINT_IMPULSES). */
#define DSN_CHECKS_COST (DSN_FILTERING || !DSN_SMALL_CODE)

#if DSN_CHECKS_COST
/* The expected impulses that one point examines, rounded up, in the costliest evaluation of the
   configured noise (lattice, continuous, and filtered with the widest footprint at each level of
   detail): at most DSN_MAX_POINT_IMPULSES for a noise that init accepted. Reads the cell size, the
   density, the periods and, with DSN_FILTERING, level_margin (evaluation_cost.cpp). */
uint64_t dsn_internal_point_cost(const dsn_noise_state *noise);

/* The expected impulses, rounded up, of one walk over a window of these extents (its length plus twice
   the walk's radius, per axis) in the noise's cells: what the mix's walks cost (mix_init.cpp). */
uint64_t dsn_internal_walk_cost(const dsn_noise_state *noise, uint32_t extent_x, uint32_t extent_y);
#endif

#if DSN_FILTERING
/* Fills level_margin from the asset's levels (filtered_point.cpp). */
void dsn_internal_compute_level_margins(dsn_noise_state *noise);
#endif

/* The loader's checks of channels, bits, shape, interpolation and width/height (format.h step 9, in
   that order): the first failure, or DSN_OK and the number of support points. dsn_noise_init runs them
   again on an asset it did not see loaded. */
int dsn_internal_check_geometry(const dsn_asset *asset, uint32_t *support_size);

#if DSN_READS_SECTIONS
/* DSN_OK when the asset's pyramid and lattice texton fields are the loader's: null and 0, or pointing at a
   section that the loader's steps 15 and 17 accept with exactly those sizes (asset.cpp); else
   DSN_ERR_ARGUMENT. dsn_noise_init runs it on the asset it is given, which it did not see loaded. */
int dsn_internal_check_sections(const dsn_asset *asset);
#endif

#endif /* DSN_INIT_INTERNAL_H */
