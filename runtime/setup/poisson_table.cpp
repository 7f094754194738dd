/* runtime/setup/poisson_table.cpp - the inverse-CDF table of the per-cell Poisson count, in integer
   arithmetic only (64-bit fixed point with 62 fraction bits), identical on every platform. */
#include "setup/init_internal.h"
#include "setup/wide_arithmetic.h"

namespace {

const uint64_t one_q62 = uint64_t(1) << 62;
const uint64_t inverse_e_q62 = 0x178B56362CEF37C7u; /* round(exp(-1) * 2^62) */

uint64_t multiply_q62(uint64_t a, uint64_t b) { return dsn_multiply_divide(a, b, one_q62); }

/* exp(-mean) for mean = mean_q32 / 2^32: exp(-1)^integer_part, times the fraction's exp(-f) computed as
   exp(-f/16)^16 with a series that converges by a factor 16 per term. */
uint64_t exp_negative_q62(uint64_t mean_q32) {
    uint64_t y = (mean_q32 & 0xFFFFFFFFu) << 26; /* f / 16 in Q62 */
    uint64_t term = one_q62, positive = one_q62, negative = 0;
    for (uint64_t k = 1; k <= 16; k++) {
        term = dsn_divide(multiply_q62(term, y), k);
        if (k % 2)
            negative += term;
        else
            positive += term;
    }
    uint64_t result = positive - negative;
    for (int square = 0; square < 4; square++) result = multiply_q62(result, result);
    for (uint64_t i = 0; i < (mean_q32 >> 32); i++) result = multiply_q62(result, inverse_e_q62);
    return result;
}

} // namespace

void dsn_internal_build_poisson_table(dsn_noise_state *noise, uint64_t cell_mean_q32) {
    const uint64_t part_max_q32 = uint64_t(DSN_POISSON_MEAN_MAX) << 32;
    uint64_t parts = (cell_mean_q32 + part_max_q32 - 1) / part_max_q32;
    uint64_t mean_q32 = dsn_divide(cell_mean_q32 + parts / 2, parts);
    noise->poisson_parts = uint32_t(parts);

    /* cdf[n] = round(2^32 P(count <= n)); stop at the first that rounds to 2^32 (the tail beyond it has
       probability below 2^-32 and is drawn as that count). */
    uint64_t probability = exp_negative_q62(mean_q32), cumulative = 0;
    uint32_t n = 0;
    const uint32_t capacity = sizeof noise->poisson_cdf / sizeof noise->poisson_cdf[0];
    for (; n < capacity; n++) {
        cumulative += probability;
        uint64_t threshold = (cumulative + (uint64_t(1) << 29)) >> 30;
        if (threshold > 0xFFFFFFFFu) break;
        noise->poisson_cdf[n] = uint32_t(threshold);
        probability = dsn_multiply_divide(probability, mean_q32, uint64_t(n + 1) << 32);
    }
    noise->poisson_size = n;
    for (uint32_t i = n; i < capacity; i++) noise->poisson_cdf[i] = 0xFFFFFFFFu;

    uint32_t candidate = 0;
    for (uint32_t bucket = 0; bucket < 64; bucket++) {
        while (candidate < n && noise->poisson_cdf[candidate] <= (bucket << 26)) candidate++;
        noise->poisson_guide[bucket] = uint8_t(candidate);
    }
}
