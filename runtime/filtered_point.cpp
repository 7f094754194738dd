/* runtime/filtered_point.cpp - the filtered evaluation at one point (dsn.h, "Filtered evaluation"): for
   each anisotropic tap, one walk over the impulses within reach of the coarser of the two levels it
   blends, each impulse adding its bilinear read of both levels to two sum vectors; each level then
   normalized with its own offset and 8 extra fraction bits, blended and averaged over the taps, rounded
   once. Also the API's filtered per-point functions. Compiled only with DSN_FILTERING. */
#include "bilinear_texton.h"
#include "cell_walk.h"
#include "continuous_internal.h"
#include "filtered_internal.h"
#include "histogram_map.h"
#include "impulse_position.h"
#include "normalize_fixed.h"
#include "poisson_count.h"

#if DSN_FILTERING

namespace {

/* Each level's value keeps 8 more fraction bits than the Q16.16 output, saturated to +-2^46 (far beyond
   the output's range): the blend of two of them times 256 and the sum of 16 taps stay below 2^59. */
const uint32_t extra_bits = 8;
const int64_t level_value_limit = static_cast<int64_t>(1) << 46;

/* floor(value / 2^shift), 0 <= shift <= 62, without shifting a negative number. */
int64_t floor_shift(int64_t value, uint32_t shift) {
    const uint64_t bias = static_cast<uint64_t>(1) << 63;
    return signed_from_bits(((static_cast<uint64_t>(value) + bias) >> shift) - (bias >> shift));
}

/* One pyramid level as the walk reads it: values at spacing 2^level texels, centred on the impulse. */
struct Level {
    const unsigned char *values;
    uint32_t width, height, radius_x, radius_y, level;
    int32_t exponent;
};

Level level_of(const dsn_noise_state *noise, uint32_t level) {
    dsn_level stored;
    Level out;
    dsn_asset_level(&noise->asset, level, &stored); /* level <= pyramid_levels: cannot fail */
    out.values = stored.values;
    out.width = stored.width;
    out.height = stored.height;
    out.radius_x = (stored.width - 1u) / 2u;
    out.radius_y = (stored.height - 1u) / 2u;
    out.level = level;
    out.exponent = stored.exponent;
    return out;
}

/* The walk radius of a level along one axis: impulses whose floor lies within radius + 1 of the point's
   integer part X, that is every impulse within (level radius + 1) 2^level texels (as the continuous
   mode's radius r for level 0). */
uint32_t walk_radius(uint32_t level_radius, uint32_t level) { return ((level_radius + 1u) << level) - 1u; }

/* The stored value of (row, column, channel), 0 outside the level's window (-1 too: unsigned). */
inline int64_t level_texel(const Level &level, uint32_t channels, uint32_t bits, uint32_t row,
                           uint32_t column, uint32_t channel) {
    if (row >= level.height || column >= level.width) return 0;
    const uint32_t index = (row * level.width + column) * channels + channel;
    return bits == 8 ? dsn_read_i8(level.values + index) : dsn_read_i16le(level.values + 2u * index);
}

/* Adds the level's bilinear texton at the impulse-to-point offset (dx, dy), Q32.32 level-0 texels, to
   the sums (Q.32, stored-value units): the offset is divided by the spacing 2^level (rounded down) and
   read as the continuous mode reads level 0 (bracket, the same weights). */
inline void add_level(const Level &level, uint32_t channels, uint32_t bits, int64_t dx, int64_t dy,
                      uint64_t *sums) {
    uint32_t row, row_weight, column, column_weight;
    if (!bracket(floor_shift(dy, level.level), level.radius_y, &row, &row_weight) ||
        !bracket(floor_shift(dx, level.level), level.radius_x, &column, &column_weight))
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

/* One axis of the walk: the cells around the point's integer part for this radius, and its fraction. */
struct WalkAxis {
    dsn_axis axis;
    uint32_t fraction;
};

WalkAxis walk_axis(uint64_t coordinate, uint32_t radius, uint32_t shift, uint32_t period) {
    WalkAxis walk;
    walk.fraction = static_cast<uint32_t>(coordinate);
    dsn_axis_init(&walk.axis, static_cast<uint32_t>(coordinate >> 32) - 1u, 3u, radius, shift, period);
    return walk;
}

/* Offset (Q32.32) from an impulse at 16-bit in-cell position bits16 of the cell at cell_origin to the
   point, as the continuous mode computes it; false beyond the period (the impulse is discarded). */
inline bool impulse_offset(const WalkAxis &walk, const dsn_span &span, uint32_t cell_origin, uint32_t bits16,
                           int64_t *offset) {
    const uint32_t shift = walk.axis.shift;
    if (cell_origin + (bits16 >> (16u - shift)) > span.last_position) return false;
    const uint32_t whole = 1u + span.base - walk.axis.radius - cell_origin; /* X - cell origin, mod 2^32 */
    const int64_t in_cell = static_cast<int64_t>(static_cast<uint64_t>(bits16) << (16u + shift));
    *offset = static_cast<int64_t>(dsn_signed_sum(whole)) * static_cast<int64_t>(one_texel) +
              static_cast<int64_t>(walk.fraction) - in_cell;
    return true;
}

/* The sums of one or two levels at the point (x, y), over every impulse within reach of either. */
void level_sums(const dsn_noise_state *noise, uint64_t x, uint64_t y, const Level *levels, uint32_t count,
                uint64_t (*sums)[DSN_MAX_CHANNELS]) {
    const uint32_t shift = noise->cell_shift, channels = noise->asset.channels, bits = noise->asset.bits;
    uint32_t radius_x = 0, radius_y = 0;
    for (uint32_t i = 0; i < count; i++) {
        const uint32_t rx = walk_radius(levels[i].radius_x, levels[i].level);
        const uint32_t ry = walk_radius(levels[i].radius_y, levels[i].level);
        radius_x = rx > radius_x ? rx : radius_x;
        radius_y = ry > radius_y ? ry : radius_y;
    }
    const WalkAxis wx = walk_axis(x, radius_x, shift, noise->period[0]);
    const WalkAxis wy = walk_axis(y, radius_y, shift, noise->period[1]);
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

/* A level's sums (stored-value units, Q.32) in level-0 units: times 2^exponent, rounded to nearest
   (halves up) when that divides; modulo 2^64 as every sum. */
uint64_t in_texton_units(uint64_t sum, int32_t exponent) {
    if (exponent >= 0) return sum << static_cast<uint32_t>(exponent);
    const uint32_t shift = static_cast<uint32_t>(-exponent);
    return static_cast<uint64_t>(
        floor_shift(signed_from_bits(sum + (static_cast<uint64_t>(1) << (shift - 1u))), shift));
}

/* The normalized value of one level (the lattice normalization of normalize_q32 with the level's offset)
   with extra_bits more fraction bits than Q16.16, saturated to +-level_value_limit. */
void level_values(const dsn_noise_state *noise, const Level &level, const uint64_t *level_sums,
                  int64_t *values) {
    const uint32_t channels = noise->asset.channels;
    const int64_t *offset = level.level == 0 ? noise->offset : noise->level_offset[level.level - 1u];
    uint64_t sums[DSN_MAX_CHANNELS];
    for (uint32_t k = 0; k < channels; k++) sums[k] = in_texton_units(level_sums[k], level.exponent);
    for (uint32_t c = 0; c < channels; c++) {
        /* |offset| <= 2^61 (init), |gain| < 2^29: below 2^63 as in normalize_q32. */
        int64_t accumulated = offset[c], fractions = 0;
        for (uint32_t k = 0; k < channels; k++) {
            const int64_t whole = dsn_signed_sum(static_cast<uint32_t>(sums[k] >> 32));
            const int64_t fraction = static_cast<int64_t>(sums[k] & 0xFFFFFFFFu);
            accumulated += noise->gain[c * 3 + k] * whole;
            fractions += noise->gain[c * 3 + k] * fraction;
        }
        accumulated += dsn_signed_sum(static_cast<uint32_t>(static_cast<uint64_t>(fractions) >> 32));
        /* gain_shift >= 8 (normalize.cpp), so the rounding shift is >= 0. */
        const uint32_t shift = noise->gain_shift - extra_bits;
        const int64_t half = shift == 0 ? 0 : static_cast<int64_t>(1) << (shift - 1u);
        const int64_t value = floor_shift(accumulated + half, shift);
        values[c] = value > level_value_limit    ? level_value_limit
                    : value < -level_value_limit ? -level_value_limit
                                                 : value;
    }
}

} // namespace

void dsn_internal_filtered_point(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                 const dsn_filter_plan *plan, int32_t *out) {
    const uint32_t channels = noise->asset.channels, levels = noise->asset.pyramid_levels;
    const uint32_t lower = static_cast<uint32_t>(plan->lod_q8) >> 8;
    const int64_t blend = plan->lod_q8 & 255;
#if DSN_HISTOGRAM
    const int mapped = noise->asset.histogram_table != 0;
    if (mapped && lower >= noise->asset.histogram_levels) { /* both tables are `expected`: whatever g is */
        dsn_internal_histogram_fade(&noise->asset, out);
        return;
    }
#endif
    if (lower > levels) { /* the mean colour, exactly */
        for (uint32_t c = 0; c < channels; c++) out[c] = dsn_round_saturate(noise->asset.mean[c], extra_bits);
        return;
    }
    if (plan->lod_q8 == 0 && plan->taps == 1) {
        dsn_internal_continuous_point(noise, x, y, out);
        return;
    }
    /* The levels walked: the lower one, and the upper one unless it has no weight or is the mean. */
    Level walked[2];
    walked[0] = level_of(noise, lower);
    uint32_t count = 1;
    if (blend != 0 && lower < levels) walked[count++] = level_of(noise, lower + 1u);
    int64_t totals[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        uint64_t sums[2][DSN_MAX_CHANNELS] = {{0, 0, 0}, {0, 0, 0}};
        level_sums(noise, x + static_cast<uint64_t>(plan->offset_x[tap]),
                   y + static_cast<uint64_t>(plan->offset_y[tap]), walked, count, sums);
        int64_t values[2][DSN_MAX_CHANNELS];
        level_values(noise, walked[0], sums[0], values[0]);
        if (count == 2) level_values(noise, walked[1], sums[1], values[1]);
        for (uint32_t c = 0; c < channels; c++) {
            const int64_t upper = count == 2   ? values[1][c]
                                  : blend != 0 ? static_cast<int64_t>(noise->asset.mean[c])
                                               : 0;
            totals[c] += values[0][c] * (256 - blend) + upper * blend;
        }
    }
    /* taps = 2^k: one rounding of totals / (256 2^k 2^extra_bits). */
    uint32_t tap_shift = 0;
    while ((1u << tap_shift) < plan->taps) tap_shift++;
    for (uint32_t c = 0; c < channels; c++)
        out[c] = dsn_round_saturate(totals[c], 8u + tap_shift + extra_bits);
#if DSN_HISTOGRAM
    if (mapped) dsn_internal_histogram_map(&noise->asset, out, lower, static_cast<uint32_t>(blend));
#endif
}

namespace {

uint32_t values_written(const dsn_noise_state *noise) {
    return noise == 0 || noise->asset.channels == 0 ? 1u : noise->asset.channels;
}

} // namespace

int dsn_internal_filtered_check(const dsn_noise_state *noise) { return dsn_internal_continuous_check(noise); }

extern "C" {

int dsn_filtered_point_fixed(const dsn_noise *handle, int64_t x, int64_t y, const dsn_footprint *footprint,
                             int32_t *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    int err = dsn_internal_filtered_check(noise);
    dsn_filter_plan plan;
    if (err == DSN_OK) err = dsn_internal_filter_plan(footprint, noise->asset.pyramid_levels, &plan);
    if (err != DSN_OK) {
        for (uint32_t c = 0; c < values_written(noise); c++) out[c] = 0;
        return err;
    }
    dsn_internal_filtered_point(noise, static_cast<uint64_t>(x), static_cast<uint64_t>(y), &plan, out);
    return DSN_OK;
}

int dsn_filtered_point_float(const dsn_noise *handle, double x, double y, const dsn_footprint *footprint,
                             float *out) {
    int32_t fixed[DSN_MAX_CHANNELS] = {0, 0, 0};
    if (out == 0) return DSN_ERR_NULL;
    const int err = dsn_filtered_point_fixed(handle, dsn_coordinate_from_double(x),
                                             dsn_coordinate_from_double(y), footprint, fixed);
    dsn_store_pixel(out, dsn_output_float, 0, fixed, values_written(dsn_state(handle)));
    return err;
}

} // extern "C"

#endif /* DSN_FILTERING */
