/* runtime/lattice_gradient.cpp - the lattice noise with its forward differences (dsn.h, "Gradients"): the
   sums at a point and at its neighbours toward +x and +y in one walk over the impulses that reach the
   three, normalized as the value (the differences without the mean); per point and per tile. */
#include "cell_walk.h"
#include "gradient_output.h"
#include "impulse_position.h"
#include "poisson_count.h"

#if DSN_GRADIENTS

namespace {

/* The sums the gradient needs: at the point, at the point + (1, 0), at the point + (0, 1). */
enum { at_point = 0, at_east = 1, at_south = 2 };

/* Texton value (row, column, channel) of the walk's texton, 0 outside its window (unsigned indices: -1 is
   outside too), as a uint32 (the sums wrap modulo 2^32). */
inline uint32_t texel_or_zero(const dsn_asset *asset, const dsn_texton_window *texton, uint32_t row,
                              uint32_t column, uint32_t channel) {
    if (row >= texton->height || column >= texton->width) return 0;
    const uint32_t index = (row * texton->width + column) * asset->channels + channel;
    const int32_t value =
        asset->bits == 8 ? dsn_read_i8(texton->values + index) : dsn_read_i16le(texton->values + 2u * index);
    return static_cast<uint32_t>(value);
}

/* The walk's view of one cell along one axis, as point.cpp's: the texton index of an impulse at in-cell
   offset 0 for window index 0, and the last in-cell offset the period keeps. */
struct CellReach {
    uint32_t reach, last_offset;
};

inline CellReach cell_reach(const dsn_span *span, uint32_t cell, uint32_t shift) {
    const uint32_t origin = cell << shift, room = span->last_position - origin;
    const CellReach result = {span->base - origin, room < (1u << shift) - 1u ? room : (1u << shift) - 1u};
    return result;
}

/* Adds every impulse of the cell `key` to the sums of the window: the point always, the east neighbour
   when `east` (the x window is 2 long), the south one when `south`. */
void add_cell(const dsn_noise_state *noise, const dsn_texton_window *texton, uint32_t key, const CellReach &x,
              const CellReach &y, bool east, bool south, uint32_t sums[3][DSN_MAX_CHANNELS]) {
    const uint32_t count = dsn_cell_impulse_count(noise, key), channels = noise->asset.channels;
    const uint32_t half_bits = 1u << (dsn_field_shift(noise->cell_shift) - 1u);
    const uint32_t drop = half_bits - noise->cell_shift, half_mask = (1u << half_bits) - 1u;
    for (uint32_t k = 0; k < count; k++) {
        const uint32_t field = dsn_impulse_field(noise, key, k);
        const uint32_t offset_x = (field & half_mask) >> drop,
                       offset_y = ((field >> half_bits) & half_mask) >> drop;
        const uint32_t column = x.reach - offset_x, row = y.reach - offset_y;
        /* in reach of some point of the window: column (or row) in [-1, size - 1] */
        if (offset_x > x.last_offset || offset_y > y.last_offset || column + 1u > texton->width ||
            row + 1u > texton->height)
            continue;
        for (uint32_t c = 0; c < channels; c++) {
            sums[at_point][c] += texel_or_zero(&noise->asset, texton, row, column, c);
            if (east) sums[at_east][c] += texel_or_zero(&noise->asset, texton, row, column + 1u, c);
            if (south) sums[at_south][c] += texel_or_zero(&noise->asset, texton, row + 1u, column, c);
        }
    }
}

/* One walk over the cells that reach the window of (x, y) and, when asked, its east and south
   neighbours (cell_walk.h's windows of length 2). */
void walk(const dsn_noise_state *noise, const dsn_texton_window *texton, uint32_t x, uint32_t y, bool east,
          bool south, uint32_t sums[3][DSN_MAX_CHANNELS]) {
    const uint32_t shift = noise->cell_shift;
    dsn_axis axis_x, axis_y;
    dsn_axis_init(&axis_x, x, east ? 2u : 1u, texton->radius[0], shift, noise->period[0]);
    dsn_axis_init(&axis_y, y, south ? 2u : 1u, texton->radius[1], shift, noise->period[1]);
    for (uint32_t span_index_y = 0; span_index_y < axis_y.span_count; span_index_y++) {
        const dsn_span span_y = dsn_axis_span(&axis_y, span_index_y);
        for (uint32_t j = 0; j < span_y.cell_count; j++) {
            const uint32_t cell_y = dsn_span_cell(&span_y, j, shift), row_key = dsn_row_key(noise, cell_y);
            const CellReach in_y = cell_reach(&span_y, cell_y, shift);
            for (uint32_t span_index_x = 0; span_index_x < axis_x.span_count; span_index_x++) {
                const dsn_span span_x = dsn_axis_span(&axis_x, span_index_x);
                for (uint32_t i = 0; i < span_x.cell_count; i++) {
                    const uint32_t cell_x = dsn_span_cell(&span_x, i, shift);
                    add_cell(noise, texton, dsn_cell_key_in_row(noise, cell_x, row_key),
                             cell_reach(&span_x, cell_x, shift), in_y, east, south, sums);
                }
            }
        }
    }
}

/* The sums at (x, y), (x + 1, y) and (x, y + 1), coordinates modulo 2^32. A periodic axis reduces each
   coordinate on its own (cell_walk.h), so where + 1 leaves the int32 range (0x7FFFFFFF + 1 is -2^31) the
   neighbour is not the next point of the reduced window: it gets a walk of its own. */
void neighbour_sums(const dsn_noise_state *noise, const dsn_texton_window *texton, uint32_t x, uint32_t y,
                    uint32_t sums[3][DSN_MAX_CHANNELS]) {
    const bool east_apart = noise->period[0] != 0 && x == 0x7FFFFFFFu;
    const bool south_apart = noise->period[1] != 0 && y == 0x7FFFFFFFu;
    walk(noise, texton, x, y, !east_apart, !south_apart, sums);
    uint32_t apart[3][DSN_MAX_CHANNELS];
    for (uint32_t neighbour = at_east; neighbour <= at_south; neighbour++) {
        if (neighbour == at_east ? !east_apart : !south_apart) continue;
        for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) apart[at_point][c] = 0;
        walk(noise, texton, neighbour == at_east ? x + 1u : x, neighbour == at_south ? y + 1u : y, false,
             false, apart);
        for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) sums[neighbour][c] = apart[at_point][c];
    }
}

/* values[0 .. 2]: the point's value, then its dx, then its dy (DSN_MAX_CHANNELS apart). */
int gradient_point(const dsn_noise_state *noise, uint32_t x, uint32_t y, int32_t *values) {
#if !DSN_READS_SECTIONS
    if (dsn_lattice_texton_unread(noise)) return DSN_ERR_UNSUPPORTED;
#endif
    const dsn_texton_window texton = dsn_lattice_texton_window(noise);
    uint32_t sums[3][DSN_MAX_CHANNELS] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    neighbour_sums(noise, &texton, x, y, sums);
    uint32_t differences[2][DSN_MAX_CHANNELS];
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) {
        differences[0][c] = sums[at_east][c] - sums[at_point][c];
        differences[1][c] = sums[at_south][c] - sums[at_point][c];
    }
    dsn_normalize_from(noise, noise->offset, sums[at_point], values);
    dsn_normalize_from(noise, dsn_no_offset, differences[0], values + DSN_MAX_CHANNELS);
    dsn_normalize_from(noise, dsn_no_offset, differences[1], values + 2 * DSN_MAX_CHANNELS);
    dsn_map_gradient(noise, values, values + DSN_MAX_CHANNELS, values + 2 * DSN_MAX_CHANNELS);
    return DSN_OK;
}

int check_noise(const dsn_noise_state *noise, const void *out, const void *dx, const void *dy) {
    if (out == 0 || dx == 0 || dy == 0 || !dsn_configured(noise)) return DSN_ERR_NULL;
    return DSN_OK;
}

int point_of_kind(const dsn_noise *handle, int32_t x, int32_t y, void *out, void *dx, void *dy,
                  dsn_output_kind kind) {
    const dsn_noise_state *noise = dsn_state(handle);
    int32_t values[3 * DSN_MAX_CHANNELS];
    int err = check_noise(noise, out, dx, dy);
    if (err == DSN_OK)
        err = gradient_point(noise, static_cast<uint32_t>(x), static_cast<uint32_t>(y), values);
    if (err != DSN_OK) return dsn_gradient_error(err, noise, out, dx, dy, kind, 1);
    dsn_store_gradient(out, dx, dy, kind, 0, values, noise->asset.channels);
    return DSN_OK;
}

/* Pixel (i, j) is the point (x0 + i, y0 + j) modulo 2^32, as a lattice tile's. */
int tile_of_kind(const dsn_noise *handle, int32_t x0, int32_t y0, uint32_t width, uint32_t height, void *out,
                 void *dx, void *dy, dsn_output_kind kind) {
    const dsn_noise_state *noise = dsn_state(handle);
    int err = check_noise(noise, out, dx, dy);
    if (err == DSN_OK &&
        (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE))
        err = DSN_ERR_TILE_SIZE;
    const size_t points = static_cast<size_t>(width) * height;
    if (err != DSN_OK) return dsn_gradient_error(err, noise, out, dx, dy, kind, points);
    const uint32_t channels = noise->asset.channels;
    int32_t values[3 * DSN_MAX_CHANNELS];
    for (uint32_t j = 0; j < height; j++) {
        for (uint32_t i = 0; i < width; i++) {
            err = gradient_point(noise, static_cast<uint32_t>(x0) + i, static_cast<uint32_t>(y0) + j, values);
            if (err != DSN_OK) return dsn_gradient_error(err, noise, out, dx, dy, kind, points);
            dsn_store_gradient(out, dx, dy, kind, (static_cast<size_t>(j) * width + i) * channels, values,
                               channels);
        }
    }
    return DSN_OK;
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
