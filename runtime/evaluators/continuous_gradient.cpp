/* runtime/evaluators/continuous_gradient.cpp - the continuous noise with its exact derivative (dsn.h,
   "Gradients"): the sums of the sifting walk's slope reader (continuous_point.cpp) normalized, the value as
   the value, the slopes per texel without the mean; per point, grid tile and batch, fixed and float. */
#include "core/continuous_internal.h"
#include "core/gradient_output.h"
#include "kernels/kernels.h"

#if DSN_GRADIENTS

void dsn_internal_continuous_gradient(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *values) {
    uint64_t value[DSN_MAX_CHANNELS], slope_x[DSN_MAX_CHANNELS], slope_y[DSN_MAX_CHANNELS];
    dsn_internal_continuous_slopes(noise, x, y, value, slope_x, slope_y);
    /* A slope is per 2^-16 texel: times 2^16 it is per texel, with the value sums' 32 fraction bits
       (modulo 2^64, as they are). */
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) {
        slope_x[c] <<= 16;
        slope_y[c] <<= 16;
    }
    normalize_q32_unmapped(noise, value, values);
    normalize_q32_from(noise, dsn_no_offset, slope_x, values + DSN_MAX_CHANNELS);
    normalize_q32_from(noise, dsn_no_offset, slope_y, values + 2 * DSN_MAX_CHANNELS);
    dsn_map_gradient(noise, values, values + DSN_MAX_CHANNELS, values + 2 * DSN_MAX_CHANNELS);
}

namespace {

int check_call(const dsn_noise_state *noise, const void *out, const void *dx, const void *dy) {
    const int err = dsn_internal_continuous_check(noise);
    if (err != DSN_OK) return err;
    return out == 0 || dx == 0 || dy == 0 ? DSN_ERR_NULL : DSN_OK;
}

int point_of_kind(const dsn_noise *handle, int64_t x, int64_t y, void *out, void *dx, void *dy,
                  dsn_output_kind kind) {
    const dsn_noise_state *noise = dsn_state(handle);
    const int err = check_call(noise, out, dx, dy);
    if (err != DSN_OK) return dsn_gradient_error(err, noise, out, dx, dy, kind, 1);
    int32_t values[3 * DSN_MAX_CHANNELS];
    dsn_internal_continuous_gradient(noise, static_cast<uint64_t>(x), static_cast<uint64_t>(y), values);
    dsn_store_gradient(out, dx, dy, kind, 0, values, noise->asset.channels);
    return DSN_OK;
}

/* The continuous gradient at a point of a grid. */
struct ContinuousPoint {
    const dsn_noise_state *noise;
    void operator()(uint64_t x, uint64_t y, int32_t *values) const {
        dsn_internal_continuous_gradient(noise, x, y, values);
    }
};

int tile_of_kind(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height, void *out,
                 void *dx, void *dy, dsn_output_kind kind) {
    const dsn_noise_state *noise = dsn_state(handle);
    int err = check_call(noise, out, dx, dy);
    if (err == DSN_OK && grid == 0) err = DSN_ERR_NULL;
    if (err == DSN_OK &&
        dsn_internal_continuous_gradient_splat(noise, grid, width, height, out, dx, dy, kind))
        return DSN_OK;
    const ContinuousPoint point = {noise};
    return dsn_gradient_grid(err, noise, grid, width, height, out, dx, dy, kind, point);
}

/* The batch kernel's gradients of the whole batch at once where nothing is converted (Q32.32 coordinates,
   fixed output); 0 otherwise. */
int whole_batch(dsn_continuous_batch_entry *batch, const dsn_noise_state *noise, const int64_t *xs,
                const int64_t *ys, uint32_t count, void *out, void *dx, void *dy, dsn_output_kind kind) {
    if (batch == 0 || kind != dsn_output_fixed) return 0;
    batch(noise, 0, xs, ys, count, static_cast<int32_t *>(out), static_cast<int32_t *>(dx),
          static_cast<int32_t *>(dy), 0);
    return 1;
}
int whole_batch(dsn_continuous_batch_entry *, const dsn_noise_state *, const double *, const double *,
                uint32_t, void *, void *, void *, dsn_output_kind) {
    return 0;
}

const uint32_t batch_chunk = 32; /* points converted and stored at a time (2.5 KB of stack) */

/* Point k is (xs[k], ys[k]); Coordinate is int64_t (Q32.32) or double. A chunk at a time through the
   batch kernel (kernels.h), else point by point (builds without batches). */
template <typename Coordinate>
int batch_of_kind(const dsn_noise *handle, const Coordinate *xs, const Coordinate *ys, uint32_t count,
                  void *out, void *dx, void *dy, dsn_output_kind kind) {
    const dsn_noise_state *noise = dsn_state(handle);
    int err = dsn_internal_continuous_check(noise);
    if (err == DSN_OK && count != 0 && (xs == 0 || ys == 0 || out == 0 || dx == 0 || dy == 0))
        err = DSN_ERR_NULL;
    if (err != DSN_OK) return dsn_gradient_error(err, noise, out, dx, dy, kind, count);
    dsn_continuous_batch_entry *batch = dsn_kernel_entries_of(noise->tile_kernel)->continuous_batch;
    const uint32_t channels = noise->asset.channels;
    if (whole_batch(batch, noise, xs, ys, count, out, dx, dy, kind)) return DSN_OK;
    int64_t chunk_x[batch_chunk], chunk_y[batch_chunk];
    int32_t fixed[3][batch_chunk * DSN_MAX_CHANNELS], values[3 * DSN_MAX_CHANNELS];
    for (uint32_t first = 0; first < count; first += batch_chunk) {
        const uint32_t points = count - first < batch_chunk ? count - first : batch_chunk;
        const int64_t *point_xs = dsn_chunk_coordinates(xs, first, points, chunk_x);
        const int64_t *point_ys = dsn_chunk_coordinates(ys, first, points, chunk_y);
        if (batch != 0) batch(noise, 0, point_xs, point_ys, points, fixed[0], fixed[1], fixed[2], 0);
        for (uint32_t k = 0; k < points; k++) {
            if (batch == 0)
                dsn_internal_continuous_gradient(noise, static_cast<uint64_t>(point_xs[k]),
                                                 static_cast<uint64_t>(point_ys[k]), values);
            else
                for (uint32_t c = 0; c < channels; c++)
                    for (uint32_t part = 0; part < 3; part++)
                        values[part * DSN_MAX_CHANNELS + c] = fixed[part][k * channels + c];
            dsn_store_gradient(out, dx, dy, kind, static_cast<size_t>(first + k) * channels, values,
                               channels);
        }
    }
    return DSN_OK;
}

} // namespace

extern "C" {

int dsn_continuous_gradient_fixed(const dsn_noise *noise, int64_t x, int64_t y, int32_t *out, int32_t *dx,
                                  int32_t *dy) {
    return point_of_kind(noise, x, y, out, dx, dy, dsn_output_fixed);
}

int dsn_continuous_gradient_float(const dsn_noise *noise, double x, double y, float *out, float *dx,
                                  float *dy) {
    return point_of_kind(noise, dsn_coordinate_from_double(x), dsn_coordinate_from_double(y), out, dx, dy,
                         dsn_output_float);
}

int dsn_sample_gradient(const dsn_noise *noise, float x, float y, float *out, float *dx, float *dy) {
    return dsn_continuous_gradient_float(noise, x, y, out, dx, dy);
}

int dsn_continuous_tile_gradient_fixed(const dsn_noise *noise, const dsn_grid *grid, uint32_t width,
                                       uint32_t height, int32_t *out, int32_t *dx, int32_t *dy) {
    return tile_of_kind(noise, grid, width, height, out, dx, dy, dsn_output_fixed);
}

int dsn_continuous_tile_gradient_float(const dsn_noise *noise, const dsn_grid *grid, uint32_t width,
                                       uint32_t height, float *out, float *dx, float *dy) {
    return tile_of_kind(noise, grid, width, height, out, dx, dy, dsn_output_float);
}

int dsn_continuous_batch_gradient_fixed(const dsn_noise *noise, const int64_t *xs, const int64_t *ys,
                                        uint32_t count, int32_t *out, int32_t *dx, int32_t *dy) {
    return batch_of_kind(noise, xs, ys, count, out, dx, dy, dsn_output_fixed);
}

int dsn_continuous_batch_gradient_float(const dsn_noise *noise, const double *xs, const double *ys,
                                        uint32_t count, float *out, float *dx, float *dy) {
    return batch_of_kind(noise, xs, ys, count, out, dx, dy, dsn_output_float);
}

} // extern "C"

#endif /* DSN_GRADIENTS */
