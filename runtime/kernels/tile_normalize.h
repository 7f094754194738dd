/* runtime/kernels/tile_normalize.h - the normalization of a strip row's 16-bit sums (tile_strips.h), bit for
   bit dsn_normalize: exactly split into 32-bit SIMD lanes when the noise allows it (a whole strip, 8
   pixels with SSE2, 16 with AVX2 or 32 with AVX-512, at once), one pixel at a time otherwise; the
   results go to the output through tile_store.h. Internal to tile_render.h. */
#ifndef DSN_TILE_NORMALIZE_H
#define DSN_TILE_NORMALIZE_H

#include "core/normalize_fixed.h"
#include "kernels/tile_store.h"

namespace {

/* ---- Normalization of 16-bit sums ----
   dsn_normalize computes round((offset_c + sum_k gain_ck Q_k) / 2^s) in 64 bits. When every |Q_k| <
   2^15 it splits exactly into 32-bit lanes: gain = 2^15 high + low with low in [-2^14, 2^14) (so |high|
   <= 2^14), A = sum high_k Q_k and B = sum low_k Q_k (|A|, |B| < 3 2^29), and P = offset + 2^(s-1) =
   2^s P_q + 2^15 P_m + P_l (P_m < 2^(s-15), P_l < 2^15). Then
       sum = 2^s P_q + 2^15 (P_m + A + floor((B + P_l) / 2^15)) + ((B + P_l) mod 2^15), so
       result = P_q + floor((P_m + A + floor((B + P_l) / 2^15)) / 2^(s-15))
   where every intermediate stays below 2^31 in magnitude. This needs s >= 16, and P_q +- 2^(46-s) inside
   int32 so that the int32 saturation of dsn_normalize can never act. With vectors, A and B + P_l are
   two pmaddwd each: (Q_0, Q_1) . (high_0, high_1) + (Q_2, 1) . (high_2, 0), and the same with
   (low_0, low_1) and (low_2, P_l). */
typedef struct split_normalization {
    int16_t high[9], low[9];
    int32_t p_q[3], p_m[3], p_l[3];
    uint32_t shift; /* s - 15 */
} split_normalization;

int make_split_normalization(const dsn_noise_state *noise, split_normalization *split) {
    const uint32_t s = noise->gain_shift, channels = noise->asset.channels;
    if (s < 16 || s > 32) return 0;
    for (uint32_t c = 0; c < channels; c++) {
        const int64_t gain_limit = int64_t(1) << 29, offset_limit = int64_t(1) << 61;
        if (noise->offset[c] <= -offset_limit || noise->offset[c] >= offset_limit) return 0;
        for (uint32_t k = 0; k < 3; k++) {
            int64_t gain = k < channels ? noise->gain[c * 3 + k] : 0;
            if (gain <= -gain_limit || gain >= gain_limit)
                return 0; /* what init guarantees; else per pixel */
            int64_t low = int64_t(uint64_t(gain) & 0x7FFFu);
            if (low >= 0x4000) low -= 0x8000;
            split->low[c * 3 + k] = int16_t(low);
            split->high[c * 3 + k] = int16_t((gain - low) / 0x8000);
        }
        int64_t p = noise->offset[c] + (int64_t(1) << (s - 1));
        int64_t below = int64_t(uint64_t(p) & ((uint64_t(1) << s) - 1u));
        int64_t p_q = (p - below) / (int64_t(1) << s), margin = int64_t(1) << (46 - s);
        if (p_q - margin < INT32_MIN || p_q + margin > INT32_MAX) return 0;
        split->p_q[c] = int32_t(p_q);
        split->p_m[c] = int32_t(below >> 15);
        split->p_l[c] = int32_t(below & 0x7FFF);
    }
    split->shift = s - 15;
    return 1;
}

#if DSN_HISTOGRAM
/* The histogram mapping of `pixels` pixels of Q16.16 values normalized in lanes, then their conversion:
   what dsn_normalize does last, pixel by pixel (a table read per value). */
template <uint32_t Channels, typename Value>
void map_pixels(const dsn_noise_state *noise, int32_t *fixed, uint32_t pixels, Value *out) {
    for (uint32_t i = 0; i < pixels; i++) {
        int32_t *pixel = fixed + i * Channels;
        dsn_internal_histogram_map(&noise->asset, pixel, 0, 0);
        for (uint32_t c = 0; c < Channels; c++) store_value(out + i * Channels + c, pixel[c]);
    }
}
#endif

/* Q_k of a 16-bit sum, as the uint32 bits dsn_normalize reads. */
inline uint32_t widen_sum(uint16_t value) { return (uint32_t(value) ^ 0x8000u) - 0x8000u; }

/* The first `pixels` pixels of a strip row, one at a time. */
template <typename Value>
void normalize_strip_scalar(const dsn_noise_state *noise, const simd_vector *sums, uint32_t pixels,
                            Value *out) {
    const uint32_t channels = noise->asset.channels;
    uint16_t values[3][lane];
    for (uint32_t c = 0; c < 3; c++) store_16(values[c], sums[c]);
    for (uint32_t i = 0; i < pixels; i++) {
        uint32_t q[3] = {0, 0, 0};
        int32_t fixed[3];
        for (uint32_t k = 0; k < channels; k++) q[k] = widen_sum(values[k][i]);
        dsn_normalize(noise, q, fixed);
        for (uint32_t c = 0; c < channels; c++) store_value(out + i * channels + c, fixed[c]);
    }
}

/* The vector operations (simd.h) work on 128-bit lanes independently in AVX2 and AVX-512 (unpacking
   and shuffles too), so this code is the SSE2 code run on two or four groups of 8 pixels at once: with
   AVX2 pixels 0-3 and 8-11 in `low`, 4-7 and 12-15 in `high`; with AVX-512 also 16-19 and 24-27 in
   `low`, 20-23 and 28-31 in `high`. */

/* The split normalization's constants, repeated in every 128-bit lane. */
typedef struct split_vectors {
    simd_vector high_pair[3], high_third[3], low_pair[3], low_third[3], p_q[3], p_m[3];
    vector_128 shift;
} split_vectors;

void make_split_vectors(const split_normalization *split, uint32_t channels, split_vectors *v) {
    for (uint32_t c = 0; c < channels; c++) {
        const int16_t *high = split->high + 3 * c, *low = split->low + 3 * c;
        const int16_t p_l = int16_t(split->p_l[c]);
        v->high_pair[c] = broadcast_lanes(
            set_lanes_8x16(high[0], high[1], high[0], high[1], high[0], high[1], high[0], high[1]));
        v->high_third[c] = broadcast_lanes(set_lanes_8x16(high[2], 0, high[2], 0, high[2], 0, high[2], 0));
        v->low_pair[c] =
            broadcast_lanes(set_lanes_8x16(low[0], low[1], low[0], low[1], low[0], low[1], low[0], low[1]));
        v->low_third[c] = broadcast_lanes(set_lanes_8x16(low[2], p_l, low[2], p_l, low[2], p_l, low[2], p_l));
        v->p_q[c] = broadcast_lanes(set_4x32(split->p_q[c]));
        v->p_m[c] = broadcast_lanes(set_4x32(split->p_m[c]));
    }
    v->shift = shift_count(int32_t(split->shift));
}

/* Output channel c of 4 pixels per 128-bit lane: `pair` holds (Q_0, Q_1) and `third` (Q_2, 1) per pixel. */
inline simd_vector high_part(const split_vectors *v, uint32_t c, simd_vector pair, simd_vector third) {
    return add_32(madd_16(pair, v->high_pair[c]), madd_16(third, v->high_third[c]));
}
inline simd_vector low_part(const split_vectors *v, uint32_t c, simd_vector pair, simd_vector third) {
    return add_32(madd_16(pair, v->low_pair[c]), madd_16(third, v->low_third[c]));
}
/* Output channel c from the parts a = A and b = B + P_l. */
inline simd_vector value_lanes(const split_vectors *v, uint32_t c, simd_vector a, simd_vector b) {
    simd_vector x = add_32(add_32(v->p_m[c], a), shift_right_15(b));
    return add_32(shift_right(x, v->shift), v->p_q[c]);
}
inline simd_vector normalize_lanes(const split_vectors *v, uint32_t c, simd_vector pair, simd_vector third) {
    return value_lanes(v, c, high_part(v, c, pair, third), low_part(v, c, pair, third));
}

/* Per 128-bit lane: (r0 r1 r2 r3), (g0 ..), (b0 ..) -> r0 g0 b0 r1 | g1 b1 r2 g2 | b2 r3 g3 b3. shufps
   only moves bits between lanes (no arithmetic), so reading the integers as floats here is exact. */
inline void interleave_3(simd_vector r, simd_vector g, simd_vector b, simd_vector *out) {
    simd_floats blue = as_floats(b);
    simd_floats rg_low = as_floats(unpack_low_32(r, g)), rg_high = as_floats(unpack_high_32(r, g));
    simd_floats first = shuffle<_MM_SHUFFLE(3, 2, 0, 0)>(blue, rg_low);  /* b0 b0 r1 g1 */
    simd_floats second = shuffle<_MM_SHUFFLE(1, 1, 3, 3)>(rg_low, blue); /* g1 g1 b1 b1 */
    simd_floats third = shuffle<_MM_SHUFFLE(3, 2, 2, 2)>(blue, rg_high); /* b2 b2 r3 g3 */
    out[0] = as_integers(shuffle<_MM_SHUFFLE(2, 0, 1, 0)>(rg_low, first));
    out[1] = as_integers(shuffle<_MM_SHUFFLE(1, 0, 2, 0)>(second, rg_high));
    simd_floats last = shuffle<_MM_SHUFFLE(3, 3, 3, 3)>(rg_high, blue); /* g3 g3 b3 b3 */
    out[2] = as_integers(shuffle<_MM_SHUFFLE(2, 0, 2, 0)>(third, last));
}

/* A strip row's values, normalized from its sums (one vector per channel), as lanes: lanes[0][c] channel c
   of the pixels of unpack_low_16, lanes[1][c] of those of unpack_high_16. */
template <uint32_t Channels>
DSN_SIMD_INLINE void normalized_lanes(const split_vectors *v, const simd_vector *sums,
                                      simd_vector (*lanes)[3]) {
    const simd_vector ones = set_16(1);
    simd_vector pair_low = unpack_low_16(sums[0], sums[1]), pair_high = unpack_high_16(sums[0], sums[1]);
    simd_vector third_low = unpack_low_16(sums[2], ones), third_high = unpack_high_16(sums[2], ones);
    /* Channel by channel, both halves: each constant is read once (AVX2's 16 registers cannot hold them
       all, and the compiler would spill them to the stack rather than read them again). */
#pragma GCC unroll 3
    for (uint32_t c = 0; c < Channels; c++) {
        lanes[0][c] = normalize_lanes(v, c, pair_low, third_low);
        lanes[1][c] = normalize_lanes(v, c, pair_high, third_high);
    }
}

/* Lanes (normalized_lanes) in the vectors store_strip takes. */
template <uint32_t Channels>
DSN_SIMD_INLINE void interleave_lanes(simd_vector (*lanes)[3], simd_vector *values) {
    if (Channels == 3) {
        interleave_3(lanes[0][0], lanes[0][1], lanes[0][2], values);
        interleave_3(lanes[1][0], lanes[1][1], lanes[1][2], values + 3);
    } else {
        values[0] = lanes[0][0];
        values[1] = lanes[1][0];
    }
}

/* The first `pixels` pixels of a strip row from its lanes (normalized_lanes). */
template <uint32_t Channels, typename Value>
DSN_SIMD_INLINE void store_lanes(simd_vector (*lanes)[3], uint32_t pixels, Value *out) {
    simd_vector values[6];
    interleave_lanes<Channels>(lanes, values);
    store_strip<Channels>(values, pixels, out, 0);
}

/* A strip row's values, normalized from its sums (one vector per channel), in the vectors store_strip
   takes. */
template <uint32_t Channels>
DSN_SIMD_INLINE void normalized_strip(const split_vectors *v, const simd_vector *sums, simd_vector *values) {
    simd_vector lanes[2][3];
    normalized_lanes<Channels>(v, sums, lanes);
    interleave_lanes<Channels>(lanes, values);
}

/* The first `pixels` pixels of a strip row from its sums (one vector per channel); `stream`: written
   past the caches (store_strip). */
template <uint32_t Channels, typename Value>
inline void normalize_strip(const split_vectors *v, const simd_vector *sums, uint32_t pixels, Value *out,
                            int stream) {
    simd_vector values[6];
    normalized_strip<Channels>(v, sums, values);
    store_strip<Channels>(values, pixels, out, stream);
}

} // namespace

#endif /* DSN_TILE_NORMALIZE_H */
