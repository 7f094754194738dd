/* runtime/kernels/filtered_candidates_vector.h - the listing of the filtered sift's candidates
   (filtered_sift.cpp) on AVX2 vectors, as a kernel (kernels.h: the AVX2 and AVX-512 kernels include it), for
   cells of side
   <= 16 (pairs of 8 impulses): each pair sifted on its packed lattice fields against the taps' box
   (continuous_sift.h) and its candidates packed to the front of a vector (continuous_lanes.h, as the
   continuous evaluator's), then their fraction hash and 16-bit positions in 32-bit lanes, their shifted
   offsets in 64-bit lanes (where the caller reads them) and those offsets / 2^16 in 32-bit lanes, 8
   stored at once (AVX-512: two pairs at once, hashed and placed on all 16 lanes while the sift runs, and
   only what is stored compressed); for a mix, only the impulses of one material, or each impulse into the
   list of the material it draws where two materials share the walk. Only the
   sift bounds them: a candidate may lie up to a texel beyond the box, which the level tests, exact for any
   offset of that size, leave out as the walk does. Internal to libdsn; not installed (everything here has
   internal linkage). */
#ifndef DSN_FILTERED_CANDIDATES_VECTOR_H
#define DSN_FILTERED_CANDIDATES_VECTOR_H

#include "core/cell_hash.h"
#include "core/continuous_sift.h"
#include "kernels/continuous_lanes.h"
#include "kernels/continuous_point_vector.h"
#include "kernels/kernels.h"

#if defined(__AVX2__) && DSN_FILTERING && !DSN_SMALL_CODE
namespace {

/* A shifted_base / 2^16 modulo 2^32, as a lane: the narrow offsets are it less the 16-bit positions times
   2^cell_shift (the offset's low 16 bits are the same for every impulse of an axis: its shifted_base's). */
inline uint32_t narrow_base(int64_t shifted_base) {
    return static_cast<uint32_t>(static_cast<uint64_t>(shifted_base) >> 16);
}

/* A mix's material filter (kernels.h's dsn_impulse_filter, DSN_MIXING) on the 32-bit lanes of the listing's
   vectors: an impulse's hash h is kept where h - low < span modulo 2^32, span = high - low (below 2^32: the
   filter of a material that draws every impulse is null). */
#if defined(__AVX512F__) && defined(__AVX512BW__)
typedef vector_512 filter_vector;
#else
typedef vector_256 filter_vector;
#endif
struct KeptLanes {
    filter_vector low, span;
};

inline KeptLanes kept_lanes_of(const dsn_impulse_filter *filter) {
    const uint32_t low = filter != 0 ? static_cast<uint32_t>(filter->low) : 0u,
                   span = filter != 0 ? static_cast<uint32_t>(filter->high - filter->low) : 0u;
    const KeptLanes kept = {all_lanes_32<filter_vector>(low), all_lanes_32<filter_vector>(span)};
    return kept;
}

/* The lanes whose impulse the filter keeps, from their streams dsn_cell_stream(key, 2^31 + k) less the
   mix: their material hashes, dsn_cell_stream(key, 2^31 + 2^30 + k), are the streams' plus 2^30 0x9E3779B9
   = 2^30 modulo 2^32, mixed. */
inline uint32_t kept_lanes(filter_vector streams, const KeptLanes &kept) {
    const filter_vector hashes = mix32_lanes(add_32(streams, all_lanes_32<filter_vector>(0x40000000u)));
    return less_unsigned_32_bits(subtract_32(hashes, kept.low), kept.span);
}

#if defined(__AVX512F__) && defined(__AVX512BW__)
/* shifted_base - bits 2^position_shift for the 16 candidates of `bits` (32-bit lanes), in order. */
inline void store_shifted_16(int64_t *at, vector_512 base, vector_512 bits, vector_128 position_shift) {
    const vector_512 low = shift_left_64_by(widen_unsigned_32x64(low_256(bits)), position_shift),
                     high = shift_left_64_by(widen_unsigned_32x64(high_256(bits)), position_shift);
    store_8x64(at, subtract_64(base, low));
    store_8x64(at + 8, subtract_64(base, high));
}

/* Two pairs' impulses placed in lanes: their 16-bit positions and narrow offsets, and the cell's bases. */
struct PlacedLanes {
    vector_512 base_x, base_y, bits_x, bits_y, narrow_x, narrow_y;
    vector_128 position_shift;
};

/* The lanes of `keep` appended to `list`, compressed to the front (Wide: their shifted offsets too). */
template <bool Wide>
inline void append_lanes_16(dsn_filter_list *list, uint32_t keep, const PlacedLanes &placed) {
    const mask_16 lanes = static_cast<mask_16>(keep);
    const uint32_t count = list->count;
    if (Wide) {
        store_shifted_16(list->xs + count, placed.base_x, compress_32(lanes, placed.bits_x),
                         placed.position_shift);
        store_shifted_16(list->ys + count, placed.base_y, compress_32(lanes, placed.bits_y),
                         placed.position_shift);
    }
    store_16x32(list->narrow_xs + count, compress_32(lanes, placed.narrow_x));
    store_16x32(list->narrow_ys + count, compress_32(lanes, placed.narrow_y));
    list->count = count + mask_count(keep);
}

/* kernels.h's filter_candidates, two pairs at a time (impulses first .. first + 15 of a cell), on 512-bit
   vectors: both sifted in one 128-bit vector (sift_two_pairs) and their candidates compressed to the front.
   Wide: xs, ys are written (a loop of its own without them: fewer live registers). Filtered: only the
   impulses that `filter` keeps (kept_lanes) go to `kept`; Split: the others to `rest`, from the same
   lanes. */
template <bool Wide, bool Filtered, bool Split>
uint32_t listed_candidates(const dsn_filter_cell *cells, uint32_t cell_count, uint32_t cell_shift,
                           dsn_filter_list *kept_list, dsn_filter_list *rest_list, const KeptLanes &kept) {
    const FieldLanes lanes = field_lanes(cell_shift);
    const vector_128 cell_shift_vector = shift_count(static_cast<int>(cell_shift));
    /* lane * 0x9E3779B9 modulo 2^32 */
    const vector_512 weyl = multiply_32(set_lanes_16x32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
                                        set_16x32(0x9E3779B9u));
    /* (copies: the stores through the lists' arrays could otherwise alias their counts) */
    dsn_filter_list kept_out = *kept_list, rest_out = Split ? *rest_list : *kept_list;
    PlacedLanes placed;
    placed.position_shift = shift_count(static_cast<int>(16u + cell_shift));
    for (uint32_t k = 0; k < cell_count; k++) {
        const dsn_filter_cell &cell = cells[k];
        placed.base_x = set_8x64(cell.x.shifted_base), placed.base_y = set_8x64(cell.y.shifted_base);
        const vector_512 narrow_base_x = set_16x32(narrow_base(cell.x.shifted_base)),
                         narrow_base_y = set_16x32(narrow_base(cell.y.shifted_base));
        for (uint32_t first = 0; first < cell.count; first += 16u) {
            const uint64_t first_pair = dsn_position_pair(cell.key, first >> 3),
                           second_pair = dsn_position_pair(cell.key, (first >> 3) + 1u);
            const vector_128 pairs = set_lanes_2x64(first_pair, second_pair);
            uint32_t sifted = sift_two_pairs(pairs, lanes, cell.x, cell.y);
            if (cell.count - first < 16u)
                sifted &= (1u << (cell.count - first)) - 1u; /* impulses that do not exist */
            /* dsn_cell_stream(key, 2^31 + k) of impulse k = first + lane */
            const vector_512 streams =
                add_32(set_16x32(cell.key + (0x80000000u + first) * 0x9E3779B9u), weyl);
            const uint32_t kept_bits = Filtered ? kept_lanes(streams, kept) : 0xFFFFu;
            /* hashed and placed before the sift's mask is known (lanewise: the same values), off its
               chain; then only what is stored is compressed */
            impulse_bits_16(widen_bytes_16x32(pairs), mix32_lanes(streams), &placed.bits_x, &placed.bits_y);
            placed.narrow_x = subtract_32(narrow_base_x, shift_left_32_by(placed.bits_x, cell_shift_vector));
            placed.narrow_y = subtract_32(narrow_base_y, shift_left_32_by(placed.bits_y, cell_shift_vector));
            append_lanes_16<Wide>(&kept_out, sifted & kept_bits, placed);
            if (Split) append_lanes_16<Wide>(&rest_out, sifted & ~kept_bits, placed);
        }
        kept_out.ends[k] = kept_out.count;
        if (Split) rest_out.ends[k] = rest_out.count;
    }
    kept_list->count = kept_out.count;
    if (Split) rest_list->count = rest_out.count;
    return kept_out.count;
}

uint32_t filter_candidates(const dsn_filter_cell *cells, uint32_t cell_count, uint32_t cell_shift,
                           dsn_filter_list *kept, dsn_filter_list *rest, const dsn_impulse_filter *filter) {
    const KeptLanes lanes = kept_lanes_of(filter);
    const bool wide = kept->xs != 0;
    if (filter == 0)
        return wide
                   ? listed_candidates<true, false, false>(cells, cell_count, cell_shift, kept, rest, lanes)
                   : listed_candidates<false, false, false>(cells, cell_count, cell_shift, kept, rest, lanes);
    else if (rest == 0)
        return wide ? listed_candidates<true, true, false>(cells, cell_count, cell_shift, kept, rest, lanes)
                    : listed_candidates<false, true, false>(cells, cell_count, cell_shift, kept, rest, lanes);
    else
        return wide ? listed_candidates<true, true, true>(cells, cell_count, cell_shift, kept, rest, lanes)
                    : listed_candidates<false, true, true>(cells, cell_count, cell_shift, kept, rest, lanes);
}
#else
/* shifted_base - bits 2^position_shift for the 8 candidates of `bits` (32-bit lanes), in order. */
inline void store_shifted(int64_t *at, vector_256 base, vector_256 bits, vector_128 position_shift) {
    const vector_256 low = shift_left_64_by(widen_unsigned_32x64(low_128(bits)), position_shift),
                     high = shift_left_64_by(widen_unsigned_32x64(high_128(bits)), position_shift);
    store_4x64(at, subtract_64(base, low));
    store_4x64(at + 4, subtract_64(base, high));
}

/* A cell's lanes as its pairs' candidates are placed: its bases, and the shifts of the positions. */
struct CellLanes {
    vector_256 base_x, base_y, narrow_base_x, narrow_base_y;
    vector_128 position_shift, cell_shift;
};

inline CellLanes cell_lanes(const dsn_filter_cell &cell, uint32_t cell_shift) {
    const CellLanes out = {set_4x64(cell.x.shifted_base),
                           set_4x64(cell.y.shifted_base),
                           set_8x32(narrow_base(cell.x.shifted_base)),
                           set_8x32(narrow_base(cell.y.shifted_base)),
                           shift_count(static_cast<int>(16u + cell_shift)),
                           shift_count(static_cast<int>(cell_shift))};
    return out;
}

/* The candidates of a pair that `keep` marks (impulses first .. first + 7 of the cell with this key),
   packed to the front and appended to `list`. */
DSN_POINT_INLINE void append_pair_8(dsn_filter_list *list, const CellLanes &cell, uint32_t key,
                                    uint32_t first, uint64_t pair, uint32_t keep) {
    vector_256 streams, fields;
    /* dsn_cell_stream(key, 2^31 + k) of impulse k = first + lane */
    const uint32_t packed =
        pack_pair_8(pair, keep, key + (0x80000000u + first) * 0x9E3779B9u, &streams, &fields);
    vector_256 bits_x, bits_y;
    impulse_bits_8(fields, mix32_lanes(streams), &bits_x, &bits_y);
    const uint32_t count = list->count;
    if (list->xs != 0) {
        store_shifted(list->xs + count, cell.base_x, bits_x, cell.position_shift);
        store_shifted(list->ys + count, cell.base_y, bits_y, cell.position_shift);
    }
    store_8x32(list->narrow_xs + count,
               subtract_32(cell.narrow_base_x, shift_left_32_by(bits_x, cell.cell_shift)));
    store_8x32(list->narrow_ys + count,
               subtract_32(cell.narrow_base_y, shift_left_32_by(bits_y, cell.cell_shift)));
    list->count = count + packed;
}

/* kernels.h's filter_candidates, a pair at a time; Split: the pair's other candidates packed and placed
   again, into `rest`. */
template <bool Split>
uint32_t listed_pairs(const dsn_filter_cell *cells, uint32_t cell_count, uint32_t cell_shift,
                      dsn_filter_list *kept, dsn_filter_list *rest, const dsn_impulse_filter *filter) {
    const FieldLanes lanes = field_lanes(cell_shift);
    const KeptLanes kept_lanes_vector = kept_lanes_of(filter);
    /* lane * 0x9E3779B9 modulo 2^32 */
    const vector_256 weyl = multiply_32(set_lanes_8x32(0, 1, 2, 3, 4, 5, 6, 7), set_8x32(0x9E3779B9u));
    dsn_filter_list kept_out = *kept, rest_out = Split ? *rest : *kept; /* (copies: see above) */
    for (uint32_t k = 0; k < cell_count; k++) {
        const dsn_filter_cell &cell = cells[k];
        const CellLanes placed = cell_lanes(cell, cell_shift);
        for (uint32_t first = 0; first < cell.count; first += 8u) {
            const uint64_t pair = dsn_position_pair(cell.key, first >> 3);
            const uint32_t present = cell.count - first < 8u ? cell.count - first : 8u;
            const uint32_t sifted =
                gather_lanes(candidate_lanes(pair, lanes, cell.x, cell.y), lanes) & ((1u << present) - 1u);
            const uint32_t kept_bits =
                filter != 0
                    ? kept_lanes(add_32(set_8x32(cell.key + (0x80000000u + first) * 0x9E3779B9u), weyl),
                                 kept_lanes_vector)
                    : 0xFFu;
            append_pair_8(&kept_out, placed, cell.key, first, pair, sifted & kept_bits);
            if (Split) append_pair_8(&rest_out, placed, cell.key, first, pair, sifted & ~kept_bits);
        }
        kept_out.ends[k] = kept_out.count;
        if (Split) rest_out.ends[k] = rest_out.count;
    }
    kept->count = kept_out.count;
    if (Split) rest->count = rest_out.count;
    return kept_out.count;
}

uint32_t filter_candidates(const dsn_filter_cell *cells, uint32_t cell_count, uint32_t cell_shift,
                           dsn_filter_list *kept, dsn_filter_list *rest, const dsn_impulse_filter *filter) {
    if (rest != 0 && filter != 0)
        return listed_pairs<true>(cells, cell_count, cell_shift, kept, rest, filter);
    else
        return listed_pairs<false>(cells, cell_count, cell_shift, kept, rest, filter);
}

#endif

} // namespace
/* The kernel entry (kernels.h): null where there is none. */
#define DSN_FILTER_CANDIDATES_ENTRY filter_candidates
#else
#define DSN_FILTER_CANDIDATES_ENTRY 0
#endif

#endif /* DSN_FILTERED_CANDIDATES_VECTOR_H */
