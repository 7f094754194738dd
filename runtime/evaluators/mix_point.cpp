/* runtime/evaluators/mix_point.cpp - the mixing of materials (dsn.h, "Mixing"): one walk over the impulses
   of material 0's process within the largest reach, each impulse picking its material from the weights
   at its position (mix_weights.h) and adding that material's texton to the material's sums; then each
   material's sums normalized with the point's weight on its mean, and summed. Lattice and continuous,
   per point; tiles point by point. */
#include "core/bilinear_texton.h"
#include "core/cell_walk.h"
#include "core/continuous_internal.h"
#include "core/continuous_sift.h"
#include "core/grid_points.h"
#include "core/impulse_position.h"
#include "core/lattice_impulses.h"
#include "core/mix_weights.h"
#include "core/normalize_fixed.h"
#include "core/poisson_count.h"
#include "evaluators/mix_evaluation.h"

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

/* The continuous sums of every material at (x, y), Q32.32: continuous_sift.h's sifting walk with the mix's
   reach. Each position pair is hashed once for its impulses, which are tested against the point on their
   lattice fields all at once; only the candidates get their fraction hash, the exact test, their material
   and their read. */
void continuous_sums(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                     uint64_t x, uint64_t y, ContinuousSums sums) {
    const dsn_noise_state *lead = &mix->material[0];
    const uint32_t shift = lead->cell_shift;
    const PointAxis px = point_axis(x, mix->radius[0], shift, lead->period[0]);
    const PointAxis py = point_axis(y, mix->radius[1], shift, lead->period[1]);
    const FieldLanes lanes = field_lanes(shift);
    const uint32_t half_mask = (1u << lanes.half_bits) - 1u, high_shift = 16u - lanes.half_bits;
    const uint32_t position_shift = 16u + shift;
    const int64_t reach_x = static_cast<int64_t>(mix->radius[0] + 1u) << 32;
    const int64_t reach_y = static_cast<int64_t>(mix->radius[1] + 1u) << 32;
    for (uint32_t sy = 0; sy < py.axis.span_count; sy++) {
        const dsn_span span_y = dsn_axis_span(&py.axis, sy);
        for (uint32_t sx = 0; sx < px.axis.span_count; sx++) {
            const dsn_span span_x = dsn_axis_span(&px.axis, sx);
            for (uint32_t j = 0; j < span_y.cell_count; j++) {
                CellAxis cell_y;
                if (!cell_axis(py, span_y, dsn_span_cell(&span_y, j, shift), lanes, &cell_y)) continue;
                const uint32_t row_key = dsn_row_key(lead, dsn_span_cell(&span_y, j, shift));
                for (uint32_t i = 0; i < span_x.cell_count; i++) {
                    CellAxis cell_x;
                    const uint32_t cell = dsn_span_cell(&span_x, i, shift);
                    if (!cell_axis(px, span_x, cell, lanes, &cell_x)) continue;
                    const uint32_t key = dsn_cell_key_in_row(lead, cell, row_key);
                    const uint32_t count = dsn_cell_impulse_count(lead, key);
                    visit_candidates(key, count, lanes, cell_x, cell_y, [&](uint32_t k, uint32_t field) {
                        const uint32_t fraction = dsn_cell_stream(key, 0x80000000u + k);
                        /* dsn_impulse_hash's 16-bit positions */
                        const uint32_t bits_x =
                            ((field & half_mask) << high_shift) | ((fraction & 0xFFFFu) >> lanes.half_bits);
                        const uint32_t bits_y = (((field >> lanes.half_bits) & half_mask) << high_shift) |
                                                ((fraction >> 16) >> lanes.half_bits);
                        const int64_t offset_x =
                            cell_x.shifted_base -
                            static_cast<int64_t>(static_cast<uint64_t>(bits_x) << position_shift) - reach_x;
                        const int64_t offset_y =
                            cell_y.shifted_base -
                            static_cast<int64_t>(static_cast<uint64_t>(bits_y) << position_shift) - reach_y;
                        if (!within_reach(offset_x, mix->radius[0]) ||
                            !within_reach(offset_y, mix->radius[1]))
                            return;
                        const uint32_t m = impulse_material(control, mix->count, region, key, k,
                                                            x - static_cast<uint64_t>(offset_x),
                                                            y - static_cast<uint64_t>(offset_y));
                        const dsn_noise_state *material = &mix->material[m];
                        uint32_t row, row_weight, column, column_weight;
                        if (bracket(offset_y, material->radius[1], &row, &row_weight) &&
                            bracket(offset_x, material->radius[0], &column, &column_weight))
                            add_bilinear(&material->asset, row, row_weight, column, column_weight, sums[m]);
                    });
                }
            }
        }
    }
}

/* The lanes of a cell's packed fields (continuous_sift.h's CellAxis, exact here) whose lattice offset o
   reaches the point along one axis: texton index reach - o in [0, 2 radius], o <= last_offset. False when
   none does. */
bool lattice_axis(const axis_cell &on_axis, uint32_t radius, const FieldLanes &lanes, uint32_t drop,
                  CellAxis *out) {
    const int64_t reach = dsn_signed_sum(on_axis.reach);
    const int64_t low =
        reach - 2 * static_cast<int64_t>(radius) > 0 ? reach - 2 * static_cast<int64_t>(radius) : 0;
    const int64_t high = reach < static_cast<int64_t>(on_axis.last_offset) ? reach : on_axis.last_offset;
    if (high < low) return false;
    out->shifted_base = 0;
    out->low_lanes = lanes.ones * (static_cast<uint64_t>(low) << drop);
    out->high_lanes =
        (lanes.ones * ((static_cast<uint64_t>(high) << drop) | ((1u << drop) - 1u))) | lanes.tops;
    return true;
}

/* The lattice sums of every material at the lattice point (x, y): lattice_impulses.h's walk with the
   mix's reach, each position pair hashed once and its impulses tested at once on their fields (exactly,
   lattice_axis), each impulse within reach reading its material's lattice texton. */
void lattice_sums(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                  uint32_t x, uint32_t y, LatticeSums sums) {
    const dsn_noise_state *lead = &mix->material[0];
    const uint32_t shift = lead->cell_shift, reach_x = mix->lattice_radius[0],
                   reach_y = mix->lattice_radius[1];
    const FieldLanes lanes = field_lanes(shift);
    const uint32_t half_mask = (1u << lanes.half_bits) - 1u, drop = lanes.half_bits - shift;
    dsn_texton_window textons[DSN_MIX_MAX_MATERIALS];
    for (uint32_t m = 0; m < mix->count; m++) textons[m] = dsn_lattice_texton_window(&mix->material[m]);
    dsn_axis ax, ay;
    dsn_axis_init(&ax, x, 1u, reach_x, shift, lead->period[0]);
    dsn_axis_init(&ay, y, 1u, reach_y, shift, lead->period[1]);
    for (uint32_t sy = 0; sy < ay.span_count; sy++) {
        const dsn_span span_y = dsn_axis_span(&ay, sy);
        for (uint32_t sx = 0; sx < ax.span_count; sx++) {
            const dsn_span span_x = dsn_axis_span(&ax, sx);
            for (uint32_t j = 0; j < span_y.cell_count; j++) {
                const uint32_t cell_y = dsn_span_cell(&span_y, j, shift);
                const axis_cell on_y = cell_on_axis(&span_y, cell_y, shift);
                CellAxis lanes_y;
                if (!lattice_axis(on_y, reach_y, lanes, drop, &lanes_y)) continue;
                const uint32_t row_key = dsn_row_key(lead, cell_y);
                for (uint32_t i = 0; i < span_x.cell_count; i++) {
                    const uint32_t cell_x = dsn_span_cell(&span_x, i, shift);
                    const axis_cell on_x = cell_on_axis(&span_x, cell_x, shift);
                    CellAxis lanes_x;
                    if (!lattice_axis(on_x, reach_x, lanes, drop, &lanes_x)) continue;
                    const uint32_t key = dsn_cell_key_in_row(lead, cell_x, row_key);
                    const uint32_t count = dsn_cell_impulse_count(lead, key);
                    visit_candidates(key, count, lanes, lanes_x, lanes_y, [&](uint32_t k, uint32_t field) {
                        /* texton indices in the walk's window of radius reach: 0 .. 2 reach */
                        const uint32_t column = on_x.reach - ((field & half_mask) >> drop);
                        const uint32_t row = on_y.reach - (((field >> lanes.half_bits) & half_mask) >> drop);
                        /* the impulse as seen from the point: x + reach - column */
                        const uint64_t at_x = static_cast<uint64_t>(x + reach_x - column) << 32;
                        const uint64_t at_y = static_cast<uint64_t>(y + reach_y - row) << 32;
                        const uint32_t m = impulse_material(control, mix->count, region, key, k, at_x, at_y);
                        const dsn_texton_window *texton = &textons[m];
                        const uint32_t own_column = column - reach_x + texton->radius[0];
                        const uint32_t own_row = row - reach_y + texton->radius[1];
                        if (own_column < texton->width && own_row < texton->height)
                            add_texton_entry(&mix->material[m].asset, texton,
                                             own_row * texton->width + own_column, sums[m]);
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

/* Each material's sums normalized from its weighted offset, summed per channel (a grey material's value
   in every channel) and saturated. */
template <typename Sum>
void mix_output(const dsn_mix_state *mix, const uint32_t *weights, const Sum (*sums)[DSN_MAX_CHANNELS],
                int32_t *out) {
    int64_t totals[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t m = 0; m < mix->count; m++) {
        const dsn_noise_state *material = &mix->material[m];
        const uint32_t channels = material->asset.channels;
        int64_t offset[DSN_MAX_CHANNELS];
        int32_t values[DSN_MAX_CHANNELS];
        for (uint32_t c = 0; c < channels; c++) offset[c] = weighted_offset(material->offset[c], weights[m]);
        normalize_material(material, offset, sums[m], values);
        add_material_value(mix, m, values, totals);
    }
    store_totals(mix, totals, out);
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
    ContinuousSums sums = {};
    continuous_sums(mix, control, region, x, y, sums);
    uint32_t weights[DSN_MIX_MAX_MATERIALS];
    point_weights(mix_weights_at(control, mix->count, x, y), mix->count, weights);
    mix_output(mix, weights, sums, out);
}

void lattice_point(const dsn_mix_state *mix, const dsn_mix_control *control, uint32_t x, uint32_t y,
                   int32_t *out) {
    const MixRegion region =
        region_around(mix, control, x, y, mix->lattice_radius[0], mix->lattice_radius[1]);
    if (region.single) {
        const dsn_noise_state *material = &mix->material[region.only];
        dsn_lattice_point_fixed(dsn_mix_material_noise(mix, region.only), static_cast<int32_t>(x),
                                static_cast<int32_t>(y), out);
        spread_channels(mix, material, out);
        return;
    }
    LatticeSums sums = {};
    lattice_sums(mix, control, region, x, y, sums);
    uint32_t weights[DSN_MIX_MAX_MATERIALS];
    point_weights(
        mix_weights_at(control, mix->count, static_cast<uint64_t>(x) << 32, static_cast<uint64_t>(y) << 32),
        mix->count, weights);
    mix_output(mix, weights, sums, out);
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

int lattice_tile_as(const dsn_mix *handle, const dsn_mix_control *control, int32_t x0, int32_t y0,
                    uint32_t width, uint32_t height, void *out, dsn_output_kind kind, void *scratch,
                    size_t scratch_size) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    const size_t points = static_cast<size_t>(width) * height;
    if (tile_size_check(width, height) != DSN_OK) return DSN_ERR_TILE_SIZE;
    if (out == 0) return DSN_ERR_NULL;
    const int err = check_call(mix, control, false);
    if (err != DSN_OK) return output_error(err, mix, out, kind, points);
    const uint32_t reach_x = mix->lattice_radius[0], reach_y = mix->lattice_radius[1];
    const uint32_t only =
        tile_material(mix, control, static_cast<uint64_t>(static_cast<uint32_t>(x0) - reach_x) << 32,
                      static_cast<uint64_t>(static_cast<uint32_t>(y0) - reach_y) << 32,
                      static_cast<uint64_t>(static_cast<uint32_t>(x0) + width - 1u + reach_x) << 32,
                      static_cast<uint64_t>(static_cast<uint32_t>(y0) + height - 1u + reach_y) << 32);
    if (only < mix->count && mix->material[only].asset.channels == mix->channels) {
        const dsn_noise *material = dsn_mix_material_noise(mix, only);
        if (kind == dsn_output_fixed)
            return dsn_lattice_tile_fixed(material, x0, y0, width, height, static_cast<int32_t *>(out), 0, 0);
        if (scratch_size >= dsn_lattice_tile_scratch_size(material, width, height))
            return kind == dsn_output_float
                       ? dsn_lattice_tile_float(material, x0, y0, width, height, static_cast<float *>(out),
                                                scratch, scratch_size)
                       : dsn_lattice_tile_u8(material, x0, y0, width, height, static_cast<uint8_t *>(out),
                                             scratch, scratch_size);
    }
    size_t index = 0;
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++, index += mix->channels) {
            int32_t value[DSN_MAX_CHANNELS];
            lattice_point(mix, control, static_cast<uint32_t>(x0) + i, static_cast<uint32_t>(y0) + j, value);
            dsn_store_pixel(out, kind, index, value, mix->channels);
        }
    return DSN_OK;
}

int continuous_tile_as(const dsn_mix *handle, const dsn_mix_control *control, const dsn_grid *grid,
                       uint32_t width, uint32_t height, void *out, dsn_output_kind kind, void *scratch,
                       size_t scratch_size) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    const size_t points = static_cast<size_t>(width) * height;
    if (tile_size_check(width, height) != DSN_OK) return DSN_ERR_TILE_SIZE;
    if (out == 0) return DSN_ERR_NULL;
    int err = check_call(mix, control, true);
    if (err == DSN_OK && grid == 0) err = DSN_ERR_NULL;
    if (err != DSN_OK) return output_error(err, mix, out, kind, points);
    int64_t low_x, low_y, high_x, high_y;
    if (grid_box(grid, width, height, &low_x, &low_y, &high_x, &high_y)) {
        /* the impulses' floors lie within radius + 1 texels of the box, itself within a texel of the points
         */
        const int64_t reach_x = static_cast<int64_t>(mix->radius[0] + 2u) << 32;
        const int64_t reach_y = static_cast<int64_t>(mix->radius[1] + 2u) << 32;
        const uint64_t origin_x = static_cast<uint64_t>(grid->origin_x),
                       origin_y = static_cast<uint64_t>(grid->origin_y);
        const uint32_t only = tile_material(mix, control, origin_x + static_cast<uint64_t>(low_x - reach_x),
                                            origin_y + static_cast<uint64_t>(low_y - reach_y),
                                            origin_x + static_cast<uint64_t>(high_x + reach_x),
                                            origin_y + static_cast<uint64_t>(high_y + reach_y));
        if (only < mix->count && mix->material[only].asset.channels == mix->channels) {
            const dsn_noise *material = dsn_mix_material_noise(mix, only);
            if (scratch_size >= dsn_continuous_tile_scratch_size(material, grid, width, height)) {
                if (kind == dsn_output_fixed)
                    return dsn_continuous_tile_fixed(material, grid, width, height,
                                                     static_cast<int32_t *>(out), scratch, scratch_size);
                if (kind == dsn_output_float)
                    return dsn_continuous_tile_float(material, grid, width, height, static_cast<float *>(out),
                                                     scratch, scratch_size);
                return dsn_continuous_tile_u8(material, grid, width, height, static_cast<uint8_t *>(out),
                                              scratch, scratch_size);
            }
        }
    }
    dsn_grid_points(grid, width, height, mix->channels, [&](size_t index, uint64_t x, uint64_t y) {
        int32_t value[DSN_MAX_CHANNELS];
        continuous_point(mix, control, x, y, value);
        dsn_store_pixel(out, kind, index, value, mix->channels);
    });
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
        for (uint32_t p = 0; p < points; p++) {
            int32_t value[DSN_MAX_CHANNELS];
            continuous_point(mix, control, static_cast<uint64_t>(x[p]), static_cast<uint64_t>(y[p]), value);
            dsn_store_pixel(out, kind, static_cast<size_t>(k + p) * mix->channels, value, mix->channels);
        }
    }
    return DSN_OK;
}

} // namespace

void dsn_internal_mix_continuous_point(const dsn_mix_state *mix, const dsn_mix_control *control, uint64_t x,
                                       uint64_t y, int32_t *out) {
    continuous_point(mix, control, x, y, out);
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

int dsn_mix_lattice_tile_u8(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                            uint32_t width, uint32_t height, uint8_t *out, void *scratch,
                            size_t scratch_size) {
    return lattice_tile_as(mix, control, x0, y0, width, height, out, dsn_output_u8, scratch, scratch_size);
}

int dsn_mix_continuous_tile_u8(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                               uint32_t width, uint32_t height, uint8_t *out, void *scratch,
                               size_t scratch_size) {
    return continuous_tile_as(mix, control, grid, width, height, out, dsn_output_u8, scratch, scratch_size);
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

size_t dsn_mix_lattice_tile_scratch_size(const dsn_mix *handle, uint32_t width, uint32_t height) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    size_t most = 0;
    if (!dsn_mix_configured(mix)) return 0;
    for (uint32_t m = 0; m < mix->count; m++) {
        const size_t size = dsn_lattice_tile_scratch_size(dsn_mix_material_noise(mix, m), width, height);
        most = size > most ? size : most;
    }
    return most;
}

size_t dsn_mix_continuous_tile_scratch_size(const dsn_mix *handle, const dsn_grid *grid, uint32_t width,
                                            uint32_t height) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    size_t most = 0;
    if (!dsn_mix_configured(mix)) return 0;
    for (uint32_t m = 0; m < mix->count; m++) {
        const size_t size =
            dsn_continuous_tile_scratch_size(dsn_mix_material_noise(mix, m), grid, width, height);
        most = size > most ? size : most;
    }
    return most;
}

int dsn_mix_lattice_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                               uint32_t width, uint32_t height, int32_t *out, void *scratch,
                               size_t scratch_size) {
    return lattice_tile_as(mix, control, x0, y0, width, height, out, dsn_output_fixed, scratch, scratch_size);
}

int dsn_mix_lattice_tile_float(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                               uint32_t width, uint32_t height, float *out, void *scratch,
                               size_t scratch_size) {
    return lattice_tile_as(mix, control, x0, y0, width, height, out, dsn_output_float, scratch, scratch_size);
}

int dsn_mix_continuous_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                                  uint32_t width, uint32_t height, int32_t *out, void *scratch,
                                  size_t scratch_size) {
    return continuous_tile_as(mix, control, grid, width, height, out, dsn_output_fixed, scratch,
                              scratch_size);
}

int dsn_mix_continuous_tile_float(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                                  uint32_t width, uint32_t height, float *out, void *scratch,
                                  size_t scratch_size) {
    return continuous_tile_as(mix, control, grid, width, height, out, dsn_output_float, scratch,
                              scratch_size);
}

} // extern "C"

#endif /* DSN_MIXING */
