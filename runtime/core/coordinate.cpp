/* runtime/core/coordinate.cpp - IEEE-754 float and double coordinates to the continuous mode's Q32.32, from
   the bits with integer operations only, so that every platform (float unit or not) gets the same
   point. */
#include "core/continuous_internal.h"
#include "core/float_bits.h"
#include "setup/noise_state.h"

namespace {

/* sign * mantissa * 2^exponent (an IEEE value) * 2^32, rounded toward minus infinity, modulo 2^64. */
int64_t coordinate_from_parts(bool negative, uint64_t mantissa, int32_t exponent) {
    const int32_t shift = exponent + 32;
    uint64_t magnitude = 0; /* shift >= 64: a multiple of 2^64, the point 0 of the torus */
    bool inexact = false;
    if (shift >= 0 && shift < 64) {
        magnitude = mantissa << shift;
    } else if (shift < 0) {
        /* mantissa < 2^53: a right shift by 63 drops every bit, as any larger one would. */
        const uint32_t right = shift > -63 ? static_cast<uint32_t>(-shift) : 63u;
        magnitude = mantissa >> right;
        inexact = (mantissa & ((static_cast<uint64_t>(1) << right) - 1u)) != 0;
    }
    /* Toward minus infinity: a negative value with dropped bits moves one unit further down. */
    return signed_from_bits(negative ? 0u - magnitude - (inexact ? 1u : 0u) : magnitude);
}

} // namespace

extern "C" {

int64_t dsn_coordinate_from_double(double value) {
    const uint64_t bits = bits_of<uint64_t>(value);
    const uint32_t exponent = static_cast<uint32_t>(bits >> 52) & 0x7FFu;
    const uint64_t fraction = bits & 0xFFFFFFFFFFFFFu;
    if (exponent == 0x7FFu) return 0; /* NaN, +-Inf */
    const uint64_t mantissa = exponent == 0 ? fraction : (fraction | (static_cast<uint64_t>(1) << 52));
    const int32_t power = (exponent == 0 ? 1 : static_cast<int32_t>(exponent)) - 1075;
    return coordinate_from_parts((bits >> 63) != 0, mantissa, power);
}

int64_t dsn_coordinate_from_float(float value) {
    const uint32_t bits = bits_of<uint32_t>(value);
    const uint32_t exponent = (bits >> 23) & 0xFFu;
    const uint32_t fraction = bits & 0x7FFFFFu;
    if (exponent == 0xFFu) return 0; /* NaN, +-Inf */
    const uint32_t mantissa = exponent == 0 ? fraction : (fraction | (1u << 23));
    const int32_t power = (exponent == 0 ? 1 : static_cast<int32_t>(exponent)) - 150;
    return coordinate_from_parts((bits >> 31) != 0, mantissa, power);
}

} // extern "C"
