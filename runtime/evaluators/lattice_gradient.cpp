/* runtime/evaluators/lattice_gradient.cpp - the lattice noise with its forward differences (dsn.h,
   "Gradients"): per tile the kernel's lattice tile with its differences (tile_gradient.h); per point the
   sums of the point's own walk at the point and one step right and below it, differenced and
   normalized as the value (the differences without the mean); a tile of one in the small build. */
#include "core/gradient_output.h"

#if DSN_GRADIENTS
#include "core/lattice_internal.h"
#include "kernels/kernels.h"

namespace {

/* The noise the lattice evaluators read (its lattice texton, format 1.3), or an error. */
int lattice_noise(const dsn_noise_state *noise, dsn_noise_state *view, const dsn_noise_state **lattice) {
#if DSN_READS_SECTIONS
    *lattice = dsn_internal_lattice_view(noise, view);
#else
    (void)view;
    if (dsn_lattice_texton_unread(noise)) return DSN_ERR_UNSUPPORTED;
    *lattice = noise;
#endif
    return DSN_OK;
}

int check_noise(const dsn_noise_state *noise, const void *out, const void *dx, const void *dy) {
    if (out == 0 || dx == 0 || dy == 0 || !dsn_configured(noise)) return DSN_ERR_NULL;
    return DSN_OK;
}

/* Pixel (i, j) of a tile is the point (x0 + i, y0 + j) modulo 2^32, as a lattice tile's; a point is a
   tile of one. */
int tile_of_kind(const dsn_noise *handle, int32_t x0, int32_t y0, uint32_t width, uint32_t height, void *out,
                 void *dx, void *dy, dsn_output_kind kind) {
    const dsn_noise_state *noise = dsn_state(handle);
    int err = check_noise(noise, out, dx, dy);
    if (err == DSN_OK &&
        (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE))
        err = DSN_ERR_TILE_SIZE;
    dsn_noise_state view;
    const dsn_noise_state *lattice = noise;
    if (err == DSN_OK) err = lattice_noise(noise, &view, &lattice);
    if (err != DSN_OK)
        return dsn_gradient_error(err, noise, out, dx, dy, kind, static_cast<size_t>(width) * height);
    dsn_kernel_entries_of(noise->tile_kernel)
        ->lattice_tile(lattice, static_cast<uint32_t>(x0), static_cast<uint32_t>(y0), width, height, out, dx,
                       dy, kind, 0, 0);
    return DSN_OK;
}

/* A point: in the small build a tile of one; else the per-point walk's sums at the point and its two
   neighbours (one walk of the fast path costs less than one through the tile's general path). */
int point_of_kind(const dsn_noise *handle, int32_t x, int32_t y, void *out, void *dx, void *dy,
                  dsn_output_kind kind) {
#if DSN_SMALL_CODE
    return tile_of_kind(handle, x, y, 1, 1, out, dx, dy, kind);
#else
    const dsn_noise_state *noise = dsn_state(handle);
    int err = check_noise(noise, out, dx, dy);
#if !DSN_READS_SECTIONS
    if (err == DSN_OK && dsn_lattice_texton_unread(noise)) err = DSN_ERR_UNSUPPORTED;
#endif
    if (err != DSN_OK) return dsn_gradient_error(err, noise, out, dx, dy, kind, 1);
    uint32_t sums[3 * DSN_MAX_CHANNELS];
    dsn_internal_lattice_neighbour_sums(noise, static_cast<uint32_t>(x), static_cast<uint32_t>(y), sums);
    int32_t values[3 * DSN_MAX_CHANNELS];
    dsn_lattice_gradient_values(noise, sums, sums + DSN_MAX_CHANNELS, sums + 2 * DSN_MAX_CHANNELS, values);
    dsn_store_gradient(out, dx, dy, kind, 0, values, noise->asset.channels);
    return DSN_OK;
#endif
}

} // namespace

extern "C" {

int dsn_lattice_gradient_fixed(const dsn_noise *noise, int32_t x, int32_t y, int32_t *out, int32_t *dx,
                               int32_t *dy) {
    return point_of_kind(noise, x, y, out, dx, dy, dsn_output_fixed);
}

int dsn_lattice_gradient_float(const dsn_noise *noise, int32_t x, int32_t y, float *out, float *dx,
                               float *dy) {
    return point_of_kind(noise, x, y, out, dx, dy, dsn_output_float);
}

int dsn_lattice_tile_gradient_fixed(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width,
                                    uint32_t height, int32_t *out, int32_t *dx, int32_t *dy) {
    return tile_of_kind(noise, x0, y0, width, height, out, dx, dy, dsn_output_fixed);
}

int dsn_lattice_tile_gradient_float(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width,
                                    uint32_t height, float *out, float *dx, float *dy) {
    return tile_of_kind(noise, x0, y0, width, height, out, dx, dy, dsn_output_float);
}

} // extern "C"

#endif /* DSN_GRADIENTS */
