/* runtime/continuous_tile.cpp - the continuous mode on a regular grid (dsn_grid): an axis-aligned grid
   without a period is splatted, each impulse adding its bilinear texton to the pixels it reaches, into
   sums kept in the caller's scratch; any other grid, and every grid in the small build (DSN_SMALL_CODE,
   dsn.h), is evaluated point by point. Both give the per-point bits. */
#include "bilinear_texton.h"
#include "cell_walk.h"
#include "continuous_internal.h"
#include "impulse_position.h"
#include "normalize_fixed.h"
#include "poisson_count.h"

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
/* ---- Fast path: splatting the impulses of an axis-aligned grid ----
   For a grid with steps (a, 0) and (0, b), a, b > 0, and no period, each impulse of the cells around
   the grid adds its bilinear texton to the pixels it reaches, into per-pixel sums held in the scratch
   buffer. Pixel by pixel these are the per-point sums exactly: the same impulses (every impulse that
   reaches a pixel lies in those cells, each cell is visited once), the same offset d (x - p modulo 2^64,
   which is what the per-point path computes for any impulse within reach), the same weights, and
   integer sums do not depend on the order. Used when it is cheaper than per point: when one pixel
   covers less area than the cells a point visits. */

struct SplatAxis {
    uint64_t origin, step;  /* Q32.32 */
    uint32_t count, radius; /* pixels along the axis, texton radius */
    uint32_t first_cell, cell_count;
};

int64_t floor_divide(int64_t numerator, int64_t denominator) { /* denominator > 0 */
    const int64_t quotient = numerator / denominator;
    return (quotient * denominator > numerator) ? quotient - 1 : quotient;
}

/* The grid spans < 2^30 texels along the axis (so every offset below fits an int64 with room to spare). */
bool splat_axis(SplatAxis *axis, int64_t origin, int64_t step, uint32_t count, uint32_t radius,
                uint32_t shift) {
    if (step <= 0 || static_cast<uint64_t>(step) > (static_cast<uint64_t>(1) << 62) / count) return false;
    axis->origin = static_cast<uint64_t>(origin);
    axis->step = static_cast<uint64_t>(step);
    axis->count = count;
    axis->radius = radius;
    const uint64_t last_point = axis->origin + axis->step * (count - 1u);
    const uint32_t low = static_cast<uint32_t>(axis->origin >> 32) - radius - 1u;
    const uint32_t high = static_cast<uint32_t>(last_point >> 32) + radius + 1u;
    axis->first_cell = low >> shift;
    axis->cell_count = ((high - low + (low & ((1u << shift) - 1u))) >> shift) + 1u;
    return true;
}

/* The pixels [*first, *last] whose points may lie within radius + 1 of the impulse at p (a superset:
   bracket() decides exactly); false when there are none. */
bool splat_range(const SplatAxis &axis, uint64_t position, uint32_t *first, uint32_t *last) {
    const int64_t relative = signed_from_bits(position - axis.origin);
    const int64_t reach = static_cast<int64_t>(axis.radius + 1u) * static_cast<int64_t>(one_texel);
    const int64_t step = static_cast<int64_t>(axis.step);
    const int64_t low = floor_divide(relative - reach, step), high = floor_divide(relative + reach, step) + 1;
    if (high < 0 || low >= static_cast<int64_t>(axis.count)) return false;
    *first = low < 0 ? 0u : static_cast<uint32_t>(low);
    *last = high >= static_cast<int64_t>(axis.count) ? axis.count - 1u : static_cast<uint32_t>(high);
    return true;
}

/* Offset (Q32.32) from the impulse at `position` to pixel `index` of the axis. */
int64_t splat_offset(const SplatAxis &axis, uint32_t index, uint64_t position) {
    return signed_from_bits(axis.origin + axis.step * index - position);
}

/* Both axes, or false when the grid does not qualify (rotation, period, too sparse, too large). */
bool splat_axes(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                SplatAxis *x, SplatAxis *y) {
    const uint32_t shift = noise->cell_shift;
    if (grid->column_step_y != 0 || grid->row_step_x != 0 || noise->period[0] != 0 || noise->period[1] != 0)
        return false;
    if (!splat_axis(x, grid->origin_x, grid->column_step_x, width, noise->radius[0], shift) ||
        !splat_axis(y, grid->origin_y, grid->row_step_y, height, noise->radius[1], shift))
        return false;
    /* Per point, a point visits about (2r + 2 + cell)^2 texels of impulses; a pixel here a * b. */
    const uint64_t visited_x = 2u * noise->radius[0] + 2u + (1u << shift);
    const uint64_t visited_y = 2u * noise->radius[1] + 2u + (1u << shift);
    return (x->step >> 16) * (y->step >> 16) <= (visited_x * visited_y) << 32;
}

size_t splat_scratch_size(const dsn_noise_state *noise, uint32_t width, uint32_t height) {
    const uint64_t bytes = static_cast<uint64_t>(width) * height * noise->asset.channels * sizeof(uint64_t);
    const uint64_t alignment_slack = sizeof(uint64_t) - 1u;
    if (bytes + alignment_slack > static_cast<size_t>(-1)) return 0; /* too large here: per point */
    return static_cast<size_t>(bytes + alignment_slack);
}

/* The scratch as an array of uint64, aligned (the caller's buffer needs no alignment). */
uint64_t *aligned_sums(void *scratch) {
    unsigned char *bytes = static_cast<unsigned char *>(scratch);
    const uintptr_t misalignment = reinterpret_cast<uintptr_t>(bytes) % sizeof(uint64_t);
    return static_cast<uint64_t *>(
        static_cast<void *>(bytes + (misalignment ? sizeof(uint64_t) - misalignment : 0u)));
}

void splat_impulse(const dsn_noise_state *noise, const SplatAxis &x, const SplatAxis &y, uint64_t position_x,
                   uint64_t position_y, uint64_t *sums) {
    uint32_t first_i, last_i, first_j, last_j;
    if (!splat_range(x, position_x, &first_i, &last_i) || !splat_range(y, position_y, &first_j, &last_j))
        return;
    const uint32_t channels = noise->asset.channels;
    for (uint32_t j = first_j; j <= last_j; j++) {
        uint32_t row, row_weight;
        if (!bracket(splat_offset(y, j, position_y), noise->radius[1], &row, &row_weight)) continue;
        for (uint32_t i = first_i; i <= last_i; i++) {
            uint32_t column, column_weight;
            if (!bracket(splat_offset(x, i, position_x), noise->radius[0], &column, &column_weight)) continue;
            add_bilinear(&noise->asset, row, row_weight, column, column_weight,
                         sums + (static_cast<size_t>(j) * x.count + i) * channels);
        }
    }
}

void splat_grid(const dsn_noise_state *noise, const SplatAxis &x, const SplatAxis &y, uint64_t *sums) {
    const uint32_t shift = noise->cell_shift, cell_mask = 0xFFFFFFFFu >> shift;
    for (uint32_t cy = 0; cy < y.cell_count; cy++)
        for (uint32_t cx = 0; cx < x.cell_count; cx++) {
            const uint32_t cell_x = (x.first_cell + cx) & cell_mask, cell_y = (y.first_cell + cy) & cell_mask;
            const uint32_t key = dsn_cell_key(noise, cell_x, cell_y);
            const uint32_t count = dsn_cell_impulse_count(noise, key);
            const uint64_t origin_x = static_cast<uint64_t>(cell_x << shift) << 32;
            const uint64_t origin_y = static_cast<uint64_t>(cell_y << shift) << 32;
            for (uint32_t k = 0; k < count; k++) {
                const uint32_t hash = dsn_impulse_hash(noise, key, k);
                splat_impulse(noise, x, y,
                              origin_x + (static_cast<uint64_t>(dsn_impulse_bits_x(hash)) << (16u + shift)),
                              origin_y + (static_cast<uint64_t>(dsn_impulse_bits_y(hash)) << (16u + shift)),
                              sums);
            }
        }
}

#endif /* !DSN_SMALL_CODE */

/* Evaluates every grid point in order into `out`: by splatting when the grid qualifies (not in the
   small build), else point by point. */
int evaluate_grid(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                  void *out, dsn_output_kind kind, void *scratch, size_t scratch_size) {
    const int err = check_tile(noise, grid, width, height, out);
    if (err != DSN_OK) return err;
    const uint32_t channels = noise->asset.channels;
    int32_t pixel[DSN_MAX_CHANNELS];
#if !DSN_SMALL_CODE
    SplatAxis x, y;
    const size_t needed =
        splat_axes(noise, grid, width, height, &x, &y) ? splat_scratch_size(noise, width, height) : 0;
    if (needed != 0) {
        if (scratch == 0 || scratch_size < needed) return DSN_ERR_SCRATCH;
        uint64_t *sums = aligned_sums(scratch);
        const size_t values = static_cast<size_t>(width) * height * channels;
        for (size_t i = 0; i < values; i++) sums[i] = 0;
        splat_grid(noise, x, y, sums);
        for (size_t p = 0; p < values; p += channels) {
            normalize_q32(noise, sums + p, pixel);
            dsn_store_pixel(out, kind, p, pixel, channels);
        }
        return DSN_OK;
    }
#else
    (void)scratch;
    (void)scratch_size;
#endif
    /* Pixel (i, j) is origin + i column_step + j row_step modulo 2^64: stepping adds the same values. */
    uint64_t row_x = static_cast<uint64_t>(grid->origin_x), row_y = static_cast<uint64_t>(grid->origin_y);
    size_t index = 0;
    for (uint32_t j = 0; j < height; j++) {
        uint64_t point_x = row_x, point_y = row_y;
        for (uint32_t i = 0; i < width; i++, index += channels) {
            dsn_internal_continuous_point(noise, point_x, point_y, pixel);
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

size_t dsn_continuous_tile_scratch_size(const dsn_noise *handle, const dsn_grid *grid, uint32_t width,
                                        uint32_t height) {
    const dsn_noise_state *noise = dsn_state(handle);
#if DSN_SMALL_CODE
    (void)noise, (void)grid, (void)width, (void)height;
    return 0; /* point by point: no scratch */
#else
    SplatAxis x, y;
    if (check_tile(noise, grid, width, height, grid) != DSN_OK) return 0;
    return splat_axes(noise, grid, width, height, &x, &y) ? splat_scratch_size(noise, width, height) : 0;
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
