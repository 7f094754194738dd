/* runtime/normalize.cpp - the fixed-point normalization of dsn_noise_init: per output channel c,
   out_c = (offset_c + sum_k gain_ck Q_k) / 2^gain_shift in Q16.16, where Q_k is the integer sum of the
   quantized texton values of channel k. With t_k = q_k scale_k / 2^40 and lambda = impacts / |S|:
       gain_ck   = K_ck scale_k / (2^40 sqrt(lambda))                    (in output units per q unit)
       offset_c  = mean_c - sum_k gain_ck lambda sum_y q_k(y)
   computed once in integer arithmetic (integer square root, 128-bit intermediates), rounded to nearest. */
#include "init_internal.h"
#include "wide_arithmetic.h"

namespace {

const uint32_t gain_limit_bits = 29; /* |gain| < 2^29 keeps a pixel's sum below 2^63 (normalize_fixed.h) */

uint64_t integer_sqrt(uint64_t value) {
    uint64_t root = 0, bit = uint64_t(1) << 62;
    while (bit > value) bit >>= 2;
    while (bit != 0) {
        if (value >= root + bit) {
            value -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return root;
}

/* sqrt(lambda) = root / 2^root_shift with root >= 2^22: the radicand impacts << e is brought near 2^62
   first (e even), so the integer square root keeps 22+ significant bits. */
void sqrt_lambda(uint32_t impacts_q16, uint32_t support_size, uint64_t *root, uint32_t *root_shift) {
    uint32_t e = 0;
    while ((uint64_t(impacts_q16) << (e + 2)) < (uint64_t(1) << 62)) e += 2;
    /* lambda 2^(e+16) = (impacts_q16 << e) / |S|, so the root is sqrt(lambda) 2^((e + 16) / 2). */
    *root = integer_sqrt(dsn_divide(uint64_t(impacts_q16) << e, support_size));
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
}
