/* runtime/poisson_count.h - a cell's impulse count: exact Poisson draws from the table init builds
   (poisson_table.cpp), driven by the cell's key. Internal to libdsn; not installed. */
#ifndef DSN_POISSON_COUNT_H
#define DSN_POISSON_COUNT_H

#include <stdint.h>

#include "cell_hash.h"

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

#endif /* DSN_POISSON_COUNT_H */
