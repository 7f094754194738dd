/* runtime/kernels/kernels.h - the kernels: the copies of the evaluation code built for different instruction
   sets, each a struct of entry points, and the table init chooses one from (kernel_table.cpp). The bits
   are the same whichever runs. Internal to libdsn; not installed.

   Every build has the default kernel (kernel_default.cpp), built with the runtime's own flags. On
   x86-64 the Makefile also builds kernel_avx2.cpp with -mavx2 and kernel_avx512.cpp with -mavx512f
   -mavx512bw -mavx512dq -mavx512vl and defines DSN_X86_DISPATCH=1 for the whole runtime: init then records
   the last row of the table whose CPU check passes: the widest kernel this CPU (and its OS) runs, or on AMD
   Zen 4 the AVX-512 kernel with AVX2's lattice tiles of RGB noises (kernel_table.cpp says why). Built any
   other way (other CPUs, other build systems, the small build) there is the default kernel alone and no CPU
   check. Adding a kernel is one file defining its entries (dsn_internal_entries_NAME, built with its flags by
   the Makefile) and one row of the table (with its id below); adding a kind of kernel is one member of
   dsn_kernel_entries, filled by every kernel file. */
#ifndef DSN_KERNELS_H
#define DSN_KERNELS_H

#include <stdint.h>

#include "core/cell_hash.h"
#include "core/normalize_fixed.h"
#include "setup/noise_state.h"

/* DSN_KERNEL_X86_COPIES: kernel_avx2.cpp and kernel_avx512.cpp hold their kernels and the table
   offers them. */
#if defined(DSN_X86_DISPATCH) && DSN_X86_DISPATCH && defined(__x86_64__) && !DSN_SMALL_CODE
#define DSN_KERNEL_X86_COPIES 1
#else
#define DSN_KERNEL_X86_COPIES 0
#endif

/* The impulses one material of a mixed tile keeps (mix_tile.cpp, where the weights are uniform): impulse
   k of the cell with key `key` where its hash dsn_cell_stream(key, 2^31 + 2^30 + k) lies in [low, high)
   (dsn_point_materials' thresholds on each side of the material). */
typedef struct dsn_impulse_filter {
    uint64_t low, high;
} dsn_impulse_filter;

/* Whether the filter keeps impulse k of the cell with key `key`. */
static inline int dsn_filter_keeps(const dsn_impulse_filter *filter, uint32_t key, uint32_t k) {
    return static_cast<uint64_t>(dsn_material_hash(key, k)) - filter->low < filter->high - filter->low;
}

/* A whole lattice tile (tile_render.h's render_tile): `width` x `height` values of `kind` from (x0, y0)
   into out, with the 32-bit accumulator of its fallback path (out itself for fixed output); where dx is
   not null (DSN_GRADIENTS; fixed or float), the forward differences too, into dx and dy, and no
   accumulator; where `filter` is not null (DSN_MIXING; no differences), from the impulses it keeps
   alone. */
typedef void dsn_lattice_tile_entry(const dsn_noise_state *noise, uint32_t x0, uint32_t y0, uint32_t width,
                                    uint32_t height, void *out, void *dx, void *dy, dsn_output_kind kind,
                                    uint32_t *accumulator, const dsn_impulse_filter *filter);

/* A lattice tile of a mix whose weights are the same over it (mix_tile.cpp; tile_mix.h's render_mix_tile):
   `count` materials' noises (on the mix's process, each with its weighted offset), each summing the
   impulses its filter keeps, their normalized values added before they are stored, into `width` x
   `height` values of `kind`. 0 where the kernel does not take them (two materials of one channel count
   on its strip path, whose values cannot add past int32), having perhaps written part of out. */
typedef int dsn_lattice_mix_tile_entry(const dsn_noise_state *const *noises,
                                       const dsn_impulse_filter *filters, uint32_t count, uint32_t x0,
                                       uint32_t y0, uint32_t width, uint32_t height, void *out,
                                       dsn_output_kind kind);

/* Whether the kernel's strip path holds the texton of `noise` (tile_render.h's lattice_strips_take): its
   lattice tiles then take that path, unless the noise is too dense for any rectangle (32-bit path). */
typedef int dsn_lattice_strips_take_entry(const dsn_noise_state *noise);

/* The materials of a mixed point (mix_point.cpp): `count` textons (lattice ones for a lattice point) of
   the same window, channels and bits (the walk's texton gives those), each impulse of the lead noise's
   process adding its material's. Impulse k of the cell with key `key` has the material hash
   dsn_cell_stream(key, 2^31 + 2^30 + k). Where `pick` is null every impulse's weights are the same, and an
   impulse takes the number of thresholds[0 .. 2] at or below its hash (mix_weights.h's pick_material by
   draw_threshold: the hashes that draw material m or a later one are those at or above thresholds[m - 1];
   2^32, above every hash, past count - 1); else pick(context, hash, x, y) gives the material of the
   impulse of that hash whose position's integer parts are (x, y) (modulo 2^32), and where `control` is
   not null (DSN_MIXING) the AVX2 and AVX-512 copies' continuous and lattice points may read the materials
   from it instead (the mix's weights, whose pick that is: mix_pick_lanes.h). */
struct dsn_mix_control;
enum { dsn_point_materials_most = 4 }; /* DSN_MIX_MAX_MATERIALS, in builds without the mix too */
typedef struct dsn_point_materials {
    uint32_t count;
    const unsigned char *values[dsn_point_materials_most];
    uint64_t thresholds[dsn_point_materials_most - 1];
    uint32_t (*pick)(const void *context, uint32_t hash, uint32_t x, uint32_t y);
    const void *context;
    const struct dsn_mix_control *control;
} dsn_point_materials;

/* A lattice point (lattice_point_walk.h's lattice_point_sums): the sums, modulo 2^32, of the texton values
   of every impulse that reaches (x, y) and, where `points` is 3, (x + 1, y) and (x, y + 1) too (sums +
   3 p); where `materials` is not null (with `points` 1), each material's at sums + 3 m instead. 0 (writing
   nothing) for a noise the kernel's walk does not take (point.cpp and mix_point.cpp walk it then). */
typedef int dsn_lattice_point_entry(const dsn_noise_state *noise, const dsn_texton_window *texton, uint32_t x,
                                    uint32_t y, uint32_t points, uint32_t *sums,
                                    const dsn_point_materials *materials);

/* A batch of continuous points (continuous_batch.h's continuous_batch): `count` points (xs[k], ys[k]),
   Q32.32, into out[k * channels], reading the texton from `quads` (continuous_batch.h's 2 x 2 texel
   table, built by continuous_batch.cpp) and using `work` (batch_work_bytes bytes, 64-byte aligned).
   Where dx is not null (DSN_GRADIENTS), the gradient instead: the values, x and y derivatives of
   dsn_internal_continuous_gradient into out, dx and dy, with neither quads nor work (both null). */
typedef void dsn_continuous_batch_entry(const dsn_noise_state *noise, const uint32_t *quads,
                                        const int64_t *xs, const int64_t *ys, uint32_t count, int32_t *out,
                                        int32_t *dx, int32_t *dy, void *work);

/* The runs of pixels one impulse of the grid splat reaches (grid_splat.cpp), one per row
   of a block: the offsets (pixel - impulse) of the run's first pixel, all `count` pixels within reach,
   and where its channel-0 sums start (channel c at sums[c * plane]). A call has dsn_splat_runs_most runs
   at most (a block's rows), each of dsn_splat_run_longest pixels at most (a block's columns). */
enum { dsn_splat_runs_most = 32, dsn_splat_run_longest = 64 };
typedef struct dsn_splat_run {
    int64_t offset_x, offset_y;
    uint64_t *sums;
    uint32_t count;
} dsn_splat_run;

/* What the grid splat reads: the texton, or a level of its pyramid (the filtered tile): the window of
   width x height texels (`channels` values of `bits` bits each) from `values`, rows `stride` texels apart.
   An offset (pixel - impulse) is divided by 2^level, rounded down, before it is read, as the filtered
   walk reads a level (filtered_walk.cpp's add_level); level 0 reads it as it is. */
typedef struct dsn_splat_texture {
    const unsigned char *values;
    uint32_t width, height, stride, channels, bits, level;
} dsn_splat_texture;

/* What every run of a grid shares: the texture, the steps (pixel to next pixel) and reaches of both axes
   (an impulse reaches the offsets in (-reach, reach): (radius + 1) 2^(32 + level), the radius the
   texture's), the distance between channel planes, and the texture's bilinear cells (splat_cells.h) or 0
   where the runs go pixel by pixel (16-bit textons, cells too large for the stack). */
typedef struct dsn_splat_setup {
    dsn_splat_texture texture;
    int64_t step_x, step_y, reach_x, reach_y;
    size_t plane;
    const uint64_t *sums_end; /* the runs' sums lie before; vectors may add 0 to any sum up to there */
    const uint64_t *cells;
    uint32_t cell_row; /* cells per row of the table */
    /* Nonzero for axis-aligned grids (the steps along a row move x alone, those to the next row y alone):
       the runs of a call then start at the same offset_x, have the same count and a constant offset_y. */
    int columns_shared;
} dsn_splat_setup;

/* The innermost loops of the continuous grid splat (splat_row.h's continuous_splat_runs): one impulse
   added to its runs. */
typedef void dsn_splat_runs_entry(const dsn_splat_setup *setup, const dsn_splat_run *runs,
                                  uint32_t run_count);

/* continuous_gradient_runs (splat_row.h's splat_add_slopes): the same runs of a texture with records
   (setup.cells), adding the value and both slopes in one pass: a run's value planes at run.sums, its
   slopes along x and y (bilinear_texton.h's add_slopes, per 2^-16 texel of the texture's level) `channels`
   and 2 `channels` planes after them, each set of planes ending `channels` planes after the last
   (setup.sums_end is the values'). */

/* The normalization of the continuous grid splat's sums (splat_row.h's continuous_splat_normalize):
   `count` pixels, channel c of pixel p at sums[c * plane + p], into out[p * channels + c] as
   normalize_q32_unmapped gives them (continuous_internal.h). */
typedef void dsn_splat_normalize_entry(const dsn_noise_state *noise, const uint64_t *sums, size_t plane,
                                       uint32_t count, int32_t *out);

/* One continuous point (continuous_point_sift.h's continuous_point_entry; the x86 copies' vector
   evaluator first, continuous_point_vector.h): the raw sums of the point (x, y), Q32.32, per channel
   modulo 2^64, into value (what dsn_internal_continuous_point normalizes), and where slope_x is not null
   (DSN_GRADIENTS) the derivative's sums too, value, slope_x and slope_y as dsn_internal_continuous_slopes
   gives them (continuous_internal.h); returns 1 (continuous_point_sums, the vector evaluator alone,
   returns 0, writing nothing, for a noise it does not take). Where materials is not null (a mix's point,
   slope_x null, its weights uniform: no pick), each material's sums at value + 3 m instead, from the
   AVX-512 copy's vector evaluator; 0, writing nothing, wherever that does not take them. */
typedef int dsn_continuous_point_entry(const dsn_noise_state *noise, uint64_t x, uint64_t y, uint64_t *value,
                                       uint64_t *slope_x, uint64_t *slope_y,
                                       const dsn_point_materials *materials);

/* The reads of one tap and one 8-bit level of the filtered sift (filtered_reads_vector.h's
   filter_level_reads): of the `count` candidates (xs[i], ys[i]) those the level's tests tests[0 .. 3] (start
   and limit along x, then along y: filtered_sift.cpp's LevelTest) keep, their bilinear reads of `level`
   (`channels` 8-bit values a texel) at the offsets (c + start + tests[4]) >> level added to
   out[0 .. channels - 1] modulo 2^64; where slopes is not null, their slopes (the gradient's) to
   slopes[0] (x) and slopes[1] (y) too. Where narrow_xs is not null the candidates are read from
   narrow_xs, narrow_ys instead (their offsets / 2^16 modulo 2^32, as filter_candidates lists them) with
   narrow_tests[0 .. 5] (filtered_sift.cpp's narrow_test along x, then along y). */
struct dsn_walked_level;
typedef void dsn_filter_level_reads_entry(const struct dsn_walked_level *level, uint32_t channels,
                                          const int64_t *xs, const int64_t *ys, const uint32_t *narrow_xs,
                                          const uint32_t *narrow_ys, uint32_t count, const uint64_t *tests,
                                          const uint32_t *narrow_tests, uint64_t *out,
                                          uint64_t (*slopes)[DSN_MAX_CHANNELS]);

/* One axis of one cell as the sifts see it: continuous_sift.h's CellAxis, which documents it. One cell
   of the filtered sift's box (filtered_sift.cpp): its key, its impulse count and both axes. */
typedef struct dsn_filter_cell_axis {
    int64_t shifted_base;
    uint64_t low_lanes, high_lanes;
} dsn_filter_cell_axis;
typedef struct dsn_filter_cell {
    uint32_t key, count;
    dsn_filter_cell_axis x, y;
} dsn_filter_cell;

/* A list of the filtered sift's candidates as the listing fills it: `count` of them so far, their shifted
   offsets (CellAxis's shifted_base less the 16-bit position's) at xs, ys (null: not written), the same
   offsets / 2^16 modulo 2^32 at narrow_xs, narrow_ys, and each listed cell's end in it at ends. */
typedef struct dsn_filter_list {
    uint32_t count;
    int64_t *xs, *ys;
    uint32_t *narrow_xs, *narrow_ys, *ends;
} dsn_filter_list;

/* The candidates of the filtered sift (filtered_candidates_vector.h's filter_candidates), for cells of
   side 2^cell_shift <= 16: the impulses of `cell_count` cells whose lattice fields let them reach the
   box, cell by cell, appended to `kept` (each cell's end at kept->ends[0 .. cell_count - 1]). Where `filter`
   is not null (DSN_MIXING: a mix whose weights are uniform) only the impulses it keeps go to `kept`, and
   where `rest` is not null too (a mix of two materials) the others go to `rest`, listed alike. Writes up to
   16 values past a list's last candidate: the caller leaves room for the sum of the cells' counts plus
   16 in each. Returns kept's new count (also in kept->count). */
typedef uint32_t dsn_filter_candidates_entry(const dsn_filter_cell *cells, uint32_t cell_count,
                                             uint32_t cell_shift, dsn_filter_list *kept,
                                             dsn_filter_list *rest, const dsn_impulse_filter *filter);

/* One cube of the surface walk (core/surface_walk.h's visit_cube), as the surface kernel reads it: its key
   and the impulses first .. first + count - 1 of it (count <= dsn_surface_impulses_most), the offsets of
   the cube's origin from the point along the frame's tangent, bitangent and normal (Q.46, origin_dot), the
   frame (Q2.30), and the reaches (Q32.32) beyond which the caller reads nothing along the tangent and
   bitangent (reach_u, reach_v; an impulse whose floored offset u has |u| >= reach_u is left out) and across
   the slab (reach_across: likewise, the offset across the plane floored to Q32.32). */
/* 16: a cube holds 8 impulses at the usual mean, rarely more than 16; the list is on the point's stack. */
enum { dsn_surface_impulses_most = 16 };
typedef struct dsn_surface_cube {
    int64_t origin_dot[3];
    int32_t frame[3][3];
    int64_t reach_u, reach_v, reach_across;
    uint32_t key, first, count, cell_shift;
} dsn_surface_cube;
/* The impulses a surface kernel keeps, in index order: their offsets from the point along the tangent,
   the bitangent and the normal, Q.46, exact (surface_walk.h says how); the offset that the reaches test
   and the reads read is this floored to Q32.32, after a filtered point's tap adds its move. */
typedef struct dsn_surface_impulses {
    int64_t along_tangent[dsn_surface_impulses_most], along_bitangent[dsn_surface_impulses_most],
        across[dsn_surface_impulses_most];
} dsn_surface_impulses;

/* The impulses of one cube of the surface walk (surface_impulses.h's surface_impulses) within the cube's
   reaches, into out; returns how many. */
typedef uint32_t dsn_surface_impulses_entry(const dsn_surface_cube *cube, dsn_surface_impulses *out);

/* A window of 8-bit texels as the surface reads take it (surface_impulses.h's surface_reads): the
   texton, or a pyramid level's walked window (filtered_internal.h's dsn_walked_level), `channels` values a
   texel, its rows `stride` texels apart, its radius (width - 1) / 2 texels along the tangent and
   (height - 1) / 2 along the bitangent. An offset is divided by 2^level, rounded down, before it is read.
   The reads may touch the 4 bytes before the window's first texel and the 4 past its last: in the asset's
   buffer, which has its header before any texel and its CRC after (format.h). */
typedef struct dsn_surface_texels {
    const unsigned char *values;
    uint32_t width, height, stride, channels, level;
} dsn_surface_texels;

/* The surface point's reads of `count` listed impulses (surface_impulses.h's surface_reads), each within
   3/4 of a cube across: the bilinear read of `texels` at its offsets along the tangent and bitangent (0
   beyond the window's reach), times the slab's window at its offset across (core/surface_walk.h's
   slab_window and windowed), added to sums[0 .. channels - 1] modulo 2^64: the unfiltered point's texton
   reads, and the filtered point's level reads (core/level_read.h's add_level, windowed). Each impulse's
   three offsets are first moved by moved[0 .. 2] (Q.46: a filtered point's tap, else 0) and floored to
   Q32.32. */
typedef void dsn_surface_reads_entry(const dsn_surface_texels *texels, const dsn_surface_impulses *listed,
                                     uint32_t count, uint32_t cell_shift, const int64_t *moved,
                                     uint64_t *sums);

/* Rows of a lattice texton added to rows of 32-bit sums, modulo 2^32 (tile_walk.h's add_texton_rows): `rows`
   rows of `count` values of `bits` bits (8 or 16) from `values`, rows `stride` bytes apart, to as many rows
   of sums from `sums`, rows sums_stride values apart. One impulse of a mixed lattice band (mix_point.cpp's
   lattice_window_sums). */
typedef void dsn_lattice_rows_entry(const unsigned char *values, size_t stride, uint32_t bits, uint32_t rows,
                                    uint32_t count, uint32_t *sums, size_t sums_stride);

/* The materials of n impulses of a mix whose weights vary, as mix_weights.h's hashed_material picks them
   (mix_weights_at and pick_material at their integer positions, 8 at a time: mix_pick_lanes.h's
   pick_materials): impulse i's material hash hashes[i] and integer position (x[i], y[i]), each within
   reach_x and reach_y texels of (whole_x, whole_y), its material into materials[i]. Returns 0, writing
   nothing, where the lanes do not read the control around that point (pick_window). One tap of a mixed
   filtered point (mix_filtered.cpp's materials_sums). */
typedef int dsn_mix_picks_entry(const struct dsn_mix_control *control, uint32_t count, uint32_t whole_x,
                                uint32_t whole_y, uint32_t reach_x, uint32_t reach_y, const uint32_t *hashes,
                                const uint32_t *x, const uint32_t *y, uint32_t n, uint32_t *materials);

/* What one kernel computes: one member per kind of kernel. continuous_batch is null where the batch
   functions are compiled out (DSN_CONTINUOUS_BATCH 0, dsn.h); continuous_splat_runs,
   continuous_splat_normalize, lattice_point and continuous_point in the small build (DSN_SMALL_CODE),
   which evaluates grids point by point and whose point.cpp and continuous_point.cpp walk the cells
   themselves; lattice_point without SSE2 too; filter_level_reads and filter_candidates in kernels built
   without AVX2 (filtered_sift.cpp then reads, or lists, each candidate itself), and
   continuous_gradient_runs too (continuous_tile.cpp then splats three grids); surface_impulses and
   surface_reads without the surface noise (DSN_SURFACE 0), surface_reads in kernels built without
   AVX2 too; lattice_mix_tile without the mix (DSN_MIXING 0) or the strip path (tile_render.h);
   lattice_rows without the mix; mix_picks without the mix or AVX2. */
typedef struct dsn_kernel_entries {
    dsn_lattice_tile_entry *lattice_tile;
    dsn_lattice_strips_take_entry *lattice_strips_take;
    dsn_lattice_point_entry *lattice_point;
    dsn_continuous_batch_entry *continuous_batch;
    dsn_splat_runs_entry *continuous_splat_runs;
    dsn_splat_runs_entry *continuous_gradient_runs;
    dsn_splat_normalize_entry *continuous_splat_normalize;
    dsn_continuous_point_entry *continuous_point;
    dsn_filter_level_reads_entry *filter_level_reads;
    dsn_filter_candidates_entry *filter_candidates;
    dsn_surface_impulses_entry *surface_impulses;
    dsn_surface_reads_entry *surface_reads;
    dsn_lattice_mix_tile_entry *lattice_mix_tile;
    dsn_lattice_rows_entry *lattice_rows;
    dsn_mix_picks_entry *mix_picks;
} dsn_kernel_entries;

/* Values of dsn_noise_state.tile_kernel: a kernel's id is its row in the table. The rows go from the
   narrowest to the widest instruction set, each CPU that runs a row running those before it too. */
typedef enum dsn_kernel_id {
    DSN_KERNEL_DEFAULT, /* the copy built with the runtime's own flags */
    DSN_KERNEL_AVX2,
    DSN_KERNEL_AVX512,           /* AVX-512 F and BW */
    DSN_KERNEL_AVX512_AVX2_TILES /* AVX-512's, but RGB lattice tiles AVX2's where its strips take them */
} dsn_kernel_id;

typedef struct dsn_kernel {
    dsn_kernel_id id;
    const char *name;
    int (*cpu_runs)(void); /* whether this CPU and its OS run the kernel; 0: every CPU the build targets */
    const dsn_kernel_entries *entries;
} dsn_kernel;

/* The table: dsn_internal_kernel_count rows (1 without the x86 copies). */
extern const dsn_kernel dsn_internal_kernels[];
extern const uint32_t dsn_internal_kernel_count;

/* The id of the last row whose CPU check passes (init records it in tile_kernel). */
uint32_t dsn_internal_choose_kernel(void);

/* The entries of kernel `id` (the default kernel's for an id outside the table). */
static inline const dsn_kernel_entries *dsn_kernel_entries_of(uint32_t id) {
    return dsn_internal_kernels[id < dsn_internal_kernel_count ? id : 0u].entries;
}

#endif /* DSN_KERNELS_H */
