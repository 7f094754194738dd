/* runtime/kernels/continuous_batch_group.h - the batch of continuous points for the noises the vector
   per-point evaluator takes (continuous_point_vector.h), 8 points at a time with a point in each vector lane:
   their cells along non-periodic axes (periodic ones point by point), and the keys and impulse counts of the
   3 x 3 cells a usual point has (the counts by comparisons with the Poisson table, no search; AVX-512: by
   the two-step search on 16 lanes, counts_16), and the first two pairs of those cells hashed and sifted
   with a pair in each 64-bit lane (group_pairs), then each point's candidates packed and visited by the
   per-point evaluator's code, its texels read from the batch's quad table where the call built it
   (continuous_batch.h: one gather per channel, AVX-512 two channels a read; no test at the window's edge;
   continuous_batch.cpp builds it for large batches only), and the group's sums normalized on vectors, a
   point in each 64-bit lane (splat_row.h). A point with more cells along an axis goes through the
   per-point evaluator. The same cells, keys, counts and pairs as per point, so the same bits. The
   gradient (batch_group_gradients) takes the same groups, sifted with the entry edge, each point's
   candidates visited with their slopes (continuous_point_vector.h's SlopeVisit). Internal to libdsn; not
   installed (everything here has internal linkage). */
#ifndef DSN_CONTINUOUS_BATCH_GROUP_H
#define DSN_CONTINUOUS_BATCH_GROUP_H

#include "core/gradient_output.h"
#include "kernels/continuous_point_vector.h"
#include "kernels/splat_row.h"
#include "simd/simd_mix64.h"

#if DSN_GRADIENTS
namespace {
/* A point's gradient (dsn_internal_continuous_gradient's values: value, dx, dy, DSN_MAX_CHANNELS apart)
   into the batch's outputs at value `first`. */
inline void store_gradient_point(const int32_t *values, uint32_t channels, size_t first, int32_t *out,
                                 int32_t *dx, int32_t *dy) {
    for (uint32_t c = 0; c < channels; c++) {
        out[first + c] = values[c];
        dx[first + c] = values[DSN_MAX_CHANNELS + c];
        dy[first + c] = values[2 * DSN_MAX_CHANNELS + c];
    }
}
} // namespace
#endif

#if defined(__AVX2__)
namespace {

const uint32_t group_points = 8; /* points a group's vectors hold */
const uint32_t group_cells = 3;  /* cells along each axis a group's vectors hold */

/* What a group's points share: the Poisson table's thresholds with their top bits flipped (compared as
   signed numbers). */
struct GroupShared {
    FieldLanes lanes;
    uint32_t flipped_cdf[sizeof(dsn_noise_state::poisson_cdf) / sizeof(uint32_t)];
    bool one_draw; /* a cell's count is one draw */
#if defined(__AVX512F__) && defined(__AVX512BW__)
    bool by_tables; /* the counts by counts_16 (count_tables_fit) */
    CountTables tables;
#endif
};

inline GroupShared group_shared(const dsn_noise_state *noise) {
    GroupShared shared;
    shared.lanes = field_lanes(noise->cell_shift);
    for (uint32_t k = 0; k < noise->poisson_size; k++)
        shared.flipped_cdf[k] = noise->poisson_cdf[k] ^ 0x80000000u;
    shared.one_draw = noise->poisson_parts == 1;
#if defined(__AVX512F__) && defined(__AVX512BW__)
    shared.by_tables = count_tables_fit(noise);
    if (shared.by_tables) count_tables(noise, &shared.tables);
#endif
    return shared;
}

/* dsn_poisson_draw of 8 uniforms (the keys: a cell's count when it is one draw), without a search: the
   thresholds cdf[0 .. size - 1] increase, so those at or below the uniform are the n below the smallest
   with uniform < cdf[n] (the guide only skips some of them), and the count is size less those above. */
inline vector_256 group_counts(const dsn_noise_state *noise, const GroupShared &shared, vector_256 keys) {
    const vector_256 flipped = bitwise_xor(keys, set_8x32(0x80000000u));
    vector_256 above = zero_256(); /* minus their number */
    for (uint32_t k = 0; k < noise->poisson_size; k++)
        above = add_32(above, greater_32(set_8x32(shared.flipped_cdf[k]), flipped));
    return add_32(set_8x32(noise->poisson_size), above);
}

/* A group's cells along one axis, cell i of point p at [i][p]: its index, floor(shifted_base / 2^16)
   (AxisCells's base) and its sifting bounds (CellAxis's low_lanes and high_lanes: 8-bit lanes, which the
   noises of the vector evaluator have, so that one 32-bit word holds a bound's repeating bytes); passes[i]:
   the points (bit p) whose cell i may reach them. Along a non-periodic axis cell i is the window's first
   cell + i, along a periodic one the i-th that axis_cells lists: a candidate's cell index means the same
   cell at every step, and the sums do not depend on the order of the cells. */
struct GroupAxis {
    uint32_t cell[group_cells][group_points], base[group_cells][group_points];
    uint32_t low[group_cells][group_points], high[group_cells][group_points];
    uint32_t passes[group_cells];
};

/* The group's cells along a non-periodic axis (`axis`: 0 for x, 1 for y), a point in each 32-bit lane:
   axis_cells(point_axis(...)) unpacked. The window's cells (dsn_axis_span's first cell and count), and
   for each cell cell_axis_within's bounds on the field halves. With the cell's offset W = X - origin (X the
   point's integer part, small: the cell is one of the point's) and the fraction f,
   shifted_base = (W + radius + 1) 2^32 + f, and the halves' bounds floor((shifted_base - 2 reach) / 2^k)
   and floor((shifted_base - 1) / 2^k), k = 28 + shift (4-bit halves, shift <= 4), are
   (W - radius - 1) 2^(32 - k) + (f >> k) and (W + radius + 1) 2^(32 - k) + ((f - 1) >> k), less
   2^(32 - k) where f = 0 (f - 1 wraps to 2^32 - 1 there, where the floor of -1 / 2^k is -1). EntryEdge
   (the gradient's cell_axis_with_entry_edge): the high bound floor(shifted_base / 2^k),
   (W + radius + 1) 2^(32 - k) + (f >> k). Returns the points (bit p) whose window has at most
   group_cells cells. */
template <bool EntryEdge>
inline uint32_t group_axis(const dsn_noise_state *noise, uint32_t axis, const int64_t *coordinates,
                           uint32_t count, GroupAxis *cells) {
    uint32_t whole[group_points], fraction[group_points];
    for (uint32_t p = 0; p < group_points; p++) {
        const uint64_t coordinate = p < count ? static_cast<uint64_t>(coordinates[p]) : 0u;
        whole[p] = static_cast<uint32_t>(coordinate >> 32), fraction[p] = static_cast<uint32_t>(coordinate);
    }
    const uint32_t radius = noise->radius[axis], shift = noise->cell_shift, up = 4u - shift;
    const vector_128 by_shift = shift_count(static_cast<int>(shift)),
                     by_up = shift_count(static_cast<int>(up));
    const vector_128 by_k = shift_count(static_cast<int>(28u + shift));
    const vector_256 x = load_8x32(whole), f = load_8x32(fraction), one = set_8x32(1);
    /* dsn_axis_span of the window [X - 1, X + 1]: its low end X - 1 - radius */
    const vector_256 low = subtract_32(x, set_8x32(1u + radius));
    const vector_256 first_cell = shift_right_logical_32_by(low, by_shift);
    const vector_256 cell_count = add_32(
        shift_right_logical_32_by(
            add_32(bitwise_and(low, set_8x32((1u << shift) - 1u)), set_8x32(2u + 2u * radius)), by_shift),
        one);
    const uint32_t fits =
        static_cast<uint32_t>(top_bits_of_32(greater_32(set_8x32(group_cells + 1u), cell_count)));
    const vector_256 sign = set_8x32(0x80000000u), room_limit = set_8x32(((1u << shift) - 1u) ^ 0x80000000u);
    const vector_256 f_high = EntryEdge ? f : subtract_32(f, one);
    const vector_256 f_zero =
        EntryEdge ? zero_256() : bitwise_and(equal_32(f, zero_256()), set_8x32(0u - (1u << up)));
    const vector_256 bytes = set_8x32(0x01010101u), tops = set_8x32(0x80808080u); /* FieldLanes's */
    for (uint32_t i = 0; i < group_cells; i++) {
        const vector_256 index = bitwise_and(add_32(first_cell, set_8x32(i)), set_8x32(0xFFFFFFFFu >> shift));
        const vector_256 origin = shift_left_32_by(index, by_shift), w = subtract_32(x, origin);
        const vector_256 low_half = add_32(shift_left_32_by(subtract_32(w, set_8x32(radius + 1u)), by_up),
                                           shift_right_logical_32_by(f, by_k));
        vector_256 high_half = add_32(add_32(shift_left_32_by(add_32(w, set_8x32(radius + 1u)), by_up),
                                             shift_right_logical_32_by(f_high, by_k)),
                                      f_zero);
        /* the period's end (none: last_position 2^32 - 1) */
        const vector_256 room = bitwise_xor(origin, set_8x32(0xFFFFFFFFu));
        const vector_256 short_room = greater_32(room_limit, bitwise_xor(room, sign));
        const vector_256 end = blend_bytes(
            set_8x32(15), bitwise_or(shift_left_32_by(room, by_up), set_8x32((1u << up) - 1u)), short_room);
        high_half = minimum_32(high_half, end);
        const vector_256 first_half = maximum_32(low_half, zero_256());
        const vector_256 pass =
            and_not(greater_32(first_half, high_half), greater_32(cell_count, set_8x32(i)));
        cells->passes[i] = static_cast<uint32_t>(top_bits_of_32(pass));
        store_8x32(cells->cell[i], index);
        store_8x32(cells->base[i], add_32(shift_left_32(add_32(w, set_8x32(radius + 1u)), 16),
                                          shift_right_logical_32(f, 16)));
        /* where the cell passes, 0 <= first_half <= high_half <= 15: one byte each */
        store_8x32(cells->low[i], bitwise_and(pass, multiply_32(first_half, bytes)));
        store_8x32(cells->high[i], bitwise_and(pass, bitwise_or(multiply_32(high_half, bytes), tops)));
    }
    return fits;
}

/* group_axis along a periodic axis, point by point (axis_cells). */
template <bool EntryEdge>
inline uint32_t group_periodic_axis(const dsn_noise_state *noise, uint32_t axis, const int64_t *coordinates,
                                    uint32_t count, const FieldLanes &lanes, GroupAxis *cells) {
    uint32_t fits = 0;
    for (uint32_t i = 0; i < group_cells; i++) cells->passes[i] = 0;
    for (uint32_t p = 0; p < group_points; p++) {
        AxisCells point;
        point.count = 0;
        if (p < count &&
            axis_cells<EntryEdge>(point_axis(static_cast<uint64_t>(coordinates[p]), noise->radius[axis],
                                             noise->cell_shift, noise->period[axis]),
                                  lanes, &point) &&
            point.count <= group_cells)
            fits |= 1u << p;
        else
            point.count = 0;
        for (uint32_t i = 0; i < group_cells; i++) {
            const bool there = i < point.count;
            cells->cell[i][p] = there ? point.cell[i] : 0u, cells->base[i][p] = there ? point.base[i] : 0u;
            cells->low[i][p] = there ? static_cast<uint32_t>(point.axis[i].low_lanes) : 0u;
            cells->high[i][p] = there ? static_cast<uint32_t>(point.axis[i].high_lanes) : 0u;
            cells->passes[i] |= static_cast<uint32_t>(there) << p;
        }
    }
    return fits;
}

/* The cells of a group's points, and the keys and counts of their first group_cells x group_cells cells:
   cell (column i, row j) of point p at keys[(j group_cells + i) group_points + p], the count 0 where
   either cell does not pass (and for the points that do not fit). */
struct PointGroup {
    GroupAxis columns, rows;
    uint32_t keys[group_cells * group_cells * group_points], counts[group_cells * group_cells * group_points];
};

/* The impulse counts of the cells of 8 points with these keys (also in memory at keys). */
inline vector_256 cell_counts(const dsn_noise_state *noise, const GroupShared &shared, vector_256 key,
                              const uint32_t *keys) {
#if defined(__AVX512F__) && defined(__AVX512BW__)
    if (shared.by_tables) return low_256(counts_16(noise, shared.tables, cast_to_512(key)));
#endif
    if (shared.one_draw) return group_counts(noise, shared, key);
    uint32_t counts[group_points];
    for (uint32_t p = 0; p < group_points; p++) counts[p] = dsn_cell_impulse_count(noise, keys[p]);
    return load_8x32(counts);
}

/* All ones in the lanes p of `points` (bit p). */
inline vector_256 point_lanes(uint32_t points) {
    const vector_256 bits = set_lanes_8x32(1, 2, 4, 8, 16, 32, 64, 128);
    return equal_32(bitwise_and(set_8x32(points), bits), bits);
}

/* Fills the group for points xs[0 .. count - 1], count <= group_points; returns the points (bit p) whose
   cells fit the vectors (at most group_cells along each axis). EntryEdge: the gradient's sifting. */
template <bool EntryEdge>
inline uint32_t fill_group(const dsn_noise_state *noise, const GroupShared &shared, const int64_t *xs,
                           const int64_t *ys, uint32_t count, PointGroup *group) {
    const uint32_t fits_x =
        noise->period[0] == 0
            ? group_axis<EntryEdge>(noise, 0, xs, count, &group->columns)
            : group_periodic_axis<EntryEdge>(noise, 0, xs, count, shared.lanes, &group->columns);
    const uint32_t fits_y =
        noise->period[1] == 0
            ? group_axis<EntryEdge>(noise, 1, ys, count, &group->rows)
            : group_periodic_axis<EntryEdge>(noise, 1, ys, count, shared.lanes, &group->rows);
    const uint32_t fits = fits_x & fits_y & ((1u << count) - 1u);
    const vector_256 seed_row = set_8x32(noise->seed_row), seed_column = set_8x32(noise->seed_column);
    for (uint32_t j = 0; j < group_cells; j++) {
        const vector_256 row_key =
            mix32_lanes(add_32(load_8x32(group->rows.cell[j]), seed_row)); /* dsn_row_key */
        const vector_256 row_there = point_lanes(group->rows.passes[j] & fits);
        for (uint32_t i = 0; i < group_cells; i++) {
            uint32_t *keys = group->keys + (j * group_cells + i) * group_points;
            uint32_t *counts = group->counts + (j * group_cells + i) * group_points;
            const vector_256 key =
                mix32_lanes(add_32(bitwise_xor(load_8x32(group->columns.cell[i]), seed_column), row_key));
            store_8x32(keys, key);
            const vector_256 there = bitwise_and(row_there, point_lanes(group->columns.passes[i]));
#if defined(__AVX512F__) && defined(__AVX512BW__)
            if (shared.by_tables) { /* the counts below, two cells a vector */
                store_8x32(counts, there);
                continue;
            }
#endif
            store_8x32(counts, bitwise_and(cell_counts(noise, shared, key, keys), there));
        }
    }
#if defined(__AVX512F__) && defined(__AVX512BW__)
    if (shared.by_tables) {
        const uint32_t cells = group_cells * group_cells * group_points;
        uint32_t at = 0;
        for (; at + 16u <= cells; at += 16u)
            store_16x32(group->counts + at,
                        bitwise_and(counts_16(noise, shared.tables, load_16x32(group->keys + at)),
                                    load_16x32(group->counts + at)));
        for (; at < cells; at += group_points)
            store_8x32(group->counts + at,
                       bitwise_and(cell_counts(noise, shared, load_8x32(group->keys + at), group->keys + at),
                                   load_8x32(group->counts + at)));
    }
#endif
    return fits;
}

/* The first two pairs of every cell of a group's points and their candidates (add_first_pairs' sifted
   bits), computed on vectors a pair in each 64-bit lane, the two pairs of a point side by side. */
struct GroupPairs {
    uint64_t pairs[group_cells * group_cells][2 * group_points];  /* point p's first two at 2p, 2p + 1 */
    uint32_t sifted[group_cells * group_cells][group_points / 2]; /* p's 16 bits at 16 (p % 2) of [p / 2] */
};

/* What group_pairs adds to (key << 32) of pairs 0 and 1: index 0x9E3779B97F4A7C15 (dsn_position_pair). */
const long long pair_1_step = -0x61C8864680B583EB; /* 0x9E3779B97F4A7C15 */

/* candidate_lanes of a pair in each 64-bit lane, given each lane's bounds (CellAxis's low_lanes and
   high_lanes): the top bit of each 8-bit lane whose impulse may reach its point. */
inline splat_vector sifted_lanes(splat_vector pairs, splat_vector halves, splat_vector tops,
                                 splat_vector low_x, splat_vector high_x, splat_vector low_y,
                                 splat_vector high_y) {
    const splat_vector halves_x = splat_and(pairs, halves),
                       halves_y = splat_and(splat_shift_right(pairs, 4), halves);
    const splat_vector in_x =
        splat_and(splat_sub(splat_or(halves_x, tops), low_x), splat_sub(high_x, halves_x));
    const splat_vector in_y =
        splat_and(splat_sub(splat_or(halves_y, tops), low_y), splat_sub(high_y, halves_y));
    return splat_and(in_x, in_y);
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* A sifting bound's word of each point (GroupAxis) in both of its 64-bit lanes: `four` holds the first
   point's index 4 times, then the next's. */
inline vector_512 bound_lanes(vector_512 four, const uint32_t *words) {
    return permute_32(cast_to_512(load_8x32(words)), four);
}

/* add_first_pairs' pairs and sifted bits of every cell of the group (the cells past a point's, defined
   values unused): dsn_position_pair(key, 0) and (key, 1), candidate_lanes of both with the lanes' top bits
   gathered by one byte movemask for 4 points, less the impulses at or past the cell's count (each
   byte's impulse index compared with the count). */
inline void group_pairs(const PointGroup &group, const FieldLanes &lanes, GroupPairs *out) {
    const vector_512 halves = set_8x64(static_cast<int64_t>(lanes.halves)),
                     tops = set_8x64(static_cast<int64_t>(lanes.tops));
    const vector_512 second = set_lanes_8x64(0, pair_1_step, 0, pair_1_step, 0, pair_1_step, 0, pair_1_step);
    const vector_512 impulse =
        broadcast_lanes(set_lanes_16x8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
    const vector_512 most = set_16x32(16);
    for (uint32_t quarter = 0; quarter < 2; quarter++) { /* points 4 quarter .. 4 quarter + 3 */
        const uint32_t from = 4u * quarter;
        const vector_256 twice = add_32(set_lanes_8x32(0, 0, 1, 1, 2, 2, 3, 3), set_8x32(from));
        const vector_512 four =
            add_32(set_lanes_16x32(0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3), set_16x32(from));
#pragma GCC unroll 9
        for (uint32_t cell = 0; cell < group_cells * group_cells; cell++) {
            const uint32_t i = cell % group_cells, j = cell / group_cells;
            const vector_512 keys =
                widen_unsigned_32x64(permute_32(load_8x32(group.keys + cell * group_points), twice));
            const vector_512 pairs = mix64_lanes(add_64(shift_left_64(keys, 32), second));
            const vector_512 counts = minimum_unsigned_32(
                permute_32(cast_to_512(load_8x32(group.counts + cell * group_points)), four), most);
            /* every byte of a point's 128 bits: its count (below 256) */
            const mask_64 exist = greater_unsigned_8(shuffle_bytes(counts, zero_512()), impulse);
            const vector_512 in_reach =
                sifted_lanes(pairs, halves, tops, bound_lanes(four, group.columns.low[i]),
                             bound_lanes(four, group.columns.high[i]), bound_lanes(four, group.rows.low[j]),
                             bound_lanes(four, group.rows.high[j]));
            const uint64_t sifted = mask_bits(exist & top_bits_of_bytes(in_reach));
            out->sifted[cell][2u * quarter] = static_cast<uint32_t>(sifted);
            out->sifted[cell][2u * quarter + 1u] = static_cast<uint32_t>(sifted >> 32);
            store_8x64(out->pairs[cell] + 2u * from, pairs);
        }
    }
}
#else
/* bound_lanes of the AVX-512 copy on AVX2 vectors, 2 points. */
inline vector_256 bound_lanes(vector_256 four, const uint32_t *words) {
    return permute_32(load_8x32(words), four);
}

/* group_pairs of the AVX-512 copy on AVX2 vectors, 2 points a vector: add_pair's pairs 0 and 1 and their
   sifted bits (candidate_lanes' top bits by one byte movemask, less the impulses at or past the count). */
inline void group_pairs(const PointGroup &group, const FieldLanes &lanes, GroupPairs *out) {
    const vector_256 halves = set_4x64(static_cast<int64_t>(lanes.halves)),
                     tops = set_4x64(static_cast<int64_t>(lanes.tops));
    const vector_256 second = set_lanes_4x64(0, pair_1_step, 0, pair_1_step);
    const vector_256 impulse = set_lanes_32x8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 0, 1, 2,
                                              3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const vector_256 most = set_8x32(16);
    for (uint32_t half = 0; half < group_points / 2; half++) { /* points 2 half and 2 half + 1 */
        const uint32_t from = 2u * half;
        const vector_256 twice = add_32(set_lanes_8x32(0, 0, 1, 1, 0, 0, 0, 0), set_8x32(from));
        const vector_256 four = add_32(set_lanes_8x32(0, 0, 0, 0, 1, 1, 1, 1), set_8x32(from));
#pragma GCC unroll 9
        for (uint32_t cell = 0; cell < group_cells * group_cells; cell++) {
            const uint32_t i = cell % group_cells, j = cell / group_cells;
            const vector_256 keys =
                widen_unsigned_32x64(low_128(permute_32(load_8x32(group.keys + cell * group_points), twice)));
            const vector_256 pairs = mix64_lanes(add_64(shift_left_64(keys, 32), second));
            const vector_256 counts =
                minimum_unsigned_32(permute_32(load_8x32(group.counts + cell * group_points), four), most);
            /* every byte of a point's 128 bits: its count (at most 16) */
            const vector_256 exist = greater_8(shuffle_bytes(counts, zero_256()), impulse);
            const vector_256 in_reach =
                sifted_lanes(pairs, halves, tops, bound_lanes(four, group.columns.low[i]),
                             bound_lanes(four, group.columns.high[i]), bound_lanes(four, group.rows.low[j]),
                             bound_lanes(four, group.rows.high[j]));
            out->sifted[cell][half] = static_cast<uint32_t>(top_bits_of_bytes(bitwise_and(exist, in_reach)));
            store_4x64(out->pairs[cell] + 2u * from, pairs);
        }
    }
}
#endif

/* The bases of point p's cells by their indices (point_visit_begin). */
inline vector_256 group_bases(const GroupAxis &cells, uint32_t p) {
    return set_lanes_8x32(static_cast<int32_t>(cells.base[0][p]), static_cast<int32_t>(cells.base[1][p]),
                          static_cast<int32_t>(cells.base[2][p]), 0, 0, 0, 0, 0);
}

/* The sifting bounds of point p's cell i (candidate_lanes reads no shifted_base). */
inline CellAxis group_cell_axis(const GroupAxis &cells, uint32_t i, uint32_t p) {
    const uint64_t repeat = 0x100000001u;
    CellAxis axis;
    axis.shifted_base = 0;
    axis.low_lanes = cells.low[i][p] * repeat, axis.high_lanes = cells.high[i][p] * repeat;
    return axis;
}

/* Buffers the candidates of point p's cells in the group, their first two pairs from group_pairs,
   visiting the buffer whenever it might not hold a cell's next pairs (the last visit is the caller's). */
template <class Visit>
DSN_POINT_INLINE void group_point_cells(const FieldLanes &lanes, const PointGroup &group,
                                        const GroupPairs &pairs, uint32_t p, Visit *visit,
                                        PointCandidates *candidates) {
    /* every cell of the vectors (those past the point's have no impulse): no branch on the cells' number;
       unrolled, each cell's offsets and indices are constants */
#pragma GCC unroll 9
    for (uint32_t cell = 0; cell < group_cells * group_cells; cell++) {
        const uint32_t i = cell % group_cells, j = cell / group_cells, indices = cell_indices(i, j);
        const uint32_t key = group.keys[cell * group_points + p],
                       count = group.counts[cell * group_points + p];
        if (candidates->count > point_vector_slots - 16u) visit_candidates(visit, candidates);
        const uint32_t sifted = (pairs.sifted[cell][p / 2u] >> (16u * (p % 2u))) & 0xFFFFu;
#if defined(__AVX512F__) && defined(__AVX512BW__)
        add_sifted_pairs(candidates, key, load_2x64(pairs.pairs[cell] + 2u * p), sifted, indices);
#else
        add_sifted_pair(candidates, key, 0, pairs.pairs[cell][2u * p], sifted & 0xFFu, indices);
        add_sifted_pair(candidates, key, 8, pairs.pairs[cell][2u * p + 1u], sifted >> 8, indices);
#endif
        if (count > 16u)
            add_later_pairs(visit, candidates, key, count, lanes, group_cell_axis(group.columns, i, p),
                            group_cell_axis(group.rows, j, p), indices);
    }
}

/* The candidates are stored at any 4-byte offset, and a store that crosses a page costs far more than one
   that crosses a cache line: 1024-byte alignment keeps the buffer (644 bytes) within one page. */
static_assert(sizeof(PointCandidates) <= 1024, "the candidates must fit their alignment");

/* point_vector_sum's sums of point p of the group: channel c at sums[c group_points + p]. */
template <uint32_t Channels>
void group_point_sum(const dsn_noise_state *noise, const FieldLanes &lanes, const PointGroup &group,
                     const GroupPairs &pairs, uint32_t p, const uint32_t *quads, uint64_t *sums) {
    PointVisit<Channels> visit;
    point_visit_begin<Channels>(noise, group_bases(group.columns, p), group_bases(group.rows, p), quads,
                                &visit);
    alignas(1024) PointCandidates candidates;
    candidates.count = 0;
    group_point_cells(lanes, group, pairs, p, &visit, &candidates);
    point_visit_sums<Channels>(&visit, &candidates, sums + p, group_points);
}

/* The batch's points, Channels values each, into out; quads: the batch's table, or null (the texels then
   read from the texton, each where it lies inside the window). */
template <uint32_t Channels>
void batch_groups(const dsn_noise_state *noise, const uint32_t *quads, const int64_t *xs, const int64_t *ys,
                  uint32_t count, int32_t *out) {
    const GroupShared shared = group_shared(noise);
    PointGroup group;
    GroupPairs pairs;
    /* the sums of the group's points that fit, channel c of point p at c group_points + p (the others'
       zero: defined values, their outputs written over) */
    uint64_t sums[Channels * group_points];
    for (uint32_t first = 0; first < count; first += group_points) {
        const uint32_t points = count - first < group_points ? count - first : group_points;
        const uint32_t fits = fill_group<false>(noise, shared, xs + first, ys + first, points, &group);
        group_pairs(group, shared.lanes, &pairs);
        for (uint32_t k = 0; k < Channels * group_points; k++) sums[k] = 0;
        for (uint32_t p = 0; p < points; p++)
            if ((fits >> p) & 1u)
                group_point_sum<Channels>(noise, shared.lanes, group, pairs, p, quads, sums);
        /* normalize_q32 of the group's points on vectors, a point in each 64-bit lane */
        int32_t *values = out + static_cast<size_t>(first) * Channels;
        continuous_splat_normalize(noise, sums, group_points, points, values);
        for (uint32_t p = 0; p < points; p++) {
            if ((fits >> p) & 1u) {
                dsn_map_output(noise, values + p * Channels);
                continue;
            }
            const uint64_t x = static_cast<uint64_t>(xs[first + p]), y = static_cast<uint64_t>(ys[first + p]);
            if (!continuous_point_vector(noise, x, y, values + p * Channels))
                dsn_internal_continuous_point(noise, x, y, values + p * Channels);
        }
    }
}

#if DSN_GRADIENTS
/* point_slopes's sums of point p of the group (the texels read from the texton: a gradient call builds no
   quad table), its cells sifted with the entry edge (fill_group<true>): channel c at sums[0] (the value),
   sums[1] and sums[2] (the slopes per texel, times 2^16), index c group_points + p. */
template <uint32_t Channels>
void group_point_slopes(const dsn_noise_state *noise, const FieldLanes &lanes, const PointGroup &group,
                        const GroupPairs &pairs, uint32_t p, uint64_t (*sums)[Channels * group_points]) {
    SlopeVisit<Channels> visit;
    slope_visit_begin<Channels>(noise, group_bases(group.columns, p), group_bases(group.rows, p), &visit);
    alignas(1024) PointCandidates candidates;
    candidates.count = 0;
    group_point_cells(lanes, group, pairs, p, &visit, &candidates);
    visit_candidates(&visit, &candidates);
    uint64_t value[DSN_MAX_CHANNELS], slope_x[DSN_MAX_CHANNELS], slope_y[DSN_MAX_CHANNELS];
    slope_visit_sums(visit, value, slope_x, slope_y);
    for (uint32_t c = 0; c < Channels; c++) {
        sums[0][c * group_points + p] = value[c];
        sums[1][c * group_points + p] = slope_x[c] << 16;
        sums[2][c * group_points + p] = slope_y[c] << 16;
    }
}

/* The batch's gradients (dsn_internal_continuous_gradient's values of each point) into out, dx and dy,
   Channels values a point each: a group's sums normalized on vectors (the slopes without the mean), then
   the mapping's chain rule point by point. */
template <uint32_t Channels>
void batch_group_gradients(const dsn_noise_state *noise, const int64_t *xs, const int64_t *ys, uint32_t count,
                           int32_t *out, int32_t *dx, int32_t *dy) {
    const GroupShared shared = group_shared(noise);
    PointGroup group;
    GroupPairs pairs;
    /* the sums of the group's points that fit (the others' zero: defined values, written over) */
    uint64_t sums[3][Channels * group_points];
    int32_t normalized[3][Channels * group_points];
    for (uint32_t first = 0; first < count; first += group_points) {
        const uint32_t points = count - first < group_points ? count - first : group_points;
        const uint32_t fits = fill_group<true>(noise, shared, xs + first, ys + first, points, &group);
        group_pairs(group, shared.lanes, &pairs);
        for (uint32_t k = 0; k < Channels * group_points; k++) sums[0][k] = sums[1][k] = sums[2][k] = 0;
        for (uint32_t p = 0; p < points; p++)
            if ((fits >> p) & 1u) group_point_slopes<Channels>(noise, shared.lanes, group, pairs, p, sums);
        splat_normalize_from(noise, noise->offset, sums[0], group_points, points, normalized[0]);
        splat_normalize_from(noise, dsn_no_offset, sums[1], group_points, points, normalized[1]);
        splat_normalize_from(noise, dsn_no_offset, sums[2], group_points, points, normalized[2]);
        for (uint32_t p = 0; p < points; p++) {
            int32_t values[3 * DSN_MAX_CHANNELS];
            if ((fits >> p) & 1u) {
                for (uint32_t part = 0; part < 3; part++)
                    for (uint32_t c = 0; c < Channels; c++)
                        values[part * DSN_MAX_CHANNELS + c] = normalized[part][p * Channels + c];
                dsn_map_gradient(noise, values, values + DSN_MAX_CHANNELS, values + 2 * DSN_MAX_CHANNELS);
            } else {
                dsn_internal_continuous_gradient(noise, static_cast<uint64_t>(xs[first + p]),
                                                 static_cast<uint64_t>(ys[first + p]), values);
            }
            store_gradient_point(values, Channels, static_cast<size_t>(first + p) * Channels, out, dx, dy);
        }
    }
}
#endif

} // namespace
#endif /* __AVX2__ */

#endif /* DSN_CONTINUOUS_BATCH_GROUP_H */
