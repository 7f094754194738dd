/* runtime/filtered_walk.cpp - the levels' sums at the taps of a filtered point, tap by tap: one walk over
   the impulses within reach of the coarser level at each tap, every impulse hashed and read at each
   level (a bilinear read with every texel's bounds tested). The small build's way, and the reference
   that the tests hold the fast build's sifted sums (filtered_sift.cpp) to. Compiled only with
   DSN_FILTERING. */
#include "bilinear_texton.h"
#include "cell_walk.h"
#include "continuous_internal.h"
#include "continuous_sift.h"
#include "filtered_internal.h"
#include "impulse_position.h"
#include "poisson_count.h"

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

/* Adds the level's bilinear texton at the impulse-to-point offset (dx, dy), Q32.32 level-0 texels, to
   the sums (Q.32, stored-value units): the offset is divided by the spacing 2^level (rounded down) and
   read as the continuous mode reads level 0 (bracket, the same weights). */
inline void add_level(const dsn_walked_level &level, uint32_t channels, uint32_t bits, int64_t dx, int64_t dy,
                      uint64_t *sums) {
    uint32_t row, row_weight, column, column_weight;
    if (!bracket(floor_shift_walk(dy, level.level), level.radius_y, &row, &row_weight) ||
        !bracket(floor_shift_walk(dx, level.level), level.radius_x, &column, &column_weight))
        return;
    const int64_t across = column_weight, down = row_weight;
    for (uint32_t c = 0; c < channels; c++) {
        const int64_t upper = (65536 - across) * level_texel(level, channels, bits, row, column, c) +
                              across * level_texel(level, channels, bits, row, column + 1u, c);
        const int64_t lower = (65536 - across) * level_texel(level, channels, bits, row + 1u, column, c) +
                              across * level_texel(level, channels, bits, row + 1u, column + 1u, c);
        sums[c] += static_cast<uint64_t>((65536 - down) * upper + down * lower); /* each term < 2^47 */
    }
}

/* The sums of one or two levels at the point (x, y), over every impulse within reach of either. */
void level_sums(const dsn_noise_state *noise, uint64_t x, uint64_t y, const dsn_walked_level *levels,
                uint32_t count, uint64_t (*sums)[DSN_MAX_CHANNELS]) {
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
                            add_level(levels[l], channels, bits, dx, dy, sums[l]);
                    }
                }
            }
        }
    }
}

} // namespace

void dsn_internal_filter_sums_walked(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                     const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                     uint32_t count, dsn_filter_sums sums) {
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        for (uint32_t l = 0; l < 2; l++)
            for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) sums[tap][l][c] = 0;
        level_sums(noise, x + static_cast<uint64_t>(plan->offset_x[tap]),
                   y + static_cast<uint64_t>(plan->offset_y[tap]), levels, count, sums[tap]);
    }
}

#endif /* DSN_FILTERING */
