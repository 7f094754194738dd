/* runtime/setup/wide_arithmetic.h - 64-bit divisions for the configuration code: a rounded a * b / d with a
   128-bit intermediate, and a plain quotient. Built from shifts and 32-bit halves (no __int128, missing on
   32-bit targets, and no compiler division helper such as __aeabi_uldivmod), out of line in
   wide_arithmetic.cpp so that every user shares one copy. Used only at configuration time. Internal to
   libdsn. */
#ifndef DSN_WIDE_ARITHMETIC_H
#define DSN_WIDE_ARITHMETIC_H

#include <stdint.h>

/* floor(numerator / divisor); UINT64_MAX when the divisor is 0. */
uint64_t dsn_divide(uint64_t numerator, uint64_t divisor);

/* round(a * b / divisor), halves rounded up; UINT64_MAX when the quotient does not fit (or the divisor
   is 0). */
uint64_t dsn_multiply_divide(uint64_t a, uint64_t b, uint64_t divisor);

#endif /* DSN_WIDE_ARITHMETIC_H */
