/* runtime/evaluators/mix_filtered.cpp - the filtered evaluation of a mix (dsn.h, "Mixing"): per material,
   filtered_point.cpp's steps (its plan, its one or two levels, their blend over the taps, one rounding)
   over the impulses that picked it, with its offsets and mean weighted by the point's weight of the
   material, the materials' values then summed; every material's sums from one walk over the impulses;
   where the weights are one material's alone, that material's own filtered point or tile. Compiled with
   DSN_MIXING and DSN_FILTERING. */
#include "core/cell_walk.h"
#include "core/continuous_sift.h"
#include "core/filtered_internal.h"
#include "core/grid_points.h"
#include "core/impulse_position.h"
#include "core/level_read.h"
#include "core/poisson_count.h"
#include "evaluators/mix_evaluation.h"
#include "kernels/kernels.h"

#if DSN_MIXING && DSN_FILTERING

namespace {

typedef dsn_filter_plan MixPlans[DSN_MIX_MAX_MATERIALS];

/* Every material's plan of the footprint (each clamps the level of detail to its own pyramid): DSN_OK or
   the plan's error. */
int mix_plans(const dsn_mix_state *mix, const dsn_footprint *footprint, MixPlans plans) {
    for (uint32_t m = 0; m < mix->count; m++) {
        const int err = dsn_internal_filter_plan(footprint, mix->material[m].asset.pyramid_levels, &plans[m]);
        if (err != DSN_OK) return err;
    }
    return DSN_OK;
}

/* The offsets from a point (Q32.32, low and high per axis) within which lie the impulses that its
   filtered evaluation reads, floors included: every material's taps and the reach of its levels. False
   when they span 2^30 texels or more (a region cannot describe them). */
bool filtered_reach(const dsn_mix_state *mix, const MixPlans plans, int64_t *low, int64_t *high) {
    const int64_t limit = static_cast<int64_t>(1) << 62;
    low[0] = low[1] = high[0] = high[1] = 0;
    for (uint32_t m = 0; m < mix->count; m++) {
        dsn_walked_level walked[2];
        uint32_t radius[2];
        const uint32_t count = dsn_internal_filter_walked_levels(&mix->material[m], &plans[m], walked);
        dsn_filter_walk_radii(walked, count, &radius[0], &radius[1]);
        for (uint32_t tap = 0; tap < plans[m].taps; tap++)
            for (uint32_t axis = 0; axis < 2; axis++) {
                const int64_t offset = axis == 0 ? plans[m].offset_x[tap] : plans[m].offset_y[tap];
                const int64_t reach = static_cast<int64_t>(radius[axis] + 2u) << 32;
                if (offset >= limit || offset <= -limit) return false;
                low[axis] = offset - reach < low[axis] ? offset - reach : low[axis];
                high[axis] = offset + reach > high[axis] ? offset + reach : high[axis];
            }
    }
    return high[0] - low[0] < limit && high[1] - low[1] < limit;
}

/* The weights' region around the point's filtered reach, or a region that reads them per impulse. */
MixRegion filtered_region(const dsn_mix_state *mix, const dsn_mix_control *control, const MixPlans plans,
                          uint64_t x, uint64_t y) {
    int64_t low[2], high[2];
    if (!filtered_reach(mix, plans, low, high)) {
        MixRegion region;
        region.uniform = region.single = false;
        region.only = 0;
        region.weights = MixWeights();
        return region;
    }
    return mix_region(control, mix->count, x + static_cast<uint64_t>(low[0]),
                      y + static_cast<uint64_t>(low[1]), x + static_cast<uint64_t>(high[0]),
                      y + static_cast<uint64_t>(high[1]), 64u);
}

/* What the filtered mix reads of a material: the one or two levels its plan blends and their walk radii;
   no levels where its plan fades (its impulses are then passed over). */
struct MaterialLevels {
    dsn_walked_level walked[2];
    uint32_t count, radius_x, radius_y;
};

/* A material's impulses in reach of a tap, waiting for their reads: their impulse-to-point offsets
   (Q32.32), with room for the kernel's reads of whole vectors past the last. */
const uint32_t waiting_most = 64;
struct WaitingImpulses {
    int64_t x[waiting_most + 16], y[waiting_most + 16];
    uint32_t count;
};

/* The waiting impulses' reads of each of a material's levels added to its sums at the tap (level_sums[l]):
   by the kernel's vector reads for 8-bit levels where it has them (each candidate's c its offset, so the
   tests' tap_shift is 0), else one by one (add_level). */
void read_waiting(const dsn_noise_state *material, const MaterialLevels &own, WaitingImpulses *waiting,
                  uint64_t (*level_sums)[DSN_MAX_CHANNELS]) {
    if (waiting->count == 0) return; /* (a tap that no impulse of the material reaches: no call) */
    const dsn_asset *asset = &material->asset;
    dsn_filter_level_reads_entry *vector_reads =
        asset->bits == 8 ? dsn_kernel_entries_of(material->tile_kernel)->filter_level_reads : 0;
    for (uint32_t l = 0; l < own.count; l++) {
        const dsn_walked_level &level = own.walked[l];
        if (vector_reads != 0) {
            const LevelTest test_x = level_test(level, level.radius_x, 0, false),
                            test_y = level_test(level, level.radius_y, 0, false);
            const uint64_t tests[5] = {test_x.start, test_x.limit, test_y.start, test_y.limit, test_x.bias};
            const uint32_t unused_narrow_tests[6] = {0, 0, 0, 0, 0, 0};
            vector_reads(&level, asset->channels, waiting->x, waiting->y, 0, 0, waiting->count, tests,
                         unused_narrow_tests, level_sums[l], 0);
        } else {
            for (uint32_t i = 0; i < waiting->count; i++)
                add_level<false>(level, asset->channels, asset->bits, waiting->x[i], waiting->y[i],
                                 level_sums[l], 0);
        }
    }
    waiting->count = 0;
}

/* The impulses of one tap within the largest reach, listed to pick their materials together: their
   impulse-to-point offsets (Q32.32), material hashes and integer positions. */
const uint32_t listed_most = 64;
struct ListedImpulses {
    int64_t x[listed_most], y[listed_most];
    uint32_t hashes[listed_most], whole_x[listed_most], whole_y[listed_most];
    uint32_t count;
};

/* Where a tap lists its impulses: the tap, the largest of the materials' reaches, and the tap's index
   in each material's sums (sums[m][tap]). */
struct ListingTap {
    uint64_t x, y;
    uint32_t radius_x, radius_y, tap;
};

/* The listed impulses' materials: 8 at a time by the kernel's lanes where it has them and they read the
   control around the tap (every listed impulse lies within the largest radius + 1 of it, so its integer
   position within radius + 2 of the tap's), else one by one (hashed_material); then each impulse waits for
   its material's reads where it lies within its levels' reach. */
void pick_listed(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                 const ListingTap &tap, const MaterialLevels *levels, ListedImpulses *listed,
                 WaitingImpulses *waiting, dsn_filter_sums *sums) {
    uint32_t materials[listed_most];
    dsn_mix_picks_entry *picks =
        region.single || region.uniform ? 0 : dsn_kernel_entries_of(mix->material[0].tile_kernel)->mix_picks;
    if (picks == 0 || !picks(control, mix->count, static_cast<uint32_t>(tap.x >> 32),
                             static_cast<uint32_t>(tap.y >> 32), tap.radius_x + 2u, tap.radius_y + 2u,
                             listed->hashes, listed->whole_x, listed->whole_y, listed->count, materials))
        for (uint32_t i = 0; i < listed->count; i++)
            materials[i] = hashed_material(control, mix->count, region, listed->hashes[i],
                                           static_cast<uint64_t>(listed->whole_x[i]) << 32,
                                           static_cast<uint64_t>(listed->whole_y[i]) << 32);
    for (uint32_t i = 0; i < listed->count; i++) {
        const uint32_t m = materials[i];
        const MaterialLevels &own = levels[m];
        if (own.count == 0 || !within_reach(listed->x[i], own.radius_x) ||
            !within_reach(listed->y[i], own.radius_y))
            continue;
        WaitingImpulses *own_waiting = &waiting[m];
        own_waiting->x[own_waiting->count] = listed->x[i];
        own_waiting->y[own_waiting->count] = listed->y[i];
        if (++own_waiting->count == waiting_most)
            read_waiting(&mix->material[m], own, own_waiting, sums[m][tap.tap]);
    }
    listed->count = 0;
}

/* The sums of every material's levels at each tap of `plan` around (x, y), over the impulses of material
   0's process: filtered_walk.cpp's tap-by-tap walk within the largest of the materials' reaches, each
   impulse within it listed, the listed impulses then picking their materials (pick_listed) and waiting
   for their material's reads. */
void materials_sums(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                    uint64_t x, uint64_t y, const dsn_filter_plan *plan, const MaterialLevels *levels,
                    dsn_filter_sums *sums) {
    const dsn_noise_state *lead = &mix->material[0];
    const uint32_t shift = lead->cell_shift;
    uint32_t radius_x = 0, radius_y = 0;
    for (uint32_t m = 0; m < mix->count; m++) {
        radius_x = levels[m].radius_x > radius_x ? levels[m].radius_x : radius_x;
        radius_y = levels[m].radius_y > radius_y ? levels[m].radius_y : radius_y;
    }
    WaitingImpulses waiting[DSN_MIX_MAX_MATERIALS];
    ListedImpulses listed;
    listed.count = 0;
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        const ListingTap at = {x + static_cast<uint64_t>(plan->offset_x[tap]),
                               y + static_cast<uint64_t>(plan->offset_y[tap]), radius_x, radius_y, tap};
        for (uint32_t m = 0; m < mix->count; m++) {
            waiting[m].count = 0;
            for (uint32_t l = 0; l < 2; l++)
                for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) sums[m][tap][l][c] = 0;
        }
        const PointAxis wx = point_axis(at.x, radius_x, shift, lead->period[0]);
        const PointAxis wy = point_axis(at.y, radius_y, shift, lead->period[1]);
        for (uint32_t sy = 0; sy < wy.axis.span_count; sy++) {
            const dsn_span span_y = dsn_axis_span(&wy.axis, sy);
            for (uint32_t j = 0; j < span_y.cell_count; j++) {
                const uint32_t cell_y = dsn_span_cell(&span_y, j, shift), origin_y = cell_y << shift;
                const uint32_t row_key = dsn_row_key(lead, cell_y);
                for (uint32_t sx = 0; sx < wx.axis.span_count; sx++) {
                    const dsn_span span_x = dsn_axis_span(&wx.axis, sx);
                    for (uint32_t i = 0; i < span_x.cell_count; i++) {
                        const uint32_t cell_x = dsn_span_cell(&span_x, i, shift), origin_x = cell_x << shift;
                        const uint32_t key = dsn_cell_key_in_row(lead, cell_x, row_key);
                        const uint32_t impulses = dsn_cell_impulse_count(lead, key);
                        for (uint32_t k = 0; k < impulses; k++) {
                            const uint32_t hash = dsn_impulse_hash(lead, key, k);
                            int64_t dx, dy;
                            if (!impulse_offset(wy, span_y, origin_y, dsn_impulse_bits_y(hash), &dy) ||
                                !impulse_offset(wx, span_x, origin_x, dsn_impulse_bits_x(hash), &dx) ||
                                !within_reach(dx, radius_x) || !within_reach(dy, radius_y))
                                continue;
                            const uint32_t n = listed.count;
                            listed.x[n] = dx;
                            listed.y[n] = dy;
                            listed.hashes[n] = region.single ? 0u : dsn_material_hash(key, k);
                            listed.whole_x[n] =
                                static_cast<uint32_t>((at.x - static_cast<uint64_t>(dx)) >> 32);
                            listed.whole_y[n] =
                                static_cast<uint32_t>((at.y - static_cast<uint64_t>(dy)) >> 32);
                            if (++listed.count == listed_most)
                                pick_listed(mix, control, region, at, levels, &listed, waiting, sums);
                        }
                    }
                }
            }
        }
        pick_listed(mix, control, region, at, levels, &listed, waiting, sums);
        for (uint32_t m = 0; m < mix->count; m++)
            read_waiting(&mix->material[m], levels[m], &waiting[m], sums[m][tap]);
    }
}

/* Material m with its offsets and mean weighted by `weight` (Q2.14): filtered_point.cpp's steps on it
   give the material's term of the mix. */
void weighted_material(const dsn_mix_state *mix, uint32_t m, uint32_t weight, dsn_noise_state *weighted) {
    *weighted = mix->material[m];
    material_weighted_offset(&mix->material[m], weight, weighted->offset);
    const uint32_t levels = weighted->asset.pyramid_levels; /* (the offsets past them are zero) */
    for (uint32_t c = 0; c < weighted->asset.channels && c < DSN_MAX_CHANNELS; c++) {
        for (uint32_t l = 0; l < levels && l < 8; l++)
            weighted->level_offset[l][c] = weighted_offset(weighted->level_offset[l][c], weight);
        weighted->asset.mean[c] = static_cast<int32_t>(weighted_offset(weighted->asset.mean[c], weight));
    }
}

/* Material m's term from its sums (filtered_point.cpp's blend over the taps and one rounding). */
void material_value(const dsn_noise_state *weighted, const dsn_filter_plan *plan, const MaterialLevels &own,
                    const dsn_filter_sums sums, int32_t *out) {
    int64_t totals[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        for (uint32_t l = 0; l < own.count; l++) {
            int64_t values[DSN_MAX_CHANNELS] = {0, 0, 0};
            dsn_internal_filter_level_values(weighted, &own.walked[l], sums[tap][l], values);
            dsn_internal_filter_add_level(weighted, plan, l, values, totals);
        }
        if (own.count == 1) dsn_internal_filter_add_mean(weighted, plan, totals);
    }
    dsn_internal_filter_round(weighted, plan, totals, out);
}

/* Material m's levels for its plan (none where the plan fades, its term then set), its material weighted
   into `weighted`. */
void material_levels(const dsn_mix_state *mix, uint32_t m, const MixPlans plans, const uint32_t *weights,
                     dsn_noise_state *weighted, MaterialLevels *own, int32_t *term) {
    own->count = own->radius_x = own->radius_y = 0;
    weighted_material(mix, m, weights[m], weighted);
    if (dsn_internal_filter_fade(weighted, &plans[m], term)) return;
    own->count = dsn_internal_filter_walked_levels(weighted, &plans[m], own->walked);
    dsn_filter_walk_radii(own->walked, own->count, &own->radius_x, &own->radius_y);
}

#if !DSN_SMALL_CODE
/* Whether two plans have the same taps (the footprint's alone: a material's pyramid clamps only its level
   of detail). */
bool same_taps(const dsn_filter_plan &a, const dsn_filter_plan &b) {
    if (a.taps != b.taps) return false;
    for (uint32_t tap = 0; tap < a.taps; tap++)
        if (a.offset_x[tap] != b.offset_x[tap] || a.offset_y[tap] != b.offset_y[tap]) return false;
    return true;
}

/* kept_terms for a mix of two materials that the sifted walk lists together (dsn_internal_filter_sums_split:
   both drawn, with the same taps and walk): each impulse listed once for the material it draws. False
   elsewhere (kept_terms then makes every term). */
bool split_terms(const dsn_mix_state *mix, const uint64_t *thresholds, uint64_t x, uint64_t y,
                 const MixPlans plans, const uint32_t *weights, int32_t (*terms)[DSN_MAX_CHANNELS]) {
    if (mix->count != 2 || thresholds[0] == 0 || thresholds[0] >> 32 != 0 || !same_taps(plans[0], plans[1]))
        return false;
    dsn_noise_state weighted[2];
    MaterialLevels own[2];
    for (uint32_t m = 0; m < 2; m++) {
        material_levels(mix, m, plans, weights, &weighted[m], &own[m], terms[m]);
        if (own[m].count == 0) return false;
    }
    if (own[0].count != own[1].count) return false;
    const dsn_impulse_filter filter = material_filter(thresholds, 0);
    dsn_filter_sums sums[2];
    if (!dsn_internal_filter_sums_split(&mix->material[0], &mix->material[1], x, y, &plans[0], own[0].walked,
                                        own[1].walked, own[0].count, &filter, sums[0], sums[1]))
        return false;
    for (uint32_t m = 0; m < 2; m++) material_value(&weighted[m], &plans[m], own[m], sums[m], terms[m]);
    return true;
}

/* The terms of the materials where the weights are uniform: two materials listed together where they
   take it (split_terms), else each material's sums by the sifted walk of one noise (filtered_sift.cpp, on
   vectors where the kernel lists candidates) over the impulses that draw it, every material's impulses
   listed again (the listing costs less than the scalar walk's pick per impulse: make bench's mix_bench),
   then its term, each material weighted once. The same impulses and reads as materials_sums's, so the
   same sums. Kept out of line, as walked_terms is, so that the sifted walk's stack is not under
   walked_terms's frame. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
void kept_terms(const dsn_mix_state *mix, const MixRegion &region, uint64_t x, uint64_t y, const MixPlans plans,
                const uint32_t *weights, int32_t (*terms)[DSN_MAX_CHANNELS]) {
    const uint64_t *thresholds = region.draws.thresholds;
    if (split_terms(mix, thresholds, x, y, plans, weights, terms)) return;
    dsn_noise_state weighted;
    for (uint32_t m = 0; m < mix->count; m++) {
        MaterialLevels own;
        material_levels(mix, m, plans, weights, &weighted, &own, terms[m]);
        if (own.count == 0) continue;
        dsn_filter_sums sums;
        const dsn_impulse_filter filter = material_filter(thresholds, m);
        if (filter.low < filter.high)
            dsn_internal_filter_sums_kept(&mix->material[m], x, y, &plans[m], own.walked, own.count, &filter,
                                          sums);
        else
            __builtin_memset(sums, 0, sizeof sums);
        material_value(&weighted, &plans[m], own, sums, terms[m]);
    }
}
#endif

/* The terms of the materials where the weights vary: each material's levels, the sums of all by one walk
   (materials_sums), then each term. Kept out of line (see kept_terms). */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
void walked_terms(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region, uint64_t x,
                  uint64_t y, const MixPlans plans, const uint32_t *weights, int32_t (*terms)[DSN_MAX_CHANNELS]) {
    MaterialLevels levels[DSN_MIX_MAX_MATERIALS];
    dsn_noise_state weighted;
    bool walked = false;
    for (uint32_t m = 0; m < mix->count; m++) {
        material_levels(mix, m, plans, weights, &weighted, &levels[m], terms[m]);
        walked = walked || levels[m].count != 0;
    }
    if (!walked) return;
    dsn_filter_sums sums[DSN_MIX_MAX_MATERIALS];
    materials_sums(mix, control, region, x, y, &plans[0], levels, sums);
    for (uint32_t m = 0; m < mix->count; m++)
        if (levels[m].count != 0) {
            weighted_material(mix, m, weights[m], &weighted);
            material_value(&weighted, &plans[m], levels[m], sums[m], terms[m]);
        }
}

/* The materials' terms where the weights mix: for each material whose plan does not fade, its levels and
   sums (the plans' taps are the footprint's alone: a material's pyramid clamps only its level of detail),
   then its term from its sums, with its weighted offsets and mean. */
void mixed_terms(const dsn_mix_state *mix, const dsn_mix_control *control, const MixRegion &region,
                 uint64_t x, uint64_t y, const MixPlans plans, const uint32_t *weights,
                 int32_t (*terms)[DSN_MAX_CHANNELS]) {
#if !DSN_SMALL_CODE /* (the small build has no sifted walk) */
    if (region.uniform) {
        kept_terms(mix, region, x, y, plans, weights, terms);
        return;
    }
#endif
    walked_terms(mix, control, region, x, y, plans, weights, terms);
}

void filtered_point(const dsn_mix_state *mix, const dsn_mix_control *control, uint64_t x, uint64_t y,
                    const MixPlans plans, int32_t *out) {
    const MixRegion region = filtered_region(mix, control, plans, x, y);
    if (region.single) {
        const dsn_noise_state *material = &mix->material[region.only];
        dsn_internal_filtered_point(material, x, y, &plans[region.only], out);
        spread_channels(mix, material, out);
        return;
    }
    if (plans[0].lod_q8 == 0 && plans[0].taps == 1) { /* unfiltered: the continuous mix, as a noise's */
        dsn_internal_mix_continuous_point(mix, control, x, y, out);
        return;
    }
    uint32_t weights[DSN_MIX_MAX_MATERIALS];
    MixWeights at_point;
    mix_weights_at(control, mix->count, x, y, &at_point);
    point_weights(at_point, mix->count, weights);
    int32_t terms[DSN_MIX_MAX_MATERIALS][DSN_MAX_CHANNELS];
    mixed_terms(mix, control, region, x, y, plans, weights, terms);
    int64_t totals[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t m = 0; m < mix->count; m++) add_material_value(mix, m, terms[m], totals);
    store_totals(mix, totals, out);
}

int filtered_point_as(const dsn_mix *handle, const dsn_mix_control *control, int64_t x, int64_t y,
                      const dsn_footprint *footprint, void *out, dsn_output_kind kind) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    if (out == 0) return DSN_ERR_NULL;
    MixPlans plans;
    int err = check_call(mix, control, true);
    if (err == DSN_OK) err = mix_plans(mix, footprint, plans);
    if (err != DSN_OK) return output_error(err, mix, out, kind, 1);
    int32_t value[DSN_MAX_CHANNELS];
    filtered_point(mix, control, static_cast<uint64_t>(x), static_cast<uint64_t>(y), plans, value);
    dsn_store_pixel(out, kind, 0, value, mix->channels);
    return DSN_OK;
}

/* A material's own filtered tile where the tile's whole reach has its weights alone; -1 where not. */
int single_material_tile(const dsn_mix_state *mix, const dsn_mix_control *control, const dsn_grid *grid,
                         uint32_t max_taps, const MixPlans plans, uint32_t width, uint32_t height, void *out,
                         dsn_output_kind kind, void *scratch, size_t scratch_size) {
    int64_t low_x, low_y, high_x, high_y, low[2], high[2];
    if (!grid_box(grid, width, height, &low_x, &low_y, &high_x, &high_y) ||
        !filtered_reach(mix, plans, low, high))
        return -1;
    const uint64_t origin_x = static_cast<uint64_t>(grid->origin_x),
                   origin_y = static_cast<uint64_t>(grid->origin_y);
    if (high_x - low_x + high[0] - low[0] >= (static_cast<int64_t>(1) << 62) ||
        high_y - low_y + high[1] - low[1] >= (static_cast<int64_t>(1) << 62))
        return -1;
    const uint32_t only = tile_material(mix, control, origin_x + static_cast<uint64_t>(low_x + low[0]),
                                        origin_y + static_cast<uint64_t>(low_y + low[1]),
                                        origin_x + static_cast<uint64_t>(high_x + high[0]),
                                        origin_y + static_cast<uint64_t>(high_y + high[1]));
    if (only >= mix->count || mix->material[only].asset.channels != mix->channels) return -1;
    const dsn_noise *material = dsn_mix_material_noise(mix, only);
    if (scratch_size < dsn_filtered_tile_scratch_size(material, grid, max_taps, width, height)) return -1;
    if (kind == dsn_output_fixed)
        return dsn_filtered_tile_fixed(material, grid, max_taps, width, height, static_cast<int32_t *>(out),
                                       scratch, scratch_size);
    if (kind == dsn_output_float)
        return dsn_filtered_tile_float(material, grid, max_taps, width, height, static_cast<float *>(out),
                                       scratch, scratch_size);
    return dsn_filtered_tile_u8(material, grid, max_taps, width, height, static_cast<uint8_t *>(out), scratch,
                                scratch_size);
}

int filtered_tile_as(const dsn_mix *handle, const dsn_mix_control *control, const dsn_grid *grid,
                     uint32_t max_taps, uint32_t width, uint32_t height, void *out, dsn_output_kind kind,
                     void *scratch, size_t scratch_size) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    int err = grid_tile_check(mix, control, grid, width, height, out, kind);
    if (err != DSN_OK) return err;
    /* the footprint of every pixel: the grid's steps */
    const dsn_footprint footprint = {grid->column_step_x, grid->column_step_y, grid->row_step_x,
                                     grid->row_step_y, max_taps};
    MixPlans plans;
    err = mix_plans(mix, &footprint, plans);
    if (err != DSN_OK) return output_error(err, mix, out, kind, static_cast<size_t>(width) * height);
    const int single = single_material_tile(mix, control, grid, max_taps, plans, width, height, out, kind,
                                            scratch, scratch_size);
    if (single >= 0) return single;
    dsn_grid_points(grid, width, height, mix->channels, [&](size_t index, uint64_t x, uint64_t y) {
        int32_t value[DSN_MAX_CHANNELS];
        filtered_point(mix, control, x, y, plans, value);
        dsn_store_pixel(out, kind, index, value, mix->channels);
    });
    return DSN_OK;
}

} // namespace

extern "C" {

int dsn_mix_filtered_point_fixed(const dsn_mix *mix, const dsn_mix_control *control, int64_t x, int64_t y,
                                 const dsn_footprint *footprint, int32_t *out) {
    return filtered_point_as(mix, control, x, y, footprint, out, dsn_output_fixed);
}

int dsn_mix_filtered_point_float(const dsn_mix *mix, const dsn_mix_control *control, double x, double y,
                                 const dsn_footprint *footprint, float *out) {
    return filtered_point_as(mix, control, dsn_coordinate_from_double(x), dsn_coordinate_from_double(y),
                             footprint, out, dsn_output_float);
}

int dsn_mix_filtered_point_u8(const dsn_mix *mix, const dsn_mix_control *control, int64_t x, int64_t y,
                              const dsn_footprint *footprint, uint8_t *out) {
    return filtered_point_as(mix, control, x, y, footprint, out, dsn_output_u8);
}

size_t dsn_mix_filtered_tile_scratch_size(const dsn_mix *handle, const dsn_grid *grid, uint32_t max_taps,
                                          uint32_t width, uint32_t height) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    size_t most = 0;
    if (!dsn_mix_configured(mix)) return 0;
    for (uint32_t m = 0; m < mix->count; m++) {
        const size_t size =
            dsn_filtered_tile_scratch_size(dsn_mix_material_noise(mix, m), grid, max_taps, width, height);
        most = size > most ? size : most;
    }
    return most;
}

int dsn_mix_filtered_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                                uint32_t max_taps, uint32_t width, uint32_t height, int32_t *out,
                                void *scratch, size_t scratch_size) {
    return filtered_tile_as(mix, control, grid, max_taps, width, height, out, dsn_output_fixed, scratch,
                            scratch_size);
}

int dsn_mix_filtered_tile_float(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                                uint32_t max_taps, uint32_t width, uint32_t height, float *out, void *scratch,
                                size_t scratch_size) {
    return filtered_tile_as(mix, control, grid, max_taps, width, height, out, dsn_output_float, scratch,
                            scratch_size);
}

int dsn_mix_filtered_tile_u8(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                             uint32_t max_taps, uint32_t width, uint32_t height, uint8_t *out, void *scratch,
                             size_t scratch_size) {
    return filtered_tile_as(mix, control, grid, max_taps, width, height, out, dsn_output_u8, scratch,
                            scratch_size);
}

} // extern "C"

#endif /* DSN_MIXING && DSN_FILTERING */
