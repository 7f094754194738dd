/* runtime/evaluators/continuous_tile.cpp - the continuous mode on a regular grid (dsn_grid): a grid under any
   affine map (zoom, rotation, shear, mirror; periodic or not) is splatted, each impulse adding its bilinear
   texton to the pixels it reaches, into sums kept in the caller's scratch; grids too sparse or too large
   for that, and every grid in the small build (DSN_SMALL_CODE, dsn.h), are evaluated point by point. Both
   give the per-point bits. */
#include "core/continuous_internal.h"
#include "core/error_output.h"
#include "core/gradient_output.h"
#include "core/grid_points.h"
#include "core/normalize_fixed.h"
#include "evaluators/grid_splat.h"
#include "kernels/kernels.h"
#include "kernels/splat_cells.h"

namespace {

int check_tile(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
               const void *out) {
    const int err = dsn_internal_continuous_check(noise);
    if (err != DSN_OK) return err;
    if (grid == 0 || out == 0) return DSN_ERR_NULL;
    if (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE)
        return DSN_ERR_TILE_SIZE;
    return DSN_OK;
}

#if !DSN_SMALL_CODE
/* The texton as the grid splat reads it. */
dsn_splat_texture texton_texture(const dsn_asset *asset) {
    dsn_splat_texture texture;
    texture.values = asset->texton;
    texture.width = texture.stride = asset->width;
    texture.height = asset->height;
    texture.channels = asset->channels;
    texture.bits = asset->bits;
    texture.level = 0;
    return texture;
}

/* The tile block by block: each block's sums are splatted into the start of the scratch, then normalized
   a row at a time by the kernel (on vectors of pixels too) and mapped and stored into `out` pixel by
   pixel; a block's sums stay in the caches. 8-bit textons are read from their cell records
   (splat_cells.h) where the kernels take them, kept on the stack for the call. */
void splat_grid(const dsn_noise_state *noise, const dsn_grid_splat &prepared, uint32_t width, uint32_t height,
                uint64_t *sums, void *out, dsn_output_kind kind) {
    const dsn_kernel_entries *kernel = dsn_kernel_entries_of(noise->tile_kernel);
    const uint32_t channels = noise->asset.channels;
    dsn_grid_splat splat = prepared;
#if DSN_SPLAT_CELLS
    alignas(64) uint64_t cells[splat_cell_capacity]; /* RGB cells on 32-byte boundaries */
    if (make_splat_cells(splat.setup.texture, cells, splat_cell_capacity, &splat.setup.cell_row, 0) != 0)
        splat.setup.cells = cells;
#endif
    for (uint32_t top = 0; top < height; top += dsn_splat_block_rows)
        for (uint32_t left = 0; left < width; left += dsn_splat_block_columns) {
            const dsn_splat_block block = dsn_internal_splat_block(left, top, width, height);
            dsn_internal_grid_splat_block(noise, &splat, &block, sums);
            for (uint32_t j = 0; j < block.rows; j++) {
                int32_t values[dsn_splat_block_columns * DSN_MAX_CHANNELS];
                kernel->continuous_splat_normalize(noise, sums + static_cast<size_t>(j) * block.stride,
                                                   block.plane, block.columns, values);
                const size_t first = (static_cast<size_t>(top + j) * width + left) * channels;
                for (uint32_t i = 0; i < block.columns; i++) dsn_map_output(noise, values + i * channels);
                if (kind == dsn_output_fixed)
                    for (uint32_t i = 0; i < block.columns * channels; i++)
                        static_cast<int32_t *>(out)[first + i] = values[i];
                else
                    for (uint32_t i = 0; i < block.columns; i++)
                        dsn_store_pixel(out, kind, first + i * channels, values + i * channels, channels);
            }
        }
}

#if DSN_GRADIENTS
/* Gradient blocks: at most gradient_block_columns x gradient_block_rows pixels, whose three blocks of
   sums stay on the stack (36 KB with RGB). */
const uint32_t gradient_block_columns = dsn_splat_block_columns, gradient_block_rows = 8;
const size_t gradient_block_sums = gradient_block_columns * gradient_block_rows * DSN_MAX_CHANNELS;

/* Whether a coordinate's int32 start, X - 1 (X its integer part), wraps from 2^31 - 1 to -2^31 when it
   moves by a weight step: where a period reduces it (and does not divide 2^32) the sums jump there, so the
   moved grid's sums less the grid's are not the slopes. A grid and its moved copy each lie on one side
   (the splat's frames), so only the origin can cross. */
bool start_wraps(int64_t coordinate) {
    const uint64_t point = static_cast<uint64_t>(coordinate);
    const uint32_t start = static_cast<uint32_t>(point >> 32) - 1u,
                   moved = static_cast<uint32_t>((point + (static_cast<uint64_t>(1) << weight_step_shift)) >>
                                                 32) -
                           1u;
    return start != moved && moved == 0x80000000u;
}

/* The grid moved by a weight step (continuous_internal.h) along x (axis 0) or y (axis 1). */
dsn_grid moved_grid(const dsn_grid *grid, int axis) {
    dsn_grid moved = *grid;
    int64_t *origin = axis == 0 ? &moved.origin_x : &moved.origin_y;
    *origin = static_cast<int64_t>(static_cast<uint64_t>(*origin) +
                                   (static_cast<uint64_t>(1) << weight_step_shift));
    return moved;
}

/* Row j of a gradient block: the value from the grid's sums (sums[0]), each derivative from sums[1] and
   sums[2], per 2^-16 texel: the slopes themselves (Moved false: the one-pass runs), or the moved grid's
   sums less the grid's (Moved true: 2^8 times the slopes); times 2^16 per texel, normalized as the value
   without the mean (`slopes`, the noise with a zero offset); then the mapping's chain rule and the stores. */
template <bool Moved>
void gradient_row(const dsn_noise_state *noise, const dsn_noise_state *slopes, const dsn_splat_block &block,
                  uint32_t j, uint32_t width, uint64_t *const *sums, void *out, void *dx, void *dy,
                  dsn_output_kind kind) {
    const dsn_kernel_entries *kernel = dsn_kernel_entries_of(noise->tile_kernel);
    const uint32_t channels = noise->asset.channels;
    const size_t row = static_cast<size_t>(j) * block.stride;
    int32_t values[3][gradient_block_columns * DSN_MAX_CHANNELS];
    kernel->continuous_splat_normalize(noise, sums[0] + row, block.plane, block.columns, values[0]);
    for (uint32_t k = 1; k < 3; k++) {
        for (uint32_t c = 0; c < channels; c++)
            for (uint32_t i = 0; i < block.columns; i++) {
                const size_t at = c * block.plane + row + i;
                sums[k][at] = Moved ? (sums[k][at] - sums[0][at]) << 8 : sums[k][at] << 16;
            }
        kernel->continuous_splat_normalize(slopes, sums[k] + row, block.plane, block.columns, values[k]);
    }
    const size_t first = (static_cast<size_t>(block.top + j) * width + block.left) * channels;
    if (kind == dsn_output_fixed && !dsn_has_mapping(noise)) {
        int32_t *const outputs[3] = {static_cast<int32_t *>(out), static_cast<int32_t *>(dx),
                                     static_cast<int32_t *>(dy)};
        for (uint32_t k = 0; k < 3; k++)
            for (uint32_t i = 0; i < block.columns * channels; i++) outputs[k][first + i] = values[k][i];
        return;
    }
    for (uint32_t i = 0; i < block.columns; i++) {
        int32_t point[3 * DSN_MAX_CHANNELS];
        for (uint32_t k = 0; k < 3; k++)
            for (uint32_t c = 0; c < channels; c++)
                point[k * DSN_MAX_CHANNELS + c] = values[k][i * channels + c];
        dsn_map_gradient(noise, point, point + DSN_MAX_CHANNELS, point + 2 * DSN_MAX_CHANNELS);
        dsn_store_gradient(out, dx, dy, kind, first + i * channels, point, channels);
    }
}

/* The noise whose normalization the slopes take: the noise's, with a zero offset (the mean does not reach
   a derivative). */
dsn_noise_state slopes_noise(const dsn_noise_state *noise) {
    dsn_noise_state slopes = *noise;
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) slopes.offset[c] = 0;
    return slopes;
}

/* Whether a periodic axis's start wraps where the grid moves by a weight step (start_wraps). */
bool moves_wrap(const dsn_noise_state *noise, const dsn_grid *grid) {
    return (noise->period[0] != 0 && start_wraps(grid->origin_x)) ||
           (noise->period[1] != 0 && start_wraps(grid->origin_y));
}

/* The gradient tile in one splat, where the kernel has the gradient's runs and the texton records (8-bit,
   small enough): each impulse adds its value and both slopes at once (kernels.h's
   continuous_gradient_runs), over the closed reach (grid_splat.h), the value planes and then those of the
   slopes along x and y in one array. The per-point gradient's bits, like the three splats'. Returns 0
   where the grid or the texton does not take it. */
int splat_gradient_one_pass(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width,
                            uint32_t height, void *out, void *dx, void *dy, dsn_output_kind kind) {
#if DSN_SPLAT_CELLS
    dsn_splat_runs_entry *runs = dsn_kernel_entries_of(noise->tile_kernel)->continuous_gradient_runs;
    const dsn_splat_texture texture = texton_texture(&noise->asset);
    dsn_grid_splat splat;
    if (runs == 0 || moves_wrap(noise, grid) ||
        !dsn_internal_grid_splat_init(noise, grid, width, height, &texture, &splat))
        return 0;
    alignas(64) uint64_t cells[splat_cell_capacity];
    if (make_splat_cells(texture, cells, splat_cell_capacity, &splat.setup.cell_row, 1) == 0) return 0;
    splat.setup.cells = cells;
    splat.runs = runs;
    dsn_internal_grid_splat_closed(&splat);
    const dsn_noise_state slopes = slopes_noise(noise);
    const uint32_t channels = noise->asset.channels;
    uint64_t sums[3 * gradient_block_sums];
    for (uint32_t top = 0; top < height; top += gradient_block_rows)
        for (uint32_t left = 0; left < width; left += gradient_block_columns) {
            const dsn_splat_block block = dsn_internal_splat_small_block(
                left, top, width, height, gradient_block_columns, gradient_block_rows);
            const size_t planes = block.plane * channels;
            uint64_t *const sets[3] = {sums, sums + planes, sums + 2 * planes};
            for (size_t i = planes; i < 3 * planes; i++) sums[i] = 0; /* the values': the block splat */
            dsn_internal_grid_splat_block(noise, &splat, &block, sums);
            for (uint32_t j = 0; j < block.rows; j++)
                gradient_row<false>(noise, &slopes, block, j, width, sets, out, dx, dy, kind);
        }
    return 1;
#else
    (void)noise, (void)grid, (void)width, (void)height, (void)out, (void)dx, (void)dy, (void)kind;
    return 0;
#endif
}

/* The gradient tile by splatting three grids: the tile's and the tile's moved one weight step right and down.
   Their sums differ by 2^8 times the slope sums exactly (continuous_internal.h: the weights step by one, and
   the impulses a move brings within reach add their slope, those it takes out remove their value), so the
   bits are the per-point gradient's. Returns 0 where a grid is not splatted or its move wraps a periodic
   axis's start (point by point instead). */
int splat_gradient_tile(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                        void *out, void *dx, void *dy, dsn_output_kind kind) {
    if (splat_gradient_one_pass(noise, grid, width, height, out, dx, dy, kind)) return 1;
    if (moves_wrap(noise, grid)) return 0;
    const dsn_grid grids[3] = {*grid, moved_grid(grid, 0), moved_grid(grid, 1)};
    const dsn_splat_texture texture = texton_texture(&noise->asset);
    dsn_grid_splat splats[3];
    for (uint32_t k = 0; k < 3; k++)
        if (!dsn_internal_grid_splat_init(noise, &grids[k], width, height, &texture, &splats[k])) return 0;
#if DSN_SPLAT_CELLS
    alignas(64) uint64_t cells[splat_cell_capacity];
    uint32_t cell_row = 0;
    if (make_splat_cells(texture, cells, splat_cell_capacity, &cell_row, 0) != 0)
        for (uint32_t k = 0; k < 3; k++) {
            splats[k].setup.cells = cells;
            splats[k].setup.cell_row = cell_row;
        }
#endif
    const dsn_noise_state slopes = slopes_noise(noise);
    uint64_t sums[3][gradient_block_sums];
    uint64_t *const sets[3] = {sums[0], sums[1], sums[2]};
    for (uint32_t top = 0; top < height; top += gradient_block_rows)
        for (uint32_t left = 0; left < width; left += gradient_block_columns) {
            const dsn_splat_block block = dsn_internal_splat_small_block(
                left, top, width, height, gradient_block_columns, gradient_block_rows);
            for (uint32_t k = 0; k < 3; k++)
                dsn_internal_grid_splat_block(noise, &splats[k], &block, sums[k]);
            for (uint32_t j = 0; j < block.rows; j++)
                gradient_row<true>(noise, &slopes, block, j, width, sets, out, dx, dy, kind);
        }
    return 1;
}
#endif /* DSN_GRADIENTS */

/* The scratch the grid asks for: the sums when it is splatted, else 0 (point by point). */
size_t splat_scratch_size(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                          dsn_grid_splat *splat) {
    const dsn_splat_texture texture = texton_texture(&noise->asset);
    if (!dsn_internal_grid_splat_init(noise, grid, width, height, &texture, splat)) return 0;
    return dsn_internal_splat_sums_size(noise->asset.channels, width, height);
}

#endif /* !DSN_SMALL_CODE */

/* A grid point evaluated on its own, stored as `kind` at value `index` of `out`. */
struct ContinuousPixel {
    const dsn_noise_state *noise;
    void *out;
    dsn_output_kind kind;
    void operator()(size_t index, uint64_t x, uint64_t y) const {
        int32_t pixel[DSN_MAX_CHANNELS];
        dsn_internal_continuous_point(noise, x, y, pixel);
        dsn_store_pixel(out, kind, index, pixel, noise->asset.channels);
    }
};

/* Evaluates every grid point in order into `out`: by splatting when the grid qualifies (not in the
   small build), else point by point. */
int evaluate_grid(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                  void *out, dsn_output_kind kind, void *scratch, size_t scratch_size) {
    const int err = check_tile(noise, grid, width, height, out);
    if (err != DSN_OK) return dsn_output_error(err, noise, out, kind, size_t(width) * height);
#if !DSN_SMALL_CODE
    dsn_grid_splat splat;
    const size_t needed = splat_scratch_size(noise, grid, width, height, &splat);
    if (needed != 0) {
        if (scratch == 0 || scratch_size < needed)
            return dsn_output_error(DSN_ERR_SCRATCH, noise, out, kind, size_t(width) * height);
        splat_grid(noise, splat, width, height, dsn_internal_aligned_sums(scratch), out, kind);
        return DSN_OK;
    }
#else
    (void)scratch;
    (void)scratch_size;
#endif
    const ContinuousPixel pixel = {noise, out, kind};
    dsn_grid_points(grid, width, height, noise->asset.channels, pixel);
    return DSN_OK;
}

} // namespace

#if DSN_GRADIENTS
int dsn_internal_continuous_gradient_splat(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width,
                                           uint32_t height, void *out, void *dx, void *dy,
                                           dsn_output_kind kind) {
#if !DSN_SMALL_CODE
    if (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE) return 0;
    return splat_gradient_tile(noise, grid, width, height, out, dx, dy, kind);
#else
    (void)noise, (void)grid, (void)width, (void)height, (void)out, (void)dx, (void)dy, (void)kind;
    return 0;
#endif
}
#endif

extern "C" {

size_t dsn_continuous_tile_scratch_size(const dsn_noise *handle, const dsn_grid *grid, uint32_t width,
                                        uint32_t height) {
    const dsn_noise_state *noise = dsn_state(handle);
#if DSN_SMALL_CODE
    (void)noise, (void)grid, (void)width, (void)height;
    return 0; /* point by point: no scratch */
#else
    dsn_grid_splat splat;
    if (check_tile(noise, grid, width, height, grid) != DSN_OK) return 0;
    return splat_scratch_size(noise, grid, width, height, &splat);
#endif
}

int dsn_continuous_tile_fixed(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height,
                              int32_t *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return evaluate_grid(noise, grid, width, height, out, dsn_output_fixed, scratch, scratch_size);
}

int dsn_continuous_tile_float(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height,
                              float *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return evaluate_grid(noise, grid, width, height, out, dsn_output_float, scratch, scratch_size);
}

int dsn_continuous_tile_u8(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height,
                           uint8_t *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return evaluate_grid(noise, grid, width, height, out, dsn_output_u8, scratch, scratch_size);
}

} // extern "C"
