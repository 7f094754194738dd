/* runtime/evaluators/mix_evaluation.h - what the mix's evaluators share (mix_point.cpp: the walks, lattice
   and continuous; mix_tile.cpp: the tiles; mix_filtered.cpp: filtered): the checks of a call and its zeroed
   output, a material's own evaluators where the weights are that material's alone (tile_material), its
   weighted offsets, the saturated sums of the materials' values, the region of the weights that a lattice
   window reads and a uniform region's draws, and mix_point.cpp's walks that the others take: groups of
   continuous points, bands and runs of lattice rows (the tiles), and the continuous point that an
   unfiltered footprint gives. Internal to libdsn; not installed. */
#ifndef DSN_MIX_EVALUATION_H
#define DSN_MIX_EVALUATION_H

#include "core/continuous_internal.h"
#include "core/mix_weights.h"
#include "core/normalize_fixed.h"
#include "kernels/kernels.h"

#if DSN_MIXING

namespace {

/* Whether a point-minus-impulse offset (Q32.32) lies within (-(radius + 1), radius + 1) texels. */
inline bool within_reach(int64_t offset, uint32_t radius) {
    const uint64_t reach = static_cast<uint64_t>(radius + 1u) << 32;
    return static_cast<uint64_t>(offset) + reach - 1u < 2u * reach - 1u;
}

/* floor(offset w / 2^14), exactly, for |offset| < 2^61 and w <= 2^14. */
inline int64_t weighted_offset(int64_t offset, uint32_t weight) {
    const uint64_t bias = static_cast<uint64_t>(1) << 63;
    const int64_t high = static_cast<int64_t>((static_cast<uint64_t>(offset) + bias) >> mix_weight_bits) -
                         static_cast<int64_t>(bias >> mix_weight_bits);
    const int64_t low = offset - high * (static_cast<int64_t>(1) << mix_weight_bits); /* in [0, 2^14) */
    return high * static_cast<int64_t>(weight) + ((low * static_cast<int64_t>(weight)) >> mix_weight_bits);
}

/* A material's offset (its mean minus its sums' expectation, per channel) weighted by its weight (of
   2^14) at a point: the impulses that draw the material are that share of the process's, so its expected
   sums take that share, and so must its mean. */
inline void material_weighted_offset(const dsn_noise_state *material, uint32_t weight, int64_t *offset) {
    /* (read once: GCC cannot tell that the stores through offset leave it alone, and reloading it after each
       made a transition's lattice tile 20% slower in mix_bench) */
    const uint32_t channels = material->asset.channels;
    for (uint32_t c = 0; c < channels && c < DSN_MAX_CHANNELS; c++)
        offset[c] = weighted_offset(material->offset[c], weight);
}

/* The value of one material's own noise (the mix where the weights are that material's alone) as the mix's
   channels: a grey material's value in each. */
inline void spread_channels(const dsn_mix_state *mix, const dsn_noise_state *material, int32_t *out) {
    if (material->asset.channels == 1)
        for (uint32_t c = 1; c < mix->channels; c++) out[c] = out[0];
}

inline uint32_t values_per_point(const dsn_mix_state *mix) {
    return dsn_mix_configured(mix) ? mix->channels : 1u;
}

inline int check_call(const dsn_mix_state *mix, const dsn_mix_control *control, bool continuous) {
    if (!dsn_mix_configured(mix)) return DSN_ERR_NULL;
    const int err = mix_control_check(control);
    if (err != DSN_OK || !continuous) return err;
    for (uint32_t m = 0; m < mix->count; m++)
        if (!dsn_continuous_reads(&mix->material[m])) return DSN_ERR_CONTINUOUS_MISMATCH;
    return DSN_OK;
}

/* The `points` points of output zeroed on an error but DSN_ERR_TILE_SIZE; returns err. */
inline int output_error(int err, const dsn_mix_state *mix, void *out, dsn_output_kind kind, size_t points) {
    if (err != DSN_OK && err != DSN_ERR_TILE_SIZE && out != 0)
        __builtin_memset(out, 0, points * values_per_point(mix) * (kind == dsn_output_u8 ? 1u : 4u));
    return err;
}

inline int tile_size_check(uint32_t width, uint32_t height) {
    return width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE
               ? DSN_ERR_TILE_SIZE
               : DSN_OK;
}

/* The checks of a continuous or filtered tile call on a grid: DSN_OK, or the error with the output zeroed
   as output_error zeroes it. */
inline int grid_tile_check(const dsn_mix_state *mix, const dsn_mix_control *control, const dsn_grid *grid,
                           uint32_t width, uint32_t height, void *out, dsn_output_kind kind) {
    if (tile_size_check(width, height) != DSN_OK) return DSN_ERR_TILE_SIZE;
    if (out == 0) return DSN_ERR_NULL;
    int err = check_call(mix, control, true);
    if (err == DSN_OK && grid == 0) err = DSN_ERR_NULL;
    return output_error(err, mix, out, kind, static_cast<size_t>(width) * height);
}

/* The material whose weights a tile's whole reach has alone (its own tile function then gives the mix's
   bits), or count where the weights mix or may: positions [low, high] per axis, Q32.32. */
inline uint32_t tile_material(const dsn_mix_state *mix, const dsn_mix_control *control, uint64_t low_x,
                              uint64_t low_y, uint64_t high_x, uint64_t high_y) {
    const MixRegion region = mix_region(control, mix->count, low_x, low_y, high_x, high_y, 1024u);
    return region.single ? region.only : mix->count;
}

/* Whether the grid's points lie within a box that a region can describe: its corners' offsets from the
   origin, low and high per axis (Q32.32), each step under 2^46 (so a side's span stays below 2^62) and
   the box under 2^30 texels. */
inline bool grid_box(const dsn_grid *grid, uint32_t width, uint32_t height, int64_t *low_x, int64_t *low_y,
                     int64_t *high_x, int64_t *high_y) {
    const int64_t steps[4] = {grid->column_step_x, grid->row_step_x, grid->column_step_y, grid->row_step_y};
    const int64_t limit = static_cast<int64_t>(1) << 46;
    for (uint32_t k = 0; k < 4; k++)
        if (steps[k] >= limit || steps[k] <= -limit) return false;
    const int64_t columns = static_cast<int64_t>(width) - 1, rows = static_cast<int64_t>(height) - 1;
    int64_t *lows[2] = {low_x, low_y}, *highs[2] = {high_x, high_y};
    for (uint32_t axis = 0; axis < 2; axis++) {
        const int64_t along_row = steps[2 * axis] * columns, along_column = steps[2 * axis + 1] * rows;
        *lows[axis] = (along_row < 0 ? along_row : 0) + (along_column < 0 ? along_column : 0);
        *highs[axis] = (along_row > 0 ? along_row : 0) + (along_column > 0 ? along_column : 0);
        if (*highs[axis] - *lows[axis] >= (static_cast<int64_t>(1) << 62)) return false;
    }
    return true;
}

/* Material m's value (its channels) added to the mix's totals: a grey material's value to each channel
   (channels are 1 or 3, as the loader allows). */
inline void add_material_value(const dsn_mix_state *mix, uint32_t m, const int32_t *value, int64_t *totals) {
    const uint32_t grey = mix->material[m].asset.channels == 1 ? 0u : 1u;
    totals[0] += value[0];
    if (mix->channels == 1) return;
    totals[1] += value[grey];
    totals[2] += value[2 * grey];
}

/* a + b saturated to int32 (the 64-bit sum saturated, exactly), in 32-bit operations: the overflow where
   both operands' signs differ from the sum's, then the limit on a's side. */
inline int32_t saturating_add(int32_t a, int32_t b) {
    const uint32_t sum = static_cast<uint32_t>(a) + static_cast<uint32_t>(b);
    const uint32_t overflow = (static_cast<uint32_t>(a) ^ sum) & (static_cast<uint32_t>(b) ^ sum);
    const uint32_t limit = (static_cast<uint32_t>(a) >> 31) + 0x7FFFFFFFu;
    return static_cast<int32_t>((overflow >> 31) != 0 ? limit : sum);
}

inline int32_t saturated_total(int64_t total) {
    return total > INT32_MAX ? INT32_MAX : total < INT32_MIN ? INT32_MIN : static_cast<int32_t>(total);
}

/* The totals as the mix's output, saturated to int32. */
inline void store_totals(const dsn_mix_state *mix, const int64_t *totals, int32_t *out) {
    for (uint32_t c = 0; c < mix->channels; c++) out[c] = saturated_total(totals[c]);
}

/* Continuous points near each other (part of a continuous tile's row, neighbours in a batch) are walked at
   once, up to group_points of them (dsn_internal_mix_continuous_points). */
const uint32_t group_points = 16;

/* The points of a run: a row of lattice points (x0 + i, y), 1 .. run_points of them, with contiguous
   coordinates (on a periodic axis not across the int32 sign change, where the reduction breaks them). */
const uint32_t run_points = 32;

/* The region of grid samples that the impulses reaching a window of `rows` rows of `length` points may
   read: their floors lie within the lattice reach of it. */
inline MixRegion window_region(const dsn_mix_state *mix, const dsn_mix_control *control, uint32_t x0,
                               uint32_t length, uint32_t y0, uint32_t rows) {
    const uint32_t reach_x = mix->lattice_radius[0], reach_y = mix->lattice_radius[1];
    const uint32_t longest = length > rows ? length : rows;
    return mix_region(control, mix->count, static_cast<uint64_t>(x0 - reach_x) << 32,
                      static_cast<uint64_t>(y0 - reach_y) << 32,
                      static_cast<uint64_t>(x0 + length - 1u + reach_x) << 32,
                      static_cast<uint64_t>(y0 + rows - 1u + reach_y) << 32, 16u + longest - 1u);
}

/* The impulses that draw material m where the weights are uniform: those whose hashes lie between
   the uniform draws' thresholds (mix_weights.h) on each side of it (none, low == high, where no hash draws
   it). */
inline dsn_impulse_filter material_filter(const uint64_t *thresholds, uint32_t m) {
    const dsn_impulse_filter filter = {m == 0 ? 0u : thresholds[m - 1u],
                                       m + 1u < dsn_point_materials_most ? thresholds[m]
                                                                         : static_cast<uint64_t>(1) << 32};
    return filter;
}

} // namespace

/* The mix's values at the continuous point (x, y), Q32.32, for a mix and control that passed check_call
   (mix_point.cpp). */
void dsn_internal_mix_continuous_point(const dsn_mix_state *mix, const dsn_mix_control *control, uint64_t x,
                                       uint64_t y, int32_t *out);

/* The values of `count` continuous points (count <= group_points): as a group where they lie close
   together and the weights mix around them, else point by point (a material's own evaluator where its
   weights hold alone). */
void dsn_internal_mix_continuous_points(const dsn_mix_state *mix, const dsn_mix_control *control,
                                        const uint64_t *xs, const uint64_t *ys, uint32_t count,
                                        int32_t (*values)[DSN_MAX_CHANNELS]);

/* The output of a band's points (or a run's), the first point at index `first` of out. */
typedef struct dsn_mix_band_target {
    void *out;
    dsn_output_kind kind;
    size_t first;
} dsn_mix_band_target;

/* A band of `rows` rows of `width` points from (x0, y): its sums of every material from one walk over the
   impulses that reach it (each found once, its texton added to the points it reaches) into `scratch`
   (mix_tile.cpp's band_row_bytes a row), then each point's output. */
void dsn_internal_mix_walk_band(const dsn_mix_state *mix, const dsn_mix_control *control, uint32_t x0,
                                uint32_t width, uint32_t y, uint32_t rows, uint32_t *scratch,
                                const dsn_mix_band_target &target);

/* A run of `length` points (at most run_points) from (x, y): walked as a band of one row, its sums on the
   stack. */
void dsn_internal_mix_walk_run(const dsn_mix_state *mix, const dsn_mix_control *control, uint32_t x,
                               uint32_t length, uint32_t y, const dsn_mix_band_target &target);

#endif /* DSN_MIXING */

#endif /* DSN_MIX_EVALUATION_H */
