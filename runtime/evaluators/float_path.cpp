/* runtime/evaluators/float_path.cpp - the float path of dsn.h: dsn_noise_load, dsn_sample and
   dsn_noise_mean_float, the common case in three calls, each a thin layer over the full API (so the same
   bits). */
#include "core/continuous_internal.h"
#include "core/histogram_map.h"
#include "setup/noise_state.h"

extern "C" int dsn_noise_load(dsn_noise *noise, const void *bytes, size_t size, uint32_t seed) {
    if (noise == 0) return DSN_ERR_NULL;
    dsn_asset asset;
    const int load_error = dsn_asset_load(&asset, bytes, size);
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = seed;
    /* The float path samples the continuous mode, which reads the texton bilinearly: allowed on every
       asset (dsn.h says what a lattice-baked texton then looks like). */
    if (asset.interpolation == DSN_INTERPOLATION_LATTICE) config.flags = DSN_FLAG_ALLOW_LATTICE_CONTINUOUS;
    /* After a failed load the asset is zeroed, which init refuses after zeroing the noise: the state every
       function refuses, as after a failed init. */
    const int init_error = dsn_noise_init(noise, &asset, &config);
    return load_error != DSN_OK ? load_error : init_error;
}

extern "C" int dsn_sample(const dsn_noise *noise, float x, float y, float *out) {
    /* dsn_continuous_point_float with the floats converted directly: dsn_coordinate_from_float(x) is
       dsn_coordinate_from_double(x) for every float, and no double arithmetic is needed. */
    return dsn_internal_continuous_point_as(noise, dsn_coordinate_from_float(x), dsn_coordinate_from_float(y),
                                            out, dsn_output_float);
}

extern "C" int dsn_noise_mean_float(const dsn_noise *handle, float *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    if (!dsn_configured(noise)) {
        out[0] = dsn_fixed_to_float(0);
        return DSN_ERR_NULL;
    }
#if DSN_HISTOGRAM
    if (noise->asset.histogram_table != 0) { /* the filtered evaluation's fade colour, exactly */
        int32_t fade[DSN_MAX_CHANNELS];
        dsn_internal_histogram_fade(&noise->asset, fade);
        for (uint32_t c = 0; c < noise->asset.channels; c++) out[c] = dsn_fixed_to_float(fade[c]);
        return DSN_OK;
    }
#endif
    /* Q8.24: one rounding to float, then an exact power-of-two scaling (as dsn_fixed_to_float). */
    for (uint32_t c = 0; c < noise->asset.channels; c++)
        out[c] = static_cast<float>(noise->asset.mean[c]) * (1.0f / 16777216.0f);
    return DSN_OK;
}
