/* runtime/core/bilinear_texton.h - the texton read with bilinear interpolation, in integer arithmetic: with
   the point-minus-impulse offset d (Q32.32) floored to 8 fractional bits, t(d) = sum over the 4 surrounding
   texels of q * wx * wy, wx and wy in Q0.16 with their low byte zero (continuous_internal.h), zero beyond
   the texton's window. Shared by the per-point evaluator and the grid splat of the continuous mode
   (everything here has internal linkage). With DSN_SMALL_CODE (dsn.h) one generic reader serves 8 and 16
   bits; the fast build reads interior texels without bounds checks, one copy per value size. */
#ifndef DSN_BILINEAR_TEXTON_H
#define DSN_BILINEAR_TEXTON_H

#include "core/cell_walk.h"
#include "core/continuous_internal.h"
#include "core/impulse_position.h"
#include "core/normalize_fixed.h"
#include "core/poisson_count.h"

namespace {

/* One axis of a point-minus-impulse offset d (Q32.32): the texton index of the lower of the two texels
   that bracket d (0xFFFFFFFF for index -1) and the weight of the upper one (Q0.16, a multiple of 2^8: bits
   24 to 31 of the fraction). False when d is outside (-(radius + 1), radius + 1), where both texels are
   zero. */
inline bool bracket(int64_t offset, uint32_t radius, uint32_t *lower_index, uint32_t *upper_weight) {
    /* Shifted so that the lower index is (shifted >> 32) - 1 and the shift is of a positive value. */
    const int64_t shifted = offset + static_cast<int64_t>(radius + 1u) * static_cast<int64_t>(one_texel);
    if (shifted <= 0 || shifted >= static_cast<int64_t>(2u * radius + 2u) * static_cast<int64_t>(one_texel))
        return false;
    const uint64_t bits = static_cast<uint64_t>(shifted);
    *lower_index = static_cast<uint32_t>(bits >> 32) - 1u;
    *upper_weight = (static_cast<uint32_t>(bits) >> 24) << 8;
    return true;
}

/* The two partial derivatives of one channel's bilinear texton, with corners (a, b) above and (c, d)
   below, at the upper weights (across, down) of add_bilinear: per 2^-16 texel of motion,
     along x  (65536 - down) (b - a) + down (d - c),
     along y  (65536 - across) (c - a) + across (d - b),
   the slopes of the piece of the interpolation that holds the point (so one-sided, toward +x and +y, on
   a texel edge). A bias added to all four corners cancels. Each is below 2^32 in magnitude. */
inline void add_slopes(int64_t a, int64_t b, int64_t c, int64_t d, int64_t across, int64_t down,
                       uint64_t *slope_x, uint64_t *slope_y) {
    *slope_x += static_cast<uint64_t>((65536 - down) * (b - a) + down * (d - c));
    *slope_y += static_cast<uint64_t>((65536 - across) * (c - a) + across * (d - b));
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
inline int32_t stored_value(const unsigned char *at) {
    return Bytes == 1 ? dsn_read_i8(at) : dsn_read_i16le(at);
}

template <uint32_t Bytes>
inline void add_interior(const dsn_asset *asset, uint32_t row, uint32_t column, const int64_t *weights,
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
inline void add_bilinear(const dsn_asset *asset, uint32_t row, uint32_t row_weight, uint32_t column,
                         uint32_t column_weight, uint64_t *sums) {
#if DSN_SMALL_CODE
    const int32_t weights[4] = {
        static_cast<int32_t>((65536u - column_weight) >> 8), static_cast<int32_t>(column_weight >> 8),
        static_cast<int32_t>((65536u - row_weight) >> 8), static_cast<int32_t>(row_weight >> 8)};
#else
    const int64_t weights[4] = {static_cast<int64_t>(65536u - column_weight),
                                static_cast<int64_t>(column_weight),
                                static_cast<int64_t>(65536u - row_weight), static_cast<int64_t>(row_weight)};
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
        /* One loop over the 4 corners (shorter code), in units of 2^16: the same integer as the row form
           below divided by 2^16 (the weights' low bytes are zero). A weighted mean of the texels times
           2^16, every partial sum within int32 (-2^31 at the least, below 2^31). */
        int32_t sum = 0;
        for (uint32_t corner = 0; corner < 4; corner++) {
            const uint32_t down = corner >> 1, right = corner & 1u;
            sum += weights[2 + down] * weights[right] * texel(asset, row + down, column + right, c);
        }
        sums[c] += static_cast<uint64_t>(static_cast<int64_t>(sum)) << 16;
#else
        const int64_t upper =
            weights[0] * texel(asset, row, column, c) + weights[1] * texel(asset, row, column + 1u, c);
        const int64_t lower = weights[0] * texel(asset, row + 1u, column, c) +
                              weights[1] * texel(asset, row + 1u, column + 1u, c);
        sums[c] += static_cast<uint64_t>(weights[2] * upper + weights[3] * lower);
#endif
    }
}

} // namespace

#endif /* DSN_BILINEAR_TEXTON_H */
