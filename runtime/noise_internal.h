/* runtime/noise_internal.h - building blocks shared by the lattice and continuous evaluators: hashing of
   cells and impulses, exact Poisson counts, fixed-point normalization, and the walk over the cells that
   can reach a window (periodic or not). Internal to libdsn; not installed.

   The impulse process (DESIGN.md section 3). The plane is the 2^32 x 2^32 torus cut into square cells of
   side c = 2^cell_shift (a power of two divides 2^32, so cells tile the torus exactly and there are
   2^(32 - cell_shift) distinct cell indices per axis, none repeated). Cell (cx, cy) has a 32-bit key;
   from the key come its impulse count (exact Poisson, possibly the sum of several independent draws, see
   poisson_parts) and then the position of each impulse k, all by stateless hashing:

       key        = cell_key(noise, cx, cy)                          32 bits
       count      = poisson(key) + poisson(cell_stream(key, 1)) + ... (parts draws)
       pair p     = position_pair(key, p)                            64 bits: packed lattice positions
       fraction k = cell_stream(key, 2^31 + k)                       continuous mode only

   The lattice positions are packed so that one hash serves several impulses: with cells of side <= 16
   an impulse takes one byte of a pair (x in the low nibble, y in the high one), eight impulses per pair;
   with larger cells it takes 16 bits (x in the low byte, y in the high one), four per pair. Impulse k
   has field k % per_pair of pair k / per_pair, and its lattice offset in the cell is the top cell_shift
   bits of each half of the field (each half is uniform, so the offsets are exactly uniform and
   independent). The continuous mode appends the fraction hash's bits below the field's to make 16-bit
   positions (dsn_impulse_hash), so the lattice impulse is exactly the floor of its continuous twin. */
#ifndef DSN_NOISE_INTERNAL_H
#define DSN_NOISE_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "noise_state.h"

/* The larger helpers below are inlined for speed; the small build (DSN_SMALL_CODE, dsn.h) keeps one
   out-of-line copy of each instead (C++ inline functions: every link keeps a single copy). */
#if DSN_SMALL_CODE && defined(__clang__)
#define DSN_SHARED inline __attribute__((noinline))
#elif DSN_SMALL_CODE && defined(__GNUC__)
#define DSN_SHARED inline __attribute__((noinline, noclone))
#else
#define DSN_SHARED static inline
#endif

/* ---- Hashing ---- */

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

/* ---- Exact Poisson counts ---- */

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

/* ---- Packed lattice positions ---- */

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

/* ---- Fixed-point normalization ----
   out_c = round((offset_c + sum_k gain_ck * Q_k) / 2^gain_shift), saturated to int32, with Q_k the
   integer sum of the quantized texton values of channel k (taken modulo 2^32 and read as int32, which
   both evaluators do identically; it cannot wrap unless ~65000 full-scale impulses hit one point).
   Init guarantees |gain| < 2^29 and |offset| < 2^61, so |sum| < 3 2^60 + 2^61 < 2^63 - 2^32. */
DSN_SHARED int32_t dsn_round_saturate(int64_t accumulated, uint32_t shift) {
    /* Shifting a negative number is implementation-defined: move to uint64 with a 2^63 bias first
       (the conversion is modulo 2^64, and the rounding half cannot overflow given the bound above). */
    const uint64_t bias = uint64_t(1) << 63;
    uint64_t biased = uint64_t(accumulated) + bias + ((uint64_t(1) << shift) >> 1);
    int64_t value = int64_t(biased >> shift) - int64_t(bias >> shift);
    if (value > INT32_MAX) return INT32_MAX;
    if (value < INT32_MIN) return INT32_MIN;
    return int32_t(value);
}

static inline int32_t dsn_signed_sum(uint32_t sum) {
    return (sum & 0x80000000u) ? -int32_t(~sum) - 1 : int32_t(sum);
}

/* Q_k sums (uint32, modulo 2^32) -> Q16.16 outputs. */
DSN_SHARED void dsn_normalize(const dsn_noise_state *noise, const uint32_t *sums, int32_t *out) {
    uint32_t c, k, channels = noise->asset.channels;
    for (c = 0; c < channels; c++) {
        int64_t accumulated = noise->offset[c];
        for (k = 0; k < channels; k++) accumulated += noise->gain[c * 3 + k] * dsn_signed_sum(sums[k]);
        out[c] = dsn_round_saturate(accumulated, noise->gain_shift);
    }
}

/* The API edge's output types, for the paths that convert pixel by pixel through a switch rather than
   with one copy of their code per type (the conversion is nothing next to evaluating a pixel). */
typedef enum dsn_output_kind { dsn_output_fixed, dsn_output_float, dsn_output_u8 } dsn_output_kind;

DSN_SHARED void dsn_store_pixel(void *out, dsn_output_kind kind, size_t first, const int32_t *pixel,
                                uint32_t channels) {
    for (uint32_t c = 0; c < channels; c++) {
        if (kind == dsn_output_float)
            static_cast<float *>(out)[first + c] = dsn_fixed_to_float(pixel[c]);
        else if (kind == dsn_output_u8)
            static_cast<uint8_t *>(out)[first + c] = dsn_fixed_to_u8(pixel[c]);
        else
            static_cast<int32_t *>(out)[first + c] = pixel[c];
    }
}

/* ---- Walking the cells that can reach a window, along one axis ----
   A window is the run of lattice coordinates [start, start + length) of one axis (a single point has
   length 1). An impulse at axis position p reaches window index j when the texton index
   start + j - p + radius lies in [0, 2 radius]. A span is one group of candidate cells: cells
   first_cell .. first_cell + cell_count - 1 (indices modulo 2^(32 - cell_shift)) whose impulses have
   positions p = (cell << cell_shift) + offset, accepted only when p <= last_position, and reach the
   window with texton index  j + (base - p)  (uint32 arithmetic). Without a period there is one span on
   the whole torus. With a period P, the coordinate is reduced to [0, P), the impulses live on [0, P)
   (cells cut at P, impulses at >= P discarded) and the window meets several copies m of that interval:
   span m has base = start + radius - m P. */
typedef struct dsn_span {
    uint32_t first_cell;
    uint32_t cell_count;
    uint32_t base;
    uint32_t last_position;
} dsn_span;

typedef struct dsn_axis {
    uint32_t radius, shift, period; /* period 0: not periodic */
    uint32_t length;                /* window length */
    uint32_t start;                 /* periodic: window start reduced to [0, P); else the start */
    uint32_t copies_before;         /* periodic: the first copy met is m = -copies_before */
    uint32_t span_count;
} dsn_axis;

/* Window [coordinate, coordinate + length) along one axis. `coordinate` is the int32 lattice
   coordinate (as a uint32 bit pattern); with a period it is reduced by floor modulo. All in 32-bit
   arithmetic (no 64-bit division, which 32-bit targets would call): the copies met are
   m = floor((start - radius) / P) .. floor((start + length - 1 + radius) / P), the first one -1 or
   below only when start < radius. */
DSN_SHARED void dsn_axis_init(dsn_axis *axis, uint32_t coordinate, uint32_t length, uint32_t radius,
                              uint32_t shift, uint32_t period) {
    axis->radius = radius;
    axis->shift = shift;
    axis->period = period;
    axis->length = length;
    axis->start = coordinate;
    axis->copies_before = 0;
    axis->span_count = 1;
    if (period != 0) {
        /* Floor modulo of the int32 coordinate: for c < 0, c mod P = P - 1 - ((-c - 1) mod P), and
           -c - 1 = ~c lies in [0, 2^31). */
        const uint32_t start =
            (coordinate & 0x80000000u) ? period - 1u - ~coordinate % period : coordinate % period;
        /* start + extent may pass 2^32: floor((start + extent) / P) is extent / P, plus 1 when the
           remainders add up to P or more. */
        const uint32_t extent = length - 1u + radius, rest = extent % period;
        axis->start = start;
        axis->copies_before = start >= radius ? 0u : 1u + (radius - 1u - start) / period;
        axis->span_count = axis->copies_before + extent / period + (rest >= period - start ? 1u : 0u) + 1u;
    }
}

/* Span `index` meets copy m = index - copies_before, which starts at m P. Seen from that copy the
   window runs from start - radius - m P to start + length - 1 + radius - m P: the first copy met is the
   only one where the low end is >= 0 and the last the only one where the high end is < P, and there
   both ends lie in [0, P), so arithmetic modulo 2^32 gives them exactly. */
DSN_SHARED dsn_span dsn_axis_span(const dsn_axis *axis, uint32_t index) {
    dsn_span span;
    const uint32_t mask = (1u << axis->shift) - 1u, low = axis->start - axis->radius;
    if (axis->period == 0) {
        span.first_cell = low >> axis->shift;
        span.cell_count = (((low & mask) + axis->length - 1u + 2u * axis->radius) >> axis->shift) + 1u;
        span.base = axis->start + axis->radius;
        span.last_position = 0xFFFFFFFFu;
    } else {
        const uint32_t copy_start = (index - axis->copies_before) * axis->period; /* m P modulo 2^32 */
        const uint32_t first = index == 0 ? low - copy_start : 0u;
        const uint32_t last = index == axis->span_count - 1u
                                  ? axis->start + axis->length - 1u + axis->radius - copy_start
                                  : axis->period - 1u;
        span.first_cell = first >> axis->shift;
        span.cell_count = (last >> axis->shift) - span.first_cell + 1u;
        /* Only differences modulo 2^32 matter (see above). */
        span.base = axis->start + axis->radius - copy_start;
        span.last_position = axis->period - 1u;
    }
    return span;
}

/* Where an impulse at axis position p meets a window of `length` points. With the impulse's end
   e = base - p + length - 1 (uint32, base the span's), some window index reaches it exactly when
   e < length - 1 + diameter (diameter = 2 radius + 1); it then reaches window indices first_index ..
   first_index + count - 1, starting at texton index first_texton. */
typedef struct dsn_reach {
    uint32_t first_index, first_texton, count;
} dsn_reach;

/* The reach of an impulse with end e < length - 1 + diameter. */
DSN_SHARED void dsn_reach_at(uint32_t e, uint32_t length, uint32_t diameter, dsn_reach *reach) {
    const uint32_t last_index =
        (length - 1u + diameter - 1u - e < length - 1u) ? length - 1u + diameter - 1u - e : length - 1u;
    reach->first_index = e < length - 1u ? length - 1u - e : 0u;
    reach->first_texton = reach->first_index + e - (length - 1u);
    reach->count = last_index - reach->first_index + 1u;
}

/* Cell index i of a span, wrapped to the torus of cells. */
static inline uint32_t dsn_span_cell(const dsn_span *span, uint32_t i, uint32_t shift) {
    return (span->first_cell + i) & (0xFFFFFFFFu >> shift);
}

#endif /* DSN_NOISE_INTERNAL_H */
