/* runtime/kernels/tile_render.h - a whole tile on the lattice, computed in this translation unit: the tile is
   cut into runs of contiguous coordinates (tile_walk.h), each run into rectangles; a rectangle's
   impulses are summed strip by strip in 16-bit registers (tile_strips.h) and normalized straight into
   the output (tile_normalize.h), or, when 16 bits cannot hold the sums (16-bit textons, large textons,
   extreme densities), splatted into a 32-bit accumulator and normalized one pixel at a time. Either way the
   sums are the per-point sums (integer addition modulo 2^32 is order-free, and the 16-bit sums provably never
   wrap), so the bits equal the per-point path's. Included by every kernel file (kernel_default.cpp, and
   on x86-64 kernel_avx2.cpp and kernel_avx512.cpp), each building it for its instruction set
   (everything here has internal linkage, so the copies never mix). */
#ifndef DSN_TILE_RENDER_H
#define DSN_TILE_RENDER_H

/* The strip path (x86: SSE2, AVX2 or AVX-512, simd.h) keeps tens of kilobytes on the stack (two padded
   copies of the texton, the impulse list and the strip entries); elsewhere the 32-bit path keeps a tile
   call's stack small, which microcontrollers need. Both give the same bits. Define DSN_TILE_BLOCKS to 0 to
   take the 32-bit path on x86 too. */
#include "simd/simd.h"
#if !DSN_SIMD
#undef DSN_TILE_BLOCKS
#define DSN_TILE_BLOCKS 0
#elif !defined(DSN_TILE_BLOCKS)
#define DSN_TILE_BLOCKS 1
#endif

#include "core/normalize_fixed.h"
#include "kernels/tile_walk.h"
#if DSN_TILE_BLOCKS
#include "kernels/tile_normalize.h"
#endif

namespace {

/* The 32-bit path converts pixel by pixel (dsn_store_pixel) rather than with one copy of the tile code
   per output type; the strip path, whose inner loops are the sums and their normalization, keeps one copy
   per type and channel count, chosen once per tile. */

#if DSN_TILE_BLOCKS
/* Outputs of this many bytes or more are written past the caches: a 16 MB tile would only evict what
   the caller has cached, and writing past them saves reading each line before it is written. */
const uint64_t stream_bytes = uint64_t(16) << 20;

/* Everything a tile call prepares once for the strip path. */
typedef struct strip_setup {
    strip_texton texton;
    rectangle_size rectangle;
    int split_ok;
    int stream; /* output far larger than the caches: written past them (put_4, stream_row) */
    split_vectors split;
} strip_setup;

/* The second copy of the texton is built only when it fits and the tile is large enough to pay for it
   (it saves a little on every pixel and costs a fixed amount per tile). */
void make_strip_setup(const dsn_noise_state *noise, rectangle_size rectangle, uint64_t pixels,
                      uint32_t value_bytes, strip_setup *setup) {
    const uint32_t copies = strip_texton_copies(&noise->asset) == 2 && pixels >= 4096 ? 2u : 1u;
    make_strip_texton(&noise->asset, copies, &setup->texton);
    setup->rectangle = rectangle;
    setup->stream = pixels * noise->asset.channels * value_bytes >= stream_bytes;
    split_normalization split;
    setup->split_ok = make_split_normalization(noise, &split);
    if (setup->split_ok) make_split_vectors(&split, noise->asset.channels, &setup->split);
}
#endif /* DSN_TILE_BLOCKS */

/* Where a tile's values go: `out` (width * channels values of type `kind` per row) and the 32-bit
   accumulator of the fallback (`out` itself for fixed output, else the scratch); and which impulses it
   sums (every one where `filter` is null). */
typedef struct tile_target {
    void *out;
    dsn_output_kind kind;
    uint32_t *accumulator;
    uint32_t row_values;
    const dsn_impulse_filter *filter;
} tile_target;

/* The 32-bit path for a rectangle of single runs (a rectangle with too many impulses, or a whole run
   when the texton does not fit the strip path): 32-bit sums in the tile accumulator, then each pixel. */
void render_rectangle_32(const dsn_noise_state *noise, const tile_run *rectangle_x,
                         const tile_run *rectangle_y, const tile_target *target) {
    const uint32_t channels = noise->asset.channels, row_values = target->row_values;
    for (uint32_t row = 0; row < rectangle_y->length; row++) {
        uint32_t *sums = target->accumulator + size_t(rectangle_y->offset + row) * row_values +
                         rectangle_x->offset * channels;
        for (uint32_t i = 0; i < rectangle_x->length * channels; i++) sums[i] = 0;
    }
    splat_region(noise, rectangle_x, rectangle_y, target->accumulator, row_values, target->filter);
    for (uint32_t row = 0; row < rectangle_y->length; row++) {
        size_t first = size_t(rectangle_y->offset + row) * row_values + rectangle_x->offset * channels;
        for (uint32_t i = 0; i < rectangle_x->length; i++) {
            const uint32_t *pixel = target->accumulator + first + i * channels;
            uint32_t sums[3] = {pixel[0], channels == 3 ? pixel[1] : 0u, channels == 3 ? pixel[2] : 0u};
            int32_t fixed[3];
            dsn_normalize(noise, sums, fixed); /* sums are copied first: fixed output may overwrite them */
            dsn_store_pixel(target->out, target->kind, first + i * channels, fixed, channels);
        }
    }
}

#if DSN_TILE_BLOCKS
/* One row of a rectangle from its strips' sums (3 vectors per strip) into `row_out`, its first pixel. */
template <uint32_t Channels, typename Value>
void normalize_row(const dsn_noise_state *noise, const strip_setup *setup,
                   simd_vector (*sums)[3 * strip_rows], uint32_t row, uint32_t width, Value *row_out) {
    Value *out = row_out;
    int stream = setup->stream;
#if DSN_SIMD_STREAM_LINES
    /* A streamed row is normalized into `stage` at the same offset in a cache line, then copied in whole
       lines (stream_row). The stores into the stage are as misaligned as the row, and a store that
       crosses a page costs far more than one that crosses a cache line: 2048-byte alignment keeps the
       stage (at most 1600 bytes) within one page. */
    alignas(2048) Value stage[rectangle_width * Channels + 64 / sizeof(Value)];
    static_assert(sizeof(stage) <= 2048, "the stage must fit its alignment to stay within a page");
    const uintptr_t address = reinterpret_cast<uintptr_t>(row_out);
    const int staged = stream && sizeof(Value) == sizeof(int32_t) && address % sizeof(Value) == 0;
    if (staged) out = stage + (address & 63u) / sizeof(Value);
    stream = 0;
#endif
    for (uint32_t s = 0; s * lane < width; s++) {
        const uint32_t pixels = width - s * lane < lane ? width - s * lane : lane;
        const simd_vector *strip = sums[s] + 3 * row;
#if DSN_HISTOGRAM
        if (setup->split_ok && noise->asset.histogram_table != 0) { /* lanes, then the mapping */
            int32_t fixed[lane * Channels];
            normalize_strip<Channels>(&setup->split, strip, pixels, fixed, 0);
            map_pixels<Channels>(noise, fixed, pixels, out + s * lane * Channels);
            continue;
        }
#endif
        if (setup->split_ok)
            normalize_strip<Channels>(&setup->split, strip, pixels, out + s * lane * Channels, stream);
        else
            normalize_strip_scalar(noise, strip, pixels, out + s * lane * Channels);
    }
#if DSN_SIMD_STREAM_LINES
    if (staged) stream_row(out, width * Channels, row_out);
#endif
}

/* A rectangle of the tile, setup->rectangle at most: its impulses are listed and filed
   under the strips once, then strip_rows rows at a time are summed strip by strip and normalized. */
template <uint32_t Channels, typename Value>
void render_rectangle(const dsn_noise_state *noise, const strip_setup *setup, const tile_run *walk_x,
                      const tile_run *walk_y, const tile_target *target) {
    impulse_list list;
    list.clear(walk_x->length, walk_y->length);
    for_each_kept_impulse(noise, walk_x, walk_y, list, target->filter);
    if (!list.prepare(setup->texton.width, setup->texton.height)) {
        render_rectangle_32(noise, walk_x, walk_y, target);
        return;
    }
    strip_entries entries;
    file_strip_entries(&list, &setup->texton, walk_x->length, walk_y->length, &entries);
    const strip_texton *texton = &setup->texton;
    const strip_texel *row_zero = texton->values + (strip_rows - 1) * texton->stride; /* after the padding */
    for (uint32_t y = 0; y < walk_y->length; y += strip_rows) {
        /* Entries active on rows y .. y + strip_rows - 1: keys y .. y + strip_rows - 2 + height. */
        const uint32_t last_key_end = y + strip_rows - 1 + texton->height;
        simd_vector sums[strip_count][3 * strip_rows];
        for (uint32_t s = 0; s * lane < walk_x->length; s++) {
            const uint32_t first = entries.key_start[s][y], end = entries.key_start[s][last_key_end];
            add_strip_rows<Channels>(row_zero + y * texton->stride, entries.base + first, end - first,
                                     texton->plane, texton->stride, sums[s]);
        }
        for (uint32_t r = 0; r < strip_rows && y + r < walk_y->length; r++) {
            Value *out = static_cast<Value *>(target->out) +
                         size_t(walk_y->offset + y + r) * target->row_values + walk_x->offset * Channels;
            normalize_row<Channels>(noise, setup, sums, r, walk_x->length, out);
        }
    }
}

/* One rectangle of the tile where both axes are single runs, in rectangles of setup->rectangle. */
template <uint32_t Channels, typename Value>
void render_region(const dsn_noise_state *noise, const strip_setup *setup, const tile_run *run_x,
                   const tile_run *run_y, const tile_target *target) {
    const uint32_t width = setup->rectangle.width, height = setup->rectangle.height;
    for (uint32_t y = 0; y < run_y->length; y += height) {
        tile_run walk_y = {run_y->start + y, run_y->offset + y,
                           run_y->length - y < height ? run_y->length - y : height};
        for (uint32_t x = 0; x < run_x->length; x += width) {
            tile_run walk_x = {run_x->start + x, run_x->offset + x,
                               run_x->length - x < width ? run_x->length - x : width};
            render_rectangle<Channels, Value>(noise, setup, &walk_x, &walk_y, target);
        }
    }
}

/* The whole tile in rectangles, with the copy of the strip path for the output type and channels. */
template <typename Value>
void render_strip_tile(const dsn_noise_state *noise, rectangle_size rectangle, const tile_run *runs_x,
                       uint32_t run_count_x, const tile_run *runs_y, uint32_t run_count_y, uint64_t pixels,
                       const tile_target *target) {
    strip_setup setup;
    make_strip_setup(noise, rectangle, pixels, sizeof(Value), &setup);
    for (uint32_t ry = 0; ry < run_count_y; ry++)
        for (uint32_t rx = 0; rx < run_count_x; rx++) {
            if (noise->asset.channels == 3)
                render_region<3, Value>(noise, &setup, &runs_x[rx], &runs_y[ry], target);
            else
                render_region<1, Value>(noise, &setup, &runs_x[rx], &runs_y[ry], target);
        }
    if (setup.stream) store_fence(); /* the streamed stores are ordered before whatever follows */
}
#endif /* DSN_TILE_BLOCKS */

/* Whether the strip path holds the noise's texton (render_tile takes it when a rectangle exists too). */
int lattice_strips_take(const dsn_noise_state *noise) {
#if DSN_TILE_BLOCKS
    return strip_texton_copies(&noise->asset) != 0;
#else
    (void)noise;
    return 0;
#endif
}

#if DSN_GRADIENTS
void render_gradient_tile(const dsn_noise_state *noise, uint32_t x0, uint32_t y0, uint32_t width,
                          uint32_t height, void *out, void *dx, void *dy, dsn_output_kind kind);
#endif

/* The whole tile (the lattice kernel entry, kernels.h): strips of 16-bit sums when the texton allows, else
   32-bit sums run by run; with its differences (tile_gradient.h) where dx is not null; from the impulses
   `filter` keeps where it is not null. */
void render_tile(const dsn_noise_state *noise, uint32_t x0, uint32_t y0, uint32_t width, uint32_t height,
                 void *out, void *dx, void *dy, dsn_output_kind kind, uint32_t *accumulator,
                 const dsn_impulse_filter *filter) {
#if DSN_GRADIENTS
    if (dx != 0) {
        render_gradient_tile(noise, x0, y0, width, height, out, dx, dy, kind);
        return;
    }
#else
    (void)dx, (void)dy;
#endif
    tile_run runs_x[2], runs_y[2];
    uint32_t run_count_x = split_runs(x0, width, noise->period[0], runs_x);
    uint32_t run_count_y = split_runs(y0, height, noise->period[1], runs_y);
    tile_target target = {out, kind, accumulator, width * noise->asset.channels, filter};
#if DSN_TILE_BLOCKS
    /* A single point takes the 32-bit path: no padded copy of the texton for one pixel. */
    const uint64_t pixels = uint64_t(width) * height;
    const rectangle_size rectangle =
        pixels > 1 && lattice_strips_take(noise) ? choose_rectangle(noise) : rectangle_size{0, 0};
    if (rectangle.width != 0) {
        if (kind == dsn_output_float)
            render_strip_tile<float>(noise, rectangle, runs_x, run_count_x, runs_y, run_count_y, pixels,
                                     &target);
        else if (kind == dsn_output_u8)
            render_strip_tile<uint8_t>(noise, rectangle, runs_x, run_count_x, runs_y, run_count_y, pixels,
                                       &target);
        else
            render_strip_tile<int32_t>(noise, rectangle, runs_x, run_count_x, runs_y, run_count_y, pixels,
                                       &target);
        return;
    }
#endif
    for (uint32_t ry = 0; ry < run_count_y; ry++)
        for (uint32_t rx = 0; rx < run_count_x; rx++)
            render_rectangle_32(noise, &runs_x[rx], &runs_y[ry], &target);
}

} // namespace

#include "kernels/tile_gradient.h"
#include "kernels/tile_mix.h"

#endif /* DSN_TILE_RENDER_H */
