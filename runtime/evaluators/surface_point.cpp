/* runtime/evaluators/surface_point.cpp - the surface noise (dsn.h, "Surface noise"): the impulses of the
   cubes of 3-D space around a point, each projected on the point's tangent plane, its bilinear texton
   read there and weighted by the slab's window across the plane. Also the API's surface functions. */
#include "core/bilinear_texton.h"
#include "core/continuous_internal.h"
#include "core/poisson_count.h"

#if DSN_SURFACE

namespace {

/* 2^16 I2 / 2 = 2^16 48/35, rounded: s = |w| / H in Q16 is |w| (Q.16) times this over 2^(16 + cell_shift). */
const uint64_t window_scale = 89878;

/* The signed value of `bits` (two's complement, modulo 2^64) over 2^shift, rounded toward minus infinity,
   for shift in 1 .. 63. */
inline int64_t floor_shift(uint64_t bits, uint32_t shift) {
    const uint64_t bias = static_cast<uint64_t>(1) << 63;
    return static_cast<int64_t>((bits + bias) >> shift) - static_cast<int64_t>(bias >> shift);
}

inline uint64_t magnitude(int64_t value) {
    return value < 0 ? 0u - static_cast<uint64_t>(value) : static_cast<uint64_t>(value);
}

/* Key of cube (cx, cy, cz): the plane's key of (cx, cy) with the layer mixed into its row part, so a
   row of cubes keeps the plane's bijection along x. */
inline uint32_t cube_key(const dsn_noise_state *noise, uint32_t cube_x, uint32_t cube_y, uint32_t cube_z) {
    return dsn_cell_key_in_row(noise, cube_x, dsn_mix32(dsn_row_key(noise, cube_y) + cube_z * 0x9E3779B9u));
}

/* The slab's window W(|w| / H) in Q16 (dsn.h): 65536 up to half the slab, a smoothstep down to 0 at
   its faces. */
inline uint32_t slab_window(int64_t across, uint32_t cell_shift) {
    const uint64_t s = ((magnitude(across) >> 16) * window_scale) >> (16u + cell_shift);
    if (s >= 65536u) return 0;
    if (s <= 32768u) return 65536u;
    const uint64_t u = 2u * s - 65536u, square = (u * u) >> 16;
    return static_cast<uint32_t>(65536u - ((square * (196608u - 2u * u)) >> 16));
}

/* The cubes an axis of the walk crosses: those within `extent` (Q32.32) of the position. */
struct CubeRange {
    uint32_t first, count;
};

CubeRange cube_range(uint64_t position, uint64_t extent, uint32_t cell_shift) {
    const uint32_t mask = 0xFFFFFFFFu >> cell_shift;
    const uint32_t first = static_cast<uint32_t>((position - extent) >> 32) >> cell_shift;
    const uint32_t last = static_cast<uint32_t>((position + extent) >> 32) >> cell_shift;
    const CubeRange range = {first, ((last - first) & mask) + 1u};
    return range;
}

/* What the walk of one point reads: its position, its frame, the oriented box of its reach and the
   cubes around it. */
struct SurfaceWalk {
    uint64_t position[3];
    int64_t frame[3][3];   /* tangent, bitangent, normal */
    uint64_t box_bound[3]; /* Q.46: how far a cube's centre may lie along each frame vector */
    CubeRange cubes[3];
};

/* Half the box's extent along each frame vector (texels: the texton's reach along the tangent and
   bitangent, 3/4 c > H along the normal) and, per space axis, the box's reach: the sum of those along the
   axis plus a texel for the floors. */
void surface_walk(const dsn_noise_state *noise, const int64_t *position, const dsn_surface_frame *frame,
                  SurfaceWalk *walk) {
    const uint32_t shift = noise->cell_shift;
    const int32_t *vectors[3] = {frame->tangent, frame->bitangent, frame->normal};
    /* Q32.32 over 2^30 per unit of the frame: the reaches in units of 2^2 (a texel times 2^30 is 2^32 / 4).
     */
    const uint64_t reach[3] = {4u * (noise->radius[0] + 1u), 4u * (noise->radius[1] + 1u),
                               static_cast<uint64_t>(3u) << shift};
    for (int i = 0; i < 3; i++) {
        walk->position[i] = static_cast<uint64_t>(position[i]);
        uint64_t extent = static_cast<uint64_t>(1) << 32, spread = 0;
        for (int v = 0; v < 3; v++) {
            walk->frame[v][i] = vectors[v][i];
            extent += reach[v] * magnitude(vectors[v][i]);
            spread += magnitude(vectors[i][v]);
        }
        walk->cubes[i] = cube_range(walk->position[i], extent, shift);
        /* The vector's reach (Q.46), half a cube times the cube's extent along it, and a texel. */
        walk->box_bound[i] = (reach[i] << 44) + (spread << (15u + shift)) + (static_cast<uint64_t>(1) << 46);
    }
}

/* The impulses of one cube: each one's texton at its projection, weighted by the window, added to the
   channel sums (Q.32). An impulse's offset from the point, floored to Q.16, is the cube origin's less its
   position in the cube (a whole number of 2^-16 texels), so its dot products with the frame vectors
   (Q.46, then floored to Q32.32) are the origin's less the position's, exactly. */
void add_cube(const dsn_noise_state *noise, const SurfaceWalk *walk, const uint32_t *cube, uint64_t *sums) {
    const uint32_t shift = noise->cell_shift;
    const uint32_t key = cube_key(noise, cube[0], cube[1], cube[2]);
    const uint32_t count = dsn_cell_impulse_count(noise, key);
    int64_t origin_dot[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++) {
        const int64_t origin =
            floor_shift(walk->position[i] - (static_cast<uint64_t>(cube[i] << shift) << 32), 16);
        for (int v = 0; v < 3; v++) origin_dot[v] += origin * walk->frame[v][i];
    }
    for (uint32_t k = 0; k < count; k++) {
        const uint64_t pair = dsn_position_pair(key, k);
        const int64_t inside[3] = {static_cast<int64_t>((pair & 0xFFFFu) << shift),
                                   static_cast<int64_t>(((pair >> 16) & 0xFFFFu) << shift),
                                   static_cast<int64_t>(((pair >> 32) & 0xFFFFu) << shift)};
        const int64_t *normal = walk->frame[2], *tangent = walk->frame[0], *bitangent = walk->frame[1];
        const uint64_t across =
            static_cast<uint64_t>(origin_dot[2]) -
            static_cast<uint64_t>(inside[0] * normal[0] + inside[1] * normal[1] + inside[2] * normal[2]);
        const uint32_t window = slab_window(floor_shift(across, 14), shift);
        if (window == 0) continue;
        const uint64_t u =
            static_cast<uint64_t>(origin_dot[0]) -
            static_cast<uint64_t>(inside[0] * tangent[0] + inside[1] * tangent[1] + inside[2] * tangent[2]);
        const uint64_t v = static_cast<uint64_t>(origin_dot[1]) -
                           static_cast<uint64_t>(inside[0] * bitangent[0] + inside[1] * bitangent[1] +
                                                 inside[2] * bitangent[2]);
        uint32_t row, row_weight, column, column_weight;
        if (!bracket(floor_shift(u, 14), noise->radius[0], &column, &column_weight) ||
            !bracket(floor_shift(v, 14), noise->radius[1], &row, &row_weight))
            continue;
        uint64_t texton[DSN_MAX_CHANNELS] = {0, 0, 0};
        add_bilinear(&noise->asset, row, row_weight, column, column_weight, texton);
        for (uint32_t c = 0; c < noise->asset.channels; c++)
            sums[c] += static_cast<uint64_t>(floor_shift(texton[c] * window, 16));
    }
}

/* Whether the walk's cubes hold more than DSN_MAX_POINT_IMPULSES impulses on average: cubes lambda c^2,
   lambda = impacts / |S| (products below 2^56: at most about 2^30 cubes of one texel, or fewer larger
   ones). */
bool walk_too_costly(const dsn_noise_state *noise, const SurfaceWalk *walk) {
    const uint64_t cubes =
        static_cast<uint64_t>(walk->cubes[0].count) * walk->cubes[1].count * walk->cubes[2].count;
    const uint64_t side = static_cast<uint64_t>(1) << noise->cell_shift;
    return cubes * side * side * noise->impacts_q16 >
           (static_cast<uint64_t>(noise->asset.support_size) * DSN_MAX_POINT_IMPULSES) << 16;
}

/* The sums of every impulse of the walk's cubes that the box may reach. A cube is skipped when its
   centre lies beyond the box's bound along a frame vector: the centre's offsets from the point along
   the three vectors (Q.46) are exact integers, so they are stepped from cube to cube by adding a cube's
   side times the vector's component. */
void surface_sums(const dsn_noise_state *noise, const SurfaceWalk *walk, uint64_t *sums) {
    const uint32_t shift = noise->cell_shift, mask = 0xFFFFFFFFu >> shift;
    int64_t first_offset[3], along[3][3];
    for (int i = 0; i < 3; i++) {
        const uint64_t middle = (static_cast<uint64_t>(walk->cubes[i].first << shift) << 32) +
                                (static_cast<uint64_t>(1) << (31u + shift));
        first_offset[i] = floor_shift(walk->position[i] - middle, 16); /* Q.16, below 2^28 */
    }
    for (int v = 0; v < 3; v++)
        for (int i = 0; i < 3; i++)
            along[v][i] = walk->frame[v][i] * (static_cast<int64_t>(1) << (16u + shift));
    int64_t plane_dot[3];
    for (int v = 0; v < 3; v++)
        plane_dot[v] = first_offset[0] * walk->frame[v][0] + first_offset[1] * walk->frame[v][1] +
                       first_offset[2] * walk->frame[v][2];
    uint32_t cube[3];
    for (uint32_t z = 0; z < walk->cubes[2].count; z++) {
        cube[2] = (walk->cubes[2].first + z) & mask;
        int64_t row_dot[3] = {plane_dot[0], plane_dot[1], plane_dot[2]};
        for (uint32_t y = 0; y < walk->cubes[1].count; y++) {
            cube[1] = (walk->cubes[1].first + y) & mask;
            int64_t dot[3] = {row_dot[0], row_dot[1], row_dot[2]};
            for (uint32_t x = 0; x < walk->cubes[0].count; x++) {
                cube[0] = (walk->cubes[0].first + x) & mask;
                if (magnitude(dot[0]) <= walk->box_bound[0] && magnitude(dot[1]) <= walk->box_bound[1] &&
                    magnitude(dot[2]) <= walk->box_bound[2])
                    add_cube(noise, walk, cube, sums);
                for (int v = 0; v < 3; v++) dot[v] -= along[v][0];
            }
            for (int v = 0; v < 3; v++) row_dot[v] -= along[v][1];
        }
        for (int v = 0; v < 3; v++) plane_dot[v] -= along[v][2];
    }
}

/* The surface offset (dsn.h): the noise's offset less 3/32 of its expected sum, which the slab's window
   makes 35/32 of the plane's. */
void surface_offset(const dsn_noise_state *noise, int64_t *offset) {
    const int64_t limit = static_cast<int64_t>(1) << 61;
    for (uint32_t c = 0; c < noise->asset.channels; c++) {
        const int64_t mean =
            static_cast<int64_t>(noise->asset.mean[c]) * (static_cast<int64_t>(1) << (noise->gain_shift - 8));
        int64_t expected = mean - noise->offset[c]; /* |mean| < 2^55, |offset| < 2^63 */
        expected = expected > limit ? limit : expected < -limit ? -limit : expected;
        offset[c] = noise->offset[c] - floor_shift(static_cast<uint64_t>(3 * expected), 5);
    }
}

bool frame_in_range(const dsn_surface_frame *frame) {
    const int32_t *vectors[3] = {frame->tangent, frame->bitangent, frame->normal};
    for (int v = 0; v < 3; v++)
        for (int i = 0; i < 3; i++)
            if (vectors[v][i] > DSN_FRAME_ONE || vectors[v][i] < -DSN_FRAME_ONE) return false;
    return true;
}

} // namespace

extern "C" {

int dsn_surface_point_fixed(const dsn_noise *handle, const int64_t *position, const dsn_surface_frame *frame,
                            int32_t *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    int err = dsn_internal_continuous_check(noise);
    if (err == DSN_OK && (position == 0 || frame == 0)) err = DSN_ERR_NULL;
    if (err == DSN_OK && !frame_in_range(frame)) err = DSN_ERR_ARGUMENT;
    SurfaceWalk walk;
    if (err == DSN_OK) {
        surface_walk(noise, position, frame, &walk);
        if (walk_too_costly(noise, &walk)) err = DSN_ERR_COST;
    }
    if (err != DSN_OK) {
        for (uint32_t c = 0; c < dsn_values_per_point(noise); c++) out[c] = 0;
        return err;
    }
    uint64_t sums[DSN_MAX_CHANNELS] = {0, 0, 0};
    int64_t offset[DSN_MAX_CHANNELS];
    surface_sums(noise, &walk, sums);
    surface_offset(noise, offset);
    normalize_q32_from(noise, offset, sums, out);
    dsn_map_output(noise, out);
    return DSN_OK;
}

int dsn_surface_point_float(const dsn_noise *handle, const double *position, const float *normal,
                            const float *tangent, float *out) {
    int32_t fixed[DSN_MAX_CHANNELS] = {0, 0, 0};
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    dsn_surface_frame frame;
    int err = position == 0 ? DSN_ERR_NULL : dsn_surface_frame_from_float(normal, tangent, &frame);
    if (err == DSN_OK) {
        const int64_t point[3] = {dsn_coordinate_from_double(position[0]),
                                  dsn_coordinate_from_double(position[1]),
                                  dsn_coordinate_from_double(position[2])};
        err = dsn_surface_point_fixed(handle, point, &frame, fixed);
    }
    dsn_store_pixel(out, dsn_output_float, 0, fixed, dsn_values_per_point(noise));
    return err;
}

int dsn_surface_point_u8(const dsn_noise *handle, const int64_t *position, const dsn_surface_frame *frame,
                         uint8_t *out) {
    int32_t fixed[DSN_MAX_CHANNELS] = {0, 0, 0};
    if (out == 0) return DSN_ERR_NULL;
    const int err = dsn_surface_point_fixed(handle, position, frame, fixed);
    dsn_store_pixel(out, dsn_output_u8, 0, fixed, dsn_values_per_point(dsn_state(handle)));
    return err;
}

int dsn_surface_batch_fixed(const dsn_noise *handle, const int64_t *positions,
                            const dsn_surface_frame *frames, uint32_t count, int32_t *out) {
    const uint32_t channels = dsn_values_per_point(dsn_state(handle));
    if (count == 0) return DSN_OK;
    if (out == 0) return DSN_ERR_NULL;
    int err = positions == 0 || frames == 0 ? DSN_ERR_NULL : DSN_OK;
    for (uint32_t k = 0; k < count && err == DSN_OK; k++)
        err = dsn_surface_point_fixed(handle, positions + 3u * k, frames + k, out + k * channels);
    if (err != DSN_OK)
        for (uint32_t k = 0; k < count * channels; k++) out[k] = 0;
    return err;
}

} // extern "C"

#endif /* DSN_SURFACE */
