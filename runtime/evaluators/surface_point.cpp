/* runtime/evaluators/surface_point.cpp - the surface noise (dsn.h, "Surface noise"): the impulses of the
   cubes of 3-D space around a point, each projected on the point's tangent plane, its bilinear texton
   read there and weighted by the slab's window across the plane. Also the API's surface functions. */
#include "core/bilinear_texton.h"
#include "core/surface_walk.h"

#if DSN_SURFACE

namespace {

/* The unfiltered point's visitor: the texton read bilinearly at the impulse's offsets along the tangent
   (columns) and bitangent (rows), weighted by the window, into the channel sums (Q.32). */
struct TextonSums {
    const dsn_noise_state *noise;
    dsn_surface_reads_entry *reads; /* the kernel's for an 8-bit texton, or null */
    dsn_surface_texels texels;
    uint64_t sums[DSN_MAX_CHANNELS];

    void visit_listed(const dsn_surface_impulses &listed, uint32_t count, uint32_t cell_shift) {
        const int64_t unmoved[3] = {0, 0, 0};
        if (reads != 0)
            reads(&texels, &listed, count, cell_shift, unmoved, sums);
        else
            visit_each(this, listed, count, cell_shift, unmoved);
    }

    void visit(int64_t along_tangent, int64_t along_bitangent, uint32_t window) {
        uint32_t row, row_weight, column, column_weight;
        if (!bracket(along_tangent, noise->radius[0], &column, &column_weight) ||
            !bracket(along_bitangent, noise->radius[1], &row, &row_weight))
            return;
        uint64_t texton[DSN_MAX_CHANNELS] = {0, 0, 0};
        add_bilinear(&noise->asset, row, row_weight, column, column_weight, texton);
        for (uint32_t c = 0; c < noise->asset.channels; c++) sums[c] += windowed(texton[c], window);
    }
};

/* Whether every component of the frame lies in [-1, 1] (Q2.30). */
bool frame_in_range(const dsn_surface_frame *frame) {
    const int32_t *vectors[3] = {frame->tangent, frame->bitangent, frame->normal};
    for (int v = 0; v < 3; v++)
        for (int i = 0; i < 3; i++)
            if (vectors[v][i] > DSN_FRAME_ONE || vectors[v][i] < -DSN_FRAME_ONE) return false;
    return true;
}

} // namespace

int dsn_internal_surface_check(const dsn_noise_state *noise, const int64_t *position,
                               const dsn_surface_frame *frame) {
    const int err = dsn_internal_continuous_check(noise);
    if (err != DSN_OK) return err;
    if (position == 0 || frame == 0) return DSN_ERR_NULL;
    return frame_in_range(frame) ? DSN_OK : DSN_ERR_ARGUMENT;
}

int dsn_internal_surface_point(const dsn_noise_state *noise, const int64_t *position,
                               const dsn_surface_frame *frame, int32_t *out) {
    SurfaceWalk walk;
    surface_walk(noise, position, frame, noise->radius[0] + 1u, noise->radius[1] + 1u, &walk);
    if (walk_too_costly(noise, &walk)) return DSN_ERR_COST;
    for (int axis = 0; axis < 2; axis++) /* bracket's: offsets in (-(radius + 1), radius + 1) */
        walk.reach[axis] = static_cast<int64_t>(noise->radius[axis] + 1u) * static_cast<int64_t>(one_texel);
    const dsn_asset *asset = &noise->asset;
    TextonSums texton = {noise,
                         asset->bits == 8 ? dsn_kernel_entries_of(noise->tile_kernel)->surface_reads : 0,
                         {asset->texton, asset->width, asset->height, asset->width, asset->channels, 0},
                         {0, 0, 0}};
    int64_t offset[DSN_MAX_CHANNELS];
    visit_impulses(noise, &walk, &texton);
    surface_offset(noise, noise->offset, offset);
    normalize_q32_from(noise, offset, texton.sums, out);
    dsn_map_output(noise, out);
    return DSN_OK;
}

extern "C" {

int dsn_surface_point_fixed(const dsn_noise *handle, const int64_t *position, const dsn_surface_frame *frame,
                            int32_t *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    int err = dsn_internal_surface_check(noise, position, frame);
    if (err == DSN_OK) err = dsn_internal_surface_point(noise, position, frame, out);
    if (err != DSN_OK)
        for (uint32_t c = 0; c < dsn_values_per_point(noise); c++) out[c] = 0;
    return err;
}

int dsn_surface_point_float(const dsn_noise *handle, const double *position, const float *normal,
                            const float *tangent, float *out) {
    int32_t fixed[DSN_MAX_CHANNELS] = {0, 0, 0};
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    dsn_surface_frame frame;
    int64_t point[3];
    int err = surface_inputs(position, normal, tangent, point, &frame);
    if (err == DSN_OK) err = dsn_surface_point_fixed(handle, point, &frame, fixed);
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
