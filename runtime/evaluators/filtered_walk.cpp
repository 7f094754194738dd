/* runtime/evaluators/filtered_walk.cpp - the levels' sums at the taps of a filtered point, tap by tap: one
   walk over the impulses within reach of the coarser level at each tap, every impulse hashed and read at each
   level (a bilinear read with every texel's bounds tested). The small build's way, and the reference
   that the tests hold the fast build's sifted sums (filtered_sift.cpp) to. Compiled only with
   DSN_FILTERING. */
#include "core/bilinear_texton.h"
#include "core/cell_walk.h"
#include "core/continuous_internal.h"
#include "core/continuous_sift.h"
#include "core/filtered_internal.h"
#include "core/impulse_position.h"
#include "core/poisson_count.h"

#if DSN_FILTERING

namespace {

/* floor(value / 2^shift), 0 <= shift <= 62, without shifting a negative number. */
int64_t floor_shift_walk(int64_t value, uint32_t shift) {
    const uint64_t bias = static_cast<uint64_t>(1) << 63;
    return signed_from_bits(((static_cast<uint64_t>(value) + bias) >> shift) - (bias >> shift));
}

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
    if (!level_bracket(floor_shift_walk(dy, level.level), level.radius_y, Slopes, &row, &row_weight) ||
        !level_bracket(floor_shift_walk(dx, level.level), level.radius_x, Slopes, &column, &column_weight))
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

/* The sums of one or two levels at the point (x, y), over every impulse within reach of either; with
   Slopes their slopes too (slopes[level][axis][channel]). */
template <bool Slopes>
void level_sums(const dsn_noise_state *noise, uint64_t x, uint64_t y, const dsn_walked_level *levels,
                uint32_t count, uint64_t (*sums)[DSN_MAX_CHANNELS], uint64_t (*slopes)[2][DSN_MAX_CHANNELS]) {
    const uint32_t shift = noise->cell_shift, channels = noise->asset.channels, bits = noise->asset.bits;
    uint32_t radius_x, radius_y;
    dsn_filter_walk_radii(levels, count, &radius_x, &radius_y);
    const PointAxis wx = point_axis(x, radius_x, shift, noise->period[0]);
    const PointAxis wy = point_axis(y, radius_y, shift, noise->period[1]);
    for (uint32_t sy = 0; sy < wy.axis.span_count; sy++) {
        const dsn_span span_y = dsn_axis_span(&wy.axis, sy);
        for (uint32_t j = 0; j < span_y.cell_count; j++) {
            const uint32_t cell_y = dsn_span_cell(&span_y, j, shift), origin_y = cell_y << shift;
            const uint32_t row_key = dsn_row_key(noise, cell_y);
            for (uint32_t sx = 0; sx < wx.axis.span_count; sx++) {
                const dsn_span span_x = dsn_axis_span(&wx.axis, sx);
                for (uint32_t i = 0; i < span_x.cell_count; i++) {
                    const uint32_t cell_x = dsn_span_cell(&span_x, i, shift), origin_x = cell_x << shift;
                    const uint32_t key = dsn_cell_key_in_row(noise, cell_x, row_key);
                    const uint32_t impulses = dsn_cell_impulse_count(noise, key);
                    for (uint32_t k = 0; k < impulses; k++) {
                        const uint32_t hash = dsn_impulse_hash(noise, key, k);
                        int64_t dx, dy;
                        if (!impulse_offset(wy, span_y, origin_y, dsn_impulse_bits_y(hash), &dy) ||
                            !impulse_offset(wx, span_x, origin_x, dsn_impulse_bits_x(hash), &dx))
                            continue;
                        for (uint32_t l = 0; l < count; l++)
                            add_level<Slopes>(levels[l], channels, bits, dx, dy, sums[l],
                                              Slopes ? slopes[l] : 0);
                    }
                }
            }
        }
    }
}

/* Zeros, then the sums (and slopes) of every tap. */
template <bool Slopes>
void tap_sums(const dsn_noise_state *noise, uint64_t x, uint64_t y, const dsn_filter_plan *plan,
              const dsn_walked_level *levels, uint32_t count, dsn_filter_sums sums,
              dsn_filter_slopes *slopes) {
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        for (uint32_t l = 0; l < 2; l++)
            for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) {
                sums[tap][l][c] = 0;
                if (Slopes) (*slopes)[tap][l][0][c] = (*slopes)[tap][l][1][c] = 0;
            }
        level_sums<Slopes>(noise, x + static_cast<uint64_t>(plan->offset_x[tap]),
                           y + static_cast<uint64_t>(plan->offset_y[tap]), levels, count, sums[tap],
                           Slopes ? (*slopes)[tap] : 0);
    }
}

} // namespace

void dsn_internal_filter_sums_walked(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                     const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                     uint32_t count, dsn_filter_sums sums) {
    tap_sums<false>(noise, x, y, plan, levels, count, sums, 0);
}

#if DSN_GRADIENTS
void dsn_internal_filter_slopes_walked(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                       const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                       uint32_t count, dsn_filter_sums sums, dsn_filter_slopes *slopes) {
    tap_sums<true>(noise, x, y, plan, levels, count, sums, slopes);
}
#endif

#endif /* DSN_FILTERING */
