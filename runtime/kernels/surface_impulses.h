/* runtime/kernels/surface_impulses.h - the impulses of one cube of the surface walk (core/surface_walk.h)
   that the slab and the reaches keep, as a kernel (kernels.h): each impulse's position hashed from the
   cube's key, its offsets from the point along the frame's three vectors taken exactly and floored to
   Q32.32, and those within the cube's reaches listed. On AVX-512, 8 impulses at once in 64-bit lanes (the
   dot products are 32 x 32-bit products: a position field has 16 bits, a frame component 31 and a sign),
   kept ones stored compressed; on AVX2 4 at once; elsewhere one at a time; the same bits everywhere. Also,
   on AVX-512 and AVX2, the unfiltered point's reads of the listed impulses of an 8-bit texton, 8 or 4 at
   a time: the slab's window, the bilinear texton and their product in 64-bit lanes (elsewhere the point
   reads them one by one, surface_point.cpp). Internal to libdsn; not installed (everything here has internal
   linkage). */
#ifndef DSN_SURFACE_IMPULSES_H
#define DSN_SURFACE_IMPULSES_H

#include "core/cell_hash.h"
#include "core/continuous_internal.h"
#include "kernels/kernels.h"
#include "simd/simd_mix64.h"

#if DSN_SURFACE
namespace {

/* What dsn_position_pair adds to (key << 32) per impulse index. */
const uint64_t impulse_index_step = 0x9E3779B97F4A7C15u;

/* Whether |value| < reach (reach >= 1), as one unsigned comparison. */
inline bool within_reach(int64_t value, int64_t reach) {
    return static_cast<uint64_t>(value) + static_cast<uint64_t>(reach - 1) <
           static_cast<uint64_t>(2 * reach - 1);
}

#if defined(__AVX2__)

/* The three 16-bit position fields of the impulses whose dsn_position_pair inputs are `indices`. */
template <typename Vector>
DSN_SIMD_INLINE void impulse_fields(Vector indices, Vector *fields) {
    const Vector pair = mix64_lanes(indices), field_mask = all_lanes_64<Vector>(0xFFFFu);
    fields[0] = bitwise_and(pair, field_mask);
    fields[1] = bitwise_and(shift_right_logical_64(pair, 16), field_mask);
    fields[2] = bitwise_and(shift_right_logical_64(pair, 32), field_mask);
}

/* One offset of the impulses (one frame vector's dot products with their 16-bit fields, a 32 x 32-bit
   product each, subtracted from the origin's and floored to Q32.32 through a 2^63 bias as floor_shift
   does). */
template <typename Vector>
DSN_SIMD_INLINE Vector offset_lanes(const Vector *fields, const int32_t *vector, int64_t origin_dot,
                                    uint32_t cell_shift) {
    const Vector dot =
        add_64(add_64(multiply_even_32(fields[0], all_lanes_64<Vector>(static_cast<uint64_t>(vector[0]))),
                      multiply_even_32(fields[1], all_lanes_64<Vector>(static_cast<uint64_t>(vector[1])))),
               multiply_even_32(fields[2], all_lanes_64<Vector>(static_cast<uint64_t>(vector[2]))));
    const Vector offset =
        subtract_64(all_lanes_64<Vector>(static_cast<uint64_t>(origin_dot)), shift_left_64(dot, cell_shift));
    const Vector bias = all_lanes_64<Vector>(static_cast<uint64_t>(1) << 63);
    return subtract_64(shift_right_logical_64(add_64(offset, bias), 14), shift_right_logical_64(bias, 14));
}

#endif

#if defined(__AVX512F__) && defined(__AVX512BW__)

/* The lanes of `within` whose value lies within the reach (within_reach on every lane). */
DSN_SIMD_INLINE mask_8 lanes_within(mask_8 within, vector_512 value, int64_t reach) {
    return less_unsigned_64(within, add_64(value, set_8x64(reach - 1)), set_8x64(2 * reach - 1));
}

uint32_t surface_impulses(const dsn_surface_cube *cube, dsn_surface_impulses *out) {
    const vector_512 index_steps = set_lanes_8x64(
        0, static_cast<int64_t>(impulse_index_step), static_cast<int64_t>(2u * impulse_index_step),
        static_cast<int64_t>(3u * impulse_index_step), static_cast<int64_t>(4u * impulse_index_step),
        static_cast<int64_t>(5u * impulse_index_step), static_cast<int64_t>(6u * impulse_index_step),
        static_cast<int64_t>(7u * impulse_index_step));
    uint64_t index = (static_cast<uint64_t>(cube->key) << 32) + cube->first * impulse_index_step;
    uint32_t kept = 0;
    for (uint32_t k = 0; k < cube->count; k += 8, index += 8u * impulse_index_step) {
        vector_512 fields[3];
        impulse_fields(add_64(set_8x64(static_cast<int64_t>(index)), index_steps), fields);
        const mask_8 lanes =
            static_cast<mask_8>(cube->count - k >= 8 ? 0xFFu : (1u << (cube->count - k)) - 1u);
        /* Across the slab first: it leaves out about half. */
        const vector_512 across = offset_lanes(fields, cube->frame[2], cube->origin_dot[2], cube->cell_shift);
        mask_8 keep = lanes_within(lanes, across, cube->reach_across);
        if (keep == 0) continue;
        const vector_512 u = offset_lanes(fields, cube->frame[0], cube->origin_dot[0], cube->cell_shift);
        keep = lanes_within(keep, u, cube->reach_u);
        const vector_512 v = offset_lanes(fields, cube->frame[1], cube->origin_dot[1], cube->cell_shift);
        keep = lanes_within(keep, v, cube->reach_v);
        store_compressed_8x64(out->along_tangent + kept, keep, u);
        store_compressed_8x64(out->along_bitangent + kept, keep, v);
        store_compressed_8x64(out->across + kept, keep, across);
        kept += static_cast<uint32_t>(__builtin_popcount(keep));
    }
    return kept;
}

/* slab_window (core/surface_walk.h) on every lane: the offsets across (Q32.32, under 3/4 of a cube) to
   the windows (Q16); the steps of the smoothstep clamped, so that 0 and 65536 come out of the same
   polynomial. */
DSN_SIMD_INLINE vector_512 window_lanes(vector_512 across, uint32_t cell_shift) {
    const vector_512 sign = shift_right_arithmetic_64(across, 63);
    const vector_512 magnitude = subtract_64(bitwise_xor(across, sign), sign);
    const vector_512 s = shift_right_logical_64(
        multiply_even_unsigned_32(shift_right_logical_64(magnitude, 16), set_8x64(89878)), 16u + cell_shift);
    const vector_512 one = set_8x64(65536);
    const vector_512 u = minimum_64(maximum_64(subtract_64(shift_left_64(s, 1), one), zero_512()), one);
    const vector_512 square = shift_right_logical_64(multiply_even_unsigned_32(u, u), 16);
    const vector_512 slope = subtract_64(set_8x64(196608), shift_left_64(u, 1));
    return subtract_64(one, shift_right_logical_64(multiply_even_unsigned_32(square, slope), 16));
}

/* Byte `index` of every 64-bit lane, sign-extended, where mask has the lane, else 0. */
DSN_SIMD_INLINE vector_512 lane_byte_64(vector_512 words, uint32_t index, mask_8 mask) {
    const vector_512 byte = shift_right_arithmetic_64(shift_left_64(words, 56u - 8u * index), 56);
    return and_64_where(zero_512(), mask, byte, set_8x64(-1));
}

/* floor(value * window / 2^16) on every lane (|value| < 2^47, window <= 2^16: windowed's product), from
   the 32 x 32-bit products of the window with value's two halves. */
DSN_SIMD_INLINE vector_512 windowed_lanes(vector_512 value, vector_512 window) {
    const vector_512 high = multiply_even_32(shift_right_arithmetic_64(value, 32), window);
    const vector_512 low = multiply_even_unsigned_32(value, window);
    return shift_right_arithmetic_64(add_64(shift_left_64(high, 32), low), 16);
}

/* The reads of 8 listed impulses (those of `lanes`), added to sums[c] lane by lane. Each row's two texels
   come from one 8-byte read from 4 bytes before the right texel, as continuous_point_vector.h's
   texton_pairs_16 reads them (within 4 bytes before the texton and 4 past it: the asset's header and CRC,
   in the buffer the loader checked): the left texel's channels end at byte 3, the right one's start at
   byte 4; each is 0 outside the texton. The bilinear sum is add_bilinear's integer, in its row form. */
template <uint32_t Channels>
DSN_SIMD_INLINE void add_reads_8(const dsn_asset *asset, vector_512 along_tangent, vector_512 along_bitangent,
                                 vector_512 window, mask_8 lanes, vector_512 *sums) {
    const uint32_t width = asset->width, height = asset->height;
    const vector_512 low_16 = set_8x64(0xFFFF), one = set_8x64(1);
    const vector_512 shifted_x =
        add_64(along_tangent, set_8x64(static_cast<int64_t>((width + 1u) / 2u) << 32));
    const vector_512 shifted_y =
        add_64(along_bitangent, set_8x64(static_cast<int64_t>((height + 1u) / 2u) << 32));
    const vector_512 right_column = shift_right_logical_64(shifted_x, 32),
                     lower_row = shift_right_logical_64(shifted_y, 32);
    const vector_512 row = subtract_64(lower_row, one);
    const vector_512 across = bitwise_and(shift_right_logical_64(shifted_x, 16), low_16),
                     down = bitwise_and(shift_right_logical_64(shifted_y, 16), low_16);
    const vector_512 columns = set_8x64(width), rows = set_8x64(height);
    const mask_8 left = less_unsigned_64(lanes, subtract_64(right_column, one), columns),
                 right = less_unsigned_64(lanes, right_column, columns);
    const mask_8 top = less_unsigned_64(left | right, row, rows),
                 bottom = less_unsigned_64(left | right, lower_row, rows);
    const vector_512 entry = add_64(multiply_even_unsigned_32(row, columns), right_column);
    const vector_512 at = subtract_64(multiply_even_unsigned_32(entry, set_8x64(Channels)), set_8x64(4));
    const vector_512 below = add_64(at, set_8x64(width * Channels));
    const vector_512 upper_words = gather_masked_64<1>(asset->texton, truncate_64x32(at), top),
                     lower_words = gather_masked_64<1>(asset->texton, truncate_64x32(below), bottom);
    const vector_512 scale = set_8x64(65536);
    for (uint32_t c = 0; c < Channels; c++) {
        const vector_512 a = lane_byte_64(upper_words, 4u - Channels + c, left),
                         b = lane_byte_64(upper_words, 4u + c, right),
                         d = lane_byte_64(lower_words, 4u - Channels + c, left),
                         e = lane_byte_64(lower_words, 4u + c, right);
        const vector_512 upper =
            add_64(multiply_even_32(a, scale), multiply_even_32(across, subtract_64(b, a)));
        const vector_512 lower =
            add_64(multiply_even_32(d, scale), multiply_even_32(across, subtract_64(e, d)));
        const vector_512 value =
            add_64(shift_left_64(upper, 16), multiply_even_32(down, subtract_64(lower, upper)));
        sums[c] = add_64(sums[c], windowed_lanes(value, window));
    }
}

/* The reads of the listed impulses, 8 at a time, each lane's sums added to sums at the end. */
template <uint32_t Channels>
void texton_reads(const dsn_asset *asset, const dsn_surface_impulses *listed, uint32_t count,
                  uint32_t cell_shift, uint64_t *sums) {
    vector_512 lanes[Channels];
    for (uint32_t c = 0; c < Channels; c++) lanes[c] = zero_512();
    for (uint32_t k = 0; k < count; k += 8) {
        const mask_8 valid = static_cast<mask_8>(count - k >= 8 ? 0xFFu : (1u << (count - k)) - 1u);
        const vector_512 window = window_lanes(load_masked_8x64(listed->across + k, valid), cell_shift);
        add_reads_8<Channels>(asset, load_masked_8x64(listed->along_tangent + k, valid),
                              load_masked_8x64(listed->along_bitangent + k, valid), window, valid, lanes);
    }
    for (uint32_t c = 0; c < Channels; c++) {
        uint64_t parts[8];
        store_8x64(parts, lanes[c]);
        for (uint32_t part = 0; part < 8; part++) sums[c] += parts[part];
    }
}

#elif defined(__AVX2__)

/* All ones in the lanes whose value lies within the reach (within_reach on every lane: the unsigned
   comparison made signed by flipping the top bits). */
DSN_SIMD_INLINE vector_256 lanes_within(vector_256 value, int64_t reach) {
    const uint64_t top = static_cast<uint64_t>(1) << 63;
    return greater_64(set_4x64(static_cast<int64_t>((static_cast<uint64_t>(2 * reach - 1)) ^ top)),
                      bitwise_xor(add_64(value, set_4x64(reach - 1)), set_4x64(static_cast<int64_t>(top))));
}

uint32_t surface_impulses(const dsn_surface_cube *cube, dsn_surface_impulses *out) {
    const vector_256 index_steps = set_lanes_4x64(0, static_cast<int64_t>(impulse_index_step),
                                                  static_cast<int64_t>(2u * impulse_index_step),
                                                  static_cast<int64_t>(3u * impulse_index_step));
    uint64_t index = (static_cast<uint64_t>(cube->key) << 32) + cube->first * impulse_index_step;
    uint32_t kept = 0;
    for (uint32_t k = 0; k < cube->count; k += 4, index += 4u * impulse_index_step) {
        vector_256 fields[3];
        impulse_fields(add_64(set_4x64(static_cast<int64_t>(index)), index_steps), fields);
        const vector_256 across = offset_lanes(fields, cube->frame[2], cube->origin_dot[2], cube->cell_shift);
        vector_256 keep = lanes_within(across, cube->reach_across);
        if (top_bits_of_32(keep) == 0) continue;
        const vector_256 u = offset_lanes(fields, cube->frame[0], cube->origin_dot[0], cube->cell_shift);
        const vector_256 v = offset_lanes(fields, cube->frame[1], cube->origin_dot[1], cube->cell_shift);
        keep = bitwise_and(keep, bitwise_and(lanes_within(u, cube->reach_u), lanes_within(v, cube->reach_v)));
        int64_t lanes[3][4];
        store_4x64(lanes[0], u);
        store_4x64(lanes[1], v);
        store_4x64(lanes[2], across);
        /* A lane's two 32-bit halves share its comparison's bits; lanes past the count are not read. */
        const uint32_t bits = static_cast<uint32_t>(top_bits_of_32(keep));
        const uint32_t count = cube->count - k < 4 ? cube->count - k : 4u;
        for (uint32_t slot = 0; slot < count; slot++) {
            out->along_tangent[kept] = lanes[0][slot];
            out->along_bitangent[kept] = lanes[1][slot];
            out->across[kept] = lanes[2][slot];
            kept += (bits >> (2u * slot)) & 1u;
        }
    }
    return kept;
}

/* The reads on AVX2 (surface_texton_reads): the AVX-512 kernel's on 4 lanes, with vector masks (all ones
   in a lane for true); the shifts of signed 64-bit lanes that AVX2 lacks made from 32-bit ones, where only
   a lane's low half is read after them, or through a 2^63 bias. */
DSN_SIMD_INLINE vector_256 below_unsigned_64(vector_256 a, vector_256 b) {
    const vector_256 top = set_4x64(INT64_MIN);
    return greater_64(bitwise_xor(b, top), bitwise_xor(a, top));
}

/* slab_window on every lane, as the AVX-512 kernel's window_lanes. */
DSN_SIMD_INLINE vector_256 window_lanes(vector_256 across, uint32_t cell_shift) {
    const vector_256 sign = greater_64(zero_256(), across);
    const vector_256 magnitude = subtract_64(bitwise_xor(across, sign), sign);
    const vector_256 s = shift_right_logical_64(
        multiply_even_unsigned_32(shift_right_logical_64(magnitude, 16), set_4x64(89878)), 16u + cell_shift);
    const vector_256 one = set_4x64(65536);
    vector_256 u = subtract_64(shift_left_64(s, 1), one);
    u = and_not(greater_64(zero_256(), u), u);
    const vector_256 over = greater_64(u, one);
    u = bitwise_or(and_not(over, u), bitwise_and(over, one));
    const vector_256 square = shift_right_logical_64(multiply_even_unsigned_32(u, u), 16);
    const vector_256 slope = subtract_64(set_4x64(196608), shift_left_64(u, 1));
    return subtract_64(one, shift_right_logical_64(multiply_even_unsigned_32(square, slope), 16));
}

/* Byte `index` of every 64-bit lane, sign-extended into the lane's low 32 bits (the high ones are not
   read: the products below take the low halves), where mask is set, else 0. */
DSN_SIMD_INLINE vector_256 lane_byte_low_32(vector_256 words, uint32_t index, vector_256 mask) {
    const vector_256 half = index >= 4 ? shift_right_logical_64(words, 32) : words;
    return bitwise_and(shift_right_arithmetic_32(shift_left_32(half, 24u - 8u * (index & 3u)), 24), mask);
}

/* windowed on every lane: the value's high half is its bits 32 .. 63, signed, in the low half of a lane. */
DSN_SIMD_INLINE vector_256 windowed_lanes(vector_256 value, vector_256 window) {
    const vector_256 high = multiply_even_32(shift_right_logical_64(value, 32), window);
    const vector_256 product = add_64(shift_left_64(high, 32), multiply_even_unsigned_32(value, window));
    const vector_256 bias = set_4x64(INT64_MIN);
    return subtract_64(shift_right_logical_64(add_64(product, bias), 16), shift_right_logical_64(bias, 16));
}

/* The AVX-512 kernel's add_reads_8 on 4 lanes. */
template <uint32_t Channels>
DSN_SIMD_INLINE void add_reads_4(const dsn_asset *asset, vector_256 along_tangent, vector_256 along_bitangent,
                                 vector_256 window, vector_256 lanes, vector_256 *sums) {
    const uint32_t width = asset->width, height = asset->height;
    const vector_256 low_16 = set_4x64(0xFFFF), one = set_4x64(1);
    const vector_256 shifted_x =
        add_64(along_tangent, set_4x64(static_cast<int64_t>((width + 1u) / 2u) << 32));
    const vector_256 shifted_y =
        add_64(along_bitangent, set_4x64(static_cast<int64_t>((height + 1u) / 2u) << 32));
    const vector_256 right_column = shift_right_logical_64(shifted_x, 32),
                     lower_row = shift_right_logical_64(shifted_y, 32);
    const vector_256 row = subtract_64(lower_row, one);
    const vector_256 across = bitwise_and(shift_right_logical_64(shifted_x, 16), low_16),
                     down = bitwise_and(shift_right_logical_64(shifted_y, 16), low_16);
    const vector_256 columns = set_4x64(width), rows = set_4x64(height);
    const vector_256 left = bitwise_and(lanes, below_unsigned_64(subtract_64(right_column, one), columns)),
                     right = bitwise_and(lanes, below_unsigned_64(right_column, columns));
    const vector_256 top = bitwise_and(bitwise_or(left, right), below_unsigned_64(row, rows)),
                     bottom = bitwise_and(bitwise_or(left, right), below_unsigned_64(lower_row, rows));
    const vector_256 entry = add_64(multiply_even_unsigned_32(row, columns), right_column);
    const vector_256 at = subtract_64(multiply_even_unsigned_32(entry, set_4x64(Channels)), set_4x64(4));
    const vector_256 below = add_64(at, set_4x64(width * Channels));
    const vector_256 low_halves = set_lanes_8x32(0, 2, 4, 6, 0, 2, 4, 6);
    const vector_256 upper_words =
                         gather_masked_64<1>(asset->texton, low_128(permute_32(at, low_halves)), top),
                     lower_words =
                         gather_masked_64<1>(asset->texton, low_128(permute_32(below, low_halves)), bottom);
    const vector_256 scale = set_4x64(65536);
    for (uint32_t c = 0; c < Channels; c++) {
        const vector_256 a = lane_byte_low_32(upper_words, 4u - Channels + c, left),
                         b = lane_byte_low_32(upper_words, 4u + c, right),
                         d = lane_byte_low_32(lower_words, 4u - Channels + c, left),
                         e = lane_byte_low_32(lower_words, 4u + c, right);
        const vector_256 upper =
            add_64(multiply_even_32(a, scale), multiply_even_32(across, subtract_64(b, a)));
        const vector_256 lower =
            add_64(multiply_even_32(d, scale), multiply_even_32(across, subtract_64(e, d)));
        const vector_256 value =
            add_64(shift_left_64(upper, 16), multiply_even_32(down, subtract_64(lower, upper)));
        sums[c] = add_64(sums[c], windowed_lanes(value, window));
    }
}

/* The reads of the listed impulses, 4 at a time, each lane's sums added to sums at the end. */
template <uint32_t Channels>
void texton_reads(const dsn_asset *asset, const dsn_surface_impulses *listed, uint32_t count,
                  uint32_t cell_shift, uint64_t *sums) {
    vector_256 lanes[Channels];
    for (uint32_t c = 0; c < Channels; c++) lanes[c] = zero_256();
    const vector_256 lane_numbers = set_lanes_4x64(0, 1, 2, 3);
    for (uint32_t k = 0; k < count; k += 4) {
        const vector_256 valid = greater_64(set_4x64(count - k), lane_numbers);
        const vector_256 window = window_lanes(load_masked_4x64(listed->across + k, valid), cell_shift);
        add_reads_4<Channels>(asset, load_masked_4x64(listed->along_tangent + k, valid),
                              load_masked_4x64(listed->along_bitangent + k, valid), window, valid, lanes);
    }
    for (uint32_t c = 0; c < Channels; c++) {
        uint64_t parts[4];
        store_4x64(parts, lanes[c]);
        for (uint32_t part = 0; part < 4; part++) sums[c] += parts[part];
    }
}

#else

/* One offset of an impulse (one frame vector's dot product with its 16-bit fields), floored to Q32.32. */
inline int64_t impulse_offset(const int64_t *fields, const int32_t *vector, int64_t origin_dot,
                              uint32_t cell_shift) {
    const int64_t dot = fields[0] * vector[0] + fields[1] * vector[1] + fields[2] * vector[2];
    return floor_shift(
        signed_from_bits(static_cast<uint64_t>(origin_dot) - (static_cast<uint64_t>(dot) << cell_shift)), 14);
}

uint32_t surface_impulses(const dsn_surface_cube *cube, dsn_surface_impulses *out) {
    uint32_t kept = 0;
    for (uint32_t k = 0; k < cube->count; k++) {
        const uint64_t pair = dsn_position_pair(cube->key, cube->first + k);
        const int64_t fields[3] = {static_cast<int64_t>(pair & 0xFFFFu),
                                   static_cast<int64_t>((pair >> 16) & 0xFFFFu),
                                   static_cast<int64_t>((pair >> 32) & 0xFFFFu)};
        /* Across the slab first: it leaves out about half. */
        const int64_t across = impulse_offset(fields, cube->frame[2], cube->origin_dot[2], cube->cell_shift);
        if (!within_reach(across, cube->reach_across)) continue;
        const int64_t u = impulse_offset(fields, cube->frame[0], cube->origin_dot[0], cube->cell_shift);
        const int64_t v = impulse_offset(fields, cube->frame[1], cube->origin_dot[1], cube->cell_shift);
        if (!within_reach(u, cube->reach_u) || !within_reach(v, cube->reach_v)) continue;
        out->along_tangent[kept] = u;
        out->along_bitangent[kept] = v;
        out->across[kept] = across;
        kept++;
    }
    return kept;
}

#endif

#if defined(__AVX2__)
/* The kernel's surface_reads (kernels.h): 8-bit textons only. */
int surface_texton_reads(const dsn_asset *asset, const dsn_surface_impulses *listed, uint32_t count,
                         uint32_t cell_shift, uint64_t *sums) {
    if (asset->bits != 8) return 0;
    if (asset->channels == 3)
        texton_reads<3>(asset, listed, count, cell_shift, sums);
    else
        texton_reads<1>(asset, listed, count, cell_shift, sums);
    return 1;
}
#define DSN_SURFACE_READS_ENTRY surface_texton_reads
#endif

} // namespace
/* The kernel entries (kernels.h): null where there is none. */
#define DSN_SURFACE_IMPULSES_ENTRY surface_impulses
#ifndef DSN_SURFACE_READS_ENTRY
#define DSN_SURFACE_READS_ENTRY 0
#endif
#else
#define DSN_SURFACE_IMPULSES_ENTRY 0
#define DSN_SURFACE_READS_ENTRY 0
#endif

#endif /* DSN_SURFACE_IMPULSES_H */
