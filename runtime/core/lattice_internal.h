/* runtime/core/lattice_internal.h - what the lattice point walk (point.cpp) offers the other evaluators: the
   raw channel sums of a point and its neighbours. Internal to libdsn; not installed. */
#ifndef DSN_LATTICE_INTERNAL_H
#define DSN_LATTICE_INTERNAL_H

#include <stdint.h>

#include "setup/noise_state.h"

#if DSN_GRADIENTS && !DSN_SMALL_CODE
/* sums[3 p + c]: the sums, modulo 2^32, of the lattice texton values of every impulse that reaches the
   lattice point p: (x, y), (x + 1, y) and (x, y + 1) (coordinates as uint32 bit patterns, + 1 modulo
   2^32), what dsn_lattice_point_fixed normalizes; through the per-point fast walk, one walk for the three
   where it takes the noise. The noise is configured and its lattice texton read. */
void dsn_internal_lattice_neighbour_sums(const dsn_noise_state *noise, uint32_t x, uint32_t y,
                                         uint32_t *sums);
#endif

#endif /* DSN_LATTICE_INTERNAL_H */
