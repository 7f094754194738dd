/* runtime/evaluators/filtered_sift.cpp - the fast build's levels' sums at the taps of a filtered point: every
   tap at once. The cells of the box that holds every tap's reach are walked once, their impulses sifted on
   their packed lattice fields against that box (continuous_sift.h), and each candidate is then tested
   against each tap and each level exactly and read where in reach (bilinear_read.h). The same impulses,
   offsets and integers as the tap-by-tap walk (filtered_walk.cpp), so the same sums: integer sums modulo
   2^64 do not depend on the order. Where the kernel has them, its listing (filtered_candidates_vector.h)
   lists the candidates of whole cells at once, each tap's level then tests only the runs of cells that
   may reach it, and its vector reads (filtered_reads_vector.h) take the reads of 8-bit levels, on the
   listing's 32-bit offsets (narrow_test) where the box is small enough; the gradient's slopes with them,
   where they take its levels, else through each tap's copies moved by a weight step. The same walk without
   the reads (the candidates counted) is make bench's listing alone. Compiled only with DSN_FILTERING in the
   fast build. */
#include "core/cell_walk.h"
#include "core/continuous_internal.h"
#include "core/continuous_sift.h"
#include "core/filtered_internal.h"
#include "core/impulse_position.h"
#include "core/level_read.h"
#include "core/normalize_fixed.h"
#include "core/poisson_count.h"
#include "kernels/bilinear_read.h"
#include "kernels/kernels.h"

#if DSN_FILTERING && !DSN_SMALL_CODE

namespace {

/* Taps whose integer parts lie further apart than this along an axis (never, under the footprint rules,
   below the mean colour's level of detail; or across the int32 seam of the coordinates, where the walk
   reduces each tap on its own side) are summed one by one: every offset then stays far below 2^31
   texels, so the box's offsets plus the taps' distances are the walk's offsets exactly. */
const int64_t tap_spread_limit = static_cast<int64_t>(1) << 20;

/* Candidates wait in a buffer, then each tap visits all of them with its own tests in registers: up to
   64 (one bit each in a tap's mask) for several taps, 32 for one (measured faster there). The kernel's
   listing (filter_candidates) fills the buffer up to its capacity instead, whole cells at a time, and
   the masks then take 64 candidates at a time. */
const uint32_t buffer_size = 64, one_tap_buffer_size = 32, mask_size = 64, buffer_capacity = 512;

/* The kernel's listing takes the box's columns of cells this many at a time, and the cells of a row of
   them at once. */
const uint32_t cell_batch = 16;
const uint32_t candidates_overrun = 16; /* the values the kernel's listing may write past the last */

/* One axis of the taps summed together: the walk's window from the lowest tap's X - 1 to the highest
   tap's X + 1 with the walk radius R; an impulse's candidate value c (the offset from the box's
   start, shifted so that 0 < c < reach_limit holds for every impulse within R + 1 texels of a tap) and
   each tap's offset to it: the tap's offset to the impulse is c - tap_shift[tap]. */
struct TapAxis {
    dsn_axis axis;
    int64_t base_extra, reach_limit;
    int64_t tap_shift[DSN_FILTER_MAX_TAPS];
};

/* False when the taps lie too far apart (tap_spread_limit). The walk reads tap t's integer part as
   S_t = int32(X_t - 1) and its offset to an impulse at integer position p (its copy's) as
   (S_t + 1 - p) 2^32 + fraction_t - in_cell; with S the lowest S_t that is
   (S + 1 - p) 2^32 - in_cell + relative_t, relative_t = (S_t - S) 2^32 + fraction_t. */
bool tap_axis(const uint64_t *coordinates, uint32_t taps, uint32_t radius, uint32_t shift, uint32_t period,
              TapAxis *out) {
    int64_t starts[DSN_FILTER_MAX_TAPS];
    int64_t lowest = 0, highest = 0;
    for (uint32_t t = 0; t < taps; t++) {
        starts[t] = dsn_signed_sum(static_cast<uint32_t>(coordinates[t] >> 32) - 1u);
        lowest = t == 0 || starts[t] < lowest ? starts[t] : lowest;
        highest = t == 0 || starts[t] > highest ? starts[t] : highest;
    }
    if (highest - lowest > tap_spread_limit) return false;
    int64_t relative[DSN_FILTER_MAX_TAPS], least = 0, most = 0;
    for (uint32_t t = 0; t < taps; t++) {
        relative[t] = (starts[t] - lowest) * static_cast<int64_t>(one_texel) +
                      static_cast<int64_t>(static_cast<uint32_t>(coordinates[t]));
        least = t == 0 || relative[t] < least ? relative[t] : least;
        most = t == 0 || relative[t] > most ? relative[t] : most;
    }
    dsn_axis_init(&out->axis, static_cast<uint32_t>(static_cast<uint64_t>(lowest)),
                  static_cast<uint32_t>(highest - lowest) + 3u, radius, shift, period);
    const int64_t reach = static_cast<int64_t>(radius + 1u) * static_cast<int64_t>(one_texel);
    out->base_extra = most + reach;
    out->reach_limit = 2 * reach + most - least;
    for (uint32_t t = 0; t < taps; t++) out->tap_shift[t] = reach + most - relative[t];
    return true;
}

/* The level test on the kernel's narrow offsets C = floor(c / 2^16) modulo 2^32, every c of an axis
   having the same low 16 bits K (its cells' shifted_base's): with A = start + K, u = c + start is
   V 2^16 + (A modulo 2^16), V = C + floor(A / 2^16). With both axes' reach_limit below
   narrow_reach_limit every |c|, |start| and |u| of the group stays below 2^46, so V modulo 2^32 is V for
   u >= 0 and at least 2^32 - 2^30 (above any limit) for u < 0: an impulse is in reach when C + add
   (modulo 2^32) is below limit = ceil((test limit - A modulo 2^16) / 2^16), and the bracket's shifted
   value (u + bias) >> (l + 16) is then (C + read) >> l, read = add + the carry of A modulo 2^16 + bias:
   tests[0 .. 2] = add, limit, read. */
const int64_t narrow_reach_limit = static_cast<int64_t>(1) << 44;

void narrow_test(const LevelTest &test, int64_t shifted_base, uint32_t *tests) {
    const uint64_t a = test.start + (static_cast<uint64_t>(shifted_base) & 0xFFFFu), a_low = a & 0xFFFFu;
    const uint32_t add = static_cast<uint32_t>(a >> 16);
    tests[0] = add;
    tests[1] = static_cast<uint32_t>((test.limit - a_low + 0xFFFFu) >> 16);
    tests[2] = add + static_cast<uint32_t>((a_low + test.bias) >> 16);
}

/* The buffer; where the kernel listed it, also each listed cell's end in it and the largest offset c
   of its candidates along each axis (their shifted_base): the cell's candidates lie within a cell's
   side below, so a tap's level need not test the cells that lie beyond its reach. */
const uint32_t listed_cells_most = 128;

struct CandidateList {
    int64_t x[buffer_capacity], y[buffer_capacity];
    uint32_t narrow_x[buffer_capacity], narrow_y[buffer_capacity]; /* the kernel's: x / 2^16, y / 2^16 */
    uint32_t count;
    uint32_t cells, cell_end[listed_cells_most];
    int64_t cell_x[listed_cells_most], cell_y[listed_cells_most];
};

void record_cell(CandidateList *list, int64_t x, int64_t y) {
    list->cell_x[list->cells] = x;
    list->cell_y[list->cells] = y;
    list->cells++;
}

/* The least and largest cell_x, cell_y of a list whose cells were recorded (reached_runs's), found
   only where runs are asked for. */
struct CellBounds {
    int64_t lowest_x, highest_x, lowest_y, highest_y;
};

CellBounds cell_bounds(const CandidateList &list) {
    CellBounds bounds = {0, 0, 0, 0};
    for (uint32_t k = 0; k < list.cells; k++) {
        const int64_t x = list.cell_x[k], y = list.cell_y[k];
        bounds.lowest_x = k == 0 || x < bounds.lowest_x ? x : bounds.lowest_x;
        bounds.highest_x = k == 0 || x > bounds.highest_x ? x : bounds.highest_x;
        bounds.lowest_y = k == 0 || y < bounds.lowest_y ? y : bounds.lowest_y;
        bounds.highest_y = k == 0 || y > bounds.highest_y ? y : bounds.highest_y;
    }
    return bounds;
}

/* The runs [runs[2k], runs[2k + 1]) of the list whose cells the level tests x, y may keep, their count:
   with u = c + start the test keeps 0 <= u < limit, and a cell's candidates have u within
   (w - 2^(32 + shift), w] for w its largest. The whole list where the cells were not recorded. */
uint32_t reached_runs(const CandidateList &list, const CellBounds &bounds, const LevelTest &x,
                      const LevelTest &y, uint32_t shift, uint32_t *runs) {
    if (list.cells == 0) {
        runs[0] = 0, runs[1] = list.count;
        return 1;
    }
    const int64_t side = static_cast<int64_t>(1) << (32u + shift);
    const int64_t limit_x = static_cast<int64_t>(x.limit) + side,
                  limit_y = static_cast<int64_t>(y.limit) + side;
    /* Every cell kept (w grows with the cell's offset: the box is far narrower than 2^62): one run. */
    if (signed_from_bits(static_cast<uint64_t>(bounds.lowest_x) + x.start) >= 0 &&
        signed_from_bits(static_cast<uint64_t>(bounds.highest_x) + x.start) < limit_x &&
        signed_from_bits(static_cast<uint64_t>(bounds.lowest_y) + y.start) >= 0 &&
        signed_from_bits(static_cast<uint64_t>(bounds.highest_y) + y.start) < limit_y) {
        runs[0] = 0, runs[1] = list.count;
        return 1;
    }
    uint32_t count = 0, from = 0, to = 0;
    for (uint32_t k = 0; k < list.cells; k++) {
        const int64_t w_x = signed_from_bits(static_cast<uint64_t>(list.cell_x[k]) + x.start),
                      w_y = signed_from_bits(static_cast<uint64_t>(list.cell_y[k]) + y.start);
        if (w_x < 0 || w_x >= limit_x || w_y < 0 || w_y >= limit_y) continue;
        const uint32_t begin = k == 0 ? 0u : list.cell_end[k - 1u];
        if (begin != to) {
            if (to != from) runs[2u * count] = from, runs[2u * count + 1u] = to, count++;
            from = begin;
        }
        to = list.cell_end[k];
    }
    if (to != from) runs[2u * count] = from, runs[2u * count + 1u] = to, count++;
    return count;
}

/* One level's sums at one tap while the candidates are visited: interior reads (8-bit ones on SSE2
   vectors) of biased values, and their count; border reads as they are. */
struct LevelAccumulator {
#if defined(__SSE2__)
    BilinearSums vector;
#endif
    uint64_t interior[DSN_MAX_CHANNELS], border[DSN_MAX_CHANNELS], interior_count;
};

void clear(LevelAccumulator *sums) {
#if defined(__SSE2__)
    sums->vector.even = sums->vector.odd = zero_128();
#endif
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) sums->interior[c] = sums->border[c] = 0;
    sums->interior_count = 0;
}

#if defined(__SSE2__)
/* The row above or below a level's window: zeros. */
const unsigned char zero_row[8] = {0, 0, 0, 0, 0, 0, 0, 0};

/* The 2 x 2 texels of 8-bit values at (row, column) in [-1, height - 1] x [-1, width - 1], width >= 2,
   zero outside the window, added without a branch: rows outside read zero_row, and the pair of texels
   is read from the column clamped into [0, width - 2] and moved by one texel where it was clamped, the
   texel that left the window zeroed. The reads stay within the rows' bytes plus 2 (as the interior's). */
template <uint32_t Channels>
inline vector_128 bordered_row(const unsigned char *values, uint32_t offset, bool inside, bool left_out,
                               bool right_out) {
    const uint32_t texel_bits = 8u * Channels;
    const unsigned char *from = inside ? values + offset : zero_row;
    uint64_t word;
    if (Channels == 3) {
        __builtin_memcpy(&word, from, sizeof word);
    } else {
        uint32_t half;
        __builtin_memcpy(&half, from, sizeof half);
        word = half;
    }
    const uint64_t right_mask =
        right_out ? (static_cast<uint64_t>(1) << texel_bits) - 1u : ~static_cast<uint64_t>(0);
    word = ((word << (left_out ? texel_bits : 0u)) >> (right_out ? texel_bits : 0u)) & right_mask;
    if (Channels == 3) return load_low_64(&word);
    return set_low_32(static_cast<int>(static_cast<uint32_t>(word))); /* the bits unchanged */
}
#endif

template <uint32_t Channels, uint32_t Bytes>
inline void read_level(const dsn_walked_level &level, uint64_t shifted_x, uint64_t shifted_y,
                       LevelAccumulator *sums) {
    const uint32_t row = static_cast<uint32_t>(shifted_y >> 32) - 1u,
                   column = static_cast<uint32_t>(shifted_x >> 32) - 1u;
    const int64_t down = static_cast<int64_t>((shifted_y >> 16) & bilinear_weight_mask),
                  across = static_cast<int64_t>((shifted_x >> 16) & bilinear_weight_mask);
    const uint32_t width = level.width;
#if defined(__SSE2__)
    if (Bytes == 1 && width >= 2) {
        const bool left_out = column == 0xFFFFFFFFu, right_out = column == width - 1u;
        const uint32_t first = column + (left_out ? 1u : 0u) - (right_out ? 1u : 0u);
        const uint32_t row_size = level.stride * Channels, top = row * row_size + first * Channels;
        sums->interior_count++;
        add_bilinear_bytes<Channels>(
            bordered_row<Channels>(level.values, top, row != 0xFFFFFFFFu, left_out, right_out),
            bordered_row<Channels>(level.values, top + row_size, row + 1u < level.height, left_out,
                                   right_out),
            static_cast<uint32_t>(across), static_cast<uint32_t>(down), &sums->vector);
        return;
    }
#endif
    if (row < level.height - 1u && column < width - 1u) { /* -1 (0xFFFFFFFF) fails too */
        /* The vector read passes a level's last value by 2 bytes: the texton and its CRC follow the
           pyramid section in the asset, so those bytes are in the buffer. */
        const unsigned char *top = level.values + (row * level.stride + column) * Channels * Bytes;
        const unsigned char *bottom = top + level.stride * Channels * Bytes;
        sums->interior_count++;
#if defined(__SSE2__)
        if (Bytes == 1) {
            add_bilinear_vector<Channels>(top, bottom, static_cast<uint32_t>(across),
                                          static_cast<uint32_t>(down), &sums->vector);
            return;
        }
#endif
        for (uint32_t c = 0; c < Channels; c++)
            sums->interior[c] +=
                bilinear_channel<Bytes, Channels * Bytes>(top + c * Bytes, bottom + c * Bytes, across, down);
    } else {
        add_border<Channels, Bytes>(level.values, width, level.height, level.stride, row, column, across,
                                    down, sums->border);
    }
}

template <uint32_t Channels, uint32_t Bytes>
void take(const LevelAccumulator &sums, uint64_t *out) {
    uint64_t interior[DSN_MAX_CHANNELS] = {sums.interior[0], sums.interior[1], sums.interior[2]};
#if defined(__SSE2__)
    if (Bytes == 1) take_bilinear_sums<Channels>(sums.vector, interior);
#endif
    /* Each interior read was of biased values: 2^(32 + 8 Bytes - 1) too high. */
    for (uint32_t c = 0; c < Channels; c++)
        out[c] += interior[c] - (sums.interior_count << (31u + 8u * Bytes)) + sums.border[c];
}

struct TapGroup;

/* A mix of two materials alike whose weights are uniform (DSN_MIXING): the candidates that the group's
   filter leaves are the other material's, listed in the same walk into its own list, visited with its own
   group and summed into its own sums. */
struct RestListing {
    const TapGroup *group;
    CandidateList *list;
    uint64_t (*sums)[2][DSN_MAX_CHANNELS];
};

/* The taps that one walk serves, and the levels they read. */
struct TapGroup {
    const dsn_walked_level *levels;
    dsn_filter_level_reads_entry *vector_reads;   /* the kernel's (8-bit levels), or null */
    dsn_filter_candidates_entry *list_candidates; /* the kernel's (cells of side <= 16), or null */
    uint32_t shift;                               /* the noise's cell_shift */
    bool narrow;      /* the kernel's listing and reads take the narrow offsets only (narrow_test) */
    uint64_t *listed; /* null, or where the candidates are counted instead of read
                         (dsn_internal_filter_listing_only) */
    const uint32_t *tap_levels; /* null (every tap reads every level), or per tap the bits of the levels
                                   it reads (the gradient's moved taps read one or none) */
    bool one_spot;              /* the taps are one tap and its moved copies */
    dsn_filter_slopes *slopes;  /* null, or where the kernel's reads add the taps' slopes (closed tests) */
    const dsn_impulse_filter *filter; /* null, or the impulses one material of a mix keeps (DSN_MIXING) */
    const RestListing *rest;          /* null, or where the impulses the filter leaves go (the kernel's
                                         listing only) */
    uint32_t level_count, first, taps;
    TapAxis x, y;
};

/* A small level read at a single tap: the impulses' bilinear weights are added up per texel first, and
   multiplied by the texels once at the end. The same integer: each read is sum over its 4 texels of
   (row weight)(column weight)(value), so the sum over impulses is sum over texels of (value)(sum of
   their weight products) modulo 2^64. Texel (R, C), R in [-1, height], C in [-1, width], has its sum at
   (R + 1)(width + 2) + C + 1 (the border ones are never multiplied: their values are 0). The coarse
   levels, whose reach holds the most impulses, have the smallest windows. */
const uint32_t splat_capacity = 128;

struct SplatGrid {
    uint64_t weights[splat_capacity];
    uint32_t level_index; /* which of the group's levels */
};

bool splat_fits(const dsn_walked_level &level) {
    return (level.width + 2u) * (level.height + 2u) <= splat_capacity;
}

inline void splat(const dsn_walked_level &level, uint64_t shifted_x, uint64_t shifted_y, SplatGrid *grid) {
    const uint32_t row = static_cast<uint32_t>(shifted_y >> 32) - 1u,
                   column = static_cast<uint32_t>(shifted_x >> 32) - 1u;
    const uint64_t down = (shifted_y >> 16) & bilinear_weight_mask,
                   across = (shifted_x >> 16) & bilinear_weight_mask;
    const uint32_t side = level.width + 2u;
    uint64_t *at = grid->weights + (row + 1u) * side + (column + 1u);
    at[0] += (65536u - down) * (65536u - across);
    at[1] += (65536u - down) * across;
    at[side] += down * (65536u - across);
    at[side + 1u] += down * across;
}

template <uint32_t Channels, uint32_t Bytes>
void take_splat(const SplatGrid &grid, const dsn_walked_level &level, uint64_t *out) {
    const uint32_t side = level.width + 2u;
    for (uint32_t row = 0; row < level.height; row++)
        for (uint32_t column = 0; column < level.width; column++) {
            const uint64_t weight = grid.weights[(row + 1u) * side + column + 1u];
            const unsigned char *at = level.values + (row * level.stride + column) * Channels * Bytes;
            for (uint32_t c = 0; c < Channels; c++) {
                const int32_t value = Bytes == 1 ? dsn_read_i8(at + c) : dsn_read_i16le(at + 2u * c);
                out[c] += weight * static_cast<uint64_t>(static_cast<int64_t>(value));
            }
        }
}

/* Every tap of the group visits every listed candidate; empties the list. The in-reach tests of a tap
   and level run over the whole list first, into a mask (no branch: most candidates of a long footprint's
   box are out of one tap's reach, and the outcome would be hard to predict), then the reads follow the
   mask's bits. */
template <uint32_t Channels, uint32_t Bytes>
void visit(const TapGroup &group, CandidateList *list, SplatGrid *grid, dsn_filter_sums sums) {
    if (group.listed != 0) {
        *group.listed += list->count;
        list->count = list->cells = 0;
        return;
    }
    /* A single tap's kernel reads take the whole list at once (their exact tests leave out what lies
       beyond the level's reach): a call per run of cells, each with its partial vectors, costs more
       than testing the candidates of the cells beyond. (No splat grid then: sum_group.) So do one tap's
       moved copies, whose reaches are the tap's within a texel. */
    const bool whole_list = Bytes == 1 && group.vector_reads != 0 && (group.taps == 1 || group.one_spot);
    const CellBounds bounds = whole_list ? CellBounds() : cell_bounds(*list);
    for (uint32_t t = 0; t < group.taps; t++) {
        for (uint32_t l = 0; l < group.level_count; l++) {
            if (group.tap_levels != 0 && ((group.tap_levels[group.first + t] >> l) & 1u) == 0) continue;
            const dsn_walked_level &level = group.levels[l];
            const bool closed = group.slopes != 0;
            const LevelTest test_x = level_test(level, level.radius_x, group.x.tap_shift[t], closed);
            const LevelTest test_y = level_test(level, level.radius_y, group.y.tap_shift[t], closed);
            const bool splat_level = grid != 0 && grid->level_index == l;
            uint32_t runs[2u * listed_cells_most + 2u];
            const uint32_t run_count = whole_list
                                           ? (runs[0] = 0, runs[1] = list->count, 1u)
                                           : reached_runs(*list, bounds, test_x, test_y, group.shift, runs);
            if (Bytes == 1 && group.vector_reads != 0 && !splat_level) {
                const uint64_t tests[5] = {test_x.start, test_x.limit, test_y.start, test_y.limit,
                                           test_x.bias};
                uint32_t narrow_tests[6] = {0, 0, 0, 0, 0, 0};
                const bool narrow = group.narrow && list->cells != 0;
                if (narrow) {
                    narrow_test(test_x, list->cell_x[0], narrow_tests);
                    narrow_test(test_y, list->cell_y[0], narrow_tests + 3);
                }
                uint64_t(*slopes)[DSN_MAX_CHANNELS] =
                    group.slopes != 0 ? (*group.slopes)[group.first + t][l] : 0;
                for (uint32_t r = 0; r < run_count; r++) {
                    const uint32_t from = runs[2u * r];
                    group.vector_reads(&level, Channels, list->x + from, list->y + from,
                                       narrow ? list->narrow_x + from : 0, narrow ? list->narrow_y + from : 0,
                                       runs[2u * r + 1u] - from, tests, narrow_tests,
                                       sums[group.first + t][l], slopes);
                }
                continue;
            }
            const uint64_t bias = test_x.bias; /* see LevelTest */
            LevelAccumulator level_sums;
            clear(&level_sums);
            for (uint32_t r = 0; r < run_count; r++)
                for (uint32_t chunk = runs[2u * r]; chunk < runs[2u * r + 1u]; chunk += mask_size) {
                    const int64_t *xs = list->x + chunk, *ys = list->y + chunk;
                    const uint32_t size =
                        runs[2u * r + 1u] - chunk < mask_size ? runs[2u * r + 1u] - chunk : mask_size;
                    uint64_t in_reach = 0;
                    for (uint32_t i = 0; i < size; i++) {
                        const uint64_t ux = static_cast<uint64_t>(xs[i]) + test_x.start;
                        const uint64_t uy = static_cast<uint64_t>(ys[i]) + test_y.start;
                        in_reach |= static_cast<uint64_t>((ux < test_x.limit) & (uy < test_y.limit)) << i;
                    }
                    for (; in_reach != 0; in_reach &= in_reach - 1u) {
                        const uint32_t i = lowest_bit(in_reach);
                        const uint64_t shifted_x = (static_cast<uint64_t>(xs[i]) + test_x.start + bias) >>
                                                   level.level,
                                       shifted_y = (static_cast<uint64_t>(ys[i]) + test_y.start + bias) >>
                                                   level.level;
                        if (splat_level)
                            splat(level, shifted_x, shifted_y, grid);
                        else
                            read_level<Channels, Bytes>(level, shifted_x, shifted_y, &level_sums);
                    }
                }
            if (!splat_level) take<Channels, Bytes>(level_sums, sums[group.first + t][l]);
        }
    }
    list->count = 0;
    list->cells = 0;
}

/* Lists the candidates of the cell with this key and impulse count: the impulses of its pairs that the
   lattice fields let reach the box, then those whose 16-bit positions do. */
template <uint32_t Channels, uint32_t Bytes>
void list_cell(const dsn_noise_state *noise, uint32_t key, uint32_t count, const FieldLanes &lanes,
               const TapGroup &group, const CellAxis &x, const CellAxis &y, CandidateList *list,
               SplatGrid *grid, dsn_filter_sums sums) {
    const uint32_t half_mask = (1u << lanes.half_bits) - 1u, fraction_shift = lanes.half_bits;
    const uint32_t position_shift = 16u + noise->cell_shift, high_shift = 16u - lanes.half_bits;
    const uint64_t limit_x = static_cast<uint64_t>(group.x.reach_limit) - 1u,
                   limit_y = static_cast<uint64_t>(group.y.reach_limit) - 1u;
    for (uint32_t first = 0; first < count; first += lanes.per_pair) {
        const uint64_t pair = dsn_position_pair(key, first >> (6u - lanes.field_shift));
        uint32_t candidates = gather_lanes(candidate_lanes(pair, lanes, x, y), lanes);
        const uint32_t present = count - first;
        if (present < lanes.per_pair) candidates &= (1u << present) - 1u; /* impulses that do not exist */
        for (; candidates != 0; candidates &= candidates - 1u) {
            const uint32_t lane = lowest_bit(candidates);
            const uint32_t field = dsn_pair_bits(pair, lane << lanes.field_shift);
            const uint32_t fraction = dsn_cell_stream(key, 0x80000000u + first + lane);
            /* dsn_impulse_hash's 16-bit positions */
            const uint32_t bits_x =
                ((field & half_mask) << high_shift) | ((fraction & 0xFFFFu) >> fraction_shift);
            const uint32_t bits_y = (((field >> lanes.half_bits) & half_mask) << high_shift) |
                                    ((fraction >> 16) >> fraction_shift);
            const uint64_t shifted_x =
                static_cast<uint64_t>(x.shifted_base) - (static_cast<uint64_t>(bits_x) << position_shift);
            const uint64_t shifted_y =
                static_cast<uint64_t>(y.shifted_base) - (static_cast<uint64_t>(bits_y) << position_shift);
            if (shifted_x - 1u >= limit_x || shifted_y - 1u >= limit_y) continue; /* beyond every tap */
            if (group.filter != 0 && !dsn_filter_keeps(group.filter, key, first + lane))
                continue; /* another material's */
            if (list->count >= (group.taps == 1 ? one_tap_buffer_size : buffer_size))
                visit<Channels, Bytes>(group, list, grid, sums);
            list->x[list->count] = static_cast<int64_t>(shifted_x);
            list->y[list->count] = static_cast<int64_t>(shifted_y);
            list->count++;
        }
    }
}

/* Whether the kernel lists the group's candidates: it has a listing, the cells have side <= 16 and an
   empty buffer holds the most impulses a cell can have (each of poisson_parts draws at most
   poisson_size). */
bool kernel_listing_takes(const dsn_noise_state *noise, const TapGroup &group) {
    return group.list_candidates != 0 && dsn_field_shift(noise->cell_shift) == 3 &&
           static_cast<uint64_t>(noise->poisson_parts) * noise->poisson_size + candidates_overrun <=
               buffer_capacity;
}

/* The list as the kernel's listing fills it (narrow: the narrow offsets alone). */
dsn_filter_list filter_list(CandidateList *list, bool narrow) {
    const dsn_filter_list listing = {list->count,    narrow ? 0 : list->x, narrow ? 0 : list->y,
                                     list->narrow_x, list->narrow_y,       list->cell_end + list->cells};
    return listing;
}

/* Up to cell_batch cells of the box along x from which its impulses may reach it (cell_axis_within). */
struct BoxColumns {
    uint32_t cell[cell_batch];
    CellAxis axis[cell_batch];
    uint32_t count;
};

/* The candidates of the box's cells in these columns: for each row of cells, the keys and counts of the
   columns' cells first (their chains of dependent loads then overlap), then the cells listed: by the
   kernel, those at once for which the buffer has room (the buffer visited where it has none for the
   next), or else one by one. Split: the group's rest (RestListing) listed in the same calls. */
template <uint32_t Channels, uint32_t Bytes, bool Split>
void list_columns(const dsn_noise_state *noise, const TapGroup &group, const BoxColumns &columns,
                  CandidateList *list, SplatGrid *grid, dsn_filter_sums sums) {
    const uint32_t shift = noise->cell_shift, batch = columns.count;
    const FieldLanes lanes = field_lanes(shift);
    const bool two_steps = dsn_poisson_two_steps_fit(noise), by_kernel = kernel_listing_takes(noise, group);
    for (uint32_t sy = 0; sy < group.y.axis.span_count; sy++) {
        const dsn_span span_y = dsn_axis_span(&group.y.axis, sy);
        for (uint32_t j = 0; j < span_y.cell_count; j++) {
            const uint32_t cell_y = dsn_span_cell(&span_y, j, shift);
            CellAxis in_y;
            if (!cell_axis_within(group.y.axis, span_y, cell_y, group.y.base_extra, group.y.reach_limit,
                                  lanes, &in_y))
                continue;
            const uint32_t row_key = dsn_row_key(noise, cell_y);
            dsn_filter_cell cells[cell_batch];
            for (uint32_t i = 0; i < batch; i++) {
                cells[i].key = dsn_cell_key_in_row(noise, columns.cell[i], row_key);
                cells[i].x = columns.axis[i];
                cells[i].y = in_y;
            }
            if (two_steps)
                for (uint32_t i = 0; i < batch; i++)
                    cells[i].count = dsn_poisson_count_two_steps(noise, cells[i].key);
            else
                for (uint32_t i = 0; i < batch; i++)
                    cells[i].count = dsn_cell_impulse_count(noise, cells[i].key);
            if (!by_kernel) {
                for (uint32_t i = 0; i < batch; i++)
                    list_cell<Channels, Bytes>(noise, cells[i].key, cells[i].count, lanes, group, cells[i].x,
                                               in_y, list, grid, sums);
                continue;
            }
            const RestListing *rest = Split ? group.rest : 0; /* (a constant without: no rest code) */
            for (uint32_t i = 0; i < batch;) {
                const uint32_t filled =
                    rest != 0 && rest->list->count > list->count ? rest->list->count : list->count;
                uint32_t end = i, room = buffer_capacity - candidates_overrun - filled;
                for (; end < batch && list->cells + (end - i) < listed_cells_most; end++) {
                    if (cells[end].count > room) break;
                    room -= cells[end].count;
                }
                if (end > i) {
                    dsn_filter_list kept = filter_list(list, group.narrow), others;
                    if (rest != 0) others = filter_list(rest->list, group.narrow);
                    list->count = group.list_candidates(cells + i, end - i, shift, &kept,
                                                        rest != 0 ? &others : 0, group.filter);
                    if (rest != 0) rest->list->count = others.count;
                    for (; i < end; i++) {
                        record_cell(list, cells[i].x.shifted_base, cells[i].y.shifted_base);
                        if (rest != 0)
                            record_cell(rest->list, cells[i].x.shifted_base, cells[i].y.shifted_base);
                    }
                } else { /* an empty buffer has room for any cell (kernel_listing_takes) */
                    visit<Channels, Bytes>(group, list, grid, sums);
                    if (rest != 0) visit<Channels, Bytes>(*rest->group, rest->list, 0, rest->sums);
                }
            }
        }
    }
}

/* The box's candidates, cell_batch columns of cells at a time. */
template <uint32_t Channels, uint32_t Bytes, bool Split>
void list_box(const dsn_noise_state *noise, const TapGroup &group, const FieldLanes &lanes,
              CandidateList *list, SplatGrid *grid, dsn_filter_sums sums) {
    BoxColumns columns;
    columns.count = 0;
    for (uint32_t s = 0; s < group.x.axis.span_count; s++) {
        const dsn_span span = dsn_axis_span(&group.x.axis, s);
        for (uint32_t i = 0; i < span.cell_count; i++) {
            const uint32_t cell = dsn_span_cell(&span, i, group.x.axis.shift);
            CellAxis axis;
            if (!cell_axis_within(group.x.axis, span, cell, group.x.base_extra, group.x.reach_limit, lanes,
                                  &axis))
                continue;
            columns.cell[columns.count] = cell;
            columns.axis[columns.count] = axis;
            if (++columns.count == cell_batch) {
                list_columns<Channels, Bytes, Split>(noise, group, columns, list, grid, sums);
                columns.count = 0;
            }
        }
    }
    if (columns.count != 0) list_columns<Channels, Bytes, Split>(noise, group, columns, list, grid, sums);
}

template <uint32_t Channels, uint32_t Bytes>
void sum_group(const dsn_noise_state *noise, const TapGroup &group, dsn_filter_sums sums) {
    const uint32_t shift = noise->cell_shift;
    const FieldLanes lanes = field_lanes(shift);
    CandidateList list;
    list.count = list.cells = 0;
    /* One tap: its coarser level through the splat grid when that is small, unless the kernel reads the
       level on vectors (faster). */
    SplatGrid splat_grid, *grid = 0;
    const dsn_walked_level &coarser = group.levels[group.level_count - 1u];
    if (group.taps == 1 && group.listed == 0 && splat_fits(coarser) &&
        !(Bytes == 1 && group.vector_reads != 0)) {
        grid = &splat_grid;
        grid->level_index = group.level_count - 1u;
        for (uint32_t i = 0; i < (coarser.width + 2u) * (coarser.height + 2u); i++) grid->weights[i] = 0;
    }
    if (group.rest != 0)
        list_box<Channels, Bytes, true>(noise, group, lanes, &list, grid, sums);
    else
        list_box<Channels, Bytes, false>(noise, group, lanes, &list, grid, sums);
    visit<Channels, Bytes>(group, &list, grid, sums);
    if (group.rest != 0) visit<Channels, Bytes>(*group.rest->group, group.rest->list, 0, group.rest->sums);
    if (grid != 0) take_splat<Channels, Bytes>(*grid, coarser, sums[group.first][grid->level_index]);
}

/* The taps first .. first + taps - 1 of the points (x, y) in one walk, their candidates counted instead of
   read where listed is not null; false when they lie too far apart. */
bool tap_group(const dsn_noise_state *noise, const uint64_t *x, const uint64_t *y, uint32_t first,
               uint32_t taps, const dsn_walked_level *levels, uint32_t count, uint64_t *listed,
               const uint32_t *tap_levels, bool one_spot, TapGroup *group) {
    uint32_t radius_x, radius_y;
    dsn_filter_walk_radii(levels, count, &radius_x, &radius_y);
    group->levels = levels;
    group->vector_reads = dsn_kernel_entries_of(noise->tile_kernel)->filter_level_reads;
    group->list_candidates = dsn_kernel_entries_of(noise->tile_kernel)->filter_candidates;
    group->shift = noise->cell_shift;
    group->level_count = count;
    group->first = first;
    group->taps = taps;
    group->listed = listed;
    group->tap_levels = tap_levels;
    group->one_spot = one_spot;
    group->slopes = 0;
    group->filter = 0;
    group->rest = 0;
    if (!tap_axis(x + first, taps, radius_x, noise->cell_shift, noise->period[0], &group->x) ||
        !tap_axis(y + first, taps, radius_y, noise->cell_shift, noise->period[1], &group->y))
        return false;
    group->narrow = group->vector_reads != 0 && group->list_candidates != 0 && noise->asset.bits == 8 &&
                    group->x.reach_limit < narrow_reach_limit && group->y.reach_limit < narrow_reach_limit;
    return true;
}

template <uint32_t Channels, uint32_t Bytes>
void sum_taps(const dsn_noise_state *noise, const uint64_t *x, const uint64_t *y, uint32_t taps,
              const dsn_walked_level *levels, uint32_t count, dsn_filter_sums sums, uint64_t *listed,
              const uint32_t *tap_levels, bool one_spot, const dsn_impulse_filter *filter) {
    TapGroup group;
    if (tap_group(noise, x, y, 0, taps, levels, count, listed, tap_levels, one_spot, &group)) {
        group.filter = filter;
        sum_group<Channels, Bytes>(noise, group, sums);
        return;
    }
    for (uint32_t t = 0; t < taps; t++) {
        tap_group(noise, x, y, t, 1, levels, count, listed, tap_levels, false, &group); /* no spread */
        group.filter = filter;
        sum_group<Channels, Bytes>(noise, group, sums);
    }
}

/* The sums at the points (tap_x, tap_y), zeroed first; one_spot, filter: TapGroup's. */
void sum_points(const dsn_noise_state *noise, const uint64_t *tap_x, const uint64_t *tap_y, uint32_t taps,
                const dsn_walked_level *levels, uint32_t count, dsn_filter_sums sums, uint64_t *listed,
                const uint32_t *tap_levels, bool one_spot, const dsn_impulse_filter *filter) {
    for (uint32_t tap = 0; tap < taps; tap++)
        for (uint32_t l = 0; l < 2; l++)
            for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) sums[tap][l][c] = 0;
    const dsn_asset *asset = &noise->asset;
    if (asset->channels == 3) {
        if (asset->bits == 8)
            sum_taps<3, 1>(noise, tap_x, tap_y, taps, levels, count, sums, listed, tap_levels, one_spot,
                           filter);
        else
            sum_taps<3, 2>(noise, tap_x, tap_y, taps, levels, count, sums, listed, tap_levels, one_spot,
                           filter);
    } else {
        if (asset->bits == 8)
            sum_taps<1, 1>(noise, tap_x, tap_y, taps, levels, count, sums, listed, tap_levels, one_spot,
                           filter);
        else
            sum_taps<1, 2>(noise, tap_x, tap_y, taps, levels, count, sums, listed, tap_levels, one_spot,
                           filter);
    }
}

void sum_taps_of_asset(const dsn_noise_state *noise, uint64_t x, uint64_t y, const dsn_filter_plan *plan,
                       const dsn_walked_level *levels, uint32_t count, dsn_filter_sums sums, uint64_t *listed,
                       const dsn_impulse_filter *filter) {
    uint64_t tap_x[DSN_FILTER_MAX_TAPS], tap_y[DSN_FILTER_MAX_TAPS];
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        tap_x[tap] = x + static_cast<uint64_t>(plan->offset_x[tap]);
        tap_y[tap] = y + static_cast<uint64_t>(plan->offset_y[tap]);
    }
    sum_points(noise, tap_x, tap_y, plan->taps, levels, count, sums, listed, 0, false, filter);
}

#if DSN_GRADIENTS
/* The sums and slopes of the taps first .. first + taps - 1 in one walk, each tap's slopes read with its
   values (the kernel's reads, closed tests), or false (the taps lie too far apart). Each tap has a copy
   moved by one weight step of the coarser level along both axes, which reads nothing: the box then holds
   the impulses at the entry edge of every level's reach too. */
template <uint32_t Channels>
bool slopes_in_one_pass(const dsn_noise_state *noise, uint64_t x, uint64_t y, const dsn_filter_plan *plan,
                        const dsn_walked_level *levels, uint32_t count, uint32_t first, uint32_t taps,
                        dsn_filter_sums sums, dsn_filter_slopes *slopes) {
    const uint64_t step = static_cast<uint64_t>(1) << (weight_step_shift + levels[count - 1u].level);
    uint64_t point_x[DSN_FILTER_MAX_TAPS], point_y[DSN_FILTER_MAX_TAPS];
    uint32_t point_levels[DSN_FILTER_MAX_TAPS];
    dsn_filter_sums point_sums;
    dsn_filter_slopes point_slopes;
    for (uint32_t t = 0; t < taps; t++) {
        point_x[2u * t] = x + static_cast<uint64_t>(plan->offset_x[first + t]);
        point_y[2u * t] = y + static_cast<uint64_t>(plan->offset_y[first + t]);
        point_x[2u * t + 1u] = point_x[2u * t] + step, point_y[2u * t + 1u] = point_y[2u * t] + step;
        point_levels[2u * t] = (1u << count) - 1u, point_levels[2u * t + 1u] = 0;
        for (uint32_t l = 0; l < 2; l++)
            for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++)
                point_sums[2u * t][l][c] = point_slopes[2u * t][l][0][c] = point_slopes[2u * t][l][1][c] = 0;
    }
    TapGroup group;
    if (!tap_group(noise, point_x, point_y, 0, 2u * taps, levels, count, 0, point_levels, taps == 1, &group))
        return false;
    group.slopes = &point_slopes;
    sum_group<Channels, 1>(noise, group, point_sums);
    for (uint32_t t = 0; t < taps; t++)
        for (uint32_t l = 0; l < 2; l++)
            for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) {
                sums[first + t][l][c] = point_sums[2u * t][l][c];
                (*slopes)[first + t][l][0][c] = point_slopes[2u * t][l][0][c];
                (*slopes)[first + t][l][1][c] = point_slopes[2u * t][l][1][c];
            }
    return true;
}

/* The sums and slopes of every tap in one pass where the kernel reads 8-bit levels (false elsewhere, and
   where the taps lie too far apart). */
bool slopes_one_pass(const dsn_noise_state *noise, uint64_t x, uint64_t y, const dsn_filter_plan *plan,
                     const dsn_walked_level *levels, uint32_t count, dsn_filter_sums sums,
                     dsn_filter_slopes *slopes) {
    if (noise->asset.bits != 8 || dsn_kernel_entries_of(noise->tile_kernel)->filter_level_reads == 0)
        return false;
    const uint32_t taps_per_walk = DSN_FILTER_MAX_TAPS / 2u;
    for (uint32_t first = 0; first < plan->taps; first += taps_per_walk) {
        const uint32_t taps = plan->taps - first < taps_per_walk ? plan->taps - first : taps_per_walk;
        const bool summed =
            noise->asset.channels == 3
                ? slopes_in_one_pass<3>(noise, x, y, plan, levels, count, first, taps, sums, slopes)
                : slopes_in_one_pass<1>(noise, x, y, plan, levels, count, first, taps, sums, slopes);
        if (!summed) return false;
    }
    return true;
}

/* Whether the walk's start along an axis, int32(X - 1), wraps from 2^31 - 1 to -2^31 when the coordinate
   moves by `step` (below a texel). */
bool start_wraps(uint64_t coordinate, uint64_t step) {
    const uint32_t start = static_cast<uint32_t>(coordinate >> 32) - 1u,
                   moved = static_cast<uint32_t>((coordinate + step) >> 32) - 1u;
    return start != moved && moved == 0x80000000u;
}
#endif

} // namespace

void dsn_internal_filter_sums_sifted(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                     const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                     uint32_t count, dsn_filter_sums sums) {
    sum_taps_of_asset(noise, x, y, plan, levels, count, sums, 0, 0);
}

#if DSN_MIXING
void dsn_internal_filter_sums_kept(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                   const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                   uint32_t count, const dsn_impulse_filter *filter, dsn_filter_sums sums) {
    sum_taps_of_asset(noise, x, y, plan, levels, count, sums, 0, filter);
}

bool dsn_internal_filter_sums_split(const dsn_noise_state *noise, const dsn_noise_state *other, uint64_t x,
                                    uint64_t y, const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                    const dsn_walked_level *other_levels, uint32_t count,
                                    const dsn_impulse_filter *filter, dsn_filter_sums sums,
                                    dsn_filter_sums other_sums) {
    const uint32_t channels = noise->asset.channels;
    uint32_t radius_x, radius_y, other_x, other_y;
    dsn_filter_walk_radii(levels, count, &radius_x, &radius_y);
    dsn_filter_walk_radii(other_levels, count, &other_x, &other_y);
    /* the same walk for both (tap_axis's inputs), 8-bit levels of the same channels read by the kernel */
    if (noise->asset.bits != 8 || other->asset.bits != 8 || other->asset.channels != channels ||
        radius_x != other_x || radius_y != other_y || noise->cell_shift != other->cell_shift ||
        noise->period[0] != other->period[0] || noise->period[1] != other->period[1] ||
        noise->tile_kernel != other->tile_kernel)
        return false;
    uint64_t tap_x[DSN_FILTER_MAX_TAPS], tap_y[DSN_FILTER_MAX_TAPS];
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        tap_x[tap] = x + static_cast<uint64_t>(plan->offset_x[tap]);
        tap_y[tap] = y + static_cast<uint64_t>(plan->offset_y[tap]);
    }
    TapGroup group, rest_group;
    if (!tap_group(noise, tap_x, tap_y, 0, plan->taps, levels, count, 0, 0, false, &group) ||
        !tap_group(other, tap_x, tap_y, 0, plan->taps, other_levels, count, 0, 0, false, &rest_group) ||
        group.vector_reads == 0 || !kernel_listing_takes(noise, group) || group.narrow != rest_group.narrow)
        return false;
    for (uint32_t tap = 0; tap < plan->taps; tap++)
        for (uint32_t l = 0; l < 2; l++)
            for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) sums[tap][l][c] = other_sums[tap][l][c] = 0;
    CandidateList rest_list;
    rest_list.count = rest_list.cells = 0;
    const RestListing rest = {&rest_group, &rest_list, other_sums};
    group.filter = filter;
    group.rest = &rest;
    channels == 3 ? sum_group<3, 1>(noise, group, sums) : sum_group<1, 1>(noise, group, sums);
    return true;
}
#endif

#if DSN_GRADIENTS
void dsn_internal_filter_slopes_sifted(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                       const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                       uint32_t count, dsn_filter_sums sums, dsn_filter_slopes *slopes) {
    if (slopes_one_pass(noise, x, y, plan, levels, count, sums, slopes)) return;
    /* Each tap with its copies moved by one weight step of each level along x and along y, in one walk with
       as many taps as fit: a copy reads its level only. Where a copy's int32 integer part less 1 (the
       walk's start, reduced modulo a period) wraps, a period that does not divide 2^32 makes the sums
       jump there: the walk's slopes (one-sided, of the tap's side) then. */
    for (uint32_t tap = 0; tap < plan->taps; tap++)
        for (uint32_t l = 0; l < count; l++) {
            const uint64_t step = static_cast<uint64_t>(1) << (weight_step_shift + levels[l].level);
            if (start_wraps(x + static_cast<uint64_t>(plan->offset_x[tap]), step) ||
                start_wraps(y + static_cast<uint64_t>(plan->offset_y[tap]), step)) {
                dsn_internal_filter_slopes_walked(noise, x, y, plan, levels, count, sums, slopes);
                return;
            }
        }
    const uint32_t points_per_tap = 1u + 2u * count, taps_per_walk = DSN_FILTER_MAX_TAPS / points_per_tap;
    for (uint32_t first = 0; first < plan->taps; first += taps_per_walk) {
        const uint32_t taps = plan->taps - first < taps_per_walk ? plan->taps - first : taps_per_walk;
        uint64_t point_x[DSN_FILTER_MAX_TAPS], point_y[DSN_FILTER_MAX_TAPS];
        uint32_t point_levels[DSN_FILTER_MAX_TAPS];
        for (uint32_t t = 0; t < taps; t++) {
            const uint64_t tap_x = x + static_cast<uint64_t>(plan->offset_x[first + t]),
                           tap_y = y + static_cast<uint64_t>(plan->offset_y[first + t]);
            uint64_t *at_x = point_x + t * points_per_tap, *at_y = point_y + t * points_per_tap;
            uint32_t *at_levels = point_levels + t * points_per_tap;
            at_x[0] = tap_x, at_y[0] = tap_y, at_levels[0] = (1u << count) - 1u;
            for (uint32_t l = 0; l < count; l++) {
                /* one weight step of level l (the offset is divided by 2^l before the read) */
                const uint64_t step = static_cast<uint64_t>(1) << (weight_step_shift + levels[l].level);
                at_x[1u + 2u * l] = tap_x + step, at_y[1u + 2u * l] = tap_y;
                at_x[2u + 2u * l] = tap_x, at_y[2u + 2u * l] = tap_y + step;
                at_levels[1u + 2u * l] = at_levels[2u + 2u * l] = 1u << l;
            }
        }
        dsn_filter_sums point_sums;
        sum_points(noise, point_x, point_y, taps * points_per_tap, levels, count, point_sums, 0, point_levels,
                   taps == 1, 0);
        /* The sums step by exactly 2^8 times the slopes over one weight step (the bilinear read is linear
           in its weights and the reach's edge reads 0): the walk's slopes. */
        for (uint32_t t = 0; t < taps; t++) {
            const uint64_t(*at)[2][DSN_MAX_CHANNELS] = point_sums + t * points_per_tap;
            for (uint32_t l = 0; l < 2; l++)
                for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) {
                    const bool read = l < count;
                    sums[first + t][l][c] = at[0][l][c];
                    (*slopes)[first + t][l][0][c] =
                        read ? slopes_from_step(at[1u + 2u * l][l][c] - at[0][l][c]) : 0;
                    (*slopes)[first + t][l][1][c] =
                        read ? slopes_from_step(at[2u + 2u * l][l][c] - at[0][l][c]) : 0;
                }
        }
    }
}
#endif

uint64_t dsn_internal_filter_listing_only(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                                          const dsn_filter_plan *plan, const dsn_walked_level *levels,
                                          uint32_t count) {
    dsn_filter_sums sums;
    uint64_t listed = 0;
    sum_taps_of_asset(noise, x, y, plan, levels, count, sums, &listed, 0);
    return listed;
}

#endif /* DSN_FILTERING && !DSN_SMALL_CODE */
