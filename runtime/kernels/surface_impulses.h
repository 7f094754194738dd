/* runtime/kernels/surface_impulses.h - the impulses of one cube of the surface walk (core/surface_walk.h)
   that the slab and the reaches keep, as a kernel (kernels.h): each impulse's position hashed from the
   cube's key, its offsets from the point along the frame's three vectors taken exactly (Q.46), and those
   whose offsets floored to Q32.32 lie within the cube's reaches listed. On AVX-512, 8 impulses at once in
   64-bit lanes (the dot products are 32 x 32-bit products: a position field has 16 bits, a frame component 31
   and a sign), kept ones stored compressed; on AVX2 4 at once; elsewhere one at a time; the same bits
   everywhere. Also, on AVX-512 and AVX2, the reads of the listed impulses of an 8-bit texton or pyramid
   level, 8 or 4 at a time: the slab's window, the bilinear read and their product in 64-bit lanes (elsewhere
   the points read them one by one, surface_point.cpp and surface_filtered.cpp). Internal to libdsn; not
   installed (everything here has internal linkage). */
#ifndef DSN_SURFACE_IMPULSES_H
#define DSN_SURFACE_IMPULSES_H

#include "core/cell_hash.h"
#include "core/continuous_internal.h"
#include "kernels/kernels.h"
#include "simd/simd_mix64.h"

#if DSN_SURFACE
namespace {

/* What dsn_position_pair adds to (key << 32) per impulse index, and k times it as a lane. */
const uint64_t impulse_index_step = 0x9E3779B97F4A7C15u;
inline int64_t step(uint64_t k) { return signed_from_bits(k * impulse_index_step); }

/* 2 reach - 1 (reach in 1 .. 2^62), for within_reach's comparison. */
inline uint64_t reach_span(int64_t reach) { return static_cast<uint64_t>(reach) * 2u - 1u; }

/* A vector's whole stores of kept impulses stay within the list (store_kept). */
static_assert(dsn_surface_impulses_most % 8 == 0, "the lists hold whole vectors of 8 lanes");

/* Whether |value| < reach (reach in 1 .. 2^62), as one unsigned comparison. */
inline bool within_reach(int64_t value, int64_t reach) {
    return static_cast<uint64_t>(value) + static_cast<uint64_t>(reach - 1) < reach_span(reach);
}

#if defined(__AVX512F__) && defined(__AVX512BW__)

/* The operations the kernel's algorithms below use, on 8 lanes of 64 bits: masks are mask_8. */
struct SurfaceLanes {
    typedef vector_512 Vector;
    typedef mask_8 Mask;
    enum { count = 8 };
    /* Lane k: k times dsn_position_pair's step. */
    static Vector index_steps() {
        return set_lanes_8x64(0, step(1), step(2), step(3), step(4), step(5), step(6), step(7));
    }
    /* The first `lanes` lanes (all for 8 or more). */
    static Mask first(uint32_t lanes) { return static_cast<Mask>(lanes >= 8 ? 0xFFu : (1u << lanes) - 1u); }
    static bool none(Mask mask) { return mask == 0; }
    static Vector load(const int64_t *at, Mask mask) { return load_masked_8x64(at, mask); }
    static void store(uint64_t *at, Vector value) { store_8x64(at, value); }
    /* The lanes of mask of each value stored from at[v] on, packed in order; how many. Whole vectors are
       stored: they write entries past the last kept one, and never past the list's end, as kept <= k for
       the listing's step k (a multiple of 8, at most dsn_surface_impulses_most - 8). */
    static uint32_t store_kept(int64_t *const *at, Mask mask, const Vector *values, uint32_t) {
        for (uint32_t v = 0; v < 3; v++) store_8x64(at[v], compress_64(mask, values[v]));
        return static_cast<uint32_t>(__builtin_popcount(mask));
    }
    /* The lanes of `within` where a < b, unsigned. */
    static Mask below(Mask within, Vector a, Vector b) { return less_unsigned_64(within, a, b); }
    static Mask either(Mask a, Mask b) { return a | b; }
    /* 8 bytes from texton + at[k] (32-bit offsets) in the lanes of mask, else 0. */
    static Vector gather(const unsigned char *texton, Vector at, Mask mask) {
        return gather_masked_64<1>(texton, truncate_64x32(at), mask);
    }
    /* Byte `index` of every lane, sign-extended (at least into the lane's low half), where mask has the
       lane, else 0. */
    static Vector byte(Vector words, uint32_t index, Mask mask) {
        const Vector byte = shift_right_arithmetic_64(shift_left_64(words, 56u - 8u * index), 56);
        return and_64_where(zero_512(), mask, byte, set_8x64(-1));
    }
    /* All ones in the lanes of negative values. */
    static Vector negative(Vector value) { return shift_right_arithmetic_64(value, 63); }
    /* value clamped to [0, top]. */
    static Vector clamp(Vector value, Vector top) { return minimum_64(maximum_64(value, zero_512()), top); }
};

#elif defined(__AVX2__)

/* SurfaceLanes on 4 lanes: masks are vectors, all ones in a lane for true; the bytes are sign-extended
   into the lanes' low halves only (the products after them read only those). */
struct SurfaceLanes {
    typedef vector_256 Vector;
    typedef vector_256 Mask;
    enum { count = 4 };
    static Vector index_steps() { return set_lanes_4x64(0, step(1), step(2), step(3)); }
    static Mask first(uint32_t lanes) {
        return greater_64(set_4x64(static_cast<int64_t>(lanes)), set_lanes_4x64(0, 1, 2, 3));
    }
    static bool none(Mask mask) { return top_bits_of_32(mask) == 0; }
    static Vector load(const int64_t *at, Mask mask) { return load_masked_4x64(at, mask); }
    static void store(uint64_t *at, Vector value) { store_4x64(at, value); }
    /* Each vector packed by a permutation and stored whole: its lanes past the kept ones land at most 3
       entries past the last kept one, and never past the list's end, as kept <= k for the listing's
       step k (a multiple of 4, at most dsn_surface_impulses_most - 4). */
    static uint32_t store_kept(int64_t *const *at, Mask mask, const Vector *values, uint32_t) {
        /* Row b: the 32-bit lane order that packs the 64-bit lanes of mask bits b first, in order. */
        /* clang-format off */
        static const int32_t packed[16][8] = {
            {0, 1, 2, 3, 4, 5, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7},
            {2, 3, 0, 1, 4, 5, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7},
            {4, 5, 0, 1, 2, 3, 6, 7}, {0, 1, 4, 5, 2, 3, 6, 7},
            {2, 3, 4, 5, 0, 1, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7},
            {6, 7, 0, 1, 2, 3, 4, 5}, {0, 1, 6, 7, 2, 3, 4, 5},
            {2, 3, 6, 7, 0, 1, 4, 5}, {0, 1, 2, 3, 6, 7, 4, 5},
            {4, 5, 6, 7, 0, 1, 2, 3}, {0, 1, 4, 5, 6, 7, 2, 3},
            {2, 3, 4, 5, 6, 7, 0, 1}, {0, 1, 2, 3, 4, 5, 6, 7}};
        /* clang-format on */
        const uint32_t bits = static_cast<uint32_t>(top_bits_of_64(mask));
        const Vector order =
            load_8x32(static_cast<const uint32_t *>(static_cast<const void *>(packed[bits])));
        for (int v = 0; v < 3; v++) store_4x64(at[v], permute_32(values[v], order));
        return static_cast<uint32_t>(__builtin_popcount(bits));
    }
    static Mask below(Mask within, Vector a, Vector b) {
        const Vector top = set_4x64(INT64_MIN);
        return bitwise_and(within, greater_64(bitwise_xor(b, top), bitwise_xor(a, top)));
    }
    static Mask either(Mask a, Mask b) { return bitwise_or(a, b); }
    static Vector gather(const unsigned char *texton, Vector at, Mask mask) {
        return gather_masked_64<1>(texton, low_128(permute_32(at, set_lanes_8x32(0, 2, 4, 6, 0, 2, 4, 6))),
                                   mask);
    }
    static Vector byte(Vector words, uint32_t index, Mask mask) {
        const Vector half = index >= 4 ? shift_right_logical_64(words, 32) : words;
        return bitwise_and(shift_right_arithmetic_32(shift_left_32(half, 24u - 8u * (index & 3u)), 24), mask);
    }
    static Vector negative(Vector value) { return greater_64(zero_256(), value); }
    static Vector clamp(Vector value, Vector top) {
        const Vector positive = and_not(greater_64(zero_256(), value), value),
                     over = greater_64(positive, top);
        return bitwise_or(and_not(over, positive), bitwise_and(over, top));
    }
};

#endif

#if defined(__AVX2__)
/* ---- The listing and the reads, written once on SurfaceLanes ---- */
typedef SurfaceLanes::Vector LaneVector;
typedef SurfaceLanes::Mask LaneMask;

DSN_SIMD_INLINE LaneVector all_lanes(int64_t value) {
    return all_lanes_64<LaneVector>(static_cast<uint64_t>(value));
}

/* The lanes of `within` whose value lies within the reach (within_reach on every lane). */
DSN_SIMD_INLINE LaneMask lanes_within(LaneMask within, LaneVector value, int64_t reach) {
    return SurfaceLanes::below(within, add_64(value, all_lanes(reach - 1)),
                               all_lanes_64<LaneVector>(reach_span(reach)));
}

/* The three 16-bit position fields of the impulses whose dsn_position_pair inputs are `indices`. */
DSN_SIMD_INLINE void impulse_fields(LaneVector indices, LaneVector *fields) {
    const LaneVector pair = mix64_lanes(indices), field_mask = all_lanes(0xFFFF);
    fields[0] = bitwise_and(pair, field_mask);
    fields[1] = bitwise_and(shift_right_logical_64(pair, 16), field_mask);
    fields[2] = bitwise_and(shift_right_logical_64(pair, 32), field_mask);
}

/* Every lane divided by 2^bits, rounded down (floor_shift, through a 2^63 bias). */
DSN_SIMD_INLINE LaneVector floor_lanes(LaneVector value, uint32_t bits) {
    const LaneVector bias = all_lanes(INT64_MIN);
    return subtract_64(shift_right_logical_64(add_64(value, bias), bits), shift_right_logical_64(bias, bits));
}

/* One offset of the impulses, Q.46: one frame vector's dot products with their 16-bit fields (a 32 x
   32-bit product each) subtracted from the origin's. */
DSN_SIMD_INLINE LaneVector offset_lanes(const LaneVector *fields, const int32_t *vector, int64_t origin_dot,
                                        uint32_t cell_shift) {
    const LaneVector dot = add_64(add_64(multiply_even_32(fields[0], all_lanes(vector[0])),
                                         multiply_even_32(fields[1], all_lanes(vector[1]))),
                                  multiply_even_32(fields[2], all_lanes(vector[2])));
    return subtract_64(all_lanes(origin_dot), shift_left_64(dot, cell_shift));
}

uint32_t surface_impulses(const dsn_surface_cube *cube, dsn_surface_impulses *out) {
    const uint32_t width = SurfaceLanes::count;
    const LaneVector index_steps = SurfaceLanes::index_steps();
    int64_t *const outputs[3] = {out->along_tangent, out->along_bitangent, out->across};
    uint64_t index = (static_cast<uint64_t>(cube->key) << 32) + cube->first * impulse_index_step;
    uint32_t kept = 0;
    for (uint32_t k = 0; k < cube->count; k += width, index += width * impulse_index_step) {
        LaneVector fields[3];
        impulse_fields(add_64(all_lanes_64<LaneVector>(index), index_steps), fields);
        /* Across the slab first: it leaves out about half. */
        LaneVector offsets[3];
        offsets[2] = offset_lanes(fields, cube->frame[2], cube->origin_dot[2], cube->cell_shift);
        LaneMask keep = lanes_within(SurfaceLanes::first(cube->count - k), floor_lanes(offsets[2], 14),
                                     cube->reach_across);
        if (SurfaceLanes::none(keep)) continue;
        offsets[0] = offset_lanes(fields, cube->frame[0], cube->origin_dot[0], cube->cell_shift);
        keep = lanes_within(keep, floor_lanes(offsets[0], 14), cube->reach_u);
        offsets[1] = offset_lanes(fields, cube->frame[1], cube->origin_dot[1], cube->cell_shift);
        keep = lanes_within(keep, floor_lanes(offsets[1], 14), cube->reach_v);
        int64_t *const at[3] = {outputs[0] + kept, outputs[1] + kept, outputs[2] + kept};
        kept += SurfaceLanes::store_kept(at, keep, offsets, cube->count - k);
    }
    return kept;
}

#else

/* One offset of an impulse, Q.46 (one frame vector's dot product with its 16-bit fields, subtracted from
   the origin's). */
inline int64_t impulse_offset(const int64_t *fields, const int32_t *vector, int64_t origin_dot,
                              uint32_t cell_shift) {
    const int64_t dot = fields[0] * vector[0] + fields[1] * vector[1] + fields[2] * vector[2];
    return signed_from_bits(static_cast<uint64_t>(origin_dot) - (static_cast<uint64_t>(dot) << cell_shift));
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
        if (!within_reach(floor_shift(across, 14), cube->reach_across)) continue;
        const int64_t u = impulse_offset(fields, cube->frame[0], cube->origin_dot[0], cube->cell_shift);
        const int64_t v = impulse_offset(fields, cube->frame[1], cube->origin_dot[1], cube->cell_shift);
        if (!within_reach(floor_shift(u, 14), cube->reach_u) ||
            !within_reach(floor_shift(v, 14), cube->reach_v))
            continue;
        out->along_tangent[kept] = u;
        out->along_bitangent[kept] = v;
        out->across[kept] = across;
        kept++;
    }
    return kept;
}

#endif

#if defined(__AVX2__)
/* ---- The unfiltered point's reads ---- */

/* slab_window (core/surface_walk.h) on every lane: the offsets across (Q32.32, under 3/4 of a cube) to
   the windows (Q16), the smoothstep's steps clamped so that 0 and 65536 come from the same polynomial. */
DSN_SIMD_INLINE LaneVector window_lanes(LaneVector across, uint32_t cell_shift) {
    const LaneVector sign = SurfaceLanes::negative(across);
    const LaneVector magnitude = subtract_64(bitwise_xor(across, sign), sign);
    const LaneVector s = shift_right_logical_64(
        multiply_even_unsigned_32(shift_right_logical_64(magnitude, 16), all_lanes(89878)), 16u + cell_shift);
    const LaneVector one = all_lanes(65536);
    const LaneVector u = SurfaceLanes::clamp(subtract_64(shift_left_64(s, 1), one), one);
    const LaneVector square = shift_right_logical_64(multiply_even_unsigned_32(u, u), 16);
    const LaneVector slope = subtract_64(all_lanes(196608), shift_left_64(u, 1));
    return subtract_64(one, shift_right_logical_64(multiply_even_unsigned_32(square, slope), 16));
}

/* windowed on every lane (|value| < 2^47, window <= 2^16): the window's 32 x 32-bit products with the
   value's halves (bits 32 .. 63, signed, read from a lane's low half), floored through a 2^63 bias. */
DSN_SIMD_INLINE LaneVector windowed_lanes(LaneVector value, LaneVector window) {
    const LaneVector high = multiply_even_32(shift_right_logical_64(value, 32), window);
    const LaneVector product = add_64(shift_left_64(high, 32), multiply_even_unsigned_32(value, window));
    const LaneVector bias = all_lanes(INT64_MIN);
    return subtract_64(shift_right_logical_64(add_64(product, bias), 16), shift_right_logical_64(bias, 16));
}

/* The reads of one vector of listed impulses (those of `lanes`; their offsets already divided by the
   level's spacing), added to sums[c] lane by lane. Each row's two texels come from one 8-byte read from 4
   bytes before the right texel, as continuous_point_vector.h's texton_pairs_16 reads them (within 4 bytes
   before the window and 4 past it: kernels.h's dsn_surface_texels): the left texel's channels end at byte
   3, the right one's start at byte 4; each is 0 outside the window. The bilinear sum is add_bilinear's
   integer, in its row form. */
template <uint32_t Channels>
DSN_SIMD_INLINE void add_reads(const dsn_surface_texels *texels, LaneVector along_tangent,
                               LaneVector along_bitangent, LaneVector window, LaneMask lanes,
                               LaneVector *sums) {
    const uint32_t width = texels->width, height = texels->height;
    const LaneVector weight_bits = all_lanes(bilinear_weight_mask), one = all_lanes(1);
    const LaneVector shifted_x =
        add_64(along_tangent, all_lanes(static_cast<int64_t>((width + 1u) / 2u) << 32));
    const LaneVector shifted_y =
        add_64(along_bitangent, all_lanes(static_cast<int64_t>((height + 1u) / 2u) << 32));
    const LaneVector right_column = shift_right_logical_64(shifted_x, 32),
                     lower_row = shift_right_logical_64(shifted_y, 32);
    const LaneVector row = subtract_64(lower_row, one);
    const LaneVector across = bitwise_and(shift_right_logical_64(shifted_x, 16), weight_bits),
                     down = bitwise_and(shift_right_logical_64(shifted_y, 16), weight_bits);
    const LaneVector columns = all_lanes(width), rows = all_lanes(height);
    const LaneMask left = SurfaceLanes::below(lanes, subtract_64(right_column, one), columns),
                   right = SurfaceLanes::below(lanes, right_column, columns);
    const LaneMask top = SurfaceLanes::below(SurfaceLanes::either(left, right), row, rows),
                   bottom = SurfaceLanes::below(SurfaceLanes::either(left, right), lower_row, rows);
    const LaneVector entry = add_64(multiply_even_unsigned_32(row, all_lanes(texels->stride)), right_column);
    const LaneVector at = subtract_64(multiply_even_unsigned_32(entry, all_lanes(Channels)), all_lanes(4));
    const LaneVector below = add_64(at, all_lanes(texels->stride * Channels));
    const LaneVector upper_words = SurfaceLanes::gather(texels->values, at, top),
                     lower_words = SurfaceLanes::gather(texels->values, below, bottom);
    const LaneVector scale = all_lanes(65536);
    for (uint32_t c = 0; c < Channels; c++) {
        const LaneVector a = SurfaceLanes::byte(upper_words, 4u - Channels + c, left),
                         b = SurfaceLanes::byte(upper_words, 4u + c, right),
                         d = SurfaceLanes::byte(lower_words, 4u - Channels + c, left),
                         e = SurfaceLanes::byte(lower_words, 4u + c, right);
        const LaneVector upper =
            add_64(multiply_even_32(a, scale), multiply_even_32(across, subtract_64(b, a)));
        const LaneVector lower =
            add_64(multiply_even_32(d, scale), multiply_even_32(across, subtract_64(e, d)));
        const LaneVector value =
            add_64(shift_left_64(upper, 16), multiply_even_32(down, subtract_64(lower, upper)));
        sums[c] = add_64(sums[c], windowed_lanes(value, window));
    }
}

/* The reads of the listed impulses moved by `moved` (Q.46), a vector at a time: each offset floored to
   Q32.32 and divided by the level's spacing (one floor: by 2^(14 + level)), each lane's sums added to sums
   at the end. */
template <uint32_t Channels>
void texel_reads(const dsn_surface_texels *texels, const dsn_surface_impulses *listed, uint32_t count,
                 uint32_t cell_shift, const int64_t *moved, uint64_t *sums) {
    const uint32_t width = SurfaceLanes::count, along_shift = 14u + texels->level;
    const LaneVector moved_u = all_lanes(moved[0]), moved_v = all_lanes(moved[1]),
                     moved_across = all_lanes(moved[2]);
    LaneVector lanes[Channels];
    for (uint32_t c = 0; c < Channels; c++) lanes[c] = all_lanes(0);
    for (uint32_t k = 0; k < count; k += width) {
        const LaneMask valid = SurfaceLanes::first(count - k);
        const LaneVector across = add_64(SurfaceLanes::load(listed->across + k, valid), moved_across);
        const LaneVector window = window_lanes(floor_lanes(across, 14), cell_shift);
        const LaneVector u = add_64(SurfaceLanes::load(listed->along_tangent + k, valid), moved_u),
                         v = add_64(SurfaceLanes::load(listed->along_bitangent + k, valid), moved_v);
        add_reads<Channels>(texels, floor_lanes(u, along_shift), floor_lanes(v, along_shift), window, valid,
                            lanes);
    }
    for (uint32_t c = 0; c < Channels; c++) {
        uint64_t parts[SurfaceLanes::count];
        SurfaceLanes::store(parts, lanes[c]);
        for (uint32_t part = 0; part < width; part++) sums[c] += parts[part];
    }
}

/* The kernel's surface_reads (kernels.h). */
void surface_reads(const dsn_surface_texels *texels, const dsn_surface_impulses *listed, uint32_t count,
                   uint32_t cell_shift, const int64_t *moved, uint64_t *sums) {
    if (texels->channels == 3)
        texel_reads<3>(texels, listed, count, cell_shift, moved, sums);
    else
        texel_reads<1>(texels, listed, count, cell_shift, moved, sums);
}
#define DSN_SURFACE_READS_ENTRY surface_reads
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
