/* runtime/core/mix_weights.h - the mixing weights (dsn.h, "Mixing"): a caller's dsn_mix_control read
   bilinearly at a position, the material an impulse picks there, and the weights of the evaluated point.
   Internal to libdsn; not installed (everything here has internal linkage). */
#ifndef DSN_MIX_WEIGHTS_H
#define DSN_MIX_WEIGHTS_H

#include <stdint.h>

#include "core/cell_hash.h"
#include "setup/mix_state.h"

#if DSN_MIXING

namespace {

const uint32_t mix_weight_bits = 14; /* the point's weights are Q2.14 */

/* DSN_OK for a control within dsn_mix_control's ranges; DSN_ERR_NULL or DSN_ERR_ARGUMENT. */
inline int mix_control_check(const dsn_mix_control *control) {
    if (control == 0 || control->weights == 0) return DSN_ERR_NULL;
    if (control->width == 0 || control->height == 0 || control->width > 65535u || control->height > 65535u ||
        static_cast<uint64_t>(control->width) * control->height > (static_cast<uint64_t>(1) << 24) ||
        control->spacing_shift > 16u || (control->flags & ~(DSN_MIX_PERIODIC_X | DSN_MIX_PERIODIC_Y)) != 0)
        return DSN_ERR_ARGUMENT;
    return DSN_OK;
}

/* One axis of a bilinear read of the grid: the two samples' indices and the upper one's 8-bit weight. */
struct MixAxis {
    uint32_t first, second, fraction;
    int64_t index; /* the lower sample's index before clamping or wrapping: floor(u) */
};

inline uint32_t clamped_sample(int64_t index, uint32_t size) {
    return index < 0 ? 0u : index >= static_cast<int64_t>(size) ? size - 1u : static_cast<uint32_t>(index);
}

/* Floor modulo of an index in [-2^31, 2^31) in 32-bit arithmetic (no 64-bit division on 32-bit targets). */
inline uint32_t wrapped_sample(int64_t index, uint32_t size) {
    const uint32_t bits = static_cast<uint32_t>(static_cast<uint64_t>(index));
    return index < 0 ? size - 1u - ~bits % size : bits % size;
}

/* The axis at a Q32.32 position: u = (position - origin) / 2^spacing_shift in samples, the difference
   taken modulo 2^32 texels and read as signed. */
inline MixAxis mix_axis(uint64_t position, int32_t origin, uint32_t spacing_shift, uint32_t size,
                        bool periodic) {
    const uint64_t relative = position - (static_cast<uint64_t>(static_cast<uint32_t>(origin)) << 32);
    /* floor(whole / 2^shift) of the signed whole part, through a 2^31 bias (no signed shift) */
    const uint32_t biased = static_cast<uint32_t>(relative >> 32) ^ 0x80000000u;
    MixAxis axis;
    axis.index = static_cast<int64_t>(biased >> spacing_shift) -
                 static_cast<int64_t>(static_cast<uint32_t>(0x80000000u) >> spacing_shift);
    axis.fraction = static_cast<uint32_t>(relative >> (24u + spacing_shift)) & 0xFFu;
    axis.first = periodic ? wrapped_sample(axis.index, size) : clamped_sample(axis.index, size);
    axis.second =
        periodic ? (axis.first + 1u == size ? 0u : axis.first + 1u) : clamped_sample(axis.index + 1, size);
    return axis;
}

/* One axis of the control as the AVX2 and AVX-512 copies read it on vectors (kernels/mix_pick_lanes.h)
   for impulses whose integer positions p lie in [first, first + span] (modulo 2^32): mix_axis's lower
   sample index is base + ((p - origin) ^ 2^31) / 2^shift - low, modulo 2^32, then clamped (as an int32)
   or, periodic, less `size` where it reaches it. A clamped axis takes every p as mix_axis does (low 0,
   base -2^31 / 2^shift); a periodic one from the window's first texel, its index wrapped once here, which
   needs the window on one side of the signed wrap of p - origin (the indices then grow with p) and at most
   `size` samples past its first: false elsewhere. */
struct PickWindowAxis {
    uint32_t origin, low, base, size;
    bool periodic;
};

inline bool pick_window_axis(int32_t origin, uint32_t shift, uint32_t size, bool periodic, uint32_t first,
                             uint32_t span, PickWindowAxis *axis) {
    axis->origin = static_cast<uint32_t>(origin);
    axis->size = size;
    axis->periodic = periodic;
    axis->low = axis->base = 0; /* (written whatever the answer) */
    const uint32_t bias = 0x80000000u >> shift;
    if (!periodic) {
        axis->low = 0;
        axis->base = 0u - bias;
        return true;
    }
    const uint32_t biased = (first - axis->origin) ^ 0x80000000u;
    if (biased > 0xFFFFFFFFu - span) return false;
    axis->low = biased >> shift;
    if (((biased + span) >> shift) - axis->low > size) return false;
    axis->base = wrapped_sample(static_cast<int64_t>(axis->low) - static_cast<int64_t>(bias), size);
    return true;
}

/* Whether the lanes read the control for impulses whose integer positions lie in [first_x, first_x +
   span_x] x [first_y, first_y + span_y]: both axes (pick_window_axis), and at least 4 bytes to gather. */
inline bool lanes_read_control(const dsn_mix_control *control, uint32_t count, uint32_t first_x,
                               uint32_t span_x, uint32_t first_y, uint32_t span_y, PickWindowAxis *x,
                               PickWindowAxis *y) {
    /* both axes written whatever the answer */
    const bool along_x = pick_window_axis(control->origin_x, control->spacing_shift, control->width,
                                          (control->flags & DSN_MIX_PERIODIC_X) != 0, first_x, span_x, x);
    const bool along_y = pick_window_axis(control->origin_y, control->spacing_shift, control->height,
                                          (control->flags & DSN_MIX_PERIODIC_Y) != 0, first_y, span_y, y);
    return control->width * control->height * count >= 4u && along_x && along_y;
}

/* The weights V_m at a position, in [0, 65280] (dsn.h), and their running sums: cumulative[m] =
   V_0 + .. + V_m, so cumulative[count - 1] is T. */
struct MixWeights {
    uint32_t cumulative[DSN_MIX_MAX_MATERIALS];
};

/* (Written through a pointer rather than returned: a returned struct goes back in two 64-bit registers
   assembled from the 32-bit stores, a load that store forwarding cannot serve.) */
inline void mix_weights_at(const dsn_mix_control *control, uint32_t count, uint64_t x, uint64_t y,
                           MixWeights *out) {
    const MixAxis ax = mix_axis(x, control->origin_x, control->spacing_shift, control->width,
                                (control->flags & DSN_MIX_PERIODIC_X) != 0);
    const MixAxis ay = mix_axis(y, control->origin_y, control->spacing_shift, control->height,
                                (control->flags & DSN_MIX_PERIODIC_Y) != 0);
    const uint8_t *top = control->weights + static_cast<size_t>(ay.first) * control->width * count;
    const uint8_t *bottom = control->weights + static_cast<size_t>(ay.second) * control->width * count;
    const uint32_t left = ax.first * count, right = ax.second * count;
    uint32_t total = 0;
    for (uint32_t m = 0; m < DSN_MIX_MAX_MATERIALS; m++) {
        if (m < count) {
            const uint32_t upper = (256u - ax.fraction) * top[left + m] + ax.fraction * top[right + m];
            const uint32_t lower = (256u - ax.fraction) * bottom[left + m] + ax.fraction * bottom[right + m];
            total += ((256u - ay.fraction) * upper + ay.fraction * lower) >> 8;
        }
        out->cumulative[m] = m < count ? total : 0u; /* the entries past count unused, zero */
    }
}

/* The material an impulse with this hash picks where the weights are these: the first m with
   floor(hash T / 2^32) < cumulative[m]; material 0 where T is 0. Unbranched: counted as the running sums
   at or below the draw (they do not decrease), without a branch on them, for a walk that turns the
   materials into masks (the kernels' mixed lattice point), where a branch on neighbouring impulses'
   materials is often mispredicted; a walk that reads the material's texton at once runs faster on the
   branch's prediction. */
inline uint32_t pick_material(const MixWeights &weights, uint32_t count, uint32_t hash,
                              bool unbranched = false) {
    const uint32_t total = weights.cumulative[count - 1u];
    const uint32_t draw = static_cast<uint32_t>((static_cast<uint64_t>(hash) * total) >> 32);
    uint32_t m = 0;
    if (unbranched) {
        for (uint32_t level = 0; level + 1u < count; level++)
            m += static_cast<uint32_t>(draw >= weights.cumulative[level]);
        return total == 0 ? 0u : m;
    }
    if (total == 0) return 0;
    while (m + 1u < count && draw >= weights.cumulative[m]) m++;
    return m;
}

/* The smallest hash that draws past running sum `running` of `total` (pick_material: floor(hash total /
   2^32) >= running): ceil(2^32 running / total), 2^32 where no hash does (running = total); and in *upto
   floor(2^14 running / total), point_weights's running sum, from the same division (floor(floor(2^32
   running / total) / 2^18)). In three 32-bit divisions, the long division in digits of 14, 14 and 4 bits, as
   running <= total < 2^18 (no 64-bit division helper on 32-bit targets); draw_threshold takes one 64-bit
   division where that is one instruction. */
inline uint64_t draw_threshold_in_digits(uint32_t running, uint32_t total, uint32_t *upto) {
    const uint32_t first = (running << 14) / total, first_rest = (running << 14) % total;
    const uint32_t second = (first_rest << 14) / total, second_rest = (first_rest << 14) % total;
    const uint32_t third = (second_rest << 4) / total, third_rest = (second_rest << 4) % total;
    *upto = first;
    return (static_cast<uint64_t>(first) << 18) + (static_cast<uint64_t>(second) << 4) + third +
           (third_rest != 0 ? 1u : 0u);
}

inline uint64_t draw_threshold(uint32_t running, uint32_t total, uint32_t *upto) {
#if defined(__x86_64__) || defined(__aarch64__)
    const uint64_t scaled = static_cast<uint64_t>(running) << 32, quotient = scaled / total;
    *upto = static_cast<uint32_t>(quotient >> 18);
    return quotient + (scaled % total != 0 ? 1u : 0u);
#else
    return draw_threshold_in_digits(running, total, upto);
#endif
}

/* The point's weights w_m in Q2.14, summing to 2^14: differences of floor(2^14 cumulative / T) (T < 2^18,
   so a 32-bit division); all on material 0 where T is 0. */
inline void point_weights(const MixWeights &weights, uint32_t count, uint32_t *out) {
    const uint32_t total = weights.cumulative[count - 1u];
    uint32_t before = 0;
    for (uint32_t m = 0; m < count; m++) {
        const uint32_t upto =
            total == 0 ? (1u << mix_weight_bits) : (weights.cumulative[m] << mix_weight_bits) / total;
        out[m] = upto - before;
        before = upto;
    }
}

/* What uniform weights give every point and impulse: each material's weight at a point (point_weights),
   and the thresholds that impulses' material hashes meet, thresholds[m] for material m + 1 or a later one
   (draw_threshold; 2^32, above every hash, past the last material and where no weight is set: every
   impulse then draws material 0). */
struct UniformDraws {
    uint32_t weights[DSN_MIX_MAX_MATERIALS];
    uint64_t thresholds[DSN_MIX_MAX_MATERIALS - 1];
};

/* The draws of uniform weights, one division per material but the last (whose running sum is the total). */
inline void uniform_draws(const MixWeights &weights, uint32_t count, UniformDraws *draws) {
    const uint32_t total = weights.cumulative[count - 1u];
    uint32_t before = 0;
    for (uint32_t m = 0; m < DSN_MIX_MAX_MATERIALS; m++) {
        uint32_t upto = 1u << mix_weight_bits;
        const uint64_t threshold = total != 0 && m + 1u < count
                                       ? draw_threshold(weights.cumulative[m], total, &upto)
                                       : static_cast<uint64_t>(1) << 32;
        if (m + 1u < DSN_MIX_MAX_MATERIALS) draws->thresholds[m] = threshold;
        draws->weights[m] = m < count ? upto - before : 0u;
        before = upto;
    }
}

/* The draws where material `only` has all the weight (or none has any: material 0): uniform_draws's,
   without a division. */
inline void single_draws(uint32_t only, UniformDraws *draws) {
    for (uint32_t m = 0; m < DSN_MIX_MAX_MATERIALS; m++) {
        if (m + 1u < DSN_MIX_MAX_MATERIALS)
            draws->thresholds[m] = m < only ? 0u : static_cast<uint64_t>(1) << 32;
        draws->weights[m] = m == only ? 1u << mix_weight_bits : 0u;
    }
}

/* Where the weights are the same at every position the point's impulses can take, the walk reads them
   once: a region of the grid. */
struct MixRegion {
    bool uniform;
    MixWeights weights; /* the weights everywhere, when uniform */
    bool single;        /* uniform with one material of non-zero weight: no impulse needs its hash */
    uint32_t only;      /* that material */
    UniformDraws draws; /* when uniform */
};

/* The samples that a run of lower-sample indices first .. last (and the samples after them) reads along an
   axis: `length` samples from `start` (wrapping modulo size where periodic); false past `most`. */
inline bool axis_samples(int64_t first, int64_t last, uint32_t size, bool periodic, int64_t most,
                         uint32_t *start, uint32_t *length) {
    if (periodic) {
        const int64_t count = last + 2 - first;
        *start = wrapped_sample(first, size);
        *length = count >= static_cast<int64_t>(size) ? size : static_cast<uint32_t>(count);
        return *length <= most;
    }
    *start = clamped_sample(first, size);
    const int64_t count = static_cast<int64_t>(clamped_sample(last + 1, size)) - *start + 1;
    *length = static_cast<uint32_t>(count);
    return count <= most;
}

/* The samples that the positions [low, high] (Q32.32) of one axis read (axis_samples); false across the
   2^31 seam of the relative positions (last < first) or past `most`. A grid one sample wide on this axis
   is read whole wherever the positions lie (a control constant along it). */
inline bool region_samples(uint64_t low, uint64_t high, int32_t origin, uint32_t spacing_shift, uint32_t size,
                           bool periodic, int64_t most, uint32_t *start, uint32_t *length) {
    if (size == 1) {
        *start = 0;
        *length = 1;
        return true;
    }
    const MixAxis first = mix_axis(low, origin, spacing_shift, size, periodic);
    const MixAxis last = mix_axis(high, origin, spacing_shift, size, periodic);
    return last.index >= first.index &&
           axis_samples(first.index, last.index, size, periodic, most, start, length);
}

/* The region of positions [low, high] (Q32.32 per axis, high - low below 2^31 texels): uniform when the
   samples it reads (at most `most` per axis) all hold the same weights. */
inline MixRegion mix_region(const dsn_mix_control *control, uint32_t count, uint64_t low_x, uint64_t low_y,
                            uint64_t high_x, uint64_t high_y, uint32_t most) {
    MixRegion region;
    region.uniform = false;
    region.single = false;
    region.only = 0;
    region.weights = MixWeights();
    const uint32_t width = control->width, height = control->height;
    uint32_t start_x, columns, start_y, rows;
    if (!region_samples(low_x, high_x, control->origin_x, control->spacing_shift, width,
                        (control->flags & DSN_MIX_PERIODIC_X) != 0, most, &start_x, &columns) ||
        !region_samples(low_y, high_y, control->origin_y, control->spacing_shift, height,
                        (control->flags & DSN_MIX_PERIODIC_Y) != 0, most, &start_y, &rows))
        return region;
    const uint8_t *reference = control->weights + (static_cast<size_t>(start_y) * width + start_x) * count;
    for (uint32_t j = 0, row = start_y; j < rows; j++, row = row + 1u == height ? 0u : row + 1u)
        for (uint32_t i = 0, column = start_x; i < columns;
             i++, column = column + 1u == width ? 0u : column + 1u) {
            const uint8_t *sample = control->weights + (static_cast<size_t>(row) * width + column) * count;
            for (uint32_t m = 0; m < count; m++)
                if (sample[m] != reference[m]) return region;
        }
    region.uniform = true;
    uint32_t total = 0, nonzero = 0;
    for (uint32_t m = 0; m < count; m++) {
        total += static_cast<uint32_t>(reference[m]) << 8; /* V_m = weight 65536 / 256 */
        region.weights.cumulative[m] = total;
        if (reference[m] != 0) nonzero++, region.only = m;
    }
    region.single = nonzero <= 1u; /* no weight at all: material 0, as pick_material gives */
    if (region.single)
        single_draws(region.only, &region.draws);
    else
        uniform_draws(region.weights, count, &region.draws);
    return region;
}

/* The material of the impulse whose material hash (dsn_cell_stream(key, 2^31 + 2^30 + k) of impulse k of
   the cell with key `key`) is `hash`, at Q32.32 position (x, y) (its floor is read); unbranched as
   pick_material's. */
inline uint32_t hashed_material(const dsn_mix_control *control, uint32_t count, const MixRegion &region,
                                uint32_t hash, uint64_t x, uint64_t y, bool unbranched = false) {
    if (region.single) return region.only;
    if (region.uniform) return pick_material(region.weights, count, hash, unbranched);
    const uint64_t whole = ~static_cast<uint64_t>(0xFFFFFFFFu);
    MixWeights weights;
    mix_weights_at(control, count, x & whole, y & whole, &weights);
    return pick_material(weights, count, hash, unbranched);
}

/* The material of impulse k of the cell with this key, at Q32.32 position (x, y): hashed_material's. */
inline uint32_t impulse_material(const dsn_mix_control *control, uint32_t count, const MixRegion &region,
                                 uint32_t key, uint32_t k, uint64_t x, uint64_t y, bool unbranched = false) {
    if (region.single) return region.only; /* (no hash needed) */
    return hashed_material(control, count, region, dsn_material_hash(key, k), x, y, unbranched);
}

} // namespace

#endif /* DSN_MIXING */

#endif /* DSN_MIX_WEIGHTS_H */
