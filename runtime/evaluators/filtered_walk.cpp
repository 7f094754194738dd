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
#include "core/level_read.h"
#include "core/poisson_count.h"

#if DSN_FILTERING

namespace {

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
