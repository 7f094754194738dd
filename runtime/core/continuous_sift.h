/* runtime/core/continuous_sift.h - what the fast continuous evaluators (one point: continuous_point.cpp; a
   batch of points: continuous_batch.h; a mix's point: mix_point.cpp) share to find the impulses around a
   point: the point's cell window along each axis and the sifting of a cell's impulses on their packed lattice
   fields, which bound the 16-bit positions to within one texel, so that only the candidates get their
   fraction hash and the exact test. Internal to libdsn; not installed (everything here has internal linkage).
 */
#ifndef DSN_CONTINUOUS_SIFT_H
#define DSN_CONTINUOUS_SIFT_H

#include "core/cell_walk.h"
#include "core/continuous_internal.h"
#include "core/impulse_position.h"
#include "kernels/kernels.h"

namespace {

/* One axis of the point: the lattice mode's candidate cells for the window [X - 1, X + 1] around the
   point's integer part X (every impulse within radius + 1 of the point has its floor in there), and
   the point's 32-bit fraction. */
struct PointAxis {
    dsn_axis axis;
    uint32_t fraction;
};

inline PointAxis point_axis(uint64_t coordinate, uint32_t radius, uint32_t shift, uint32_t period) {
    PointAxis point;
    point.fraction = static_cast<uint32_t>(coordinate);
    dsn_axis_init(&point.axis, static_cast<uint32_t>(coordinate >> 32) - 1u, 3u, radius, shift, period);
    return point;
}

/* Offset (Q32.32) from an impulse to the point along one axis, given the impulse's cell origin and its
   16-bit in-cell position; false when the impulse lies beyond the period (discarded, as in lattice mode).
   The point is at window index 1, that is at texton index 1 + base - p for an impulse at lattice p. */
inline bool impulse_offset(const PointAxis &point, const dsn_span &span, uint32_t cell_origin,
                           uint32_t bits16, int64_t *offset) {
    const uint32_t shift = point.axis.shift;
    if (cell_origin + (bits16 >> (16u - shift)) > span.last_position) return false;
    const uint32_t whole = 1u + span.base - point.axis.radius - cell_origin; /* X - cell origin, mod 2^32 */
    const int64_t in_cell = static_cast<int64_t>(static_cast<uint64_t>(bits16) << (16u + shift));
    *offset = static_cast<int64_t>(dsn_signed_sum(whole)) * static_cast<int64_t>(one_texel) +
              static_cast<int64_t>(point.fraction) - in_cell;
    return true;
}

/* The packed fields of one pair as SWAR lanes: 8 lanes of 8 bits (halves of 4 bits) or 4 of 16 (halves
   of 8 bits). A lane's top bit is above both halves' values, so a lane-wise subtraction of values below
   it never borrows from the next lane. */
struct FieldLanes {
    uint32_t field_shift, half_bits, per_pair;
    uint64_t ones, halves, tops; /* 1, the low half's mask, the top bit, in every lane */
};

inline FieldLanes field_lanes(uint32_t cell_shift) {
    FieldLanes lanes;
    lanes.field_shift = dsn_field_shift(cell_shift);
    lanes.half_bits = 1u << (lanes.field_shift - 1u);
    lanes.per_pair = 64u >> lanes.field_shift;
    lanes.ones = ~static_cast<uint64_t>(0) / ((static_cast<uint64_t>(1) << (1u << lanes.field_shift)) - 1u);
    lanes.halves = lanes.ones * ((1u << lanes.half_bits) - 1u);
    lanes.tops = lanes.ones << ((1u << lanes.field_shift) - 1u);
    return lanes;
}

/* One axis of one cell as seen from the point. An impulse at 16-bit in-cell position b has
   shifted = shifted_base - b 2^(16 + shift), the offset plus radius + 1 texels (bracket's `shifted`):
   it is in reach when 0 < shifted < reach_limit. Its field half h (the top half_bits bits of b) bounds
   b to [h, h + 1) 2^(16 - half_bits), that is the offset to within one texel: the halves in
   [low, high] (in every lane of low_lanes, and of high_lanes with the top bits set) are those that may
   be in reach and lie before the period's end. */
typedef dsn_filter_cell_axis CellAxis; /* kernels.h's, for the filtered sift's kernel (the same fields) */

/* The sifting of cell_axis for any reach: an impulse of the cell at in-cell position b is in reach when
   0 < (X - cell origin) one_texel + base_extra - b 2^(16 + shift) < reach_limit, X the window's start + 1
   (span.base - radius + 1). False when no impulse of the cell can be. */
inline bool cell_axis_within(const dsn_axis &axis, const dsn_span &span, uint32_t cell, int64_t base_extra,
                             int64_t reach_limit, const FieldLanes &lanes, CellAxis *out) {
    const uint32_t shift = axis.shift, origin = cell << shift;
    const uint32_t whole = 1u + span.base - axis.radius - origin; /* as in impulse_offset */
    out->shifted_base =
        static_cast<int64_t>(dsn_signed_sum(whole)) * static_cast<int64_t>(one_texel) + base_extra;
    /* With step = 2^(32 + shift - half_bits) (the offset's change per unit of h, at most one texel) and
       the rest of b taking less than a step: h is in reach only when h step < shifted_base and
       h step + step > shifted_base - reach_limit - step. */
    const uint32_t step_shift = 32u + shift - lanes.half_bits;
    const int64_t low = floor_shift(out->shifted_base - reach_limit, step_shift);
    int64_t high = floor_shift(out->shifted_base - 1, step_shift);
    /* The period: the lattice offset h >> (half_bits - shift) may not pass last_position - origin. */
    const uint32_t room = span.last_position - origin, below = lanes.half_bits - shift;
    const uint32_t last =
        room < (1u << shift) - 1u ? (room << below) | ((1u << below) - 1u) : (1u << lanes.half_bits) - 1u;
    if (high > static_cast<int64_t>(last)) high = static_cast<int64_t>(last);
    const uint32_t first = low < 0 ? 0u : static_cast<uint32_t>(low);
    if (high < static_cast<int64_t>(first)) return false;
    out->low_lanes = lanes.ones * first;
    out->high_lanes = (lanes.ones * static_cast<uint64_t>(high)) | lanes.tops;
    return true;
}

/* False when no impulse of the cell can reach the point along this axis. */
inline bool cell_axis(const PointAxis &point, const dsn_span &span, uint32_t cell, const FieldLanes &lanes,
                      CellAxis *out) {
    const int64_t reach = static_cast<int64_t>(point.axis.radius + 1u) * static_cast<int64_t>(one_texel);
    return cell_axis_within(point.axis, span, cell, static_cast<int64_t>(point.fraction) + reach, 2 * reach,
                            lanes, out);
}

/* cell_axis for the gradient's walks, which take the impulses at the entry edge too (offset -(radius + 1)
   texels: value 0, slope not): 0 <= shifted < reach limit. */
inline bool cell_axis_with_entry_edge(const PointAxis &point, const dsn_span &span, uint32_t cell,
                                      const FieldLanes &lanes, CellAxis *out) {
    const int64_t reach = static_cast<int64_t>(point.axis.radius + 1u) * static_cast<int64_t>(one_texel);
    if (!cell_axis_within(point.axis, span, cell, static_cast<int64_t>(point.fraction) + reach + 1,
                          2 * reach + 1, lanes, out))
        return false;
    out->shifted_base -= 1;
    return true;
}

/* The lanes of a pair whose halves (x low, y high) may reach the point: their top bits. */
inline uint64_t candidate_lanes(uint64_t pair, const FieldLanes &lanes, const CellAxis &x,
                                const CellAxis &y) {
    const uint64_t halves_x = pair & lanes.halves, halves_y = (pair >> lanes.half_bits) & lanes.halves;
    return ((halves_x | lanes.tops) - x.low_lanes) & (x.high_lanes - halves_x) &
           ((halves_y | lanes.tops) - y.low_lanes) & (y.high_lanes - halves_y) & lanes.tops;
}

/* Index of the lowest set bit of a non-zero word. */
inline uint32_t lowest_bit(uint64_t bits) {
#if defined(__GNUC__)
    return static_cast<uint32_t>(__builtin_ctzll(bits));
#else
    uint32_t index = 0;
    while ((bits & 1u) == 0) bits >>= 1, index++;
    return index;
#endif
}

/* The candidate lanes of a pair (top bits of the lanes) as one bit per lane, lane order: the multiplier
   moves lane i's top bit (at 2^field_shift (i + 1) - 1, shifted down to 2^field_shift i) to bit
   64 - per_pair + i, and no two of the products meet there. */
inline uint32_t gather_lanes(uint64_t candidates, const FieldLanes &lanes) {
    if (lanes.field_shift == 3) return static_cast<uint32_t>(((candidates >> 7) * 0x0102040810204080u) >> 56);
    return static_cast<uint32_t>(((candidates >> 15) * 0x1000200040008000u) >> 60);
}

} // namespace

#endif /* DSN_CONTINUOUS_SIFT_H */
