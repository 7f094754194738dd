/* runtime/evaluators/lattice_gradient.cpp - the lattice noise with its forward differences (dsn.h,
   "Gradients"): the sums of a block of points and of the points one step right and below it, splatted by the
   lattice tile's 32-bit path (tile_walk.h), then differenced and normalized as the value (the differences
   without the mean), per tile; per point the same from three walks of the point's own (a block of one in the
   small build). */
#include "core/gradient_output.h"

#if DSN_GRADIENTS
#include "core/lattice_internal.h"
#include "kernels/tile_walk.h" /* its functions are defined where included: only where they are used */

namespace {

/* Blocks of a gradient tile: their sums, one more column and row, stay on the stack (about 7 KB). */
const uint32_t block_width = 32, block_height = 16;

/* The sums of the (width + 1) x (height + 1) points from (x0, y0) (coordinates modulo 2^32, as a lattice
   tile's pixels: the point right of x is x + 1 even where a period's reduction cuts the run at INT32_MAX,
   split_runs), into `sums`, row-major, channels interleaved. */
void extended_sums(const dsn_noise_state *lattice, uint32_t x0, uint32_t y0, uint32_t width, uint32_t height,
                   uint32_t *sums) {
    const uint32_t channels = lattice->asset.channels, row_stride = (width + 1u) * channels;
    for (uint32_t i = 0; i < row_stride * (height + 1u); i++) sums[i] = 0;
    tile_run runs_x[2], runs_y[2];
    const uint32_t count_x = split_runs(x0, width + 1u, lattice->period[0], runs_x);
    const uint32_t count_y = split_runs(y0, height + 1u, lattice->period[1], runs_y);
    for (uint32_t j = 0; j < count_y; j++)
        for (uint32_t i = 0; i < count_x; i++)
            splat_region(lattice, &runs_x[i], &runs_y[j], sums, row_stride);
}

/* A block of width x height points (at most block_width x block_height) from (x0, y0): each point's
   value and differences, normalized (values[0 .. 2]: value, dx, dy, DSN_MAX_CHANNELS apart), to store(). */
template <typename Store>
void gradient_block(const dsn_noise_state *noise, const dsn_noise_state *lattice, uint32_t x0, uint32_t y0,
                    uint32_t width, uint32_t height, Store &store) {
    uint32_t sums[(block_width + 1) * (block_height + 1) * DSN_MAX_CHANNELS];
    extended_sums(lattice, x0, y0, width, height, sums);
    const uint32_t channels = noise->asset.channels, row_stride = (width + 1u) * channels;
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            const uint32_t *here = sums + j * row_stride + i * channels;
            uint32_t differences[2][DSN_MAX_CHANNELS] = {{0, 0, 0}, {0, 0, 0}};
            for (uint32_t c = 0; c < channels; c++) {
                differences[0][c] = here[channels + c] - here[c];
                differences[1][c] = here[row_stride + c] - here[c];
            }
            int32_t values[3 * DSN_MAX_CHANNELS];
            dsn_normalize_from(noise, noise->offset, here, values);
            dsn_normalize_from(noise, dsn_no_offset, differences[0], values + DSN_MAX_CHANNELS);
            dsn_normalize_from(noise, dsn_no_offset, differences[1], values + 2 * DSN_MAX_CHANNELS);
            dsn_map_gradient(noise, values, values + DSN_MAX_CHANNELS, values + 2 * DSN_MAX_CHANNELS);
            store(i, j, values);
        }
}

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

/* Stores a block's points at their place in a tile of `tile_width` points, as `kind`. */
struct TileStore {
    void *out, *dx, *dy;
    dsn_output_kind kind;
    uint32_t channels, tile_width, left, top;

    void operator()(uint32_t i, uint32_t j, const int32_t *values) const {
        const size_t first = (static_cast<size_t>(top + j) * tile_width + left + i) * channels;
        dsn_store_gradient(out, dx, dy, kind, first, values, channels);
    }
};

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
    TileStore store = {out, dx, dy, kind, noise->asset.channels, width, 0, 0};
    for (store.top = 0; store.top < height; store.top += block_height)
        for (store.left = 0; store.left < width; store.left += block_width) {
            const uint32_t block_w = width - store.left < block_width ? width - store.left : block_width;
            const uint32_t block_h = height - store.top < block_height ? height - store.top : block_height;
            gradient_block(noise, lattice, static_cast<uint32_t>(x0) + store.left,
                           static_cast<uint32_t>(y0) + store.top, block_w, block_h, store);
        }
    return DSN_OK;
}

/* A point: in the small build a tile of one; else the per-point walk's sums at the point and its two
   neighbours (three fast walks cost less than one through the tile's general path). */
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
    const uint32_t px = static_cast<uint32_t>(x), py = static_cast<uint32_t>(y);
    uint32_t here[DSN_MAX_CHANNELS] = {0, 0, 0}, east[DSN_MAX_CHANNELS] = {0, 0, 0},
             south[DSN_MAX_CHANNELS] = {0, 0, 0};
    dsn_internal_lattice_sums(noise, px, py, here);
    dsn_internal_lattice_sums(noise, px + 1u, py, east);
    dsn_internal_lattice_sums(noise, px, py + 1u, south);
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) {
        east[c] -= here[c];
        south[c] -= here[c];
    }
    int32_t values[3 * DSN_MAX_CHANNELS];
    dsn_normalize_from(noise, noise->offset, here, values);
    dsn_normalize_from(noise, dsn_no_offset, east, values + DSN_MAX_CHANNELS);
    dsn_normalize_from(noise, dsn_no_offset, south, values + 2 * DSN_MAX_CHANNELS);
    dsn_map_gradient(noise, values, values + DSN_MAX_CHANNELS, values + 2 * DSN_MAX_CHANNELS);
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
