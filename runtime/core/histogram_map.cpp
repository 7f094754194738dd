/* runtime/core/histogram_map.cpp - the histogram-preserving output of format 1.2 (histogram_map.h): the
   table reads, their blend and the rotation, in exact integer arithmetic with one rounding each for v_k
   and out_c, as format.h states them. One out-of-line copy: it costs little next to the evaluation of
   the point it maps. Compiled only with DSN_HISTOGRAM. */
#include "core/histogram_map.h"

#include "core/normalize_fixed.h"
#include "setup/format_bytes.h"

#if DSN_HISTOGRAM

namespace {

/* The asset's mapping as the reads need it. */
struct mapping {
    const unsigned char *table;
    uint32_t channels, entries, levels, d; /* d = 16 - step_shift: fraction bits of an entry step */
    int64_t low, top;                      /* input_low; (N - 1) 2^d, the clamp's top, < 2^26 */
};

inline mapping mapping_of(const dsn_asset *asset) {
    mapping m;
    m.table = asset->histogram_table;
    m.channels = asset->channels;
    m.entries = asset->histogram_entries;
    m.levels = asset->histogram_levels;
    m.d = 16u - asset->histogram_step_shift;
    m.low = asset->histogram_input_low_q16;
    m.top = static_cast<int64_t>(m.entries - 1u) << m.d;
    return m;
}

/* X_l of format.h: the table of level `level` < M and channel k read at g, linearly interpolated, in
   Q16.16 with d more fraction bits. The interpolation lies between T[i] 2^d and T[j] 2^d (0 <= f <
   2^d), so |X| <= 32767 2^4 2^16 < 2^35. */
inline int64_t table_read(const mapping &m, uint32_t level, uint32_t k, int32_t g) {
    /* g - input_low is exact in int64 (both int32); the clamp keeps u within [0, (N - 1) 2^d]. */
    int64_t u = static_cast<int64_t>(g) - m.low;
    u = u < 0 ? 0 : u > m.top ? m.top : u;
    const uint32_t position = static_cast<uint32_t>(u);
    const uint32_t i = position >> m.d, f = position & ((1u << m.d) - 1u);
    const uint32_t j = i + 1u < m.entries ? i + 1u : i;
    const unsigned char *row = m.table + 2u * ((level * m.channels + k) * m.entries);
    const int64_t low = dsn_read_i16le(row + 2u * i), high = dsn_read_i16le(row + 2u * j);
    return (low * (static_cast<int64_t>(1) << m.d) + (high - low) * static_cast<int64_t>(f)) * 16;
}

/* X_l for any level: expected[k] 2^d at and above M (|expected| <= 32767 2^4, so below 2^35 too). */
inline int64_t level_read(const dsn_asset *asset, const mapping &m, uint32_t level, uint32_t k, int32_t g) {
    if (level >= m.levels)
        return static_cast<int64_t>(asset->histogram_expected_q16[k]) * (int64_t(1) << m.d);
    return table_read(m, level, k, g);
}

} // namespace

void dsn_internal_histogram_map(const dsn_asset *asset, int32_t *values, uint32_t level, uint32_t blend) {
    const mapping m = mapping_of(asset);
    int64_t v[DSN_MAX_CHANNELS] = {0, 0, 0}; /* |v_k| <= 32767 2^4 < 2^19 */
    if (blend == 0 && level < m.levels) {    /* one table, every unfiltered evaluation: round(X / 2^d) */
        for (uint32_t k = 0; k < m.channels; k++)
            v[k] = dsn_round_saturate(table_read(m, level, k, values[k]), m.d);
    } else {
        /* |(256 - b) X_l + b X_(l+1)| <= 256 2^35 = 2^43. */
        for (uint32_t k = 0; k < m.channels; k++) {
            const int64_t lower = level_read(asset, m, level, k, values[k]);
            const int64_t upper = blend == 0 ? 0 : level_read(asset, m, level + 1u, k, values[k]);
            v[k] = dsn_round_saturate(
                static_cast<int64_t>(256u - blend) * lower + static_cast<int64_t>(blend) * upper, m.d + 8u);
        }
    }
    /* |centre 2^16| <= 2^47 and |P v| < 2^31 2^19: the sum stays below 2^52 and out_c below 2^28 (format.h),
       so dsn_round_saturate's int32 saturation never acts here, nor for v_k: each is one rounding half up. */
    const int32_t *p = asset->histogram_rotation;
    for (uint32_t c = 0; c < m.channels; c++) {
        const int64_t sum = static_cast<int64_t>(asset->histogram_centre[c]) * 65536 + p[3 * c] * v[0] +
                            p[3 * c + 1] * v[1] + p[3 * c + 2] * v[2]; /* v[1], v[2] are 0 for grey */
        values[c] = dsn_round_saturate(sum, 24);
    }
}

#if DSN_GRADIENTS
namespace {

/* The slope of level `level`'s table of channel k at g: X per unit of g (X as table_read's), the segment
   that holds g (its upper one at an entry), 0 where the read is clamped and at levels past the tables
   (the constant `expected`). |slope| <= 65535 16 < 2^20. */
inline int64_t table_slope(const mapping &m, uint32_t level, uint32_t k, int32_t g) {
    const int64_t u = static_cast<int64_t>(g) - m.low;
    if (level >= m.levels || u < 0 || u >= m.top) return 0;
    const uint32_t i = static_cast<uint32_t>(u) >> m.d; /* u < (N - 1) 2^d: i + 1 < N */
    const unsigned char *row = m.table + 2u * ((level * m.channels + k) * m.entries);
    return (static_cast<int64_t>(dsn_read_i16le(row + 2u * (i + 1u))) - dsn_read_i16le(row + 2u * i)) * 16;
}

/* v_k' = slope_k d_k / 2^(d + 8) rounded (slope_k blended, 256 times a table's), saturated to +-2^29 so
   that the rotation's sum stays below 2^63 (|P| < 2^31), then out_c' = sum_k P[c][k] v_k' / 2^24
   rounded. */
void map_derivative(const dsn_asset *asset, const mapping &m, const int64_t *slopes, int32_t *derivative) {
    const int64_t limit = int64_t(1) << 29;
    int64_t v[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t k = 0; k < m.channels; k++) {
        const int64_t scaled = dsn_round_saturate(slopes[k] * derivative[k], m.d + 8u); /* |product| < 2^59 */
        v[k] = scaled > limit ? limit : scaled < -limit ? -limit : scaled;
    }
    const int32_t *p = asset->histogram_rotation;
    for (uint32_t c = 0; c < m.channels; c++)
        derivative[c] = dsn_round_saturate(p[3 * c] * v[0] + p[3 * c + 1] * v[1] + p[3 * c + 2] * v[2], 24);
}

} // namespace

void dsn_internal_histogram_map_gradient(const dsn_asset *asset, const int32_t *values, uint32_t level,
                                         uint32_t blend, int32_t *dx, int32_t *dy) {
    const mapping m = mapping_of(asset);
    int64_t slopes[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t k = 0; k < m.channels; k++)
        slopes[k] = static_cast<int64_t>(256u - blend) * table_slope(m, level, k, values[k]) +
                    (blend == 0 ? 0 : static_cast<int64_t>(blend) * table_slope(m, level + 1u, k, values[k]));
    map_derivative(asset, m, slopes, dx);
    map_derivative(asset, m, slopes, dy);
}
#endif

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
