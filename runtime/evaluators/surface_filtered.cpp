/* runtime/evaluators/surface_filtered.cpp - the surface noise filtered by a footprint in the tangent plane
   (dsn.h, "Surface noise"): the filtered evaluation's plan (taps along the footprint's long axis, two
   pyramid levels blended) with each tap moved along the frame's tangent and bitangent, and each level read
   at the impulses of the tap's slab as the plane's filtered walk reads it (level_read.h), weighted by the
   window, the taps sharing one walk where they lie close; then the levels' values from their surface
   offsets, blended, averaged and rounded as a filtered point's. Also the API's filtered surface functions.
   Compiled with DSN_SURFACE and DSN_FILTERING. */
#include "core/filtered_internal.h"
#include "core/level_read.h"
#include "core/surface_walk.h"

#if DSN_SURFACE && DSN_FILTERING

namespace {

/* The filtered point's visitor: at taps first .. end - 1, the one or two levels read at the impulse's
   offsets moved by the tap (moves[tap], Q.46 along the tangent, bitangent and normal) and floored to Q32.32,
   weighted by the window there, into that tap's level sums (Q.32, stored-value units); by the kernel's
   reads for 8-bit levels, where it has them. */
struct TapSums {
    const dsn_noise_state *noise;
    const dsn_walked_level *levels;
    uint32_t count, first, end;
    int64_t moves[DSN_FILTER_MAX_TAPS][3];
    dsn_surface_reads_entry *reads; /* the kernel's for 8-bit levels, or null */
    dsn_surface_texels texels[2];
    uint32_t tap; /* the tap that visit adds to */
    dsn_filter_sums sums;

    void visit_listed(const dsn_surface_impulses &listed, uint32_t listed_count, uint32_t cell_shift) {
        for (tap = first; tap < end; tap++) {
            if (reads == 0) {
                visit_each(this, listed, listed_count, cell_shift, moves[tap]);
                continue;
            }
            for (uint32_t l = 0; l < count; l++)
                reads(&texels[l], &listed, listed_count, cell_shift, moves[tap], sums[tap][l]);
        }
    }

    void visit(int64_t along_tangent, int64_t along_bitangent, uint32_t window) {
        const uint32_t channels = noise->asset.channels;
        for (uint32_t l = 0; l < count; l++) {
            uint64_t level[DSN_MAX_CHANNELS] = {0, 0, 0};
            add_level<false>(levels[l], channels, noise->asset.bits, along_tangent, along_bitangent, level,
                             0);
            for (uint32_t c = 0; c < channels; c++) sums[tap][l][c] += windowed(level[c], window);
        }
    }
};

/* The tap's position: the point moved by the plan's offset (Q32.32 texels along the tangent and
   bitangent), each floored to Q.16 and projected in Q.46, then floored to Q32.32, modulo 2^64. */
void tap_position(const int64_t *position, const dsn_surface_frame *frame, int64_t along_tangent,
                  int64_t along_bitangent, int64_t *tap) {
    const int64_t u = floor_shift(along_tangent, 16);
    const int64_t v = floor_shift(along_bitangent, 16);
    for (int i = 0; i < 3; i++) {
        const int64_t moved = u * frame->tangent[i] + v * frame->bitangent[i];
        tap[i] = signed_from_bits(static_cast<uint64_t>(position[i]) +
                                  static_cast<uint64_t>(floor_shift(moved, 14)));
    }
}

/* What moving from the point to the tap adds to an impulse's offsets along the frame's vectors (Q.46):
   the walk takes an impulse's offset from a position floored to Q.16 (surface_walk.h), so the tap's floor
   less the point's, dotted with each vector. Exact: the tap's walk would list the same offsets plus this. */
void tap_move(const int64_t *position, const int64_t *tap, const dsn_surface_frame *frame, int64_t *move) {
    int64_t step[3];
    for (int i = 0; i < 3; i++) /* the point's floor to Q.16 is 0 from its own position rounded down */
        step[i] =
            floor_shift(signed_from_bits(static_cast<uint64_t>(tap[i]) - (static_cast<uint64_t>(position[i]) &
                                                                          ~static_cast<uint64_t>(0xFFFF))),
                        16);
    const int32_t *vectors[3] = {frame->tangent, frame->bitangent, frame->normal};
    for (int v = 0; v < 3; v++) { /* modulo 2^64: a move is read only for taps within a tap's reach */
        uint64_t sum = 0;
        for (int i = 0; i < 3; i++)
            sum +=
                static_cast<uint64_t>(step[i]) * static_cast<uint64_t>(static_cast<int64_t>(vectors[v][i]));
        move[v] = signed_from_bits(sum);
    }
}

/* The reach of a walk over every tap's box (texels along one frame vector): the taps' largest offset along
   it plus a texel (the floors, and the frame's quantization), added to one tap's; 0 where the taps spread
   wider than one tap's reach (their boxes are then walked one by one). */
uint32_t shared_reach(const int64_t *offsets, uint32_t taps, uint32_t reach) {
    uint64_t spread = 0;
    for (uint32_t tap = 0; tap < taps; tap++) {
        const uint64_t magnitude =
            offsets[tap] < 0 ? 0u - static_cast<uint64_t>(offsets[tap]) : static_cast<uint64_t>(offsets[tap]);
        spread = magnitude > spread ? magnitude : spread;
    }
    spread = (spread >> 32) + 1u;
    return spread <= reach ? reach + static_cast<uint32_t>(spread) : 0u;
}

/* The sums of every tap's levels: one walk over the box that holds every tap's box, each impulse read at
   each tap with its offsets moved by the tap (tap_move), where there are several taps and they lie within
   one tap's reach of the point; else a walk per tap. DSN_OK, or DSN_ERR_COST when a tap's walk would examine
   too many impulses (whichever walk is taken). */
int taps_sums(const dsn_noise_state *noise, const int64_t *position, const dsn_surface_frame *frame,
              const dsn_filter_plan *plan, uint32_t reach_x, uint32_t reach_y, TapSums *sums) {
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        int64_t at[3];
        tap_position(position, frame, plan->offset_x[tap], plan->offset_y[tap], at);
        SurfaceWalk walk;
        surface_walk(noise, at, frame, reach_x, reach_y, &walk);
        if (walk_too_costly(noise, &walk)) return DSN_ERR_COST;
        tap_move(position, at, frame, sums->moves[tap]);
    }
    const uint32_t shared_x = shared_reach(plan->offset_x, plan->taps, reach_x),
                   shared_y = shared_reach(plan->offset_y, plan->taps, reach_y);
    SurfaceWalk walk;
    if (plan->taps > 1 && shared_x != 0 && shared_y != 0) {
        surface_walk(noise, position, frame, shared_x, shared_y, &walk);
        if (!walk_too_costly(noise, &walk)) {
            sums->first = 0;
            sums->end = plan->taps;
            visit_impulses(noise, &walk, sums);
            return DSN_OK;
        }
    }
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        int64_t at[3];
        tap_position(position, frame, plan->offset_x[tap], plan->offset_y[tap], at);
        surface_walk(noise, at, frame, reach_x, reach_y, &walk);
        sums->moves[tap][0] = sums->moves[tap][1] = sums->moves[tap][2] = 0;
        sums->first = tap;
        sums->end = tap + 1u;
        visit_impulses(noise, &walk, sums);
    }
    return DSN_OK;
}

/* The filtered value under a plan whose level of detail the pyramid holds: DSN_OK, or DSN_ERR_COST when a
   tap's walk would examine too many impulses. */
int filtered_value(const dsn_noise_state *noise, const int64_t *position, const dsn_surface_frame *frame,
                   const dsn_filter_plan *plan, int32_t *out) {
    dsn_walked_level walked[2];
    const uint32_t count = dsn_internal_filter_walked_levels(noise, plan, walked);
    uint32_t radius_x, radius_y;
    dsn_filter_walk_radii(walked, count, &radius_x, &radius_y);
    TapSums sums;
    sums.noise = noise;
    sums.levels = walked;
    sums.count = count;
    sums.reads = noise->asset.bits == 8 ? dsn_kernel_entries_of(noise->tile_kernel)->surface_reads : 0;
    for (uint32_t l = 0; l < count; l++) {
        const dsn_surface_texels level = {walked[l].values, walked[l].width,       walked[l].height,
                                          walked[l].stride, noise->asset.channels, walked[l].level};
        sums.texels[l] = level;
    }
    __builtin_memset(sums.sums, 0, sizeof sums.sums);
    const int err = taps_sums(noise, position, frame, plan, radius_x + 1u, radius_y + 1u, &sums);
    if (err != DSN_OK) return err;
    int64_t offsets[2][DSN_MAX_CHANNELS], totals[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t l = 0; l < count; l++)
        surface_offset(noise, dsn_internal_level_offset(noise, walked[l].level), offsets[l]);
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        for (uint32_t l = 0; l < count; l++) {
            int64_t values[DSN_MAX_CHANNELS] = {0, 0, 0};
            dsn_internal_filter_level_values_from(noise, &walked[l], sums.sums[tap][l], offsets[l], values);
            dsn_internal_filter_add_level(noise, plan, l, values, totals);
        }
        if (count == 1) dsn_internal_filter_add_mean(noise, plan, totals);
    }
    dsn_internal_filter_finish(noise, plan, totals, out);
    return DSN_OK;
}

} // namespace

extern "C" {

int dsn_surface_filtered_point_fixed(const dsn_noise *handle, const int64_t *position,
                                     const dsn_surface_frame *frame, const dsn_footprint *footprint,
                                     int32_t *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    int err = dsn_internal_surface_check(noise, position, frame);
    dsn_filter_plan plan;
    if (err == DSN_OK) err = dsn_internal_filter_plan(footprint, noise->asset.pyramid_levels, &plan);
    if (err == DSN_OK && !dsn_internal_filter_fade(noise, &plan, out))
        err = plan.lod_q8 == 0 && plan.taps == 1 ? dsn_internal_surface_point(noise, position, frame, out)
                                                 : filtered_value(noise, position, frame, &plan, out);
    if (err != DSN_OK)
        for (uint32_t c = 0; c < dsn_values_per_point(noise); c++) out[c] = 0;
    return err;
}

int dsn_surface_filtered_point_float(const dsn_noise *handle, const double *position, const float *normal,
                                     const float *tangent, const dsn_footprint *footprint, float *out) {
    int32_t fixed[DSN_MAX_CHANNELS] = {0, 0, 0};
    if (out == 0) return DSN_ERR_NULL;
    dsn_surface_frame frame;
    int64_t point[3];
    int err = surface_inputs(position, normal, tangent, point, &frame);
    if (err == DSN_OK) err = dsn_surface_filtered_point_fixed(handle, point, &frame, footprint, fixed);
    dsn_store_pixel(out, dsn_output_float, 0, fixed, dsn_values_per_point(dsn_state(handle)));
    return err;
}

} // extern "C"

#endif /* DSN_SURFACE && DSN_FILTERING */
