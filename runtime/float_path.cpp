/* runtime/float_path.cpp - the float path of dsn.h: dsn_noise_load, dsn_sample and dsn_noise_mean_float,
   the common case in three calls, each a thin layer over the full API (so the same bits). */
#include "noise_state.h"

namespace {

/* The number of values a call writes: the noise's channels, or, for a noise with none (null, never
   configured, failed), the one value that every caller's array has, zeroed. */
uint32_t values_written(const dsn_noise_state *noise) {
    return noise == 0 || noise->asset.channels == 0 ? 1u : noise->asset.channels;
}

} // namespace

extern "C" int dsn_noise_load(dsn_noise *noise, const void *bytes, size_t size, uint32_t seed) {
    if (noise == 0) return DSN_ERR_NULL;
    dsn_asset asset;
    int err = dsn_asset_load(&asset, bytes, size);
    if (err != DSN_OK) {
        /* What dsn_noise_init leaves after a failure: a zeroed noise that every function refuses. */
        for (uint32_t i = 0; i < DSN_NOISE_WORDS; i++) noise->words[i] = 0;
        return err;
    }
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = seed;
    /* The float path samples the continuous mode, which reads the texton bilinearly: allowed on every
       asset (dsn.h says what a lattice-baked texton then looks like). */
    if (asset.interpolation == DSN_INTERPOLATION_LATTICE) config.flags |= DSN_FLAG_ALLOW_LATTICE_CONTINUOUS;
    return dsn_noise_init(noise, &asset, &config);
}

extern "C" int dsn_sample(const dsn_noise *handle, float x, float y, float *out) {
    if (out == 0) return DSN_ERR_NULL;
    /* dsn_continuous_point_float's steps with the float converted directly: dsn_coordinate_from_float(x)
       is dsn_coordinate_from_double(x) for every float, and no double arithmetic is needed. */
    int32_t fixed[DSN_MAX_CHANNELS] = {0, 0, 0};
    const int err =
        dsn_continuous_point_fixed(handle, dsn_coordinate_from_float(x), dsn_coordinate_from_float(y), fixed);
    for (uint32_t c = 0; c < values_written(dsn_state(handle)); c++) out[c] = dsn_fixed_to_float(fixed[c]);
    return err;
}

extern "C" int dsn_noise_mean_float(const dsn_noise *handle, float *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    if (noise == 0 || noise->asset.texton == 0) {
        out[0] = dsn_fixed_to_float(0);
        return DSN_ERR_NULL;
    }
    /* The mean is Q8.24: one rounding to float, then an exact power-of-two scaling (as dsn_fixed_to_float).
     */
    for (uint32_t c = 0; c < noise->asset.channels; c++)
        out[c] = static_cast<float>(noise->asset.mean[c]) * (1.0f / 16777216.0f);
    return DSN_OK;
}
