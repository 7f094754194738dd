/* runtime/setup/evaluation_cost.cpp - the work of one evaluated point, bounded at init (dsn.h, dsn_noise_init
   and DSN_MAX_POINT_IMPULSES): the expected impulses that one point of each evaluator examines, from the
   density, the cell size, the periods and the reach of each walk, the filtered walks with the widest
   footprint the filtered evaluation accepts. An upper bound of what the walks visit (cell_walk.h), not a
   timing model: the format bounds neither a level's reach (255 values at spacing 2^8) nor the density
   (1024 impacts over a support as small as one texel), so without it a valid asset of a few hundred bytes
   makes one filtered point examine trillions of impulses. Compiled where the cost is checked. */
#include "setup/init_internal.h"

#if DSN_CHECKS_COST

#include "core/filtered_internal.h"
#include "setup/wide_arithmetic.h"

namespace {

/* Costs are Q8 impulses, capped here (2^32 impulses, far past any bound) so that no product overflows:
   a cell mean below 2^35 (Q8) times the cells of an axis (below 2^20) stays below 2^55, and the cap
   times the other axis's below 2^60. */
const uint64_t cost_cap_q8 = static_cast<uint64_t>(1) << 40;

uint64_t capped(uint64_t cost_q8) { return cost_q8 > cost_cap_q8 ? cost_cap_q8 : cost_q8; }

/* The cells a walk visits along one axis for a window whose extent (its length plus twice the walk
   radius) is `extent` (dsn_axis_span): without a period, ceil(extent / side) + 1 (the window's start
   anywhere in its first cell). With period P the extent meets at most floor((extent - 1) / P) + 2 copies,
   each a span of at most two cells more than its share of the extent, and of at most the ceil(P / side)
   cells of one period; every cell counts whole (its count is drawn before the positions beyond the period
   are dropped), which makes small periods with large cells costly. */
uint64_t axis_cells(uint32_t extent, uint32_t shift, uint32_t period) {
    const uint64_t side = static_cast<uint64_t>(1) << shift;
    const uint64_t cells = ((extent + side - 1u) >> shift) + 1u;
    if (period == 0) return cells;
    const uint64_t spans = (extent - 1u) / period + 2u, period_cells = (period + side - 1u) >> shift;
    const uint64_t by_extent = cells + 2u * spans, by_period = spans * period_cells;
    return by_extent < by_period ? by_extent : by_period;
}

/* lambda c^2 (the mean impulse count of a cell) in Q8, rounded up. */
uint64_t cell_mean_q8(const dsn_noise_state *noise) {
    const uint64_t numerator = static_cast<uint64_t>(noise->impacts_q16)
                               << (2u * noise->cell_shift); /* < 2^42 */
    const uint64_t support = noise->asset.support_size;
    const uint64_t mean_q16 = dsn_divide(numerator + support - 1u, support);
    return (mean_q16 + 255u) >> 8;
}

/* A walk over windows of these extents: the cell mean times the cells visited. */
uint64_t walk_cost_q8(const dsn_noise_state *noise, uint64_t mean_q8, uint32_t extent_x, uint32_t extent_y) {
    const uint64_t cells_x = axis_cells(extent_x, noise->cell_shift, noise->period[0]);
    const uint64_t cells_y = axis_cells(extent_y, noise->cell_shift, noise->period[1]);
    return capped(capped(mean_q8 * cells_x) * cells_y);
}

uint64_t larger(uint64_t a, uint64_t b) { return a > b ? a : b; }

#if DSN_FILTERING
/* The filtered walks whose lower level is `lower` (its level of detail in [lower, lower + 1)): the level
   and the next one (or the level alone at the coarsest), walked from X - 1 to X + 1 around each tap with
   the larger radius (dsn_filter_walk_radii). Up to DSN_FILTER_MAX_TAPS taps span less than Pmax <
   DSN_FILTER_MAX_TAPS 2^(lower + 1) texels (the level of detail is at least log2(Pmax / taps), dsn.h,
   floored to 1/256 level), at most span / sqrt(2) < 182 / 256 span along both axes at once where the box
   is the largest; the taps share one walk over the box that holds their reaches, one more texel per axis
   for their integer parts, except where they lie across the int32 seam of the coordinates
   (filtered_sift.cpp), where each tap walks alone. */
uint64_t filtered_cost_q8(const dsn_noise_state *noise, uint64_t mean_q8, uint32_t lower) {
    dsn_walked_level walked[2];
    uint32_t count = 1;
    walked[0] = dsn_internal_walked_level(noise, lower);
    if (lower < noise->asset.pyramid_levels) walked[count++] = dsn_internal_walked_level(noise, lower + 1u);
    uint32_t radius_x, radius_y;
    dsn_filter_walk_radii(walked, count, &radius_x, &radius_y);
    const uint32_t spread = ((DSN_FILTER_MAX_TAPS << (lower + 1u)) * 182u >> 8) + 1u;
    const uint32_t one_x = 2u * radius_x + 3u, one_y = 2u * radius_y + 3u;
    const uint64_t shared = walk_cost_q8(noise, mean_q8, one_x + spread, one_y + spread);
    const uint64_t alone = capped(DSN_FILTER_MAX_TAPS * walk_cost_q8(noise, mean_q8, one_x, one_y));
    return larger(shared, alone);
}
#endif

} // namespace

uint64_t dsn_internal_walk_cost(const dsn_noise_state *noise, uint32_t extent_x, uint32_t extent_y) {
    return (walk_cost_q8(noise, cell_mean_q8(noise), extent_x, extent_y) + 255u) >> 8;
}

uint64_t dsn_internal_point_cost(const dsn_noise_state *noise) {
    const uint64_t mean_q8 = cell_mean_q8(noise);
    /* The lattice point: the window of one point, with the radius of the texton the lattice reads. */
    const dsn_asset *asset = &noise->asset;
    const uint32_t lattice_width = asset->lattice_texton != 0 ? asset->lattice_width : asset->width;
    const uint32_t lattice_height = asset->lattice_texton != 0 ? asset->lattice_height : asset->height;
    uint64_t cost = walk_cost_q8(noise, mean_q8, lattice_width, lattice_height);
    /* The continuous point: X - 1 .. X + 1 with the texton's radius. */
    cost = larger(cost, walk_cost_q8(noise, mean_q8, 2u * noise->radius[0] + 3u, 2u * noise->radius[1] + 3u));
#if DSN_FILTERING
    for (uint32_t lower = 0; lower <= asset->pyramid_levels; lower++)
        cost = larger(cost, filtered_cost_q8(noise, mean_q8, lower));
#endif
    return (cost + 255u) >> 8;
}

#endif /* DSN_CHECKS_COST */
