/* runtime/evaluators/continuous_tile.cpp - the continuous mode on a regular grid (dsn_grid): a grid under any
   affine map (zoom, rotation, shear, mirror; periodic or not) is splatted, each impulse adding its bilinear
   texton to the pixels it reaches, into sums kept in the caller's scratch; grids too sparse or too large
   for that, and every grid in the small build (DSN_SMALL_CODE, dsn.h), are evaluated point by point. Both
   give the per-point bits. */
#include "core/continuous_internal.h"
#include "core/error_output.h"
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
    if (make_splat_cells(splat.setup.texture, cells, splat_cell_capacity, &splat.setup.cell_row) != 0)
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
