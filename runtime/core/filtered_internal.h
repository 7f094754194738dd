/* runtime/core/filtered_internal.h - what the files of the filtered evaluation share: the plan of one
   footprint (level of detail, taps and their spacing, computed in filter_footprint.cpp), the levels'
   sums at the taps (filtered_walk.cpp, filtered_sift.cpp) and the filtered point evaluator
   (filtered_point.cpp) that the tile calls at each grid point. The mathematics
   is documented in dsn.h ("Filtered evaluation"). Compiled only with DSN_FILTERING. Internal to libdsn;
   not installed. */
#ifndef DSN_FILTERED_INTERNAL_H
#define DSN_FILTERED_INTERNAL_H

#include <stdint.h>

#include "core/normalize_fixed.h"
#include "setup/noise_state.h"

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

/* floor((log2(square) in 16 fraction bits, truncated + 1) / 512) for square >= 1: the isotropic shortcut's
   level of detail in 1/256 levels before scaling (the tests compare it with the squarings' log2). */
int32_t dsn_internal_isotropic_lod_q8(uint64_t square);

/* The same plan by the general rule alone, without the shortcut that isotropic footprints take (the
   tests' reference for it). */
int dsn_internal_filter_plan_general(const dsn_footprint *footprint, uint32_t levels, dsn_filter_plan *plan);

/* One pyramid level as the walks read it: values at spacing 2^level texels, centred on the impulse
   (level 0 is the texton): the window of width x height values from `values`, rows `stride` values
   apart. */
typedef struct dsn_walked_level {
    const unsigned char *values;
    uint32_t width, height, stride, radius_x, radius_y, level;
    int32_t exponent;
} dsn_walked_level;

/* Level `level` (<= pyramid_levels) as the walks read it: its window less its all-zero margins
   (level_margin), so the same texton with a shorter reach (filtered_point.cpp). */
dsn_walked_level dsn_internal_walked_level(const dsn_noise_state *noise, uint32_t level);

/* The sums (Q.32, stored-value units, modulo 2^64) of each tap, of each of one or two levels, of each
   channel: the bilinear reads of the level at every impulse within its reach of the tap. */
typedef uint64_t dsn_filter_sums[DSN_FILTER_MAX_TAPS][2][DSN_MAX_CHANNELS];

/* The walk radii of `count` levels along each axis: the larger of theirs, a level's being that of the
   impulses whose floor lies within radius + 1 of the point's integer part X, that is every impulse
   within (level radius + 1) 2^level texels (as the continuous mode's radius r for level 0). */
static inline void dsn_filter_walk_radii(const dsn_walked_level *levels, uint32_t count, uint32_t *radius_x,
                                         uint32_t *radius_y) {
    *radius_x = *radius_y = 0;
    for (uint32_t i = 0; i < count; i++) {
        const uint32_t rx = ((levels[i].radius_x + 1u) << levels[i].level) - 1u;
        const uint32_t ry = ((levels[i].radius_y + 1u) << levels[i].level) - 1u;
        *radius_x = rx > *radius_x ? rx : *radius_x;
        *radius_y = ry > *radius_y ? ry : *radius_y;
    }
}

/* The sums of `count` levels at each tap of the plan around (x, y), zeroed first. Two ways, the same
   integers: tap by tap, impulse by impulse (filtered_walk.cpp: the small build's, and the reference
   of the tests), and, in the fast build, every tap at once over impulses sifted on their lattice
   fields (filtered_sift.cpp). */
void dsn_internal_filter_sums_walked(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                     const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                     uint32_t count, dsn_filter_sums sums);
/* The slopes of those sums per 2^-16 texel of each level (add_slopes): [tap][level][axis x, y][channel]
   (the walk's shared code names the type in every build, DSN_GRADIENTS or not). */
typedef uint64_t dsn_filter_slopes[DSN_FILTER_MAX_TAPS][2][2][DSN_MAX_CHANNELS];
#if DSN_GRADIENTS
/* dsn_internal_filter_sums_walked's sums and their slopes, in one walk (filtered_walk.cpp). */
void dsn_internal_filter_slopes_walked(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                       const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                       uint32_t count, dsn_filter_sums sums, dsn_filter_slopes *slopes);
#endif
#if !DSN_SMALL_CODE
void dsn_internal_filter_sums_sifted(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                     const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                     uint32_t count, dsn_filter_sums sums);
#if DSN_MIXING
struct dsn_impulse_filter;
/* dsn_internal_filter_sums_sifted over the impulses that `filter` keeps (one material of a mix whose
   weights are uniform, on the mix's impulse process: mix_filtered.cpp). */
void dsn_internal_filter_sums_kept(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                   const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                   uint32_t count, const struct dsn_impulse_filter *filter,
                                   dsn_filter_sums sums);
/* dsn_internal_filter_sums_kept of a mix's two materials in one walk: `noise`'s sums over the impulses that
   `filter` keeps into sums, `other`'s over the rest into other_sums, each over its own `count` levels at the
   plan's taps. False, summing nothing, where the pair does not take it: 8-bit levels of the same channels
   read and listed by the kernel, and the same walk for both (walk radii and process). */
bool dsn_internal_filter_sums_split(const dsn_noise_state *noise, const dsn_noise_state *other, uint64_t x,
                                    uint64_t y, const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                    const dsn_walked_level *other_levels, uint32_t count,
                                    const struct dsn_impulse_filter *filter, dsn_filter_sums sums,
                                    dsn_filter_sums other_sums);
#endif
#if DSN_GRADIENTS
/* dsn_internal_filter_slopes_walked's sums and slopes from sifted walks: each tap with its copies moved by
   one 2^-16 texel step of each level along x and y, whose level sums less the tap's are the slopes. */
void dsn_internal_filter_slopes_sifted(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                       const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                       uint32_t count, dsn_filter_sums sums, dsn_filter_slopes *slopes);
#endif

/* The same walk as dsn_internal_filter_sums_sifted with no level read: the candidates are listed (every
   impulse within reach of a tap's level, and those the sift could not tell apart from them), counted and
   dropped. Returns their count. make bench's floor under a filtered point's cost: the listing alone. */
uint64_t dsn_internal_filter_listing_only(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                          const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                          uint32_t count);
#endif

/* A filtered value, step by step (filtered_point.cpp; the filtered tile takes the same steps):
   - dsn_internal_filter_fade: where the plan's level of detail lies past the pyramid (or the histogram's
     levels), writes the faded value and returns 1; else returns 0;
   - dsn_internal_filter_walked_levels: the one or two levels the plan blends, into walked; returns how many;
   - per tap and level, dsn_internal_filter_level_values normalizes the level's sums (8 more fraction bits
     than Q16.16, saturated to +-2^46) and dsn_internal_filter_add_level adds them, times the level's blend
     weight out of 256, to the totals (int64, zeroed first); with one level,
     dsn_internal_filter_add_mean adds the mean colour at the upper level's weight;
   - dsn_internal_filter_finish divides the totals by 256 x taps x 2^8, rounding once, and maps the
     histogram. */
int dsn_internal_filter_fade(const dsn_noise_state *noise, const dsn_filter_plan *plan, int32_t *out);
uint32_t dsn_internal_filter_walked_levels(const dsn_noise_state *noise, const dsn_filter_plan *plan,
                                           dsn_walked_level *walked);
void dsn_internal_filter_level_values(const dsn_noise_state *noise, const dsn_walked_level *level,
                                      const uint64_t *level_sums, int64_t *values);
/* The same from `offset` instead of the level's own (the surface noise's offsets, surface_filtered.cpp), and
   the level's own: noise->offset for level 0, else its level_offset. */
void dsn_internal_filter_level_values_from(const dsn_noise_state *noise, const dsn_walked_level *level,
                                           const uint64_t *level_sums, const int64_t *offset,
                                           int64_t *values);
const int64_t *dsn_internal_level_offset(const dsn_noise_state *noise, uint32_t level);
#if DSN_GRADIENTS
/* dsn_internal_filter_level_values of a level's slopes (dsn_filter_slopes): the derivatives per texel,
   without the offset (the mean does not reach a derivative). */
void dsn_internal_filter_level_slopes(const dsn_noise_state *noise, const dsn_walked_level *level,
                                      const uint64_t *level_slopes, int64_t *values);
#endif
void dsn_internal_filter_add_level(const dsn_noise_state *noise, const dsn_filter_plan *plan, uint32_t index,
                                   const int64_t *values, int64_t *totals);
void dsn_internal_filter_add_mean(const dsn_noise_state *noise, const dsn_filter_plan *plan, int64_t *totals);
/* dsn_internal_filter_finish without the histogram mapping: the rounding alone. */
void dsn_internal_filter_round(const dsn_noise_state *noise, const dsn_filter_plan *plan,
                               const int64_t *totals, int32_t *out);
void dsn_internal_filter_finish(const dsn_noise_state *noise, const dsn_filter_plan *plan,
                                const int64_t *totals, int32_t *out);
#if DSN_GRADIENTS
/* The filtered gradient's values (value, dx, dy, DSN_MAX_CHANNELS apart) from its three totals, as
   dsn_internal_filter_finish finishes the value's: each rounded once, then the histogram mapping's chain
   rule (filtered_gradient.cpp). */
void dsn_internal_filter_gradient_finish(const dsn_noise_state *noise, const dsn_filter_plan *plan,
                                         const int64_t (*totals)[DSN_MAX_CHANNELS], int32_t *values);
#if !DSN_SMALL_CODE
/* The filtered gradient tile of a grid under its plan (a filtered one: not the continuous tile's) by
   splatting each tap's grid and its copies moved one step of each level along x and along y, with the
   per-point bits (filtered_tile.cpp); 0, writing nothing, for a tile size the call refuses or a grid the
   value's tile would not splat, or whose move wraps a periodic axis's start (point by point then). */
int dsn_internal_filtered_gradient_splat(const dsn_noise_state *noise, const dsn_grid *grid,
                                         const dsn_filter_plan *plan, uint32_t width, uint32_t height,
                                         void *out, void *dx, void *dy, dsn_output_kind kind);
#endif
#endif

/* DSN_OK when the filtered functions may evaluate `noise` (the continuous mode's check). */
int dsn_internal_filtered_check(const dsn_noise_state *noise);

/* The Q16.16 values of the filtered point (x, y) under `plan`, on a noise that passed the check
   (filtered_point.cpp). */
void dsn_internal_filtered_point(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                 const dsn_filter_plan *plan, int32_t *out);

/* The same bits through dsn_internal_filter_sums_walked in every build (the tests' reference). */
void dsn_internal_filtered_point_walked(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                        const dsn_filter_plan *plan, int32_t *out);

#endif /* DSN_FILTERING */

#endif /* DSN_FILTERED_INTERNAL_H */
