/* runtime/continuous.cpp - the continuous (renderer) mode: the spot noise at real-valued points.

   The impulses are those of the lattice mode read with their full 16-bit in-cell positions (so each
   lattice impulse is the floor of its continuous twin): a continuous Poisson process of the same
   intensity, with 16 - cell_shift fractional bits per axis. The texton is read with bilinear
   interpolation, in integer arithmetic: with the point-minus-impulse offset d (Q32.32) cut to 16
   fractional bits, t(d) = sum over the 4 surrounding texels of q * wx * wy, wx, wy in Q0.16. The per-
   channel sums carry 32 fractional bits and go through the lattice mode's normalization. With
   DSN_SMALL_CODE (dsn.h) a point walks its impulses one by one, the texton is read by one generic
   reader and grid tiles go point by point; the fast build sifts the impulses on their packed lattice
   fields first (evaluate_fast) and splats axis-aligned grids. */
#include "cell_walk.h"
#include "impulse_position.h"
#include "normalize_fixed.h"
#include "poisson_count.h"

namespace {

const uint64_t one_texel = static_cast<uint64_t>(1) << 32;

/* Two's-complement reinterpretation without implementation-defined conversions. */
int64_t signed_from_bits(uint64_t bits) {
    return (bits & 0x8000000000000000u) ? -static_cast<int64_t>(~bits) - 1 : static_cast<int64_t>(bits);
}

/* sign * mantissa * 2^exponent (an IEEE value) * 2^32, rounded toward minus infinity, modulo 2^64. */
int64_t coordinate_from_parts(bool negative, uint64_t mantissa, int32_t exponent) {
    const int32_t shift = exponent + 32;
    uint64_t magnitude = 0; /* shift >= 64: a multiple of 2^64, the point 0 of the torus */
    bool inexact = false;
    if (shift >= 0 && shift < 64) {
        magnitude = mantissa << shift;
    } else if (shift < 0) {
        /* mantissa < 2^53: a right shift by 63 drops every bit, as any larger one would. */
        const uint32_t right = shift > -63 ? static_cast<uint32_t>(-shift) : 63u;
        magnitude = mantissa >> right;
        inexact = (mantissa & ((static_cast<uint64_t>(1) << right) - 1u)) != 0;
    }
    /* Toward minus infinity: a negative value with dropped bits moves one unit further down. */
    return signed_from_bits(negative ? 0u - magnitude - (inexact ? 1u : 0u) : magnitude);
}

/* The object representation of a value as an unsigned integer of the same size (character copies are
   the only aliasing-safe way without memcpy; compilers reduce this to a move). */
template <typename Bits, typename Value>
Bits bits_of(Value value) {
    Bits bits = 0;
    const unsigned char *from = reinterpret_cast<const unsigned char *>(&value);
    unsigned char *to = reinterpret_cast<unsigned char *>(&bits);
    for (unsigned i = 0; i < sizeof(Value); i++) to[i] = from[i];
    return bits;
}

/* ---- The texton, bilinearly ---- */

/* One axis of a point-minus-impulse offset d (Q32.32): the texton index of the lower of the two texels
   that bracket d (0xFFFFFFFF for index -1) and the weight of the upper one (Q0.16). False when d is
   outside (-(radius + 1), radius + 1), where both texels are zero. */
bool bracket(int64_t offset, uint32_t radius, uint32_t *lower_index, uint32_t *upper_weight) {
    /* Shifted so that the lower index is (shifted >> 32) - 1 and the shift is of a positive value. */
    const int64_t shifted = offset + static_cast<int64_t>(radius + 1u) * static_cast<int64_t>(one_texel);
    if (shifted <= 0 || shifted >= static_cast<int64_t>(2u * radius + 2u) * static_cast<int64_t>(one_texel))
        return false;
    const uint64_t bits = static_cast<uint64_t>(shifted);
    *lower_index = static_cast<uint32_t>(bits >> 32) - 1u;
    *upper_weight = static_cast<uint32_t>(bits >> 16) & 0xFFFFu;
    return true;
}

/* Quantized value of the texton at (row, column, channel); 0 outside the window (indices are unsigned,
   so -1 is out of range too). The small build calls the loader's reader; the fast one reads inline. */
inline int32_t texel(const dsn_asset *asset, uint32_t row, uint32_t column, uint32_t channel) {
#if DSN_SMALL_CODE
    return dsn_asset_texton_value(asset, row, column, channel);
#else
    if (row >= asset->height || column >= asset->width) return 0;
    const uint32_t index = (row * asset->width + column) * asset->channels + channel;
    return asset->bits == 8 ? dsn_read_i8(asset->texton + index) : dsn_read_i16le(asset->texton + 2u * index);
#endif
}

#if !DSN_SMALL_CODE
/* The 2x2 texels of every channel with their top-left at (row, column), all inside the window: read
   without bounds checks, 8- or 16-bit. */
template <uint32_t Bytes>
int32_t stored_value(const unsigned char *at) {
    return Bytes == 1 ? dsn_read_i8(at) : dsn_read_i16le(at);
}

template <uint32_t Bytes>
void add_interior(const dsn_asset *asset, uint32_t row, uint32_t column, const int64_t *weights,
                  uint64_t *sums) {
    const uint32_t channels = asset->channels, row_bytes = asset->width * channels * Bytes;
    const unsigned char *top = asset->texton + (row * asset->width + column) * channels * Bytes;
    const unsigned char *bottom = top + row_bytes;
    for (uint32_t c = 0; c < channels; c++) {
        const uint32_t left = c * Bytes, right = (channels + c) * Bytes;
        const int64_t upper =
            weights[0] * stored_value<Bytes>(top + left) + weights[1] * stored_value<Bytes>(top + right);
        const int64_t lower = weights[0] * stored_value<Bytes>(bottom + left) +
                              weights[1] * stored_value<Bytes>(bottom + right);
        /* |upper|, |lower| <= 2^31, so each term is below 2^47; the sums wrap (defined) as uint64. */
        sums[c] += static_cast<uint64_t>(weights[2] * upper + weights[3] * lower);
    }
}
#endif

/* Adds the bilinear texton at the offset (rows, columns brackets) to the channel sums (Q.32). The four
   texels are read one by one, zero outside the window; the fast build reads them directly when all lie
   inside (the common case). */
void add_bilinear(const dsn_asset *asset, uint32_t row, uint32_t row_weight, uint32_t column,
                  uint32_t column_weight, uint64_t *sums) {
    const int64_t weights[4] = {static_cast<int64_t>(65536u - column_weight),
                                static_cast<int64_t>(column_weight),
                                static_cast<int64_t>(65536u - row_weight), static_cast<int64_t>(row_weight)};
#if !DSN_SMALL_CODE
    if (row < asset->height - 1u && column < asset->width - 1u) { /* -1 (0xFFFFFFFF) fails too */
        if (asset->bits == 8)
            add_interior<1>(asset, row, column, weights, sums);
        else
            add_interior<2>(asset, row, column, weights, sums);
        return;
    }
#endif
    for (uint32_t c = 0; c < asset->channels; c++) {
#if DSN_SMALL_CODE
        /* One loop over the 4 corners (shorter code): the same integer as the row form below, each term
           being below 2^47, so nothing wraps before the uint64 sums (which wrap as defined). */
        int64_t sum = 0;
        for (uint32_t corner = 0; corner < 4; corner++) {
            const uint32_t down = corner >> 1, right = corner & 1u;
            sum += weights[2 + down] * weights[right] * texel(asset, row + down, column + right, c);
        }
        sums[c] += static_cast<uint64_t>(sum);
#else
        const int64_t upper =
            weights[0] * texel(asset, row, column, c) + weights[1] * texel(asset, row, column + 1u, c);
        const int64_t lower = weights[0] * texel(asset, row + 1u, column, c) +
                              weights[1] * texel(asset, row + 1u, column + 1u, c);
        sums[c] += static_cast<uint64_t>(weights[2] * upper + weights[3] * lower);
#endif
    }
}

/* ---- Walking the impulses around one point ---- */

/* One axis of the point: the lattice mode's candidate cells for the window [X - 1, X + 1] around the
   point's integer part X (every impulse within radius + 1 of the point has its floor in there), and
   the point's 32-bit fraction. */
struct PointAxis {
    dsn_axis axis;
    uint32_t fraction;
};

PointAxis point_axis(uint64_t coordinate, uint32_t radius, uint32_t shift, uint32_t period) {
    PointAxis point;
    point.fraction = static_cast<uint32_t>(coordinate);
    dsn_axis_init(&point.axis, static_cast<uint32_t>(coordinate >> 32) - 1u, 3u, radius, shift, period);
    return point;
}

/* The lattice normalization of sums that carry 32 more fraction bits: the integer parts go through
   it as in lattice mode, the fractions are added once, rounded down, before the final rounding. */
void normalize_q32(const dsn_noise_state *noise, const uint64_t *sums, int32_t *out) {
    const uint32_t channels = noise->asset.channels;
    for (uint32_t c = 0; c < channels; c++) {
        int64_t accumulated = noise->offset[c], fractions = 0;
        for (uint32_t k = 0; k < channels; k++) {
            const int64_t whole = dsn_signed_sum(static_cast<uint32_t>(sums[k] >> 32)); /* floor, mod 2^32 */
            const int64_t fraction = static_cast<int64_t>(sums[k] & 0xFFFFFFFFu);
            accumulated += noise->gain[c * 3 + k] * whole;
            fractions += noise->gain[c * 3 + k] * fraction; /* |gain| < 2^29: each term below 2^61 */
        }
        accumulated += dsn_signed_sum(static_cast<uint32_t>(static_cast<uint64_t>(fractions) >> 32));
        out[c] = dsn_round_saturate(accumulated, noise->gain_shift);
    }
}

#if DSN_SMALL_CODE
/* Offset (Q32.32) from an impulse to the point along one axis, given the impulse's cell origin and its
   16-bit in-cell position; false when the impulse lies beyond the period (discarded, as in lattice mode).
   The point is at window index 1, that is at texton index 1 + base - p for an impulse at lattice p. */
bool impulse_offset(const PointAxis &point, const dsn_span &span, uint32_t cell_origin, uint32_t bits16,
                    int64_t *offset) {
    const uint32_t shift = point.axis.shift;
    if (cell_origin + (bits16 >> (16u - shift)) > span.last_position) return false;
    const uint32_t whole = 1u + span.base - point.axis.radius - cell_origin; /* X - cell origin, mod 2^32 */
    const int64_t in_cell = static_cast<int64_t>(static_cast<uint64_t>(bits16) << (16u + shift));
    *offset = static_cast<int64_t>(dsn_signed_sum(whole)) * static_cast<int64_t>(one_texel) +
              static_cast<int64_t>(point.fraction) - in_cell;
    return true;
}

/* Both steps along one axis: the texels that bracket the impulse (see bracket), or false when it lies
   beyond the period or out of reach. */
bool impulse_bracket(const PointAxis &point, const dsn_span &span, uint32_t cell_origin, uint32_t bits16,
                     uint32_t *lower_index, uint32_t *upper_weight) {
    int64_t offset;
    return impulse_offset(point, span, cell_origin, bits16, &offset) &&
           bracket(offset, point.axis.radius, lower_index, upper_weight);
}

/* Sums (Q.32, per channel) of the bilinear texton over every impulse of the cell (cell_x, cell_y). */
void add_cell(const dsn_noise_state *noise, const PointAxis &px, const dsn_span &span_x, uint32_t cell_x,
              const PointAxis &py, const dsn_span &span_y, uint32_t cell_y, uint64_t *sums) {
    const uint32_t key = dsn_cell_key(noise, cell_x, cell_y);
    const uint32_t count = dsn_cell_impulse_count(noise, key);
    const uint32_t origin_x = cell_x << noise->cell_shift, origin_y = cell_y << noise->cell_shift;
    for (uint32_t k = 0; k < count; k++) {
        const uint32_t hash = dsn_impulse_hash(noise, key, k);
        uint32_t row, row_weight, column, column_weight;
        if (impulse_bracket(py, span_y, origin_y, dsn_impulse_bits_y(hash), &row, &row_weight) &&
            impulse_bracket(px, span_x, origin_x, dsn_impulse_bits_x(hash), &column, &column_weight))
            add_bilinear(&noise->asset, row, row_weight, column, column_weight, sums);
    }
}

/* The small build: impulse by impulse, each through dsn_impulse_hash. */
void evaluate(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out) {
    uint64_t sums[DSN_MAX_CHANNELS] = {0, 0, 0};
    const uint32_t shift = noise->cell_shift;
    const PointAxis px = point_axis(x, noise->radius[0], shift, noise->period[0]);
    const PointAxis py = point_axis(y, noise->radius[1], shift, noise->period[1]);
    for (uint32_t sy = 0; sy < py.axis.span_count; sy++) {
        const dsn_span span_y = dsn_axis_span(&py.axis, sy);
        for (uint32_t sx = 0; sx < px.axis.span_count; sx++) {
            const dsn_span span_x = dsn_axis_span(&px.axis, sx);
            for (uint32_t j = 0; j < span_y.cell_count; j++)
                for (uint32_t i = 0; i < span_x.cell_count; i++)
                    add_cell(noise, px, span_x, dsn_span_cell(&span_x, i, shift), py, span_y,
                             dsn_span_cell(&span_y, j, shift), sums);
        }
    }
    normalize_q32(noise, sums, out);
}

#else
/* ---- Fast per point: the impulses sifted by their packed lattice fields ----
   The same impulses, offsets and weights as the small build's walk above (so the same bits; integer sums do
   not depend on the order), found with less work: each position pair is hashed once for all the impulses it
   holds, all of them are tested against the point at once on their lattice fields (which bound the 16-bit
   positions to within one texel), and only the candidates get their fraction hash and the exact test. */

/* Floor of value / 2^shift (1 <= shift <= 63) for a value far from the int64 limits, without shifting
   a negative number (implementation-defined): through a 2^63 bias, as dsn_round_saturate does. */
int64_t floor_shift(int64_t value, uint32_t shift) {
    const uint64_t bias = static_cast<uint64_t>(1) << 63;
    return static_cast<int64_t>((static_cast<uint64_t>(value) + bias) >> shift) -
           static_cast<int64_t>(bias >> shift);
}

/* The packed fields of one pair as SWAR lanes: 8 lanes of 8 bits (halves of 4 bits) or 4 of 16 (halves
   of 8 bits). A lane's top bit is above both halves' values, so a lane-wise subtraction of values below
   it never borrows from the next lane. */
struct FieldLanes {
    uint32_t field_shift, half_bits, per_pair;
    uint64_t ones, halves, tops; /* 1, the low half's mask, the top bit, in every lane */
};

FieldLanes field_lanes(uint32_t cell_shift) {
    FieldLanes lanes;
    lanes.field_shift = dsn_field_shift(cell_shift);
    lanes.half_bits = 1u << (lanes.field_shift - 1u);
    lanes.per_pair = 64u >> lanes.field_shift;
    lanes.ones = ~static_cast<uint64_t>(0) / ((static_cast<uint64_t>(1) << (1u << lanes.field_shift)) - 1u);
    lanes.halves = lanes.ones * ((1u << lanes.half_bits) - 1u);
    lanes.tops = lanes.ones << ((1u << lanes.field_shift) - 1u);
    return lanes;
}

/* One axis of one cell as seen from the point. An impulse at 16-bit in-cell position b has
   shifted = shifted_base - b 2^(16 + shift), the offset plus radius + 1 texels (bracket's `shifted`):
   it is in reach when 0 < shifted < reach_limit. Its field half h (the top half_bits bits of b) bounds
   b to [h, h + 1) 2^(16 - half_bits), that is the offset to within one texel: the halves in
   [low, high] (in every lane of low_lanes, and of high_lanes with the top bits set) are those that may
   be in reach and lie before the period's end. */
struct CellAxis {
    int64_t shifted_base;
    uint64_t low_lanes, high_lanes;
};

/* False when no impulse of the cell can reach the point along this axis. */
bool cell_axis(const PointAxis &point, const dsn_span &span, uint32_t cell, const FieldLanes &lanes,
               CellAxis *out) {
    const uint32_t shift = point.axis.shift, origin = cell << shift;
    const uint32_t whole = 1u + span.base - point.axis.radius - origin; /* as in impulse_offset */
    const int64_t reach_limit =
        static_cast<int64_t>(2u * point.axis.radius + 2u) * static_cast<int64_t>(one_texel);
    out->shifted_base = static_cast<int64_t>(dsn_signed_sum(whole)) * static_cast<int64_t>(one_texel) +
                        static_cast<int64_t>(point.fraction) +
                        static_cast<int64_t>(point.axis.radius + 1u) * static_cast<int64_t>(one_texel);
    /* With step = 2^(32 + shift - half_bits) (the offset's change per unit of h, at most one texel) and
       the rest of b taking less than a step: h is in reach only when h step < shifted_base and
       h step + step > shifted_base - reach_limit - step. */
    const uint32_t step_shift = 32u + shift - lanes.half_bits;
    const int64_t low = floor_shift(out->shifted_base - reach_limit, step_shift);
    int64_t high = floor_shift(out->shifted_base - 1, step_shift);
    /* The period: the lattice offset h >> (half_bits - shift) may not pass last_position - origin. */
    const uint32_t room = span.last_position - origin, below = lanes.half_bits - shift;
    const uint32_t last =
        room < (1u << shift) - 1u ? (room << below) | ((1u << below) - 1u) : (1u << lanes.half_bits) - 1u;
    if (high > static_cast<int64_t>(last)) high = static_cast<int64_t>(last);
    const uint32_t first = low < 0 ? 0u : static_cast<uint32_t>(low);
    if (high < static_cast<int64_t>(first)) return false;
    out->low_lanes = lanes.ones * first;
    out->high_lanes = (lanes.ones * static_cast<uint64_t>(high)) | lanes.tops;
    return true;
}

/* The lanes of a pair whose halves (x low, y high) may reach the point: their top bits. */
uint64_t candidate_lanes(uint64_t pair, const FieldLanes &lanes, const CellAxis &x, const CellAxis &y) {
    const uint64_t halves_x = pair & lanes.halves, halves_y = (pair >> lanes.half_bits) & lanes.halves;
    return ((halves_x | lanes.tops) - x.low_lanes) & (x.high_lanes - halves_x) &
           ((halves_y | lanes.tops) - y.low_lanes) & (y.high_lanes - halves_y) & lanes.tops;
}

/* Index of the lowest set bit of a non-zero word. */
inline uint32_t lowest_bit(uint64_t bits) {
#if defined(__GNUC__)
    return static_cast<uint32_t>(__builtin_ctzll(bits));
#else
    uint32_t index = 0;
    while ((bits & 1u) == 0) bits >>= 1, index++;
    return index;
#endif
}

/* Stored value (8- or 16-bit) plus 2^(8 Bytes - 1), as an unsigned number: flipping the sign bit of a
   two's-complement value (one operation; sign-extending it takes more). */
template <uint32_t Bytes>
inline int64_t biased_value(const unsigned char *at) {
    if (Bytes == 1) return static_cast<int64_t>(at[0] ^ 0x80u);
    return static_cast<int64_t>((at[0] | (static_cast<uint32_t>(at[1]) << 8)) ^ 0x8000u);
}

/* One channel of the bilinear texton (as add_bilinear) of the biased values, with its top-left texel at
   `top`, the texel right of it Stride bytes further, the row below at `bottom`: the weights add up to
   2^32, so it is the texton's plus 2^(32 + 8 Bytes - 1) exactly (the caller takes that off). The
   interpolation is rewritten with one product per step, (65536 - w) a + w b = 65536 a + w (b - a): the
   same integers. */
template <uint32_t Bytes, uint32_t Stride>
inline uint64_t bilinear_channel(const unsigned char *top, const unsigned char *bottom, int64_t across,
                                 int64_t down) {
    const int64_t top_left = biased_value<Bytes>(top), bottom_left = biased_value<Bytes>(bottom);
    const int64_t upper = top_left * 65536 + across * (biased_value<Bytes>(top + Stride) - top_left);
    const int64_t lower = bottom_left * 65536 + across * (biased_value<Bytes>(bottom + Stride) - bottom_left);
    return static_cast<uint64_t>(upper * 65536 + down * (lower - upper));
}

/* The candidates of up to 16 pairs (the usual point has 9 cells of 1 or 2 pairs) wait in a buffer and
   are visited all together: the loop over them then ends once per buffer rather than once per pair, and
   its end, hard to predict, is known long before (the reason of point.cpp's lattice walk too). Slot s
   holds a pair, its first impulse's fraction hash input (dsn_cell_stream's), its cell's axes, and its
   candidate lanes in bits 8 (s % 8) + lane of lanes[s / 8]. */
struct CandidateBuffer {
    uint64_t pairs[16];
    int64_t shifted_x[16], shifted_y[16];
    uint32_t streams[16];
    uint64_t lanes[2];
    uint32_t count;
};

/* The candidate lanes of a pair (top bits of the lanes) as one bit per lane, lane order: the multiplier
   moves lane i's top bit (at 2^field_shift (i + 1) - 1, shifted down to 2^field_shift i) to bit
   64 - per_pair + i, and no two of the products meet there. */
inline uint32_t gather_lanes(uint64_t candidates, const FieldLanes &lanes) {
    if (lanes.field_shift == 3) return static_cast<uint32_t>(((candidates >> 7) * 0x0102040810204080u) >> 56);
    return static_cast<uint32_t>(((candidates >> 15) * 0x1000200040008000u) >> 60);
}

/* Visits every buffered candidate: those in reach add their bilinear texton. Empties the buffer. */
template <uint32_t Channels, uint32_t Bytes>
void add_candidates(const dsn_noise_state *noise, const FieldLanes &lanes, CandidateBuffer *buffer,
                    uint64_t *sums) {
    const uint32_t half_mask = (1u << lanes.half_bits) - 1u, fraction_shift = lanes.half_bits;
    const uint32_t position_shift = 16u + noise->cell_shift, high_shift = 16u - lanes.half_bits;
    const uint64_t limit_x = static_cast<uint64_t>(2u * noise->radius[0] + 2u) * one_texel - 1u;
    const uint64_t limit_y = static_cast<uint64_t>(2u * noise->radius[1] + 2u) * one_texel - 1u;
    const uint32_t width = noise->asset.width, height = noise->asset.height;
    const unsigned char *texton = noise->asset.texton;
    /* Interior texels go to local sums (kept in registers), those at the edge through add_bilinear. */
    uint64_t interior[DSN_MAX_CHANNELS] = {0, 0, 0}, border[DSN_MAX_CHANNELS] = {0, 0, 0};
    uint64_t interior_count = 0;
    for (uint32_t word = 0; word < 2; word++) {
        for (uint64_t bits = buffer->lanes[word]; bits != 0; bits &= bits - 1u) {
            const uint32_t bit = lowest_bit(bits), slot = 8u * word + (bit >> 3), lane = bit & 7u;
            const uint32_t field = dsn_pair_bits(buffer->pairs[slot], lane << lanes.field_shift);
            const uint32_t fraction = dsn_mix32(buffer->streams[slot] + lane * 0x9E3779B9u);
            /* dsn_impulse_hash's 16-bit positions */
            const uint32_t bits_x =
                ((field & half_mask) << high_shift) | ((fraction & 0xFFFFu) >> fraction_shift);
            const uint32_t bits_y = (((field >> lanes.half_bits) & half_mask) << high_shift) |
                                    ((fraction >> 16) >> fraction_shift);
            /* bracket's shifted values, in reach when in (0, 2 radius + 2 texels): one unsigned test each */
            const uint64_t shifted_x = static_cast<uint64_t>(buffer->shifted_x[slot]) -
                                       (static_cast<uint64_t>(bits_x) << position_shift);
            const uint64_t shifted_y = static_cast<uint64_t>(buffer->shifted_y[slot]) -
                                       (static_cast<uint64_t>(bits_y) << position_shift);
            if (shifted_x - 1u >= limit_x || shifted_y - 1u >= limit_y) continue;
            const uint32_t row = static_cast<uint32_t>(shifted_y >> 32) - 1u,
                           column = static_cast<uint32_t>(shifted_x >> 32) - 1u;
            const int64_t down = static_cast<int64_t>((shifted_y >> 16) & 0xFFFFu),
                          across = static_cast<int64_t>((shifted_x >> 16) & 0xFFFFu);
            if (row < height - 1u && column < width - 1u) { /* -1 (0xFFFFFFFF) fails too */
                const unsigned char *top = texton + (row * width + column) * Channels * Bytes;
                const unsigned char *bottom = top + width * Channels * Bytes;
                interior_count++;
                interior[0] += bilinear_channel<Bytes, Channels * Bytes>(top, bottom, across, down);
                if (Channels == 3) {
                    interior[1] +=
                        bilinear_channel<Bytes, Channels * Bytes>(top + Bytes, bottom + Bytes, across, down);
                    interior[2] += bilinear_channel<Bytes, Channels * Bytes>(
                        top + 2 * Bytes, bottom + 2 * Bytes, across, down);
                }
            } else {
                add_bilinear(&noise->asset, row, static_cast<uint32_t>(down), column,
                             static_cast<uint32_t>(across), border);
            }
        }
        buffer->lanes[word] = 0;
    }
    buffer->count = 0;
    /* The interior sums were of biased values: each bilinear texton 2^(32 + 8 Bytes - 1) too high. */
    for (uint32_t c = 0; c < Channels; c++)
        sums[c] += interior[c] - (interior_count << (31u + 8u * Bytes)) + border[c];
}

/* Buffers the candidates of every pair of the cell with this key (visiting the buffer when full). */
template <uint32_t Channels, uint32_t Bytes>
void add_cell_fast(const dsn_noise_state *noise, uint32_t key, const FieldLanes &lanes, const CellAxis &x,
                   const CellAxis &y, CandidateBuffer *buffer, uint64_t *sums) {
    const uint32_t count = dsn_cell_impulse_count(noise, key);
    for (uint32_t first = 0; first < count; first += lanes.per_pair) {
        if (buffer->count == 16) add_candidates<Channels, Bytes>(noise, lanes, buffer, sums);
        const uint32_t slot = buffer->count++;
        const uint64_t pair = dsn_position_pair(key, first >> (6u - lanes.field_shift));
        uint32_t candidates = gather_lanes(candidate_lanes(pair, lanes, x, y), lanes);
        const uint32_t present = count - first;
        if (present < lanes.per_pair) candidates &= (1u << present) - 1u; /* impulses that do not exist */
        buffer->pairs[slot] = pair;
        buffer->shifted_x[slot] = x.shifted_base;
        buffer->shifted_y[slot] = y.shifted_base;
        buffer->streams[slot] = key + (0x80000000u + first) * 0x9E3779B9u;
        buffer->lanes[slot >> 3] |= static_cast<uint64_t>(candidates) << (8u * (slot & 7u));
    }
}

template <uint32_t Channels, uint32_t Bytes>
void evaluate_fast(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out) {
    uint64_t sums[DSN_MAX_CHANNELS] = {0, 0, 0};
    const uint32_t shift = noise->cell_shift;
    const FieldLanes lanes = field_lanes(shift);
    const PointAxis px = point_axis(x, noise->radius[0], shift, noise->period[0]);
    const PointAxis py = point_axis(y, noise->radius[1], shift, noise->period[1]);
    CandidateBuffer buffer;
    buffer.lanes[0] = buffer.lanes[1] = 0;
    buffer.count = 0;
    for (uint32_t sy = 0; sy < py.axis.span_count; sy++) {
        const dsn_span span_y = dsn_axis_span(&py.axis, sy);
        for (uint32_t j = 0; j < span_y.cell_count; j++) {
            const uint32_t cell_y = dsn_span_cell(&span_y, j, shift);
            CellAxis in_y;
            if (!cell_axis(py, span_y, cell_y, lanes, &in_y)) continue;
            const uint32_t row_key = dsn_row_key(noise, cell_y);
            for (uint32_t sx = 0; sx < px.axis.span_count; sx++) {
                const dsn_span span_x = dsn_axis_span(&px.axis, sx);
                for (uint32_t i = 0; i < span_x.cell_count; i++) {
                    const uint32_t cell_x = dsn_span_cell(&span_x, i, shift);
                    CellAxis in_x;
                    if (cell_axis(px, span_x, cell_x, lanes, &in_x))
                        add_cell_fast<Channels, Bytes>(noise, dsn_cell_key_in_row(noise, cell_x, row_key),
                                                       lanes, in_x, in_y, &buffer, sums);
                }
            }
        }
    }
    add_candidates<Channels, Bytes>(noise, lanes, &buffer, sums);
    normalize_q32(noise, sums, out);
}

/* The fast build evaluates through the sifting walk, one copy per channel count and value size. */
void evaluate(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out) {
    const dsn_asset *asset = &noise->asset;
    if (asset->channels == 3)
        asset->bits == 8 ? evaluate_fast<3, 1>(noise, x, y, out) : evaluate_fast<3, 2>(noise, x, y, out);
    else
        asset->bits == 8 ? evaluate_fast<1, 1>(noise, x, y, out) : evaluate_fast<1, 2>(noise, x, y, out);
}
#endif /* DSN_SMALL_CODE */

int continuous_check(const dsn_noise_state *noise) {
    if (noise == 0 || noise->asset.texton == 0) return DSN_ERR_NULL;
    if (noise->asset.interpolation != DSN_INTERPOLATION_BILINEAR &&
        (noise->flags & DSN_FLAG_ALLOW_LATTICE_CONTINUOUS) == 0)
        return DSN_ERR_CONTINUOUS_MISMATCH;
    return DSN_OK;
}

void zero(int32_t *out, uint32_t count) {
    for (uint32_t i = 0; i < count; i++) out[i] = 0;
}

int check_tile(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
               const void *out) {
    const int err = continuous_check(noise);
    if (err != DSN_OK) return err;
    if (grid == 0 || out == 0) return DSN_ERR_NULL;
    if (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE)
        return DSN_ERR_TILE_SIZE;
    return DSN_OK;
}

#if !DSN_SMALL_CODE
/* ---- Fast path: splatting the impulses of an axis-aligned grid ----
   For a grid with steps (a, 0) and (0, b), a, b > 0, and no period, each impulse of the cells around
   the grid adds its bilinear texton to the pixels it reaches, into per-pixel sums held in the scratch
   buffer. Pixel by pixel these are the per-point sums exactly: the same impulses (every impulse that
   reaches a pixel lies in those cells, each cell is visited once), the same offset d (x - p modulo 2^64,
   which is what the per-point path computes for any impulse within reach), the same weights, and
   integer sums do not depend on the order. Used when it is cheaper than per point: when one pixel
   covers less area than the cells a point visits. */

struct SplatAxis {
    uint64_t origin, step;  /* Q32.32 */
    uint32_t count, radius; /* pixels along the axis, texton radius */
    uint32_t first_cell, cell_count;
};

int64_t floor_divide(int64_t numerator, int64_t denominator) { /* denominator > 0 */
    const int64_t quotient = numerator / denominator;
    return (quotient * denominator > numerator) ? quotient - 1 : quotient;
}

/* The grid spans < 2^30 texels along the axis (so every offset below fits an int64 with room to spare). */
bool splat_axis(SplatAxis *axis, int64_t origin, int64_t step, uint32_t count, uint32_t radius,
                uint32_t shift) {
    if (step <= 0 || static_cast<uint64_t>(step) > (static_cast<uint64_t>(1) << 62) / count) return false;
    axis->origin = static_cast<uint64_t>(origin);
    axis->step = static_cast<uint64_t>(step);
    axis->count = count;
    axis->radius = radius;
    const uint64_t last_point = axis->origin + axis->step * (count - 1u);
    const uint32_t low = static_cast<uint32_t>(axis->origin >> 32) - radius - 1u;
    const uint32_t high = static_cast<uint32_t>(last_point >> 32) + radius + 1u;
    axis->first_cell = low >> shift;
    axis->cell_count = ((high - low + (low & ((1u << shift) - 1u))) >> shift) + 1u;
    return true;
}

/* The pixels [*first, *last] whose points may lie within radius + 1 of the impulse at p (a superset:
   bracket() decides exactly); false when there are none. */
bool splat_range(const SplatAxis &axis, uint64_t position, uint32_t *first, uint32_t *last) {
    const int64_t relative = signed_from_bits(position - axis.origin);
    const int64_t reach = static_cast<int64_t>(axis.radius + 1u) * static_cast<int64_t>(one_texel);
    const int64_t step = static_cast<int64_t>(axis.step);
    const int64_t low = floor_divide(relative - reach, step), high = floor_divide(relative + reach, step) + 1;
    if (high < 0 || low >= static_cast<int64_t>(axis.count)) return false;
    *first = low < 0 ? 0u : static_cast<uint32_t>(low);
    *last = high >= static_cast<int64_t>(axis.count) ? axis.count - 1u : static_cast<uint32_t>(high);
    return true;
}

/* Offset (Q32.32) from the impulse at `position` to pixel `index` of the axis. */
int64_t splat_offset(const SplatAxis &axis, uint32_t index, uint64_t position) {
    return signed_from_bits(axis.origin + axis.step * index - position);
}

/* Both axes, or false when the grid does not qualify (rotation, period, too sparse, too large). */
bool splat_axes(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                SplatAxis *x, SplatAxis *y) {
    const uint32_t shift = noise->cell_shift;
    if (grid->column_step_y != 0 || grid->row_step_x != 0 || noise->period[0] != 0 || noise->period[1] != 0)
        return false;
    if (!splat_axis(x, grid->origin_x, grid->column_step_x, width, noise->radius[0], shift) ||
        !splat_axis(y, grid->origin_y, grid->row_step_y, height, noise->radius[1], shift))
        return false;
    /* Per point, a point visits about (2r + 2 + cell)^2 texels of impulses; a pixel here a * b. */
    const uint64_t visited_x = 2u * noise->radius[0] + 2u + (1u << shift);
    const uint64_t visited_y = 2u * noise->radius[1] + 2u + (1u << shift);
    return (x->step >> 16) * (y->step >> 16) <= (visited_x * visited_y) << 32;
}

size_t splat_scratch_size(const dsn_noise_state *noise, uint32_t width, uint32_t height) {
    const uint64_t bytes = static_cast<uint64_t>(width) * height * noise->asset.channels * sizeof(uint64_t);
    const uint64_t alignment_slack = sizeof(uint64_t) - 1u;
    if (bytes + alignment_slack > static_cast<size_t>(-1)) return 0; /* too large here: per point */
    return static_cast<size_t>(bytes + alignment_slack);
}

/* The scratch as an array of uint64, aligned (the caller's buffer needs no alignment). */
uint64_t *aligned_sums(void *scratch) {
    unsigned char *bytes = static_cast<unsigned char *>(scratch);
    const uintptr_t misalignment = reinterpret_cast<uintptr_t>(bytes) % sizeof(uint64_t);
    return static_cast<uint64_t *>(
        static_cast<void *>(bytes + (misalignment ? sizeof(uint64_t) - misalignment : 0u)));
}

void splat_impulse(const dsn_noise_state *noise, const SplatAxis &x, const SplatAxis &y, uint64_t position_x,
                   uint64_t position_y, uint64_t *sums) {
    uint32_t first_i, last_i, first_j, last_j;
    if (!splat_range(x, position_x, &first_i, &last_i) || !splat_range(y, position_y, &first_j, &last_j))
        return;
    const uint32_t channels = noise->asset.channels;
    for (uint32_t j = first_j; j <= last_j; j++) {
        uint32_t row, row_weight;
        if (!bracket(splat_offset(y, j, position_y), noise->radius[1], &row, &row_weight)) continue;
        for (uint32_t i = first_i; i <= last_i; i++) {
            uint32_t column, column_weight;
            if (!bracket(splat_offset(x, i, position_x), noise->radius[0], &column, &column_weight)) continue;
            add_bilinear(&noise->asset, row, row_weight, column, column_weight,
                         sums + (static_cast<size_t>(j) * x.count + i) * channels);
        }
    }
}

void splat_grid(const dsn_noise_state *noise, const SplatAxis &x, const SplatAxis &y, uint64_t *sums) {
    const uint32_t shift = noise->cell_shift, cell_mask = 0xFFFFFFFFu >> shift;
    for (uint32_t cy = 0; cy < y.cell_count; cy++)
        for (uint32_t cx = 0; cx < x.cell_count; cx++) {
            const uint32_t cell_x = (x.first_cell + cx) & cell_mask, cell_y = (y.first_cell + cy) & cell_mask;
            const uint32_t key = dsn_cell_key(noise, cell_x, cell_y);
            const uint32_t count = dsn_cell_impulse_count(noise, key);
            const uint64_t origin_x = static_cast<uint64_t>(cell_x << shift) << 32;
            const uint64_t origin_y = static_cast<uint64_t>(cell_y << shift) << 32;
            for (uint32_t k = 0; k < count; k++) {
                const uint32_t hash = dsn_impulse_hash(noise, key, k);
                splat_impulse(noise, x, y,
                              origin_x + (static_cast<uint64_t>(dsn_impulse_bits_x(hash)) << (16u + shift)),
                              origin_y + (static_cast<uint64_t>(dsn_impulse_bits_y(hash)) << (16u + shift)),
                              sums);
            }
        }
}

#endif /* !DSN_SMALL_CODE */

/* Evaluates every grid point in order into `out`: by splatting when the grid qualifies (not in the
   small build), else point by point. */
int evaluate_grid(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                  void *out, dsn_output_kind kind, void *scratch, size_t scratch_size) {
    const int err = check_tile(noise, grid, width, height, out);
    if (err != DSN_OK) return err;
    const uint32_t channels = noise->asset.channels;
    int32_t pixel[DSN_MAX_CHANNELS];
#if !DSN_SMALL_CODE
    SplatAxis x, y;
    const size_t needed =
        splat_axes(noise, grid, width, height, &x, &y) ? splat_scratch_size(noise, width, height) : 0;
    if (needed != 0) {
        if (scratch == 0 || scratch_size < needed) return DSN_ERR_SCRATCH;
        uint64_t *sums = aligned_sums(scratch);
        const size_t values = static_cast<size_t>(width) * height * channels;
        for (size_t i = 0; i < values; i++) sums[i] = 0;
        splat_grid(noise, x, y, sums);
        for (size_t p = 0; p < values; p += channels) {
            normalize_q32(noise, sums + p, pixel);
            dsn_store_pixel(out, kind, p, pixel, channels);
        }
        return DSN_OK;
    }
#else
    (void)scratch;
    (void)scratch_size;
#endif
    /* Pixel (i, j) is origin + i column_step + j row_step modulo 2^64: stepping adds the same values. */
    uint64_t row_x = static_cast<uint64_t>(grid->origin_x), row_y = static_cast<uint64_t>(grid->origin_y);
    size_t index = 0;
    for (uint32_t j = 0; j < height; j++) {
        uint64_t point_x = row_x, point_y = row_y;
        for (uint32_t i = 0; i < width; i++, index += channels) {
            evaluate(noise, point_x, point_y, pixel);
            dsn_store_pixel(out, kind, index, pixel, channels);
            point_x += static_cast<uint64_t>(grid->column_step_x);
            point_y += static_cast<uint64_t>(grid->column_step_y);
        }
        row_x += static_cast<uint64_t>(grid->row_step_x);
        row_y += static_cast<uint64_t>(grid->row_step_y);
    }
    return DSN_OK;
}

} // namespace

extern "C" {

int64_t dsn_coordinate_from_double(double value) {
    const uint64_t bits = bits_of<uint64_t>(value);
    const uint32_t exponent = static_cast<uint32_t>(bits >> 52) & 0x7FFu;
    const uint64_t fraction = bits & 0xFFFFFFFFFFFFFu;
    if (exponent == 0x7FFu) return 0; /* NaN, +-Inf */
    const uint64_t mantissa = exponent == 0 ? fraction : (fraction | (static_cast<uint64_t>(1) << 52));
    const int32_t power = (exponent == 0 ? 1 : static_cast<int32_t>(exponent)) - 1075;
    return coordinate_from_parts((bits >> 63) != 0, mantissa, power);
}

int64_t dsn_coordinate_from_float(float value) {
    const uint32_t bits = bits_of<uint32_t>(value);
    const uint32_t exponent = (bits >> 23) & 0xFFu;
    const uint32_t fraction = bits & 0x7FFFFFu;
    if (exponent == 0xFFu) return 0; /* NaN, +-Inf */
    const uint32_t mantissa = exponent == 0 ? fraction : (fraction | (1u << 23));
    const int32_t power = (exponent == 0 ? 1 : static_cast<int32_t>(exponent)) - 150;
    return coordinate_from_parts((bits >> 31) != 0, mantissa, power);
}

int dsn_continuous_check(const dsn_noise *handle) { return continuous_check(dsn_state(handle)); }

int dsn_continuous_point_fixed(const dsn_noise *handle, int64_t x, int64_t y, int32_t *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    const int err = continuous_check(noise);
    if (err != DSN_OK) {
        zero(out, noise == 0 ? 1u : noise->asset.channels);
        return err;
    }
    evaluate(noise, static_cast<uint64_t>(x), static_cast<uint64_t>(y), out);
    return DSN_OK;
}

int dsn_continuous_point_float(const dsn_noise *handle, double x, double y, float *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    int32_t fixed[DSN_MAX_CHANNELS] = {0, 0, 0};
    if (out == 0) return DSN_ERR_NULL;
    const int err = dsn_continuous_point_fixed(handle, dsn_coordinate_from_double(x),
                                               dsn_coordinate_from_double(y), fixed);
    dsn_store_pixel(out, dsn_output_float, 0, fixed, noise == 0 ? 1u : noise->asset.channels);
    return err;
}

size_t dsn_continuous_tile_scratch_size(const dsn_noise *handle, const dsn_grid *grid, uint32_t width,
                                        uint32_t height) {
    const dsn_noise_state *noise = dsn_state(handle);
#if DSN_SMALL_CODE
    (void)noise, (void)grid, (void)width, (void)height;
    return 0; /* point by point: no scratch */
#else
    SplatAxis x, y;
    if (check_tile(noise, grid, width, height, grid) != DSN_OK) return 0;
    return splat_axes(noise, grid, width, height, &x, &y) ? splat_scratch_size(noise, width, height) : 0;
#endif
}

int dsn_continuous_tile_fixed(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height,
                              int32_t *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return evaluate_grid(noise, grid, width, height, out, dsn_output_fixed, scratch, scratch_size);
}

int dsn_continuous_tile_float(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height,
                              float *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return evaluate_grid(noise, grid, width, height, out, dsn_output_float, scratch, scratch_size);
}

int dsn_continuous_tile_u8(const dsn_noise *handle, const dsn_grid *grid, uint32_t width, uint32_t height,
                           uint8_t *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return evaluate_grid(noise, grid, width, height, out, dsn_output_u8, scratch, scratch_size);
}

} // extern "C"
