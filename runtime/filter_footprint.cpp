/* runtime/filter_footprint.cpp - from a pixel's footprint to how the filtered evaluation reads it: the
   level of detail (8 fraction bits) and the anisotropic taps, in integer arithmetic only (the same on
   every platform), for every int64 footprint; and the footprint from float derivatives. The rules are
   dsn.h's ("Filtered evaluation"). Compiled only with DSN_FILTERING. */
#include "continuous_internal.h"
#include "filtered_internal.h"

#if DSN_FILTERING

namespace {

/* Footprint components above this magnitude are clamped to it: 2^62 texels / 2^32 = 2^30 texels per
   pixel is far beyond the coarsest level, so the result (the mean colour) is the same. */
const uint64_t component_limit = static_cast<uint64_t>(1) << 62;

/* floor(log2(value)) * 2^16 + 16 fraction bits (truncated), for value >= 1: the integer part is the top
   bit's index, the fraction bits come one by one from squaring the mantissa (kept in [2^31, 2^32)). Two
   values at once, their chains of squarings overlapping. */
uint64_t log2_mantissa(uint64_t value, uint32_t *top) {
#if defined(__GNUC__)
    *top = 63u - static_cast<uint32_t>(__builtin_clzll(value));
#else
    *top = 63;
    while ((value >> *top) == 0) --*top;
#endif
    return *top >= 31 ? value >> (*top - 31u) : value << (31u - *top);
}

/* One fraction bit: the mantissa squared back into [2^31, 2^32), and whether the square passed 2^63
   (chosen without a branch: either way is as likely). */
uint32_t log2_step(uint64_t *mantissa) {
    const uint64_t square = *mantissa * *mantissa; /* below 2^64 */
    const uint32_t over = static_cast<uint32_t>(square >> 63);
    *mantissa = over != 0 ? square >> 32 : square >> 31;
    return over;
}

void log2_q16_pair(uint64_t first, uint64_t second, int32_t *log_first, int32_t *log_second) {
    uint32_t top_first, top_second;
    uint64_t mantissa_first = log2_mantissa(first, &top_first),
             mantissa_second = log2_mantissa(second, &top_second);
    uint32_t fraction_first = 0, fraction_second = 0;
    for (uint32_t bit = 0; bit < 16; bit++) {
        fraction_first = (fraction_first << 1) | log2_step(&mantissa_first);
        fraction_second = (fraction_second << 1) | log2_step(&mantissa_second);
    }
    *log_first = static_cast<int32_t>((top_first << 16) | fraction_first);
    *log_second = static_cast<int32_t>((top_second << 16) | fraction_second);
}

uint64_t magnitude_of(int64_t value) {
    const uint64_t bits = static_cast<uint64_t>(value);
    const uint64_t magnitude = value < 0 ? 0u - bits : bits;
    return magnitude > component_limit ? component_limit : magnitude;
}

/* The component's magnitude shifted right by `shift`, with its sign: below 2^31 in magnitude. */
int64_t scaled(int64_t value, uint32_t shift) {
    const int64_t magnitude = static_cast<int64_t>(magnitude_of(value) >> shift);
    return value < 0 ? -magnitude : magnitude;
}

/* floor(value / 2^shift), 0 <= shift <= 62, without shifting a negative number. */
int64_t floor_shift_signed(int64_t value, uint32_t shift) {
    const uint64_t bias = static_cast<uint64_t>(1) << 63;
    return signed_from_bits(((static_cast<uint64_t>(value) + bias) >> shift) - (bias >> shift));
}

/* floor(value * multiple / 2^shift) modulo 2^64 (|multiple| < 2^5, shift <= 5): value = high 2^shift +
   low, low in [0, 2^shift), so the product is high * multiple plus the floor of the small low * multiple
   / 2^shift, exactly. */
int64_t scaled_offset(int64_t value, int32_t multiple, uint32_t shift) {
    const int64_t high = floor_shift_signed(value, shift);
    const int64_t low = value - high * (static_cast<int64_t>(1) << shift);
    const uint64_t product =
        static_cast<uint64_t>(high) * static_cast<uint64_t>(static_cast<int64_t>(multiple));
    return signed_from_bits(product + static_cast<uint64_t>(floor_shift_signed(low * multiple, shift)));
}

/* floor((log2_q16(square) + 1) / 512) for square >= 1, log2_q16 being log2_q16_pair's: the level of
   detail in 1/256 levels of a footprint whose area is its major square (ceil(log2_q16 / 2) / 256,
   floored). Only the first 7 fraction bits and whether the 9 after them are all ones decide it, so the
   squarings stop at the first zero among those 9. */
int32_t isotropic_lod_q8(uint64_t square) {
    uint32_t top;
    uint64_t mantissa = log2_mantissa(square, &top);
    uint32_t high = 0;
    for (uint32_t bit = 0; bit < 7; bit++) high = (high << 1) | log2_step(&mantissa);
    uint32_t carry = 1;
    for (uint32_t bit = 0; bit < 9 && carry != 0; bit++) carry = log2_step(&mantissa);
    return static_cast<int32_t>((top << 7) + high + carry);
}

/* dsn_internal_filter_plan; isotropic_shortcut: whether isotropic footprints take isotropic_lod_q8. */
int filter_plan(const dsn_footprint *footprint, uint32_t levels, dsn_filter_plan *plan,
                bool isotropic_shortcut) {
    plan->lod_q8 = 0;
    plan->taps = 1;
    plan->offset_x[0] = plan->offset_y[0] = 0;
    if (footprint == 0) return DSN_ERR_NULL;
    const uint32_t max_taps = footprint->max_taps;
    if (max_taps == 0 || max_taps > DSN_FILTER_MAX_TAPS) return DSN_ERR_ARGUMENT;

    /* A common scale 2^(shift - 32) texels that brings every component below 2^31: squares and the
       determinant then fit in 64 bits. */
    const uint64_t largest = magnitude_of(footprint->column_step_x) | magnitude_of(footprint->column_step_y) |
                             magnitude_of(footprint->row_step_x) | magnitude_of(footprint->row_step_y);
    uint32_t shift = 0;
    while ((largest >> shift) >= (static_cast<uint64_t>(1) << 31)) shift++;
    const int64_t cx = scaled(footprint->column_step_x, shift), cy = scaled(footprint->column_step_y, shift);
    const int64_t rx = scaled(footprint->row_step_x, shift), ry = scaled(footprint->row_step_y, shift);
    const uint64_t column_square = static_cast<uint64_t>(cx * cx) + static_cast<uint64_t>(cy * cy);
    const uint64_t row_square = static_cast<uint64_t>(rx * rx) + static_cast<uint64_t>(ry * ry);
    const bool column_major = column_square >= row_square;
    const uint64_t major_square = column_major ? column_square : row_square;
    /* A footprint of at most one texel (zero included) needs no filter: the continuous mode's bits, even
       where rounding made a rotated square look slightly anisotropic. One texel is 2^(32 - shift) in the
       scaled units; with shift 0 every component is below half a texel. */
    if (shift == 0 || major_square <= (static_cast<uint64_t>(1) << (64u - 2u * shift))) return DSN_OK;
    const int64_t determinant = cx * ry - cy * rx; /* each product below 2^62 */
    const uint64_t area =
        determinant < 0 ? 0u - static_cast<uint64_t>(determinant) : static_cast<uint64_t>(determinant);
    const int32_t lod_limit = static_cast<int32_t>((levels + 1u) << 8);

    /* An isotropic footprint (a rotated square: its area is its major square): one tap at the point, the
       level of detail log2(area) / 2 (below, the general rule's: its minor part ceil(L / 2) is the
       larger). */
    if (isotropic_shortcut && area == major_square) {
        const int32_t lod_q8 = isotropic_lod_q8(area) + (static_cast<int32_t>(shift) - 32) * 256;
        plan->lod_q8 = lod_q8 < 0 ? 0 : lod_q8 > lod_limit ? lod_limit : lod_q8;
        return DSN_OK;
    }

    /* Taps: the smallest 2^k with 2^k area >= major^2 (= Pmax / Pmin >= ... exactly), capped. */
    uint32_t most = 0;
    while ((2u << most) <= max_taps) most++;
    uint32_t tap_shift = 0;
    while (tap_shift < most) {
        const uint64_t needed =
            (major_square >> tap_shift) +
            ((major_square & ((static_cast<uint64_t>(1) << tap_shift) - 1u)) != 0 ? 1u : 0u);
        if (area >= needed) break;
        tap_shift++;
    }

    /* LOD = log2(max(Pmax / N, Pmin)), Pmin = area / Pmax, in the scaled units, then back to texels. */
    int32_t log_major_square, log_area;
    log2_q16_pair(major_square, area != 0 ? area : 1u, &log_major_square, &log_area);
    const int32_t log_major = log_major_square / 2;
    int32_t lod_q16 = log_major - static_cast<int32_t>(tap_shift << 16);
    if (area != 0) {
        const int32_t log_minor = log_area - log_major;
        if (log_minor > lod_q16) lod_q16 = log_minor;
    }
    lod_q16 += (static_cast<int32_t>(shift) - 32) * 65536;
    const int32_t lod_q8 = static_cast<int32_t>(floor_shift_signed(lod_q16, 8));
    plan->lod_q8 = lod_q8 < 0 ? 0 : lod_q8 > lod_limit ? lod_limit : lod_q8;

    /* Tap k at ((2k + 1 - N) / (2N)) along the major step vector (its exact components, modulo 2^64). */
    const uint32_t taps = 1u << tap_shift;
    plan->taps = taps;
    const int64_t major_x = column_major ? footprint->column_step_x : footprint->row_step_x;
    const int64_t major_y = column_major ? footprint->column_step_y : footprint->row_step_y;
    for (uint32_t k = 0; k < taps; k++) {
        const int32_t multiple = static_cast<int32_t>(2u * k + 1u) - static_cast<int32_t>(taps);
        plan->offset_x[k] = scaled_offset(major_x, multiple, tap_shift + 1u);
        plan->offset_y[k] = scaled_offset(major_y, multiple, tap_shift + 1u);
    }
    return DSN_OK;
}

} // namespace

int dsn_internal_filter_plan(const dsn_footprint *footprint, uint32_t levels, dsn_filter_plan *plan) {
    return filter_plan(footprint, levels, plan, true);
}

int dsn_internal_filter_plan_general(const dsn_footprint *footprint, uint32_t levels, dsn_filter_plan *plan) {
    return filter_plan(footprint, levels, plan, false);
}

namespace {

/* A double's bits as Q32.32, rounded toward minus infinity and saturated to the int64 range; false for
   NaN and infinities. Integer operations only, as dsn_coordinate_from_double. */
bool step_from_double(double value, int64_t *out) {
    uint64_t bits = 0;
    const unsigned char *from = reinterpret_cast<const unsigned char *>(&value);
    unsigned char *to = reinterpret_cast<unsigned char *>(&bits);
    for (unsigned i = 0; i < sizeof value; i++) to[i] = from[i];
    const uint32_t exponent = static_cast<uint32_t>(bits >> 52) & 0x7FFu;
    if (exponent == 0x7FFu) return false;
    const uint64_t fraction = bits & 0xFFFFFFFFFFFFFu;
    const uint64_t mantissa = exponent == 0 ? fraction : (fraction | (static_cast<uint64_t>(1) << 52));
    const int32_t shift = (exponent == 0 ? 1 : static_cast<int32_t>(exponent)) - 1075 + 32;
    const uint64_t largest = (static_cast<uint64_t>(1) << 63) - 1u;
    uint64_t magnitude = 0;
    bool inexact = false;
    if (shift >= 0) {
        magnitude = shift >= 11 || mantissa > (largest >> shift) ? largest : mantissa << shift;
    } else {
        const uint32_t right = shift > -63 ? static_cast<uint32_t>(-shift) : 63u;
        magnitude = mantissa >> right;
        inexact = (mantissa & ((static_cast<uint64_t>(1) << right) - 1u)) != 0;
    }
    const bool negative = (bits >> 63) != 0;
    *out = negative ? -static_cast<int64_t>(magnitude) - (inexact ? 1 : 0) : static_cast<int64_t>(magnitude);
    return true;
}

} // namespace

extern "C" {

int dsn_footprint_from_float(dsn_footprint *footprint, double dx_dpx, double dy_dpx, double dx_dpy,
                             double dy_dpy, uint32_t max_taps) {
    if (footprint == 0) return DSN_ERR_NULL;
    const bool finite = step_from_double(dx_dpx, &footprint->column_step_x) &&
                        step_from_double(dy_dpx, &footprint->column_step_y) &&
                        step_from_double(dx_dpy, &footprint->row_step_x) &&
                        step_from_double(dy_dpy, &footprint->row_step_y);
    footprint->max_taps = max_taps;
    if (finite && max_taps != 0 && max_taps <= DSN_FILTER_MAX_TAPS) return DSN_OK;
    footprint->column_step_x = footprint->column_step_y = footprint->row_step_x = footprint->row_step_y = 0;
    footprint->max_taps = 0;
    return DSN_ERR_ARGUMENT;
}

int dsn_filter_level(const dsn_noise *handle, const dsn_footprint *footprint, int32_t *lod_q8,
                     uint32_t *taps) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (lod_q8 != 0) *lod_q8 = 0;
    if (taps != 0) *taps = 0;
    if (noise == 0 || noise->asset.texton == 0 || lod_q8 == 0 || taps == 0) return DSN_ERR_NULL;
    dsn_filter_plan plan;
    const int err = dsn_internal_filter_plan(footprint, noise->asset.pyramid_levels, &plan);
    if (err != DSN_OK) return err;
    *lod_q8 = plan.lod_q8;
    *taps = plan.taps;
    return DSN_OK;
}

} // extern "C"

#endif /* DSN_FILTERING */
