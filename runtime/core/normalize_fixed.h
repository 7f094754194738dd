/* runtime/core/normalize_fixed.h - from a point's integer texton sums to its output: the fixed-point
   normalization both evaluators share, and the conversion to the API's output types. Internal to
   libdsn; not installed. */
#ifndef DSN_NORMALIZE_FIXED_H
#define DSN_NORMALIZE_FIXED_H

#include <stddef.h>
#include <stdint.h>

#include "core/histogram_map.h"
#include "core/shared_inline.h"
#include "setup/noise_state.h"

/* out_c = round((offset_c + sum_k gain_ck * Q_k) / 2^gain_shift), saturated to int32, with Q_k the
   integer sum of the quantized texton values of channel k (taken modulo 2^32 and read as int32, which
   both evaluators do identically; it cannot wrap unless ~65000 full-scale impulses hit one point).
   Init guarantees |gain| < 2^29 and |offset| < 2^61, so |sum| < 3 2^60 + 2^61 < 2^63 - 2^32. */
DSN_SHARED int32_t dsn_round_saturate(int64_t accumulated, uint32_t shift) {
    /* Shifting a negative number is implementation-defined: move to uint64 with a 2^63 bias first
       (the conversion is modulo 2^64, and the rounding half cannot overflow given the bound above). */
    /* The difference is taken in uint64 too: with shift 0 (a histogram table of step shift 16) both
       terms are at least 2^63, where a signed subtraction would overflow. */
    const uint64_t bias = uint64_t(1) << 63;
    uint64_t biased = uint64_t(accumulated) + bias + ((uint64_t(1) << shift) >> 1);
    const uint64_t difference = (biased >> shift) - (bias >> shift);
    int64_t value = (difference & bias) ? -int64_t(~difference) - 1 : int64_t(difference);
    if (value > INT32_MAX) return INT32_MAX;
    if (value < INT32_MIN) return INT32_MIN;
    return int32_t(value);
}

static inline int32_t dsn_signed_sum(uint32_t sum) {
    return (sum & 0x80000000u) ? -int32_t(~sum) - 1 : int32_t(sum);
}

/* Whether the noise's outputs go through a histogram mapping (dsn_map_output). */
static inline int dsn_has_mapping(const dsn_noise_state *noise) {
#if DSN_HISTOGRAM
    return noise->asset.histogram_table != 0;
#else
    (void)noise;
    return 0;
#endif
}

/* The last step of every unfiltered evaluation: the histogram mapping's level 0, where the noise has
   one (dsn_noise_init leaves it out of the noise with DSN_FLAG_NO_HISTOGRAM). */
static inline void dsn_map_output(const dsn_noise_state *noise, int32_t *out) {
#if DSN_HISTOGRAM
    if (noise->asset.histogram_table != 0) dsn_internal_histogram_map(&noise->asset, out, 0, 0);
#else
    (void)noise;
    (void)out;
#endif
}

/* Q_k sums (uint32, modulo 2^32) -> Q16.16 values before the mapping, from `offset`: the noise's own, or
   zeros for a difference of sums (a gradient), which the mean does not reach. */
DSN_INLINE void dsn_normalize_from(const dsn_noise_state *noise, const int64_t *offset, const uint32_t *sums,
                                   int32_t *out) {
    const uint32_t shift = noise->gain_shift;
    const int64_t *gain = noise->gain;
#if DSN_SMALL_CODE
    const uint32_t channels = noise->asset.channels;
    for (uint32_t c = 0; c < channels; c++) {
        int64_t accumulated = offset[c];
        for (uint32_t k = 0; k < channels; k++) accumulated += gain[c * 3 + k] * dsn_signed_sum(sums[k]);
        out[c] = dsn_round_saturate(accumulated, shift);
    }
#else
    /* 1 or 3 channels (the loader's check) written out: loops over a count known only at run time cost as
       much as their products */
    const int64_t q0 = dsn_signed_sum(sums[0]);
    if (noise->asset.channels == 1) {
        out[0] = dsn_round_saturate(offset[0] + gain[0] * q0, shift);
        return;
    }
    const int64_t q1 = dsn_signed_sum(sums[1]), q2 = dsn_signed_sum(sums[2]);
    out[0] = dsn_round_saturate(offset[0] + gain[0] * q0 + gain[1] * q1 + gain[2] * q2, shift);
    out[1] = dsn_round_saturate(offset[1] + gain[3] * q0 + gain[4] * q1 + gain[5] * q2, shift);
    out[2] = dsn_round_saturate(offset[2] + gain[6] * q0 + gain[7] * q1 + gain[8] * q2, shift);
#endif
}

/* Q_k sums (uint32, modulo 2^32) -> Q16.16 outputs. */
DSN_SHARED void dsn_normalize(const dsn_noise_state *noise, const uint32_t *sums, int32_t *out) {
    dsn_normalize_from(noise, noise->offset, sums, out);
    dsn_map_output(noise, out);
}

/* The API edge's output types, for the paths that convert pixel by pixel through a switch rather than
   with one copy of their code per type (the conversion is nothing next to evaluating a pixel). */
typedef enum dsn_output_kind { dsn_output_fixed, dsn_output_float, dsn_output_u8 } dsn_output_kind;

DSN_SHARED void dsn_store_pixel(void *out, dsn_output_kind kind, size_t first, const int32_t *pixel,
                                uint32_t channels) {
    for (uint32_t c = 0; c < channels; c++) {
        if (kind == dsn_output_float)
            static_cast<float *>(out)[first + c] = dsn_fixed_to_float(pixel[c]);
        else if (kind == dsn_output_u8)
            static_cast<uint8_t *>(out)[first + c] = dsn_fixed_to_u8(pixel[c]);
        else
            static_cast<int32_t *>(out)[first + c] = pixel[c];
    }
}

#endif /* DSN_NORMALIZE_FIXED_H */
