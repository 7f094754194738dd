/* runtime/core/lattice_internal.h - what the lattice point walk (point.cpp) offers the other evaluators: the
   raw channel sums of one point. Internal to libdsn; not installed. */
#ifndef DSN_LATTICE_INTERNAL_H
#define DSN_LATTICE_INTERNAL_H

#include <stdint.h>

#include "setup/noise_state.h"

#if DSN_GRADIENTS && !DSN_SMALL_CODE
/* sums[channels]: the sums, modulo 2^32, of the lattice texton values of every impulse that reaches the
   lattice point (x, y) (coordinates as uint32 bit patterns), what dsn_lattice_point_fixed normalizes;
   through the per-point fast walk. The noise is configured and its lattice texton read. */
void dsn_internal_lattice_sums(const dsn_noise_state *noise, uint32_t x, uint32_t y, uint32_t *sums);
#endif

#endif /* DSN_LATTICE_INTERNAL_H */
