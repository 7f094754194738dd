/* runtime/core/level_read.h - one pyramid level read at an impulse-to-point offset, bilinearly, as the
   filtered walks read it (the tap-by-tap walk, filtered_walk.cpp, and a mix's filtered point,
   mix_filtered.cpp): the offset divided by the level's spacing, then the continuous mode's read of the
   level's values, optionally with its slopes; and the same read's exact test on a candidate's offset, as
   the kernels' vector reads take it. Compiled with DSN_FILTERING. Internal to libdsn; not
   installed (everything here has internal linkage). */
#ifndef DSN_LEVEL_READ_H
#define DSN_LEVEL_READ_H

#include "core/bilinear_texton.h"
#include "core/continuous_internal.h"
#include "core/filtered_internal.h"

#if DSN_FILTERING

namespace {

/* The stored value of (row, column, channel), 0 outside the level's window (-1 too: unsigned). */
inline int64_t level_texel(const dsn_walked_level &level, uint32_t channels, uint32_t bits, uint32_t row,
                           uint32_t column, uint32_t channel) {
    if (row >= level.height || column >= level.width) return 0;
    const uint32_t index = (row * level.stride + column) * channels + channel;
    return bits == 8 ? dsn_read_i8(level.values + index) : dsn_read_i16le(level.values + 2u * index);
}

/* bracket (bilinear_texton.h) of a level offset; with `entry_edge` an offset of exactly -(radius + 1)
   texels is kept, as index -1 with weight 0. */
inline bool level_bracket(int64_t offset, uint32_t radius, bool entry_edge, uint32_t *lower_index,
                          uint32_t *upper_weight) {
    if (entry_edge && offset == -static_cast<int64_t>(radius + 1u) * static_cast<int64_t>(one_texel)) {
        *lower_index = 0xFFFFFFFFu;
        *upper_weight = 0;
        return true;
    }
    return bracket(offset, radius, lower_index, upper_weight);
}

/* Adds the level's bilinear texton at the impulse-to-point offset (dx, dy), Q32.32 level-0 texels, to
   the sums (Q.32, stored-value units): the offset is divided by the spacing 2^level (rounded down) and
   read as the continuous mode reads level 0 (bracket, the same weights). With Slopes, also its partial
   derivatives per 2^-16 level texel (add_slopes) to slopes[0] (x) and slopes[1] (y), the impulses exactly
   at the entry edge of the level's reach included (value 0, slope not), as the continuous gradient's. */
template <bool Slopes>
inline void add_level(const dsn_walked_level &level, uint32_t channels, uint32_t bits, int64_t dx, int64_t dy,
                      uint64_t *sums, uint64_t (*slopes)[DSN_MAX_CHANNELS]) {
    uint32_t row, row_weight, column, column_weight;
    if (!level_bracket(floor_shift(dy, level.level), level.radius_y, Slopes, &row, &row_weight) ||
        !level_bracket(floor_shift(dx, level.level), level.radius_x, Slopes, &column, &column_weight))
        return;
    const int64_t across = column_weight, down = row_weight;
    for (uint32_t c = 0; c < channels; c++) {
        const int64_t a = level_texel(level, channels, bits, row, column, c),
                      b = level_texel(level, channels, bits, row, column + 1u, c),
                      d = level_texel(level, channels, bits, row + 1u, column, c),
                      e = level_texel(level, channels, bits, row + 1u, column + 1u, c);
        const int64_t upper = (65536 - across) * a + across * b, lower = (65536 - across) * d + across * e;
        sums[c] += static_cast<uint64_t>((65536 - down) * upper + down * lower); /* each term < 2^47 */
        if (Slopes) add_slopes(a, b, d, e, across, down, &slopes[0][c], &slopes[1][c]);
    }
}

/* The exact test of one level along one axis for one tap, as the walk's bracket of floor(offset / 2^l),
   on a candidate's c, the impulse-to-point offset plus tap_shift (Q32.32): with u = c + start (modulo
   2^64) the impulse is in reach when u < limit, and then (u + bias) >> l is bracket's shifted value.
   Closed: the gradient's, which keeps the offsets at the entry edge of the level's reach (add_level's:
   floor(offset / 2^l) = -(radius + 1) texels, the 2^l values of u below 0), start and limit moved up by
   2^l and the bias 0. */
struct LevelTest {
    uint64_t start, limit, bias;
};

inline LevelTest level_test(const dsn_walked_level &level, uint32_t level_radius, int64_t tap_shift,
                            bool closed) {
    const uint32_t l = level.level;
    const int64_t spacing_texel = static_cast<int64_t>(one_texel) << l, spacing = static_cast<int64_t>(1)
                                                                                  << l;
    const int64_t edge = closed ? 0 : spacing;
    LevelTest test;
    test.start =
        static_cast<uint64_t>(static_cast<int64_t>(level_radius + 1u) * spacing_texel - edge - tap_shift);
    test.limit = static_cast<uint64_t>(static_cast<int64_t>(2u * level_radius + 2u) * spacing_texel - edge);
    test.bias = static_cast<uint64_t>(edge);
    return test;
}

} // namespace

#endif /* DSN_FILTERING */

#endif /* DSN_LEVEL_READ_H */
