/* runtime/kernels/tile_strips.h - the fast path for 8-bit textons (SSE2, AVX2 or AVX-512BW, as compiled): a
   rectangle of the tile is cut into vertical strips one vector wide (8 pixels with SSE2, 16 with AVX2,
   32 with AVX-512). The impulses that reach the rectangle are listed once (with where they meet it),
   sorted by the row of their texton's first row, and filed under every strip they reach. Then, row by
   row, each strip adds in registers one texton row per impulse active on that row (a range of its sorted
   entries), in 16-bit lanes, read from a copy of the texton padded with a vector of zeros on each side so
   that every read is one whole vector (two rows at a time, sharing the loop; with AVX2 and AVX-512 a
   channel's two rows in one load, see make_paired_texel). A sum is normalized
   straight from its register: nothing is accumulated in memory, so the cost is loads, not
   read-modify-write stores.
   When no column of the rectangle is reached by more than coverage_limit impulses, no pixel is, and no
   sum can overflow: |q| <= 128 for any texton byte and 255 * 128 < 2^15. Otherwise (or when the list
   is full) the caller falls back to the 32-bit splat of tile_walk.h. Internal to tile_render.h. */
#ifndef DSN_TILE_STRIPS_H
#define DSN_TILE_STRIPS_H

#include "setup/noise_state.h"
#include "simd/simd.h"

namespace {

/* Pixels per strip (16-bit sums per vector); the texton's values as the strips read them (16 bits, one
   per pixel of a vector); rows summed at once (sharing the loop over entries; strip_rows - 1 rows of
   zeros pad the texton above and below, for the entries active on only some of them). */
typedef uint16_t strip_texel;
const uint32_t lane = simd_int16_count, strip_rows = 2;
static_assert(strip_rows == 2, "add_strip_rows and the paired planes sum two rows");
/* Where the ops header sums two rows from one load (DSN_SIMD_PAIRED_ROWS), every channel is kept as a
   paired plane: the texel at the place of texton row t (in an unpaired plane) holds rows t and t + 1 at
   its column, one byte each, biased by 128 (so unsigned), and one load gives both rows of a strip
   (add_pair, then finish_pair). Elsewhere (SSE2) the planes keep one row per texel, sign-extended. The
   padding of every plane is zero_texel (a paired texel of zeros, or 0), and the sums take count times
   the bias off at the end (modulo 2^16, exact: the true sums fit). */
const uint32_t zero_texel = DSN_SIMD_PAIRED_ROWS ? 0x8080u : 0u;
/* Texels per 64-byte cache line, and copies of the texton (strip_texton) worth keeping: two where a
   window is shorter than a line, one where it is a whole line (AVX-512), since such a window crosses a
   line wherever it starts but at the line's start, and a second copy cannot change that. */
const uint32_t line_texels = 64 / sizeof(strip_texel);
const uint32_t copies_limit = lane < line_texels ? 2 : 1;
const uint32_t rectangle_width = 128, rectangle_height = 128; /* the largest rectangle */
const uint32_t strip_count = rectangle_width / lane;
/* A gradient's sums are one column wider than its rectangle (tile_gradient.h): one strip more. */
const uint32_t strip_capacity = strip_count + 1;
const uint32_t coverage_limit = 255;
/* Rectangles are chosen to meet at most rectangle_impulses impulses on average (at 30 impacts per pixel
   a 31 x 31 texton gets 128 x 128 rectangles, meeting lambda (128 + 30)^2 = 779); the list holds 1024,
   almost 9 standard deviations more (a fuller rectangle takes the 32-bit path). Larger rectangles walk
   fewer cells twice and file fewer impulses per pixel; the lists then take more of the L1 cache. */
const uint32_t rectangle_impulses = 800, list_capacity = 1024;
/* And at most column_impulses on average in a column: the count is Poisson, so a column goes over
   coverage_limit about once in 10^4 (3.9 standard deviations; that rectangle takes the 32-bit path). */
const uint32_t column_impulses = 200;
/* Largest texton side of this path, and most strips one impulse may reach (a texton w wide reaches at
   most (w + lane - 2) / lane + 1: 5 of 8 pixels for w <= 33, and of 16 for w <= 63). */
const uint32_t strip_texton_side = 63, strips_per_impulse_limit = 5;
const uint32_t strip_entry_capacity = list_capacity * strips_per_impulse_limit;
/* Sort keys: the rectangle row where an impulse's texton row 0 lies, plus height - 1 (so >= 0). */
const uint32_t key_limit = rectangle_height + strip_texton_side;

/* Texels per texton row in strip_texton: room for lane zeros on the left of copy 0's windows, 2 lane in
   copy 1 (when there is one), a whole number of cache lines. */
constexpr uint32_t strip_stride(uint32_t width) {
    return (width + copies_limit * lane + line_texels - 1) / line_texels * line_texels;
}

/* The texton as strip_texel values, twice (once where copies_limit is 1). Each copy has one plane per
   channel, strip_rows - 1 rows of zeros (zero_texel) above and below each plane, and rows of `stride` values:
   zeros, the texton row from value lane (copy 0) or 2 lane (copy 1, `shifted` values further), zeros. The
   sums are bound by their loads, and a vector load that crosses a 64-byte cache line costs two: rows are
   whole cache lines, so whether a window's load crosses one depends only on its column, and the other copy
   then holds the same window at a column where it does not (file_strip_entries picks it). Every window read
   is inside the copies or the `stride` zeros after them (a copy 1 window may run up to lane - 1 values into
   the next row's zeros). */
typedef struct strip_texton {
    /* 31 x 31 RGB fits twice, or (one copy only) the largest RGB texton once */
    alignas(64) strip_texel
        values[copies_limit == 2
                   ? 2 * 3 * (31 + 2 * (strip_rows - 1)) * strip_stride(31) + strip_stride(31)
                   : 3 * (strip_texton_side + 2 * (strip_rows - 1)) * strip_stride(strip_texton_side) +
                         strip_stride(strip_texton_side)];
    uint32_t stride, plane, width, height, shifted; /* values per row and plane, texton size, copy 1 offset */
    uint32_t copies; /* 1 or 2: copy 1 pays off only over thousands of pixels */
} strip_texton;

/* A texton byte (two's complement) as a strip_texel of an unpaired plane: sign-extended to 16 bits. */
inline strip_texel make_texel(unsigned char byte) { return strip_texel((uint32_t(byte) ^ 0x80u) - 0x80u); }

/* Texel (t, x) of a paired plane, from the texton's channel c (rows outside the texton are zeros). */
inline strip_texel make_paired_texel(const dsn_asset *asset, uint32_t c, uint32_t t, uint32_t x) {
    const unsigned char *column = asset->texton + x * asset->channels + c;
    const uint32_t row_bytes = asset->width * asset->channels;
    const uint32_t first = t > 0 ? column[(t - 1) * row_bytes] : 0u,
                   second = t < asset->height ? column[t * row_bytes] : 0u;
    return strip_texel((first ^ 0x80u) | (second ^ 0x80u) << 8);
}

/* How many copies of the texton strip_texton can hold (2, 1, or 0 when the strip path cannot take it). */
uint32_t strip_texton_copies(const dsn_asset *asset) {
    if (asset->bits != 8 || asset->width > strip_texton_side || asset->height > strip_texton_side ||
        (asset->width + lane - 2) / lane + 1 > strips_per_impulse_limit)
        return 0;
    const uint32_t copy =
        asset->channels * (asset->height + 2 * (strip_rows - 1)) * strip_stride(asset->width);
    const uint32_t room = sizeof(strip_texton().values) / sizeof(strip_texel) - strip_stride(asset->width);
    return 2 * copy <= room && copies_limit == 2 ? 2 : copy <= room ? 1 : 0;
}

/* The size of the rectangles a tile is cut into. Below 4 rows, walking the cells per rectangle costs
   more than the strips save: such dense noises take the 32-bit path. */
const uint32_t minimum_rectangle_height = 4;
typedef struct rectangle_size {
    uint32_t width, height;
} rectangle_size;

/* The rectangle (width a multiple of lane, sides at most rectangle_width and rectangle_height) with the
   most pixels per impulse met, among those where on average at most rectangle_impulses impulses reach
   the rectangle, lambda (W + w - 1)(H + h - 1), and at most column_impulses reach a column,
   lambda w (H + h - 1), with lambda = impacts / |S| per pixel (compared in integers: impacts_q16 is
   impacts 2^16). Dense noises (small textons, many impacts) get smaller rectangles instead of
   overflowing the list or the 16-bit sums; {0, 0} when none has minimum_rectangle_height rows. */
rectangle_size choose_rectangle(const dsn_noise_state *noise) {
    const uint32_t margin_x = noise->asset.width - 1, margin_y = noise->asset.height - 1;
    const uint64_t budget = (uint64_t(rectangle_impulses) << 16) * noise->asset.support_size;
    const uint64_t column_rows = ((uint64_t(column_impulses) << 16) * noise->asset.support_size) /
                                 (uint64_t(noise->impacts_q16) * noise->asset.width); /* H + h - 1 */
    rectangle_size best = {0, 0};
    uint64_t best_pixels = 0, best_reach = 1; /* pixels / (pixels and margins) of the best so far */
    for (uint32_t width = lane; width <= rectangle_width; width += lane) {
        uint64_t rows = budget / (uint64_t(noise->impacts_q16) * (width + margin_x)); /* H + h - 1 */
        if (rows > column_rows) rows = column_rows;
        if (rows < margin_y + minimum_rectangle_height) continue;
        const uint32_t height =
            rows - margin_y < rectangle_height ? uint32_t(rows - margin_y) : rectangle_height;
        const uint64_t pixels = uint64_t(width) * height,
                       reach = uint64_t(width + margin_x) * (height + margin_y);
        if (pixels * best_reach > best_pixels * reach) {
            best.width = width;
            best.height = height;
            best_pixels = pixels;
            best_reach = reach;
        }
    }
    return best;
}

void make_strip_texton(const dsn_asset *asset, uint32_t copies, strip_texton *texton) {
    const uint32_t channels = asset->channels;
    texton->copies = copies;
    texton->stride = strip_stride(asset->width);
    texton->plane = (asset->height + 2 * (strip_rows - 1)) * texton->stride;
    texton->width = asset->width;
    texton->height = asset->height;
    texton->shifted = channels * texton->plane;
    for (uint32_t i = 0; i < copies * texton->shifted + texton->stride; i++)
        texton->values[i] = strip_texel(zero_texel);
    for (uint32_t c = 0; c < channels; c++) {
        if (DSN_SIMD_PAIRED_ROWS) {
            /* Pair row t holds texton rows t - 1 and t: at the place of texton row t - 1 in an unpaired
               plane. */
            for (uint32_t t = 0; t <= asset->height; t++) {
                strip_texel *dst = texton->values + c * texton->plane + t * texton->stride + lane;
                for (uint32_t column = 0; column < asset->width; column++) {
                    const strip_texel value = make_paired_texel(asset, c, t, column);
                    dst[column] = value;
                    if (copies == 2) dst[texton->shifted + lane + column] = value;
                }
            }
            continue;
        }
        for (uint32_t row = 0; row < asset->height; row++) {
            strip_texel *dst =
                texton->values + c * texton->plane + (row + strip_rows - 1) * texton->stride + lane;
            const unsigned char *src = asset->texton + row * asset->width * channels + c;
            for (uint32_t column = 0; column < asset->width; column++) {
                const strip_texel value = make_texel(src[column * channels]);
                dst[column] = value;
                if (copies == 2) dst[texton->shifted + lane + column] = value;
            }
        }
    }
}

/* An impulse that reaches the rectangle: the rectangle column and row of its texton's first texel
   (from -(side - 1), so stored as 16-bit two's complement; origin() reads them back), then, once the list
   is complete (impulse_list::prepare), its key and the strips it reaches. */
typedef struct listed_impulse {
    uint16_t origin_x, origin_y;
    uint8_t key, first_strip, strips;
} listed_impulse;

inline int32_t origin(uint16_t stored) { return int32_t(uint32_t(stored) ^ 0x8000u) - 0x8000; }

/* The impulses that reach a rectangle of length_x x length_y, from for_each_nearby_impulse. Every
   impulse is stored, only those that reach are counted: no branch on a coin flip. */
struct impulse_list {
    listed_impulse impulses[list_capacity + 1]; /* the last takes the stores past the capacity */
    uint32_t count;                             /* may exceed list_capacity: then only the count is kept */
    uint32_t length_x, length_y;

    void clear(uint32_t rectangle_length_x, uint32_t rectangle_length_y) {
        count = 0;
        length_x = rectangle_length_x;
        length_y = rectangle_length_y;
    }

    void operator()(uint32_t end_x, uint32_t end_y, uint32_t reaches) {
        listed_impulse *impulse = &impulses[count < list_capacity ? count : list_capacity];
        impulse->origin_x = uint16_t(length_x - 1u - end_x);
        impulse->origin_y = uint16_t(length_y - 1u - end_y);
        count += reaches;
    }

    /* Fills in each impulse's key (its origin row plus height - 1, >= 0 as it reaches the rectangle) and
       strips, and returns whether every pixel is reached by at most coverage_limit listed impulses (and
       all are listed): no column is reached by more. */
    int prepare(uint32_t texton_width, uint32_t texton_height) {
        if (count > list_capacity) return 0;
        int32_t column_change[rectangle_width + 2]; /* impulses starting minus ending at each column */
        for (uint32_t i = 0; i <= length_x; i++) column_change[i] = 0;
        for (uint32_t n = 0; n < count; n++) {
            listed_impulse *impulse = &impulses[n];
            const int32_t first = origin(impulse->origin_x), end = first + int32_t(texton_width);
            const uint32_t first_column = first > 0 ? uint32_t(first) : 0u;
            const uint32_t end_column = end < int32_t(length_x) ? uint32_t(end) : length_x;
            column_change[first_column]++;
            column_change[end_column]--;
            impulse->key = uint8_t(origin(impulse->origin_y) + int32_t(texton_height) - 1);
            impulse->first_strip = uint8_t(first_column / lane);
            impulse->strips = uint8_t((end_column - 1u) / lane - first_column / lane + 1u);
        }
        int32_t coverage = 0;
        for (uint32_t i = 0; i < length_x; i++) {
            coverage += column_change[i];
            if (coverage > int32_t(coverage_limit)) return 0;
        }
        return 1;
    }
};

/* The listed impulses filed under the strips they reach, each strip's entries in key order. An entry
   is where the impulse's texton window for the strip starts in strip_texton.values, less row * stride
   (adding row * stride for a rectangle row then gives the texton row on that row). An impulse puts a
   texton row on rectangle row y when y <= key <= y + height - 1, so the entries of strip s active on
   row y are [key_start[s][y], key_start[s][y + height]). */
typedef struct strip_entries {
    /* First entry of strip s with key >= k; the rows past strip_capacity let every impulse update
       strips_per_impulse_limit rows (unconditionally: the branch would be unpredictable). */
    uint16_t key_start[strip_capacity + strips_per_impulse_limit - 1][key_limit + 1];
    int32_t base[strip_entry_capacity + 1]; /* the last one takes the writes of those rows */
} strip_entries;

/* Where the window of strip s starts in a texton row, given `column`, the padded column of rectangle
   column 0: in copy 0, or in copy 1 when copy 0's vector load would cross a cache line (its texel in the
   line, column mod line_texels, past line_texels - lane; copy 1 holds it lane texels later, where it does
   not). */
inline int32_t window_column(const strip_texton *texton, int32_t column, uint32_t s) {
    const uint32_t in_copy_0 = uint32_t(column) + s * lane;
    return int32_t(texton->copies == 2 && in_copy_0 % line_texels > line_texels - lane
                       ? in_copy_0 + texton->shifted + lane
                       : in_copy_0);
}

/* Files the prepared list (at most list_capacity impulses) of a rectangle `columns` x `rows` under its
   strips, sorted by key: one counting sort over (strip, key). Each impulse files at most
   strips_per_impulse_limit entries, so they fit. */
void file_strip_entries(const impulse_list *list, const strip_texton *texton, uint32_t columns, uint32_t rows,
                        strip_entries *entries) {
    uint16_t(*start)[key_limit + 1] = entries->key_start;
    const uint32_t spans = (texton->width + lane - 2) / lane + 1; /* most strips an impulse reaches */
    const uint32_t strips = (columns + lane - 1) / lane;
    /* Keys the rows look up (render_rectangle): up to rows - 1 + strip_rows - 1 + height. */
    const uint32_t keys = rows + strip_rows + texton->height - 1 < key_limit + 1
                              ? rows + strip_rows + texton->height - 1
                              : key_limit + 1;
    for (uint32_t s = 0; s < strips + spans - 1; s++)
        for (uint32_t k = 0; k < keys; k++) start[s][k] = 0;
    for (uint32_t n = 0; n < list->count; n++) {
        const listed_impulse *impulse = &list->impulses[n];
        const uint32_t key = impulse->key, first = impulse->first_strip, reached = impulse->strips;
        for (uint32_t j = 0; j < spans; j++)
            start[first + j][key] = uint16_t(start[first + j][key] + (j < reached));
    }
    /* Counts become each bucket's end; filling backwards leaves each at the bucket's start. */
    uint32_t total = 0;
    for (uint32_t s = 0; s < strips; s++)
        for (uint32_t k = 0; k < keys; k++) {
            total += start[s][k];
            start[s][k] = uint16_t(total);
        }
    for (uint32_t n = 0; n < list->count; n++) {
        const listed_impulse *impulse = &list->impulses[n];
        const uint32_t key = impulse->key, first = impulse->first_strip, reached = impulse->strips;
        /* The padded texton column of rectangle column 0, and the texton row of rectangle row 0. */
        const int32_t column = int32_t(lane) - origin(impulse->origin_x), row = -origin(impulse->origin_y);
        for (uint32_t j = 0; j < spans; j++) {
            const uint32_t valid = j < reached, position = start[first + j][key] - valid;
            start[first + j][key] = uint16_t(position);
            entries->base[valid ? position : strip_entry_capacity] =
                row * int32_t(texton->stride) + window_column(texton, column, first + j);
        }
    }
}

/* Both rows of one plane: a paired plane's from one load, an unpaired one's from two. */
inline void add_rows(const strip_texel *texels, uint32_t stride, simd_vector *row_0, simd_vector *row_1) {
#if DSN_SIMD_PAIRED_ROWS
    (void)stride;
    add_pair(load_texels(texels), row_0, row_1);
#else
    *row_0 = add_16(*row_0, load_texels(texels));
    *row_1 = add_16(*row_1, load_texels(texels + stride));
#endif
}

#if DSN_SIMD_PAIRED_ROWS
/* A paired plane's two sums finished, less `total`, the entries' bias. */
inline void finish_rows(simd_vector *row_0, simd_vector *row_1, simd_vector total) {
    finish_pair(row_0, *row_1);
    *row_0 = subtract_16(*row_0, total);
    *row_1 = subtract_16(*row_1, total);
}
#endif

/* strip_rows rows of one strip: sums[3 r + c] = the sum over `count` entries of the texton row each
   puts on row r, channel c, read from `row` (texton row 0 offset by the first rectangle row). An entry
   active on only some of the rows reads zero padding rows on the others; paired planes' sums are
   finished and their bias taken off at the end. Out of line: inlined into the row loop, the compiler
   runs out of registers and reloads in the inner loop. */
template <uint32_t Channels>
__attribute__((noinline)) void add_strip_rows(const strip_texel *row, const int32_t *base, uint32_t count,
                                              uint32_t plane, uint32_t stride, simd_vector *sums) {
    /* Named accumulators (row, channel): from an array GCC copies every sum to another register on
       every entry. */
    simd_vector sum_00 = zero_vector(), sum_01 = zero_vector(), sum_02 = zero_vector();
    simd_vector sum_10 = zero_vector(), sum_11 = zero_vector(), sum_12 = zero_vector();
    for (uint32_t i = 0; i < count; i++) {
        const strip_texel *texels = row + base[i];
        add_rows(texels, stride, &sum_00, &sum_10);
        if (Channels == 3) {
            add_rows(texels + plane, stride, &sum_01, &sum_11);
            add_rows(texels + 2 * plane, stride, &sum_02, &sum_12);
        }
    }
    /* Stored before they are finished: finished in registers, the accumulators take register copies
       on every entry. */
    sums[0] = sum_00, sums[1] = sum_01, sums[2] = sum_02, sums[3] = sum_10, sums[4] = sum_11,
    sums[5] = sum_12;
#if DSN_SIMD_PAIRED_ROWS
    const uint32_t bias = 0x80u * count & 0xFFFFu; /* each entry's, per byte, modulo 2^16 */
    const simd_vector total = set_16(int16_t(int32_t(bias ^ 0x8000u) - 0x8000));
    for (uint32_t c = 0; c < Channels; c++) finish_rows(&sums[c], &sums[3 + c], total);
#endif
}

} // namespace

#endif /* DSN_TILE_STRIPS_H */
