/* runtime/core/lattice_impulses.h - the lattice mode's impulse-by-impulse test of one cell (any cell size,
   any period): which of a cell's impulses reach a point, each adding its texton entry to the point's
   sums. The per-point walk (point.cpp) and the kernels' vector walk (lattice_point_walk.h), which takes
   a cell's rare impulses past 16 this way, share it. Internal to libdsn; not installed (everything here
   has internal linkage). */
#ifndef DSN_LATTICE_IMPULSES_H
#define DSN_LATTICE_IMPULSES_H

#include "core/cell_walk.h"
#include "core/impulse_position.h"
#include "setup/noise_state.h"

namespace {

/* Texton value `index` (channels interleaved), sign-extended in uint32 arithmetic without
   implementation-defined conversions: (b ^ 0x80) - 128 is the two's-complement byte. */
template <uint32_t Bits>
inline uint32_t texton_value(const unsigned char *texton, uint32_t index) {
    if (Bits == 8) return uint32_t(texton[index] ^ 0x80u) - 0x80u;
    return (uint32_t(texton[2 * index] | (texton[2 * index + 1] << 8)) ^ 0x8000u) - 0x8000u;
}

/* Adds texton entry `entry` of every channel to sums, modulo 2^32. */
inline void add_texton_entry(const dsn_asset *asset, const dsn_texton_window *texton, uint32_t entry,
                             uint32_t *sums) {
    for (uint32_t c = 0; c < asset->channels; c++)
        sums[c] += asset->bits == 8 ? texton_value<8>(texton->values, entry * asset->channels + c)
                                    : texton_value<16>(texton->values, entry * asset->channels + c);
}

/* ---- Any cell size, any period: impulse by impulse ---- */

/* One cell of the walk along one axis: reach = span base - cell origin (the texton index of an impulse
   at offset 0, a small signed number held in a uint32) and the last acceptable in-cell offset (the
   period cuts the last cell). */
typedef struct axis_cell {
    uint32_t reach, last_offset;
} axis_cell;

inline axis_cell cell_on_axis(const dsn_span *span, uint32_t cell, uint32_t shift) {
    const uint32_t origin = cell << shift, room = span->last_position - origin;
    axis_cell result = {span->base - origin, room < (1u << shift) - 1u ? room : (1u << shift) - 1u};
    return result;
}

/* visit(k, offset_x, offset_y, entry) for each of impulses first .. count - 1 of a cell that reaches the
   point: its in-cell offsets and its texton entry. */
template <typename Visit>
inline void visit_reaching_impulses(const dsn_noise_state *noise, const dsn_texton_window *texton,
                                    uint32_t key, uint32_t first, uint32_t count, const axis_cell *x,
                                    const axis_cell *y, const Visit &visit) {
    const uint32_t field_shift = dsn_field_shift(noise->cell_shift), per_pair = 64u >> field_shift;
    const uint32_t half_bits = 1u << (field_shift - 1u), half_mask = (1u << half_bits) - 1u;
    const uint32_t drop = half_bits - noise->cell_shift, width = texton->width, height = texton->height;
    uint64_t pair = 0;
    for (uint32_t k = first; k < count; k++) {
        if (k == first || k % per_pair == 0) pair = dsn_position_pair(key, k / per_pair);
        const uint32_t field = uint32_t(pair >> ((k % per_pair) << field_shift));
        const uint32_t offset_x = (field & half_mask) >> drop,
                       offset_y = ((field >> half_bits) & half_mask) >> drop;
        const uint32_t column = x->reach - offset_x, row = y->reach - offset_y;
        if (column < width && row < height && offset_x <= x->last_offset && offset_y <= y->last_offset)
            visit(k, offset_x, offset_y, row * width + column);
    }
}

/* Impulses first .. count - 1 of a cell: each one that reaches the point adds its texton entry. */
inline void add_impulses(const dsn_noise_state *noise, const dsn_texton_window *texton, uint32_t key,
                         uint32_t first, uint32_t count, const axis_cell *x, const axis_cell *y,
                         uint32_t *sums) {
    visit_reaching_impulses(noise, texton, key, first, count, x, y,
                            [&](uint32_t, uint32_t, uint32_t, uint32_t entry) {
                                add_texton_entry(&noise->asset, texton, entry, sums);
                            });
}

} // namespace

#endif /* DSN_LATTICE_IMPULSES_H */
