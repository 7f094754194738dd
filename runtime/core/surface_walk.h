/* runtime/core/surface_walk.h - the walk of the surface noise (dsn.h, "Surface noise"): the cubes of 3-D
   space around a point that its oriented box can reach, each cube's impulses projected on the point's
   frame, and the slab's window across it; a visitor reads the texton (the unfiltered point,
   surface_point.cpp) or the pyramid's levels (the filtered one, surface_filtered.cpp) at each impulse
   that the window keeps. Also the surface offset and the float functions' inputs. Internal to libdsn; not
   installed (everything here has internal linkage but the two functions of surface_point.cpp at its end). */
#ifndef DSN_SURFACE_WALK_H
#define DSN_SURFACE_WALK_H

#include "core/continuous_internal.h"
#include "core/poisson_count.h"
#include "kernels/kernels.h"

#if DSN_SURFACE

namespace {

/* 2^16 I2 / 2 = 2^16 48/35, rounded: s = |w| / H in Q16 is |w| (Q.16) times this over 2^(16 + cell_shift). */
const uint64_t window_scale = 89878;

inline uint64_t magnitude(int64_t value) {
    return value < 0 ? 0u - static_cast<uint64_t>(value) : static_cast<uint64_t>(value);
}

/* The row part of the keys of cubes (., cy, cz): the plane's row key with the layer mixed in, so that a
   row of cubes keeps the plane's bijection along x; the key of cube (cx, cy, cz) is
   dsn_cell_key_in_row(cx, this). */
inline uint32_t cube_row_key(const dsn_noise_state *noise, uint32_t cube_y, uint32_t cube_z) {
    return dsn_mix32(dsn_row_key(noise, cube_y) + cube_z * 0x9E3779B9u);
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

inline CubeRange cube_range(uint64_t position, uint64_t extent, uint32_t cell_shift) {
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
    int64_t reach[2]; /* Q32.32: the visitor reads nothing at offsets |u| or |v| this far or farther */
};

/* Half the box's extent along each frame vector (texels: `reach_x` and `reach_y`, what the texton or the
   levels read reaches along the tangent and bitangent, and 3/4 c > H along the normal) and, per space
   axis, the box's reach: the sum of those along the axis plus a texel for the floors. */
inline void surface_walk(const dsn_noise_state *noise, const int64_t *position,
                         const dsn_surface_frame *frame, uint32_t reach_x, uint32_t reach_y,
                         SurfaceWalk *walk) {
    const uint32_t shift = noise->cell_shift;
    const int32_t *vectors[3] = {frame->tangent, frame->bitangent, frame->normal};
    /* Q32.32 over 2^30 per unit of the frame: the reaches in units of 2^2 (a texel times 2^30 is 2^32 / 4).
     */
    const uint64_t reach[3] = {4u * static_cast<uint64_t>(reach_x), 4u * static_cast<uint64_t>(reach_y),
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
    walk->reach[0] = walk->reach[1] = static_cast<int64_t>(1) << 62; /* the visitor's own test: none here */
}

/* Listed impulses waiting for the visitor: the kernels read them a vector at a time, and a cube keeps
   about 2 of the usual 31 x 31 texton's, so the walk hands them over in fuller lists (the offsets are the
   point's, whatever their cube). */
struct PendingImpulses {
    dsn_surface_impulses listed;
    uint32_t count;
};

template <typename Visitor>
void visit_pending(PendingImpulses *pending, uint32_t cell_shift, Visitor *visitor) {
    if (pending->count != 0) visitor->visit_listed(pending->listed, pending->count, cell_shift);
    pending->count = 0;
}

/* The impulses of one cube (its key and origin set by visit_impulses), listed by the kernel
   (surface_impulses.h) up to dsn_surface_impulses_most at a time and added to the pending list, which
   goes to the visitor's visit_listed when the next would not fit: those within the walk's reaches and 3/4
   of a cube across the slab, where the window is 0 (it is 0 from 35/48 of a cube, and 2^-16 texel more for
   the floors). An impulse's offset from the point, floored to Q.16, is the cube origin's less its position
   in the cube (a whole number of 2^-16 texels), so its dot products with the frame vectors (Q.46, floored
   to Q32.32 where they are read) are the origin's less the position's, exactly. */
template <typename Visitor>
void visit_cube(const dsn_noise_state *noise, dsn_surface_cube *impulses_of,
                dsn_surface_impulses_entry *list_impulses, PendingImpulses *pending, Visitor *visitor) {
    const uint32_t shift = noise->cell_shift;
    const uint32_t count = dsn_cell_impulse_count(noise, impulses_of->key);
    const uint32_t most = dsn_surface_impulses_most;
    dsn_surface_impulses listed;
    for (uint32_t first = 0; first < count; first += most) {
        impulses_of->first = first;
        impulses_of->count = count - first < most ? count - first : most;
        const uint32_t kept = list_impulses(impulses_of, &listed);
        if (pending->count + kept > most) visit_pending(pending, shift, visitor);
        for (uint32_t k = 0; k < kept; k++) {
            pending->listed.along_tangent[pending->count + k] = listed.along_tangent[k];
            pending->listed.along_bitangent[pending->count + k] = listed.along_bitangent[k];
            pending->listed.across[pending->count + k] = listed.across[k];
        }
        pending->count += kept;
    }
}

/* An impulse's offset (Q.46) moved by `moved` (Q.46) and floored to Q32.32. */
inline int64_t moved_offset(int64_t offset, int64_t moved) {
    return floor_shift(signed_from_bits(static_cast<uint64_t>(offset) + static_cast<uint64_t>(moved)), 14);
}

/* The visitor's visit of each listed impulse that the window keeps, its offsets moved by moved[0 .. 2]
   (Q.46; a filtered point's tap, else 0) and floored to Q32.32 (what a visitor's visit_listed does where
   no kernel reads them all at once). */
template <typename Visitor>
void visit_each(Visitor *visitor, const dsn_surface_impulses &listed, uint32_t count, uint32_t cell_shift,
                const int64_t *moved) {
    for (uint32_t k = 0; k < count; k++) {
        const uint32_t window = slab_window(moved_offset(listed.across[k], moved[2]), cell_shift);
        if (window != 0)
            visitor->visit(moved_offset(listed.along_tangent[k], moved[0]),
                           moved_offset(listed.along_bitangent[k], moved[1]), window);
    }
}

/* A texton read weighted by the window: floor(sum * window / 2^16), the sum of one impulse (below 2^47 in
   magnitude: the product fits 64 bits). */
inline uint64_t windowed(uint64_t sum, uint32_t window) {
    return static_cast<uint64_t>(floor_shift(signed_from_bits(sum * window), 16));
}

/* Whether the walk would visit more than DSN_MAX_POINT_IMPULSES cubes, or examine more impulses than that
   on average: its cubes times lambda c^2, lambda = impacts / |S| (products below 2^62 once the cubes are
   bounded; a filtered walk's coarse levels can reach 2^16 texels and more, so the counts are checked one
   axis at a time first). */
inline bool walk_too_costly(const dsn_noise_state *noise, const SurfaceWalk *walk) {
    uint64_t cubes = 1;
    for (int i = 0; i < 3; i++) {
        if (walk->cubes[i].count > DSN_MAX_POINT_IMPULSES) return true;
        cubes *= walk->cubes[i].count; /* below 2^20 times 2^20 */
        if (cubes > DSN_MAX_POINT_IMPULSES) return true;
    }
    const uint64_t side = static_cast<uint64_t>(1) << noise->cell_shift;
    return cubes * side * side * noise->impacts_q16 >
           (static_cast<uint64_t>(noise->asset.support_size) * DSN_MAX_POINT_IMPULSES) << 16;
}

/* Every impulse of the walk's cubes that the box may reach, to the visitor (visit_cube). A cube is skipped
   when its centre lies beyond the box's bound along a frame vector: the centre's offsets from the point along
   the three vectors (Q.46) are exact integers, so they are stepped from cube to cube by adding a cube's
   side times the vector's component; its origin's (the cube's corner, half a side from its centre along
   each axis, a whole number of 2^-16 texels) are those plus a constant. */
template <typename Visitor>
void visit_impulses(const dsn_noise_state *noise, const SurfaceWalk *walk, Visitor *visitor) {
    dsn_surface_impulses_entry *const list_impulses =
        dsn_kernel_entries_of(noise->tile_kernel)->surface_impulses;
    const uint32_t shift = noise->cell_shift, mask = 0xFFFFFFFFu >> shift;
    dsn_surface_cube impulses_of = {{0, 0, 0},
                                    {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}},
                                    walk->reach[0],
                                    walk->reach[1],
                                    static_cast<int64_t>(static_cast<uint64_t>(3) << (30u + shift)),
                                    0,
                                    0,
                                    0,
                                    shift};
    PendingImpulses pending;
    pending.count = 0;
    int64_t first_offset[3], along[3][3], corner[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++) {
        const uint64_t middle = (static_cast<uint64_t>(walk->cubes[i].first << shift) << 32) +
                                (static_cast<uint64_t>(1) << (31u + shift));
        first_offset[i] =
            floor_shift(signed_from_bits(walk->position[i] - middle), 16); /* Q.16, below 2^28 */
    }
    for (int v = 0; v < 3; v++)
        for (int i = 0; i < 3; i++) {
            along[v][i] = walk->frame[v][i] * (static_cast<int64_t>(1) << (16u + shift));
            corner[v] += walk->frame[v][i] * (static_cast<int64_t>(1) << (15u + shift));
            impulses_of.frame[v][i] = static_cast<int32_t>(walk->frame[v][i]);
        }
    int64_t plane_dot[3];
    for (int v = 0; v < 3; v++)
        plane_dot[v] = first_offset[0] * walk->frame[v][0] + first_offset[1] * walk->frame[v][1] +
                       first_offset[2] * walk->frame[v][2];
    for (uint32_t z = 0; z < walk->cubes[2].count; z++) {
        const uint32_t cube_z = (walk->cubes[2].first + z) & mask;
        int64_t row_dot[3] = {plane_dot[0], plane_dot[1], plane_dot[2]};
        for (uint32_t y = 0; y < walk->cubes[1].count; y++) {
            const uint32_t row_key = cube_row_key(noise, (walk->cubes[1].first + y) & mask, cube_z);
            int64_t dot[3] = {row_dot[0], row_dot[1], row_dot[2]};
            for (uint32_t x = 0; x < walk->cubes[0].count; x++) {
                if (magnitude(dot[0]) <= walk->box_bound[0] && magnitude(dot[1]) <= walk->box_bound[1] &&
                    magnitude(dot[2]) <= walk->box_bound[2]) {
                    impulses_of.key = dsn_cell_key_in_row(noise, (walk->cubes[0].first + x) & mask, row_key);
                    for (int v = 0; v < 3; v++) impulses_of.origin_dot[v] = dot[v] + corner[v];
                    visit_cube(noise, &impulses_of, list_impulses, &pending, visitor);
                }
                for (int v = 0; v < 3; v++) dot[v] -= along[v][0];
            }
            for (int v = 0; v < 3; v++) row_dot[v] -= along[v][1];
        }
        for (int v = 0; v < 3; v++) plane_dot[v] -= along[v][2];
    }
    visit_pending(&pending, shift, visitor);
}

/* The surface offset of a level's offset (dsn.h): less 3/32 of its expected sum (the mean less the
   offset), which the slab's window makes 35/32 of the plane's. */
inline void surface_offset(const dsn_noise_state *noise, const int64_t *plane_offset, int64_t *offset) {
    const int64_t limit = static_cast<int64_t>(1) << 61;
    for (uint32_t c = 0; c < noise->asset.channels; c++) {
        const int64_t mean =
            static_cast<int64_t>(noise->asset.mean[c]) * (static_cast<int64_t>(1) << (noise->gain_shift - 8));
        int64_t expected = mean - plane_offset[c]; /* |mean| < 2^55, |offset| <= 2^61 */
        expected = expected > limit ? limit : expected < -limit ? -limit : expected;
        offset[c] = plane_offset[c] - floor_shift(3 * expected, 5);
    }
}

/* The float functions' inputs: the position converted by dsn_coordinate_from_double, the frame made by
   dsn_surface_frame_from_float (its errors; DSN_ERR_NULL for a null position). */
inline int surface_inputs(const double *position, const float *normal, const float *tangent, int64_t *point,
                          dsn_surface_frame *frame) {
    if (position == 0) return DSN_ERR_NULL;
    for (int i = 0; i < 3; i++) point[i] = dsn_coordinate_from_double(position[i]);
    return dsn_surface_frame_from_float(normal, tangent, frame);
}

} // namespace

/* DSN_OK when the surface functions may evaluate `noise` at `position` in `frame`: the continuous mode's
   check, then DSN_ERR_NULL (null position or frame) or DSN_ERR_ARGUMENT (a frame component out of range). */
int dsn_internal_surface_check(const dsn_noise_state *noise, const int64_t *position,
                               const dsn_surface_frame *frame);

/* The Q16.16 values of the surface point, for arguments that passed the check: DSN_OK, or DSN_ERR_COST
   with nothing written (surface_point.cpp). */
int dsn_internal_surface_point(const dsn_noise_state *noise, const int64_t *position,
                               const dsn_surface_frame *frame, int32_t *out);

#endif /* DSN_SURFACE */

#endif /* DSN_SURFACE_WALK_H */
