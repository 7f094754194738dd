/* runtime/core/continuous_internal.h - what the files of the continuous (renderer) mode share: the Q32.32
   texel, the normalization of sums that carry 32 fraction bits, the mode check and the per-point
   evaluator that grid tiles fall back to. Internal to libdsn; not installed.

   The mode: the impulses are those of the lattice mode read with their full 16-bit in-cell positions (so
   each lattice impulse is the floor of its continuous twin): a continuous Poisson process of the same
   intensity, with 16 - cell_shift fractional bits per axis. The texton is read with bilinear
   interpolation in integer arithmetic (bilinear_texton.h). The per-channel sums carry 32 fractional bits
   and go through the lattice mode's normalization. coordinate.cpp turns float coordinates into Q32.32,
   continuous_point.cpp evaluates one point, continuous_tile.cpp a grid of points. */
#ifndef DSN_CONTINUOUS_INTERNAL_H
#define DSN_CONTINUOUS_INTERNAL_H

#include "core/cell_walk.h"
#include "core/impulse_position.h"
#include "core/normalize_fixed.h"
#include "core/poisson_count.h"

namespace {

const uint64_t one_texel = static_cast<uint64_t>(1) << 32;

/* The bilinear weights keep 8 fractional bits, as GPUs' texture units do: an offset's fraction bits 24 to
   31, taken in Q0.16 with the low byte zero, so every product below has 8 zero low bits. */
const uint32_t bilinear_weight_mask = 0xFF00u;

/* Two's-complement reinterpretation without implementation-defined conversions. */
inline int64_t signed_from_bits(uint64_t bits) {
    return (bits & 0x8000000000000000u) ? -static_cast<int64_t>(~bits) - 1 : static_cast<int64_t>(bits);
}

/* floor(value / 2^shift), 0 <= shift <= 63, without shifting a negative number (implementation-defined):
   through a 2^63 bias, as dsn_round_saturate does. */
inline int64_t floor_shift(int64_t value, uint32_t shift) {
    const uint64_t bias = static_cast<uint64_t>(1) << 63;
    return signed_from_bits(((static_cast<uint64_t>(value) + bias) >> shift) - (bias >> shift));
}

/* One step of the bilinear weights, 2^-8 texel, is 2^weight_step_shift in Q32.32. A point moved by one
   step reads every weight one step up (across a texel edge, the next texel's piece at weight 0, which
   equals the last one's at weight 1), so its sums less the point's are 2^8 times the slopes per 2^-16
   texel, exactly; slopes_from_step divides them back (the slope sums are far below 2^55). */
const uint32_t weight_step_shift = 24;

inline uint64_t slopes_from_step(uint64_t difference) {
    return static_cast<uint64_t>(floor_shift(signed_from_bits(difference), 8));
}

/* One output channel of normalize_q32_channels from its row of gains and the sums' whole parts w and
   fractions f (zero past the noise's channels). */
inline int32_t normalized_q32_channel(int64_t offset, const int64_t *gain, int64_t w0, int64_t f0, int64_t w1,
                                      int64_t f1, int64_t w2, int64_t f2, uint32_t shift) {
    const int64_t fractions = gain[0] * f0 + gain[1] * f1 + gain[2] * f2; /* |gain| < 2^29: each below 2^61 */
    const int64_t accumulated = offset + gain[0] * w0 + gain[1] * w1 + gain[2] * w2 +
                                dsn_signed_sum(static_cast<uint32_t>(static_cast<uint64_t>(fractions) >> 32));
    return dsn_round_saturate(accumulated, shift);
}

/* The lattice normalization of sums that carry 32 more fraction bits: the integer parts go through
   it as in lattice mode, the fractions are added once, rounded down, before the final rounding; from
   `offset` (the noise's own, or zeros for a derivative, which the mean does not reach). For a noise of
   `Channels` channels (1 or 3), written out: each sum split into its whole part (its floor, modulo 2^32)
   and fraction once, not once per output channel. */
template <uint32_t Channels>
inline void normalize_q32_channels(const dsn_noise_state *noise, const int64_t *offset, const uint64_t *sums,
                                   int32_t *out) {
    const uint64_t low = 0xFFFFFFFFu;
    const int64_t w0 = dsn_signed_sum(static_cast<uint32_t>(sums[0] >> 32));
    const int64_t w1 = Channels == 3 ? dsn_signed_sum(static_cast<uint32_t>(sums[1] >> 32)) : 0;
    const int64_t w2 = Channels == 3 ? dsn_signed_sum(static_cast<uint32_t>(sums[2] >> 32)) : 0;
    const int64_t f0 = static_cast<int64_t>(sums[0] & low);
    const int64_t f1 = Channels == 3 ? static_cast<int64_t>(sums[1] & low) : 0;
    const int64_t f2 = Channels == 3 ? static_cast<int64_t>(sums[2] & low) : 0;
    for (uint32_t c = 0; c < Channels; c++)
        out[c] =
            normalized_q32_channel(offset[c], noise->gain + 3 * c, w0, f0, w1, f1, w2, f2, noise->gain_shift);
}

/* normalize_q32_channels for the noise's 1 or 3 channels (the loader's check), but in the small build,
   whose one loop over the count read at run time takes fewer bytes. */
inline void normalize_q32_from(const dsn_noise_state *noise, const int64_t *offset, const uint64_t *sums,
                               int32_t *out) {
#if DSN_SMALL_CODE
    const uint32_t channels = noise->asset.channels;
    for (uint32_t c = 0; c < channels; c++) {
        int64_t accumulated = offset[c], fractions = 0;
        for (uint32_t k = 0; k < channels; k++) {
            accumulated += noise->gain[c * 3 + k] * dsn_signed_sum(static_cast<uint32_t>(sums[k] >> 32));
            fractions += noise->gain[c * 3 + k] * static_cast<int64_t>(sums[k] & 0xFFFFFFFFu);
        }
        accumulated += dsn_signed_sum(static_cast<uint32_t>(static_cast<uint64_t>(fractions) >> 32));
        out[c] = dsn_round_saturate(accumulated, noise->gain_shift);
    }
#else
    if (noise->asset.channels == 3)
        normalize_q32_channels<3>(noise, offset, sums, out);
    else
        normalize_q32_channels<1>(noise, offset, sums, out);
#endif
}

/* The value: then the histogram mapping (normalize_q32), or not yet (normalize_q32_unmapped). */
inline void normalize_q32_unmapped(const dsn_noise_state *noise, const uint64_t *sums, int32_t *out) {
    normalize_q32_from(noise, noise->offset, sums, out);
}

inline void normalize_q32(const dsn_noise_state *noise, const uint64_t *sums, int32_t *out) {
    normalize_q32_unmapped(noise, sums, out);
    dsn_map_output(noise, out);
}

} // namespace

/* DSN_OK when the continuous functions may evaluate `noise`, else DSN_ERR_NULL (null or not configured)
   or DSN_ERR_CONTINUOUS_MISMATCH (continuous_point.cpp). */
int dsn_internal_continuous_check(const dsn_noise_state *noise);

/* dsn_internal_continuous_check of a noise known to be configured (a mix's materials, checked with it):
   whether its texton may be read between texels (baked for it, or allowed by the flag). */
inline bool dsn_continuous_reads(const dsn_noise_state *noise) {
    return noise->asset.interpolation == DSN_INTERPOLATION_BILINEAR ||
           (noise->flags & DSN_FLAG_ALLOW_LATTICE_CONTINUOUS) != 0;
}

/* A batch chunk's coordinates as the kernels read them: Q32.32 ones where they are, float64 ones converted
   into `chunk` (dsn_coordinate_from_double). */
inline const int64_t *dsn_chunk_coordinates(const int64_t *values, uint32_t first, uint32_t, int64_t *) {
    return values + first;
}
inline const int64_t *dsn_chunk_coordinates(const double *values, uint32_t first, uint32_t points,
                                            int64_t *chunk) {
    for (uint32_t k = 0; k < points; k++) chunk[k] = dsn_coordinate_from_double(values[first + k]);
    return chunk;
}

/* The Q16.16 values of the point (x, y), Q32.32 coordinates, on a noise that passed the check
   (continuous_point.cpp). */
void dsn_internal_continuous_point(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out);

/* The continuous point at Q32.32 coordinates as `kind` (float or u8): the errors and the zeroed output of
   dsn_continuous_point_fixed, the values converted (continuous_point.cpp; dsn_sample calls it too). */
int dsn_internal_continuous_point_as(const dsn_noise *noise, int64_t x, int64_t y, void *out,
                                     dsn_output_kind kind);

#if DSN_GRADIENTS
/* values[0 .. 2]: the continuous gradient's value, dx and dy at (x, y), DSN_MAX_CHANNELS apart, Q16.16,
   mapped (continuous_gradient.cpp). */
void dsn_internal_continuous_gradient(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *values);
/* The raw sums of the point (x, y) for its gradient (continuous_point.cpp), per channel, modulo 2^64:
   value[c] the bilinear texton's (Q.32, what dsn_internal_continuous_point normalizes), slope_x[c] and
   slope_y[c] its partial derivatives per 2^-16 texel (bilinear_read.h's add_slopes). */
void dsn_internal_continuous_slopes(const dsn_noise_state *noise, uint64_t x, uint64_t y, uint64_t *value,
                                    uint64_t *slope_x, uint64_t *slope_y);
/* The gradient tile of a grid (dsn.h's dsn_continuous_tile_gradient_fixed) by splatting, with the
   per-point bits (continuous_tile.cpp), for a noise and outputs that passed the call's checks; 0, writing
   nothing, for a tile size the call refuses or a grid it does not splat (the small build: none). */
int dsn_internal_continuous_gradient_splat(const dsn_noise_state *noise, const dsn_grid *grid, uint32_t width,
                                           uint32_t height, void *out, void *dx, void *dy,
                                           dsn_output_kind kind);
#endif

#endif /* DSN_CONTINUOUS_INTERNAL_H */
