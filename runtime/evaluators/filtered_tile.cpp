/* runtime/evaluators/filtered_tile.cpp - the filtered evaluation on a grid (dsn_grid) whose footprint is the
   grid's own steps: the plan (level of detail, taps) is computed once; then each tap's grid (the grid moved
   by the tap's offset) is splatted with each level the plan blends (grid_splat.h), block by block, and each
   pixel's level sums go through the filtered point's steps (filtered_internal.h), so the tile has the
   filtered point's bits. Grids that do not splat (too sparse, too large, the small build) and faded plans
   go point by point; an unfiltered plan (level of detail 0, one tap) is the continuous mode's tile.
   Compiled only with DSN_FILTERING. */
#include "core/continuous_internal.h"
#include "core/error_output.h"
#include "core/filtered_internal.h"
#include "core/gradient_output.h"
#include "core/grid_points.h"
#include "core/normalize_fixed.h"
#include "evaluators/grid_splat.h"
#include "kernels/splat_cells.h"

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

#if !DSN_SMALL_CODE
/* The level as the grid splat reads it. */
dsn_splat_texture level_texture(const dsn_noise_state *noise, const dsn_walked_level &level) {
    dsn_splat_texture texture;
    texture.values = level.values;
    texture.width = level.width;
    texture.height = level.height;
    texture.stride = level.stride;
    texture.channels = noise->asset.channels;
    texture.bits = noise->asset.bits;
    texture.level = level.level;
    return texture;
}

/* The grid of one tap: moved by the tap's offset (modulo 2^64, as per point). */
dsn_grid tap_grid(const dsn_grid *grid, const dsn_filter_plan &plan, uint32_t tap) {
    dsn_grid moved = *grid;
    moved.origin_x =
        signed_from_bits(static_cast<uint64_t>(grid->origin_x) + static_cast<uint64_t>(plan.offset_x[tap]));
    moved.origin_y =
        signed_from_bits(static_cast<uint64_t>(grid->origin_y) + static_cast<uint64_t>(plan.offset_y[tap]));
    return moved;
}

/* What a splatted filtered tile shares: the plan, its levels and their cell records. */
struct FilteredSplat {
    dsn_filter_plan plan;
    dsn_walked_level walked[2];
    uint32_t count;
    const uint64_t *cells[2];
    uint32_t cell_row[2];
    /* Splatted as the transposed grid (columns and rows swapped, whose rows are then the longer runs):
       its pixel (i, j) is the tile's (j, i). */
    int transposed;
};

/* The grid with its columns and rows swapped. */
dsn_grid transposed_grid(const dsn_grid *grid) {
    dsn_grid swapped = *grid;
    swapped.column_step_x = grid->row_step_x;
    swapped.column_step_y = grid->row_step_y;
    swapped.row_step_x = grid->column_step_x;
    swapped.row_step_y = grid->column_step_y;
    return swapped;
}

/* The splat of one tap's grid with one level (its records where made), or 0 where it does not splat. */
int tap_level_splat(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                    const FilteredSplat &filtered, uint32_t tap, uint32_t index, dsn_grid_splat *splat) {
    const dsn_grid moved = tap_grid(grid, filtered.plan, tap);
    const dsn_splat_texture texture = level_texture(noise, filtered.walked[index]);
    if (!dsn_internal_grid_splat_init(noise, &moved, width, height, &texture, splat)) return 0;
    splat->setup.cells = filtered.cells[index];
    splat->setup.cell_row = filtered.cell_row[index];
    return 1;
}

/* Whether every tap's grid splats with every level (else the tile goes point by point). */
bool tile_splats(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                 const FilteredSplat &filtered) {
    for (uint32_t tap = 0; tap < filtered.plan.taps; tap++)
        for (uint32_t k = 0; k < filtered.count; k++) {
            dsn_grid_splat splat;
            if (!tap_level_splat(noise, grid, width, height, filtered, tap, k, &splat)) return false;
        }
    return true;
}

/* One block of the splatted grid (width x height pixels; the tile's own or, transposed, the tile's
   height x width): every tap's levels splatted into `sums` in turn, each pixel's values added to its
   totals, then the totals finished and stored at the tile's pixel. */
void filter_block(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                  const FilteredSplat &filtered, const dsn_splat_block &block, uint64_t *sums,
                  int64_t *totals, void *out, dsn_output_kind kind) {
    const uint32_t channels = noise->asset.channels, pixels = block.columns * block.rows;
    for (uint32_t i = 0; i < pixels * channels; i++) totals[i] = 0;
    for (uint32_t tap = 0; tap < filtered.plan.taps; tap++) {
        for (uint32_t k = 0; k < filtered.count; k++) {
            dsn_grid_splat splat;
            tap_level_splat(noise, grid, width, height, filtered, tap, k, &splat); /* tile_splats said 1 */
            dsn_internal_grid_splat_block(noise, &splat, &block, sums);
            for (uint32_t p = 0; p < pixels; p++) {
                const size_t at = static_cast<size_t>(p / block.columns) * block.stride + p % block.columns;
                uint64_t level_sums[DSN_MAX_CHANNELS];
                int64_t values[DSN_MAX_CHANNELS];
                for (uint32_t c = 0; c < channels; c++) level_sums[c] = sums[c * block.plane + at];
                dsn_internal_filter_level_values(noise, &filtered.walked[k], level_sums, values);
                dsn_internal_filter_add_level(noise, &filtered.plan, k, values, totals + p * channels);
            }
        }
        if (filtered.count == 1)
            for (uint32_t p = 0; p < pixels; p++)
                dsn_internal_filter_add_mean(noise, &filtered.plan, totals + p * channels);
    }
    /* Output pixels from one splatted grid column and row to the next. */
    const size_t step_i = filtered.transposed ? height : 1u, step_j = filtered.transposed ? 1u : width;
    for (uint32_t p = 0; p < pixels; p++) {
        int32_t pixel[DSN_MAX_CHANNELS];
        dsn_internal_filter_finish(noise, &filtered.plan, totals + p * channels, pixel);
        const size_t i = block.left + p % block.columns, j = block.top + p / block.columns;
        dsn_store_pixel(out, kind, (i * step_i + j * step_j) * channels, pixel, channels);
    }
}

/* The scratch a splatted filtered tile takes: the block sums, then the totals. */
size_t filtered_splat_size(const dsn_noise_state *noise, uint32_t width, uint32_t height) {
    return 2u * dsn_internal_splat_sums_size(noise->asset.channels, width, height);
}

/* Whether an impulse of every level reaches at least splat_run_least pixels of a row through its centre:
   2 (radius + 1) 2^level texels against the column step along each axis. On shorter runs the splat's
   cost per impulse outweighs what it shares, and the filtered point (which shares each impulse across
   the taps) is as fast or faster. */
const uint64_t splat_run_least = 12;

bool runs_long_enough(const dsn_grid *grid, const FilteredSplat &filtered) {
    const uint64_t step_x =
        static_cast<uint64_t>(grid->column_step_x < 0 ? -grid->column_step_x : grid->column_step_x);
    const uint64_t step_y =
        static_cast<uint64_t>(grid->column_step_y < 0 ? -grid->column_step_y : grid->column_step_y);
    for (uint32_t k = 0; k < filtered.count; k++) {
        const dsn_walked_level &level = filtered.walked[k];
        const uint64_t reach_x = static_cast<uint64_t>(level.radius_x + 1u) << (32u + level.level);
        const uint64_t reach_y = static_cast<uint64_t>(level.radius_y + 1u) << (32u + level.level);
        /* |steps| < 2^46 (tile_splats), reaches < 2^60 */
        if (2u * reach_x < splat_run_least * step_x || 2u * reach_y < splat_run_least * step_y) return false;
    }
    return true;
}

/* Prepares `filtered` and returns the scratch the splat needs, or 0 when the tile goes point by point.
   A grid whose rows make runs too short is splatted transposed where its columns make them long enough
   (a footprint stretched along the rows' direction). */
size_t filtered_splat_prepare(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width,
                              uint32_t height, const dsn_filter_plan &plan, FilteredSplat *filtered) {
    int32_t faded[DSN_MAX_CHANNELS];
    if (dsn_internal_filter_fade(noise, &plan, faded)) return 0;
    filtered->plan = plan;
    filtered->count = dsn_internal_filter_walked_levels(noise, &plan, filtered->walked);
    filtered->cells[0] = filtered->cells[1] = 0; /* made by filtered_splat */
    filtered->cell_row[0] = filtered->cell_row[1] = 0;
    filtered->transposed = 0;
    if (tile_splats(noise, grid, width, height, *filtered) && runs_long_enough(grid, *filtered))
        return filtered_splat_size(noise, width, height);
    const dsn_grid swapped = transposed_grid(grid);
    if (!tile_splats(noise, &swapped, height, width, *filtered) || !runs_long_enough(&swapped, *filtered))
        return 0;
    filtered->transposed = 1;
    return filtered_splat_size(noise, height, width);
}

void filtered_splat(const dsn_noise_state *noise, const dsn_grid *tile_grid, uint32_t tile_width,
                    uint32_t tile_height, FilteredSplat *filtered, void *scratch, void *out,
                    dsn_output_kind kind) {
    const dsn_grid swapped = transposed_grid(tile_grid);
    const dsn_grid *grid = filtered->transposed ? &swapped : tile_grid;
    const uint32_t width = filtered->transposed ? tile_height : tile_width;
    const uint32_t height = filtered->transposed ? tile_width : tile_height;
    uint64_t *sums = dsn_internal_aligned_sums(scratch);
    int64_t *totals = static_cast<int64_t *>(
        static_cast<void *>(sums + dsn_internal_splat_block_pixels(width, height) * noise->asset.channels));
#if DSN_SPLAT_CELLS
    alignas(64) uint64_t cells[splat_cell_capacity]; /* the levels' records, one after the other */
    uint32_t used = 0;
    for (uint32_t k = 0; k < filtered->count; k++) {
        const dsn_splat_texture texture = level_texture(noise, filtered->walked[k]);
        const uint32_t records =
            make_splat_cells(texture, cells + used, splat_cell_capacity - used, &filtered->cell_row[k], 0);
        if (records != 0) filtered->cells[k] = cells + used;
        used += records;
    }
#endif
    for (uint32_t top = 0; top < height; top += dsn_splat_block_rows)
        for (uint32_t left = 0; left < width; left += dsn_splat_block_columns) {
            const dsn_splat_block block = dsn_internal_splat_block(left, top, width, height);
            filter_block(noise, grid, width, height, *filtered, block, sums, totals, out, kind);
        }
    filtered->cells[0] = filtered->cells[1] = 0;
}
#endif

#if DSN_GRADIENTS && !DSN_SMALL_CODE
/* Gradient blocks: at most gradient_block_columns x gradient_block_rows pixels, whose sums (the tap's grid's
   and a moved one's) and three outputs' totals stay on the stack (60 KB with RGB, beside the levels' 64 KB
   of records). */
const uint32_t gradient_block_columns = dsn_splat_block_columns, gradient_block_rows = 8;
const size_t gradient_block_values = gradient_block_columns * gradient_block_rows * DSN_MAX_CHANNELS;

/* Whether a coordinate's int32 start, X - 1, wraps from 2^31 - 1 to -2^31 when it moves by `step` (below a
   texel): where a period reduces it the sums jump there (the continuous gradient tile's seam). A grid and
   its moved copy each lie on one side, so only the origin can cross. */
bool start_wraps(int64_t coordinate, uint64_t step) {
    const uint64_t point = static_cast<uint64_t>(coordinate);
    const uint32_t start = static_cast<uint32_t>(point >> 32) - 1u,
                   moved = static_cast<uint32_t>((point + step) >> 32) - 1u;
    return start != moved && moved == 0x80000000u;
}

/* The splats of one tap and level: the tap's grid, and the same moved one weight step of the level (2^-8
   level texel) along x and along y, whose sums less the tap's are 2^8 times the level's slope sums exactly
   (the filtered gradient's sifted walk, filtered_sift.cpp); 0 where one does not splat or a move wraps a
   periodic axis's start. */
int tap_level_gradient_splats(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width,
                              uint32_t height, const FilteredSplat &filtered, uint32_t tap, uint32_t index,
                              dsn_grid_splat *splats) {
    const uint64_t step = static_cast<uint64_t>(1) << (weight_step_shift + filtered.walked[index].level);
    dsn_grid grids[3] = {tap_grid(grid, filtered.plan, tap), tap_grid(grid, filtered.plan, tap),
                         tap_grid(grid, filtered.plan, tap)};
    if ((noise->period[0] != 0 && start_wraps(grids[0].origin_x, step)) ||
        (noise->period[1] != 0 && start_wraps(grids[0].origin_y, step)))
        return 0;
    grids[1].origin_x = signed_from_bits(static_cast<uint64_t>(grids[1].origin_x) + step);
    grids[2].origin_y = signed_from_bits(static_cast<uint64_t>(grids[2].origin_y) + step);
    const dsn_splat_texture texture = level_texture(noise, filtered.walked[index]);
    for (uint32_t k = 0; k < 3; k++) {
        if (!dsn_internal_grid_splat_init(noise, &grids[k], width, height, &texture, &splats[k])) return 0;
        splats[k].setup.cells = filtered.cells[index];
        splats[k].setup.cell_row = filtered.cell_row[index];
    }
    return 1;
}

bool gradient_splats(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                     const FilteredSplat &filtered) {
    for (uint32_t tap = 0; tap < filtered.plan.taps; tap++)
        for (uint32_t k = 0; k < filtered.count; k++) {
            dsn_grid_splat splats[3];
            if (!tap_level_gradient_splats(noise, grid, width, height, filtered, tap, k, splats))
                return false;
        }
    return true;
}

/* A tap's level sums in one splat (kernels.h's continuous_gradient_runs, over the closed reach:
   grid_splat.h): the value planes, then the slopes' along x and y, each `channels` planes, at `sums`. */
void one_pass_sums(const dsn_noise_state *noise, dsn_grid_splat *splat, const dsn_splat_block &block,
                   uint64_t *sums) {
    const size_t planes = block.plane * noise->asset.channels;
    splat->runs = dsn_kernel_entries_of(noise->tile_kernel)->continuous_gradient_runs;
    dsn_internal_grid_splat_closed(splat);
    for (size_t i = planes; i < 3 * planes; i++) sums[i] = 0; /* the values': the block splat */
    dsn_internal_grid_splat_block(noise, splat, &block, sums);
}

/* One gradient block (filter_block's, with the three grids of every tap and level, the moved ones in turn
   in the second sums; or with One_pass each tap and level splatted once, its value and slopes at once):
   each pixel's level values and slopes blended into the three totals, then finished and stored at the
   tile's pixel. */
template <bool One_pass>
void gradient_block(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                    const FilteredSplat &filtered, const dsn_splat_block &block, uint64_t *sums,
                    int64_t (*totals)[gradient_block_values], void *out, void *dx, void *dy,
                    dsn_output_kind kind) {
    const uint32_t channels = noise->asset.channels, pixels = block.columns * block.rows;
    const size_t planes = block.plane * channels;
    for (uint32_t output = 0; output < 3; output++)
        for (uint32_t i = 0; i < pixels * channels; i++) totals[output][i] = 0;
    for (uint32_t tap = 0; tap < filtered.plan.taps; tap++) {
        for (uint32_t k = 0; k < filtered.count; k++) {
            const dsn_walked_level *level = &filtered.walked[k];
            dsn_grid_splat splats[3];
            tap_level_gradient_splats(noise, grid, width, height, filtered, tap, k, splats); /* checked */
            if (One_pass)
                one_pass_sums(noise, &splats[0], block, sums);
            else
                dsn_internal_grid_splat_block(noise, &splats[0], &block, sums);
            for (uint32_t output = 0; output < 3; output++) {
                if (!One_pass && output != 0)
                    dsn_internal_grid_splat_block(noise, &splats[output], &block,
                                                  sums + gradient_block_values);
                for (uint32_t p = 0; p < pixels; p++) {
                    uint64_t level_sums[DSN_MAX_CHANNELS];
                    for (uint32_t c = 0; c < channels; c++) {
                        const size_t at = c * block.plane + p;
                        level_sums[c] = output == 0 ? sums[at]
                                        : One_pass
                                            ? sums[output * planes + at]
                                            : slopes_from_step(sums[gradient_block_values + at] - sums[at]);
                    }
                    int64_t values[DSN_MAX_CHANNELS];
                    if (output == 0)
                        dsn_internal_filter_level_values(noise, level, level_sums, values);
                    else
                        dsn_internal_filter_level_slopes(noise, level, level_sums, values);
                    dsn_internal_filter_add_level(noise, &filtered.plan, k, values,
                                                  totals[output] + p * channels);
                }
            }
        }
        if (filtered.count == 1) /* a constant: no slope */
            for (uint32_t p = 0; p < pixels; p++)
                dsn_internal_filter_add_mean(noise, &filtered.plan, totals[0] + p * channels);
    }
    const size_t step_i = filtered.transposed ? height : 1u, step_j = filtered.transposed ? 1u : width;
    for (uint32_t p = 0; p < pixels; p++) {
        int64_t pixel_totals[3][DSN_MAX_CHANNELS];
        for (uint32_t output = 0; output < 3; output++)
            for (uint32_t c = 0; c < channels; c++)
                pixel_totals[output][c] = totals[output][p * channels + c];
        int32_t values[3 * DSN_MAX_CHANNELS];
        dsn_internal_filter_gradient_finish(noise, &filtered.plan, pixel_totals, values);
        const size_t i = block.left + p % block.columns, j = block.top + p / block.columns;
        dsn_store_gradient(out, dx, dy, kind, (i * step_i + j * step_j) * channels, values, channels);
    }
}
#endif

/* The scratch the tile asks for: the continuous tile's for an unfiltered plan, the splat's, or 0. */
size_t tile_scratch_size(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height,
                         const dsn_filter_plan &plan) {
    if (unfiltered(plan)) return dsn_continuous_tile_scratch_size(handle, grid, width, height);
#if !DSN_SMALL_CODE
    FilteredSplat filtered;
    return filtered_splat_prepare(dsn_state(handle), grid, width, height, plan, &filtered);
#else
    return 0;
#endif
}

/* A grid point filtered on its own, stored as `kind` at value `index` of `out`. */
struct FilteredPixel {
    const dsn_noise_state *noise;
    const dsn_filter_plan *plan;
    void *out;
    dsn_output_kind kind;
    void operator()(size_t index, uint64_t x, uint64_t y) const {
        int32_t pixel[DSN_MAX_CHANNELS];
        dsn_internal_filtered_point(noise, x, y, plan, pixel);
        dsn_store_pixel(out, kind, index, pixel, noise->asset.channels);
    }
};

int evaluate_grid(const dsn_noise *handle, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                  uint32_t height, void *out, dsn_output_kind kind, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    dsn_filter_plan plan;
    const int err = tile_plan(noise, grid, max_taps, width, height, out, &plan);
    if (err != DSN_OK) return dsn_output_error(err, noise, out, kind, size_t(width) * height);
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
#if !DSN_SMALL_CODE
    FilteredSplat filtered;
    const size_t needed = filtered_splat_prepare(noise, grid, width, height, plan, &filtered);
    if (needed != 0) {
        if (scratch == 0 || scratch_size < needed)
            return dsn_output_error(DSN_ERR_SCRATCH, noise, out, kind, size_t(width) * height);
        filtered_splat(noise, grid, width, height, &filtered, scratch, out, kind);
        return DSN_OK;
    }
#else
    (void)scratch, (void)scratch_size;
#endif
    const FilteredPixel pixel = {noise, &plan, out, kind};
    dsn_grid_points(grid, width, height, noise->asset.channels, pixel);
    return DSN_OK;
}

} // namespace

#if DSN_GRADIENTS && !DSN_SMALL_CODE
int dsn_internal_filtered_gradient_splat(const dsn_noise_state *noise, const dsn_grid *tile_grid,
                                         const dsn_filter_plan *plan, uint32_t tile_width,
                                         uint32_t tile_height, void *out, void *dx, void *dy,
                                         dsn_output_kind kind) {
    if (tile_width == 0 || tile_height == 0 || tile_width > DSN_TILE_MAX_SIDE ||
        tile_height > DSN_TILE_MAX_SIDE)
        return 0;
    FilteredSplat filtered;
    if (filtered_splat_prepare(noise, tile_grid, tile_width, tile_height, *plan, &filtered) == 0) return 0;
    const dsn_grid swapped = transposed_grid(tile_grid);
    const dsn_grid *grid = filtered.transposed ? &swapped : tile_grid;
    const uint32_t width = filtered.transposed ? tile_height : tile_width;
    const uint32_t height = filtered.transposed ? tile_width : tile_height;
    if (!gradient_splats(noise, grid, width, height, filtered)) return 0;
    /* One splat per tap and level where the kernel adds the slopes and every level has records, with a
       margin (splat_cells.h); else three. */
    bool one_pass = dsn_kernel_entries_of(noise->tile_kernel)->continuous_gradient_runs != 0;
#if DSN_SPLAT_CELLS
    alignas(64) uint64_t cells[splat_cell_capacity]; /* the levels' records, one after the other */
    uint32_t used = 0;
    for (uint32_t k = 0; k < filtered.count; k++) {
        const dsn_splat_texture texture = level_texture(noise, filtered.walked[k]);
        const uint32_t records = make_splat_cells(texture, cells + used, splat_cell_capacity - used,
                                                  &filtered.cell_row[k], one_pass ? 1u : 0u);
        if (records != 0) filtered.cells[k] = cells + used;
        one_pass = one_pass && records != 0;
        used += records;
    }
#endif
    uint64_t sums[3 * gradient_block_values];
    int64_t totals[3][gradient_block_values];
    for (uint32_t top = 0; top < height; top += gradient_block_rows)
        for (uint32_t left = 0; left < width; left += gradient_block_columns) {
            const dsn_splat_block block = dsn_internal_splat_small_block(
                left, top, width, height, gradient_block_columns, gradient_block_rows);
            if (one_pass)
                gradient_block<true>(noise, grid, width, height, filtered, block, sums, totals, out, dx, dy,
                                     kind);
            else
                gradient_block<false>(noise, grid, width, height, filtered, block, sums, totals, out, dx, dy,
                                      kind);
        }
    return 1;
}
#endif

extern "C" {

size_t dsn_filtered_tile_scratch_size(const dsn_noise *handle, const dsn_grid *grid, uint32_t max_taps,
                                      uint32_t width, uint32_t height) {
    dsn_filter_plan plan;
    if (tile_plan(dsn_state(handle), grid, max_taps, width, height, grid, &plan) != DSN_OK) return 0;
    return tile_scratch_size(handle, grid, width, height, plan);
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
