/* runtime/kernels/mix_pick_lanes.h - the materials of a mixed point's impulses where the weights vary, in
   the AVX2 and AVX-512 copies: the continuous point's candidates' integer positions from their S
   (continuous_point_vector.h), then their materials, impulse by impulse through the caller's pick, or 8 at
   a time on AVX2 vectors from the control itself, as the lattice point's hits too (lattice_point_walk.h's
   picked_hits): mix_weights.h's mix_weights_at and pick_material in 32-bit lanes, the samples gathered 4
   bytes at a time, the same integers, so the same materials. Internal to libdsn; not installed
   (everything here has internal linkage). */
#ifndef DSN_MIX_PICK_LANES_H
#define DSN_MIX_PICK_LANES_H

#include <stdint.h>

#include "simd/simd.h" /* the 256-bit operations (simd_256.h) on AVX2 and AVX-512 */
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
/* impulse_whole of 8 lanes. */
inline vector_256 impulse_wholes(const PickAxis &axis, vector_256 s) {
    const vector_256 step =
        subtract_32(shift_right_logical_32(subtract_32(set_8x32(axis.shifted), s), 16), set_8x32(axis.whole));
    return add_32(set_8x32(axis.whole), shift_right_arithmetic_32(shift_left_32(step, 16), 16));
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

/* mix_axis of 8 integer positions: both samples' indices and the upper one's 8-bit weight. */
struct AxisLanes {
    vector_256 first, second, fraction;
};

inline AxisLanes axis_lanes(const PickWindow &window, const PickWindowAxis &axis, vector_256 positions) {
    const vector_256 biased =
        bitwise_xor(subtract_32(positions, set_8x32(axis.origin)), set_8x32(0x80000000u));
    const vector_256 index =
        add_32(subtract_32(shift_right_logical_32_by(biased, window.shift), set_8x32(axis.low)),
               set_8x32(axis.base));
    const vector_256 size = set_8x32(axis.size), one = set_8x32(1);
    AxisLanes lanes;
    if (axis.periodic) {
        /* index < 2 size: less size where that does not wrap below zero */
        lanes.first = minimum_unsigned_32(index, subtract_32(index, size));
        const vector_256 next = add_32(lanes.first, one);
        lanes.second = minimum_unsigned_32(next, subtract_32(next, size));
    } else {
        /* clamped as int32; the upper one as min(max(index, -1), size - 2) + 1, which cannot overflow */
        lanes.first = minimum_32(maximum_32(index, zero_256()), set_8x32(axis.size - 1u));
        lanes.second =
            add_32(minimum_32(maximum_32(index, set_8x32(0xFFFFFFFFu)), set_8x32(axis.size - 2u)), one);
    }
    lanes.fraction =
        bitwise_and(window.fraction_down ? shift_right_logical_32_by(biased, window.fraction_shift)
                                         : shift_left_32_by(biased, window.fraction_shift),
                    set_8x32(0xFFu));
    return lanes;
}

/* The 4 bytes of the control from each lane's byte offset, read so that they end by its last byte (the
   caller's buffer may end there) and moved down to the lane's low bytes; the offsets of the lanes out of
   reach may be anything (their reads stay in the control). */
inline vector_256 sample_words(const PickWindow &window, vector_256 offsets) {
    const vector_256 read = minimum_unsigned_32(offsets, set_8x32(window.last_word));
    return shift_right_logical_32_per_lane(gather_32<1>(window.weights, read),
                                           shift_left_32(subtract_32(offsets, read), 3));
}

/* Lane k of levels[l] all ones where candidate k's material (pick_material's, unbranched, from its hash at
   its integer position (x, y)) is past l, for l < count - 1; zero elsewhere. */
DSN_SIMD_INLINE void picked_level_lanes(const PickWindow &window, vector_256 hashes, vector_256 x,
                                        vector_256 y, vector_256 *levels) {
    const AxisLanes ax = axis_lanes(window, window.x, x), ay = axis_lanes(window, window.y, y);
    const vector_256 count = set_8x32(window.count), row = set_8x32(window.row_bytes);
    const vector_256 top = multiply_32(ay.first, row), bottom = multiply_32(ay.second, row);
    const vector_256 left = multiply_32(ax.first, count), right = multiply_32(ax.second, count);
    const vector_256 top_left = sample_words(window, add_32(top, left)),
                     top_right = sample_words(window, add_32(top, right)),
                     bottom_left = sample_words(window, add_32(bottom, left)),
                     bottom_right = sample_words(window, add_32(bottom, right));
    /* mix_weights_at's interpolation as 256 a + f (b - a), the same integers */
    const vector_256 byte = set_8x32(0xFFu);
    vector_256 cumulative[dsn_point_materials_most], total = zero_256();
    for (uint32_t m = 0; m < window.count && m < dsn_point_materials_most; m++) {
        const uint32_t at = 8u * m;
        const vector_256 a = bitwise_and(shift_right_logical_32(top_left, at), byte),
                         b = bitwise_and(shift_right_logical_32(top_right, at), byte),
                         c = bitwise_and(shift_right_logical_32(bottom_left, at), byte),
                         d = bitwise_and(shift_right_logical_32(bottom_right, at), byte);
        const vector_256 upper = add_32(shift_left_32(a, 8), multiply_32(ax.fraction, subtract_32(b, a)));
        const vector_256 lower = add_32(shift_left_32(c, 8), multiply_32(ax.fraction, subtract_32(d, c)));
        total =
            add_32(total, shift_right_logical_32(add_32(shift_left_32(upper, 8),
                                                        multiply_32(ay.fraction, subtract_32(lower, upper))),
                                                 8));
        cumulative[m] = total;
    }
    /* the draw floor(hash total / 2^32): the even lanes' 64-bit products' high halves moved down, the odd
       lanes' in place */
    const vector_256 even = shift_right_logical_64(multiply_even_unsigned_32(hashes, total), 32);
    const vector_256 odd =
        multiply_even_unsigned_32(shift_right_logical_64(hashes, 32), shift_right_logical_64(total, 32));
    const vector_256 draw = bitwise_or(even, bitwise_and(odd, set_lanes_8x32(0, -1, 0, -1, 0, -1, 0, -1)));
    /* every sum below 2^18: signed compares; no weight at all draws material 0 */
    const vector_256 weighed = greater_32(total, zero_256());
    for (uint32_t level = 0; level < 3; level++)
        levels[level] =
            level + 1u < window.count ? and_not(greater_32(cumulative[level], draw), weighed) : zero_256();
}
#endif /* DSN_MIXING */

} // namespace
#endif /* __AVX2__ */

#endif /* DSN_MIX_PICK_LANES_H */
