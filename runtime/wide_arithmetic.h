/* runtime/wide_arithmetic.h - 64 x 64 -> 128-bit products and a rounded 128 / 64 division, built from
   32-bit halves so that they need no compiler extension (__int128 is missing on 32-bit targets). Used
   only at configuration time. Internal to libdsn. */
#ifndef DSN_WIDE_ARITHMETIC_H
#define DSN_WIDE_ARITHMETIC_H

#include <stdint.h>

typedef struct dsn_u128 {
    uint64_t high, low;
} dsn_u128;

static inline dsn_u128 dsn_multiply_wide(uint64_t a, uint64_t b) {
    uint64_t a_low = a & 0xFFFFFFFFu, a_high = a >> 32, b_low = b & 0xFFFFFFFFu, b_high = b >> 32;
    uint64_t low_low = a_low * b_low, low_high = a_low * b_high, high_low = a_high * b_low;
    uint64_t middle = (low_low >> 32) + (low_high & 0xFFFFFFFFu) + (high_low & 0xFFFFFFFFu);
    dsn_u128 product;
    product.low = (middle << 32) | (low_low & 0xFFFFFFFFu);
    product.high = a_high * b_high + (low_high >> 32) + (high_low >> 32) + (middle >> 32);
    return product;
}

/* round(numerator / divisor), halves rounded up; UINT64_MAX when the quotient does not fit (or the
   divisor is 0). Restoring division, one bit per step. */
static inline uint64_t dsn_divide_wide_rounded(dsn_u128 numerator, uint64_t divisor) {
    uint64_t remainder = numerator.high, quotient = 0, low = numerator.low;
    int bit;
    if (divisor == 0 || remainder >= divisor) return UINT64_MAX;
    for (bit = 0; bit < 64; bit++) {
        uint64_t carry = remainder >> 63;
        remainder = (remainder << 1) | (low >> 63);
        low <<= 1;
        quotient <<= 1;
        if (carry || remainder >= divisor) {
            remainder -= divisor;
            quotient |= 1u;
        }
    }
    if (remainder >= divisor - remainder) {
        if (quotient == UINT64_MAX) return UINT64_MAX;
        quotient++;
    }
    return quotient;
}

/* round(a * b / divisor) with a 128-bit intermediate, saturated to UINT64_MAX. */
static inline uint64_t dsn_multiply_divide(uint64_t a, uint64_t b, uint64_t divisor) {
    return dsn_divide_wide_rounded(dsn_multiply_wide(a, b), divisor);
}

#endif /* DSN_WIDE_ARITHMETIC_H */
