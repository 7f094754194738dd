/* golden.cpp - the cross test's golden program: evaluates the runtime on the fixed assets and prints one
   FNV-1a 64 hash per (kind of output, asset), plus one per kind over all assets.

   Every target (compiler, optimization level, CPU, endianness, microcontroller) must print the same
   lines as tests/cross/golden.txt. Values are hashed as little-endian bytes whatever the host, float32
   outputs as their IEEE bits. The program allocates nothing and prints through golden_write() only, so
   it runs unchanged on a bare-metal Cortex-M. A new kind of output (the continuous mode, say) is one
   function and one line in `kinds` below. */
#include <stdint.h>
#include <string.h>

#include "dsn/dsn.h"
#include "golden_assets.h"
#include "golden_output.h"

namespace {

struct Fnv {
    uint64_t state;
};

const uint64_t fnv_offset_basis = 0xCBF29CE484222325ull;
const uint64_t fnv_prime = 0x100000001B3ull;

void hash_byte(Fnv *hash, uint32_t byte) { hash->state = (hash->state ^ (byte & 0xFFu)) * fnv_prime; }

void hash_u32(Fnv *hash, uint32_t value) {
    for (uint32_t shift = 0; shift < 32; shift += 8) hash_byte(hash, value >> shift);
}

void hash_u64(Fnv *hash, uint64_t value) {
    hash_u32(hash, static_cast<uint32_t>(value));
    hash_u32(hash, static_cast<uint32_t>(value >> 32));
}

void hash_fixed(Fnv *hash, const int32_t *values, uint32_t count) {
    for (uint32_t i = 0; i < count; i++) hash_u32(hash, static_cast<uint32_t>(values[i]));
}

void hash_float(Fnv *hash, const float *values, uint32_t count) {
    for (uint32_t i = 0; i < count; i++) {
        uint32_t bits;
        memcpy(&bits, &values[i], sizeof bits);
        hash_u32(hash, bits);
    }
}

void hash_u8(Fnv *hash, const uint8_t *values, uint32_t count) {
    for (uint32_t i = 0; i < count; i++) hash_byte(hash, values[i]);
}

/* A tile of the lattice; the additions x + i and y + j wrap modulo 2^32 like the runtime's. */
struct Window {
    int32_t x, y;
    uint32_t width, height;
};

int32_t wrapped(int32_t origin, uint32_t step) {
    const uint32_t sum = static_cast<uint32_t>(origin) + step;
    return sum >= 0x80000000u ? -static_cast<int32_t>(~sum) - 1 : static_cast<int32_t>(sum);
}

/* Ordinary points, the sign change at 0, both int32 ends and the 32-bit wrap, far cells, a larger tile. */
const Window lattice_windows[] = {
    {0, 0, 6, 5},
    {-3, -2, 5, 4},
    {INT32_MAX - 2, INT32_MAX - 1, 5, 4}, /* wraps to INT32_MIN on both axes */
    {INT32_MIN, INT32_MAX, 4, 3},         /* x at the low end, y wraps */
    {1234567891, -987654321, 4, 4},
    {-100, 50, 32, 16}, /* a larger tile: many impulses cross its inner cell borders */
};

/* Tileable windows span more than one period, around 0 and across the wrap. */
const Window tileable_windows[] = {
    {-5, -3, 20, 6},
    {INT32_MAX - 3, INT32_MIN + 9, 8, 3},
};

struct Setting {
    uint32_t seed, impacts_q16, period_x, period_y, flags;
};

/* Seeds at 0, the top of the range and in between; densities from the minimum to 100 per pixel. */
const Setting lattice_settings[] = {
    {0u, 0u, 0u, 0u, 0u},
    {1234567u, DSN_IMPACTS_MIN_Q16, 0u, 0u, 0u},
    {0xFFFFFFFFu, (30u << 16) + (1u << 15), 0u, 0u, 0u},
    {0x9E3779B9u, 100u << 16, 0u, 0u, DSN_FLAG_NO_COLOR_TRANSFORM},
};

/* A power of two, an odd period that is no multiple of any cell size, and the degenerate period 1. */
const Setting tileable_settings[] = {
    {77u, 0u, 16u, 8u, 0u},
    {0xFFFFFFFFu, 9u << 16, 13u, 0u, 0u},
    {3u, 0u, 1u, 7u, 0u},
};

/* The continuous mode also on the lattice-baked assets, and with a period. */
const uint32_t lattice_continuous = DSN_FLAG_ALLOW_LATTICE_CONTINUOUS;
const Setting continuous_settings[] = {
    {0u, 0u, 0u, 0u, lattice_continuous},
    {0xFFFFFFFFu, (30u << 16) + (1u << 15), 0u, 0u, lattice_continuous},
    {0x9E3779B9u, 100u << 16, 0u, 0u, lattice_continuous | DSN_FLAG_NO_COLOR_TRANSFORM},
    {5u, DSN_IMPACTS_MIN_Q16, 16u, 13u, lattice_continuous},
};

/* A continuous window: a grid of Q32.32 points (dsn_grid) and its size. */
struct Grid {
    dsn_grid grid;
    uint32_t width, height;
};

const int64_t q32_one = INT64_C(1) << 32;

/* A zoom, a rotation by 30 degrees across both 32-bit wraps, a minification with shear, a tiny step
   across 0 (16-bit sub-texel positions) and a larger slightly rotated tile. Steps are Q32.32: 1288490189 is
   0.3, 3719550787 is cos 30. */
const Grid continuous_grids[] = {
    {{-3 * q32_one - q32_one / 4, 7 * q32_one + q32_one / 2, 1288490189, 0, 0, 1288490189}, 6, 5},
    {{INT64_MAX - q32_one / 2, INT64_MIN + 123, 3719550787, -2147483648, 2147483648, 3719550787}, 5, 4},
    {{0, -5 * q32_one, 11 * q32_one / 4, -9 * q32_one / 8, q32_one / 3, 2 * q32_one}, 4, 3},
    {{-2 * 65536, 65536 * 3 + 1, 65536, 0, -65536, 131072}, 4, 4},
    {{-40 * q32_one / 3, 20 * q32_one, q32_one * 3 / 4, q32_one / 16, -q32_one / 16, q32_one * 3 / 4},
     24,
     12},
};

/* Affine grids for the splatting path: rotations by 30 degrees at zooms 0.7 and 1.7 (across the int32 and
   2^64 wraps), an axis-aligned zoom 1.7, a minification by 4 rotated by 200 degrees, a magnification by 4
   rotated by -75 degrees, a shear and a mirror. Steps are Q32.32 integers (no libm on the targets). */
const Grid affine_grids[] = {
    {{INT64_MAX - 9 * q32_one, -5 * q32_one / 3, 2603685551, 1503238554, -1503238554, 2603685551}, 20, 14},
    {{-11 * q32_one / 7, (INT64_C(0x7FFFFFF0) << 32) + 77, 6323236337, 3650722202, -3650722202, 6323236337},
     16,
     12},
    {{q32_one / 3, q32_one / 7, 7301444403, 0, 0, 7301444403}, 12, 10},
    {{40 * q32_one, -3 * q32_one, -1008987269, -367241333, 367241333, -1008987269}, 24, 16},
    {{INT64_MIN + q32_one / 5, 3 * q32_one, 4446477337, -16594479337, 16594479337, 4446477337}, 9, 7},
    {{-2 * q32_one, 12345, 4563481818, 1222781268, 667004343, 4563481818}, 14, 11},
    {{q32_one / 2, -q32_one / 9, 1932735283, 3347595708, -3347595708, -1932735283}, 13, 9},
};

/* The affine grids under the continuous settings and two more periods (one that every grid crosses
   the int32 wrap of, per point then, and one small enough to repeat within a tile). */
const Setting affine_settings[] = {
    {0u, 0u, 0u, 0u, lattice_continuous},
    {0x9E3779B9u, 100u << 16, 0u, 0u, lattice_continuous | DSN_FLAG_NO_COLOR_TRANSFORM},
    {5u, DSN_IMPACTS_MIN_Q16, 16u, 13u, lattice_continuous},
    {77u, 20u << 16, 37u, 0u, lattice_continuous},
    {78u, 0u, 5u, 7u, lattice_continuous},
};

const uint32_t max_window_values = 32u * 16u * DSN_MAX_CHANNELS; /* the largest window or grid */
const size_t scratch_capacity = 64u * 1024u;

/* Caller-owned buffers for tile outputs and scratch: static so that nothing large sits on a small
   microcontroller stack. The golden program is single-threaded. */
int32_t tile_fixed_values[max_window_values];
float tile_float_values[max_window_values];
uint8_t tile_u8_values[max_window_values];
unsigned char tile_scratch[scratch_capacity];

/* Each evaluator hashes one window and returns DSN_OK or the runtime's error. */
typedef int (*Evaluator)(const dsn_noise *noise, const Window &window, Fnv *hash);

int scratch_for(const dsn_noise *noise, const Window &window, size_t *size) {
    *size = dsn_lattice_tile_scratch_size(noise, window.width, window.height);
    return *size <= scratch_capacity && window.width * window.height * DSN_MAX_CHANNELS <= max_window_values
               ? DSN_OK
               : DSN_ERR_SCRATCH;
}

int point_fixed(const dsn_noise *noise, const Window &window, Fnv *hash) {
    for (uint32_t j = 0; j < window.height; j++)
        for (uint32_t i = 0; i < window.width; i++) {
            int32_t values[DSN_MAX_CHANNELS];
            dsn_lattice_point_fixed(noise, wrapped(window.x, i), wrapped(window.y, j), values);
            hash_fixed(hash, values, dsn_noise_channels(noise));
        }
    return DSN_OK;
}

int tile_fixed(const dsn_noise *noise, const Window &window, Fnv *hash) {
    size_t scratch_size;
    int err = scratch_for(noise, window, &scratch_size);
    if (err == DSN_OK)
        err = dsn_lattice_tile_fixed(noise, window.x, window.y, window.width, window.height,
                                     tile_fixed_values, tile_scratch, scratch_size);
    if (err == DSN_OK)
        hash_fixed(hash, tile_fixed_values, window.width * window.height * dsn_noise_channels(noise));
    return err;
}

/* Per point, then the same window as a tile: both conversions of the API edge. */
int float_outputs(const dsn_noise *noise, const Window &window, Fnv *hash) {
    size_t scratch_size;
    for (uint32_t j = 0; j < window.height; j++)
        for (uint32_t i = 0; i < window.width; i++) {
            float values[DSN_MAX_CHANNELS];
            dsn_lattice_point_float(noise, wrapped(window.x, i), wrapped(window.y, j), values);
            hash_float(hash, values, dsn_noise_channels(noise));
        }
    int err = scratch_for(noise, window, &scratch_size);
    if (err == DSN_OK)
        err = dsn_lattice_tile_float(noise, window.x, window.y, window.width, window.height,
                                     tile_float_values, tile_scratch, scratch_size);
    if (err == DSN_OK)
        hash_float(hash, tile_float_values, window.width * window.height * dsn_noise_channels(noise));
    return err;
}

int u8_outputs(const dsn_noise *noise, const Window &window, Fnv *hash) {
    size_t scratch_size;
    for (uint32_t j = 0; j < window.height; j++)
        for (uint32_t i = 0; i < window.width; i++) {
            uint8_t values[DSN_MAX_CHANNELS];
            dsn_lattice_point_u8(noise, wrapped(window.x, i), wrapped(window.y, j), values);
            hash_u8(hash, values, dsn_noise_channels(noise));
        }
    int err = scratch_for(noise, window, &scratch_size);
    if (err == DSN_OK)
        err = dsn_lattice_tile_u8(noise, window.x, window.y, window.width, window.height, tile_u8_values,
                                  tile_scratch, scratch_size);
    if (err == DSN_OK)
        hash_u8(hash, tile_u8_values, window.width * window.height * dsn_noise_channels(noise));
    return err;
}

int point_then_tile(const dsn_noise *noise, const Window &window, Fnv *hash) {
    const int err = point_fixed(noise, window, hash);
    return err == DSN_OK ? tile_fixed(noise, window, hash) : err;
}

/* Two's complement without implementation-defined conversions. */
int64_t signed_from(uint64_t value) {
    return value >= (UINT64_C(1) << 63) ? -static_cast<int64_t>(~value) - 1 : static_cast<int64_t>(value);
}

/* Pixel (i, j) of a grid, with the additions modulo 2^64 as documented for dsn_grid. */
void grid_point(const dsn_grid &grid, uint32_t i, uint32_t j, int64_t *x, int64_t *y) {
    *x = signed_from(static_cast<uint64_t>(grid.origin_x) + i * static_cast<uint64_t>(grid.column_step_x) +
                     j * static_cast<uint64_t>(grid.row_step_x));
    *y = signed_from(static_cast<uint64_t>(grid.origin_y) + i * static_cast<uint64_t>(grid.column_step_y) +
                     j * static_cast<uint64_t>(grid.row_step_y));
}

/* The coordinate in texels as a double, exactly: 16 fractional bits of a 48-bit value survive, so the
   input of the float API is the same number on every platform (no rounding anywhere). */
double grid_double(int64_t coordinate) {
    return static_cast<double>(static_cast<int32_t>(static_cast<uint64_t>(coordinate) >> 16)) / 65536.0;
}

typedef int (*GridEvaluator)(const dsn_noise *noise, const Grid &grid, Fnv *hash);

int continuous_point_fixed(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    for (uint32_t j = 0; j < grid.height; j++)
        for (uint32_t i = 0; i < grid.width; i++) {
            int32_t values[DSN_MAX_CHANNELS];
            int64_t x, y;
            grid_point(grid.grid, i, j, &x, &y);
            const int err = dsn_continuous_point_fixed(noise, x, y, values);
            if (err != DSN_OK) return err;
            hash_fixed(hash, values, dsn_noise_channels(noise));
        }
    return DSN_OK;
}

int continuous_scratch_for(const dsn_noise *noise, const Grid &grid, size_t *size) {
    *size = dsn_continuous_tile_scratch_size(noise, &grid.grid, grid.width, grid.height);
    return *size <= scratch_capacity && grid.width * grid.height * DSN_MAX_CHANNELS <= max_window_values
               ? DSN_OK
               : DSN_ERR_SCRATCH;
}

int continuous_tile_fixed(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    size_t scratch_size;
    int err = continuous_scratch_for(noise, grid, &scratch_size);
    if (err == DSN_OK)
        err = dsn_continuous_tile_fixed(noise, &grid.grid, grid.width, grid.height, tile_fixed_values,
                                        tile_scratch, scratch_size);
    if (err == DSN_OK)
        hash_fixed(hash, tile_fixed_values, grid.width * grid.height * dsn_noise_channels(noise));
    return err;
}

/* The float API per point (from double coordinates), then the float and 8-bit grid tiles. */
int continuous_conversions(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    for (uint32_t j = 0; j < grid.height; j++)
        for (uint32_t i = 0; i < grid.width; i++) {
            float values[DSN_MAX_CHANNELS];
            int64_t x, y;
            grid_point(grid.grid, i, j, &x, &y);
            const int err = dsn_continuous_point_float(noise, grid_double(x), grid_double(y), values);
            if (err != DSN_OK) return err;
            hash_float(hash, values, dsn_noise_channels(noise));
        }
    size_t scratch_size;
    const uint32_t count = grid.width * grid.height * dsn_noise_channels(noise);
    int err = continuous_scratch_for(noise, grid, &scratch_size);
    if (err == DSN_OK)
        err = dsn_continuous_tile_float(noise, &grid.grid, grid.width, grid.height, tile_float_values,
                                        tile_scratch, scratch_size);
    if (err == DSN_OK) hash_float(hash, tile_float_values, count);
    if (err == DSN_OK)
        err = dsn_continuous_tile_u8(noise, &grid.grid, grid.width, grid.height, tile_u8_values, tile_scratch,
                                     scratch_size);
    if (err == DSN_OK) hash_u8(hash, tile_u8_values, count);
    return err;
}

/* The grid's points as one batch: the fixed values, then the float values from the coordinates of
   continuous_conversions. The small build has no batch functions (DSN_CONTINUOUS_BATCH 0): it takes the
   points one by one, which must give the same bytes. (The continuous grids only: the emulated
   microcontroller evaluates every kind point by point, within the run's time limit.) */
int64_t batch_x[max_window_values / DSN_MAX_CHANNELS], batch_y[max_window_values / DSN_MAX_CHANNELS];
double batch_x_double[max_window_values / DSN_MAX_CHANNELS],
    batch_y_double[max_window_values / DSN_MAX_CHANNELS];

int continuous_batch(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    const uint32_t points = grid.width * grid.height, count = points * dsn_noise_channels(noise);
    if (points * DSN_MAX_CHANNELS > max_window_values) return DSN_ERR_SCRATCH;
    for (uint32_t j = 0; j < grid.height; j++)
        for (uint32_t i = 0; i < grid.width; i++) {
            const uint32_t k = j * grid.width + i;
            grid_point(grid.grid, i, j, &batch_x[k], &batch_y[k]);
            batch_x_double[k] = grid_double(batch_x[k]);
            batch_y_double[k] = grid_double(batch_y[k]);
        }
#if DSN_CONTINUOUS_BATCH
    const size_t scratch_size = dsn_continuous_batch_scratch_size(noise);
    if (scratch_size > scratch_capacity) return DSN_ERR_SCRATCH;
    int err = dsn_continuous_batch_fixed(noise, batch_x, batch_y, points, tile_fixed_values, tile_scratch,
                                         scratch_size);
    if (err == DSN_OK)
        err = dsn_continuous_batch_float(noise, batch_x_double, batch_y_double, points, tile_float_values,
                                         tile_scratch, scratch_size);
#else
    int err = DSN_OK;
    const uint32_t channels = dsn_noise_channels(noise);
    for (uint32_t k = 0; err == DSN_OK && k < points; k++) {
        err = dsn_continuous_point_fixed(noise, batch_x[k], batch_y[k], &tile_fixed_values[k * channels]);
        if (err == DSN_OK)
            err = dsn_continuous_point_float(noise, batch_x_double[k], batch_y_double[k],
                                             &tile_float_values[k * channels]);
    }
#endif
    if (err != DSN_OK) return err;
    hash_fixed(hash, tile_fixed_values, count);
    hash_float(hash, tile_float_values, count);
    return DSN_OK;
}

#if DSN_SURFACE && !defined(GOLDEN_WITHOUT_SURFACE)
/* The surface noise (dsn.h, "Surface noise"): each grid point (x, y) lifted to the sloped plane
   z = x / 2 - y / 4 of 3-D space, under frames made from exactly representable float vectors: a plane's,
   a tilted normal with a tangent, the x axis (where the frame from the normal alone turns around) and a
   normal next to it, a tangent along its normal (the frame from the normal alone), a tangent crossing a
   non-unit normal, a normal and a tangent of subnormal floats only. */
struct SurfaceVectors {
    float normal[3], tangent[3];
    bool has_tangent;
};

const SurfaceVectors surface_vectors[] = {
    {{0, 0, 1}, {0, 0, 0}, false},
    {{0.3f, -0.5f, 0.8f}, {1, 0.25f, 0}, true},
    {{-1, 0, 0}, {0, 0, 0}, false},
    {{-1, 2e-3f, -1e-3f}, {0, 0, 0}, false},
    {{-3, 6, 1.5f}, {-3, 6, 1.5f}, true},
    {{1, 1, 0}, {0, 0, 5}, true},
    {{1e-40f, -3e-39f, 2e-39f}, {3e-41f, 1e-39f, 0}, true},
};
const uint32_t surface_vector_count = sizeof surface_vectors / sizeof surface_vectors[0];
const uint32_t surface_points_max = 32u;

int64_t surface_positions[surface_points_max * 3];
dsn_surface_frame surface_frames[surface_points_max];

/* The grid's points (at most surface_points_max: the first ones) as positions, with their frame. */
uint32_t surface_points(const Grid &grid, const dsn_surface_frame &frame) {
    uint32_t count = 0;
    for (uint32_t j = 0; j < grid.height; j++)
        for (uint32_t i = 0; i < grid.width && count < surface_points_max; i++, count++) {
            int64_t *position = &surface_positions[3 * count];
            grid_point(grid.grid, i, j, &position[0], &position[1]);
            position[2] = signed_from((static_cast<uint64_t>(position[0]) >> 1) -
                                      (static_cast<uint64_t>(position[1]) >> 2));
            surface_frames[count] = frame;
        }
    return count;
}

/* Each frame's bits, then the fixed values of every point of the grid. */
int surface_point_fixed(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    for (uint32_t f = 0; f < surface_vector_count; f++) {
        const SurfaceVectors &vectors = surface_vectors[f];
        dsn_surface_frame frame;
        int err =
            dsn_surface_frame_from_float(vectors.normal, vectors.has_tangent ? vectors.tangent : 0, &frame);
        if (err != DSN_OK) return err;
        hash_fixed(hash, frame.tangent, 3);
        hash_fixed(hash, frame.bitangent, 3);
        hash_fixed(hash, frame.normal, 3);
        const uint32_t count = surface_points(grid, frame);
        for (uint32_t k = 0; k < count; k++) {
            int32_t values[DSN_MAX_CHANNELS];
            err = dsn_surface_point_fixed(noise, &surface_positions[3 * k], &frame, values);
            if (err != DSN_OK) return err;
            hash_fixed(hash, values, dsn_noise_channels(noise));
        }
    }
    return DSN_OK;
}

/* The float API per point (double positions, float vectors), then the batch and the 8-bit values. */
int surface_conversions(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    const uint32_t channels = dsn_noise_channels(noise);
    for (uint32_t f = 0; f < surface_vector_count; f++) {
        const SurfaceVectors &vectors = surface_vectors[f];
        dsn_surface_frame frame;
        int err =
            dsn_surface_frame_from_float(vectors.normal, vectors.has_tangent ? vectors.tangent : 0, &frame);
        const uint32_t count = surface_points(grid, frame);
        for (uint32_t k = 0; err == DSN_OK && k < count; k++) {
            const int64_t *position = &surface_positions[3 * k];
            const double point[3] = {grid_double(position[0]), grid_double(position[1]),
                                     grid_double(position[2])};
            float values[DSN_MAX_CHANNELS];
            err = dsn_surface_point_float(noise, point, vectors.normal,
                                          vectors.has_tangent ? vectors.tangent : 0, values);
            if (err == DSN_OK) hash_float(hash, values, channels);
        }
        if (err == DSN_OK)
            err = dsn_surface_batch_fixed(noise, surface_positions, surface_frames, count, tile_fixed_values);
        if (err == DSN_OK) hash_fixed(hash, tile_fixed_values, count * channels);
        for (uint32_t k = 0; err == DSN_OK && k < count; k++) {
            uint8_t values[DSN_MAX_CHANNELS];
            err = dsn_surface_point_u8(noise, &surface_positions[3 * k], &frame, values);
            if (err == DSN_OK) hash_u8(hash, values, channels);
        }
        if (err != DSN_OK) return err;
    }
    return DSN_OK;
}
#endif

#if DSN_GRADIENTS && !defined(GOLDEN_WITHOUT_GRADIENTS)
/* The gradients (dsn.h, "Gradients"): the values, then the x derivatives, then the y derivatives of a
   window or grid, hashed as three arrays; per point and tile give the same bytes. */
int32_t gradient_dx_values[max_window_values], gradient_dy_values[max_window_values];
float gradient_dx_floats[max_window_values], gradient_dy_floats[max_window_values];

void hash_gradient(Fnv *hash, uint32_t count) {
    hash_fixed(hash, tile_fixed_values, count);
    hash_fixed(hash, gradient_dx_values, count);
    hash_fixed(hash, gradient_dy_values, count);
}

void hash_gradient_floats(Fnv *hash, uint32_t count) {
    hash_float(hash, tile_float_values, count);
    hash_float(hash, gradient_dx_floats, count);
    hash_float(hash, gradient_dy_floats, count);
}

int continuous_gradient_point(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    const uint32_t channels = dsn_noise_channels(noise), count = grid.width * grid.height * channels;
    if (grid.width * grid.height * DSN_MAX_CHANNELS > max_window_values) return DSN_ERR_SCRATCH;
    for (uint32_t j = 0; j < grid.height; j++)
        for (uint32_t i = 0; i < grid.width; i++) {
            const uint32_t at = (j * grid.width + i) * channels;
            int64_t x, y;
            grid_point(grid.grid, i, j, &x, &y);
            const int err = dsn_continuous_gradient_fixed(noise, x, y, &tile_fixed_values[at],
                                                          &gradient_dx_values[at], &gradient_dy_values[at]);
            if (err != DSN_OK) return err;
        }
    hash_gradient(hash, count);
    return DSN_OK;
}

int continuous_gradient_tile(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    const uint32_t count = grid.width * grid.height * dsn_noise_channels(noise);
    if (grid.width * grid.height * DSN_MAX_CHANNELS > max_window_values) return DSN_ERR_SCRATCH;
    const int err =
        dsn_continuous_tile_gradient_fixed(noise, &grid.grid, grid.width, grid.height, tile_fixed_values,
                                           gradient_dx_values, gradient_dy_values);
    if (err != DSN_OK) return err;
    hash_gradient(hash, count);
    return DSN_OK;
}

/* The float API per point (from double coordinates), then the grid's points as one float batch. */
int continuous_gradient_floats(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    const uint32_t channels = dsn_noise_channels(noise), points = grid.width * grid.height;
    if (points * DSN_MAX_CHANNELS > max_window_values) return DSN_ERR_SCRATCH;
    for (uint32_t j = 0; j < grid.height; j++)
        for (uint32_t i = 0; i < grid.width; i++) {
            const uint32_t k = j * grid.width + i;
            int64_t x, y;
            grid_point(grid.grid, i, j, &x, &y);
            batch_x_double[k] = grid_double(x);
            batch_y_double[k] = grid_double(y);
            const int err = dsn_continuous_gradient_float(
                noise, batch_x_double[k], batch_y_double[k], &tile_float_values[k * channels],
                &gradient_dx_floats[k * channels], &gradient_dy_floats[k * channels]);
            if (err != DSN_OK) return err;
        }
    hash_gradient_floats(hash, points * channels);
    const int err =
        dsn_continuous_batch_gradient_float(noise, batch_x_double, batch_y_double, points, tile_float_values,
                                            gradient_dx_floats, gradient_dy_floats);
    if (err != DSN_OK) return err;
    hash_gradient_floats(hash, points * channels);
    return DSN_OK;
}
#endif

/* The filtered evaluation: each grid's steps are the footprint, evaluated with 16 taps allowed then 1:
   a minification by 2.5 rotated, by 6 across the int32 wrap, a slanted footprint (8 taps) with a
   mirror, a degenerate one (zero determinant: the most taps), a magnification (the continuous bits), a
   huge one (the mean colour) and one slanted along its rows, whose tiles are splatted (levels 1 and 2
   with one tap, level 0 at 8 taps on the RGB 8-bit asset). */
const Grid filtered_grids[] = {
    {{-7 * q32_one / 3, 5 * q32_one, 10307921510, 3006477107, -3006477107, 10307921510}, 5, 4},
    {{(INT64_C(0x7FFFFFF0) << 32) + 99, -q32_one / 5, 6 * q32_one, q32_one / 8, 0, 6 * q32_one}, 4, 3},
    {{q32_one / 3, 40 * q32_one, 12 * q32_one, 5 * q32_one, q32_one / 2, -3 * q32_one / 2}, 4, 4},
    {{-q32_one, -q32_one, 3 * q32_one, 3 * q32_one, 2 * q32_one, 2 * q32_one}, 3, 3},
    {{11 * q32_one / 7, q32_one / 9, q32_one / 2, q32_one / 5, -q32_one / 5, q32_one / 2}, 4, 3},
    {{0, 0, INT64_MAX / 3, INT64_MIN / 5, INT64_MAX / 7, INT64_MAX / 2}, 3, 2},
    {{-13 * q32_one / 7, 3 * q32_one + 5, 3221225472, 536870912, -2147483648, 13958643712}, 10, 6},
};

#if DSN_FILTERING
dsn_footprint grid_footprint(const Grid &grid, uint32_t max_taps) {
    dsn_footprint footprint;
    footprint.column_step_x = grid.grid.column_step_x;
    footprint.column_step_y = grid.grid.column_step_y;
    footprint.row_step_x = grid.grid.row_step_x;
    footprint.row_step_y = grid.grid.row_step_y;
    footprint.max_taps = max_taps;
    return footprint;
}

/* The level of detail and taps, then the points. */
int filtered_point_fixed(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    for (uint32_t max_taps = 16; max_taps >= 1; max_taps /= 16) {
        const dsn_footprint footprint = grid_footprint(grid, max_taps);
        int32_t lod_q8;
        uint32_t taps;
        int err = dsn_filter_level(noise, &footprint, &lod_q8, &taps);
        if (err != DSN_OK) return err;
        hash_u32(hash, static_cast<uint32_t>(lod_q8));
        hash_u32(hash, taps);
        for (uint32_t j = 0; j < grid.height; j++)
            for (uint32_t i = 0; i < grid.width; i++) {
                int32_t values[DSN_MAX_CHANNELS];
                int64_t x, y;
                grid_point(grid.grid, i, j, &x, &y);
                err = dsn_filtered_point_fixed(noise, x, y, &footprint, values);
                if (err != DSN_OK) return err;
                hash_fixed(hash, values, dsn_noise_channels(noise));
            }
    }
    return DSN_OK;
}

#if DSN_SURFACE && !defined(GOLDEN_WITHOUT_SURFACE)
/* The filtered surface noise: the grid's steps as the footprint in the tangent plane (4 taps at most, then
   1), at the surface points of three of the frames (a plane's, the tilted one with a tangent, next to the
   x axis). */
int surface_filtered(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    const uint32_t frames[] = {0, 1, 3};
    for (uint32_t max_taps = 4; max_taps >= 1; max_taps /= 4) {
        const dsn_footprint footprint = grid_footprint(grid, max_taps);
        for (uint32_t f = 0; f < 3; f++) {
            const SurfaceVectors &vectors = surface_vectors[frames[f]];
            dsn_surface_frame frame;
            int err = dsn_surface_frame_from_float(vectors.normal, vectors.has_tangent ? vectors.tangent : 0,
                                                   &frame);
            const uint32_t count = surface_points(grid, frame);
            for (uint32_t k = 0; err == DSN_OK && k < count; k++) {
                int32_t values[DSN_MAX_CHANNELS];
                err = dsn_surface_filtered_point_fixed(noise, &surface_positions[3 * k], &frame, &footprint,
                                                       values);
                if (err == DSN_OK) hash_fixed(hash, values, dsn_noise_channels(noise));
            }
            if (err != DSN_OK) return err;
        }
    }
    return DSN_OK;
}
#endif

int filtered_scratch_for(const dsn_noise *noise, const Grid &grid, uint32_t max_taps, size_t *size) {
    *size = dsn_filtered_tile_scratch_size(noise, &grid.grid, max_taps, grid.width, grid.height);
    return *size <= scratch_capacity && grid.width * grid.height * DSN_MAX_CHANNELS <= max_window_values
               ? DSN_OK
               : DSN_ERR_SCRATCH;
}

/* The same bytes as filtered_point_fixed, from the tile. */
int filtered_tile_fixed(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    for (uint32_t max_taps = 16; max_taps >= 1; max_taps /= 16) {
        const dsn_footprint footprint = grid_footprint(grid, max_taps);
        int32_t lod_q8;
        uint32_t taps;
        size_t scratch_size;
        int err = dsn_filter_level(noise, &footprint, &lod_q8, &taps);
        if (err == DSN_OK) err = filtered_scratch_for(noise, grid, max_taps, &scratch_size);
        if (err == DSN_OK)
            err = dsn_filtered_tile_fixed(noise, &grid.grid, max_taps, grid.width, grid.height,
                                          tile_fixed_values, tile_scratch, scratch_size);
        if (err != DSN_OK) return err;
        hash_u32(hash, static_cast<uint32_t>(lod_q8));
        hash_u32(hash, taps);
        hash_fixed(hash, tile_fixed_values, grid.width * grid.height * dsn_noise_channels(noise));
    }
    return DSN_OK;
}

/* The float API per point, then the float and 8-bit tiles, with 16 taps allowed. */
int filtered_conversions(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    const dsn_footprint footprint = grid_footprint(grid, 16);
    for (uint32_t j = 0; j < grid.height; j++)
        for (uint32_t i = 0; i < grid.width; i++) {
            float values[DSN_MAX_CHANNELS];
            int64_t x, y;
            grid_point(grid.grid, i, j, &x, &y);
            const int err =
                dsn_filtered_point_float(noise, grid_double(x), grid_double(y), &footprint, values);
            if (err != DSN_OK) return err;
            hash_float(hash, values, dsn_noise_channels(noise));
        }
    size_t scratch_size;
    const uint32_t count = grid.width * grid.height * dsn_noise_channels(noise);
    int err = filtered_scratch_for(noise, grid, 16, &scratch_size);
    if (err == DSN_OK)
        err = dsn_filtered_tile_float(noise, &grid.grid, 16, grid.width, grid.height, tile_float_values,
                                      tile_scratch, scratch_size);
    if (err == DSN_OK) hash_float(hash, tile_float_values, count);
    if (err == DSN_OK)
        err = dsn_filtered_tile_u8(noise, &grid.grid, 16, grid.width, grid.height, tile_u8_values,
                                   tile_scratch, scratch_size);
    if (err == DSN_OK) hash_u8(hash, tile_u8_values, count);
    return err;
}
#endif

#if DSN_GRADIENTS && !defined(GOLDEN_WITHOUT_GRADIENTS)
int gradient_point(const dsn_noise *noise, const Window &window, Fnv *hash) {
    const uint32_t channels = dsn_noise_channels(noise);
    if (window.width * window.height * DSN_MAX_CHANNELS > max_window_values) return DSN_ERR_SCRATCH;
    for (uint32_t j = 0; j < window.height; j++)
        for (uint32_t i = 0; i < window.width; i++) {
            const uint32_t at = (j * window.width + i) * channels;
            const int err = dsn_lattice_gradient_fixed(noise, wrapped(window.x, i), wrapped(window.y, j),
                                                       &tile_fixed_values[at], &gradient_dx_values[at],
                                                       &gradient_dy_values[at]);
            if (err != DSN_OK) return err;
        }
    hash_gradient(hash, window.width * window.height * channels);
    return DSN_OK;
}

int gradient_tile(const dsn_noise *noise, const Window &window, Fnv *hash) {
    if (window.width * window.height * DSN_MAX_CHANNELS > max_window_values) return DSN_ERR_SCRATCH;
    const int err =
        dsn_lattice_tile_gradient_fixed(noise, window.x, window.y, window.width, window.height,
                                        tile_fixed_values, gradient_dx_values, gradient_dy_values);
    if (err == DSN_OK) hash_gradient(hash, window.width * window.height * dsn_noise_channels(noise));
    return err;
}

/* Per point as float, then the float tile. */
int gradient_floats(const dsn_noise *noise, const Window &window, Fnv *hash) {
    const uint32_t channels = dsn_noise_channels(noise), count = window.width * window.height * channels;
    if (window.width * window.height * DSN_MAX_CHANNELS > max_window_values) return DSN_ERR_SCRATCH;
    for (uint32_t j = 0; j < window.height; j++)
        for (uint32_t i = 0; i < window.width; i++) {
            const uint32_t at = (j * window.width + i) * channels;
            const int err = dsn_lattice_gradient_float(noise, wrapped(window.x, i), wrapped(window.y, j),
                                                       &tile_float_values[at], &gradient_dx_floats[at],
                                                       &gradient_dy_floats[at]);
            if (err != DSN_OK) return err;
        }
    hash_gradient_floats(hash, count);
    const int err =
        dsn_lattice_tile_gradient_float(noise, window.x, window.y, window.width, window.height,
                                        tile_float_values, gradient_dx_floats, gradient_dy_floats);
    if (err == DSN_OK) hash_gradient_floats(hash, count);
    return err;
}
#endif

#if DSN_GRADIENTS && DSN_FILTERING && !defined(GOLDEN_WITHOUT_GRADIENTS)
/* The filtered gradient at the grid's points with the grid's footprint, 16 taps allowed then 1, then the
   float tile. */
int filtered_gradient(const dsn_noise *noise, const Grid &grid, Fnv *hash) {
    const uint32_t channels = dsn_noise_channels(noise), count = grid.width * grid.height * channels;
    if (grid.width * grid.height * DSN_MAX_CHANNELS > max_window_values) return DSN_ERR_SCRATCH;
    for (uint32_t max_taps = 16; max_taps >= 1; max_taps /= 16) {
        const dsn_footprint footprint = grid_footprint(grid, max_taps);
        for (uint32_t j = 0; j < grid.height; j++)
            for (uint32_t i = 0; i < grid.width; i++) {
                const uint32_t at = (j * grid.width + i) * channels;
                int64_t x, y;
                grid_point(grid.grid, i, j, &x, &y);
                const int err = dsn_filtered_gradient_fixed(noise, x, y, &footprint, &tile_fixed_values[at],
                                                            &gradient_dx_values[at], &gradient_dy_values[at]);
                if (err != DSN_OK) return err;
            }
        hash_gradient(hash, count);
    }
    const int err =
        dsn_filtered_tile_gradient_float(noise, &grid.grid, 16, grid.width, grid.height, tile_float_values,
                                         gradient_dx_floats, gradient_dy_floats);
    if (err == DSN_OK) hash_gradient_floats(hash, count);
    return err;
}
#endif

/* IEEE bit patterns for the coordinate conversions: zeros, halves, the int32 ends, beyond 2^63, the
   smallest subnormal, the largest finite, infinities and NaNs. Built from bits so that no compiler
   option (-ffast-math) can change them. */
const uint64_t double_patterns[] = {
    0x0000000000000000u, 0x8000000000000000u, 0x3FE0000000000000u, 0xBFE0000000000000u, 0x41DFFFFFFFC00000u,
    0xC1E0000000000000u, 0xC1E0000000100000u, 0x43E0000000000000u, 0x4415AF1D78B58C40u, 0x0000000000000001u,
    0x7FEFFFFFFFFFFFFFu, 0x7FF0000000000000u, 0xFFF0000000000000u, 0x7FF8000000000000u, 0xFFF0000000000001u,
    0x400921FB54442D18u, 0xC00921FB54442D18u, 0x3DF0000000000000u, 0x3DEFFFFFFFFFFFFFu, 0xBDF0000000000000u,
};
const uint32_t float_patterns[] = {
    0x00000000u, 0x80000000u, 0x3F000000u, 0xBF000000u, 0x4EFFFFFFu, 0xCF000000u,
    0x5F000000u, 0x00000001u, 0x7F7FFFFFu, 0x7F800000u, 0xFF800000u, 0x7FC00000u,
    0x40490FDBu, 0xC0490FDBu, 0x2F800000u, 0xAF800000u, 0x2F7FFFFFu,
};

uint64_t coordinate_conversions_hash() {
    Fnv hash = {fnv_offset_basis};
    for (uint32_t i = 0; i < sizeof double_patterns / sizeof double_patterns[0]; i++) {
        double value;
        memcpy(&value, &double_patterns[i], sizeof value);
        hash_u64(&hash, static_cast<uint64_t>(dsn_coordinate_from_double(value)));
    }
    for (uint32_t i = 0; i < sizeof float_patterns / sizeof float_patterns[0]; i++) {
        float value;
        memcpy(&value, &float_patterns[i], sizeof value);
        hash_u64(&hash, static_cast<uint64_t>(dsn_coordinate_from_float(value)));
    }
    return hash.state;
}

#define GOLDEN_COUNT(array) static_cast<uint32_t>(sizeof(array) / sizeof((array)[0]))

/* Which settings and windows (lattice) or grids (continuous) a kind of output is evaluated under. */
struct Plan {
    const Setting *settings;
    uint32_t setting_count;
    const Window *windows;
    uint32_t window_count;
    const Grid *grids;
    uint32_t grid_count;
};

const Plan lattice_plan = {
    lattice_settings, GOLDEN_COUNT(lattice_settings), lattice_windows, GOLDEN_COUNT(lattice_windows), 0, 0};
const Plan tileable_plan = {tileable_settings,
                            GOLDEN_COUNT(tileable_settings),
                            tileable_windows,
                            GOLDEN_COUNT(tileable_windows),
                            0,
                            0};
const Plan continuous_plan = {continuous_settings, GOLDEN_COUNT(continuous_settings), 0, 0,
                              continuous_grids,    GOLDEN_COUNT(continuous_grids)};

const Plan affine_plan = {affine_settings, GOLDEN_COUNT(affine_settings), 0, 0,
                          affine_grids,    GOLDEN_COUNT(affine_grids)};
/* The surface noise's grids: the zoom, the rotation across both 32-bit wraps and the tiny steps across 0 of
   the continuous grids. */
const Grid surface_grids[] = {
    {{-3 * q32_one - q32_one / 4, 7 * q32_one + q32_one / 2, 1288490189, 0, 0, 1288490189}, 6, 5},
    {{INT64_MAX - q32_one / 2, INT64_MIN + 123, 3719550787, -2147483648, 2147483648, 3719550787}, 5, 4},
    {{-2 * 65536, 65536 * 3 + 1, 65536, 0, -65536, 131072}, 4, 4},
};
const Plan surface_plan = {continuous_settings, GOLDEN_COUNT(continuous_settings), 0, 0,
                           surface_grids,       GOLDEN_COUNT(surface_grids)};
const Plan filtered_plan = {continuous_settings, GOLDEN_COUNT(continuous_settings), 0, 0,
                            filtered_grids,      GOLDEN_COUNT(filtered_grids)};
/* The filtered surface noise's footprints: a rotated minification by about 2.4, a magnification and
   minification by 3 with shear, and steps so large that the texture has faded to its mean. */
const Grid surface_filtered_grids[] = {
    {{-7 * q32_one / 3, 5 * q32_one, 10307921510, 3006477107, -3006477107, 10307921510}, 5, 4},
    {{-q32_one, -q32_one, 3 * q32_one, 3 * q32_one, 2 * q32_one, 2 * q32_one}, 3, 3},
    {{0, 0, INT64_MAX / 3, INT64_MIN / 5, INT64_MAX / 7, INT64_MAX / 2}, 3, 2},
};
const Plan surface_filtered_plan = {continuous_settings,    GOLDEN_COUNT(continuous_settings),   0, 0,
                                    surface_filtered_grids, GOLDEN_COUNT(surface_filtered_grids)};

/* One kind of output: a lattice evaluator over the plan's windows or a continuous one over its grids, on
   the four assets or (`mapped`) on the two with a histogram mapping (format 1.2). */
struct Kind {
    const char *name;
    Evaluator evaluate;
    GridEvaluator evaluate_grid;
    const Plan *plan;
    bool mapped;
};

const Kind kinds[] = {
    {"point", point_fixed, 0, &lattice_plan, false},
    {"tile", tile_fixed, 0, &lattice_plan, false}, /* the same bytes as "point": the two paths must agree */
    {"float32", float_outputs, 0, &lattice_plan, false},
    {"u8", u8_outputs, 0, &lattice_plan, false},
    {"tileable", point_then_tile, 0, &tileable_plan, false},
    {"c-point", 0, continuous_point_fixed, &continuous_plan, false},
    {"c-tile", 0, continuous_tile_fixed, &continuous_plan, false}, /* the same bytes as "c-point" */
    {"c-float", 0, continuous_conversions, &continuous_plan, false},
    {"a-point", 0, continuous_point_fixed, &affine_plan, false},
    {"a-tile", 0, continuous_tile_fixed, &affine_plan, false},   /* the same bytes as "a-point" */
    {"a-float", 0, continuous_conversions, &affine_plan, false}, /* per point, tile float and u8 */
    {"c-batch", 0, continuous_batch, &continuous_plan, false},   /* fixed then float, each as one batch */
#if DSN_GRADIENTS && !defined(GOLDEN_WITHOUT_GRADIENTS)
    {"d-point", gradient_point, 0, &lattice_plan, false},
    {"d-tile", gradient_tile, 0, &lattice_plan, false}, /* the same bytes as "d-point" */
    {"d-float", gradient_floats, 0, &tileable_plan, false},
    {"d-c-point", 0, continuous_gradient_point, &affine_plan, false},
    {"d-c-tile", 0, continuous_gradient_tile, &affine_plan, false}, /* the same bytes as "d-c-point" */
    {"d-c-float", 0, continuous_gradient_floats, &continuous_plan, false},
#endif
#if DSN_SURFACE && !defined(GOLDEN_WITHOUT_SURFACE)
    {"s-point", 0, surface_point_fixed, &surface_plan, false},
    {"s-float", 0, surface_conversions, &surface_plan, false}, /* float per point, batch fixed, u8 */
#endif
#if DSN_FILTERING
    {"f-point", 0, filtered_point_fixed, &filtered_plan, false},
    {"f-tile", 0, filtered_tile_fixed, &filtered_plan, false},   /* the same bytes as "f-point" */
    {"f-float", 0, filtered_conversions, &filtered_plan, false}, /* per point, tile float and u8 */
#endif
#if DSN_SURFACE && DSN_FILTERING && !defined(GOLDEN_WITHOUT_SURFACE)
    {"s-filtered", 0, surface_filtered, &surface_filtered_plan, false},
#endif
#if DSN_GRADIENTS && DSN_FILTERING && !defined(GOLDEN_WITHOUT_GRADIENTS)
    {"d-f-point", 0, filtered_gradient, &filtered_plan, false},
#endif
#ifndef GOLDEN_WITHOUT_HISTOGRAM /* the GLSL evaluator has no histogram mapping (tests/gpu leaves these out) \
                                  */
    {"h-point", point_fixed, 0, &lattice_plan, true},
    {"h-tile", tile_fixed, 0, &lattice_plan, true}, /* the same bytes as "h-point" */
    {"h-u8", u8_outputs, 0, &lattice_plan, true},
    {"h-c-point", 0, continuous_point_fixed, &affine_plan, true},
    {"h-c-tile", 0, continuous_tile_fixed, &affine_plan, true}, /* the same bytes as "h-c-point" */
#if DSN_SURFACE && !defined(GOLDEN_WITHOUT_SURFACE)
    {"h-s-point", 0, surface_point_fixed, &surface_plan, true},
#endif
#if DSN_GRADIENTS && !defined(GOLDEN_WITHOUT_GRADIENTS)
    {"h-d-point", gradient_point, 0, &lattice_plan, true},
    {"h-d-c-point", 0, continuous_gradient_point, &affine_plan, true},
#endif
#if DSN_GRADIENTS && DSN_FILTERING && !defined(GOLDEN_WITHOUT_GRADIENTS)
    {"h-d-f-point", 0, filtered_gradient, &filtered_plan, true},
#endif
#if DSN_FILTERING
    {"h-f-point", 0, filtered_point_fixed, &filtered_plan, true},
    {"h-f-tile", 0, filtered_tile_fixed, &filtered_plan, true}, /* the same bytes as "h-f-point" */
#endif
#endif
};

void write_line(const char *kind, const char *asset, const char *detail) {
    golden_write(kind);
    golden_write(" ");
    golden_write(asset);
    golden_write(" ");
    golden_write(detail);
    golden_write("\n");
}

void write_hash(const char *kind, const char *asset, uint64_t value) {
    char hex[17];
    for (int digit = 15; digit >= 0; digit--, value >>= 4) hex[digit] = "0123456789abcdef"[value & 15u];
    hex[16] = '\0';
    write_line(kind, asset, hex);
}

void write_error(const char *kind, const char *asset, int err) {
    golden_write("error ");
    write_line(kind, asset, dsn_error_message(err));
}

/* Hashes one kind over every setting and window of one asset. */
int hash_asset(const Kind &kind, const dsn_asset *asset, Fnv *hash) {
    const Plan &plan = *kind.plan;
    for (uint32_t s = 0; s < plan.setting_count; s++) {
        const Setting &setting = plan.settings[s];
        dsn_config config;
        dsn_noise noise;
        dsn_config_defaults(&config);
        config.seed = setting.seed;
        config.impacts_q16 = setting.impacts_q16;
        config.period_x = setting.period_x;
        config.period_y = setting.period_y;
        config.flags = setting.flags;
        int err = dsn_noise_init(&noise, asset, &config);
        for (uint32_t w = 0; err == DSN_OK && kind.evaluate && w < plan.window_count; w++)
            err = kind.evaluate(&noise, plan.windows[w], hash);
        for (uint32_t g = 0; err == DSN_OK && kind.evaluate_grid && g < plan.grid_count; g++)
            err = kind.evaluate_grid(&noise, plan.grids[g], hash);
        if (err != DSN_OK) return err;
    }
    return DSN_OK;
}

#if DSN_MIXING && !defined(GOLDEN_WITHOUT_MIXING)
/* ---- Mixing (dsn.h, "Mixing") ----
   Each asset as material 0 with the next asset (grey with RGB, 8 with 16 bits) as material 1, under three
   controls: a grid of varying weights (a zero sample, a periodic x axis, samples 4 texels apart, its origin
   off the lattice), a constant 50/50 and material 1 alone (which tiles take by its own tile function). */
const uint8_t mix_grid_weights[] = {255, 0, 200, 55, 0,  0,  9,   3,   0, 255, 128, 128, 60, 61, 1,  250,
                                    77,  7, 0,   1,  30, 90, 255, 255, 0, 40,  100, 0,   5,  5,  17, 200};
const uint8_t mix_half_weights[] = {128, 128}, mix_second_weights[] = {0, 255};
const dsn_mix_control mix_controls[] = {
    {mix_grid_weights, 4, 4, 2, -7, 3, DSN_MIX_PERIODIC_X},
    {mix_half_weights, 1, 1, 0, 0, 0, 0},
    {mix_second_weights, 1, 1, 0, 0, 0, 0},
};
const Window mix_windows[] = {
    {-3, -2, 5, 4}, {INT32_MAX - 2, INT32_MAX - 1, 5, 4}, {1234567891, -987654321, 6, 3}};
const Setting mix_settings[] = {
    {0u, 0u, 0u, 0u, lattice_continuous},
    {5u, DSN_IMPACTS_MIN_Q16, 16u, 13u, lattice_continuous},
    {0x9E3779B9u, 100u << 16, 0u, 0u, lattice_continuous | DSN_FLAG_NO_COLOR_TRANSFORM},
};
const Grid *const mix_grids[] = {&affine_grids[0], &affine_grids[4], &continuous_grids[3]};

dsn_mix golden_mix;
int64_t mix_xs[max_window_values / DSN_MAX_CHANNELS], mix_ys[max_window_values / DSN_MAX_CHANNELS];

/* The mix of assets a and a + 1 under a setting (material 1 with the next seed). */
int make_mix(uint32_t a, const Setting &setting) {
    dsn_asset assets[2];
    static dsn_noise noises[2];
    for (uint32_t m = 0; m < 2; m++) {
        const cross_asset &bytes = cross_assets[(a + m) % CROSS_ASSET_COUNT];
        int err = dsn_asset_load(&assets[m], bytes.bytes, bytes.size);
        dsn_config config;
        dsn_config_defaults(&config);
        config.seed = setting.seed + m;
        config.impacts_q16 = setting.impacts_q16;
        config.period_x = setting.period_x;
        config.period_y = setting.period_y;
        config.flags = setting.flags;
        if (err == DSN_OK) err = dsn_noise_init(&noises[m], &assets[m], &config);
        if (err != DSN_OK) return err;
    }
    const dsn_noise *materials[2] = {&noises[0], &noises[1]};
    return dsn_mix_init(&golden_mix, materials, 2);
}

/* One kind of mixed output over the windows or grids of one setting and control. */
typedef int (*MixEvaluator)(const dsn_mix_control *control, Fnv *hash);

int mix_lattice_points(const dsn_mix_control *control, Fnv *hash) {
    const uint32_t channels = dsn_mix_channels(&golden_mix);
    for (uint32_t w = 0; w < GOLDEN_COUNT(mix_windows); w++)
        for (uint32_t j = 0; j < mix_windows[w].height; j++)
            for (uint32_t i = 0; i < mix_windows[w].width; i++) {
                int32_t values[DSN_MAX_CHANNELS];
                const int err = dsn_mix_lattice_point_fixed(
                    &golden_mix, control, wrapped(mix_windows[w].x, i), wrapped(mix_windows[w].y, j), values);
                if (err != DSN_OK) return err;
                hash_fixed(hash, values, channels);
            }
    return DSN_OK;
}

int mix_lattice_tiles(const dsn_mix_control *control, Fnv *hash) {
    const uint32_t channels = dsn_mix_channels(&golden_mix);
    for (uint32_t w = 0; w < GOLDEN_COUNT(mix_windows); w++) {
        const Window &window = mix_windows[w];
        const int err =
            dsn_mix_lattice_tile_fixed(&golden_mix, control, window.x, window.y, window.width, window.height,
                                       tile_fixed_values, tile_scratch, scratch_capacity);
        if (err != DSN_OK) return err;
        hash_fixed(hash, tile_fixed_values, window.width * window.height * channels);
    }
    return DSN_OK;
}

int mix_continuous_points(const dsn_mix_control *control, Fnv *hash) {
    const uint32_t channels = dsn_mix_channels(&golden_mix);
    for (uint32_t g = 0; g < GOLDEN_COUNT(mix_grids); g++)
        for (uint32_t j = 0; j < mix_grids[g]->height; j++)
            for (uint32_t i = 0; i < mix_grids[g]->width; i++) {
                int32_t values[DSN_MAX_CHANNELS];
                int64_t x, y;
                grid_point(mix_grids[g]->grid, i, j, &x, &y);
                const int err = dsn_mix_continuous_point_fixed(&golden_mix, control, x, y, values);
                if (err != DSN_OK) return err;
                hash_fixed(hash, values, channels);
            }
    return DSN_OK;
}

int mix_continuous_tiles(const dsn_mix_control *control, Fnv *hash) {
    const uint32_t channels = dsn_mix_channels(&golden_mix);
    for (uint32_t g = 0; g < GOLDEN_COUNT(mix_grids); g++) {
        const Grid &grid = *mix_grids[g];
        const int err =
            dsn_mix_continuous_tile_fixed(&golden_mix, control, &grid.grid, grid.width, grid.height,
                                          tile_fixed_values, tile_scratch, scratch_capacity);
        if (err != DSN_OK) return err;
        hash_fixed(hash, tile_fixed_values, grid.width * grid.height * channels);
    }
    return DSN_OK;
}

/* The conversions: float lattice tiles, continuous points from float64 coordinates, u8 continuous tiles
   and a u8 batch of the continuous grids' points. */
int mix_floats(const dsn_mix_control *control, Fnv *hash) {
    const uint32_t channels = dsn_mix_channels(&golden_mix);
    for (uint32_t w = 0; w < GOLDEN_COUNT(mix_windows); w++) {
        const Window &window = mix_windows[w];
        const int err =
            dsn_mix_lattice_tile_float(&golden_mix, control, window.x, window.y, window.width, window.height,
                                       tile_float_values, tile_scratch, scratch_capacity);
        if (err != DSN_OK) return err;
        hash_float(hash, tile_float_values, window.width * window.height * channels);
    }
    for (uint32_t i = 0; i < sizeof double_patterns / sizeof double_patterns[0]; i++) {
        double x, y;
        memcpy(&x, &double_patterns[i], sizeof x);
        memcpy(&y, &double_patterns[(i + 3) % (sizeof double_patterns / sizeof double_patterns[0])],
               sizeof y);
        float values[DSN_MAX_CHANNELS];
        const int err = dsn_mix_continuous_point_float(&golden_mix, control, x, y, values);
        if (err != DSN_OK) return err;
        hash_float(hash, values, channels);
    }
    for (uint32_t g = 0; g < GOLDEN_COUNT(mix_grids); g++) {
        const Grid &grid = *mix_grids[g];
        const uint32_t points = grid.width * grid.height;
        int err = dsn_mix_continuous_tile_u8(&golden_mix, control, &grid.grid, grid.width, grid.height,
                                             tile_u8_values, tile_scratch, scratch_capacity);
        if (err != DSN_OK) return err;
        hash_u8(hash, tile_u8_values, points * channels);
        for (uint32_t p = 0; p < points; p++)
            grid_point(grid.grid, p % grid.width, p / grid.width, &mix_xs[p], &mix_ys[p]);
        err = dsn_mix_continuous_batch_u8(&golden_mix, control, mix_xs, mix_ys, points, tile_u8_values);
        if (err != DSN_OK) return err;
        hash_u8(hash, tile_u8_values, points * channels);
    }
    return DSN_OK;
}

#if DSN_FILTERING
/* The filtered mix: a minification by 11/4 with shear, one by 3 (level of detail about 1.6) and a
   magnification (unfiltered), per point under each grid's footprint (4 taps), then as tiles. */
const Grid mix_filtered_grid = {
    {5 * q32_one, -3 * q32_one, 3 * q32_one, q32_one / 2, -q32_one / 2, 3 * q32_one}, 6, 4};
const Grid *const mix_filtered_grids[] = {&continuous_grids[2], &mix_filtered_grid, &affine_grids[4]};

int mix_filtered(const dsn_mix_control *control, Fnv *hash) {
    const uint32_t channels = dsn_mix_channels(&golden_mix);
    for (uint32_t g = 0; g < GOLDEN_COUNT(mix_filtered_grids); g++) {
        const Grid &grid = *mix_filtered_grids[g];
        const dsn_footprint footprint = grid_footprint(grid, 4);
        for (uint32_t j = 0; j < grid.height; j++)
            for (uint32_t i = 0; i < grid.width; i++) {
                int32_t values[DSN_MAX_CHANNELS];
                int64_t x, y;
                grid_point(grid.grid, i, j, &x, &y);
                const int err = dsn_mix_filtered_point_fixed(&golden_mix, control, x, y, &footprint, values);
                if (err != DSN_OK) return err;
                hash_fixed(hash, values, channels);
            }
        const int err =
            dsn_mix_filtered_tile_fixed(&golden_mix, control, &grid.grid, 4, grid.width, grid.height,
                                        tile_fixed_values, tile_scratch, scratch_capacity);
        if (err != DSN_OK) return err;
        hash_fixed(hash, tile_fixed_values, grid.width * grid.height * channels);
    }
    return DSN_OK;
}
#endif

const struct {
    const char *name;
    MixEvaluator evaluate;
} mix_kinds[] = {
    {"m-point", mix_lattice_points},
    {"m-tile", mix_lattice_tiles}, /* the same bytes as "m-point" */
    {"m-c-point", mix_continuous_points},
    {"m-c-tile", mix_continuous_tiles}, /* the same bytes as "m-c-point" */
    {"m-float", mix_floats},
#if DSN_FILTERING
    {"m-f-point", mix_filtered}, /* points, then the same as tiles */
#endif
};

/* Writes the mix kinds' lines; returns the number of assets that failed. */
int write_mix_hashes() {
    int failures = 0;
    for (uint32_t k = 0; k < GOLDEN_COUNT(mix_kinds); k++) {
        Fnv all = {fnv_offset_basis};
        for (uint32_t a = 0; a < CROSS_ASSET_COUNT; a++) {
            Fnv hash = {fnv_offset_basis};
            int err = DSN_OK;
            for (uint32_t s = 0; err == DSN_OK && s < GOLDEN_COUNT(mix_settings); s++) {
                err = make_mix(a, mix_settings[s]);
                for (uint32_t c = 0; err == DSN_OK && c < GOLDEN_COUNT(mix_controls); c++)
                    err = mix_kinds[k].evaluate(&mix_controls[c], &hash);
            }
            if (err != DSN_OK) {
                write_error(mix_kinds[k].name, cross_assets[a].name, err);
                failures++;
                continue;
            }
            write_hash(mix_kinds[k].name, cross_assets[a].name, hash.state);
            hash_u64(&all, hash.state);
        }
        write_hash(mix_kinds[k].name, "all", all.state);
    }
    return failures;
}
#endif

} // namespace

int main() {
    int failures = 0;
    for (uint32_t k = 0; k < GOLDEN_COUNT(kinds); k++) {
        Fnv all = {fnv_offset_basis};
        const uint32_t asset_count = kinds[k].mapped ? CROSS_HISTOGRAM_ASSET_COUNT : CROSS_ASSET_COUNT;
        for (uint32_t a = 0; a < asset_count; a++) {
            const cross_asset &bytes = kinds[k].mapped ? cross_histogram_assets[a] : cross_assets[a];
            Fnv hash = {fnv_offset_basis};
            dsn_asset asset;
            int err = dsn_asset_load(&asset, bytes.bytes, bytes.size);
            if (err == DSN_OK) err = hash_asset(kinds[k], &asset, &hash);
            if (err != DSN_OK) {
                write_error(kinds[k].name, bytes.name, err);
                failures++;
                continue;
            }
            write_hash(kinds[k].name, bytes.name, hash.state);
            hash_u64(&all, hash.state);
        }
        write_hash(kinds[k].name, "all", all.state);
    }
#if DSN_MIXING && !defined(GOLDEN_WITHOUT_MIXING)
    failures += write_mix_hashes();
#endif
    write_hash("coords", "all", coordinate_conversions_hash());
    return failures == 0 ? 0 : 1;
}
