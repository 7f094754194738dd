/* runtime/kernels/lattice_point_walk.h - the lattice mode at one point, at its two neighbours for the
   gradient, and at a mix's point (each impulse adding its material's texton), on 128-bit vectors, as a
   kernel (kernels.h: each kernel file includes it, so it is built once per instruction set): the 16 x 16
   cells of a noise without a period, each cell's first 16 impulses tested at once. The same impulses and
   the same sums modulo 2^32 as point.cpp's and mix_point.cpp's walks, so the same bits. Internal to
   libdsn; not installed (everything here has internal linkage). */
#ifndef DSN_LATTICE_POINT_WALK_H
#define DSN_LATTICE_POINT_WALK_H

#include "core/lattice_impulses.h"
#include "core/poisson_count.h"
#include "kernels/kernels.h"
#include "kernels/mix_pick_lanes.h"

#if defined(__SSE2__) && !DSN_SMALL_CODE
#include "simd/simd_mix64.h"

namespace {

/* ---- 16 x 16 cells without a period (the usual case), 16 impulses per SSE2 vector ----
   Each cell's first 16 impulses are the 16 bytes of its first two pairs: all are tested at once, and
   the texton entries of all 16 lanes computed at once; the hits of several cells are then visited
   together, after they are all tested (see accumulate_cells16). Impulses beyond 16 (0.4% of cells at
   the usual mean of 8) go one by one. */

inline vector_128 broadcast(uint32_t pattern) {
    /* The bits go in unchanged (int conversion is modulo 2^32 on every x86 compiler). */
    return shuffle_32<0>(set_low_32(static_cast<int>(pattern)));
}

/* The in-cell offsets t of one axis that reach the point, 0 <= reach - t < size, tested on every lane's
   byte v as an unsigned range: low <= v <= low + span exactly when min(v - low, span) == v - low. reach is
   the texton index of offset 0; it lies in [0, size + 14] for a cell that reaches the point, so the range
   is never empty. The x test takes the x offsets (low nibbles), the y test whole fields, 16 y + x: y lies
   in [low, high] exactly when the field lies in [16 low, 16 high + 15] (at most 255: no wrap). */
typedef struct lane_range {
    vector_128 low, span;
} lane_range;

inline lane_range lane_range_of(uint32_t reach, uint32_t size, uint32_t unit, uint32_t below_unit) {
    const uint32_t low = reach >= size ? reach - size + 1u : 0u, high = reach < 15u ? reach : 15u;
    lane_range range = {broadcast(unit * low * 0x01010101u),
                        broadcast((unit * (high - low) + below_unit) * 0x01010101u)};
    return range;
}

inline lane_range x_range_of(uint32_t reach, uint32_t size) { return lane_range_of(reach, size, 1u, 0u); }
inline lane_range y_range_of(uint32_t reach, uint32_t size) { return lane_range_of(reach, size, 16u, 15u); }

/* dsn_position_pair(key, 0) and (key, 1), low and high lanes, for the key in the low 32 bits of `key`:
   dsn_mix64 on vectors, the same bits. */
inline vector_128 position_pairs(vector_128 key) {
    /* key 2^32 + index G, index 0 and 1 */
    return mix64_lanes(add_64(shuffle_32<0x11>(key), set_lanes_2x64(0, 0x9E3779B97F4A7C15u)));
}

/* Lanes k >= count as all-ones bytes (the impulses that do not exist): 16 bytes of absent_window from
   16 - min(count, 16). */
/* clang-format off */
const unsigned char absent_window[32] = {
    0,   0,   0,   0,   0,   0,   0,   0,   0,   0,   0,   0,   0,   0,   0,   0,
    255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255};
/* clang-format on */

inline vector_128 absent_impulses(uint32_t count) {
    const unsigned char *window = absent_window + 16 - (count < 16 ? count : 16u);
    return load_16x8(window);
}

/* Texton entries of 8 lanes whose fields (16 offset_y + offset_x) are in 16-bit lanes: corner -
   (offset_y width + offset_x) = corner - field - offset_y (width - 16), corner = reach_y width + reach_x.
   Exact in 16 bits for hits. */
inline vector_128 lane_entries(vector_128 fields, vector_128 corner, vector_128 widths_less_16) {
    return subtract_16(corner,
                       add_16(fields, multiply_16(shift_right_logical_16(fields, 4), widths_less_16)));
}

/* Hit masks of the cell's first 16 impulses (bit k for impulse k), for the point in masks[0] and, where
   the walk sums its neighbours too (Points 3), for the point right of it in masks[12] and the point below
   it in masks[24] (x[1] and y[1] their moved ranges; `live`, 0 or all ones per point, clears the masks of
   a point this cell cannot reach); and all 16 lanes' texton entries for the point (garbage for lanes that
   miss, never read; a neighbour's entry is the point's plus 1 or plus the width, modulo 2^16). */
template <uint32_t Points>
inline void cell_hits(vector_128 fields, vector_128 absent, const lane_range *x, const lane_range *y,
                      vector_128 corner, vector_128 widths_less_16, uint16_t *entries, uint16_t *masks,
                      const uint32_t *live) {
    const uint32_t ranges = Points == 1 ? 1u : 2u;
    const vector_128 offset_x = bitwise_and(fields, set_16x8(0x0F));
    vector_128 in_x[2], in_y[2];
    for (uint32_t r = 0; r < ranges; r++) {
        const vector_128 dx = subtract_8(offset_x, x[r].low), dy = subtract_8(fields, y[r].low);
        in_x[r] = equal_8(minimum_unsigned_8(dx, x[r].span), dx);
        in_y[r] = equal_8(minimum_unsigned_8(dy, y[r].span), dy);
    }
    const vector_128 zero = zero_128();
    store_8x16(entries, lane_entries(unpack_low_8(fields, zero), corner, widths_less_16));
    store_8x16(entries + 8, lane_entries(unpack_high_8(fields, zero), corner, widths_less_16));
    masks[0] = uint16_t(top_bits_of_bytes(and_not(absent, bitwise_and(in_x[0], in_y[0]))));
    if (Points == 3) {
        masks[0] = uint16_t(masks[0] & live[0]);
        masks[12] =
            uint16_t(uint32_t(top_bits_of_bytes(and_not(absent, bitwise_and(in_x[1], in_y[0])))) & live[1]);
        masks[24] =
            uint16_t(uint32_t(top_bits_of_bytes(and_not(absent, bitwise_and(in_x[0], in_y[1])))) & live[2]);
    }
}

/* The hits' texton values are summed while visiting them, then added to the channel sums (flush_hit_sums).
   Grey values go to a scalar sum through one sign-extending load each (x86 only: a little-endian
   two's-complement host, where the stored bytes read as signed char or int16 are the values; the
   conversions to uint32 are modulo 2^32). RGB values go to the low lanes of a vector, the scalar ALUs
   being the busier units on this path: one unaligned load of 4 bytes (8-bit values) or 8 (16-bit)
   reads 1 or 2 bytes past the entry, at most into the asset's 4-byte CRC, which the loader guarantees
   is in the buffer right after the texton (format.h: total_size). 8-bit values are summed in 16-bit
   lanes, which cannot overflow between two flushes (at most 9 x 16 hits, 144 x 127 < 2^15); 16-bit
   values in 32-bit lanes. */
typedef struct hit_sums {
    uint32_t grey;
    vector_128 rgb;
} hit_sums;

template <uint32_t Bits>
inline uint32_t grey_value(const unsigned char *entry) {
    if (Bits == 8) return uint32_t(*static_cast<const signed char *>(static_cast<const void *>(entry)));
    int16_t value;
    __builtin_memcpy(&value, entry, sizeof value);
    return uint32_t(value);
}

template <uint32_t Bits>
inline vector_128 rgb_values(const unsigned char *entry) {
    if (Bits == 8) {
        uint32_t bytes;
        __builtin_memcpy(&bytes, entry, sizeof bytes);
        const vector_128 values = set_low_32(static_cast<int>(bytes)); /* the bits unchanged */
#if defined(__AVX2__)
        return widen_signed_8_to_16(values);
#else
        return shift_right_arithmetic_16(unpack_low_8(values, values), 8);
#endif
    }
    const vector_128 values = load_low_8x8(entry);
    return shift_right_arithmetic_32(unpack_low_16(values, values), 16);
}

/* Adds the texton values at `entry` to the hit sums. */
template <uint32_t Channels, uint32_t Bits>
inline void add_hit_value(const unsigned char *entry, hit_sums *sums) {
    if (Channels == 1)
        sums->grey += grey_value<Bits>(entry);
    else
        sums->rgb = Bits == 8 ? add_16(sums->rgb, rgb_values<Bits>(entry))
                              : add_32(sums->rgb, rgb_values<Bits>(entry));
}

/* add_hit_value where `in` is 1, else adding zeros (the values read at `entry`, a texel of the texton, and
   masked). */
template <uint32_t Channels, uint32_t Bits>
inline void add_hit_value_if(const unsigned char *entry, uint32_t in, hit_sums *sums) {
    if (Channels == 1) {
        sums->grey += grey_value<Bits>(entry) & (0u - in);
        return;
    }
    const vector_128 values = bitwise_and(rgb_values<Bits>(entry), set_2x64(-int64_t(in)));
    sums->rgb = Bits == 8 ? add_16(sums->rgb, values) : add_32(sums->rgb, values);
}

/* Number of set bits (SWAR: the popcnt instruction is not in the SSE2 baseline). */
inline uint32_t popcount64(uint64_t bits) {
    bits -= (bits >> 1) & 0x5555555555555555u;
    bits = (bits & 0x3333333333333333u) + ((bits >> 2) & 0x3333333333333333u);
    bits = (bits + (bits >> 4)) & 0x0F0F0F0F0F0F0F0Fu;
    return uint32_t((bits * 0x0101010101010101u) >> 56);
}

/* Sums the texton values of the hits of (at most) four cells: bit 16 c + k of hits is impulse k of cell
   c, whose entries are entries[16 c ..]. The loop counts the hits down rather than testing the mask for
   zero: its exit, hard to predict, then resolves once the count is known and one cycle per hit later,
   not at the end of the mask's chain of two dependent instructions per hit. */
template <uint32_t Channels, uint32_t Bits>
inline void sum_hits(const unsigned char *texton, uint64_t hits, const uint16_t *entries, uint32_t moved,
                     hit_sums *sums) {
    for (uint32_t left = popcount64(hits); left != 0; left--, hits &= hits - 1) {
        const uint16_t index = uint16_t(entries[lowest_bit(hits)] + moved);
        add_hit_value<Channels, Bits>(texton + size_t(index) * Channels * (Bits / 8), sums);
    }
}

/* The hits of three 64-bit words (bit b of word w: hit 64 w + b), visited in one loop: the empty words
   dropped first, then each word moved down as the one before it empties, by masks rather than branches
   (hit_words_of, next_hit). For a few hits spread over the words (the gradient's edge hits): each loop's
   exit is hard to predict, and costs more than the moves. Many hits keep a loop per word, whose step
   is one instruction long where the moves make it five. */
typedef struct hit_words {
    uint64_t bits[3];
    uint32_t base[3]; /* the hit number of each word's bit 0 */
} hit_words;

/* Where words->bits[at] is empty, the words past it move down one. */
inline void drop_if_empty(hit_words *words, uint32_t at) {
    const uint64_t moves = uint64_t(0) - uint64_t(words->bits[at] == 0);
    for (uint32_t w = at; w < 2; w++) {
        words->bits[w] = (words->bits[w] & ~moves) | (words->bits[w + 1] & moves);
        words->base[w] ^= (words->base[w] ^ words->base[w + 1]) & uint32_t(moves);
    }
    words->bits[2] &= ~moves;
}

/* The words with the empty ones dropped. */
inline hit_words hit_words_of(uint64_t first, uint64_t second, uint64_t third) {
    hit_words words = {{first, second, third}, {0, 64, 128}};
    drop_if_empty(&words, 1);
    drop_if_empty(&words, 0);
    return words;
}

/* The next hit's number, taken from the words: to be called as many times as they have hits (popcount64
   of each word, summed). */
inline uint32_t next_hit(hit_words *words) {
    const uint32_t hit = words->base[0] + lowest_bit(words->bits[0]);
    words->bits[0] &= words->bits[0] - 1;
    drop_if_empty(words, 0);
    return hit;
}

/* Adds the hit sums to the channel sums (sign-extended, modulo 2^32) and clears them. */
template <uint32_t Channels, uint32_t Bits>
inline void flush_hit_sums(hit_sums *hit, uint32_t *sums) {
    if (Channels == 1) {
        sums[0] += hit->grey;
    } else if (Bits == 8) {
        /* The lanes come out zero-extended: (v ^ 2^15) - 2^15 sign-extends them. */
        sums[0] += (uint32_t(lane_16<0>(hit->rgb)) ^ 0x8000u) - 0x8000u;
        sums[1] += (uint32_t(lane_16<1>(hit->rgb)) ^ 0x8000u) - 0x8000u;
        sums[2] += (uint32_t(lane_16<2>(hit->rgb)) ^ 0x8000u) - 0x8000u;
    } else {
        sums[0] += uint32_t(low_32(hit->rgb));
        sums[1] += uint32_t(low_32(shuffle_32<1>(hit->rgb)));
        sums[2] += uint32_t(low_32(shuffle_32<2>(hit->rgb)));
    }
    hit->grey = 0;
    hit->rgb = zero_128();
}

/* Sums the hits of `cells` (up to 9) cells, cell s's mask at masks[s] and its entries (plus `moved`) at
   entries[16 s]: 4 masks read at once as a 64-bit word (x86: little-endian), those past the cells cleared
   first. */
template <uint32_t Channels, uint32_t Bits>
inline void sum_buffered_hits(const unsigned char *texton, uint16_t *masks, uint32_t cells,
                              const uint16_t *entries, uint32_t moved, hit_sums *sums) {
    for (uint32_t s = cells; s < 12; s++) masks[s] = 0;
    uint64_t hits0, hits1, hits2;
    __builtin_memcpy(&hits0, masks, sizeof hits0);
    __builtin_memcpy(&hits1, masks + 4, sizeof hits1);
    __builtin_memcpy(&hits2, masks + 8, sizeof hits2);
    sum_hits<Channels, Bits>(texton, hits0, entries, moved, sums);
    sum_hits<Channels, Bits>(texton, hits1, entries + 64, moved, sums);
    sum_hits<Channels, Bits>(texton, hits2, entries + 128, moved, sums);
}

/* The hits common to a point and its right and lower neighbours (the gradient's three points), each
   visited once: its entry read for the point, the next for the right neighbour, one row down for the lower
   one. RGB 8-bit: the point's texel and the next, adjacent, read into one vector and summed by one
   addition, in point->rgb until the flush splits them (flush_three): by two 4-byte loads on SSE2 (16-bit
   lanes 0-2 and 4-6); by one sign-extending load of 8 bytes where SSE4.1 is there (AVX2 and AVX-512
   copies: lanes 0-2 and 3-5), which reads 2 bytes past the next texel, and the lower texel by one of 4
   bytes into 32-bit lanes. */
#if defined(__AVX2__)
const uint32_t common_right_lane = 3; /* the lane of sum_common_hits' right texel, RGB 8-bit */
#else
const uint32_t common_right_lane = 4;
#endif

template <uint32_t Channels, uint32_t Bits>
inline void sum_common_hits(const unsigned char *texton, uint32_t width, uint64_t hits,
                            const uint16_t *entries, hit_sums *point, hit_sums *right, hit_sums *lower) {
    const size_t texel = Channels * (Bits / 8);
#if defined(__AVX2__)
    if (Channels == 3 && Bits == 8) {
        /* A common hit's entry is the point's own, a texel of the texton, so the lower one's, index + width,
           is below 255 * 256 with no wrap: its texel is at lower_texton + index texels. */
        const unsigned char *lower_texton = texton + size_t(width) * texel;
        for (uint32_t left = popcount64(hits); left != 0; left--, hits &= hits - 1) {
            const size_t at = size_t(entries[lowest_bit(hits)]) * texel;
            point->rgb = add_16(point->rgb, load_signed_8x8_to_16(texton + at));
            lower->rgb = add_32(lower->rgb, load_signed_8x4_to_32(lower_texton + at));
        }
        return;
    }
#endif
    for (uint32_t left = popcount64(hits); left != 0; left--, hits &= hits - 1) {
        const uint16_t index = entries[lowest_bit(hits)];
        const unsigned char *entry = texton + size_t(index) * texel;
        if (Channels == 3 && Bits == 8) {
            uint32_t here, next;
            __builtin_memcpy(&here, entry, sizeof here);
            __builtin_memcpy(&next, entry + texel, sizeof next);
            const vector_128 pair =
                unpack_low_32(set_low_32(static_cast<int>(here)), set_low_32(static_cast<int>(next)));
            point->rgb = add_16(point->rgb, shift_right_arithmetic_16(unpack_low_8(pair, pair), 8));
        } else {
            add_hit_value<Channels, Bits>(entry, point);
            add_hit_value<Channels, Bits>(entry + texel, right);
        }
        add_hit_value<Channels, Bits>(texton + size_t(uint16_t(index + width)) * texel, lower);
    }
}

/* The hits of the three points not common to all three (a column or row at a window's edge), bit 64 w + b
   set in edges[w] where some point's word hits[p][w] has it: one visit each, without a branch, adding its
   texel to each point it hits and zeros to the others (texel 0 read, masked). */
template <uint32_t Channels, uint32_t Bits>
inline void sum_edge_hits(const unsigned char *texton, uint32_t width, const uint64_t (*hits)[3],
                          const uint64_t *edges, const uint16_t *entries, hit_sums *point, hit_sums *right,
                          hit_sums *lower) {
    const size_t texel = Channels * (Bits / 8);
    hit_words words = hit_words_of(edges[0], edges[1], edges[2]);
    for (uint32_t left = popcount64(edges[0]) + popcount64(edges[1]) + popcount64(edges[2]); left != 0;
         left--) {
        const uint32_t hit = next_hit(&words);
        const uint32_t word = hit >> 6, bit = hit & 63u, entry = entries[hit];
        const uint32_t in[3] = {uint32_t(hits[0][word] >> bit) & 1u, uint32_t(hits[1][word] >> bit) & 1u,
                                uint32_t(hits[2][word] >> bit) & 1u};
        add_hit_value_if<Channels, Bits>(texton + size_t(entry & (0u - in[0])) * texel, in[0], point);
        add_hit_value_if<Channels, Bits>(texton + size_t(((entry + 1u) & 0xFFFFu) & (0u - in[1])) * texel,
                                         in[1], right);
        add_hit_value_if<Channels, Bits>(texton + size_t(((entry + width) & 0xFFFFu) & (0u - in[2])) * texel,
                                         in[2], lower);
    }
}

/* The buffered hits of the three points: those common to all three by sum_common_hits, the rest (a column
   or row at a window's edge) by sum_edge_hits. A lane sums at most the 9 x 16 hits of one point between
   two flushes. */
template <uint32_t Channels, uint32_t Bits>
inline void flush_three(const unsigned char *texton, uint32_t width, uint16_t *masks, uint32_t cells,
                        const uint16_t *entries, uint32_t *sums) {
    for (uint32_t s = cells; s < 12; s++) masks[s] = masks[12 + s] = masks[24 + s] = 0;
    /* Named sums, not arrays: kept in registers. */
    hit_sums point = {0, zero_128()}, right = point, lower = point, point_edge = point, right_edge = point,
             lower_edge = point;
    uint64_t hits[3][3], edges[3];
    for (uint32_t word = 0; word < 3; word++) {
        for (uint32_t p = 0; p < 3; p++)
            __builtin_memcpy(&hits[p][word], masks + 12 * p + 4 * word, sizeof hits[p][word]);
        const uint64_t common = hits[0][word] & hits[1][word] & hits[2][word];
        edges[word] = (hits[0][word] | hits[1][word] | hits[2][word]) & ~common;
        sum_common_hits<Channels, Bits>(texton, width, common, entries + 64 * word, &point, &right, &lower);
    }
    sum_edge_hits<Channels, Bits>(texton, width, hits, edges, entries, &point_edge, &right_edge, &lower_edge);
    if (Channels == 3 && Bits == 8) /* the right neighbour's common hits in lanes 3-5 or 4-6 of the point's */
        right.rgb = shift_right_bytes<common_right_lane * 2>(point.rgb);
    flush_hit_sums<Channels, Bits>(&point, sums);
    flush_hit_sums<Channels, Bits>(&point_edge, sums);
    flush_hit_sums<Channels, Bits>(&right, sums + 3);
    flush_hit_sums<Channels, Bits>(&right_edge, sums + 3);
#if defined(__AVX2__)
    if (Channels == 3 && Bits == 8) /* sum_common_hits' lower sums in 32-bit lanes, as 16-bit values' */
        flush_hit_sums<Channels, 16>(&lower, sums + 6);
    else
#endif
        flush_hit_sums<Channels, Bits>(&lower, sums + 6);
    flush_hit_sums<Channels, Bits>(&lower_edge, sums + 6);
}

/* The buffered hits of every point summed into its channel sums (sums + 3 p), the point's entries moved
   by 0, 1 (the point right of it) and the width (the point below it). */
template <uint32_t Channels, uint32_t Bits, uint32_t Points>
inline void flush_cells(const unsigned char *texton, uint32_t width, uint16_t *masks, uint32_t cells,
                        const uint16_t *entries, hit_sums *hit, uint32_t *sums) {
    if (Points == 3) {
        flush_three<Channels, Bits>(texton, width, masks, cells, entries, sums);
        return;
    }
    const uint32_t moved[3] = {0u, 1u, width};
    for (uint32_t p = 0; p < Points; p++) {
        sum_buffered_hits<Channels, Bits>(texton, masks + 12 * p, cells, entries, moved[p], hit);
        flush_hit_sums<Channels, Bits>(hit, sums + 3 * p);
    }
}

/* ---- The mixed point (mix_point.cpp): each hit adds its material's texton ---- */

#if (defined(__AVX512F__) && defined(__AVX512BW__)) || defined(__AVX2__)
#define DSN_MATERIAL_MASKS 1
#else
#define DSN_MATERIAL_MASKS 0
#endif

/* What the mixed walk keeps of each buffered cell beside its masks and entries: its key, its origin and
   its impulses' fields (16 offset_y + offset_x), from which a hit's material comes. */
typedef struct material_slots {
    uint32_t keys[9], origins_x[9], origins_y[9];
    unsigned char fields[9 * 16];
#if DSN_MATERIAL_MASKS
    /* Where the weights are uniform, the cells' impulses of material m or a later one, bit k for impulse
       k: at_least[m - 1][slot], hashed 16 at a time as the cell is buffered (material_masks). */
    uint16_t at_least[3][12];
#endif
} material_slots;

/* Where the weights vary, the control as mix_pick_lanes.h's lanes read it (AVX2 and AVX-512 copies), or
   null: the pick then goes hit by hit. */
struct PickWindow;

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* A cell's 16 impulses as one vector of 16 lanes (AVX-512) or two of 8 (AVX2). */
typedef vector_512 material_vector;
const uint32_t material_lanes = 16;
inline material_vector lane_indices() {
    return set_lanes_16x32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}
/* Bit k: lane k's hash at least the threshold (unsigned). */
inline uint32_t at_least_bits(material_vector hashes, material_vector threshold) {
    return greater_equal_unsigned_32(hashes, threshold);
}
#elif DSN_MATERIAL_MASKS
typedef vector_256 material_vector;
const uint32_t material_lanes = 8;
inline material_vector lane_indices() { return set_lanes_8x32(0, 1, 2, 3, 4, 5, 6, 7); }
inline uint32_t at_least_bits(material_vector hashes, material_vector threshold) {
    /* the threshold is the smaller of the two */
    return uint32_t(top_bits_of_32(equal_32(minimum_unsigned_32(threshold, hashes), threshold)));
}
#endif

#if DSN_MATERIAL_MASKS
const uint32_t material_vectors = 16 / material_lanes;

/* The uniform weights' thresholds as 32-bit lanes, with the levels that no hash reaches (2^32) marked. */
typedef struct material_thresholds {
    material_vector threshold[3];
    uint32_t reached[3]; /* 0xFFFF, or 0 where no hash reaches the level */
    /* lane k of vector v: (material_lanes v + k) 0x9E3779B9 (dsn_cell_stream's Weyl step) */
    material_vector lane_steps[material_vectors];
} material_thresholds;

inline material_thresholds thresholds_of(const dsn_point_materials *materials) {
    material_thresholds out;
    for (uint32_t level = 0; level < 3; level++) {
        out.threshold[level] = all_lanes_32<material_vector>(uint32_t(materials->thresholds[level]));
        out.reached[level] = materials->thresholds[level] >> 32 ? 0u : 0xFFFFu;
    }
    for (uint32_t v = 0; v < material_vectors; v++)
        out.lane_steps[v] =
            multiply_32(add_32(lane_indices(), all_lanes_32<material_vector>(material_lanes * v)),
                        all_lanes_32<material_vector>(0x9E3779B9u));
    return out;
}

/* The masks of a buffered cell's 16 impulses (at_least[.][slot]): their hashes dsn_cell_stream(key, 2^31 +
   2^30 + k) at once against the thresholds. */
inline void material_masks(const material_thresholds *thresholds, uint32_t levels, uint32_t key,
                           uint32_t slot, material_slots *slots) {
    const material_vector start = all_lanes_32<material_vector>(key + 0xC0000000u * 0x9E3779B9u);
    material_vector hashes[material_vectors];
    for (uint32_t v = 0; v < material_vectors; v++)
        hashes[v] = mix32_lanes(add_32(start, thresholds->lane_steps[v]));
    for (uint32_t level = 0; level < 3; level++) {
        uint32_t bits = 0;
        for (uint32_t v = 0; v < material_vectors; v++)
            bits |= at_least_bits(hashes[v], thresholds->threshold[level]) << (material_lanes * v);
        slots->at_least[level][slot] =
            level < levels ? uint16_t(bits & thresholds->reached[level]) : uint16_t(0);
    }
}
#endif

/* What the hits of the cell (cell_x, cell_y) buffered in `slot` need to pick their materials by hash:
   its key, origin and fields (material_masks has made the masks instead where the weights are uniform). */
inline void keep_cell(uint32_t key, uint32_t cell_x, uint32_t cell_y, vector_128 fields, uint32_t slot,
                      material_slots *slots) {
    slots->keys[slot] = key;
    slots->origins_x[slot] = cell_x << 4;
    slots->origins_y[slot] = cell_y << 4;
    store_16x8(slots->fields + 16 * slot, fields);
}

/* The material of impulse k of the cell with this key, at lattice position (x, y) (kernels.h's
   dsn_point_materials). */
inline uint32_t material_of(const dsn_point_materials *materials, uint32_t key, uint32_t k, uint32_t x,
                            uint32_t y) {
    const uint32_t hash = dsn_material_hash(key, k);
    if (materials->pick != 0) return materials->pick(materials->context, hash, x, y);
    return uint32_t(hash >= materials->thresholds[0]) + uint32_t(hash >= materials->thresholds[1]) +
           uint32_t(hash >= materials->thresholds[2]);
}

#if DSN_MATERIAL_MASKS && DSN_MIXING
/* The hits of one word of masks (bit 16 s + k: impulse k of slot first + s) of material 1 or more, 2 or
   more and 3 (at_least[0 .. 2]), their materials read from the control on vectors (mix_pick_lanes.h): the
   hits' hashes and positions (their cells' origins plus their fields' offsets) listed, then picked 8 at a
   time. */
inline void picked_hits(const PickWindow *window, uint64_t hits, const material_slots *slots, uint32_t first,
                        uint64_t *at_least) {
    uint32_t streams[64 + 8], xs[64 + 8], ys[64 + 8];
    uint32_t listed = 0;
    for (uint64_t left = hits; left != 0; left &= left - 1, listed++) {
        const uint32_t bit = lowest_bit(left), slot = first + (bit >> 4);
        const uint32_t field = slots->fields[16 * first + bit];
        /* dsn_material_hash's stream, hashed on the lanes */
        streams[listed] = slots->keys[slot] + (0xC0000000u + (bit & 15u)) * 0x9E3779B9u;
        xs[listed] = slots->origins_x[slot] + (field & 15u);
        ys[listed] = slots->origins_y[slot] + (field >> 4);
    }
    for (uint32_t k = listed; k < listed + 8u; k++) streams[k] = xs[k] = ys[k] = 0; /* a last group's rest */
    uint64_t listed_levels[3] = {0, 0, 0};                                          /* bit k: listed hit k */
    for (uint32_t group = 0; group < listed; group += 8) {
        vector_256 levels[3];
        picked_level_lanes(*window, mix32_lanes(load_8x32(streams + group)), load_8x32(xs + group),
                           load_8x32(ys + group), levels);
        for (uint32_t level = 0; level < 3; level++)
            listed_levels[level] |= uint64_t(uint32_t(top_bits_of_32(levels[level]))) << group;
    }
    /* each listed hit's bits back to its own bit of the word */
    for (uint64_t left = hits; left != 0; left &= left - 1) {
        const uint64_t lowest = left & (~left + 1u);
        for (uint32_t level = 0; level < 3; level++) {
            at_least[level] |= lowest & (0u - (listed_levels[level] & 1u));
            listed_levels[level] >>= 1;
        }
    }
}
#endif

/* The hits of one word of masks (bit 16 s + k: impulse k of slot first + s) split by material: of[m] the
   hits of material m. Built as the hits of material 1 or more, 2 or more and 3 by masks, not branches:
   the materials of neighbouring impulses are as unpredictable as a mix's weights make them. */
template <bool Laned>
inline void split_by_material(const dsn_point_materials *materials, const PickWindow *picks, uint64_t hits,
                              const material_slots *slots, uint32_t first, uint64_t *of) {
    uint64_t one_or_more = 0, two_or_more = 0, three = 0, to_hash = hits;
#if DSN_MATERIAL_MASKS
    if (materials->pick == 0) {
        __builtin_memcpy(&one_or_more, slots->at_least[0] + first, sizeof one_or_more);
        __builtin_memcpy(&two_or_more, slots->at_least[1] + first, sizeof two_or_more);
        __builtin_memcpy(&three, slots->at_least[2] + first, sizeof three);
        to_hash = 0;
    }
#if DSN_MIXING
    if (Laned && picks != 0) {
        uint64_t at_least[3] = {0, 0, 0};
        picked_hits(picks, hits, slots, first, at_least);
        one_or_more = at_least[0], two_or_more = at_least[1], three = at_least[2];
        to_hash = 0;
    }
#else
    (void)picks;
#endif
#else
    (void)picks;
#endif
    for (uint64_t left = to_hash; left != 0; left &= left - 1) {
        const uint32_t bit = lowest_bit(left), slot = first + (bit >> 4);
        const uint32_t field = slots->fields[16 * first + bit];
        const uint32_t m =
            material_of(materials, slots->keys[slot], bit & 15u, slots->origins_x[slot] + (field & 15u),
                        slots->origins_y[slot] + (field >> 4));
        const uint64_t lowest = left & (~left + 1u);
        one_or_more |= lowest & (0u - uint64_t(m >= 1u));
        two_or_more |= lowest & (0u - uint64_t(m >= 2u));
        three |= lowest & (0u - uint64_t(m >= 3u));
    }
    of[0] = hits & ~one_or_more;
    of[1] = hits & one_or_more & ~two_or_more;
    of[2] = hits & two_or_more & ~three;
    of[3] = hits & three;
}

/* The buffered hits of the mixed point summed into each material's sums (sums + 3 m). */
template <uint32_t Channels, uint32_t Bits, bool Laned>
inline void flush_materials(const dsn_point_materials *materials, const PickWindow *picks, uint16_t *masks,
                            uint32_t cells, const uint16_t *entries, material_slots *slots, uint32_t *sums) {
    for (uint32_t s = cells; s < 12; s++) masks[s] = 0;
#if DSN_MATERIAL_MASKS
    for (uint32_t s = cells; s < 12; s++)
        slots->at_least[0][s] = slots->at_least[1][s] = slots->at_least[2][s] = 0;
#endif
    hit_sums hit[dsn_point_materials_most];
    for (uint32_t m = 0; m < dsn_point_materials_most; m++) hit[m].grey = 0, hit[m].rgb = zero_128();
    for (uint32_t word = 0; word < 3; word++) {
        uint64_t hits, of[dsn_point_materials_most];
        __builtin_memcpy(&hits, masks + 4 * word, sizeof hits);
        split_by_material<Laned>(materials, picks, hits, slots, 4 * word, of);
        for (uint32_t m = 0; m < dsn_point_materials_most; m++)
            if (m < materials->count)
                sum_hits<Channels, Bits>(materials->values[m], of[m], entries + 64 * word, 0u, &hit[m]);
    }
    for (uint32_t m = 0; m < dsn_point_materials_most; m++)
        if (m < materials->count) flush_hit_sums<Channels, Bits>(&hit[m], sums + 3 * m);
}

/* The buffered hits flushed: into each material's sums for the mixed point (Mixed), else into each
   point's. */
template <uint32_t Channels, uint32_t Bits, uint32_t Points, bool Mixed, bool Laned>
inline void flush_walked(const unsigned char *texton, uint32_t width, uint16_t *masks, uint32_t cells,
                         const uint16_t *entries, hit_sums *hit, material_slots *slots,
                         const dsn_point_materials *materials, const PickWindow *picks, uint32_t *sums) {
    if (Mixed)
        flush_materials<Channels, Bits, Laned>(materials, picks, masks, cells, entries, slots, sums);
    else
        flush_cells<Channels, Bits, Points>(texton, width, masks, cells, entries, hit, sums);
}

/* A cell's rare impulses past 16 for the mixed point, each adding its material's texton entry. */
template <uint32_t Channels, uint32_t Bits>
inline void add_material_impulses(const dsn_noise_state *noise, const dsn_texton_window *texton,
                                  const dsn_point_materials *materials, uint32_t key, uint32_t count,
                                  uint32_t origin_x, uint32_t origin_y, const axis_cell *in_x,
                                  const axis_cell *in_y, uint32_t *sums) {
    visit_reaching_impulses(noise, texton, key, 16, count, in_x, in_y,
                            [&](uint32_t k, uint32_t offset_x, uint32_t offset_y, uint32_t entry) {
                                const uint32_t m =
                                    material_of(materials, key, k, origin_x + offset_x, origin_y + offset_y);
                                for (uint32_t c = 0; c < Channels; c++)
                                    sums[3 * m + c] +=
                                        texton_value<Bits>(materials->values[m], entry * Channels + c);
                            });
}

/* The x range of one column of cells for a point whose reach there is `reach`, and whether the column
   reaches it at all (all ones) or not (0: a column of the walk over a point and its right neighbour may
   reach only one of them). */
inline uint32_t live_range(uint32_t reach, uint32_t size) { return reach < size + 15u ? 0xFFFFu : 0u; }

/* The sums of the point (x, y), and where Points is 3 of the points (x + 1, y) and (x, y + 1) too (sums +
   3, sums + 6: the lattice gradient's neighbours), from one walk over the cells that reach any of them;
   where Mixed (Points 1), each material's sums of the point (sums + 3 m). */
template <uint32_t Channels, uint32_t Bits, uint32_t Points, bool Mixed, bool Laned>
void accumulate_cells16(const dsn_noise_state *noise, const dsn_texton_window *texton, uint32_t x, uint32_t y,
                        uint32_t *sums, const dsn_point_materials *materials) {
    const uint32_t reached = Points == 1 ? 0u : 1u; /* the window grows by one column and one row */
    const uint32_t width = texton->width, height = texton->height;
    const uint32_t low_x = x - texton->radius[0], low_y = y - texton->radius[1];
    const uint32_t columns = (((low_x & 15u) + width + reached - 1u) >> 4) + 1u,
                   rows = (((low_y & 15u) + height + reached - 1u) >> 4) + 1u;
    const uint32_t first_column = low_x >> 4, reach_x = x + texton->radius[0] - (first_column << 4);
    /* width - 16 in 16-bit lanes (modulo 2^16, like the entries: the short conversion is modulo 2^16 on
       every x86 compiler) */
    const vector_128 widths_less_16 = set_8x16(static_cast<int16_t>((width - 16) & 0xFFFFu)),
                     sixteen = set_8x16(16);
    /* Only the first and last columns cut the texton: a column j between them is within it whole, for the
       point and for its right neighbour. Its reach, reach_x - 16 j with reach_x <= 2 radius + 15, is at
       most 2 radius - 1, and the neighbour's 2 radius, both below the width (2 radius + 1 or + 2); and
       column j + 1 is reached, so its reach is at least 16. The edge columns may reach one of the point
       and its neighbour and not the other: `live` says which (all ones or 0). */
    const uint32_t last_reach = reach_x - 16 * (columns - 1);
    const lane_range whole = {zero_128(), set_16x8(15)};
    const lane_range first_ranges[2] = {x_range_of(reach_x, width), x_range_of(reach_x + reached, width)},
                     last_ranges[2] = {x_range_of(last_reach, width),
                                       x_range_of(last_reach + reached, width)},
                     whole_ranges[2] = {whole, whole};
    const uint32_t first_live[2] = {live_range(reach_x, width), live_range(reach_x + reached, width)},
                   last_live[2] = {live_range(last_reach, width), live_range(last_reach + reached, width)},
                   whole_live[2] = {0xFFFFu, 0xFFFFu};
    /* The hits of up to 9 cells wait until all are tested (the 3 x 3 cells of the usual 31 x 31 texton:
       one wait per point): cell s's mask in masks[s], its entries at entries[16 s]. Visiting hits ends
       with a loop exit that depends on the last cell's mask, hard to predict. When the masks were made
       long before, a misprediction resolves at once; right after its cells, it waits for their whole
       hash-and-test chain, and the work of the next cells with it, so the fewer visits per point the
       better. The masks are stored one by one rather than shifted into words: fewer instructions. A
       neighbour's masks follow, 12 apart. */
    uint16_t entries[9 * 16], masks[12 * Points];
    material_slots slots; /* (filled for the mixed point alone) */
#if DSN_MATERIAL_MASKS
    const bool thresholded = Mixed && materials->pick == 0;
    material_thresholds thresholds;
    if (thresholded) thresholds = thresholds_of(materials);
#endif
    const PickWindow *picks = 0; /* (the mixed point's, where Laned) */
#if DSN_MATERIAL_MASKS && DSN_MIXING
    PickWindow window = {};
    if (Laned && materials->pick != 0 && materials->control != 0 &&
        pick_window(materials->control, materials->count, x, y, texton->radius[0], texton->radius[1],
                    &window))
        picks = &window;
#endif
    uint32_t slot = 0;
    hit_sums hit = {0, zero_128()};
    for (uint32_t i = 0; i < rows; i++) {
        const uint32_t cell_y = ((low_y >> 4) + i) & 0x0FFFFFFFu, row_key = dsn_row_key(noise, cell_y);
        const uint32_t reach_y = y + texton->radius[1] - (cell_y << 4);
        const lane_range row_range[2] = {y_range_of(reach_y, height), y_range_of(reach_y + reached, height)};
        const uint32_t row_live[2] = {live_range(reach_y, height), live_range(reach_y + reached, height)};
        /* Texton index of offset 0 in cell j: corner - 16 j (16-bit lanes, modulo 2^16; the short
           conversion is modulo 2^16 on every x86 compiler). */
        vector_128 corner = set_8x16(static_cast<int16_t>((reach_y * width + reach_x) & 0xFFFFu));
        for (uint32_t j = 0; j < columns; j++) {
            /* The cell key and its count (one Poisson draw: poisson_parts is 1 on this path). */
            const uint32_t cell_x = (first_column + j) & 0x0FFFFFFFu;
            const uint32_t key = dsn_mix32((cell_x ^ noise->seed_column) + row_key);
            const vector_128 key_vector = set_low_32(static_cast<int>(key)); /* the bits unchanged */
            const uint32_t column_reach = reach_x - 16 * j;
            const bool first = j == 0, last = j + 1 == columns;
            const lane_range *column_range = first ? first_ranges : last ? last_ranges : whole_ranges;
            uint32_t live[3] = {0, 0, 0};
            if (Points == 3) {
                const uint32_t *column_live = first ? first_live : last ? last_live : whole_live;
                live[0] = column_live[0] & row_live[0];
                live[1] = column_live[1] & row_live[0];
                live[2] = column_live[0] & row_live[1];
            }
            if (slot == 9) {
                flush_walked<Channels, Bits, Points, Mixed, Laned>(texton->values, width, masks, 9, entries,
                                                                   &hit, &slots, materials, picks, sums);
                slot = 0;
            }
            const uint32_t count = dsn_poisson_count_two_steps(noise, key);
            const vector_128 fields = position_pairs(key_vector);
            cell_hits<Points>(fields, absent_impulses(count), column_range, row_range, corner, widths_less_16,
                              entries + 16 * slot, masks + slot, live);
            if (Mixed) {
#if DSN_MATERIAL_MASKS
                if (thresholded)
                    material_masks(&thresholds, materials->count - 1u, key, slot, &slots);
                else
                    keep_cell(key, cell_x, cell_y, fields, slot, &slots);
#else
                keep_cell(key, cell_x, cell_y, fields, slot, &slots);
#endif
            }
            slot++;
            corner = subtract_16(corner, sixteen);
            if (count > 16) {
                /* The rare rest, through the generic cell walk's per-impulse test. */
                for (uint32_t p = 0; p < Points; p++) {
                    const axis_cell in_x = {column_reach + (p == 1), 15u}, in_y = {reach_y + (p == 2), 15u};
                    if (Mixed)
                        add_material_impulses<Channels, Bits>(noise, texton, materials, key, count,
                                                              cell_x << 4, cell_y << 4, &in_x, &in_y, sums);
                    else
                        add_impulses(noise, texton, key, 16, count, &in_x, &in_y, sums + 3 * p);
                }
            }
        }
    }
    flush_walked<Channels, Bits, Points, Mixed, Laned>(texton->values, width, masks, slot, entries, &hit,
                                                       &slots, materials, picks, sums);
}

/* Whether the 16 x 16 cells' vector walk takes the noise. dsn_poisson_count_two_steps reads up to
   cdf[size + 1]: always in the table for one draw (mean <= 16), checked. */
bool cells16_walk(const dsn_noise_state *noise) {
    return noise->cell_shift == 4 && noise->poisson_parts == 1 && noise->period[0] == 0 &&
           noise->period[1] == 0 &&
           noise->poisson_size + 2 <= sizeof noise->poisson_cdf / sizeof noise->poisson_cdf[0];
}

/* The sums of Points points, or of each material (zeroed first), by the walk of the noise's channels and
   value size. */
template <uint32_t Points, bool Mixed, bool Laned>
inline void walk_points(const dsn_noise_state *noise, const dsn_texton_window *texton, uint32_t x, uint32_t y,
                        uint32_t *sums, const dsn_point_materials *materials) {
    const uint32_t values = 3 * (Mixed ? materials->count : Points);
    for (uint32_t i = 0; i < values; i++) sums[i] = 0;
    const dsn_asset *asset = &noise->asset;
    if (asset->channels == 3)
        asset->bits == 8
            ? accumulate_cells16<3, 8, Points, Mixed, Laned>(noise, texton, x, y, sums, materials)
            : accumulate_cells16<3, 16, Points, Mixed, Laned>(noise, texton, x, y, sums, materials);
    else
        asset->bits == 8
            ? accumulate_cells16<1, 8, Points, Mixed, Laned>(noise, texton, x, y, sums, materials)
            : accumulate_cells16<1, 16, Points, Mixed, Laned>(noise, texton, x, y, sums, materials);
}

/* The kernel entry (kernels.h's dsn_lattice_point_entry): the sums of `points` points (1, or 3: the point
   and its right and lower neighbours, sums + 3 p), or of each material of a mixed point; 0 (writing
   nothing) where the vector walk does not take the noise. */
inline int lattice_point_sums(const dsn_noise_state *noise, const dsn_texton_window *texton, uint32_t x,
                              uint32_t y, uint32_t points, uint32_t *sums,
                              const dsn_point_materials *materials) {
    if (!cells16_walk(noise) ||
        (materials != 0 && (points != 1 || materials->count > dsn_point_materials_most)))
        return 0;
    if (materials != 0)
        materials->pick != 0 && materials->control != 0
            ? walk_points<1, true, true>(noise, texton, x, y, sums, materials)
            : walk_points<1, true, false>(noise, texton, x, y, sums, materials);
    else
        points == 3 ? walk_points<3, false, false>(noise, texton, x, y, sums, 0)
                    : walk_points<1, false, false>(noise, texton, x, y, sums, 0);
    return 1;
}

} // namespace
/* The kernel entry (kernels.h): null where there is none (point.cpp then walks cell by cell). */
#define DSN_LATTICE_POINT_ENTRY lattice_point_sums
#else
#define DSN_LATTICE_POINT_ENTRY 0
#endif

#endif /* DSN_LATTICE_POINT_WALK_H */
