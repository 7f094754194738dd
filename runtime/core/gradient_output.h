/* runtime/core/gradient_output.h - what every gradient function does with a point's normalized value and
   derivatives (dsn.h, "Gradients"): the histogram mapping's chain rule, the float conversion, and the
   zeroing of the three outputs on an error. Internal to libdsn; not installed. */
#ifndef DSN_GRADIENT_OUTPUT_H
#define DSN_GRADIENT_OUTPUT_H

#include <stddef.h>
#include <stdint.h>

#include "core/error_output.h"
#include "core/grid_points.h"
#include "core/histogram_map.h"
#include "core/normalize_fixed.h"

#if DSN_GRADIENTS

/* Zeros and no mean: the offset of a derivative's normalization. */
static const int64_t dsn_no_offset[DSN_MAX_CHANNELS] = {0, 0, 0};

/* The value (Gaussian-space, before the mapping) and its derivatives to the outputs: with a histogram
   mapping, the chain rule at the unmapped value, then the value mapped. */
static inline void dsn_map_gradient(const dsn_noise_state *noise, int32_t *value, int32_t *dx, int32_t *dy) {
#if DSN_HISTOGRAM
    if (noise->asset.histogram_table != 0) {
        dsn_internal_histogram_map_gradient(&noise->asset, value, 0, 0, dx, dy);
        dsn_internal_histogram_map(&noise->asset, value, 0, 0);
    }
#else
    (void)noise, (void)value, (void)dx, (void)dy;
#endif
}

/* A lattice point's value and forward differences (values[0 .. 2]: value, dx, dy, DSN_MAX_CHANNELS apart)
   from its sums and those of the points right of it and below it (modulo 2^32): the differences normalized
   as the value without the mean, then the mapping's chain rule. */
static inline void dsn_lattice_gradient_values(const dsn_noise_state *noise, const uint32_t *here,
                                               const uint32_t *east, const uint32_t *south, int32_t *values) {
    uint32_t differences[2][DSN_MAX_CHANNELS] = {{0, 0, 0}, {0, 0, 0}};
    for (uint32_t c = 0; c < noise->asset.channels; c++) {
        differences[0][c] = east[c] - here[c];
        differences[1][c] = south[c] - here[c];
    }
    dsn_normalize_from(noise, noise->offset, here, values);
    dsn_normalize_from(noise, dsn_no_offset, differences[0], values + DSN_MAX_CHANNELS);
    dsn_normalize_from(noise, dsn_no_offset, differences[1], values + 2 * DSN_MAX_CHANNELS);
    dsn_map_gradient(noise, values, values + DSN_MAX_CHANNELS, values + 2 * DSN_MAX_CHANNELS);
}

/* A gradient call's error `err`, after zeroing its three outputs (error_output.h: `points` points each). */
static inline int dsn_gradient_error(int err, const dsn_noise_state *noise, void *out, void *dx, void *dy,
                                     dsn_output_kind kind, size_t points) {
    dsn_output_error(err, noise, out, kind, points);
    dsn_output_error(err, noise, dx, kind, points);
    return dsn_output_error(err, noise, dy, kind, points);
}

/* The fixed-point results of one point stored as the call's type at value index `first`. */
static inline void dsn_store_gradient(void *out, void *dx, void *dy, dsn_output_kind kind, size_t first,
                                      const int32_t *values, uint32_t channels) {
    dsn_store_pixel(out, kind, first, values, channels);
    dsn_store_pixel(dx, kind, first, values + DSN_MAX_CHANNELS, channels);
    dsn_store_pixel(dy, kind, first, values + 2 * DSN_MAX_CHANNELS, channels);
}

/* A grid point's gradient from point(x, y, values) (value, dx, dy, DSN_MAX_CHANNELS apart), stored as
   `kind` at value `index` of the three outputs. */
template <typename Point>
struct DsnGradientPixel {
    const Point &point;
    void *out, *dx, *dy;
    dsn_output_kind kind;
    uint32_t channels;
    void operator()(size_t index, uint64_t x, uint64_t y) const {
        int32_t values[3 * DSN_MAX_CHANNELS];
        point(x, y, values);
        dsn_store_gradient(out, dx, dy, kind, index, values, channels);
    }
};

/* A gradient tile over a grid (dsn.h's dsn_grid): the tile size checked, then its points in order
   (grid_points.h). `err` is the call's checks so far. */
template <typename Point>
int dsn_gradient_grid(int err, const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width,
                      uint32_t height, void *out, void *dx, void *dy, dsn_output_kind kind,
                      const Point &point) {
    if (err == DSN_OK &&
        (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE))
        err = DSN_ERR_TILE_SIZE;
    if (err != DSN_OK)
        return dsn_gradient_error(err, noise, out, dx, dy, kind, static_cast<size_t>(width) * height);
    const DsnGradientPixel<Point> pixel = {point, out, dx, dy, kind, noise->asset.channels};
    dsn_grid_points(grid, width, height, noise->asset.channels, pixel);
    return DSN_OK;
}

#endif /* DSN_GRADIENTS */

#endif /* DSN_GRADIENT_OUTPUT_H */
