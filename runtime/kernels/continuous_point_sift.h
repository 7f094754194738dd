/* runtime/kernels/continuous_point_sift.h - the continuous mode at one point by the sifting walk, as a
   kernel (kernels.h: each kernel file includes it, so it is built once per instruction set): every noise
   of the fast build, the vector evaluator aside (continuous_point_vector.h takes the usual ones in the
   AVX2 and AVX-512 kernels). Internal to libdsn; not installed (everything here has internal linkage). */
#ifndef DSN_CONTINUOUS_POINT_SIFT_H
#define DSN_CONTINUOUS_POINT_SIFT_H

#include "core/bilinear_texton.h"
#include "core/cell_walk.h"
#include "core/continuous_internal.h"
#include "core/continuous_sift.h"
#include "core/impulse_position.h"
#include "core/poisson_count.h"
#include "kernels/bilinear_read.h"
#include "kernels/continuous_point_vector.h"
#include "kernels/kernels.h"

#if !DSN_SMALL_CODE
namespace {

/* ---- Fast per point: the impulses sifted by their packed lattice fields ----
   The same impulses, offsets and weights as the small build's walk above (so the same bits; integer sums do
   not depend on the order), found with less work: each position pair is hashed once for all the impulses it
   holds, all of them are tested against the point at once on their lattice fields (which bound the 16-bit
   positions to within one texel), and only the candidates get their fraction hash and the exact test.
   The texels are read by bilinear_read.h. */

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

/* What a candidate in reach adds, one type per output: ValueRead sums the bilinear texton (the value),
   SlopeRead the value and its two partial derivatives (the gradient). A reader lives for one visit of
   the buffer, so that its sums stay in registers, and then takes them into the point's (`Sums`). */
struct ValueSums {
    uint64_t value[DSN_MAX_CHANNELS];
};

template <uint32_t Channels, uint32_t Bytes>
struct ValueRead {
    typedef ValueSums Sums;
    static const uint32_t channels = Channels, bytes = Bytes;
    static const bool entry_edge = false; /* see SlopeRead */
    /* Interior texels go to local sums (8-bit ones in vectors on SSE2), those at the edge through
       add_border. */
    uint64_t interior[DSN_MAX_CHANNELS], border[DSN_MAX_CHANNELS];
    uint64_t interior_count;
#if defined(__SSE2__)
    BilinearSums vector_sums;
#endif

    ValueRead() : interior_count(0) {
        for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) interior[c] = border[c] = 0;
#if defined(__SSE2__)
        vector_sums.even = vector_sums.odd = zero_128();
#endif
    }

    /* 2 x 2 texels inside the window: `top` the top-left one, `bottom` the one below it. */
    void add_interior(const unsigned char *top, const unsigned char *bottom, int64_t across, int64_t down) {
        interior_count++;
#if defined(__SSE2__)
        if (Bytes == 1) {
            add_bilinear_vector<Channels>(top, bottom, static_cast<uint32_t>(across),
                                          static_cast<uint32_t>(down), &vector_sums);
            return;
        }
#endif
        interior[0] += bilinear_channel<Bytes, Channels * Bytes>(top, bottom, across, down);
        if (Channels == 3) {
            interior[1] +=
                bilinear_channel<Bytes, Channels * Bytes>(top + Bytes, bottom + Bytes, across, down);
            interior[2] +=
                bilinear_channel<Bytes, Channels * Bytes>(top + 2 * Bytes, bottom + 2 * Bytes, across, down);
        }
    }

    /* 2 x 2 texels with their top-left at (row, column), some of them outside the window. */
    void add_edge(const dsn_asset *asset, uint32_t row, uint32_t column, int64_t across, int64_t down) {
        add_border<Channels, Bytes>(asset->texton, asset->width, asset->height, asset->width, row, column,
                                    across, down, border);
    }

    void take(uint64_t *sums) const {
#if defined(__SSE2__)
        uint64_t vector_interior[DSN_MAX_CHANNELS] = {0, 0, 0};
        if (Bytes == 1) take_bilinear_sums<Channels>(vector_sums, vector_interior);
#else
        const uint64_t vector_interior[DSN_MAX_CHANNELS] = {0, 0, 0};
#endif
        /* The interior sums were of biased values: each bilinear texton 2^(32 + 8 Bytes - 1) too high. */
        for (uint32_t c = 0; c < Channels; c++)
            sums[c] += interior[c] + vector_interior[c] - (interior_count << (31u + 8u * Bytes)) + border[c];
    }
    void take(Sums *sums) const { take(sums->value); }
};

struct SlopeSums {
    uint64_t value[DSN_MAX_CHANNELS], slope_x[DSN_MAX_CHANNELS], slope_y[DSN_MAX_CHANNELS];
};

template <uint32_t Channels, uint32_t Bytes>
struct SlopeRead {
    typedef SlopeSums Sums;
    static const uint32_t channels = Channels, bytes = Bytes;
    /* An impulse exactly at the edge where it enters the reach (offset -(radius + 1) texels on an axis)
       adds nothing to the value but its slope: the value's walk leaves it out, this one reads it. */
    static const bool entry_edge = true;
    ValueRead<Channels, Bytes> values;
    uint64_t slope_x[DSN_MAX_CHANNELS], slope_y[DSN_MAX_CHANNELS];
#if defined(__SSE2__)
    SlopeLanes lanes; /* 8-bit interior texels (bilinear_read.h) */
#endif

    SlopeRead() {
        for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) slope_x[c] = slope_y[c] = 0;
#if defined(__SSE2__)
        lanes.along_x = lanes.along_y = zero_128();
#endif
    }

    void add_interior(const unsigned char *top, const unsigned char *bottom, int64_t across, int64_t down) {
        values.add_interior(top, bottom, across, down);
#if defined(__SSE2__)
        if (Bytes == 1) {
            add_slopes_vector<Channels>(top, bottom, static_cast<uint32_t>(across),
                                        static_cast<uint32_t>(down), &lanes);
            return;
        }
#endif
        for (uint32_t c = 0; c < Channels; c++)
            add_slopes(
                biased_value<Bytes>(top + c * Bytes), biased_value<Bytes>(top + (Channels + c) * Bytes),
                biased_value<Bytes>(bottom + c * Bytes), biased_value<Bytes>(bottom + (Channels + c) * Bytes),
                across, down, &slope_x[c], &slope_y[c]);
    }

    void add_edge(const dsn_asset *asset, uint32_t row, uint32_t column, int64_t across, int64_t down) {
        values.add_edge(asset, row, column, across, down);
        int64_t corners[4][DSN_MAX_CHANNELS];
        read_corners<Channels, Bytes>(asset->texton, asset->width, asset->height, asset->width, row, column,
                                      corners);
        for (uint32_t c = 0; c < Channels; c++)
            add_slopes(corners[0][c], corners[1][c], corners[2][c], corners[3][c], across, down, &slope_x[c],
                       &slope_y[c]);
    }

    void take(Sums *sums) const {
        values.take(sums->value);
#if defined(__SSE2__)
        int32_t along_x[4], along_y[4];
        take_32_lanes(lanes.along_x, along_x);
        take_32_lanes(lanes.along_y, along_y);
#endif
        for (uint32_t c = 0; c < Channels; c++) {
            sums->slope_x[c] += slope_x[c];
            sums->slope_y[c] += slope_y[c];
#if defined(__SSE2__)
            if (Bytes == 1) {
                sums->slope_x[c] += static_cast<uint64_t>(static_cast<int64_t>(along_x[c]));
                sums->slope_y[c] += static_cast<uint64_t>(static_cast<int64_t>(along_y[c]));
            }
#endif
        }
    }
};

/* Visits every buffered candidate: those in reach go to a Read (above). Empties the buffer. */
template <class Read>
void add_candidates(const dsn_noise_state *noise, const FieldLanes &lanes, CandidateBuffer *buffer,
                    typename Read::Sums *sums) {
    const uint32_t half_mask = (1u << lanes.half_bits) - 1u, fraction_shift = lanes.half_bits;
    const uint32_t position_shift = 16u + noise->cell_shift, high_shift = 16u - lanes.half_bits;
    const uint64_t limit_x = static_cast<uint64_t>(2u * noise->radius[0] + 2u) * one_texel - 1u;
    const uint64_t limit_y = static_cast<uint64_t>(2u * noise->radius[1] + 2u) * one_texel - 1u;
    const uint32_t width = noise->asset.width, height = noise->asset.height;
    const uint32_t texel_bytes = Read::channels * Read::bytes;
    const unsigned char *texton = noise->asset.texton;
    Read read;
    for (uint32_t word = 0; word < 2; word++) {
        for (uint64_t bits = buffer->lanes[word]; bits != 0; bits &= bits - 1u) {
            const uint32_t bit = lowest_bit(bits), slot = 8u * word + (bit >> 3), impulse = bit & 7u;
            const uint32_t field = dsn_pair_bits(buffer->pairs[slot], impulse << lanes.field_shift);
            const uint32_t fraction = dsn_mix32(buffer->streams[slot] + impulse * 0x9E3779B9u);
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
            if (Read::entry_edge ? shifted_x > limit_x || shifted_y > limit_y
                                 : shifted_x - 1u >= limit_x || shifted_y - 1u >= limit_y)
                continue;
            const uint32_t row = static_cast<uint32_t>(shifted_y >> 32) - 1u,
                           column = static_cast<uint32_t>(shifted_x >> 32) - 1u;
            const int64_t down = static_cast<int64_t>((shifted_y >> 16) & bilinear_weight_mask),
                          across = static_cast<int64_t>((shifted_x >> 16) & bilinear_weight_mask);
            if (row < height - 1u && column < width - 1u) { /* -1 (0xFFFFFFFF) fails too */
                const unsigned char *top = texton + (row * width + column) * texel_bytes;
                read.add_interior(top, top + width * texel_bytes, across, down);
            } else {
                read.add_edge(&noise->asset, row, column, across, down);
            }
        }
        buffer->lanes[word] = 0;
    }
    buffer->count = 0;
    read.take(sums);
}

/* Buffers the candidates of every pair of the cell with this key (visiting the buffer when full). */
template <class Read>
void add_cell_fast(const dsn_noise_state *noise, uint32_t key, const FieldLanes &lanes, const CellAxis &x,
                   const CellAxis &y, CandidateBuffer *buffer, typename Read::Sums *sums) {
    const uint32_t count = dsn_cell_impulse_count(noise, key);
    for (uint32_t first = 0; first < count; first += lanes.per_pair) {
        if (buffer->count == 16) add_candidates<Read>(noise, lanes, buffer, sums);
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

/* The sifting of one axis for Read: with the entry edge where Read takes it (continuous_sift.h). */
template <class Read>
inline bool read_axis(const PointAxis &point, const dsn_span &span, uint32_t cell, const FieldLanes &lanes,
                      CellAxis *out) {
    return Read::entry_edge ? cell_axis_with_entry_edge(point, span, cell, lanes, out)
                            : cell_axis(point, span, cell, lanes, out);
}

/* The sums of every impulse that reaches the point (x, y), through the reader Read. */
template <class Read>
void sum_point(const dsn_noise_state *noise, uint64_t x, uint64_t y, typename Read::Sums *sums) {
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
            if (!read_axis<Read>(py, span_y, cell_y, lanes, &in_y)) continue;
            const uint32_t row_key = dsn_row_key(noise, cell_y);
            for (uint32_t sx = 0; sx < px.axis.span_count; sx++) {
                const dsn_span span_x = dsn_axis_span(&px.axis, sx);
                for (uint32_t i = 0; i < span_x.cell_count; i++) {
                    const uint32_t cell_x = dsn_span_cell(&span_x, i, shift);
                    CellAxis in_x;
                    if (read_axis<Read>(px, span_x, cell_x, lanes, &in_x))
                        add_cell_fast<Read>(noise, dsn_cell_key_in_row(noise, cell_x, row_key), lanes, in_x,
                                            in_y, &buffer, sums);
                }
            }
        }
    }
    add_candidates<Read>(noise, lanes, &buffer, sums);
}

/* sum_point with the reader of the asset's channel count and value size. */
template <template <uint32_t, uint32_t> class Read, class Sums>
void sum_point_of_asset(const dsn_noise_state *noise, uint64_t x, uint64_t y, Sums *sums) {
    const dsn_asset *asset = &noise->asset;
    if (asset->channels == 3)
        asset->bits == 8 ? sum_point<Read<3, 1>>(noise, x, y, sums)
                         : sum_point<Read<3, 2>>(noise, x, y, sums);
    else
        asset->bits == 8 ? sum_point<Read<1, 1>>(noise, x, y, sums)
                         : sum_point<Read<1, 2>>(noise, x, y, sums);
}

/* The kernel entry (kernels.h's dsn_continuous_point_entry): the point's sums, and where slope_x is not
   null its derivative's, through the vector evaluator where the kernel has one that takes the noise, else
   through the sifting walk; every channel past the noise's zero. A mix's materials go through the vector
   evaluator alone (0 where it does not take them). */
inline int continuous_point_entry(const dsn_noise_state *noise, uint64_t x, uint64_t y, uint64_t *value,
                                  uint64_t *slope_x, uint64_t *slope_y,
                                  const dsn_point_materials *materials) {
#if defined(__AVX2__)
    if (continuous_point_sums(noise, x, y, value, slope_x, slope_y, materials)) return 1;
#endif
    if (materials != 0) return 0;
#if DSN_GRADIENTS
    if (slope_x != 0) {
        SlopeSums sums = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        sum_point_of_asset<SlopeRead>(noise, x, y, &sums);
        for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) {
            value[c] = sums.value[c];
            slope_x[c] = sums.slope_x[c];
            slope_y[c] = sums.slope_y[c];
        }
        return 1;
    }
#else
    (void)slope_x, (void)slope_y;
#endif
    ValueSums sums = {{0, 0, 0}};
    sum_point_of_asset<ValueRead>(noise, x, y, &sums);
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) value[c] = sums.value[c];
    return 1;
}

} // namespace
/* The kernel entry: null in the small build (continuous_point.cpp walks impulse by impulse). */
#define DSN_CONTINUOUS_POINT_ENTRY continuous_point_entry
#else
#define DSN_CONTINUOUS_POINT_ENTRY 0
#endif

#endif /* DSN_CONTINUOUS_POINT_SIFT_H */
