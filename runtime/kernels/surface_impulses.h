/* runtime/kernels/surface_impulses.h - the impulses of one cube of the surface walk (core/surface_walk.h)
   that the slab and the reaches keep, as a kernel (kernels.h): each impulse's position hashed from the
   cube's key, its offsets from the point along the frame's three vectors taken exactly and floored to
   Q32.32, and those within the cube's reaches listed. On AVX-512, 8 impulses at once in 64-bit lanes (the
   dot products are 32 x 32-bit products: a position field has 16 bits, a frame component 31 and a sign),
   kept ones stored compressed; on AVX2 4 at once; elsewhere one at a time; the same bits everywhere. Internal
   to libdsn; not installed (everything here has internal linkage). */
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

} // namespace
/* The kernel entry (kernels.h): null where there is none. */
#define DSN_SURFACE_IMPULSES_ENTRY surface_impulses
#else
#define DSN_SURFACE_IMPULSES_ENTRY 0
#endif

#endif /* DSN_SURFACE_IMPULSES_H */
