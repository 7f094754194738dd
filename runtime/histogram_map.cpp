/* runtime/histogram_map.cpp - the histogram-preserving output of format 1.2 (histogram_map.h): the
   table reads, their blend and the rotation, in exact integer arithmetic with one rounding each for v_k
   and out_c, as format.h states them. One out-of-line copy: it costs little next to the evaluation of
   the point it maps. Compiled only with DSN_HISTOGRAM. */
#include "histogram_map.h"

#include "format_bytes.h"
#include "normalize_fixed.h"

#if DSN_HISTOGRAM

namespace {

/* X_l of format.h: level l's table of channel k read at g, linearly interpolated, Q16.16 with d = 16 - s
   more fraction bits; expected[k] 2^d for l >= M. The interpolation lies between T[i] 2^d and T[j] 2^d
   (0 <= f < 2^d), so |X| <= 32767 2^4 2^16 < 2^35, and so is |expected 2^d| (the loader bounds
   expected by 32767 2^4). */
int64_t table_read(const dsn_asset *asset, uint32_t level, uint32_t k, int32_t g) {
    const uint32_t d = 16u - asset->histogram_step_shift;
    const int64_t unit = static_cast<int64_t>(1) << d;
    if (level >= asset->histogram_levels)
        return static_cast<int64_t>(asset->histogram_expected_q16[k]) * unit;
    const uint32_t entries = asset->histogram_entries;
    /* g - input_low is exact in int64 (both int32); the clamp keeps u within [0, (N - 1) 2^d] < 2^26. */
    const int64_t top = static_cast<int64_t>(entries - 1u) * unit;
    int64_t u = static_cast<int64_t>(g) - asset->histogram_input_low_q16;
    u = u < 0 ? 0 : u > top ? top : u;
    const uint32_t position = static_cast<uint32_t>(u);
    const uint32_t i = position >> d, f = position & (static_cast<uint32_t>(unit) - 1u);
    const uint32_t j = i + 1u < entries ? i + 1u : entries - 1u;
    const unsigned char *row = asset->histogram_table + 2u * ((level * asset->channels + k) * entries);
    const int64_t low = dsn_read_i16le(row + 2u * i), high = dsn_read_i16le(row + 2u * j);
    return (low * unit + (high - low) * static_cast<int64_t>(f)) * 16;
}

} // namespace

void dsn_internal_histogram_map(const dsn_asset *asset, int32_t *values, uint32_t level, uint32_t blend) {
    const uint32_t channels = asset->channels, d = 16u - asset->histogram_step_shift;
    int64_t mapped[DSN_MAX_CHANNELS];
    for (uint32_t k = 0; k < channels; k++) {
        /* |(256 - b) X_l + b X_(l+1)| <= 256 2^35 = 2^43; v_k then lies within +-32767 2^4 < 2^19. */
        int64_t blended = static_cast<int64_t>(256u - blend) * table_read(asset, level, k, values[k]);
        if (blend != 0) blended += static_cast<int64_t>(blend) * table_read(asset, level + 1u, k, values[k]);
        mapped[k] = dsn_round_saturate(blended, d + 8u);
    }
    for (uint32_t c = 0; c < channels; c++) {
        /* |centre 2^16| <= 2^47 and |P v| < 2^31 2^19: the sum stays below 2^52 (format.h). */
        int64_t accumulated = static_cast<int64_t>(asset->histogram_centre[c]) * 65536;
        for (uint32_t k = 0; k < channels; k++)
            accumulated += static_cast<int64_t>(asset->histogram_rotation[c * 3 + k]) * mapped[k];
        values[c] = dsn_round_saturate(accumulated, 24);
    }
}

void dsn_internal_histogram_fade(const dsn_asset *asset, int32_t *out) {
    for (uint32_t c = 0; c < asset->channels; c++) out[c] = 0; /* read, but no table is */
    dsn_internal_histogram_map(asset, out, asset->histogram_levels, 0);
}

int dsn_internal_histogram_usable(const dsn_asset *asset) {
    if (asset->histogram_table == 0) return 1;
    for (uint32_t k = 0; k < 3; k++)
        if (asset->histogram_expected_q16[k] < -DSN_HISTOGRAM_EXPECTED_LIMIT ||
            asset->histogram_expected_q16[k] > DSN_HISTOGRAM_EXPECTED_LIMIT)
            return 0;
    return asset->histogram_entries >= 2 && asset->histogram_entries <= DSN_HISTOGRAM_MAX_ENTRIES &&
           asset->histogram_levels >= 1 && asset->histogram_levels <= DSN_HISTOGRAM_MAX_LEVELS &&
           asset->histogram_step_shift <= DSN_HISTOGRAM_MAX_STEP_SHIFT;
}

#endif /* DSN_HISTOGRAM */
