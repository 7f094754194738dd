/* runtime/kernels/mix_pick_lanes.h - the materials of a mixed point's impulses where the weights vary, in
   the AVX2 and AVX-512 copies: the continuous point's candidates' integer positions from their S
   (continuous_point_vector.h), then their materials, impulse by impulse through the caller's pick, or 8 at
   a time on AVX2 vectors from the control itself, as the lattice point's hits too (lattice_point_walk.h's
   picked_hits) and the filtered point's listed impulses (the pick_materials entry): mix_weights.h's
   mix_weights_at and pick_material in 32-bit lanes, the samples gathered 4 bytes at a time, the same
   integers, so the same materials. Internal to libdsn; not installed (internal linkage throughout). */
#ifndef DSN_MIX_PICK_LANES_H
#define DSN_MIX_PICK_LANES_H

#include <stdint.h>

#include "simd/simd_mix64.h" /* simd.h, and all_lanes_32 */
#if DSN_MIXING
#include "core/mix_weights.h"
#endif

#if defined(__AVX2__) && !DSN_SMALL_CODE
namespace {

/* A candidate's material is picked at the integer parts of its position, found from its S along each axis
   (the walk's floor(shifted / 2^16), shifted = point - impulse + radius + 1 in texels): the impulse's
   position times 2^16 is an integer (a cell's 16-bit position grid), so it is floor((point + radius + 1)
   2^16) - S exactly, and its integer part lies within radius + 2 of the point's: taken modulo 2^16 from
   32-bit lanes, then as a signed step from the point's. */
struct PickAxis {
    uint32_t whole;   /* the point's integer part, modulo 2^32 */
    uint32_t shifted; /* floor((point + radius + 1) 2^16), modulo 2^32 */
};

inline PickAxis pick_axis(uint64_t coordinate, uint32_t radius) {
    const PickAxis axis = {
        static_cast<uint32_t>(coordinate >> 32),
        static_cast<uint32_t>((coordinate + (static_cast<uint64_t>(radius + 1u) << 32)) >> 16)};
    return axis;
}

/* The integer part of a candidate's position along an axis from its S. */
inline uint32_t impulse_whole(const PickAxis &axis, uint32_t s) {
    const uint32_t low = ((axis.shifted - s) >> 16) - axis.whole; /* the step, modulo 2^16 */
    return axis.whole + static_cast<uint32_t>(static_cast<int32_t>(static_cast<int16_t>(low & 0xFFFFu)));
}

/* Bit k of at_least[l], for each level l below the material the visit's pick gives candidate lane k in
   `reach` (bit per lane), from the lanes' hashes and S (stored). */
template <class Visit>
inline void picked_levels(const Visit *visit, const uint32_t *hashes, const uint32_t *s_x,
                          const uint32_t *s_y, uint32_t reach, uint32_t *at_least) {
    for (; reach != 0; reach &= reach - 1u) {
        const uint32_t k = static_cast<uint32_t>(__builtin_ctz(reach));
        const uint32_t m = visit->pick(visit->context, hashes[k], impulse_whole(visit->pick_x, s_x[k]),
                                       impulse_whole(visit->pick_y, s_y[k]));
        for (uint32_t level = 0; level < 3; level++) at_least[level] |= static_cast<uint32_t>(m > level) << k;
    }
}

#if DSN_MIXING
/* The lanes are 8 (AVX2's vector_256) or 16 (AVX-512's vector_512) at a time, written once for both
   (all_lanes_32 broadcasts); the gathers of 4 bytes from byte offsets: */
DSN_SIMD_INLINE vector_256 gathered_words(const void *base, vector_256 offsets) {
    return gather_32<1>(base, offsets);
}
#if defined(__AVX512F__) && defined(__AVX512BW__)
DSN_SIMD_INLINE vector_512 gathered_words(const void *base, vector_512 offsets) {
    return gather_masked_32<1>(base, offsets, static_cast<mask_16>(0xFFFFu));
}
#endif

/* impulse_whole of every lane. */
template <class Vector>
DSN_SIMD_INLINE Vector impulse_wholes(const PickAxis &axis, Vector s) {
    const Vector step =
        subtract_32(shift_right_logical_32(subtract_32(all_lanes_32<Vector>(axis.shifted), s), 16),
                    all_lanes_32<Vector>(axis.whole));
    return add_32(all_lanes_32<Vector>(axis.whole), shift_right_arithmetic_32(shift_left_32(step, 16), 16));
}

/* The control around one point as the lanes read it (mix_weights.h's pick_window_axis for each axis), and
   its bytes: each sample's `count` weights, rows row_bytes apart, the last 4-byte word at last_word. */
struct PickWindow {
    const uint8_t *weights;
    uint32_t row_bytes, last_word, count;
    vector_128 shift, fraction_shift; /* spacing_shift, and |spacing_shift - 8| */
    bool fraction_down;               /* spacing_shift >= 8 */
    PickWindowAxis x, y;
};

/* The window of the control that holds the impulses whose integer positions lie within (reach_x, reach_y)
   texels of (whole_x, whole_y); false where the lanes do not take it (mix_weights.h's lanes_read_control). */
inline bool pick_window(const dsn_mix_control *control, uint32_t count, uint32_t whole_x, uint32_t whole_y,
                        uint32_t reach_x, uint32_t reach_y, PickWindow *window) {
    const uint32_t shift = control->spacing_shift;
    window->weights = control->weights;
    window->row_bytes = control->width * count;
    window->last_word = control->width * control->height * count - 4u; /* (at most 2^26 bytes) */
    window->count = count;
    window->shift = shift_count(static_cast<int>(shift));
    window->fraction_down = shift >= 8u;
    window->fraction_shift = shift_count(static_cast<int>(shift >= 8u ? shift - 8u : 8u - shift));
    return lanes_read_control(control, count, whole_x - reach_x, 2u * reach_x, whole_y - reach_y,
                              2u * reach_y, &window->x, &window->y);
}

/* mix_axis of every lane's integer position: both samples' indices and the upper one's 8-bit weight. */
template <class Vector>
struct AxisLanes {
    Vector first, second, fraction;
};

template <class Vector>
DSN_SIMD_INLINE AxisLanes<Vector> axis_lanes(const PickWindow &window, const PickWindowAxis &axis,
                                             Vector positions) {
    const Vector biased = bitwise_xor(subtract_32(positions, all_lanes_32<Vector>(axis.origin)),
                                      all_lanes_32<Vector>(0x80000000u));
    const Vector index =
        add_32(subtract_32(shift_right_logical_32_by(biased, window.shift), all_lanes_32<Vector>(axis.low)),
               all_lanes_32<Vector>(axis.base));
    const Vector size = all_lanes_32<Vector>(axis.size), one = all_lanes_32<Vector>(1);
    AxisLanes<Vector> lanes;
    if (axis.periodic) {
        /* index < 2 size: less size where that does not wrap below zero */
        lanes.first = minimum_unsigned_32(index, subtract_32(index, size));
        const Vector next = add_32(lanes.first, one);
        lanes.second = minimum_unsigned_32(next, subtract_32(next, size));
    } else {
        /* clamped as int32; the upper one as min(max(index, -1), size - 2) + 1, which cannot overflow */
        lanes.first =
            minimum_32(maximum_32(index, all_lanes_32<Vector>(0)), all_lanes_32<Vector>(axis.size - 1u));
        lanes.second = add_32(minimum_32(maximum_32(index, all_lanes_32<Vector>(0xFFFFFFFFu)),
                                         all_lanes_32<Vector>(axis.size - 2u)),
                              one);
    }
    lanes.fraction =
        bitwise_and(window.fraction_down ? shift_right_logical_32_by(biased, window.fraction_shift)
                                         : shift_left_32_by(biased, window.fraction_shift),
                    all_lanes_32<Vector>(0xFFu));
    return lanes;
}

/* The 4 bytes of the control from each lane's byte offset, read so that they end by its last byte (the
   caller's buffer may end there) and moved down to the lane's low bytes; the offsets of the lanes out of
   reach may be anything (their reads stay in the control). */
template <class Vector>
DSN_SIMD_INLINE Vector sample_words(const PickWindow &window, Vector offsets) {
    const Vector read = minimum_unsigned_32(offsets, all_lanes_32<Vector>(window.last_word));
    return shift_right_logical_32_per_lane(gathered_words(window.weights, read),
                                           shift_left_32(subtract_32(offsets, read), 3));
}

/* Each lane's running sums of the weights at its integer position (x, y) (mix_weights_at's cumulative[0 ..
   count - 1]), and its draw floor(hash total / 2^32) (pick_material's): the material is the number of
   levels l < count - 1 with draw >= cumulative[l], or 0 where the total is 0. */
template <class Vector>
DSN_SIMD_INLINE void drawn_lanes(const PickWindow &window, Vector hashes, Vector x, Vector y,
                                 Vector *cumulative, Vector *draw) {
    const AxisLanes<Vector> ax = axis_lanes(window, window.x, x), ay = axis_lanes(window, window.y, y);
    const Vector count = all_lanes_32<Vector>(window.count), row = all_lanes_32<Vector>(window.row_bytes);
    const Vector top = multiply_32(ay.first, row), bottom = multiply_32(ay.second, row);
    const Vector left = multiply_32(ax.first, count), right = multiply_32(ax.second, count);
    const Vector top_left = sample_words(window, add_32(top, left)),
                 top_right = sample_words(window, add_32(top, right)),
                 bottom_left = sample_words(window, add_32(bottom, left)),
                 bottom_right = sample_words(window, add_32(bottom, right));
    /* mix_weights_at's interpolation as 256 a + f (b - a), the same integers */
    const Vector byte = all_lanes_32<Vector>(0xFFu);
    Vector total = all_lanes_32<Vector>(0);
    for (uint32_t m = 0; m < window.count && m < dsn_point_materials_most; m++) {
        const uint32_t at = 8u * m;
        const Vector a = bitwise_and(shift_right_logical_32(top_left, at), byte),
                     b = bitwise_and(shift_right_logical_32(top_right, at), byte),
                     c = bitwise_and(shift_right_logical_32(bottom_left, at), byte),
                     d = bitwise_and(shift_right_logical_32(bottom_right, at), byte);
        const Vector upper = add_32(shift_left_32(a, 8), multiply_32(ax.fraction, subtract_32(b, a)));
        const Vector lower = add_32(shift_left_32(c, 8), multiply_32(ax.fraction, subtract_32(d, c)));
        total =
            add_32(total, shift_right_logical_32(add_32(shift_left_32(upper, 8),
                                                        multiply_32(ay.fraction, subtract_32(lower, upper))),
                                                 8));
        cumulative[m] = total;
    }
    /* the even lanes' 64-bit products' high halves moved down, the odd lanes' in place */
    const Vector even = shift_right_logical_64(multiply_even_unsigned_32(hashes, total), 32);
    const Vector odd =
        multiply_even_unsigned_32(shift_right_logical_64(hashes, 32), shift_right_logical_64(total, 32));
    *draw = bitwise_or(even, bitwise_and(odd, shift_left_64(all_lanes_32<Vector>(0xFFFFFFFFu), 32)));
}

/* Lane k of levels[l] all ones where lane k's material (drawn_lanes's) is past l, for l < count - 1; zero
   elsewhere: 8 lanes. Every sum is below 2^18: signed compares. */
DSN_SIMD_INLINE void picked_level_lanes(const PickWindow &window, vector_256 hashes, vector_256 x,
                                        vector_256 y, vector_256 *levels) {
    vector_256 cumulative[dsn_point_materials_most], draw;
    drawn_lanes(window, hashes, x, y, cumulative, &draw);
    const vector_256 weighed = greater_32(cumulative[window.count - 1u], zero_256());
    for (uint32_t level = 0; level < 3; level++)
        levels[level] =
            level + 1u < window.count ? and_not(greater_32(cumulative[level], draw), weighed) : zero_256();
}

/* The kernel entry (kernels.h's dsn_mix_picks_entry): picked_level_lanes 8 impulses at a time, each lane's
   material the number of levels it is past; the last group's lanes past n read the point itself, hash 0. */
inline int pick_materials(const dsn_mix_control *control, uint32_t count, uint32_t whole_x, uint32_t whole_y,
                          uint32_t reach_x, uint32_t reach_y, const uint32_t *hashes, const uint32_t *x,
                          const uint32_t *y, uint32_t n, uint32_t *materials) {
    PickWindow window;
    if (count > dsn_point_materials_most ||
        !pick_window(control, count, whole_x, whole_y, reach_x, reach_y, &window))
        return 0;
    for (uint32_t done = 0; done < n; done += 8u) {
        uint32_t lanes[3][8], picked[8];
        const uint32_t in_group = n - done < 8u ? n - done : 8u;
        for (uint32_t k = 0; k < 8u; k++) {
            const bool listed = k < in_group;
            lanes[0][k] = listed ? hashes[done + k] : 0u;
            lanes[1][k] = listed ? x[done + k] : whole_x;
            lanes[2][k] = listed ? y[done + k] : whole_y;
        }
        vector_256 levels[3];
        picked_level_lanes(window, load_8x32(lanes[0]), load_8x32(lanes[1]), load_8x32(lanes[2]), levels);
        /* each level past is -1 in its lane */
        store_8x32(picked, subtract_32(zero_256(), add_32(add_32(levels[0], levels[1]), levels[2])));
        for (uint32_t k = 0; k < in_group; k++) materials[done + k] = picked[k];
    }
    return 1;
}
#define DSN_MIX_PICKS_ENTRY pick_materials

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* picked_level_lanes of 16 lanes, bit k of levels[l] for lane k. */
DSN_SIMD_INLINE void picked_level_bits(const PickWindow &window, vector_512 hashes, vector_512 x,
                                       vector_512 y, uint32_t *levels) {
    vector_512 cumulative[dsn_point_materials_most], draw;
    drawn_lanes(window, hashes, x, y, cumulative, &draw);
    const uint32_t weighed = greater_32(cumulative[window.count - 1u], zero_512());
    for (uint32_t level = 0; level < 3; level++)
        levels[level] =
            level + 1u < window.count ? ~uint32_t(greater_32(cumulative[level], draw)) & weighed : 0u;
}
#endif
#endif /* DSN_MIXING */

} // namespace
#endif /* __AVX2__ */

#ifndef DSN_MIX_PICKS_ENTRY
#define DSN_MIX_PICKS_ENTRY 0
#endif

#endif /* DSN_MIX_PICK_LANES_H */
