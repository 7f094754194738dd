/* runtime/core/poisson_count.h - a cell's impulse count: exact Poisson draws from the table init builds
   (poisson_table.cpp), driven by the cell's key. Internal to libdsn; not installed. */
#ifndef DSN_POISSON_COUNT_H
#define DSN_POISSON_COUNT_H

#include <stdint.h>

#include "core/cell_hash.h"

/* Inverse CDF: the smallest n with uniform < poisson_cdf[n], or poisson_size when there is none (the
   tail beyond the table has probability below 2^-32). The guide gives the first candidate for the top
   6 bits of the uniform, so the search is one or two comparisons on average. */
DSN_SHARED uint32_t dsn_poisson_draw(const dsn_noise_state *noise, uint32_t uniform) {
    uint32_t n = noise->poisson_guide[uniform >> 26];
    while (n < noise->poisson_size && uniform >= noise->poisson_cdf[n]) n++;
    return n;
}

/* Impulse count of the cell with this key: the sum of poisson_parts independent draws (a sum of
   independent Poisson variables is Poisson; splitting keeps the table small for dense cells). The key
   itself is the first uniform: it is already a full-avalanche hash. */
DSN_SHARED uint32_t dsn_cell_impulse_count(const dsn_noise_state *noise, uint32_t key) {
    uint32_t count = dsn_poisson_draw(noise, key), part;
    for (part = 1; part < noise->poisson_parts; part++)
        count += dsn_poisson_draw(noise, dsn_cell_stream(key, part));
    return count;
}

/* dsn_poisson_draw (one draw on this path) with its first two steps of search taken without a branch:
   from the guide, 90% of the counts need no step, 8% one and 1.3% two at the usual mean of 8, so a
   branch on them would often be mispredicted. A step from n adds uniform >= cdf[n]:
   exact below the table size; at or past it (cdf = 2^32 - 1, undercut by no uniform but 2^32 - 1) it
   may overshoot, which the rare exact search behind catches, as it does counts that need more steps.
   The reads go at most to cdf[size + 1]: callers check that it is in the table
   (dsn_poisson_two_steps_fit). */
static inline uint32_t dsn_poisson_count_two_steps(const dsn_noise_state *noise, uint32_t uniform) {
    uint32_t n = noise->poisson_guide[uniform >> 26];
    n += static_cast<uint32_t>(uniform >= noise->poisson_cdf[n]);
    n += static_cast<uint32_t>(uniform >= noise->poisson_cdf[n]);
    if (n > noise->poisson_size || (n < noise->poisson_size && uniform >= noise->poisson_cdf[n]))
        n = dsn_poisson_draw(noise, uniform);
    return n;
}

/* Whether dsn_poisson_count_two_steps gives the cell counts of this noise: one draw per cell, and
   cdf[size + 1] in the table. */
static inline bool dsn_poisson_two_steps_fit(const dsn_noise_state *noise) {
    return noise->poisson_parts == 1 &&
           noise->poisson_size + 2 <= sizeof noise->poisson_cdf / sizeof noise->poisson_cdf[0];
}

#endif /* DSN_POISSON_COUNT_H */
