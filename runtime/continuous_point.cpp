/* runtime/continuous_point.cpp - the continuous mode at one point: the impulses of the cells around it,
   each adding its bilinear texton (bilinear_texton.h) to the channel sums. With DSN_SMALL_CODE (dsn.h) a
   point walks its impulses one by one; the fast build sifts them on their packed lattice fields first
   (evaluate_fast) and, on SSE2, interpolates 8-bit textons on vectors; kernels built for AVX2 have their
   own copy for the usual noises (continuous_point_vector.h). Also the API's mode check and
   per-point functions. */
#include "bilinear_texton.h"
#include "cell_walk.h"
#include "continuous_internal.h"
#include "continuous_sift.h"
#include "impulse_position.h"
#include "kernels.h"
#include "normalize_fixed.h"
#include "poisson_count.h"

#if !DSN_SMALL_CODE && defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace {

/* ---- Walking the impulses around one point ---- */

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

} // namespace

/* The small build: impulse by impulse, each through dsn_impulse_hash. */
void dsn_internal_continuous_point(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out) {
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

namespace {

#else
/* ---- Fast per point: the impulses sifted by their packed lattice fields ----
   The same impulses, offsets and weights as the small build's walk above (so the same bits; integer sums do
   not depend on the order), found with less work: each position pair is hashed once for all the impulses it
   holds, all of them are tested against the point at once on their lattice fields (which bound the 16-bit
   positions to within one texel), and only the candidates get their fraction hash and the exact test. */

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

/* The bilinear texton of every channel, as add_bilinear computes it, for 2 x 2 texels that may leave the
   window (zero there): the same integers, each texel read with its own bounds test. */
template <uint32_t Channels, uint32_t Bytes>
inline void add_border(const unsigned char *texton, uint32_t width, uint32_t height, uint32_t row,
                       uint32_t column, int64_t across, int64_t down, uint64_t *sums) {
    int64_t corners[4][DSN_MAX_CHANNELS];
    for (uint32_t corner = 0; corner < 4; corner++) {
        const uint32_t at_row = row + (corner >> 1), at_column = column + (corner & 1u);
        const bool inside = at_row < height && at_column < width; /* -1 (0xFFFFFFFF) is outside too */
        const unsigned char *at = texton + (inside ? (at_row * width + at_column) * Channels * Bytes : 0u);
        for (uint32_t c = 0; c < Channels; c++)
            corners[corner][c] =
                inside ? biased_value<Bytes>(at + c * Bytes) - (static_cast<int64_t>(1) << (8u * Bytes - 1u))
                       : 0;
    }
    for (uint32_t c = 0; c < Channels; c++) {
        const int64_t upper = (65536 - across) * corners[0][c] + across * corners[1][c];
        const int64_t lower = (65536 - across) * corners[2][c] + across * corners[3][c];
        sums[c] += static_cast<uint64_t>((65536 - down) * upper + down * lower);
    }
}

#if defined(__SSE2__)
/* ---- The bilinear texton of 8-bit values on SSE2 vectors ----
   The same integers as bilinear_channel, exactly, with every channel at once. The biased values v
   (0..255) of the two texels of a row sit in 16-bit lanes as pairs (left, right), one pair per
   channel; the row's interpolation (65536 - across) left + across right is a dot product with the
   weight pair, each weight w split as 128 (w >> 7) + (w & 127) so that both parts fit signed 16-bit
   lanes (w >> 7 <= 512): two _mm_madd_epi16, exact in 32 bits (below 2^24). The column's interpolation
   (65536 - down) upper + down lower, below 2^41, takes 64-bit lanes (_mm_mul_epu32, unsigned: every
   term is non-negative). Reads: 8 bytes from a row's first texel (RGB: the 6 needed and 2 more) or 4
   (grey: 2 and 2 more); past the texton's last row they reach at most 2 bytes into the asset's 4-byte
   CRC, which the loader guarantees lies in the buffer right after the texton (format.h: total_size). */
struct BilinearSums {
    __m128i even, odd; /* 64-bit lanes: channels 0 and 2; channel 1 (RGB) or the lower row (grey) */
};

/* A row's texels as (left, right) 16-bit pairs of biased values, one pair per channel (lanes past the
   channels hold garbage, never used). */
template <uint32_t Channels>
inline __m128i row_pairs(const unsigned char *row) {
    __m128i bytes;
    if (Channels == 3) {
        bytes = _mm_loadl_epi64(static_cast<const __m128i *>(static_cast<const void *>(row)));
    } else {
        uint32_t word;
        __builtin_memcpy(&word, row, sizeof word);
        bytes = _mm_cvtsi32_si128(static_cast<int>(word)); /* the bits unchanged */
    }
    const __m128i values = _mm_unpacklo_epi8(_mm_xor_si128(bytes, _mm_set1_epi8(-128)), _mm_setzero_si128());
    /* grey: (left, right) already; RGB: left channels in lanes 0-2, right ones in lanes 3-5 */
    return Channels == 3 ? _mm_unpacklo_epi16(values, _mm_srli_si128(values, 6)) : values;
}

/* A weight pair (65536 - w, w) as its two parts: high parts (w >> 7) and low parts (w & 127), each
   broadcast as a (left, right) pair of 16-bit lanes. */
inline void weight_parts(uint32_t weight, __m128i *high, __m128i *low) {
    const uint32_t left = 65536u - weight;
    *high = _mm_set1_epi32(static_cast<int>((left >> 7) | ((weight >> 7) << 16)));
    *low = _mm_set1_epi32(static_cast<int>((left & 127u) | ((weight & 127u) << 16)));
}

/* (65536 - w) left + w right of every pair, in 32-bit lanes. */
inline __m128i interpolate_pairs(__m128i pairs, __m128i high, __m128i low) {
    return _mm_add_epi32(_mm_slli_epi32(_mm_madd_epi16(pairs, high), 7), _mm_madd_epi16(pairs, low));
}

template <uint32_t Channels>
inline void add_bilinear_vector(const unsigned char *top, const unsigned char *bottom, uint32_t across,
                                uint32_t down, BilinearSums *sums) {
    __m128i high, low;
    weight_parts(across, &high, &low);
    const __m128i down_weights = _mm_set_epi32(0, static_cast<int>(down), 0, static_cast<int>(65536u - down));
    if (Channels == 3) {
        const __m128i upper = interpolate_pairs(row_pairs<3>(top), high, low);
        const __m128i lower = interpolate_pairs(row_pairs<3>(bottom), high, low);
        const __m128i up_weight = _mm_shuffle_epi32(down_weights, 0x00),
                      down_weight = _mm_shuffle_epi32(down_weights, 0xAA);
        sums->even = _mm_add_epi64(
            sums->even, _mm_add_epi64(_mm_mul_epu32(upper, up_weight), _mm_mul_epu32(lower, down_weight)));
        sums->odd =
            _mm_add_epi64(sums->odd, _mm_add_epi64(_mm_mul_epu32(_mm_srli_epi64(upper, 32), up_weight),
                                                   _mm_mul_epu32(_mm_srli_epi64(lower, 32), down_weight)));
    } else {
        /* lanes: upper, lower; spread to 64-bit lanes, each times its weight */
        const __m128i rows =
            interpolate_pairs(_mm_unpacklo_epi32(row_pairs<1>(top), row_pairs<1>(bottom)), high, low);
        sums->even = _mm_add_epi64(sums->even, _mm_mul_epu32(_mm_shuffle_epi32(rows, 0x10), down_weights));
    }
}

/* The channel sums of the vector's lanes (modulo 2^64). */
template <uint32_t Channels>
inline void take_bilinear_sums(const BilinearSums &sums, uint64_t *out) {
    uint64_t even[2], odd[2];
    __builtin_memcpy(even, &sums.even, sizeof even);
    __builtin_memcpy(odd, &sums.odd, sizeof odd);
    if (Channels == 3) {
        out[0] = even[0], out[1] = odd[0], out[2] = even[1];
    } else {
        out[0] = even[0] + even[1];
    }
}
#endif

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
    /* Interior texels go to local sums (kept in registers; 8-bit ones in vectors on SSE2), those at the
       edge through add_border. */
    uint64_t interior[DSN_MAX_CHANNELS] = {0, 0, 0}, border[DSN_MAX_CHANNELS] = {0, 0, 0};
    uint64_t interior_count = 0;
#if defined(__SSE2__)
    BilinearSums vector_sums = {_mm_setzero_si128(), _mm_setzero_si128()};
#endif
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
#if defined(__SSE2__)
                if (Bytes == 1) {
                    add_bilinear_vector<Channels>(top, bottom, static_cast<uint32_t>(across),
                                                  static_cast<uint32_t>(down), &vector_sums);
                    continue;
                }
#endif
                interior[0] += bilinear_channel<Bytes, Channels * Bytes>(top, bottom, across, down);
                if (Channels == 3) {
                    interior[1] +=
                        bilinear_channel<Bytes, Channels * Bytes>(top + Bytes, bottom + Bytes, across, down);
                    interior[2] += bilinear_channel<Bytes, Channels * Bytes>(
                        top + 2 * Bytes, bottom + 2 * Bytes, across, down);
                }
            } else {
                add_border<Channels, Bytes>(texton, width, height, row, column, across, down, border);
            }
        }
        buffer->lanes[word] = 0;
    }
    buffer->count = 0;
#if defined(__SSE2__)
    if (Bytes == 1) {
        uint64_t vector_interior[DSN_MAX_CHANNELS];
        take_bilinear_sums<Channels>(vector_sums, vector_interior);
        for (uint32_t c = 0; c < Channels; c++) interior[c] += vector_interior[c];
    }
#endif
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

} // namespace

/* The fast build evaluates through the kernel's vector evaluator where it has one that takes the noise
   (continuous_point_vector.h), else through the sifting walk, one copy per channel count and value size. */
void dsn_internal_continuous_point(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out) {
    dsn_continuous_point_entry *vector = dsn_kernel_entries_of(noise->tile_kernel)->continuous_point;
    if (vector != 0 && vector(noise, x, y, out)) return;
    const dsn_asset *asset = &noise->asset;
    if (asset->channels == 3)
        asset->bits == 8 ? evaluate_fast<3, 1>(noise, x, y, out) : evaluate_fast<3, 2>(noise, x, y, out);
    else
        asset->bits == 8 ? evaluate_fast<1, 1>(noise, x, y, out) : evaluate_fast<1, 2>(noise, x, y, out);
}

namespace {
#endif /* DSN_SMALL_CODE */

/* The number of values a call writes: the noise's channels, or, for a noise with none (null, never
   configured, failed), the one value that every caller's array has, zeroed. */
uint32_t values_written(const dsn_noise_state *noise) {
    return noise == 0 || noise->asset.channels == 0 ? 1u : noise->asset.channels;
}

} // namespace

int dsn_internal_continuous_check(const dsn_noise_state *noise) {
    if (noise == 0 || noise->asset.texton == 0) return DSN_ERR_NULL;
    if (noise->asset.interpolation != DSN_INTERPOLATION_BILINEAR &&
        (noise->flags & DSN_FLAG_ALLOW_LATTICE_CONTINUOUS) == 0)
        return DSN_ERR_CONTINUOUS_MISMATCH;
    return DSN_OK;
}

int dsn_internal_continuous_point_float(const dsn_noise *handle, int64_t x, int64_t y, float *out) {
    int32_t fixed[DSN_MAX_CHANNELS] = {0, 0, 0};
    if (out == 0) return DSN_ERR_NULL;
    const int err = dsn_continuous_point_fixed(handle, x, y, fixed);
    dsn_store_pixel(out, dsn_output_float, 0, fixed, values_written(dsn_state(handle)));
    return err;
}

extern "C" {

int dsn_continuous_check(const dsn_noise *handle) { return dsn_internal_continuous_check(dsn_state(handle)); }

int dsn_continuous_point_fixed(const dsn_noise *handle, int64_t x, int64_t y, int32_t *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    const int err = dsn_internal_continuous_check(noise);
    if (err != DSN_OK) {
        for (uint32_t c = 0; c < values_written(noise); c++) out[c] = 0;
        return err;
    }
    dsn_internal_continuous_point(noise, static_cast<uint64_t>(x), static_cast<uint64_t>(y), out);
    return DSN_OK;
}

int dsn_continuous_point_float(const dsn_noise *handle, double x, double y, float *out) {
    return dsn_internal_continuous_point_float(handle, dsn_coordinate_from_double(x),
                                               dsn_coordinate_from_double(y), out);
}

} // extern "C"
