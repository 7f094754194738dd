/* runtime/core/output_conversion.cpp - the public output conversions of dsn.h: a Q16.16 channel value to
   float and to 8 bits, which every evaluator's float and u8 outputs (and normalize_fixed.h) go through. */
#include "dsn/dsn.h"

extern "C" float dsn_fixed_to_float(int32_t value) {
    /* One rounding (int32 -> float), then an exact power-of-two scaling: the same on every FPU. */
    return float(value) * (1.0f / 65536.0f);
}

extern "C" uint8_t dsn_fixed_to_u8(int32_t value) {
    if (value <= 0) return 0;
    if (value >= DSN_ONE) return 255;
    return uint8_t((uint32_t(value) * 255u + 32768u) >> 16);
}
