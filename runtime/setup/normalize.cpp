/* runtime/setup/normalize.cpp - the fixed-point normalization of dsn_noise_init: per output channel c,
   out_c = (offset_c + sum_k gain_ck Q_k) / 2^gain_shift in Q16.16, where Q_k is the integer sum of the
   quantized texton values of channel k. With t_k = q_k scale_k / 2^40 and lambda = impacts / |S|:
       gain_ck   = K_ck scale_k / (2^40 sqrt(lambda))                    (in output units per q unit)
       offset_c  = mean_c - sum_k gain_ck lambda sum_y q_k(y)
   computed once in integer arithmetic (integer square root, 128-bit intermediates), rounded to nearest. */
#include "setup/init_internal.h"
#include "setup/wide_arithmetic.h"

namespace {

const uint32_t gain_limit_bits = 29; /* |gain| < 2^29 keeps a pixel's sum below 2^63 (normalize_fixed.h) */

/* sqrt(lambda) = root / 2^root_shift with root >= 2^22: the radicand impacts << e is brought near 2^62
   first (e even), so the integer square root keeps 22+ significant bits. */
void sqrt_lambda(uint32_t impacts_q16, uint32_t support_size, uint64_t *root, uint32_t *root_shift) {
    uint32_t e = 0;
    while ((uint64_t(impacts_q16) << (e + 2)) < (uint64_t(1) << 62)) e += 2;
    /* lambda 2^(e+16) = (impacts_q16 << e) / |S|, so the root is sqrt(lambda) 2^((e + 16) / 2). */
    *root = dsn_integer_sqrt(dsn_divide(uint64_t(impacts_q16) << e, support_size));
    *root_shift = (e + 16) / 2;
}

int64_t negate_if(uint64_t magnitude, int negative) {
    const uint64_t limit = uint64_t(INT64_MAX);
    if (magnitude > limit) magnitude = limit;
    return negative ? -int64_t(magnitude) : int64_t(magnitude);
}

/* K_ck scale_k 2^(fraction_bits + 16) / (2^64 sqrt(lambda)): K is Q8.24 and scale Q.40, the output Q16. */
int64_t gain_value(int32_t transform, uint32_t scale, uint64_t root, uint32_t root_shift,
                   uint32_t fraction_bits) {
    uint64_t magnitude = transform < 0 ? uint64_t(0u - uint32_t(transform)) : uint64_t(transform);
    uint64_t product = magnitude * scale; /* < 2^63 */
    int32_t exponent = int32_t(fraction_bits + root_shift) - 48;
    uint64_t quotient = exponent >= 0 ? dsn_multiply_divide(product, uint64_t(1) << exponent, root)
                                      : dsn_multiply_divide(product, 1, root << -exponent);
    return negate_if(quotient, transform < 0);
}

int32_t transform_entry(const dsn_noise_state *noise, uint32_t index) {
    if (noise->flags & DSN_FLAG_NO_COLOR_TRANSFORM) return (index % 4 == 0) ? int32_t(DSN_Q24_ONE) : 0;
    return noise->asset.color_transform[index];
}

int64_t texton_sum(const dsn_asset *asset, uint32_t channel) {
    int64_t sum = 0;
    for (uint32_t row = 0; row < asset->height; row++)
        for (uint32_t column = 0; column < asset->width; column++)
            sum += dsn_asset_texton_value(asset, row, column, channel);
    return sum;
}

/* gain * lambda * sum(q), exactly rounded: lambda = impacts_q16 / (2^16 |S|). */
int64_t expected_sum(int64_t gain, int64_t sum, uint32_t impacts_q16, uint32_t support_size) {
    int negative = (gain < 0) != (sum < 0);
    uint64_t gain_magnitude = gain < 0 ? uint64_t(0) - uint64_t(gain) : uint64_t(gain);
    uint64_t sum_magnitude = sum < 0 ? uint64_t(0) - uint64_t(sum) : uint64_t(sum);
    uint64_t magnitude =
        dsn_multiply_divide(gain_magnitude * sum_magnitude, impacts_q16, uint64_t(support_size) << 16);
    return negate_if(magnitude, negative);
}

#if DSN_FILTERING
/* gain * lambda * sum * 2^power exactly rounded (power in [-24, 40]: a pyramid level's expected sum in
   texton units, with sum its stored values' sum); saturated when it does not fit. */
int64_t expected_level_sum(int64_t gain, int64_t sum, int32_t power, uint32_t impacts_q16,
                           uint32_t support_size) {
    int negative = (gain < 0) != (sum < 0);
    uint64_t gain_magnitude = gain < 0 ? uint64_t(0) - uint64_t(gain) : uint64_t(gain);
    uint64_t sum_magnitude = sum < 0 ? uint64_t(0) - uint64_t(sum) : uint64_t(sum);
    uint64_t product = gain_magnitude * sum_magnitude; /* < 2^29 2^31 */
    uint64_t divisor = uint64_t(support_size) << 16;
    uint64_t magnitude;
    if (power < 0)
        magnitude = dsn_multiply_divide(product, impacts_q16, divisor << -power); /* below 2^54 */
    else if (product > (UINT64_MAX >> power))
        magnitude = UINT64_MAX;
    else
        magnitude = dsn_multiply_divide(product << power, impacts_q16, divisor);
    return negate_if(magnitude, negative);
}

int64_t level_sum(const dsn_level *level, uint32_t channels, uint32_t bits, uint32_t channel) {
    int64_t sum = 0;
    const uint32_t count = level->width * level->height;
    for (uint32_t i = 0; i < count; i++) {
        const uint32_t index = i * channels + channel;
        sum += bits == 8 ? dsn_read_i8(level->values + index) : dsn_read_i16le(level->values + 2 * index);
    }
    return sum;
}

/* Each pyramid level's offset: its expected value E[sum_i t_l(x - x_i)] = lambda 4^l sum s_l is, in
   texton units, lambda (sum of its stored values) 2^(2l + exponent). Kept within +-2^61 like level 0's
   (absurd assets saturate), which keeps the evaluator's sums below 2^63. */
void compute_level_offsets(dsn_noise_state *noise) {
    const dsn_asset *asset = &noise->asset;
    const int64_t limit = int64_t(1) << 61;
    for (uint32_t l = 1; l <= asset->pyramid_levels && l <= 8; l++) {
        dsn_level level;
        if (dsn_asset_level(asset, l, &level) != DSN_OK) return;
        const int32_t power = int32_t(2 * l) + level.exponent;
        for (uint32_t c = 0; c < asset->channels; c++) {
            int64_t offset = int64_t(asset->mean[c]) * (int64_t(1) << (noise->gain_shift - 8));
            for (uint32_t k = 0; k < asset->channels; k++) {
                const int64_t expected = expected_level_sum(
                    noise->gain[c * 3 + k], level_sum(&level, asset->channels, asset->bits, k), power,
                    noise->impacts_q16, asset->support_size);
                /* offset - expected, saturated (both are below 2^63 in magnitude) */
                offset = expected > 0 && offset < INT64_MIN + expected   ? INT64_MIN
                         : expected < 0 && offset > INT64_MAX + expected ? INT64_MAX
                                                                         : offset - expected;
            }
            noise->level_offset[l - 1][c] = offset > limit ? limit : offset < -limit ? -limit : offset;
        }
    }
}
#endif

} // namespace

void dsn_internal_compute_normalization(dsn_noise_state *noise) {
    const dsn_asset *asset = &noise->asset;
    const uint32_t channels = asset->channels;
    const int64_t gain_limit = int64_t(1) << gain_limit_bits;
    uint64_t root;
    uint32_t root_shift;
    sqrt_lambda(noise->impacts_q16, asset->support_size, &root, &root_shift);

    /* The most fraction bits (at most 32) that keep every gain below the limit; gains still too large
       at 8 bits (absurd assets: one q unit worth thousands of output units) are clamped. */
    uint32_t fraction_bits = 32;
    for (;; fraction_bits--) {
        int fits = 1;
        for (uint32_t c = 0; c < channels; c++)
            for (uint32_t k = 0; k < channels; k++) {
                int64_t gain = gain_value(transform_entry(noise, c * 3 + k), asset->scale[k], root,
                                          root_shift, fraction_bits);
                if (gain >= gain_limit || gain <= -gain_limit) fits = 0;
                noise->gain[c * 3 + k] = gain < -gain_limit + 1  ? -gain_limit + 1
                                         : gain > gain_limit - 1 ? gain_limit - 1
                                                                 : gain;
            }
        if (fits || fraction_bits == 8) break;
    }
    noise->gain_shift = fraction_bits;

    for (uint32_t c = 0; c < channels; c++) {
        /* mean is Q8.24, the output Q16.16: mean 2^(fraction_bits - 8), exact. */
        int64_t offset = int64_t(asset->mean[c]) * (int64_t(1) << (fraction_bits - 8));
        for (uint32_t k = 0; k < channels; k++)
            offset -= expected_sum(noise->gain[c * 3 + k], texton_sum(asset, k), noise->impacts_q16,
                                   asset->support_size);
        noise->offset[c] = offset;
    }
#if DSN_FILTERING
    compute_level_offsets(noise);
#endif
}
