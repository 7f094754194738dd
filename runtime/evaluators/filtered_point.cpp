/* runtime/evaluators/filtered_point.cpp - the filtered evaluation at one point (dsn.h, "Filtered
   evaluation"): the sums of the one or two levels it blends at each anisotropic tap (filtered_sift.cpp in the
   fast build, filtered_walk.cpp in the small one); each level then normalized with its own offset and 8 extra
   fraction bits, blended and averaged over the taps, rounded once. Also the API's filtered per-point
   functions. Compiled only with DSN_FILTERING. */
#include "core/continuous_internal.h"
#include "core/filtered_internal.h"
#include "core/histogram_map.h"
#include "core/normalize_fixed.h"

#if DSN_FILTERING

namespace {

/* Each level's value keeps 8 more fraction bits than the Q16.16 output, saturated to +-2^46 (far beyond
   the output's range): the blend of two of them times 256 and the sum of 16 taps stay below 2^59. */
const uint32_t extra_bits = 8;
const int64_t level_value_limit = static_cast<int64_t>(1) << 46;

/* A level's sums (stored-value units, Q.32) in level-0 units: times 2^exponent, rounded to nearest
   (halves up) when that divides; modulo 2^64 as every sum. */
uint64_t in_texton_units(uint64_t sum, int32_t exponent) {
    if (exponent >= 0) return sum << static_cast<uint32_t>(exponent);
    const uint32_t shift = static_cast<uint32_t>(-exponent);
    return static_cast<uint64_t>(
        floor_shift(signed_from_bits(sum + (static_cast<uint64_t>(1) << (shift - 1u))), shift));
}

} // namespace

namespace {

/* A level's sums (level-0 units once in_texton_units has scaled them) normalized from `offset`, with
   extra_bits more fraction bits than Q16.16, saturated to +-level_value_limit. */
void level_values_from(const dsn_noise_state *noise, const int64_t *offset, const uint64_t *sums,
                       int64_t *values) {
    const uint32_t channels = noise->asset.channels;
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

const int64_t *dsn_internal_level_offset(const dsn_noise_state *noise, uint32_t level) {
    return level == 0 ? noise->offset : noise->level_offset[level - 1u];
}

void dsn_internal_filter_level_values(const dsn_noise_state *noise, const dsn_walked_level *level,
                                      const uint64_t *level_sums, int64_t *values) {
    dsn_internal_filter_level_values_from(noise, level, level_sums,
                                          dsn_internal_level_offset(noise, level->level), values);
}

void dsn_internal_filter_level_values_from(const dsn_noise_state *noise, const dsn_walked_level *level,
                                           const uint64_t *level_sums, const int64_t *offset,
                                           int64_t *values) {
    uint64_t sums[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t k = 0; k < noise->asset.channels; k++)
        sums[k] = in_texton_units(level_sums[k], level->exponent);
    level_values_from(noise, offset, sums, values);
}

#if DSN_GRADIENTS
void dsn_internal_filter_level_slopes(const dsn_noise_state *noise, const dsn_walked_level *level,
                                      const uint64_t *level_slopes, int64_t *values) {
    static const int64_t no_offset[DSN_MAX_CHANNELS] = {0, 0, 0};
    uint64_t sums[DSN_MAX_CHANNELS] = {0, 0, 0};
    /* per 2^-16 level texel, that is per 2^(level - 16) texel: times 2^(16 - level) per texel */
    for (uint32_t k = 0; k < noise->asset.channels; k++)
        sums[k] = in_texton_units(level_slopes[k] << (16u - level->level), level->exponent);
    level_values_from(noise, no_offset, sums, values);
}
#endif

int dsn_internal_filter_fade(const dsn_noise_state *noise, const dsn_filter_plan *plan, int32_t *out) {
    const uint32_t lower = static_cast<uint32_t>(plan->lod_q8) >> 8;
#if DSN_HISTOGRAM
    if (noise->asset.histogram_table != 0 && lower >= noise->asset.histogram_levels) {
        dsn_internal_histogram_fade(&noise->asset, out); /* both tables are `expected`: whatever g is */
        return 1;
    }
#endif
    if (lower <= noise->asset.pyramid_levels) return 0;
    for (uint32_t c = 0; c < noise->asset.channels; c++) /* the mean colour, exactly */
        out[c] = dsn_round_saturate(noise->asset.mean[c], extra_bits);
    return 1;
}

uint32_t dsn_internal_filter_walked_levels(const dsn_noise_state *noise, const dsn_filter_plan *plan,
                                           dsn_walked_level *walked) {
    const uint32_t lower = static_cast<uint32_t>(plan->lod_q8) >> 8;
    walked[0] = dsn_internal_walked_level(noise, lower);
    if ((plan->lod_q8 & 255) == 0 || lower >= noise->asset.pyramid_levels) return 1;
    walked[1] = dsn_internal_walked_level(noise, lower + 1u);
    return 2;
}

void dsn_internal_filter_add_level(const dsn_noise_state *noise, const dsn_filter_plan *plan, uint32_t index,
                                   const int64_t *values, int64_t *totals) {
    const int64_t blend = plan->lod_q8 & 255, weight = index == 0 ? 256 - blend : blend;
    for (uint32_t c = 0; c < noise->asset.channels; c++) totals[c] += values[c] * weight;
}

void dsn_internal_filter_add_mean(const dsn_noise_state *noise, const dsn_filter_plan *plan,
                                  int64_t *totals) {
    const int64_t blend = plan->lod_q8 & 255;
    for (uint32_t c = 0; c < noise->asset.channels; c++)
        totals[c] += static_cast<int64_t>(noise->asset.mean[c]) * blend;
}

void dsn_internal_filter_round(const dsn_noise_state *noise, const dsn_filter_plan *plan,
                               const int64_t *totals, int32_t *out) {
    /* taps = 2^k: one rounding of totals / (256 2^k 2^extra_bits). */
    uint32_t tap_shift = 0;
    while ((1u << tap_shift) < plan->taps) tap_shift++;
    for (uint32_t c = 0; c < noise->asset.channels; c++)
        out[c] = dsn_round_saturate(totals[c], 8u + tap_shift + extra_bits);
}

void dsn_internal_filter_finish(const dsn_noise_state *noise, const dsn_filter_plan *plan,
                                const int64_t *totals, int32_t *out) {
    dsn_internal_filter_round(noise, plan, totals, out);
#if DSN_HISTOGRAM
    if (noise->asset.histogram_table != 0)
        dsn_internal_histogram_map(&noise->asset, out, static_cast<uint32_t>(plan->lod_q8) >> 8,
                                   static_cast<uint32_t>(plan->lod_q8 & 255));
#endif
}

namespace {

typedef void (*filter_sums_function)(const dsn_noise_state *, uint64_t, uint64_t, const dsn_filter_plan *,
                                     const dsn_walked_level *, uint32_t, dsn_filter_sums);

void filtered_point(const dsn_noise_state *noise, uint64_t x, uint64_t y, const dsn_filter_plan *plan,
                    filter_sums_function level_sums, int32_t *out) {
    if (dsn_internal_filter_fade(noise, plan, out)) return;
    if (plan->lod_q8 == 0 && plan->taps == 1) {
        dsn_internal_continuous_point(noise, x, y, out);
        return;
    }
    /* The levels walked: the lower one, and the upper one unless it has no weight or is the mean. */
    dsn_walked_level walked[2];
    const uint32_t count = dsn_internal_filter_walked_levels(noise, plan, walked);
    dsn_filter_sums sums;
    level_sums(noise, x, y, plan, walked, count, sums);
    int64_t totals[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        for (uint32_t l = 0; l < count; l++) {
            int64_t values[DSN_MAX_CHANNELS] = {0, 0, 0};
            dsn_internal_filter_level_values(noise, &walked[l], sums[tap][l], values);
            dsn_internal_filter_add_level(noise, plan, l, values, totals);
        }
        if (count == 1) dsn_internal_filter_add_mean(noise, plan, totals);
    }
    dsn_internal_filter_finish(noise, plan, totals, out);
}

} // namespace

void dsn_internal_filtered_point(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                 const dsn_filter_plan *plan, int32_t *out) {
#if DSN_SMALL_CODE
    filtered_point(noise, x, y, plan, dsn_internal_filter_sums_walked, out);
#else
    filtered_point(noise, x, y, plan, dsn_internal_filter_sums_sifted, out);
#endif
}

void dsn_internal_filtered_point_walked(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                        const dsn_filter_plan *plan, int32_t *out) {
    filtered_point(noise, x, y, plan, dsn_internal_filter_sums_walked, out);
}

namespace {

uint32_t values_written(const dsn_noise_state *noise) { return dsn_values_per_point(noise); }

/* dsn_filtered_point_fixed's values, errors and zeroed output as `kind` (float or u8). */
int filtered_point_as(const dsn_noise *handle, int64_t x, int64_t y, const dsn_footprint *footprint,
                      void *out, dsn_output_kind kind) {
    int32_t fixed[DSN_MAX_CHANNELS] = {0, 0, 0};
    if (out == 0) return DSN_ERR_NULL;
    const int err = dsn_filtered_point_fixed(handle, x, y, footprint, fixed);
    dsn_store_pixel(out, kind, 0, fixed, values_written(dsn_state(handle)));
    return err;
}

} // namespace

int dsn_internal_filtered_check(const dsn_noise_state *noise) { return dsn_internal_continuous_check(noise); }

namespace {

/* Whether the values of rows first .. first + rows - 1 and columns left .. left + columns - 1 are all 0. */
bool zero_block(const dsn_level &level, uint32_t channels, uint32_t bits, uint32_t first, uint32_t rows,
                uint32_t left, uint32_t columns) {
    for (uint32_t row = first; row < first + rows; row++)
        for (uint32_t index = (row * level.width + left) * channels;
             index < (row * level.width + left + columns) * channels; index++)
            if ((bits == 8 ? dsn_read_i8(level.values + index) : dsn_read_i16le(level.values + 2u * index)) !=
                0)
                return false;
    return true;
}

} // namespace

/* The margins grow while both outer columns (rows) inside the current ones are zero: a symmetric cut
   keeps the window centred on the impulse (radius - margin on each side), so every read is the same. */
void dsn_internal_compute_level_margins(dsn_noise_state *noise) {
    const dsn_asset *asset = &noise->asset;
    for (uint32_t l = 0; l <= asset->pyramid_levels && l <= DSN_PYRAMID_MAX_LEVELS; l++) {
        dsn_level level;
        if (dsn_asset_level(asset, l, &level) != DSN_OK) return;
        uint32_t x = 0, y = 0;
        while (2u * x + 2u < level.width &&
               zero_block(level, asset->channels, asset->bits, 0, level.height, x, 1) &&
               zero_block(level, asset->channels, asset->bits, 0, level.height, level.width - 1u - x, 1))
            x++;
        while (2u * y + 2u < level.height &&
               zero_block(level, asset->channels, asset->bits, y, 1, 0, level.width) &&
               zero_block(level, asset->channels, asset->bits, level.height - 1u - y, 1, 0, level.width))
            y++;
        noise->level_margin[l][0] = static_cast<uint8_t>(x);
        noise->level_margin[l][1] = static_cast<uint8_t>(y);
    }
}

dsn_walked_level dsn_internal_walked_level(const dsn_noise_state *noise, uint32_t level) {
    dsn_level stored;
    dsn_walked_level out;
    dsn_asset_level(&noise->asset, level, &stored); /* level <= pyramid_levels: cannot fail */
    const uint32_t margin_x = noise->level_margin[level][0], margin_y = noise->level_margin[level][1];
    const uint32_t value_bytes = noise->asset.channels * noise->asset.bits / 8u;
    out.values = stored.values + (margin_y * stored.width + margin_x) * value_bytes;
    out.width = stored.width - 2u * margin_x;
    out.height = stored.height - 2u * margin_y;
    out.stride = stored.width;
    out.radius_x = (out.width - 1u) / 2u;
    out.radius_y = (out.height - 1u) / 2u;
    out.level = level;
    out.exponent = stored.exponent;
    return out;
}

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
    return filtered_point_as(handle, dsn_coordinate_from_double(x), dsn_coordinate_from_double(y), footprint,
                             out, dsn_output_float);
}

int dsn_filtered_point_u8(const dsn_noise *handle, int64_t x, int64_t y, const dsn_footprint *footprint,
                          uint8_t *out) {
    return filtered_point_as(handle, x, y, footprint, out, dsn_output_u8);
}

} // extern "C"

#endif /* DSN_FILTERING */
