/* runtime/core/filter_footprint.cpp - from a pixel's footprint to how the filtered evaluation reads it: the
   level of detail (8 fraction bits) and the anisotropic taps, in integer arithmetic only (the same on
   every platform), for every int64 footprint; and the footprint from float derivatives. The rules are
   dsn.h's ("Filtered evaluation"). Compiled only with DSN_FILTERING. */
#include "core/continuous_internal.h"
#include "core/filtered_internal.h"

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

/* floor(value * multiple / 2^shift) modulo 2^64 (|multiple| < 2^5, shift <= 5): value = high 2^shift +
   low, low in [0, 2^shift), so the product is high * multiple plus the floor of the small low * multiple
   / 2^shift, exactly. */
int64_t scaled_offset(int64_t value, int32_t multiple, uint32_t shift) {
    const int64_t high = floor_shift(value, shift);
    const int64_t low = value - high * (static_cast<int64_t>(1) << shift);
    const uint64_t product =
        static_cast<uint64_t>(high) * static_cast<uint64_t>(static_cast<int64_t>(multiple));
    return signed_from_bits(product + static_cast<uint64_t>(floor_shift(low * multiple, shift)));
}

/* floor((log2_q16(square) + 1) / 512) for square >= 1, log2_q16 being log2_q16_pair's: the level of
   detail in 1/256 levels of a footprint whose area is its major square (ceil(log2_q16 / 2) / 256,
   floored). Only the first 7 fraction bits and whether the 9 after them are all ones decide it, a
   function of the 32-bit mantissa m in [2^31, 2^32) that never decreases as m grows and steps by one at
   most once within each of the 256 ranges of m's top 9 bits (the steps lie 2^(1/128) apart, more than
   such a range): lod_step_below[b] + (m >= lod_step_at[b]) for b = (m >> 23) - 256. The tables hold the
   squarings' results (16 fraction bits, the carry's squarings stopping at the first zero), checked
   against them for every m. */
const uint8_t lod_step_below[256] = {
    0,   0,   1,   2,   2,   3,   4,   4,   5,   6,   7,   7,   8,   9,   9,   10,  11,  11,  12,  13,
    13,  14,  15,  15,  16,  17,  17,  18,  19,  19,  20,  21,  21,  22,  23,  23,  24,  24,  25,  26,
    26,  27,  28,  28,  29,  29,  30,  31,  31,  32,  32,  33,  34,  34,  35,  35,  36,  37,  37,  38,
    38,  39,  40,  40,  41,  41,  42,  42,  43,  44,  44,  45,  45,  46,  46,  47,  48,  48,  49,  49,
    50,  50,  51,  51,  52,  52,  53,  54,  54,  55,  55,  56,  56,  57,  57,  58,  58,  59,  59,  60,
    60,  61,  61,  62,  62,  63,  63,  64,  64,  65,  66,  66,  67,  67,  68,  68,  69,  69,  70,  70,
    70,  71,  71,  72,  72,  73,  73,  74,  74,  75,  75,  76,  76,  77,  77,  78,  78,  79,  79,  80,
    80,  81,  81,  81,  82,  82,  83,  83,  84,  84,  85,  85,  86,  86,  86,  87,  87,  88,  88,  89,
    89,  90,  90,  90,  91,  91,  92,  92,  93,  93,  94,  94,  94,  95,  95,  96,  96,  97,  97,  97,
    98,  98,  99,  99,  100, 100, 100, 101, 101, 102, 102, 102, 103, 103, 104, 104, 104, 105, 105, 106,
    106, 107, 107, 107, 108, 108, 109, 109, 109, 110, 110, 111, 111, 111, 112, 112, 112, 113, 113, 114,
    114, 114, 115, 115, 116, 116, 116, 117, 117, 117, 118, 118, 119, 119, 119, 120, 120, 121, 121, 121,
    122, 122, 122, 123, 123, 123, 124, 124, 125, 125, 125, 126, 126, 126, 127, 127};
const uint32_t lod_step_at[256] = {
    0xFFFFFFFFu, 0x80B1941Cu, 0x81647844u, 0xFFFFFFFFu, 0x82185518u, 0x82CD2BEFu, 0xFFFFFFFFu, 0x8382FE27u,
    0x8439CD1Eu, 0x84F19A31u, 0xFFFFFFFFu, 0x85AA66C2u, 0x86643435u, 0xFFFFFFFFu, 0x871F03EFu, 0x87DAD756u,
    0xFFFFFFFFu, 0x8897AFD3u, 0x89558ED3u, 0xFFFFFFFFu, 0x8A1475C0u, 0x8AD4660Bu, 0xFFFFFFFFu, 0x8B956124u,
    0x8C57687Eu, 0xFFFFFFFFu, 0x8D1A7D8Eu, 0x8DDEA1CBu, 0xFFFFFFFFu, 0x8EA3D6ADu, 0x8F6A1DB0u, 0xFFFFFFFFu,
    0x90317852u, 0x90F9E80Fu, 0xFFFFFFFFu, 0x91C36E6Bu, 0xFFFFFFFFu, 0x928E0CE9u, 0x9359C50Du, 0xFFFFFFFFu,
    0x94269860u, 0x94F4886Au, 0xFFFFFFFFu, 0x95C396B8u, 0xFFFFFFFFu, 0x9693C4D9u, 0x9765145Au, 0xFFFFFFFFu,
    0x983786D0u, 0xFFFFFFFFu, 0x990B1DCEu, 0x99DFDAEBu, 0xFFFFFFFFu, 0x9AB5BFC1u, 0xFFFFFFFFu, 0x9B8CCDE9u,
    0x9C650701u, 0xFFFFFFFFu, 0x9D3E6CAAu, 0xFFFFFFFFu, 0x9E190084u, 0x9EF4C433u, 0xFFFFFFFFu, 0x9FD1B95Fu,
    0xFFFFFFFFu, 0xA0AFE1AFu, 0xFFFFFFFFu, 0xA18F3ECFu, 0xA26FD26Cu, 0xFFFFFFFFu, 0xA3519E36u, 0xFFFFFFFFu,
    0xA434A3DDu, 0xFFFFFFFFu, 0xA518E518u, 0xA5FE639Bu, 0xFFFFFFFFu, 0xA6E52122u, 0xFFFFFFFFu, 0xA7CD1F66u,
    0xFFFFFFFFu, 0xA8B66026u, 0xFFFFFFFFu, 0xA9A0E522u, 0xFFFFFFFFu, 0xAA8CB01Cu, 0xAB79C2DBu, 0xFFFFFFFFu,
    0xAC681F25u, 0xFFFFFFFFu, 0xAD57C6C4u, 0xFFFFFFFFu, 0xAE48BB86u, 0xFFFFFFFFu, 0xAF3AFF38u, 0xFFFFFFFFu,
    0xB02E93AEu, 0xFFFFFFFFu, 0xB1237ABAu, 0xFFFFFFFFu, 0xB219B634u, 0xFFFFFFFFu, 0xB31147F5u, 0xFFFFFFFFu,
    0xB40A31D8u, 0xFFFFFFFFu, 0xB50475BCu, 0xFFFFFFFFu, 0xB6001582u, 0xB6FD130Du, 0xFFFFFFFFu, 0xB7FB7045u,
    0xFFFFFFFFu, 0xB8FB2F10u, 0xFFFFFFFFu, 0xB9FC515Cu, 0xFFFFFFFFu, 0xBAFED915u, 0xFFFFFFFFu, 0xFFFFFFFFu,
    0xBC02C82Eu, 0xFFFFFFFFu, 0xBD08209Au, 0xFFFFFFFFu, 0xBE0EE44Du, 0xFFFFFFFFu, 0xBF171543u, 0xFFFFFFFFu,
    0xC020B577u, 0xFFFFFFFFu, 0xC12BC6E6u, 0xFFFFFFFFu, 0xC2384B93u, 0xFFFFFFFFu, 0xC3464580u, 0xFFFFFFFFu,
    0xC455B6B6u, 0xFFFFFFFFu, 0xC566A13Eu, 0xFFFFFFFFu, 0xC6790725u, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xC78CEA78u,
    0xFFFFFFFFu, 0xC8A24D4Cu, 0xFFFFFFFFu, 0xC9B931B5u, 0xFFFFFFFFu, 0xCAD199CAu, 0xFFFFFFFFu, 0xCBEB87A7u,
    0xFFFFFFFFu, 0xFFFFFFFFu, 0xCD06FD6Au, 0xFFFFFFFFu, 0xCE23FD33u, 0xFFFFFFFFu, 0xCF428927u, 0xFFFFFFFFu,
    0xD062A36Bu, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xD1844E29u, 0xFFFFFFFFu, 0xD2A78B8Fu, 0xFFFFFFFFu, 0xD3CC5DCBu,
    0xFFFFFFFFu, 0xD4F2C712u, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xD61AC997u, 0xFFFFFFFFu, 0xD7446795u, 0xFFFFFFFFu,
    0xD86FA348u, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xD99C7EEDu, 0xFFFFFFFFu, 0xDACAFCC8u, 0xFFFFFFFFu, 0xDBFB1F1Eu,
    0xFFFFFFFFu, 0xFFFFFFFFu, 0xDD2CE837u, 0xFFFFFFFFu, 0xDE605A60u, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xDF9577E6u,
    0xFFFFFFFFu, 0xE0CC431Cu, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xE204BE57u, 0xFFFFFFFFu, 0xE33EEBF0u, 0xFFFFFFFFu,
    0xE47ACE43u, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xE5B867ADu, 0xFFFFFFFFu, 0xE6F7BA94u, 0xFFFFFFFFu, 0xFFFFFFFFu,
    0xE838C95Bu, 0xFFFFFFFFu, 0xE97B966Bu, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xEAC02431u, 0xFFFFFFFFu, 0xFFFFFFFFu,
    0xEC06751Eu, 0xFFFFFFFFu, 0xED4E8BA2u, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xEE986A37u, 0xFFFFFFFFu, 0xEFE41355u,
    0xFFFFFFFFu, 0xFFFFFFFFu, 0xF131897Au, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xF280CF26u, 0xFFFFFFFFu, 0xF3D1E6DEu,
    0xFFFFFFFFu, 0xFFFFFFFFu, 0xF524D32Au, 0xFFFFFFFFu, 0xF6799695u, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xF7D033AFu,
    0xFFFFFFFFu, 0xFFFFFFFFu, 0xF928AD08u, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xFA830538u, 0xFFFFFFFFu, 0xFBDF3ED8u,
    0xFFFFFFFFu, 0xFFFFFFFFu, 0xFD3D5C85u, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xFE9D60E1u, 0xFFFFFFFFu, 0xFFFF4E8Fu};

int32_t isotropic_lod_q8(uint64_t square) {
    uint32_t top;
    const uint32_t mantissa = static_cast<uint32_t>(log2_mantissa(square, &top));
    const uint32_t range = (mantissa >> 23) - 256u;
    return static_cast<int32_t>((top << 7) + lod_step_below[range] +
                                (mantissa >= lod_step_at[range] ? 1u : 0u));
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
#if defined(__GNUC__)
    if (largest >= (static_cast<uint64_t>(1) << 31))
        shift = 33u - static_cast<uint32_t>(__builtin_clzll(largest));
#else
    while ((largest >> shift) >= (static_cast<uint64_t>(1) << 31)) shift++;
#endif
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
    const int32_t lod_q8 = static_cast<int32_t>(floor_shift(lod_q16, 8));
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

int32_t dsn_internal_isotropic_lod_q8(uint64_t square) { return isotropic_lod_q8(square); }

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
    if (!dsn_configured(noise) || lod_q8 == 0 || taps == 0) return DSN_ERR_NULL;
    dsn_filter_plan plan;
    const int err = dsn_internal_filter_plan(footprint, noise->asset.pyramid_levels, &plan);
    if (err != DSN_OK) return err;
    *lod_q8 = plan.lod_q8;
    *taps = plan.taps;
    return DSN_OK;
}

} // extern "C"

#endif /* DSN_FILTERING */
