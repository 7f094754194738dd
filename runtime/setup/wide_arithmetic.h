/* runtime/setup/wide_arithmetic.h - 64-bit arithmetic for the configuration code: a rounded a * b / d with a
   128-bit intermediate, a plain quotient and an integer square root. Built from shifts and 32-bit halves
   (no __int128, missing on 32-bit targets, and no compiler division helper such as __aeabi_uldivmod), the
   divisions out of line in wide_arithmetic.cpp so that every user shares one copy. Used at configuration
   time, and by the surface frame's construction (once per frame, not per impulse). Internal to libdsn. */
#ifndef DSN_WIDE_ARITHMETIC_H
#define DSN_WIDE_ARITHMETIC_H

#include <stdint.h>

/* floor(numerator / divisor); UINT64_MAX when the divisor is 0. */
uint64_t dsn_divide(uint64_t numerator, uint64_t divisor);

/* round(a * b / divisor), halves rounded up; UINT64_MAX when the quotient does not fit (or the divisor
   is 0). */
uint64_t dsn_multiply_divide(uint64_t a, uint64_t b, uint64_t divisor);

/* floor(sqrt(value)), one result bit per step. Inline, unlike the divisions: the small build's one caller
   (normalize.cpp) keeps it inside its own code, which its 8 KB budget needs. */
inline uint64_t dsn_integer_sqrt(uint64_t value) {
    uint64_t root = 0, bit = uint64_t(1) << 62;
    while (bit > value) bit >>= 2;
    while (bit != 0) {
        if (value >= root + bit) {
            value -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return root;
}

#endif /* DSN_WIDE_ARITHMETIC_H */
