/* runtime/filtered_tile.cpp - the filtered evaluation on a grid (dsn_grid) whose footprint is the grid's
   own steps: the plan (level of detail, taps) is computed once, then each grid point is the filtered
   point's bits. An unfiltered plan (level of detail 0, one tap) is the continuous mode's tile, splat
   included. Compiled only with DSN_FILTERING. */
#include "continuous_internal.h"
#include "filtered_internal.h"
#include "normalize_fixed.h"

#if DSN_FILTERING

namespace {

dsn_footprint grid_footprint(const dsn_grid *grid, uint32_t max_taps) {
    dsn_footprint footprint;
    footprint.column_step_x = grid->column_step_x;
    footprint.column_step_y = grid->column_step_y;
    footprint.row_step_x = grid->row_step_x;
    footprint.row_step_y = grid->row_step_y;
    footprint.max_taps = max_taps;
    return footprint;
}

/* The checks of every filtered tile, then its plan. */
int tile_plan(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
              uint32_t height, const void *out, dsn_filter_plan *plan) {
    const int err = dsn_internal_filtered_check(noise);
    if (err != DSN_OK) return err;
    if (grid == 0 || out == 0) return DSN_ERR_NULL;
    const dsn_footprint footprint = grid_footprint(grid, max_taps);
    const int plan_error = dsn_internal_filter_plan(&footprint, noise->asset.pyramid_levels, plan);
    if (plan_error != DSN_OK) return plan_error;
    if (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE)
        return DSN_ERR_TILE_SIZE;
    return DSN_OK;
}

bool unfiltered(const dsn_filter_plan &plan) { return plan.lod_q8 == 0 && plan.taps == 1; }

int evaluate_grid(const dsn_noise *handle, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                  uint32_t height, void *out, dsn_output_kind kind, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    dsn_filter_plan plan;
    const int err = tile_plan(noise, grid, max_taps, width, height, out, &plan);
    if (err != DSN_OK) return err;
    if (unfiltered(plan)) {
        if (kind == dsn_output_fixed)
            return dsn_continuous_tile_fixed(handle, grid, width, height, static_cast<int32_t *>(out),
                                             scratch, scratch_size);
        if (kind == dsn_output_float)
            return dsn_continuous_tile_float(handle, grid, width, height, static_cast<float *>(out), scratch,
                                             scratch_size);
        return dsn_continuous_tile_u8(handle, grid, width, height, static_cast<uint8_t *>(out), scratch,
                                      scratch_size);
    }
    /* Pixel (i, j) is origin + i column_step + j row_step modulo 2^64: stepping adds the same values. */
    const uint32_t channels = noise->asset.channels;
    int32_t pixel[DSN_MAX_CHANNELS];
    uint64_t row_x = static_cast<uint64_t>(grid->origin_x), row_y = static_cast<uint64_t>(grid->origin_y);
    size_t index = 0;
    for (uint32_t j = 0; j < height; j++) {
        uint64_t point_x = row_x, point_y = row_y;
        for (uint32_t i = 0; i < width; i++, index += channels) {
            dsn_internal_filtered_point(noise, point_x, point_y, &plan, pixel);
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

size_t dsn_filtered_tile_scratch_size(const dsn_noise *handle, const dsn_grid *grid, uint32_t max_taps,
                                      uint32_t width, uint32_t height) {
    dsn_filter_plan plan;
    if (tile_plan(dsn_state(handle), grid, max_taps, width, height, grid, &plan) != DSN_OK) return 0;
    return unfiltered(plan) ? dsn_continuous_tile_scratch_size(handle, grid, width, height) : 0;
}

int dsn_filtered_tile_fixed(const dsn_noise *handle, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                            uint32_t height, int32_t *out, void *scratch, size_t scratch_size) {
    return evaluate_grid(handle, grid, max_taps, width, height, out, dsn_output_fixed, scratch, scratch_size);
}

int dsn_filtered_tile_float(const dsn_noise *handle, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                            uint32_t height, float *out, void *scratch, size_t scratch_size) {
    return evaluate_grid(handle, grid, max_taps, width, height, out, dsn_output_float, scratch, scratch_size);
}

int dsn_filtered_tile_u8(const dsn_noise *handle, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                         uint32_t height, uint8_t *out, void *scratch, size_t scratch_size) {
    return evaluate_grid(handle, grid, max_taps, width, height, out, dsn_output_u8, scratch, scratch_size);
}

} // extern "C"

#endif /* DSN_FILTERING */
