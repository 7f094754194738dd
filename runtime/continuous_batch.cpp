/* runtime/continuous_batch.cpp - the continuous mode at a batch of arbitrary points (a renderer's ray
   hits): arrays of Q32.32 coordinates in, values out, each exactly the per-point value. */
#include "continuous_internal.h"
#include "normalize_fixed.h"

namespace {

int evaluate_batch(const dsn_noise *handle, const int64_t *x, const int64_t *y, size_t count, void *out,
                   dsn_output_kind kind) {
    const dsn_noise_state *noise = dsn_state(handle);
    const int err = dsn_internal_continuous_check(noise);
    if (err != DSN_OK) return err;
    if (count == 0) return DSN_OK;
    if (x == 0 || y == 0 || out == 0) return DSN_ERR_NULL;
    const uint32_t channels = noise->asset.channels;
    int32_t pixel[DSN_MAX_CHANNELS];
    for (size_t i = 0; i < count; i++) {
        dsn_internal_continuous_point(noise, static_cast<uint64_t>(x[i]), static_cast<uint64_t>(y[i]), pixel);
        dsn_store_pixel(out, kind, i * channels, pixel, channels);
    }
    return DSN_OK;
}

} // namespace

extern "C" {

int dsn_continuous_batch_fixed(const dsn_noise *noise, const int64_t *x, const int64_t *y, size_t count,
                               int32_t *out) {
    return evaluate_batch(noise, x, y, count, out, dsn_output_fixed);
}

int dsn_continuous_batch_float(const dsn_noise *noise, const int64_t *x, const int64_t *y, size_t count,
                               float *out) {
    return evaluate_batch(noise, x, y, count, out, dsn_output_float);
}

} // extern "C"
