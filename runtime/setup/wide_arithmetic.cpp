/* runtime/setup/wide_arithmetic.cpp - the 64-bit divisions of wide_arithmetic.h: a 64 x 64 -> 128-bit product
   from 32-bit halves and a restoring division, one quotient bit per step (the configuration code runs
   them a few hundred times per dsn_noise_init: microseconds; a surface frame from floats a few times per
   point, so dsn_divide takes the CPU's own division where it has one for 64 bits). */
#include "setup/wide_arithmetic.h"

namespace {

typedef struct u128 {
    uint64_t high, low;
} u128;

u128 multiply_wide(uint64_t a, uint64_t b) {
    const uint64_t a_low = a & 0xFFFFFFFFu, a_high = a >> 32, b_low = b & 0xFFFFFFFFu, b_high = b >> 32;
    const uint64_t low_low = a_low * b_low, low_high = a_low * b_high, high_low = a_high * b_low;
    const uint64_t middle = (low_low >> 32) + (low_high & 0xFFFFFFFFu) + (high_low & 0xFFFFFFFFu);
    u128 product;
    product.low = (middle << 32) | (low_low & 0xFFFFFFFFu);
    product.high = a_high * b_high + (low_high >> 32) + (high_low >> 32) + (middle >> 32);
    return product;
}

/* floor(numerator / divisor) and the remainder, for numerator.high < divisor (the quotient fits 64
   bits). A divisor of 0 gives UINT64_MAX. */
uint64_t divide_wide(u128 numerator, uint64_t divisor, uint64_t *remainder) {
    uint64_t rest = numerator.high, quotient = 0, low = numerator.low;
    for (int bit = 0; bit < 64; bit++) {
        const uint64_t carry = rest >> 63;
        rest = (rest << 1) | (low >> 63);
        low <<= 1;
        quotient <<= 1;
        if (carry || rest >= divisor) {
            rest -= divisor;
            quotient |= 1u;
        }
    }
    *remainder = rest;
    return quotient;
}

} // namespace

uint64_t dsn_divide(uint64_t numerator, uint64_t divisor) {
#if defined(__x86_64__) || defined(__aarch64__)
    /* One instruction there (no helper call); the same quotient, and UINT64_MAX for 0 as below. */
    return divisor == 0 ? UINT64_MAX : numerator / divisor;
#else
    const u128 wide = {0, numerator};
    uint64_t remainder;
    return divide_wide(wide, divisor, &remainder);
#endif
}

uint64_t dsn_multiply_divide(uint64_t a, uint64_t b, uint64_t divisor) {
    const u128 product = multiply_wide(a, b);
    uint64_t remainder;
    if (divisor == 0 || product.high >= divisor) return UINT64_MAX;
    const uint64_t quotient = divide_wide(product, divisor, &remainder);
    if (remainder < divisor - remainder) return quotient;
    return quotient == UINT64_MAX ? UINT64_MAX : quotient + 1u;
}
