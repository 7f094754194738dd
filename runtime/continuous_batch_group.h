/* runtime/continuous_batch_group.h - the batch of continuous points for the noises the vector per-point
   evaluator takes (continuous_point_vector.h), 8 points at a time: their cells found point by point, the
   keys and impulse counts of the 3 x 3 cells a usual point has computed on vectors with a point in each
   lane (the key hashes and the counts' table searches, chains of dependent steps per point, then run 8
   points abreast), then each point's impulses sifted, visited and normalized by the per-point evaluator's
   code, its texels read from the batch's quad table (continuous_batch.h: one gather per channel, no test
   at the window's edge). A point with more cells along an axis goes through the per-point evaluator. The same
   keys and counts as per point, so the same bits. Internal to libdsn; not installed (everything here has
   internal linkage). */
#ifndef DSN_CONTINUOUS_BATCH_GROUP_H
#define DSN_CONTINUOUS_BATCH_GROUP_H

#include "continuous_point_vector.h"

#if defined(__AVX2__)
namespace {

const uint32_t group_points = 8; /* points a group's vectors hold */
const uint32_t group_cells = 3;  /* cells along each axis a group's vectors hold */

/* What a group's points share: the noise's Poisson guide widened to 32 bits (for gathers). */
struct GroupShared {
    FieldLanes lanes;
    uint32_t guide[64];
    bool two_steps;
};

inline GroupShared group_shared(const dsn_noise_state *noise) {
    GroupShared shared;
    shared.lanes = field_lanes(noise->cell_shift);
    for (uint32_t k = 0; k < 64; k++) shared.guide[k] = noise->poisson_guide[k];
    shared.two_steps = dsn_poisson_two_steps_fit(noise);
    return shared;
}

/* a >= b as unsigned 32-bit lanes. */
inline __m256i at_least(__m256i a, __m256i b) { return _mm256_cmpeq_epi32(_mm256_max_epu32(a, b), a); }

/* dsn_poisson_count_two_steps of 8 keys (the noise passed dsn_poisson_two_steps_fit): the guide, two
   steps (a step adds 1 where the key is at least cdf[n]: the compare's -1 subtracted), and the exact
   search for the lanes that need it, one by one. */
inline __m256i group_counts(const dsn_noise_state *noise, const GroupShared &shared, __m256i keys) {
    const int *cdf = static_cast<const int *>(static_cast<const void *>(noise->poisson_cdf));
    const int *guide = static_cast<const int *>(static_cast<const void *>(shared.guide));
    __m256i n = _mm256_i32gather_epi32(guide, _mm256_srli_epi32(keys, 26), 4);
    n = _mm256_sub_epi32(n, at_least(keys, _mm256_i32gather_epi32(cdf, n, 4)));
    n = _mm256_sub_epi32(n, at_least(keys, _mm256_i32gather_epi32(cdf, n, 4)));
    const __m256i size = broadcast_8(noise->poisson_size);
    const __m256i over = _mm256_cmpgt_epi32(n, size), under = _mm256_cmpgt_epi32(size, n);
    const __m256i next = _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), cdf, n, under, 4);
    const __m256i search = _mm256_or_si256(over, _mm256_and_si256(under, at_least(keys, next)));
    uint32_t searched = static_cast<uint32_t>(_mm256_movemask_ps(_mm256_castsi256_ps(search)));
    if (searched == 0) return n;
    uint32_t counts[8], values[8];
    store_8(counts, n), store_8(values, keys);
    for (; searched != 0; searched &= searched - 1u) {
        const uint32_t point = lowest_bit(searched);
        counts[point] = dsn_poisson_draw(noise, values[point]);
    }
    return load_8(counts);
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
    uint32_t cell_x[group_cells][group_points], cell_y[group_cells][group_points], fits = 0;
    for (uint32_t p = 0; p < group_points; p++) {
        AxisCells *columns = &group->columns[p], *rows = &group->rows[p];
        const bool fit = p < count &&
                         point_cells(noise, static_cast<uint64_t>(xs[p]), static_cast<uint64_t>(ys[p]),
                                     shared.lanes, columns, rows) &&
                         columns->count <= group_cells && rows->count <= group_cells;
        fits |= static_cast<uint32_t>(fit) << p;
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
            if (shared.two_steps)
                store_8(counts, group_counts(noise, shared, key));
            else
                for (uint32_t p = 0; p < group_points; p++)
                    counts[p] = dsn_cell_impulse_count(noise, keys[p]);
        }
    }
    return fits;
}

/* The batch's points, Channels values each, into out; quads: the batch's table. */
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
