/* runtime/core/impulse_position.h - where impulse k of a cell lies: its lattice offset, unpacked from the
   cell's position pairs (cell_hash.h), and its 16-bit continuous position. Internal to libdsn; not
   installed.

   The lattice positions are packed so that one hash serves several impulses: with cells of side <= 16
   an impulse takes one byte of a pair (x in the low nibble, y in the high one), eight impulses per pair;
   with larger cells it takes 16 bits (x in the low byte, y in the high one), four per pair. Impulse k
   has field k % per_pair of pair k / per_pair, and its lattice offset in the cell is the top cell_shift
   bits of each half of the field (each half is uniform, so the offsets are exactly uniform and
   independent). The continuous mode appends the fraction hash's bits below the field's to make 16-bit
   positions (dsn_impulse_hash), so the lattice impulse is exactly the floor of its continuous twin. */
#ifndef DSN_IMPULSE_POSITION_H
#define DSN_IMPULSE_POSITION_H

#include <stdint.h>

#include "core/cell_hash.h"

/* log2 of the bits of one impulse's field: 3 (a byte) for cells of side <= 16, else 4 (16 bits). */
static inline uint32_t dsn_field_shift(uint32_t cell_shift) { return cell_shift <= 4 ? 3u : 4u; }

/* The pair that holds impulse k's field (k counts from 0). */
static inline uint64_t dsn_impulse_pair(const dsn_noise_state *noise, uint32_t key, uint32_t k) {
    return dsn_position_pair(key, k >> (6u - dsn_field_shift(noise->cell_shift)));
}

/* The low 32 bits of pair >> bit (bit < 64), choosing the half first: 32-bit targets then shift one
   word, not a pair of them. */
static inline uint32_t dsn_pair_bits(uint64_t pair, uint32_t bit) {
    return (bit >= 32u ? uint32_t(pair >> 32) : uint32_t(pair)) >> (bit & 31u);
}

/* The field of impulse k: x in the low half, y in the high half. */
DSN_SHARED uint32_t dsn_impulse_field(const dsn_noise_state *noise, uint32_t key, uint32_t k) {
    const uint32_t field_shift = dsn_field_shift(noise->cell_shift), per_pair_shift = 6u - field_shift;
    const uint32_t bit = (k & ((1u << per_pair_shift) - 1u)) << field_shift;
    return dsn_pair_bits(dsn_impulse_pair(noise, key, k), bit) & (0xFFFFFFFFu >> (32u - (1u << field_shift)));
}

/* 16-bit in-cell positions of impulse k for the continuous mode (units of 2^-(16 - cell_shift) lattice
   steps): x in the low 16 bits, y in the high 16. The top bits are the packed field's, the rest come
   from the impulse's own fraction hash. */
DSN_SHARED uint32_t dsn_impulse_hash(const dsn_noise_state *noise, uint32_t key, uint32_t k) {
    const uint32_t half_bits = 1u << (dsn_field_shift(noise->cell_shift) - 1u);
    const uint32_t field = dsn_impulse_field(noise, key, k);
    const uint32_t fraction = dsn_cell_stream(key, 0x80000000u + k);
    const uint32_t x =
        ((field & ((1u << half_bits) - 1u)) << (16u - half_bits)) | ((fraction & 0xFFFFu) >> half_bits);
    const uint32_t y = ((field >> half_bits) << (16u - half_bits)) | ((fraction >> 16) >> half_bits);
    return x | (y << 16);
}

/* 16-bit in-cell positions of an impulse (units of 2^-(16 - cell_shift) lattice steps). */
static inline uint32_t dsn_impulse_bits_x(uint32_t hash) { return hash & 0xFFFFu; }
static inline uint32_t dsn_impulse_bits_y(uint32_t hash) { return hash >> 16; }

/* Lattice offset of an impulse inside its cell: the top cell_shift bits of its 16-bit position. */
static inline uint32_t dsn_impulse_offset(uint32_t bits16, uint32_t cell_shift) {
    return bits16 >> (16u - cell_shift);
}

#endif /* DSN_IMPULSE_POSITION_H */
