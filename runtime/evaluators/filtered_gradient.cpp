/* runtime/evaluators/filtered_gradient.cpp - the filtered noise with its derivative (dsn.h, "Gradients"):
   each blended level's slopes, from the reference walk that also gives its sums (filtered_walk.cpp),
   normalized per texel without the offset, blended, averaged over the taps and rounded once as the
   value; the histogram mapping's chain rule through the two levels' tables; per point and grid tile. */
#include "core/continuous_internal.h"
#include "core/filtered_internal.h"
#include "core/gradient_output.h"

#if DSN_GRADIENTS && DSN_FILTERING

void dsn_internal_filter_gradient_finish(const dsn_noise_state *noise, const dsn_filter_plan *plan,
                                         const int64_t (*totals)[DSN_MAX_CHANNELS], int32_t *values) {
    for (uint32_t output = 0; output < 3; output++)
        dsn_internal_filter_round(noise, plan, totals[output], values + output * DSN_MAX_CHANNELS);
#if DSN_HISTOGRAM
    if (noise->asset.histogram_table != 0) {
        const uint32_t level = static_cast<uint32_t>(plan->lod_q8) >> 8, blend = plan->lod_q8 & 255;
        dsn_internal_histogram_map_gradient(&noise->asset, values, level, blend, values + DSN_MAX_CHANNELS,
                                            values + 2 * DSN_MAX_CHANNELS);
        dsn_internal_histogram_map(&noise->asset, values, level, blend);
    }
#endif
}

namespace {

/* values[0 .. 2]: the filtered value, dx and dy at (x, y), DSN_MAX_CHANNELS apart. */
void gradient_point(const dsn_noise_state *noise, uint64_t x, uint64_t y, const dsn_filter_plan *plan,
                    int32_t *values) {
    int32_t *dx = values + DSN_MAX_CHANNELS, *dy = values + 2 * DSN_MAX_CHANNELS;
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) dx[c] = dy[c] = 0;
    if (dsn_internal_filter_fade(noise, plan, values)) return; /* the mean colour: no slope */
    if (plan->lod_q8 == 0 && plan->taps == 1) {
        dsn_internal_continuous_gradient(noise, x, y, values);
        return;
    }
    dsn_walked_level walked[2];
    const uint32_t count = dsn_internal_filter_walked_levels(noise, plan, walked);
    dsn_filter_sums sums;
    dsn_filter_slopes slopes;
#if DSN_SMALL_CODE
    dsn_internal_filter_slopes_walked(noise, x, y, plan, walked, count, sums, &slopes);
#else
    dsn_internal_filter_slopes_sifted(noise, x, y, plan, walked, count, sums, &slopes);
#endif
    int64_t totals[3][DSN_MAX_CHANNELS] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        for (uint32_t l = 0; l < count; l++) {
            int64_t level[3][DSN_MAX_CHANNELS] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
            dsn_internal_filter_level_values(noise, &walked[l], sums[tap][l], level[0]);
            dsn_internal_filter_level_slopes(noise, &walked[l], slopes[tap][l][0], level[1]);
            dsn_internal_filter_level_slopes(noise, &walked[l], slopes[tap][l][1], level[2]);
            for (uint32_t output = 0; output < 3; output++)
                dsn_internal_filter_add_level(noise, plan, l, level[output], totals[output]);
        }
        if (count == 1) dsn_internal_filter_add_mean(noise, plan, totals[0]); /* a constant: no slope */
    }
    dsn_internal_filter_gradient_finish(noise, plan, totals, values);
}

int check_call(const dsn_noise_state *noise, const void *out, const void *dx, const void *dy) {
    const int err = dsn_internal_filtered_check(noise);
    if (err != DSN_OK) return err;
    return out == 0 || dx == 0 || dy == 0 ? DSN_ERR_NULL : DSN_OK;
}

int point_of_kind(const dsn_noise *handle, int64_t x, int64_t y, const dsn_footprint *footprint, void *out,
                  void *dx, void *dy, dsn_output_kind kind) {
    const dsn_noise_state *noise = dsn_state(handle);
    int err = check_call(noise, out, dx, dy);
    dsn_filter_plan plan;
    if (err == DSN_OK) err = dsn_internal_filter_plan(footprint, noise->asset.pyramid_levels, &plan);
    if (err != DSN_OK) return dsn_gradient_error(err, noise, out, dx, dy, kind, 1);
    int32_t values[3 * DSN_MAX_CHANNELS];
    gradient_point(noise, static_cast<uint64_t>(x), static_cast<uint64_t>(y), &plan, values);
    dsn_store_gradient(out, dx, dy, kind, 0, values, noise->asset.channels);
    return DSN_OK;
}

/* The filtered gradient at a point of a grid, under the grid's plan. */
struct FilteredPoint {
    const dsn_noise_state *noise;
    const dsn_filter_plan *plan;
    void operator()(uint64_t x, uint64_t y, int32_t *values) const {
        gradient_point(noise, x, y, plan, values);
    }
};

/* A grid filtered by its own footprint, as dsn_filtered_tile_fixed's: splatted where the value's tile
   splats (an unfiltered one as the continuous gradient's tile), else point by point. */
int tile_of_kind(const dsn_noise *handle, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                 uint32_t height, void *out, void *dx, void *dy, dsn_output_kind kind) {
    const dsn_noise_state *noise = dsn_state(handle);
    int err = check_call(noise, out, dx, dy);
    if (err == DSN_OK && grid == 0) err = DSN_ERR_NULL;
    dsn_filter_plan plan;
    if (err == DSN_OK) {
        const dsn_footprint footprint = {grid->column_step_x, grid->column_step_y, grid->row_step_x,
                                         grid->row_step_y, max_taps};
        err = dsn_internal_filter_plan(&footprint, noise->asset.pyramid_levels, &plan);
    }
    /* Unfiltered (level of detail 0, one tap): the continuous gradient, whose grids splat. */
    if (err == DSN_OK && plan.lod_q8 == 0 && plan.taps == 1 &&
        dsn_internal_continuous_gradient_splat(noise, grid, width, height, out, dx, dy, kind))
        return DSN_OK;
#if !DSN_SMALL_CODE
    if (err == DSN_OK && !(plan.lod_q8 == 0 && plan.taps == 1) &&
        dsn_internal_filtered_gradient_splat(noise, grid, &plan, width, height, out, dx, dy, kind))
        return DSN_OK;
#endif
    const FilteredPoint point = {noise, &plan};
    return dsn_gradient_grid(err, noise, grid, width, height, out, dx, dy, kind, point);
}

} // namespace

extern "C" {

int dsn_filtered_gradient_fixed(const dsn_noise *noise, int64_t x, int64_t y, const dsn_footprint *footprint,
                                int32_t *out, int32_t *dx, int32_t *dy) {
    return point_of_kind(noise, x, y, footprint, out, dx, dy, dsn_output_fixed);
}

int dsn_filtered_gradient_float(const dsn_noise *noise, double x, double y, const dsn_footprint *footprint,
                                float *out, float *dx, float *dy) {
    return point_of_kind(noise, dsn_coordinate_from_double(x), dsn_coordinate_from_double(y), footprint, out,
                         dx, dy, dsn_output_float);
}

int dsn_filtered_tile_gradient_fixed(const dsn_noise *noise, const dsn_grid *grid, uint32_t max_taps,
                                     uint32_t width, uint32_t height, int32_t *out, int32_t *dx,
                                     int32_t *dy) {
    return tile_of_kind(noise, grid, max_taps, width, height, out, dx, dy, dsn_output_fixed);
}

int dsn_filtered_tile_gradient_float(const dsn_noise *noise, const dsn_grid *grid, uint32_t max_taps,
                                     uint32_t width, uint32_t height, float *out, float *dx, float *dy) {
    return tile_of_kind(noise, grid, max_taps, width, height, out, dx, dy, dsn_output_float);
}

} // extern "C"

#endif /* DSN_GRADIENTS && DSN_FILTERING */
