/* runtime/core/cell_hash.h - the stateless hashes from which every impulse comes: cell keys, a cell's random
   stream and its packed position pairs. Internal to libdsn; not installed.

   The impulse process. The plane is the 2^32 x 2^32 torus cut into square cells of side
   c = 2^cell_shift (a power of two divides 2^32, so cells tile the torus exactly and there are
   2^(32 - cell_shift) distinct cell indices per axis, none repeated). Cell (cx, cy) has a 32-bit key;
   from the key come its impulse count (exact Poisson, possibly the sum of several independent draws:
   poisson_count.h) and then the position of each impulse k (impulse_position.h), all by stateless
   hashing:

       key        = cell_key(noise, cx, cy)                          32 bits
       count      = poisson(key) + poisson(cell_stream(key, 1)) + ... (parts draws)
       pair p     = position_pair(key, p)                            64 bits: packed lattice positions
       fraction k = cell_stream(key, 2^31 + k)                       continuous mode only */
#ifndef DSN_CELL_HASH_H
#define DSN_CELL_HASH_H

#include <stdint.h>

#include "core/shared_inline.h"
#include "setup/noise_state.h"

/* lowbias32 (C. Wellons' hash prospector): a bijection of the 32-bit integers with a near-ideal
   avalanche. Being a bijection is what makes x -> cell_key(x, y) free of any period. */
DSN_SHARED uint32_t dsn_mix32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7FEB352Du;
    x ^= x >> 15;
    x *= 0x846CA68Bu;
    x ^= x >> 16;
    return x;
}

/* Key of cell (cx, cy). For a fixed row and seed, cx -> key is mix((cx ^ a) + b): a bijection, so no
   two cells of a row share a key. The seed enters twice (seed_column, seed_row, precomputed at init) so
   that two seeds are not simply shifted copies of each other. The row part is split out so that loops
   over a row of cells compute it once. */
static inline uint32_t dsn_row_key(const dsn_noise_state *noise, uint32_t cell_y) {
    return dsn_mix32(cell_y + noise->seed_row);
}

static inline uint32_t dsn_cell_key_in_row(const dsn_noise_state *noise, uint32_t cell_x, uint32_t row_key) {
    return dsn_mix32((cell_x ^ noise->seed_column) + row_key);
}

static inline uint32_t dsn_cell_key(const dsn_noise_state *noise, uint32_t cell_x, uint32_t cell_y) {
    return dsn_cell_key_in_row(noise, cell_x, dsn_row_key(noise, cell_y));
}

/* Value `index` of a cell's random stream: a Weyl step then the mixer. */
static inline uint32_t dsn_cell_stream(uint32_t key, uint32_t index) {
    return dsn_mix32(key + index * 0x9E3779B9u);
}

/* The hash from which impulse k of the cell with key `key` draws its material in a mix: value
   2^31 + 2^30 + k of the cell's stream. */
static inline uint32_t dsn_material_hash(uint32_t key, uint32_t k) {
    return dsn_cell_stream(key, 0xC0000000u + k);
}

/* The SplitMix64 finalizer (S. Vigna, after D. Stafford's Mix13): a bijection of the 64-bit integers. */
DSN_SHARED uint64_t dsn_mix64(uint64_t x) {
    x ^= x >> 30;
    x *= 0xBF58476D1CE4E5B9u;
    x ^= x >> 27;
    x *= 0x94D049BB133111EBu;
    x ^= x >> 31;
    return x;
}

/* Pair `index` of a cell's packed positions. (key, index) -> key 2^32 + index G is injective for
   index < 2^32 (G odd), so every cell and index gets its own input to the bijection. */
static inline uint64_t dsn_position_pair(uint32_t key, uint32_t index) {
    return dsn_mix64((uint64_t(key) << 32) + uint64_t(index) * 0x9E3779B97F4A7C15u);
}

#endif /* DSN_CELL_HASH_H */
