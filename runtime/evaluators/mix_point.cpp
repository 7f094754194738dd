/* runtime/evaluators/mix_point.cpp - the mixing of materials (dsn.h, "Mixing") by walks: one walk over the
   impulses of material 0's process within the largest reach, each impulse picking its material from the
   weights at its position (mix_weights.h) and adding that material's texton to the material's sums; then
   each material's sums normalized with the point's weight on its mean, and summed. Lattice and continuous,
   per point (through the kernels' vector walks where the materials' textons share one size, kernels.h's
   dsn_point_materials; else the scalar walks here) and by groups of points walked at once: continuous
   points near each other (a batch's, or a continuous tile's row), a band of a lattice tile's rows, a run of
   a row. Which tiles take the walks, and the tile paths where the weights agree over a tile's reach, are
   mix_tile.cpp's. */
#include "core/bilinear_texton.h"
#include "core/cell_walk.h"
#include "core/continuous_internal.h"
#include "core/continuous_sift.h"
#include "core/impulse_position.h"
#include "core/lattice_impulses.h"
#include "core/mix_weights.h"
#include "core/normalize_fixed.h"
#include "core/poisson_count.h"
#include "evaluators/mix_evaluation.h"
#include "kernels/kernels.h"

#if DSN_MIXING

namespace {

typedef uint64_t ContinuousSums[DSN_MIX_MAX_MATERIALS][DSN_MAX_CHANNELS];
typedef uint32_t LatticeSums[DSN_MIX_MAX_MATERIALS][DSN_MAX_CHANNELS];

/* ---- The walks ---- */

/* The region of grid samples that the impulses around the integer point (x, y) may read: their floors lie
   within reach_x, reach_y texels. */
MixRegion region_around(const dsn_mix_state *mix, const dsn_mix_control *control, uint32_t x, uint32_t y,
                        uint32_t reach_x, uint32_t reach_y) {
    return mix_region(control, mix->count, static_cast<uint64_t>(x - reach_x) << 32,
                      static_cast<uint64_t>(y - reach_y) << 32, static_cast<uint64_t>(x + reach_x) << 32,
                      static_cast<uint64_t>(y + reach_y) << 32, 16u);
}

/* visit(k, field) for impulse k of the cell (key, count), its packed field, wherever that field passes the
   cell's axes: each position pair hashed once, its impulses tested at once (candidate_lanes). */
template <typename Visit>
void visit_candidates(uint32_t key, uint32_t count, const FieldLanes &lanes, const CellAxis &x,
                      const CellAxis &y, const Visit &visit) {
    for (uint32_t first = 0; first < count; first += lanes.per_pair) {
        const uint64_t pair = dsn_position_pair(key, first / lanes.per_pair);
        uint64_t candidates = candidate_lanes(pair, lanes, x, y);
        if (count - first < lanes.per_pair)
            candidates &= (static_cast<uint64_t>(1) << ((count - first) << lanes.field_shift)) - 1u;
        for (; candidates != 0; candidates &= candidates - 1u) {
            const uint32_t lane = lowest_bit(candidates) >> lanes.field_shift;
            visit(first + lane, dsn_pair_bits(pair, lane << lanes.field_shift));
        }
    }
}

/* How far apart along each axis, in texels, the points of a group (group_points) may lie. */
const uint32_t group_extent = 32;

/* The points of a group along one axis: their box [low, low + extent] (Q32.32) and the window of cells
   [floor(low) - 1, floor(low + extent) + 1] with the mix's reach (a point's window, point_axis, for a
   group of one). */
struct GroupAxis {
    dsn_axis axis;
    uint64_t low;
    int64_t extent;
};

/* False when the points are too far apart, or (on a periodic axis) when the window of several crosses the
   int32 sign change, where the reduction modulo the period breaks its coordinates' contiguity: there each
   point goes on its own. offsets[p]: point p's offset from low. */
bool group_axis(const uint64_t *coordinates, uint32_t count, uint32_t radius, uint32_t shift, uint32_t period,
                GroupAxis *out, int64_t *offsets) {
    const int64_t limit = static_cast<int64_t>(group_extent) << 32;
    int64_t low = 0, high = 0;
    for (uint32_t p = 1; p < count; p++) {
        const int64_t offset = static_cast<int64_t>(coordinates[p] - coordinates[0]);
        if (offset >= limit || offset <= -limit) return false; /* (so that high - low cannot overflow) */
        low = offset < low ? offset : low;
        high = offset > high ? offset : high;
    }
    if (high - low >= limit) return false;
    out->low = coordinates[0] + static_cast<uint64_t>(low);
    out->extent = high - low;
    const uint32_t first = static_cast<uint32_t>(out->low >> 32) - 1u;
    const uint32_t length =
        static_cast<uint32_t>((out->low + static_cast<uint64_t>(out->extent)) >> 32) - first + 2u;
    const uint32_t until_sign_change = 0x80000000u - first;
    if (count > 1 && period != 0 && until_sign_change != 0 && until_sign_change < length) return false;
    dsn_axis_init(&out->axis, first, length, radius, shift, period);
    for (uint32_t p = 0; p < count; p++) offsets[p] = static_cast<int64_t>(coordinates[p] - out->low);
    return true;
}

/* The continuous sums of every material at each point of a group, Q32.32: continuous_sift.h's sifting walk
   with the mix's reach over the group's box. Each position pair is hashed once for its impulses, which are
   tested against the box on their lattice fields all at once; only the candidates get their fraction
   hash, the exact test, their material and their reads, at the points they reach. */
void continuous_group_sums(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                           const GroupAxis &gx, const GroupAxis &gy, const int64_t *offsets_x,
                           const int64_t *offsets_y, uint32_t points, ContinuousSums *sums) {
    const dsn_noise_state *lead = &mix->material[0];
    const uint32_t shift = lead->cell_shift;
    const FieldLanes lanes = field_lanes(shift);
    const uint32_t half_mask = (1u << lanes.half_bits) - 1u, high_shift = 16u - lanes.half_bits;
    const uint32_t position_shift = 16u + shift;
    const int64_t reach_x = static_cast<int64_t>(mix->radius[0] + 1u) << 32;
    const int64_t reach_y = static_cast<int64_t>(mix->radius[1] + 1u) << 32;
    /* cell_axis's sifting for the box: shifted = high - impulse + reach, in reach of a point of the box
       when 0 < shifted < 2 reach + extent */
    const int64_t extra_x = static_cast<int64_t>(static_cast<uint32_t>(gx.low)) + reach_x + gx.extent;
    const int64_t extra_y = static_cast<int64_t>(static_cast<uint32_t>(gy.low)) + reach_y + gy.extent;
    for (uint32_t sy = 0; sy < gy.axis.span_count; sy++) {
        const dsn_span span_y = dsn_axis_span(&gy.axis, sy);
        for (uint32_t sx = 0; sx < gx.axis.span_count; sx++) {
            const dsn_span span_x = dsn_axis_span(&gx.axis, sx);
            for (uint32_t j = 0; j < span_y.cell_count; j++) {
                CellAxis cell_y;
                const uint32_t cell_row = dsn_span_cell(&span_y, j, shift);
                if (!cell_axis_within(gy.axis, span_y, cell_row, extra_y, 2 * reach_y + gy.extent, lanes,
                                      &cell_y))
                    continue;
                const uint32_t row_key = dsn_row_key(lead, cell_row);
                for (uint32_t i = 0; i < span_x.cell_count; i++) {
                    CellAxis cell_x;
                    const uint32_t cell = dsn_span_cell(&span_x, i, shift);
                    if (!cell_axis_within(gx.axis, span_x, cell, extra_x, 2 * reach_x + gx.extent, lanes,
                                          &cell_x))
                        continue;
                    const uint32_t key = dsn_cell_key_in_row(lead, cell, row_key);
                    const uint32_t count = dsn_cell_impulse_count(lead, key);
                    visit_candidates(key, count, lanes, cell_x, cell_y, [&](uint32_t k, uint32_t field) {
                        const uint32_t fraction = dsn_cell_stream(key, 0x80000000u + k);
                        /* dsn_impulse_hash's 16-bit positions */
                        const uint32_t bits_x =
                            ((field & half_mask) << high_shift) | ((fraction & 0xFFFFu) >> lanes.half_bits);
                        const uint32_t bits_y = (((field >> lanes.half_bits) & half_mask) << high_shift) |
                                                ((fraction >> 16) >> lanes.half_bits);
                        /* low - impulse, Q32.32 */
                        const int64_t near_x =
                            cell_x.shifted_base -
                            static_cast<int64_t>(static_cast<uint64_t>(bits_x) << position_shift) - reach_x -
                            gx.extent;
                        const int64_t near_y =
                            cell_y.shifted_base -
                            static_cast<int64_t>(static_cast<uint64_t>(bits_y) << position_shift) - reach_y -
                            gy.extent;
                        const uint32_t m = impulse_material(control, mix->count, region, key, k,
                                                            gx.low - static_cast<uint64_t>(near_x),
                                                            gy.low - static_cast<uint64_t>(near_y));
                        const dsn_noise_state *material = &mix->material[m];
                        for (uint32_t p = 0; p < points; p++) {
                            const int64_t offset_x = near_x + offsets_x[p], offset_y = near_y + offsets_y[p];
                            uint32_t row, row_weight, column, column_weight;
                            if (within_reach(offset_x, mix->radius[0]) &&
                                within_reach(offset_y, mix->radius[1]) &&
                                bracket(offset_y, material->radius[1], &row, &row_weight) &&
                                bracket(offset_x, material->radius[0], &column, &column_weight))
                                add_bilinear(&material->asset, row, row_weight, column, column_weight,
                                             sums[p][m]);
                        }
                    });
                }
            }
        }
    }
}

/* The lanes of a cell's packed fields (continuous_sift.h's CellAxis, exact here) whose lattice offset o
   reaches the points along one axis: texton index reach - o in [0, span], o <= last_offset (a point: span
   2 radius, reach its index; a run of points: span 2 radius + length - 1, reach the last point's index).
   False when none does. */
bool lattice_axis(const axis_cell &on_axis, uint32_t span, const FieldLanes &lanes, uint32_t drop,
                  CellAxis *out) {
    const int64_t reach = dsn_signed_sum(on_axis.reach);
    const int64_t low = reach - static_cast<int64_t>(span) > 0 ? reach - static_cast<int64_t>(span) : 0;
    const int64_t high = reach < static_cast<int64_t>(on_axis.last_offset) ? reach : on_axis.last_offset;
    if (high < low) return false;
    out->shifted_base = 0;
    out->low_lanes = lanes.ones * (static_cast<uint64_t>(low) << drop);
    out->high_lanes =
        (lanes.ones * ((static_cast<uint64_t>(high) << drop) | ((1u << drop) - 1u))) | lanes.tops;
    return true;
}

/* The lattice sums of every material over a window of `rows` rows of `length` points from (x0, y0): point
   i of row j's sums of material m at sums[m][(j length + i) channels + c], that material's channels
   apart: lattice_impulses.h's walk with the mix's reach over the window, each position pair hashed once
   and its impulses tested at once on their fields (exactly, lattice_axis), each impulse that reaches the
   window adding its material's lattice texton rows and columns to the points it reaches (dsn_reach_at
   per axis; the kernel's rows, kernels.h's dsn_lattice_rows_entry). A run of a row is a window of one row, a
   point a run of one. */
void lattice_window_sums(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                         uint32_t x0, uint32_t length, uint32_t y0, uint32_t rows, uint32_t *const *sums) {
    const dsn_noise_state *lead = &mix->material[0];
    const uint32_t shift = lead->cell_shift, reach_x = mix->lattice_radius[0],
                   reach_y = mix->lattice_radius[1], last = length - 1u, last_row = rows - 1u;
    const FieldLanes lanes = field_lanes(shift);
    const uint32_t half_mask = (1u << lanes.half_bits) - 1u, drop = lanes.half_bits - shift;
    dsn_texton_window textons[DSN_MIX_MAX_MATERIALS];
    for (uint32_t m = 0; m < mix->count; m++) textons[m] = dsn_lattice_texton_window(&mix->material[m]);
    dsn_lattice_rows_entry *const add_rows = dsn_kernel_entries_of(lead->tile_kernel)->lattice_rows;
    dsn_axis ax, ay;
    dsn_axis_init(&ax, x0, length, reach_x, shift, lead->period[0]);
    dsn_axis_init(&ay, y0, rows, reach_y, shift, lead->period[1]);
    for (uint32_t sy = 0; sy < ay.span_count; sy++) {
        const dsn_span span_y = dsn_axis_span(&ay, sy);
        for (uint32_t sx = 0; sx < ax.span_count; sx++) {
            const dsn_span span_x = dsn_axis_span(&ax, sx);
            for (uint32_t j = 0; j < span_y.cell_count; j++) {
                const uint32_t cell_y = dsn_span_cell(&span_y, j, shift);
                axis_cell on_y = cell_on_axis(&span_y, cell_y, shift);
                on_y.reach += last_row; /* the index at the window's last row */
                CellAxis lanes_y;
                if (!lattice_axis(on_y, 2u * reach_y + last_row, lanes, drop, &lanes_y)) continue;
                const uint32_t row_key = dsn_row_key(lead, cell_y);
                for (uint32_t i = 0; i < span_x.cell_count; i++) {
                    const uint32_t cell_x = dsn_span_cell(&span_x, i, shift);
                    axis_cell on_x = cell_on_axis(&span_x, cell_x, shift);
                    on_x.reach += last; /* the index at the window's last point */
                    CellAxis lanes_x;
                    if (!lattice_axis(on_x, 2u * reach_x + last, lanes, drop, &lanes_x)) continue;
                    const uint32_t key = dsn_cell_key_in_row(lead, cell_x, row_key);
                    const uint32_t count = dsn_cell_impulse_count(lead, key);
                    visit_candidates(key, count, lanes, lanes_x, lanes_y, [&](uint32_t k, uint32_t field) {
                        /* texton indices in the walk's window of radius reach at the window's last
                           column and row: 0 .. 2 reach + last, 0 .. 2 reach + last_row */
                        const uint32_t end = on_x.reach - ((field & half_mask) >> drop);
                        const uint32_t end_row =
                            on_y.reach - (((field >> lanes.half_bits) & half_mask) >> drop);
                        /* the impulse as seen from the window: its last point + reach - end */
                        const uint64_t at_x = static_cast<uint64_t>(x0 + last + reach_x - end) << 32;
                        const uint64_t at_y = static_cast<uint64_t>(y0 + last_row + reach_y - end_row) << 32;
                        const uint32_t m = impulse_material(control, mix->count, region, key, k, at_x, at_y);
                        const dsn_texton_window *texton = &textons[m];
                        const uint32_t own_end = end - reach_x + texton->radius[0];
                        const uint32_t own_end_row = end_row - reach_y + texton->radius[1];
                        if (own_end > last + texton->width - 1u ||
                            own_end_row > last_row + texton->height - 1u)
                            return;
                        dsn_reach reach, reach_rows;
                        dsn_reach_at(own_end, length, texton->width, &reach);
                        dsn_reach_at(own_end_row, rows, texton->height, &reach_rows);
                        const dsn_asset *asset = &mix->material[m].asset;
                        const size_t texel = asset->channels * (asset->bits / 8u);
                        add_rows(
                            texton->values + (static_cast<size_t>(reach_rows.first_texton) * texton->width +
                                              reach.first_texton) *
                                                 texel,
                            texton->width * texel, asset->bits, reach_rows.count,
                            reach.count * asset->channels,
                            sums[m] +
                                (static_cast<size_t>(reach_rows.first_index) * length + reach.first_index) *
                                    asset->channels,
                            static_cast<size_t>(length) * asset->channels);
                    });
                }
            }
        }
    }
}

/* ---- The output ---- */

/* A material's sums normalized from `offset`: Q.32 sums (continuous) or whole ones (lattice). */
void normalize_material(const dsn_noise_state *material, const int64_t *offset, const uint64_t *sums,
                        int32_t *out) {
    normalize_q32_from(material, offset, sums, out);
}
void normalize_material(const dsn_noise_state *material, const int64_t *offset, const uint32_t *sums,
                        int32_t *out) {
    dsn_normalize_from(material, offset, sums, out);
}

/* normalize_material for a material of `Channels` channels: the continuous sums' copy written for it,
   inline; the lattice normalization (already written out for 1 and 3 channels). */
template <uint32_t Channels>
void normalize_channels(const dsn_noise_state *material, const int64_t *offset, const uint64_t *sums,
                        int32_t *out) {
    normalize_q32_channels<Channels>(material, offset, sums, out);
}
template <uint32_t Channels>
void normalize_channels(const dsn_noise_state *material, const int64_t *offset, const uint32_t *sums,
                        int32_t *out) {
    dsn_normalize_from(material, offset, sums, out);
}

typedef int64_t MixOffsets[DSN_MIX_MAX_MATERIALS][DSN_MAX_CHANNELS];

/* Each material's offset weighted by its weight at a point. */
void weighted_offsets(const dsn_mix_state *mix, const uint32_t *weights, MixOffsets offsets) {
    for (uint32_t m = 0; m < mix->count; m++)
        material_weighted_offset(&mix->material[m], weights[m], offsets[m]);
}

/* Each material's sums normalized from its weighted offset, summed per channel (a grey material's value
   in every channel) and saturated. */
template <typename Sum>
void mix_output_from(const dsn_mix_state *mix, const MixOffsets offsets, const Sum (*sums)[DSN_MAX_CHANNELS],
                     int32_t *out) {
    int64_t totals[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t m = 0; m < mix->count; m++) {
        int32_t values[DSN_MAX_CHANNELS];
        normalize_material(&mix->material[m], offsets[m], sums[m], values);
        add_material_value(mix, m, values, totals);
    }
    store_totals(mix, totals, out);
}

/* mix_output_from with weighted_offsets for materials of the mix's `Channels` channels each (those alike
   in their textons): the same sums, each material's offset weighted as it is used. */
template <uint32_t Channels, typename Sum>
void alike_output(const dsn_mix_state *mix, const uint32_t *weights, const Sum (*sums)[DSN_MAX_CHANNELS],
                  int32_t *out) {
    int64_t totals[Channels] = {};
    for (uint32_t m = 0; m < mix->count; m++) {
        const dsn_noise_state *material = &mix->material[m];
        int64_t offset[DSN_MAX_CHANNELS];
        for (uint32_t c = 0; c < Channels; c++) offset[c] = weighted_offset(material->offset[c], weights[m]);
        int32_t values[DSN_MAX_CHANNELS] = {0, 0, 0}; /* (each material fills Channels; GCC cannot tell) */
        normalize_channels<Channels>(material, offset, sums[m], values);
        for (uint32_t c = 0; c < Channels; c++) totals[c] += values[c];
    }
    for (uint32_t c = 0; c < Channels; c++) out[c] = saturated_total(totals[c]);
}

template <typename Sum>
void mix_output(const dsn_mix_state *mix, const uint32_t *weights, const Sum (*sums)[DSN_MAX_CHANNELS],
                int32_t *out) {
#if !DSN_SMALL_CODE
    if (mix->alike != 0) {
        if (mix->channels == 3)
            alike_output<3>(mix, weights, sums, out);
        else
            alike_output<1>(mix, weights, sums, out);
        return;
    }
#endif
    MixOffsets offsets = {};
    weighted_offsets(mix, weights, offsets);
    mix_output_from(mix, offsets, sums, out);
}

/* The mix's value at continuous point (x, y) (Q32.32) from its materials' sums there, in a region of the
   weights that holds the point (a uniform one's weights are the point's). */
template <typename Sum>
void point_output(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                  uint64_t x, uint64_t y, const Sum (*sums)[DSN_MAX_CHANNELS], int32_t *out) {
    if (region.uniform) {
        mix_output(mix, region.draws.weights, sums, out);
        return;
    }
    uint32_t weights[DSN_MIX_MAX_MATERIALS] = {0, 0, 0, 0}; /* (GCC cannot tell point_weights fills them) */
    MixWeights at_point;
    mix_weights_at(control, mix->count, x, y, &at_point);
    point_weights(at_point, mix->count, weights);
    mix_output(mix, weights, sums, out);
}

/* The mix's value at lattice point (x, y) from its materials' sums there. */
void lattice_output(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                    uint32_t x, uint32_t y, const LatticeSums sums, int32_t *out) {
    point_output(mix, control, region, static_cast<uint64_t>(x) << 32, static_cast<uint64_t>(y) << 32, sums,
                 out);
}

/* ---- The kernels' mixed points ---- */

static_assert(DSN_MIX_MAX_MATERIALS == dsn_point_materials_most, "the kernels' mixed point takes every mix");

/* What the kernels' mixed lattice point asks of a non-uniform region's impulses: their materials. */
struct ImpulsePick {
    const dsn_mix_state *mix;
    const dsn_mix_control *control;
    const MixRegion *region;
};

uint32_t pick_at(const void *context, uint32_t hash, uint32_t x, uint32_t y) {
    const ImpulsePick *pick = static_cast<const ImpulsePick *>(context);
    return hashed_material(pick->control, pick->mix->count, *pick->region, hash,
                           static_cast<uint64_t>(x) << 32, static_cast<uint64_t>(y) << 32, true);
}

/* The materials as the kernels' mixed points take them (kernels.h's dsn_point_materials): their textons
   (the lattice ones in lattice mode), which must all have the lead's window, channels and bits (mix_init
   tells: the mix's reach is then the lead's), and the region's weights as the hashes' thresholds where it
   is uniform, else `pick`. False where a texton differs. */
bool point_materials(const dsn_mix_state *mix, const MixRegion &region, bool lattice, const ImpulsePick *pick,
                     dsn_point_materials *materials) {
    if ((mix->alike & (lattice ? dsn_mix_alike_lattice_textons : dsn_mix_alike_textons)) == 0) return false;
    const dsn_point_materials none = {mix->count, {0, 0, 0, 0}, {0, 0, 0}, 0, 0, 0};
    *materials = none;
    for (uint32_t m = 0; m < mix->count; m++) {
        const dsn_noise_state *material = &mix->material[m];
        materials->values[m] = lattice ? dsn_lattice_texton_window(material).values : material->asset.texton;
    }
    if (region.uniform) {
        for (uint32_t level = 0; level + 1u < dsn_point_materials_most; level++)
            materials->thresholds[level] = region.draws.thresholds[level];
    } else {
        materials->pick = pick_at;
        materials->context = pick;
        materials->control = pick->control;
    }
    return true;
}

/* The lattice sums of every material at (x, y), into zeroed sums, from the kernel's vector walk, where it
   takes the mix (point_materials). False, writing nothing, elsewhere. */
bool kernel_lattice_sums(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                         uint32_t x, uint32_t y, LatticeSums sums) {
    const dsn_noise_state *lead = &mix->material[0];
    dsn_lattice_point_entry *walk = dsn_kernel_entries_of(lead->tile_kernel)->lattice_point;
    const ImpulsePick pick = {mix, control, &region};
    dsn_point_materials materials;
    if (walk == 0 || !point_materials(mix, region, true, &pick, &materials)) return false;
    const dsn_texton_window texton = dsn_lattice_texton_window(lead);
    uint32_t flat[3 * DSN_MIX_MAX_MATERIALS];
    if (!walk(lead, &texton, x, y, 1u, flat, &materials)) return false;
    for (uint32_t m = 0; m < mix->count && m < DSN_MIX_MAX_MATERIALS; m++)
        __builtin_memcpy(sums[m], flat + 3 * m, sizeof sums[m]);
    return true;
}

/* The continuous sums of every material at `count` points (xs[p], ys[p]), into zeroed sums, from the kernel's
   vector evaluator, the materials made once, where it takes the mix (point_materials; the AVX2 and AVX-512
   copies, 8-bit textons) and the region's weights are uniform, or where `picks`: a point alone, or a group
   whose candidates' weights the kernel's lanes read (each candidate in reach then reads its weights; where
   the lanes do not read them, a group's walk reads each impulse's once for the group). False where it does
   not (sums then undefined). */
bool kernel_continuous_sums(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                            bool picks, const uint64_t *xs, const uint64_t *ys, uint32_t count,
                            ContinuousSums *sums) {
    const dsn_noise_state *lead = &mix->material[0];
    dsn_continuous_point_entry *point = dsn_kernel_entries_of(lead->tile_kernel)->continuous_point;
    const ImpulsePick pick = {mix, control, &region};
    dsn_point_materials materials;
    if (point == 0 || (!region.uniform && !picks) || !point_materials(mix, region, false, &pick, &materials))
        return false;
    for (uint32_t p = 0; p < count; p++) {
        uint64_t flat[DSN_MAX_CHANNELS * DSN_MIX_MAX_MATERIALS];
        if (!point(lead, xs[p], ys[p], flat, 0, 0, &materials)) return false;
        for (uint32_t m = 0; m < mix->count && m < DSN_MIX_MAX_MATERIALS; m++)
            __builtin_memcpy(sums[p][m], flat + DSN_MAX_CHANNELS * m, sizeof sums[p][m]);
    }
    return true;
}

void continuous_point(const dsn_mix_state *mix, const dsn_mix_control *control, uint64_t x, uint64_t y,
                      int32_t *out) {
    const MixRegion region =
        region_around(mix, control, static_cast<uint32_t>(x >> 32), static_cast<uint32_t>(y >> 32),
                      mix->radius[0] + 1u, mix->radius[1] + 1u);
    if (region.single) {
        const dsn_noise_state *material = &mix->material[region.only];
        dsn_internal_continuous_point(material, x, y, out);
        spread_channels(mix, material, out);
        return;
    }
    ContinuousSums sums[1] = {};
    if (!kernel_continuous_sums(mix, control, region, true, &x, &y, 1u, sums)) {
        __builtin_memset(sums, 0, sizeof sums);
        const dsn_noise_state *lead = &mix->material[0];
        GroupAxis gx, gy;
        int64_t offset_x, offset_y; /* a point is a group of one */
        group_axis(&x, 1u, mix->radius[0], lead->cell_shift, lead->period[0], &gx, &offset_x);
        group_axis(&y, 1u, mix->radius[1], lead->cell_shift, lead->period[1], &gy, &offset_y);
        continuous_group_sums(mix, control, region, gx, gy, &offset_x, &offset_y, 1u, sums);
    }
    point_output(mix, control, region, x, y, sums[0], out);
}

/* The values of up to group_points continuous points: as a group where they lie close together and the
   weights mix around them, else point by point (a material's own evaluator where its weights hold alone). */
void continuous_points(const dsn_mix_state *mix, const dsn_mix_control *control, const uint64_t *xs,
                       const uint64_t *ys, uint32_t count, int32_t (*values)[DSN_MAX_CHANNELS]) {
    const dsn_noise_state *lead = &mix->material[0];
    GroupAxis gx, gy;
    int64_t offsets_x[group_points], offsets_y[group_points];
    MixRegion region;
    region.single = true;
    bool laned = false; /* the kernels' lanes read each candidate's weights (mix_pick_lanes.h) */
    if (count > 1 &&
        group_axis(xs, count, mix->radius[0], lead->cell_shift, lead->period[0], &gx, offsets_x) &&
        group_axis(ys, count, mix->radius[1], lead->cell_shift, lead->period[1], &gy, offsets_y)) {
        const uint32_t reach_x = mix->radius[0] + 1u, reach_y = mix->radius[1] + 1u;
        const uint32_t low_x = static_cast<uint32_t>(gx.low >> 32),
                       low_y = static_cast<uint32_t>(gy.low >> 32);
        const uint32_t high_x = static_cast<uint32_t>((gx.low + static_cast<uint64_t>(gx.extent)) >> 32);
        const uint32_t high_y = static_cast<uint32_t>((gy.low + static_cast<uint64_t>(gy.extent)) >> 32);
        region = mix_region(control, mix->count, static_cast<uint64_t>(low_x - reach_x) << 32,
                            static_cast<uint64_t>(low_y - reach_y) << 32,
                            static_cast<uint64_t>(high_x + reach_x) << 32,
                            static_cast<uint64_t>(high_y + reach_y) << 32, 16u + group_extent);
        PickWindowAxis lanes_x, lanes_y; /* (a point's candidates lie within radius + 2 of it) */
        laned =
            !region.uniform &&
            lanes_read_control(control, mix->count, low_x - reach_x - 1u, high_x - low_x + 2u * reach_x + 2u,
                               low_y - reach_y - 1u, high_y - low_y + 2u * reach_y + 2u, &lanes_x, &lanes_y);
    }
    if (region.single) {
        for (uint32_t p = 0; p < count; p++) continuous_point(mix, control, xs[p], ys[p], values[p]);
        return;
    }
    /* Where the weights are uniform, or vary where the kernel's lanes read them, each point by the kernel's
       vector evaluator where it takes the mix (faster than the group's scalar walk: make bench's
       mix_bench); else the group's walk. */
    ContinuousSums sums[group_points] = {};
    if (!kernel_continuous_sums(mix, control, region, laned, xs, ys, count, sums)) {
        for (uint32_t p = 0; p < count; p++) __builtin_memset(sums[p], 0, sizeof sums[p]);
        continuous_group_sums(mix, control, region, gx, gy, offsets_x, offsets_y, count, sums);
    }
    for (uint32_t p = 0; p < count; p++) point_output(mix, control, region, xs[p], ys[p], sums[p], values[p]);
}

void lattice_point(const dsn_mix_state *mix, const dsn_mix_control *control, uint32_t x, uint32_t y,
                   int32_t *out) {
    const MixRegion region = window_region(mix, control, x, 1u, y, 1u);
    if (region.single) {
        const dsn_noise_state *material = &mix->material[region.only];
        dsn_lattice_point_fixed(dsn_mix_material_noise(mix, region.only), static_cast<int32_t>(x),
                                static_cast<int32_t>(y), out);
        spread_channels(mix, material, out);
        return;
    }
    LatticeSums sums = {};
    if (!kernel_lattice_sums(mix, control, region, x, y, sums)) {
        uint32_t *const material_sums[DSN_MIX_MAX_MATERIALS] = {sums[0], sums[1], sums[2], sums[3]};
        lattice_window_sums(mix, control, region, x, 1u, y, 1u, material_sums);
    }
    lattice_output(mix, control, region, x, y, sums, out);
}

/* Point `point`'s sums of every material from a window's (lattice_window_sums's layout), zero past a
   material's channels. (The loops' bounds keep GCC -O3 from warning of writes past sums.) */
void point_sums(const dsn_mix_state *mix, const uint32_t *const *planes, size_t point, LatticeSums sums) {
    for (uint32_t m = 0; m < DSN_MIX_MAX_MATERIALS; m++)
        for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) {
            const uint32_t channels = m < mix->count ? mix->material[m].asset.channels : 0u;
            sums[m][c] = c < channels ? planes[m][point * channels + c] : 0u;
        }
}

/* ---- The API ---- */

int lattice_point_as(const dsn_mix *handle, const dsn_mix_control *control, int32_t x, int32_t y, void *out,
                     dsn_output_kind kind) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    if (out == 0) return DSN_ERR_NULL;
    const int err = check_call(mix, control, false);
    if (err != DSN_OK) return output_error(err, mix, out, kind, 1);
    int32_t value[DSN_MAX_CHANNELS];
    lattice_point(mix, control, static_cast<uint32_t>(x), static_cast<uint32_t>(y), value);
    dsn_store_pixel(out, kind, 0, value, mix->channels);
    return DSN_OK;
}

int continuous_point_as(const dsn_mix *handle, const dsn_mix_control *control, int64_t x, int64_t y,
                        void *out, dsn_output_kind kind) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    if (out == 0) return DSN_ERR_NULL;
    const int err = check_call(mix, control, true);
    if (err != DSN_OK) return output_error(err, mix, out, kind, 1);
    int32_t value[DSN_MAX_CHANNELS];
    continuous_point(mix, control, static_cast<uint64_t>(x), static_cast<uint64_t>(y), value);
    dsn_store_pixel(out, kind, 0, value, mix->channels);
    return DSN_OK;
}

template <typename Coordinate>
int continuous_batch_as(const dsn_mix *handle, const dsn_mix_control *control, const Coordinate *xs,
                        const Coordinate *ys, uint32_t count, void *out, dsn_output_kind kind) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    if (out == 0) return DSN_ERR_NULL;
    int err = check_call(mix, control, true);
    if (err == DSN_OK && count != 0 && (xs == 0 || ys == 0)) err = DSN_ERR_NULL;
    if (err != DSN_OK) return output_error(err, mix, out, kind, count);
    for (uint32_t k = 0; k < count; k += 32) {
        int64_t chunk_x[32], chunk_y[32];
        const uint32_t points = count - k < 32 ? count - k : 32u;
        const int64_t *x = dsn_chunk_coordinates(xs, k, points, chunk_x);
        const int64_t *y = dsn_chunk_coordinates(ys, k, points, chunk_y);
        for (uint32_t first = 0; first < points; first += group_points) {
            const uint32_t grouped = points - first < group_points ? points - first : group_points;
            uint64_t group_x[group_points], group_y[group_points];
            for (uint32_t p = 0; p < grouped; p++) {
                group_x[p] = static_cast<uint64_t>(x[first + p]);
                group_y[p] = static_cast<uint64_t>(y[first + p]);
            }
            int32_t values[group_points][DSN_MAX_CHANNELS];
            continuous_points(mix, control, group_x, group_y, grouped, values);
            for (uint32_t p = 0; p < grouped; p++)
                dsn_store_pixel(out, kind, static_cast<size_t>(k + first + p) * mix->channels, values[p],
                                mix->channels);
        }
    }
    return DSN_OK;
}

} // namespace

void dsn_internal_mix_continuous_point(const dsn_mix_state *mix, const dsn_mix_control *control, uint64_t x,
                                       uint64_t y, int32_t *out) {
    continuous_point(mix, control, x, y, out);
}

void dsn_internal_mix_continuous_points(const dsn_mix_state *mix, const dsn_mix_control *control,
                                        const uint64_t *xs, const uint64_t *ys, uint32_t count,
                                        int32_t (*values)[DSN_MAX_CHANNELS]) {
    continuous_points(mix, control, xs, ys, count, values);
}

void dsn_internal_mix_walk_band(const dsn_mix_state *mix, const dsn_mix_control *control, uint32_t x0,
                                uint32_t width, uint32_t y, uint32_t rows, uint32_t *scratch,
                                const dsn_mix_band_target &target) {
    uint32_t *planes[DSN_MIX_MAX_MATERIALS] = {scratch, scratch, scratch, scratch};
    uint32_t *next = scratch;
    for (uint32_t m = 0; m < mix->count; m++) {
        const size_t values = static_cast<size_t>(rows) * width * mix->material[m].asset.channels;
        planes[m] = next;
        for (size_t v = 0; v < values; v++) next[v] = 0;
        next += values;
    }
    const MixRegion region = window_region(mix, control, x0, width, y, rows);
    lattice_window_sums(mix, control, region, x0, width, y, rows, planes);
    /* where the region is uniform, the weighted offsets of every point of the band */
    MixOffsets uniform_offsets = {};
    if (region.uniform) weighted_offsets(mix, region.draws.weights, uniform_offsets);
    for (uint32_t j = 0; j < rows; j++)
        for (uint32_t i = 0; i < width; i++) {
            const size_t point = static_cast<size_t>(j) * width + i;
            LatticeSums sums;
            point_sums(mix, planes, point, sums);
            int32_t value[DSN_MAX_CHANNELS];
            if (region.uniform)
                mix_output_from(mix, uniform_offsets, sums, value);
            else
                lattice_output(mix, control, region, x0 + i, y + j, sums, value);
            dsn_store_pixel(target.out, target.kind, (target.first + point) * mix->channels, value,
                            mix->channels);
        }
}

static_assert(DSN_MIX_MAX_MATERIALS == 4, "the runs' sums are listed for four materials");

void dsn_internal_mix_walk_run(const dsn_mix_state *mix, const dsn_mix_control *control, uint32_t x,
                               uint32_t length, uint32_t y, const dsn_mix_band_target &target) {
    uint32_t run_sums[DSN_MIX_MAX_MATERIALS][run_points * DSN_MAX_CHANNELS] = {};
    uint32_t *const material_sums[DSN_MIX_MAX_MATERIALS] = {run_sums[0], run_sums[1], run_sums[2],
                                                            run_sums[3]};
    const MixRegion region = window_region(mix, control, x, length, y, 1u);
    lattice_window_sums(mix, control, region, x, length, y, 1u, material_sums);
    for (uint32_t p = 0; p < length; p++) {
        LatticeSums sums;
        const uint32_t *const planes[DSN_MIX_MAX_MATERIALS] = {run_sums[0], run_sums[1], run_sums[2],
                                                               run_sums[3]};
        point_sums(mix, planes, p, sums);
        int32_t value[DSN_MAX_CHANNELS];
        lattice_output(mix, control, region, x + p, y, sums, value);
        dsn_store_pixel(target.out, target.kind, (target.first + p) * mix->channels, value, mix->channels);
    }
}

extern "C" {

int dsn_mix_lattice_point_fixed(const dsn_mix *mix, const dsn_mix_control *control, int32_t x, int32_t y,
                                int32_t *out) {
    return lattice_point_as(mix, control, x, y, out, dsn_output_fixed);
}

int dsn_mix_lattice_point_float(const dsn_mix *mix, const dsn_mix_control *control, int32_t x, int32_t y,
                                float *out) {
    return lattice_point_as(mix, control, x, y, out, dsn_output_float);
}

int dsn_mix_lattice_point_u8(const dsn_mix *mix, const dsn_mix_control *control, int32_t x, int32_t y,
                             uint8_t *out) {
    return lattice_point_as(mix, control, x, y, out, dsn_output_u8);
}

int dsn_mix_continuous_point_u8(const dsn_mix *mix, const dsn_mix_control *control, int64_t x, int64_t y,
                                uint8_t *out) {
    return continuous_point_as(mix, control, x, y, out, dsn_output_u8);
}

int dsn_mix_continuous_batch_fixed(const dsn_mix *mix, const dsn_mix_control *control, const int64_t *xs,
                                   const int64_t *ys, uint32_t count, int32_t *out) {
    return continuous_batch_as(mix, control, xs, ys, count, out, dsn_output_fixed);
}

int dsn_mix_continuous_batch_float(const dsn_mix *mix, const dsn_mix_control *control, const double *xs,
                                   const double *ys, uint32_t count, float *out) {
    return continuous_batch_as(mix, control, xs, ys, count, out, dsn_output_float);
}

int dsn_mix_continuous_batch_u8(const dsn_mix *mix, const dsn_mix_control *control, const int64_t *xs,
                                const int64_t *ys, uint32_t count, uint8_t *out) {
    return continuous_batch_as(mix, control, xs, ys, count, out, dsn_output_u8);
}

int dsn_mix_continuous_point_fixed(const dsn_mix *mix, const dsn_mix_control *control, int64_t x, int64_t y,
                                   int32_t *out) {
    return continuous_point_as(mix, control, x, y, out, dsn_output_fixed);
}

int dsn_mix_continuous_point_float(const dsn_mix *mix, const dsn_mix_control *control, double x, double y,
                                   float *out) {
    return continuous_point_as(mix, control, dsn_coordinate_from_double(x), dsn_coordinate_from_double(y),
                               out, dsn_output_float);
}

} // extern "C"

#endif /* DSN_MIXING */
