/* runtime/continuous_batch_group.h - the batch of continuous points for the noises the vector per-point
   evaluator takes (continuous_point_vector.h), 8 points at a time with a point in each vector lane: their
   cells along non-periodic axes (periodic ones point by point), and the keys and impulse counts of the
   3 x 3 cells a usual point has (the counts by comparisons with the Poisson table, no search; AVX-512: by
   the two-step search on 16 lanes, counts_16), then each point's impulses sifted, visited and normalized
   by the per-point evaluator's code, its texels read from the batch's quad table where the call built it
   (continuous_batch.h: one gather per channel, AVX-512 two channels a read; no test at the window's edge;
   continuous_batch.cpp builds it for large batches only). A
   point with more cells along an axis goes through the per-point evaluator. The same cells, keys and
   counts as per point, so the same bits. Internal to libdsn; not installed (everything here has internal
   linkage). */
#ifndef DSN_CONTINUOUS_BATCH_GROUP_H
#define DSN_CONTINUOUS_BATCH_GROUP_H

#include "continuous_point_vector.h"

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
inline __m256i group_counts(const dsn_noise_state *noise, const GroupShared &shared, __m256i keys) {
    const __m256i flipped = _mm256_xor_si256(keys, broadcast_8(0x80000000u));
    __m256i above = _mm256_setzero_si256(); /* minus their number */
    for (uint32_t k = 0; k < noise->poisson_size; k++)
        above = _mm256_add_epi32(above, _mm256_cmpgt_epi32(broadcast_8(shared.flipped_cdf[k]), flipped));
    return _mm256_add_epi32(broadcast_8(noise->poisson_size), above);
}

/* axis_cells(point_axis(...)) of the group's points along a non-periodic axis (`axis`: 0 for x, 1 for y)
   with a point in each lane, all in 32-bit lanes: the window's cells (dsn_axis_span's first cell and count),
   and for each cell cell_axis_within's bounds on the field halves. With the cell's offset
   W = X - origin (X the point's integer part, small: the cell is one of the point's) and the fraction f,
   shifted_base = (W + radius + 1) 2^32 + f, and the halves' bounds floor((shifted_base - 2 reach) / 2^k)
   and floor((shifted_base - 1) / 2^k), k = 28 + shift (4-bit halves, shift <= 4), are
   (W - radius - 1) 2^(32 - k) + (f >> k) and (W + radius + 1) 2^(32 - k) + ((f - 1) >> k), less
   2^(32 - k) where f = 0 (f - 1 wraps to 2^32 - 1 there, where the floor of -1 / 2^k is -1). The cells
   that pass are written to cells[p] in the window's order, as axis_cells writes them. Returns the points
   (bit p) whose window has at most group_cells cells. */
inline uint32_t group_axis(const dsn_noise_state *noise, uint32_t axis, const int64_t *coordinates,
                           uint32_t count, const FieldLanes &lanes, AxisCells *cells) {
    uint32_t whole[group_points], fraction[group_points];
    for (uint32_t p = 0; p < group_points; p++) {
        const uint64_t coordinate = p < count ? static_cast<uint64_t>(coordinates[p]) : 0u;
        whole[p] = static_cast<uint32_t>(coordinate >> 32), fraction[p] = static_cast<uint32_t>(coordinate);
    }
    const uint32_t radius = noise->radius[axis], shift = noise->cell_shift, up = 4u - shift;
    const __m128i by_shift = _mm_cvtsi32_si128(static_cast<int>(shift)),
                  by_up = _mm_cvtsi32_si128(static_cast<int>(up));
    const __m128i by_k = _mm_cvtsi32_si128(static_cast<int>(28u + shift));
    const __m256i x = load_8(whole), f = load_8(fraction), one = broadcast_8(1);
    /* dsn_axis_span of the window [X - 1, X + 1]: its low end X - 1 - radius */
    const __m256i low = _mm256_sub_epi32(x, broadcast_8(1u + radius));
    const __m256i first_cell = _mm256_srl_epi32(low, by_shift);
    const __m256i cell_count = _mm256_add_epi32(
        _mm256_srl_epi32(_mm256_add_epi32(_mm256_and_si256(low, broadcast_8((1u << shift) - 1u)),
                                          broadcast_8(2u + 2u * radius)),
                         by_shift),
        one);
    const uint32_t fits = static_cast<uint32_t>(_mm256_movemask_ps(
        _mm256_castsi256_ps(_mm256_cmpgt_epi32(broadcast_8(group_cells + 1u), cell_count))));
    const __m256i sign = broadcast_8(0x80000000u),
                  room_limit = broadcast_8(((1u << shift) - 1u) ^ 0x80000000u);
    const __m256i f_zero =
        _mm256_and_si256(_mm256_cmpeq_epi32(f, _mm256_setzero_si256()), broadcast_8(0u - (1u << up)));
    uint32_t cell[group_cells][group_points], offset[group_cells][group_points],
        first[group_cells][group_points], last[group_cells][group_points], base[group_cells][group_points],
        passes[group_cells];
    for (uint32_t i = 0; i < group_cells; i++) {
        const __m256i index =
            _mm256_and_si256(_mm256_add_epi32(first_cell, broadcast_8(i)), broadcast_8(0xFFFFFFFFu >> shift));
        const __m256i origin = _mm256_sll_epi32(index, by_shift), w = _mm256_sub_epi32(x, origin);
        const __m256i low_half =
            _mm256_add_epi32(_mm256_sll_epi32(_mm256_sub_epi32(w, broadcast_8(radius + 1u)), by_up),
                             _mm256_srl_epi32(f, by_k));
        __m256i high_half = _mm256_add_epi32(
            _mm256_add_epi32(_mm256_sll_epi32(_mm256_add_epi32(w, broadcast_8(radius + 1u)), by_up),
                             _mm256_srl_epi32(_mm256_sub_epi32(f, one), by_k)),
            f_zero);
        /* the period's end (none: last_position 2^32 - 1) */
        const __m256i room = _mm256_xor_si256(origin, broadcast_8(0xFFFFFFFFu));
        const __m256i short_room = _mm256_cmpgt_epi32(room_limit, _mm256_xor_si256(room, sign));
        const __m256i end = _mm256_blendv_epi8(
            broadcast_8(15), _mm256_or_si256(_mm256_sll_epi32(room, by_up), broadcast_8((1u << up) - 1u)),
            short_room);
        high_half = _mm256_min_epi32(high_half, end);
        const __m256i first_half = _mm256_max_epi32(low_half, _mm256_setzero_si256());
        const __m256i pass = _mm256_andnot_si256(_mm256_cmpgt_epi32(first_half, high_half),
                                                 _mm256_cmpgt_epi32(cell_count, broadcast_8(i)));
        passes[i] = static_cast<uint32_t>(_mm256_movemask_ps(_mm256_castsi256_ps(pass)));
        store_8(cell[i], index), store_8(offset[i], w), store_8(first[i], first_half),
            store_8(last[i], high_half);
        store_8(base[i],
                _mm256_add_epi32(_mm256_slli_epi32(_mm256_add_epi32(w, broadcast_8(radius + 1u)), 16),
                                 _mm256_srli_epi32(f, 16)));
    }
    const int64_t reach = static_cast<int64_t>(radius + 1u) * static_cast<int64_t>(one_texel);
    for (uint32_t p = 0; p < count; p++) {
        AxisCells *point = &cells[p];
        point->count = 0;
        store_8(point->base, _mm256_setzero_si256());
        for (uint32_t i = 0; i < group_cells; i++) {
            if (((passes[i] >> p) & 1u) == 0) continue;
            const uint32_t at = point->count++;
            point->cell[at] = cell[i][p], point->base[at] = base[i][p];
            CellAxis *bounds = &point->axis[at];
            bounds->shifted_base =
                static_cast<int64_t>(dsn_signed_sum(offset[i][p])) * static_cast<int64_t>(one_texel) +
                static_cast<int64_t>(fraction[p]) + reach;
            bounds->low_lanes = lanes.ones * first[i][p];
            bounds->high_lanes = (lanes.ones * last[i][p]) | lanes.tops;
        }
    }
    return fits;
}

/* The cells of a group's points, and the keys and counts of their first group_cells x group_cells cells:
   cell (column i, row j) of point p at keys[(j group_cells + i) group_points + p]. */
struct PointGroup {
    AxisCells columns[group_points], rows[group_points];
    uint32_t keys[group_cells * group_cells * group_points], counts[group_cells * group_cells * group_points];
};

/* Fills the group for points xs[0 .. count - 1], count <= group_points; returns the points (bit p) whose
   cells fit the vectors (at most group_cells along each axis). */
inline uint32_t fill_group(const dsn_noise_state *noise, const GroupShared &shared, const int64_t *xs,
                           const int64_t *ys, uint32_t count, PointGroup *group) {
    uint32_t cell_x[group_cells][group_points], cell_y[group_cells][group_points];
    const uint32_t shift = noise->cell_shift;
    const uint32_t fits_x =
        noise->period[0] == 0 ? group_axis(noise, 0, xs, count, shared.lanes, group->columns) : 0xFFu;
    const uint32_t fits_y =
        noise->period[1] == 0 ? group_axis(noise, 1, ys, count, shared.lanes, group->rows) : 0xFFu;
    uint32_t fits = fits_x & fits_y & ((1u << count) - 1u);
    for (uint32_t p = 0; p < group_points; p++) {
        AxisCells *columns = &group->columns[p], *rows = &group->rows[p];
        /* periodic axes point by point */
        if (((fits >> p) & 1u) != 0 && noise->period[0] != 0 &&
            !axis_cells(point_axis(static_cast<uint64_t>(xs[p]), noise->radius[0], shift, noise->period[0]),
                        shared.lanes, columns))
            fits &= ~(1u << p);
        if (((fits >> p) & 1u) != 0 && noise->period[1] != 0 &&
            !axis_cells(point_axis(static_cast<uint64_t>(ys[p]), noise->radius[1], shift, noise->period[1]),
                        shared.lanes, rows))
            fits &= ~(1u << p);
        const bool fit =
            ((fits >> p) & 1u) != 0 && columns->count <= group_cells && rows->count <= group_cells;
        fits &= ~(static_cast<uint32_t>(!fit) << p);
        for (uint32_t i = 0; i < group_cells; i++) {
            cell_x[i][p] = fit && i < columns->count ? columns->cell[i] : 0u;
            cell_y[i][p] = fit && i < rows->count ? rows->cell[i] : 0u;
        }
    }
    const __m256i seed_row = broadcast_8(noise->seed_row), seed_column = broadcast_8(noise->seed_column);
    for (uint32_t j = 0; j < group_cells; j++) {
        const __m256i row_key = mix32_8(_mm256_add_epi32(load_8(cell_y[j]), seed_row)); /* dsn_row_key */
        for (uint32_t i = 0; i < group_cells; i++) {
            uint32_t *keys = group->keys + (j * group_cells + i) * group_points;
            uint32_t *counts = group->counts + (j * group_cells + i) * group_points;
            const __m256i key =
                mix32_8(_mm256_add_epi32(_mm256_xor_si256(load_8(cell_x[i]), seed_column), row_key));
            store_8(keys, key);
#if defined(__AVX512F__) && defined(__AVX512BW__)
            if (shared.by_tables) {
                store_8(counts,
                        _mm512_castsi512_si256(counts_16(noise, shared.tables, _mm512_castsi256_si512(key))));
                continue;
            }
#endif
            if (shared.one_draw)
                store_8(counts, group_counts(noise, shared, key));
            else
                for (uint32_t p = 0; p < group_points; p++)
                    counts[p] = dsn_cell_impulse_count(noise, keys[p]);
        }
    }
    return fits;
}

/* The batch's points, Channels values each, into out; quads: the batch's table, or null (the texels then
   read from the texton, each where it lies inside the window). */
template <uint32_t Channels>
void batch_groups(const dsn_noise_state *noise, const uint32_t *quads, const int64_t *xs, const int64_t *ys,
                  uint32_t count, int32_t *out) {
    const GroupShared shared = group_shared(noise);
    PointGroup group;
    for (uint32_t first = 0; first < count; first += group_points) {
        const uint32_t points = count - first < group_points ? count - first : group_points;
        const uint32_t fits = fill_group(noise, shared, xs + first, ys + first, points, &group);
        for (uint32_t p = 0; p < points; p++) {
            int32_t *values = out + static_cast<size_t>(first + p) * Channels;
            if ((fits >> p) & 1u) {
                point_vector_sum<Channels>(noise, shared.lanes, group.columns[p], group.rows[p],
                                           group.keys + p, group.counts + p, group_cells * group_points,
                                           group_points, quads, values);
                continue;
            }
            const uint64_t x = static_cast<uint64_t>(xs[first + p]), y = static_cast<uint64_t>(ys[first + p]);
            if (!continuous_point_vector(noise, x, y, values))
                dsn_internal_continuous_point(noise, x, y, values);
        }
    }
}

} // namespace
#endif /* __AVX2__ */

#endif /* DSN_CONTINUOUS_BATCH_GROUP_H */
