/* runtime/setup/wide_arithmetic.h - 64-bit arithmetic for the configuration code: a rounded a * b / d with a
   128-bit intermediate, a plain quotient and an integer square root. Built from shifts and 32-bit halves
   (no __int128, missing on 32-bit targets, and no compiler division helper such as __aeabi_uldivmod), out
   of line in wide_arithmetic.cpp so that every user shares one copy. Used at configuration time, and by
   the surface frame's construction (once per frame, not per impulse). Internal to libdsn. */
#ifndef DSN_WIDE_ARITHMETIC_H
#define DSN_WIDE_ARITHMETIC_H

#include <stdint.h>

/* floor(numerator / divisor); UINT64_MAX when the divisor is 0. */
uint64_t dsn_divide(uint64_t numerator, uint64_t divisor);

/* round(a * b / divisor), halves rounded up; UINT64_MAX when the quotient does not fit (or the divisor
   is 0). */
uint64_t dsn_multiply_divide(uint64_t a, uint64_t b, uint64_t divisor);

/* floor(sqrt(value)), one result bit per step. */
uint64_t dsn_integer_sqrt(uint64_t value);

#endif /* DSN_WIDE_ARITHMETIC_H */
