/* dsn/dsn.h - discrete spot noise runtime: load a .dsnt asset, evaluate the noise per point or per tile.

   What it does
     Evaluates, at any point of the plane, a Gaussian-looking texture defined by a small texton (spot)
     baked offline by dsn-bake: F(x) = sum_i t(x - x_i) over a Poisson point process, normalized and
     colour-transformed (the formula is in dsn/format.h). The impulses are not stored anywhere: they are
     recomputed on demand from a stateless hash of (cell, seed, impulse index). Two modes: the lattice
     mode at integer points (the texton as baked, for textures drawn pixel for texel) and the continuous
     mode at real-valued points (the texton read bilinearly, for renderers that zoom, rotate and warp).

   What it guarantees
     - Same asset bytes + same configuration + same point = same output bits, on every compiler, CPU,
       endianness and optimization level. The evaluation path is integer-only; float output is a final
       conversion of the fixed-point value.
     - Per-point and tile evaluation give identical bits.
     - No heap, no libm, no exceptions, no global mutable state: every function is reentrant, and a
       configured dsn_noise may be shared read-only between threads.
     - Every input has a defined result: every int32 coordinate (the lattice is the 2^32 x 2^32 torus,
       so a window may straddle the 32-bit wrap), every float coordinate (NaN and infinities included),
       every seed, every period; invalid arguments return a negative dsn_error code (dsn/format.h lists
       them all), never undefined behaviour.
     - On any error every evaluator's output is zeroed, never left undefined: every channel of a
       configured noise, out[0] alone where the noise is null or not configured (its channel count is
       unknown), and a tile's or batch's whole output (width * height or count points, of its channels or
       of one value each), never beyond it; a tile refused for its size (DSN_ERR_TILE_SIZE) is left as it
       is. The lattice per-point functions return no code: a null or unconfigured noise gives out[0] = 0.
     - The loader validates the asset in place and keeps pointers into the caller's buffer: the buffer
       must outlive the dsn_asset and every dsn_noise made from it.

   How to call it
     The float path: one call to load, one per sample (x, y in texels, any float; colour in float, about
     0 .. 1 for a texture baked from an 8-bit image).
       dsn_noise noise;
       float rgb[DSN_MAX_CHANNELS];
       int err = dsn_noise_load(&noise, bytes, size, 1234);     (bytes: the .dsnt file, kept alive)
       if (err != DSN_OK) { puts(dsn_error_message(err)); return; }
       dsn_sample(&noise, x, y, rgb);                           (dsn_noise_channels(&noise) values)

     The fixed-point lattice path, with every option: load the asset, configure, evaluate.
       dsn_asset asset;
       dsn_noise noise;
       dsn_config config;
       int32_t rgb[DSN_MAX_CHANNELS];
       int err = dsn_asset_load(&asset, bytes, size);
       if (err != DSN_OK) { puts(dsn_error_message(err)); return; }
       dsn_config_defaults(&config);                            (seed 0, asset density, no period)
       config.seed = 1234;
       err = dsn_noise_init(&noise, &asset, &config);
       if (err != DSN_OK) { puts(dsn_error_message(err)); return; }
       dsn_lattice_point_fixed(&noise, x, y, rgb);              (Q16.16: 65536 is intensity 1.0)

   Fixed-point output: channel values are int32 Q16.16 (DSN_ONE = 1.0, the exemplar's white), saturated
   to the int32 range. Grey assets fill one value, RGB assets three.

   Configuration: macros read when the runtime itself is compiled (defining them in a program that only
   includes this header changes nothing). Every choice gives the same bits; they trade speed for code
   size, stack or portability.

     DSN_SMALL_CODE     default: 1 when built for size (-Os, which defines __OPTIMIZE_SIZE__), else 0.
                        1 compiles generic, compact code paths instead of the speed-tuned ones: one
                        bilinear texton reader for 8 and 16 bits, continuous grid tiles evaluated point by
                        point, a lattice point evaluated as a 1 x 1 tile, no code copied per output type.
                        The runtime of this header then takes under 8 KB of Cortex-M0 or M4 code
                        (tests/cross/footprint checks it), and dsn_continuous_tile_scratch_size returns 0:
                        continuous tiles need no scratch.
     DSN_FILTERING      default: 1, but 0 when DSN_SMALL_CODE is 1. 0 leaves the filtered evaluation out
                        (the section "Filtered evaluation" below): its functions and dsn_asset_level are
                        not compiled, so a program that calls them fails to link, and the loader does not
                        read a 1.1 asset's sections (its pyramid is then neither checked nor used, so such
                        a build accepts an asset whose pyramid a full build rejects). That keeps the small
                        build under its 8 KB.
     DSN_HISTOGRAM      default: 1, but 0 when DSN_SMALL_CODE is 1. 0 leaves the histogram-preserving
                        output of format 1.2 out (the section "Histogram-preserving output" below): the
                        loader then answers DSN_ERR_UNSUPPORTED for an asset that needs it (format.h,
                        step 8) and does not check its section, and no evaluation applies a mapping.
                        That keeps the small build under its 8 KB. 1 with DSN_FILTERING 0 reads the
                        sections (and so checks a 1.1 asset's pyramid) to find the mapping.
     DSN_GRADIENTS      default: 1, but 0 when DSN_SMALL_CODE is 1. 0 leaves the gradient functions out
                        (the section "Gradients" below): a program that calls them fails to link.
     DSN_MIXING         default: 1, but 0 when DSN_SMALL_CODE is 1. 0 leaves the mixing of materials out
                        (the section "Mixing" below): a program that calls it fails to link. It needs a
                        build that reads sections (DSN_FILTERING or DSN_HISTOGRAM).
     DSN_SURFACE        default: 1, but 0 when DSN_SMALL_CODE is 1. 0 leaves the surface noise out (the
                        section "Surface noise" below): a program that calls it fails to link.
     DSN_TILE_BLOCKS    default: 1 where SSE2 is available (x86), else 0 (forced to 0 without SSE2).
                        1 lets lattice tiles sum their impulses in 16-bit vector strips, which keeps
                        copies of the texton and the impulse list on the stack: 62-80 KB per tile call
                        by the copy of the tile code (make bench's runtime_bench). 0 takes the
                        32-bit accumulator path, under 1 KB of stack per tile call, slower.
     DSN_X86_DISPATCH   default: undefined (0); the Makefile defines it to 1 on x86-64. 1 builds the
                        evaluation kernels twice more, runtime/kernels/kernel_avx2.cpp with -mavx2 and
                        runtime/kernels/kernel_avx512.cpp with -mavx512f -mavx512bw -mavx512dq
                        -mavx512vl (the build must pass those flags to those two files; without
                        -mavx512dq or -mavx512vl the same bits, its hashes slower), and dsn_noise_init
                        picks from the table of kernels (runtime/kernels/kernel_table.cpp) the widest copy
                        that the CPU and the OS run (with what -mavx2 implies: SSE4.2 and POPCNT among
                        them); on AMD Zen 4, which runs 512-bit vectors as two halves, AVX-512 but for
                        the lattice tiles of RGB noises whose texton the AVX2 copy's strips hold, which
                        it makes faster there. Left at 0 there is one copy, built with the runtime's
                        own flags.

   Stack, as make bench measures it on x86-64 (painted, the deepest of its cases): a per-point call uses
   under 1 KB (its fast path keeps the impulses of the nearby cells on the stack), a continuous per-point
   call under 3 KB, a batch call under 8 KB (a gradient batch about 10 KB), a filtered per-point call up
   to about 30 KB (the candidate impulses of every tap, and the coarse levels' tables of the AVX-512
   copy; a filtered gradient point up to about 36 KB), a lattice tile call under 1 KB unless DSN_TILE_BLOCKS
   (see above), a continuous or filtered tile up to about 88 KB where it is splatted (the texture's records,
   see dsn_continuous_tile_fixed), and what its points take where it goes point by point; a continuous
   gradient tile splatted up to about 128 KB and a filtered one up to about 144 KB (blocks of sums and totals
   more, see "Gradients").
*/
#ifndef DSN_DSN_H
#define DSN_DSN_H

#include <stddef.h>
#include <stdint.h>

#include "dsn/format.h"

#ifndef DSN_SMALL_CODE
#if defined(__OPTIMIZE_SIZE__)
#define DSN_SMALL_CODE 1
#else
#define DSN_SMALL_CODE 0
#endif
#endif

#ifndef DSN_FILTERING /* 1: the filtered evaluation and the texton pyramid; default 0 in the small build */
#define DSN_FILTERING (!DSN_SMALL_CODE)
#endif

#ifndef DSN_HISTOGRAM /* 1: the histogram-preserving output of format 1.2; default 0 in the small build */
#define DSN_HISTOGRAM (!DSN_SMALL_CODE)
#endif

#ifndef DSN_GRADIENTS /* 1: the gradient functions ("Gradients" below); default 0 in the small build */
#define DSN_GRADIENTS (!DSN_SMALL_CODE)
#endif

#ifndef DSN_MIXING /* 1: the mixing of materials ("Mixing" below); default 0 in the small build */
#define DSN_MIXING (!DSN_SMALL_CODE)
#endif

#ifdef __cplusplus
extern "C" {
#endif

#define DSN_VERSION_MAJOR 2
#define DSN_VERSION_MINOR 0
#define DSN_VERSION_PATCH 0
#define DSN_VERSION_STRING "2.0.0"

/* The version of the runtime linked in (DSN_VERSION_STRING when it was built): "MAJOR.MINOR.PATCH". */
const char *dsn_version(void);

#define DSN_ONE 65536 /* 1.0 in the Q16.16 output */
#define DSN_MAX_CHANNELS 3
#define DSN_TILE_MAX_SIDE 65536u /* tile width and height are at most this */

/* A validated view of an asset. Every field is read-only information; `texton` points into the
   caller's buffer (quantized values as described in format.h). */
typedef struct dsn_asset {
    const unsigned char *texton;
    uint32_t version_minor;
    uint32_t channels;            /* 1 or 3 */
    uint32_t bits;                /* 8 or 16 */
    uint32_t shape;               /* DSN_SHAPE_RECTANGLE or DSN_SHAPE_DISK */
    uint32_t interpolation;       /* DSN_INTERPOLATION_LATTICE or DSN_INTERPOLATION_BILINEAR */
    uint32_t width, height;       /* odd, 1..255 */
    uint32_t support_size;        /* |S|: number of support points */
    uint32_t default_impacts_q16; /* 0 when the asset gives none */
    uint32_t scale[3];            /* value = raw / 2^40 */
    int32_t mean[3];              /* Q8.24 */
    int32_t color_transform[9];   /* Q8.24, row-major */
    uint32_t bake_iterations, bake_seed, bake_rme_q24;
    uint32_t exemplar_width, exemplar_height;
    /* The texton pyramid of a 1.1 asset (format.h): the prefiltered levels 1 .. pyramid_levels that the
       filtered evaluation reads. `pyramid` points at the first level record in the caller's buffer;
       read the levels with dsn_asset_level. Null and 0 for an asset without one, and always in a
       runtime built with DSN_FILTERING 0 and DSN_HISTOGRAM 0 (its loader does not read sections). */
    const unsigned char *pyramid;
    uint32_t pyramid_levels; /* 0 .. DSN_PYRAMID_MAX_LEVELS */
    /* The histogram mapping of a 1.2 asset (format.h, section kind 2; "Histogram-preserving output"
       below): `histogram_table` points at the table values T[l][k][i] in the caller's buffer (i16
       little-endian, Q3.12, index (l channels + k) histogram_entries + i). Null and the other fields 0
       for an asset without one, and always in a runtime built with DSN_HISTOGRAM 0 (its loader refuses
       assets that have one). */
    const unsigned char *histogram_table;
    uint32_t histogram_entries;        /* N: 2 .. DSN_HISTOGRAM_MAX_ENTRIES */
    uint32_t histogram_levels;         /* M: 1 .. 1 + pyramid_levels */
    uint32_t histogram_step_shift;     /* s: entry i stands for input_low + i 2^-s */
    int32_t histogram_input_low_q16;   /* Q16.16 */
    int32_t histogram_rotation[9];     /* P, Q8.24, row-major */
    int32_t histogram_centre[3];       /* Q8.24 */
    int32_t histogram_expected_q16[3]; /* Q16.16: what the filtered evaluation fades to */
    /* The lattice texton of a 1.3 bilinear asset (format.h, section kind 3): the texton convolved with
       the two-tap filter whose power spectrum is the bilinear read's, which the lattice evaluators read
       instead of `texton` so that a bilinear bake gives the exemplar's statistics on the lattice too.
       Same channels, bits and scale as `texton`, rectangle shape, in the caller's buffer. Null and 0 for
       an asset without one: lattice-baked assets, and bilinear ones written before format 1.3. */
    const unsigned char *lattice_texton;
    uint32_t lattice_width, lattice_height; /* odd, 1..255 */
} dsn_asset;

/* Validates `size` bytes at `bytes` as a .dsnt asset and fills `asset`. Returns DSN_OK or the first
   failure in the order documented in format.h. On failure `asset` is zeroed. */
int dsn_asset_load(dsn_asset *asset, const void *bytes, size_t size);

/* The quantized texton value of `channel` at texton row `row` (0 = top) and column `column`
   (0 = left); 0 for any index out of range. */
int32_t dsn_asset_texton_value(const dsn_asset *asset, uint32_t row, uint32_t column, uint32_t channel);

/* One level of the texton pyramid (format.h, version 1.1): width * height * channels quantized values
   (i8 or i16 little-endian as the asset's `bits`, row-major, channels interleaved) at spacing 2^level
   texels, centred on the impulse; value q of channel c stands for q * scale[c] * 2^exponent / 2^40. */
typedef struct dsn_level {
    const unsigned char *values; /* in the caller's buffer */
    uint32_t width, height;      /* odd, 1..255 */
    int32_t exponent;            /* -24..24; 0 for level 0 */
} dsn_level;

/* Fills `out` with level `level` of the asset: 0 is the texton itself (exponent 0), 1 ..
   asset->pyramid_levels the pyramid's levels. Returns DSN_OK, DSN_ERR_NULL (null `asset` or `out`, or
   an asset without a texton) or DSN_ERR_ARGUMENT (level above pyramid_levels); on an error *out is
   zeroed. Not compiled when DSN_FILTERING is 0 (a program calling it then fails to link). */
int dsn_asset_level(const dsn_asset *asset, uint32_t level, dsn_level *out);

/* A static, one-line, human-readable message for any code (unknown codes included). */
const char *dsn_error_message(int code);

/* ---- Configuration ---- */

#define DSN_FLAG_NO_COLOR_TRANSFORM 1u       /* use the identity instead of the asset's transform */
#define DSN_FLAG_ALLOW_LATTICE_CONTINUOUS 2u /* continuous mode on a lattice-baked texton */
#define DSN_FLAG_NO_HISTOGRAM 4u /* skip the asset's histogram mapping: its Gaussian-space values */
#define DSN_FLAGS_ALL                                                                                        \
    (DSN_FLAG_NO_COLOR_TRANSFORM | DSN_FLAG_ALLOW_LATTICE_CONTINUOUS | DSN_FLAG_NO_HISTOGRAM)

typedef struct dsn_config {
    uint32_t seed;        /* any value */
    uint32_t impacts_q16; /* impacts per pixel, Q16.16; 0 = the asset's default (30 if it has none).
                             Accepted range [DSN_IMPACTS_MIN_Q16, DSN_IMPACTS_MAX_Q16]. */
    uint32_t period_x;    /* 0 = not periodic along x; otherwise value(x + period_x, y) == value(x, y) */
    uint32_t period_y;    /* 0 = not periodic along y */
    uint32_t flags;       /* DSN_FLAG_* ; unknown bits are an error */
} dsn_config;

/* seed 0, impacts 0 (asset default), no period, no flags. */
void dsn_config_defaults(dsn_config *config);

/* The configured noise: caller-owned storage of a fixed size (DSN_NOISE_BYTES on every platform), filled by
   dsn_noise_init and read by every evaluator. Its contents are private to the runtime and change between
   versions: copy it with memcpy if needed, never read or write its words. It keeps a pointer to the
   asset's texton (the caller's buffer), and init records which copy of the tile and continuous point code
   the CPU runs (x86-64: AVX-512, AVX2 or SSE2), so use a dsn_noise on the machine that initialized it.
   "Not configured", below, means a noise that no dsn_noise_init accepted: zeroed (init failed), or bytes
   init never wrote (an uninitialised variable). Init stores a 32-bit check value over the noise's key
   fields (the asset's pointers and sizes, the cells, periods and tables' sizes) and every function
   verifies it, so such a noise is refused as documented (DSN_ERR_NULL, or the lattice tiles'
   DSN_ERR_ARGUMENT, the output zeroed as for a null noise). That is a check, not a proof: garbage that
   happens to hold a texton pointer and a matching check value (about one chance in 2^32) is read as a
   noise, so initialise every dsn_noise (zeroing it is enough to be refused). The small build
   (DSN_SMALL_CODE) keeps no check value, for its 8 KB: it refuses a zeroed noise only. */
#define DSN_NOISE_WORDS 144 /* 64-bit words: DSN_NOISE_BYTES = 1152 */
#define DSN_NOISE_BYTES (DSN_NOISE_WORDS * 8)
typedef union dsn_noise {
    uint64_t words[DSN_NOISE_WORDS];
    void *align_pointer; /* aligned for every field the runtime keeps */
} dsn_noise;

/* The number of channel values each evaluation writes per point: 1 (grey) or 3 (RGB); 0 for a null or
   unconfigured noise. */
uint32_t dsn_noise_channels(const dsn_noise *noise);

/* ---- The float path: load once, then sample ----
   Three calls over the full API below, for the common case: a seed, the asset's own density, no period,
   float coordinates in texels and float colours. */

/* Loads and validates the asset (dsn_asset_load) and configures `noise` with the defaults of
   dsn_config_defaults and this seed (dsn_noise_init), in one call. `bytes` (the .dsnt file's contents)
   must stay alive and unchanged for as long as `noise` is used: the noise reads its texton there.
   A lattice-baked asset (dsn-bake --interpolation lattice) gets DSN_FLAG_ALLOW_LATTICE_CONTINUOUS, so that
   dsn_sample works on every valid asset: read bilinearly, its texton gives a slightly smoother noise than
   the exemplar (its spectrum times the bilinear filter's: see the continuous mode below); an asset baked with
   `dsn-bake --interpolation bilinear` is compensated for that and matches the exemplar. The lattice
   functions are unaffected by the flag. Returns DSN_OK, DSN_ERR_NULL (noise or bytes null), any error of
   dsn_asset_load (DSN_ERR_TRUNCATED, DSN_ERR_BAD_MAGIC, DSN_ERR_CRC, ...; format.h's validation order)
   or DSN_ERR_IMPACTS (never for an asset that loads: its default density is checked there). On failure
   `noise` is zeroed and every function refuses it. */
int dsn_noise_load(dsn_noise *noise, const void *bytes, size_t size, uint32_t seed);

/* out[channels]: the noise at the point (x, y), in texels (the texture's pixels: texture coordinates
   times the texture size), as float. Any float is a point: coordinates wrap modulo 2^32 texels, NaN and
   infinities are the point 0. Exactly dsn_continuous_point_float(noise, x, y, out) (the float converts to
   double exactly), so the same bits on every platform. Returns DSN_OK, or DSN_ERR_NULL (null `noise` or
   `out`, or a noise that was never configured or whose load failed) or DSN_ERR_CONTINUOUS_MISMATCH (a
   lattice-baked asset configured by dsn_noise_init without DSN_FLAG_ALLOW_LATTICE_CONTINUOUS); on an
   error out[0] (and every channel of a configured noise) is set to 0. */
int dsn_sample(const dsn_noise *noise, float x, float y, float *out);

/* out[channels]: the noise's mean colour as float, the value its samples average to over any large area
   (the asset's mean, which the normalization keeps exact up to the output's 1/65536 resolution; the
   colour transform and the density change the contrast around it, not the mean). What a renderer fades
   to where the texture is too fine to show (far away, minified). With a histogram mapping (see
   "Histogram-preserving output" below) it is the colour the filtered evaluation fades to, exactly
   (centre + P expected, rounded to Q16.16 then converted as dsn_fixed_to_float).
   Returns DSN_OK, or DSN_ERR_NULL (null `noise` or `out`, or a noise never configured); on an error
   out[0] (and every channel of a configured noise) is set to 0. Any configured noise, lattice or
   continuous. */
int dsn_noise_mean_float(const dsn_noise *noise, float *out);

/* Checks `config` against `asset` and precomputes the per-cell Poisson table and the fixed-point
   normalization. Integer arithmetic only. Returns DSN_OK, DSN_ERR_NULL, DSN_ERR_IMPACTS,
   DSN_ERR_ARGUMENT (unknown flag bits, or an asset that dsn_asset_load did not fill or that was altered
   since: its geometry, its histogram fields out of format.h's ranges, and, in a build that reads sections,
   its pyramid and lattice texton, which must be null with their sizes 0 or point where the loader points
   them, at a section that the loader's steps 15 and 17 accept with exactly the sizes the asset gives; a
   build with DSN_HISTOGRAM 0 refuses any histogram table) or DSN_ERR_COST (one point would examine more
   than DSN_MAX_POINT_IMPULSES impulses, below). Init reads only what the asset's pointers point at, so
   it cannot tell a pointer moved to other bytes that look like a section of that kind. Every period
   1 .. 2^32 - 1 is valid, within that bound. On failure `noise` is zeroed, and the evaluation functions then
   refuse it: the lattice per-point functions set out[0] to 0, the others return an error and zero their
   output as they state.
   Cells are 2^cell_shift points wide, cell_shift in 0..8, chosen by a fixed cost model of the per-point
   call (the same choice on every platform, since the cell size is part of the output); a 31 x 31 texton
   at 30 impacts per pixel gets 16 x 16 cells (mean 8 impulses each).
   The channel sums are integers taken modulo 2^32 (identically by every path); they cannot wrap unless
   tens of thousands of full-scale impulses hit one point. */
int dsn_noise_init(dsn_noise *noise, const dsn_asset *asset, const dsn_config *config);

/* The work of one point. The asset format bounds neither the reach of the pyramid's levels (255 values
   at spacing 2^8 texels: 65 280 texels) nor the density (1024 impacts per pixel over a support of one
   texel), so a valid asset of a few hundred bytes could make one filtered point examine trillions of
   impulses. dsn_noise_init therefore computes the expected number of impulses that one point examines in
   the costliest evaluation of the configured noise, and refuses the configuration with DSN_ERR_COST above
   DSN_MAX_POINT_IMPULSES (every build but the small one, which checks nothing of it: its evaluations are
   unfiltered, bounded by the density and the texton, but a period much smaller than its cells multiplies
   them). That count is
   lambda c^2 (the mean impulse count of a cell, c its side) times the cells each walk visits, for
     - the lattice point: a window of the lattice texton's size;
     - the continuous point: the texton's window plus one texel on each side;
     - the filtered point, at each level of detail l = 0 .. L (L the pyramid's levels): the walk of levels
       l and l + 1 (l alone at L), whose reach is (r_l + 1) 2^l texels each side (r_l the level's radius less
       its all-zero margins), with the widest footprint the filtered evaluation accepts there:
       DSN_FILTER_MAX_TAPS taps spread over up to DSN_FILTER_MAX_TAPS 2^(l + 1) texels diagonally, walked
       together, or one by one where they straddle the 32-bit wrap of the coordinates (16 walks);
   a periodic axis counting whole cells per copy of the period (the impulses beyond the period are drawn,
   then dropped: a period much smaller than a cell costs a cell per copy). Expected means over the seeds:
   one point's count is Poisson-like around it (tests/evaluation_cost_test.cpp's widest footprints list
   64-94% of it). dsn-bake's assets need at most 12 788 at the density they carry (30 impacts per
   pixel; measured on a 512 x 512 exemplar: the default radius 15, 12 788, 10 230 with --histogram;
   --radius 126 --bits 16, with or without --histogram, 12 288; --radius 127 --bits 16 --interpolation
   lattice --histogram, 12 100) and 315 372 at 1024 impacts; their geometry with every value non-zero
   (no margin) at most 22 000, 34 000 with periods of 256. The bound leaves a margin of 82 over the
   first, and admits every asset without a pyramid at any density up to 1024 without a period (at most
   746 496: a 1 x 1 texton at 1024 impacts, 16 taps). A 1 x 1 texton at 1024 impacts under 8 levels of 5 x 5
   values (377 bytes) would need billions, under 8 levels of 255 x 255 (0.5 MB) trillions: both are refused.
   Each impulse listed is read at every tap and level it reaches (up to 32 reads): the costliest accepted
   point measured, a 1 x 1 texton at 1024 impacts under 16 taps at level of detail 0.99 (545 000 impulses
   listed), takes 21 ms on one core of a current x86-64. The bound makes every point finite, not cheap: a
   renderer that evaluates many points of an asset it does not trust needs its own time budget. */
#define DSN_MAX_POINT_IMPULSES 1048576u /* 2^20 */

/* ---- Per-point evaluation (lattice) ----
   The lattice evaluators (these and the lattice tiles below) read the asset's lattice texton where it
   has one (format 1.3: every bilinear bake of dsn-bake 1.4 and later), the texton itself otherwise, so
   that a default (bilinear) bake shows the exemplar's statistics on the lattice as in continuous mode:
   the same variance and spectrum as the continuous noise at lattice points (format.h says why). A
   bilinear asset written before format 1.3 has none: read on the lattice, it has up to 9 times the
   exemplar's power at the highest frequencies (re-bake it). A build that reads no sections (the small
   build: DSN_FILTERING 0 and DSN_HISTOGRAM 0) has not read a 1.3 bilinear asset's lattice texton: its
   lattice evaluators refuse such an asset (the tiles return DSN_ERR_UNSUPPORTED, a point is zeroed);
   bake `--interpolation lattice` for it, or read it in continuous mode. */

/* out[channels]: Q16.16 values at lattice point (x, y). A null or unconfigured `noise` sets out[0] to 0
   (its channel count is unknown; there is no error code to return); a null `out` is ignored. */
void dsn_lattice_point_fixed(const dsn_noise *noise, int32_t x, int32_t y, int32_t *out);
/* out[channels]: the same value as float, exactly fixed / 65536 rounded to float. */
void dsn_lattice_point_float(const dsn_noise *noise, int32_t x, int32_t y, float *out);
/* out[channels]: the same value clamped to [0, 1] and rounded to 0..255 (half up). */
void dsn_lattice_point_u8(const dsn_noise *noise, int32_t x, int32_t y, uint8_t *out);

/* Conversions used by the functions above, for callers that keep fixed-point values. */
float dsn_fixed_to_float(int32_t value);
uint8_t dsn_fixed_to_u8(int32_t value);

/* ---- Tile evaluation (lattice) ----
   Pixel (i, j) of a width x height tile at (x0, y0) is the point ((int32)(x0 + i), (int32)(y0 + j)) with
   the additions done modulo 2^32: exactly what the per-point functions return there. Output is row-major,
   top row (y0) first, channels interleaved: width * height * channels values. dsn_lattice_tile_fixed
   accumulates in `out` and ignores scratch (pass null, 0). dsn_lattice_tile_float and dsn_lattice_tile_u8
   need a scratch buffer of at least dsn_lattice_tile_scratch_size() bytes (an integer accumulator; no
   alignment needed), else they return DSN_ERR_SCRATCH. dsn_lattice_tile_scratch_size returns 0 for an invalid
   noise or size. Width and height are 1 .. DSN_TILE_MAX_SIDE (else DSN_ERR_TILE_SIZE, also when the tile is
   not addressable); null pointers give DSN_ERR_NULL, a noise that is not configured DSN_ERR_ARGUMENT. On
   any error but DSN_ERR_TILE_SIZE a non-null `out` is zeroed: width * height * channels values, or
   width * height for a null or unconfigured noise. */
/* On x86, fixed and float tiles of 16 MB of output or more are written with non-temporal stores (they
   would not stay in the caches anyway), so reading them right after the call comes from memory. */
size_t dsn_lattice_tile_scratch_size(const dsn_noise *noise, uint32_t width, uint32_t height);
int dsn_lattice_tile_fixed(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                           int32_t *out, void *scratch, size_t scratch_size);
int dsn_lattice_tile_float(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                           float *out, void *scratch, size_t scratch_size);
int dsn_lattice_tile_u8(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                        uint8_t *out, void *scratch, size_t scratch_size);

/* ==== Continuous mode (renderer mode) ===============================================================
   Evaluates the noise at continuous texture coordinates, for renderers that zoom, rotate and warp.
   The impulses form a continuous Poisson process of the same intensity (exact per-cell Poisson counts
   from the same table, positions uniform in the cell with 16 - cell_shift >= 8 fractional bits per
   axis; each lattice impulse is the floor of its continuous twin) and the texton is read with bilinear
   interpolation (zero beyond its window), in integer arithmetic only, with 8-bit weights as GPUs' texture
   units filter: each impulse's texton is read at its offset from the point (point minus impulse) floored
   to a multiple of 2^-8 texel along each axis, exactly bilinearly there. So each impulse is read as if
   moved, for this point, by less than 2^-8 texel along each axis, and its read differs from the exact real
   bilinear interpolation by less than 2^-8 (Lx + Ly), Lx and Ly the largest differences between the texels
   of its 2 x 2 cell along x and along y. Between two points a whole number k of 2^-8 texel steps apart
   along an axis every weight moves by exactly k steps (a weight past the texel edge continues on the next
   texel pair, where the interpolation is continuous), so the value changes as the interpolation does:
   up to 256x magnification a render has no plateaus, and the step between neighbouring pixels is at most
   their distance times the largest derivative on the way, plus the output's rounding (tests/
   continuous_test.cpp checks it at 64x); past 256x, each impulse's read holds over each of its steps, whose
   phases differ from impulse to impulse (their positions have 16 - cell_shift fraction bits). Why 8 bits:
   each term (256 - u) a + u b of an 8-bit texton fits a 16-bit lane and an impulse's whole read 24 bits, so
   GPUs and vector units can read and sum in 32-bit lanes; the sums' definition (Q.32, modulo 2^64) is
   unchanged, their low 16 bits zero. Runtime 2.0 made this change (1.x took the weights' 16 bits): the
   continuous, filtered, mixed and surface values changed once, the lattice mode's did not, and every asset
   reads as before. Sampled on the lattice, this noise has the texton's spectrum times (2/3 + cos(2 pi
   xi1)/3)(2/3 + cos(2 pi xi2)/3); a texton baked with `dsn-bake --interpolation bilinear` compensates it. The
   continuous functions return DSN_ERR_CONTINUOUS_MISMATCH for a lattice-baked asset unless the noise was
   configured with DSN_FLAG_ALLOW_LATTICE_CONTINUOUS.

   Coordinates are Q32.32 fixed point in texel units, in an int64_t: value / 2^32 texels. The integer
   part wraps modulo 2^32 like the lattice coordinates, so every int64_t is a point of the same
   2^32 x 2^32 torus, and ((int64_t)x << 32) is the lattice point x. Periods apply as in lattice mode.
   The same guarantees hold: same bits everywhere, no heap, no float on the evaluation path, and a
   regular grid (tile) gives exactly the bits of the per-point function at each grid point. */

#define DSN_COORDINATE_ONE ((int64_t)1 << 32) /* 1.0 texel in Q32.32 */

/* IEEE-754 value -> Q32.32 coordinate, computed from the bits with integer operations (identical on
   every platform, float unit or not): value * 2^32 rounded toward minus infinity, reduced modulo 2^64
   (that is, the coordinate modulo 2^32 texels, the torus). NaN and +-Inf give 0. */
int64_t dsn_coordinate_from_double(double value);
int64_t dsn_coordinate_from_float(float value);

/* DSN_OK when the continuous functions may be used with `noise`, else DSN_ERR_NULL or
   DSN_ERR_CONTINUOUS_MISMATCH. */
int dsn_continuous_check(const dsn_noise *noise);

/* out[channels]: Q16.16 values at the continuous point (x, y) (Q32.32). Returns DSN_OK, or
   DSN_ERR_NULL (null `noise` or `out`, or a noise not configured) or DSN_ERR_CONTINUOUS_MISMATCH; on an
   error out[0] (and every channel of a configured noise) is set to 0. */
int dsn_continuous_point_fixed(const dsn_noise *noise, int64_t x, int64_t y, int32_t *out);
/* The same from float64 coordinates (converted by dsn_coordinate_from_double), output as float
   (exactly fixed / 65536 rounded to float); the same errors. */
int dsn_continuous_point_float(const dsn_noise *noise, double x, double y, float *out);
/* The same at Q32.32 coordinates as 8-bit values (dsn_fixed_to_u8 of each fixed value); the same errors,
   the same zeroed output. Not in the small build (DSN_SMALL_CODE), which has no byte of its 8 KB left for
   it: convert dsn_continuous_point_fixed's values with dsn_fixed_to_u8 there. */
#if !DSN_SMALL_CODE
int dsn_continuous_point_u8(const dsn_noise *noise, int64_t x, int64_t y, uint8_t *out);
#endif

/* A regular grid of continuous points: pixel (i, j) is the point
   (origin_x + i * column_step_x + j * row_step_x, origin_y + i * column_step_y + j * row_step_y),
   all in Q32.32 with the arithmetic done modulo 2^64. Steps (a, 0) and (0, a) give a zoom by 1/a; any
   other pair of vectors gives rotations and shears. */
typedef struct dsn_grid {
    int64_t origin_x, origin_y;
    int64_t column_step_x, column_step_y; /* from pixel (i, j) to (i + 1, j) */
    int64_t row_step_x, row_step_y;       /* from pixel (i, j) to (i, j + 1) */
} dsn_grid;

/* Tile evaluation on a grid: width x height pixels, row-major, top row (j = 0) first, channels
   interleaved, exactly the per-point values. `scratch` as in lattice tile evaluation (at least
   dsn_continuous_tile_scratch_size() bytes, no alignment needed). Returns DSN_OK, DSN_ERR_NULL,
   DSN_ERR_CONTINUOUS_MISMATCH, DSN_ERR_TILE_SIZE or DSN_ERR_SCRATCH; on an error but DSN_ERR_TILE_SIZE
   a non-null `out` is zeroed as a lattice tile's is.
   Any grid (zoom in or out, rotation, shear, mirror, periodic noises) is evaluated by splatting: each
   impulse near the tile adds its texton to the pixels it reaches, so the cost follows the tile's area in
   texels rather than its pixel count; the scratch then holds the 64-bit sums of a block of pixels (the
   tile goes through it 64 x 32 pixels at a time, each row of sums padded by a cache line where that fits:
   it is asked for min(width * height, 72 * 32) * channels * 8 bytes, plus 7, at most 55 303 bytes). On x86 an
   8-bit texton is read from 64-bit records per 2 x 2 texels kept on the tile call's stack (up to 64 KB,
   beside up to about 24 KB of the splat's own), unless it has more than 8192 of them (RGB past 49 x 49
   texels, grey past 89 x 89), which go pixel by pixel; on an axis-aligned grid (column step along x alone,
   row step along y alone, either sign) each record's interpolation along its row of texels is shared by the
   pixels of a column. Grids where that does not pay or cannot be done exactly (a pixel covering more texels
   than a point visits, steps of 2^14 texels or more, a periodic axis whose points cross the int32 wrap of the
   coordinate or a period of 2^27 or more) are evaluated point by point and dsn_continuous_tile_scratch_size()
   returns 0 for them; so does every grid in the small build (DSN_SMALL_CODE), which evaluates point by point.
   Either way the bits are the per-point ones. */
size_t dsn_continuous_tile_scratch_size(const dsn_noise *noise, const dsn_grid *grid, uint32_t width,
                                        uint32_t height);
int dsn_continuous_tile_fixed(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                              int32_t *out, void *scratch, size_t scratch_size);
int dsn_continuous_tile_float(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                              float *out, void *scratch, size_t scratch_size);
int dsn_continuous_tile_u8(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                           uint8_t *out, void *scratch, size_t scratch_size);

/* ---- Batches of continuous points (a renderer's ray hits) ----
   DSN_CONTINUOUS_BATCH   default: 0 in the small build (DSN_SMALL_CODE), else 1. Like the configuration
                          macros at the top, read when the runtime is compiled: 0 leaves the four batch
                          functions below out of the runtime (and out of this header), so the small
                          build keeps its code size; call dsn_continuous_point_* in a loop there.
   Point k of a batch is (xs[k], ys[k]); out receives count * channels values, point k's channels at
   out[k * channels], exactly what the per-point function of the same type returns there (the float
   variant: dsn_continuous_point_float, coordinates converted by dsn_coordinate_from_double; the u8
   variant: dsn_continuous_point_u8, Q32.32 coordinates). The points
   may lie anywhere, in any order; where the CPU runs AVX2 (the copy init chose, as for tiles) the batch
   evaluates them on vectors: 8-bit textons with cells of side <= 16 (the usual densities) 8 points at a
   time (their cells, cell hashes, impulse counts and the first 16 impulses' positions of each cell across
   points, then each point's impulses through the vectorized per-point evaluator), other assets together,
   hashing and interpolating across points; elsewhere point by point.
   The scratch holds a table of the texton's 2 x 2 texel neighbourhoods and the work arrays: at least
   dsn_continuous_batch_scratch_size() bytes (no alignment needed; it depends on the asset's texton size,
   not on count: about 32 KB for a 31 x 31 RGB texton). Returns DSN_OK (count 0
   included: nothing is read or written), DSN_ERR_NULL (a null pointer with count > 0, or a noise not
   configured), DSN_ERR_CONTINUOUS_MISMATCH or DSN_ERR_SCRATCH; on an error a non-null `out` gets
   count * channels zeros (count for a null or unconfigured noise).
   dsn_continuous_batch_scratch_size returns 0 for a noise that the continuous functions refuse. */
#ifndef DSN_CONTINUOUS_BATCH
#define DSN_CONTINUOUS_BATCH (!DSN_SMALL_CODE)
#endif
#if DSN_CONTINUOUS_BATCH
size_t dsn_continuous_batch_scratch_size(const dsn_noise *noise);
int dsn_continuous_batch_fixed(const dsn_noise *noise, const int64_t *xs, const int64_t *ys, uint32_t count,
                               int32_t *out, void *scratch, size_t scratch_size);
int dsn_continuous_batch_float(const dsn_noise *noise, const double *xs, const double *ys, uint32_t count,
                               float *out, void *scratch, size_t scratch_size);
int dsn_continuous_batch_u8(const dsn_noise *noise, const int64_t *xs, const int64_t *ys, uint32_t count,
                            uint8_t *out, void *scratch, size_t scratch_size);
#endif

/* ==== End of the continuous mode ===================================================================== */

/* ==== Filtered evaluation (anti-aliased continuous mode) ===========================================
   The continuous mode point-sampled: seen from afar (a ground plane toward the horizon, a small distant
   object) a pixel covers many texels and one sample per pixel aliases and shimmers as the camera moves.
   The filtered evaluation returns instead, at each pixel, the noise filtered by the pixel's footprint,
   in integer arithmetic with the same guarantees as the rest of this header (same bits everywhere, no
   heap, no float on the evaluation path). It needs a runtime built with DSN_FILTERING (see the
   configuration above) and reads the texton pyramid of a 1.1 asset (format.h; dsn-bake writes one).

   The mathematics.
   - A spot noise F = sum_i t(. - x_i) filtered by a kernel g is the spot noise of the same impulses
     with the texton t * g (van Wijk, "Spot noise", SIGGRAPH 1991; Lagae, Lefebvre, Drettakis and Dutre,
     "Procedural noise using sparse Gabor convolution", SIGGRAPH 2009, filter their Gabor kernels this
     way). So a filtered evaluation is the ordinary evaluation with a prefiltered texton, over the same
     impulses: its variance falls by itself as detail is filtered away, and its expectation does not
     change. No renormalization is applied: dividing by the filtered standard deviation would bring the
     aliasing back.
   - The pyramid. Level 0 is the texton as the continuous mode reads it, t0(x) = sum_j t[j] hat(x - j)
     (hat the bilinear tent). Level l >= 1 stands for t0 * G_l, G_l the isotropic Gaussian of standard
     deviation 2^(l-1) texels, stored as a bilinear texton at spacing 2^l centred on the impulse (its
     texel (i, j) at offset 2^l (i - r_l, j - r'_l) texels, r_l = (width_l - 1) / 2, so that changing
     level does not shift the texture): t_l(x) = sum s_l[i, j] hat(x / 2^l - (i - r_l, j - r'_l)). The
     baker chooses s_l as the least-squares (L2) projection of t0 * G_l on those tents; by Campbell's
     theorem E[(F_l - F * G_l)^2] = lambda * integral (t_l - t0 * G_l)^2, so this is the best prefilter
     of that form. Every level is read as the continuous mode reads the texton, with 8-bit weights (the
     offset divided by 2^l, then floored to 2^-8 of a level texel). The blurred texton spills past the
   texton's window: the spill is kept (Texton Noise, Galerne, Leclaire and Moisan, Computer Graphics Forum
   2017, discards impulses whose read falls outside the texture, and its mean drifts). The pyramid has L =
   floor(log2(max(r, r'))) + 1 levels, down to a few texels (a 31 x 31 RGB 8-bit asset with its pyramid is
   under 6 KB).
   - The mean stays exact at every level: E[sum_i t_l(x - x_i)] = lambda * integral t_l = lambda 4^l
     sum s_l, so each level has its own offset (the expected sum subtracted by the normalization),
     computed by dsn_noise_init from the exact integer sum of the level's stored values. Beyond the
     coarsest level the texture has faded to its mean colour (dsn_noise_mean_float) exactly: "level
     L + 1" is the mean.
   - Level of detail (Williams, "Pyramidal parametrics", SIGGRAPH 1983, for the trilinear blend; the
     anisotropic taps follow the GPUs' anisotropic filtering, e.g. OpenGL's
     EXT_texture_filter_anisotropic). From the footprint's two step vectors (texels per pixel):
       Pmax = the longer length, Pmin = |det J| / Pmax (the footprint parallelogram's width across it),
       N = taps = the smallest power of two >= Pmax / Pmin, at most the largest power of two <= max_taps,
       LOD = log2(max(Pmax / N, Pmin)), computed in integers with 8 fraction bits (dsn_filter_level).
     The N taps lie at x + ((2k + 1 - N) / (2N)) v, k = 0 .. N - 1, along the longer step vector v, with
     equal weights 1/N. Each tap blends levels floor(LOD) and floor(LOD) + 1 with weights (1 - f, f), f
     the fraction of LOD. Two levels that share the impulses blend linearly with no variance
     correction: the blend is itself a linear filter of the same draw. So the filter a pixel gets is
     sum_taps (1/N) [(1 - f) G_floor(LOD) + f G_floor(LOD)+1] (G_0 = no filter), centred on each tap.
   - Exactness: a footprint whose longer step is at most one texel is not filtered (LOD 0, one tap,
     whatever its shape) and gives exactly the bits of dsn_continuous_point_fixed, as does any footprint
     with LOD <= 0 and one tap. LOD >= L + 1 gives exactly the mean colour without walking impulses.
     In between, each level's value is normalized with 8 more fraction bits than the output, the two
     levels are blended and the taps averaged in 64-bit integers, and the result is rounded once (half
     up) to Q16.16 and saturated. An asset with a histogram mapping then maps that value through the
     two levels' tables, and fades to its own colour (see "Histogram-preserving output" below).
   - Cost: a level-l tap reads the impulses within (r_l + 1) 2^l texels, lambda (2 (r_l + 1) 2^l)^2 of them,
     up to 4 times more per level than level 0 near the coarsest levels (the blurred texton covers more
     impulses: for make bench's 31 x 31 texton and its baked pyramid about 1.9x level 0's at level 1, 3x at
     2, 6x at 3, 16x at 4). All-zero columns and rows at the edges of a level's window (the spill often
     quantizes to 0 there) are left out of its reach: the same values, fewer impulses (1.4x, 2.3x, 5x for
     that texton). A fractional LOD reads both levels over one walk of the coarser one's impulses. The N
     taps of a point share one walk over the box that holds their reaches, each impulse read at every tap it
     reaches, so a tap costs less than a point of its level alone. make bench reports the ratios to the
     continuous mode per level of detail and per tap, with the impulse counts and, per level of detail,
     the cost of listing the impulses alone (no level read).
   An asset without a pyramid (format 1.0, or a 1 x 1 texton) has L = 0: the filtered evaluation then
   fades from the continuous mode (LOD 0) to the mean colour (LOD 1 and beyond).

   The same errors as the continuous mode (DSN_ERR_NULL, DSN_ERR_CONTINUOUS_MISMATCH), DSN_ERR_NULL for
   a null footprint, and DSN_ERR_ARGUMENT for max_taps 0 or above DSN_FILTER_MAX_TAPS. Every other
   footprint has a defined result: zero steps are LOD <= 0 (unfiltered), a negative determinant (a mirror)
   is taken by its absolute value, a zero determinant (a degenerate, line-like footprint) gets the most
   taps allowed, huge steps the mean colour. Lengths are computed without overflow for every int64
   value. */

#define DSN_FILTER_MAX_TAPS 16u

/* A pixel's footprint in texture space: the 2 x 2 Jacobian of the texel coordinates per pixel, as two
   step vectors in Q32.32 texels (the derivatives a renderer gets from ray differentials or from its
   neighbours, ddx and ddy on a GPU), and the most anisotropic taps allowed. */
typedef struct dsn_footprint {
    int64_t column_step_x, column_step_y; /* texels per pixel step along the screen's x, Q32.32 */
    int64_t row_step_x, row_step_y;       /* texels per pixel step along the screen's y, Q32.32 */
    uint32_t max_taps;                    /* 1: isotropic; up to DSN_FILTER_MAX_TAPS: anisotropic */
} dsn_footprint;

/* Fills `footprint` from float derivatives in texels per pixel (dx_dpx = d texel x / d screen x, etc.):
   each converted to Q32.32 from its bits with integer operations (rounded toward minus infinity, as
   dsn_coordinate_from_double, but saturated to the int64 range instead of wrapped). Returns DSN_OK,
   DSN_ERR_NULL (null footprint) or DSN_ERR_ARGUMENT (a NaN or infinite derivative, or max_taps 0 or
   above DSN_FILTER_MAX_TAPS; the footprint is then zeroed). */
int dsn_footprint_from_float(dsn_footprint *footprint, double dx_dpx, double dy_dpx, double dx_dpy,
                             double dy_dpy, uint32_t max_taps);

/* The level of detail and tap count the filtered evaluation uses for this footprint on this noise:
   *lod_q8 in 1/256 levels, clamped to [0, 256 (L + 1)] (0: unfiltered; 256 (L + 1): the mean colour,
   L the asset's pyramid levels), *taps in 1 .. max_taps (a power of two). Integer arithmetic: the same
   on every platform. Returns DSN_OK, DSN_ERR_NULL (a null pointer or a noise not configured) or
   DSN_ERR_ARGUMENT (max_taps 0 or above DSN_FILTER_MAX_TAPS); on an error *lod_q8 and *taps are 0. */
int dsn_filter_level(const dsn_noise *noise, const dsn_footprint *footprint, int32_t *lod_q8, uint32_t *taps);

/* out[channels]: Q16.16 values of the noise filtered by the footprint at the continuous point (x, y)
   (Q32.32). Returns DSN_OK, DSN_ERR_NULL, DSN_ERR_CONTINUOUS_MISMATCH or DSN_ERR_ARGUMENT; on an error
   out[0] (and every channel of a configured noise) is set to 0. */
int dsn_filtered_point_fixed(const dsn_noise *noise, int64_t x, int64_t y, const dsn_footprint *footprint,
                             int32_t *out);
/* The same from float64 coordinates (dsn_coordinate_from_double), output as float (exactly fixed /
   65536 rounded to float); the same errors. */
int dsn_filtered_point_float(const dsn_noise *noise, double x, double y, const dsn_footprint *footprint,
                             float *out);
/* The same at Q32.32 coordinates as 8-bit values (dsn_fixed_to_u8 of each fixed value); the same errors,
   the same zeroed output. */
int dsn_filtered_point_u8(const dsn_noise *noise, int64_t x, int64_t y, const dsn_footprint *footprint,
                          uint8_t *out);

/* A grid tile (dsn_grid, as dsn_continuous_tile_fixed) filtered by the grid's own footprint: its column
   and row steps, with max_taps as in dsn_footprint. Exactly the per-point values of
   dsn_filtered_point_fixed with that footprint at each grid point (the level of detail and taps are
   computed once per tile). A grid whose footprint is unfiltered (level of detail 0, one tap) is
   dsn_continuous_tile_fixed's tile, splat included, and needs its scratch. Any other is splatted too:
   the grid of each tap (moved by the tap's offset) with each level the plan blends, each impulse adding
   the level to the pixels it reaches, block by block, the scratch holding the pixels' 64-bit sums and
   their totals (twice the continuous tile's). A grid whose impulses would each reach fewer than 12
   pixels of a row at some blended level is splatted transposed (columns for rows) where its columns
   are long enough (a footprint stretched along the rows' direction), and otherwise (the coarse levels
   of small textons) evaluated point by point without scratch, as the filtered point, which shares each
   impulse among the taps, is as fast there; so are grids the continuous tile would not splat (too
   sparse, too large); plans past the coarsest level (the fade); every grid of the small build. `scratch`
   holds at least dsn_filtered_tile_scratch_size() bytes (no alignment needed; 0 for an invalid call or a grid
   evaluated point by point). Returns DSN_OK, DSN_ERR_NULL, DSN_ERR_CONTINUOUS_MISMATCH, DSN_ERR_ARGUMENT
   (max_taps), DSN_ERR_TILE_SIZE or DSN_ERR_SCRATCH; on an error but DSN_ERR_TILE_SIZE a non-null `out`
   is zeroed as a lattice tile's is. */
size_t dsn_filtered_tile_scratch_size(const dsn_noise *noise, const dsn_grid *grid, uint32_t max_taps,
                                      uint32_t width, uint32_t height);
int dsn_filtered_tile_fixed(const dsn_noise *noise, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                            uint32_t height, int32_t *out, void *scratch, size_t scratch_size);
int dsn_filtered_tile_float(const dsn_noise *noise, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                            uint32_t height, float *out, void *scratch, size_t scratch_size);
int dsn_filtered_tile_u8(const dsn_noise *noise, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                         uint32_t height, uint8_t *out, void *scratch, size_t scratch_size);

/* ==== End of the filtered evaluation ================================================================= */

/* ==== Gradients (bump and normal mapping) ===========================================================
   The noise's value and its gradient together, per channel: what a renderer needs to bump or
   normal-map a surface with the texture (perturb the normal by -(dx, dy) scaled by a height, or take the
   noise as a height field). Integer arithmetic, the same bits everywhere, as the values; the value `out`
   is exactly what the evaluator of the same mode returns. Built with DSN_GRADIENTS (not the small build).

   Definitions, in Q16.16 output units per texel:
   - Continuous mode: the exact derivative of the bilinear noise. Each impulse's bilinear texton is, on
     the 2 x 2 texels that hold the point, (1 - v)((1 - u) a + u b) + v((1 - u) c + u d) (u, v the
     read's 8-bit weights, see the continuous mode, a b / c d the texels above / below); its partial
     derivatives are (1 - v)(b - a) + v(d - c) along x and (1 - u)(c - a) + u(d - b) along y, summed over
     the impulses exactly in integers (per 2^-16 texel) and normalized once, as the value, by the colour
     transform and the density's scale (the mean does not enter). The bilinear noise is piecewise linear
     in each axis: where a texel edge of some impulse is crossed the derivative jumps, and the one given
     there is the slope of the piece toward +x (or +y): one-sided. Exactness: a point moved by one step of
     the weights, 2^-8 texel, moves every weight by one step (a weight past its texel edge continues on the
     next texel pair), so the sums at x + 2^-8 minus those at x are 2^8 times the derivative's sums, bit
     for bit, and over any whole number of steps the sums' change is the sum of those at each step on the
     way (tests/gradient_test.cpp checks both); between steps the value is constant.
   - Lattice mode: forward differences, dx = F(x + 1, y) - F(x, y) and dy = F(x, y + 1) - F(x, y) of the
     noise before its rounding (coordinates + 1 modulo 2^32): the spot noise of the differenced texton
     t(p + 1) - t(p), normalized as the value without the mean and rounded once, so it differs from the
     difference of two rounded values by at most one unit.
   - Histogram mapping (an asset of format 1.2): the chain rule, value and gradient in Gaussian space g
     first, then dout_c = sum_k P[c][k] T_k'(g_k) dg_k, T_k' the slope of the table's segment that holds
     g_k (0 where the table is clamped; its upper segment at an entry), rounded once per channel after the
     table (saturated to +-2^29) and once after the rotation.
   Float variants: each value exactly fixed / 65536 rounded to float.

   Per point: the errors of the value's function (dsn_lattice_point_fixed returns none; its gradient
   returns DSN_ERR_NULL for a null or unconfigured noise or null outputs, and DSN_ERR_UNSUPPORTED where
   the lattice point zeroes its output); null `dx` or `dy` is DSN_ERR_NULL. On an error every non-null
   output is zeroed as the value's function zeroes `out`. Tiles and batches: the layout, the grid and
   the errors of the value's functions, three arrays of width * height * channels (or count * channels)
   values, exactly the per-point results; they take no scratch (make bench's gradient_bench reports their
   cost next to the value's, and their stack). A lattice tile sums one more column and row than it has
   (the differences' neighbours) by the value's strips; a continuous tile that the value's function would
   splat is splatted in blocks of 64 x 8 pixels whose sums stay on the stack: once, each impulse adding its
   value and both slopes, over offsets up to and including the reach (at its entry edge an impulse's value
   is 0, its slope is not), where the kernel can (AVX2 and AVX-512, 8-bit textons); else three times, at the
   grid and at the grid moved one weight step (2^-8 texel) along x and along y, the differences being 2^8
   times the derivative's sums exactly (see the continuous mode above). A grid whose move would carry a
   periodic axis's int32 start (X - 1) across its wrap, where the sums jump, goes point by point. A batch goes
   8 points at a time through the vector walk where the value's batch does (the AVX2 and AVX-512 kernels), its
   texels read from the texton (no scratch, no table), the groups' sums normalized together. An unfiltered
   filtered gradient tile (level of detail 0, one tap) is the continuous one; a filtered one that the value's
   function would splat is splatted per tap and level, in blocks of 64 x 8 pixels: once, as the continuous
   tile, where the kernel can and every level has its records; else three times, the tap's grid and the
   same moved one weight step of the level (2^-8 level texel) along x and along y (the same exception at
   a periodic axis's seam); the others go point by point.
   - Filtered evaluation (DSN_FILTERING): the derivative of the filtered noise, the same blend of the same
     levels at the same taps as the value: each level's exact derivative (its bilinear slopes per texel of
     the level, over 2^level per texel), normalized per level without its offset, blended with the
     level's weight (the mean's share of a fade is constant: no slope), averaged over the taps and rounded
     once; with a mapping, the chain rule through the blend of the two levels' tables ((1 - w) T_l' +
     w T_(l+1)', the levels past the tables flat). Past the coarsest level (the mean colour) it is 0, and
     an unfiltered footprint gives the continuous gradient's bits. The slopes come from the value's sifted
     walk: where the AVX2 or AVX-512 copy reads 8-bit levels, each impulse's slopes are read with its value
     (the impulses exactly at the entry edge of a level's reach, whose value is 0, included); elsewhere
     (16-bit levels, the SSE2 copy) from each tap's copies moved by one weight step of each level along x
     and along y (a level's sums step by exactly its slopes there; a tap whose move crosses the int32 wrap
     of a periodic axis takes the tap-by-tap walk instead). */
#if DSN_GRADIENTS
int dsn_lattice_gradient_fixed(const dsn_noise *noise, int32_t x, int32_t y, int32_t *out, int32_t *dx,
                               int32_t *dy);
int dsn_lattice_gradient_float(const dsn_noise *noise, int32_t x, int32_t y, float *out, float *dx,
                               float *dy);
int dsn_continuous_gradient_fixed(const dsn_noise *noise, int64_t x, int64_t y, int32_t *out, int32_t *dx,
                                  int32_t *dy);
int dsn_continuous_gradient_float(const dsn_noise *noise, double x, double y, float *out, float *dx,
                                  float *dy);
/* dsn_sample with its gradient: exactly dsn_continuous_gradient_float(noise, x, y, out, dx, dy). */
int dsn_sample_gradient(const dsn_noise *noise, float x, float y, float *out, float *dx, float *dy);

int dsn_lattice_tile_gradient_fixed(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width,
                                    uint32_t height, int32_t *out, int32_t *dx, int32_t *dy);
int dsn_lattice_tile_gradient_float(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width,
                                    uint32_t height, float *out, float *dx, float *dy);
int dsn_continuous_tile_gradient_fixed(const dsn_noise *noise, const dsn_grid *grid, uint32_t width,
                                       uint32_t height, int32_t *out, int32_t *dx, int32_t *dy);
int dsn_continuous_tile_gradient_float(const dsn_noise *noise, const dsn_grid *grid, uint32_t width,
                                       uint32_t height, float *out, float *dx, float *dy);
int dsn_continuous_batch_gradient_fixed(const dsn_noise *noise, const int64_t *xs, const int64_t *ys,
                                        uint32_t count, int32_t *out, int32_t *dx, int32_t *dy);
int dsn_continuous_batch_gradient_float(const dsn_noise *noise, const double *xs, const double *ys,
                                        uint32_t count, float *out, float *dx, float *dy);
#if DSN_FILTERING
/* The filtered evaluation's errors (dsn_filtered_point_fixed, dsn_filtered_tile_fixed, their scratch
   aside), the same zeroing. */
int dsn_filtered_gradient_fixed(const dsn_noise *noise, int64_t x, int64_t y, const dsn_footprint *footprint,
                                int32_t *out, int32_t *dx, int32_t *dy);
int dsn_filtered_gradient_float(const dsn_noise *noise, double x, double y, const dsn_footprint *footprint,
                                float *out, float *dx, float *dy);
int dsn_filtered_tile_gradient_fixed(const dsn_noise *noise, const dsn_grid *grid, uint32_t max_taps,
                                     uint32_t width, uint32_t height, int32_t *out, int32_t *dx, int32_t *dy);
int dsn_filtered_tile_gradient_float(const dsn_noise *noise, const dsn_grid *grid, uint32_t max_taps,
                                     uint32_t width, uint32_t height, float *out, float *dx, float *dy);
#endif
#endif

/* ==== End of the gradients =========================================================================== */

/* ==== Mixing (several materials blended in space) ===================================================
   Sand turning to gravel, moss over stone: up to DSN_MIX_MAX_MATERIALS noises mixed as Texton Noise
   mixes them (Galerne, Leclaire and Moisan, "Texton Noise", Computer Graphics Forum 2017): one Poisson
   process of impulses, each impulse carrying the texton of one material, drawn from the mixing weights
   at the impulse's own position with a hash of its own. A point then sees a spot noise whose covariance
   is the weights' mixture of the materials' covariances: no crossfade blur, no loss of contrast in a
   transition (a crossfade of two independent noises w A + (1 - w) B has the variance w^2 + (1 - w)^2 of
   theirs, half of it at w = 1/2), and one walk of impulses instead of one per material.

   Definition. The materials are configured noises (dsn_noise_init, each with its asset, flags and colour
   transform); material 0 leads: its seed, density lambda, cells and periods make the impulse process of
   the whole mix, walked with the largest reach among the materials. Each material m is normalized for
   that density (its gain K_m scale_m / sqrt(lambda), as dsn_noise_init computes it for its own), so that
     out_c(x) = sum_m [ w_m(x) offset_m,c + sum_k gain_m,ck S_m,k(x) ],
     offset_m,c = mean_m,c - sum_k gain_m,ck lambda sum_y t_m,k(y),
   each material's term rounded to Q16.16 as a noise's value is, then summed (saturated to int32), where
   S_m(x) is the sum of the textons t_m of the impulses that picked material m (read as the mode reads
   them: bilinear in continuous mode, the lattice texton in lattice mode) and w_m(x) the mixing weights at
   the evaluated point, in Q2.14, summing to exactly 1. Where the weights are those of one material m over
   the reach of the point, the noise is exactly a noise of material m at density lambda: its mean and
   covariance are material m's (Campbell's theorem, as for one noise); for material 0 it is bit for bit
   material 0's own noise. Where the weights mix, the impulses that pick material m form a Poisson process
   of intensity w_m lambda, independent of the others' (thinning), so the mean is the weights' mixture of
   the means and the covariance at lag h the mixture sum_m w_m C_m(h) (with weights that vary slowly over
   the reach).
   Configure material 0 at the density the mix should have: the other materials' impacts per pixel are
   then lambda |S_m|, whatever their configuration said.

   The weights. A dsn_mix_control is a grid of 8-bit weights per material (any non-negative scale: they
   are normalized where they are read), samples 2^spacing_shift texels apart with sample (0, 0) at texel
   (origin_x, origin_y), read bilinearly with 8-bit fractions (the precision of a GPU's texture filter):
   at a position p, the sample coordinate u = (p - origin) / 2^spacing_shift, samples i = floor(u) and
   i + 1 weighted by 256 - f and f, f = floor(256 (u - i)), per axis; samples past the grid's edge are
   the edge's (clamped) unless the axis is periodic (DSN_MIX_PERIODIC_X / _Y: index modulo the grid's
   size). That gives V_m(p) = (sum over the 4 samples of weight * (256 - f or f)(256 - g or g)) / 256,
   an integer in [0, 65280], and T(p) = sum_m V_m(p).
   - An impulse at lattice position p (the floor of its position: the same material in both modes, the
     lattice impulse being the floor of its continuous twin) picks the first m with
     floor(h T(p) / 2^32) < V_0(p) + ... + V_m(p), h = mix32(key + (2^31 + 2^30 + k) 0x9E3779B9) for
     impulse k of the cell with this key (the stream its positions' fractions come from, at other
     indices; dsn.glsl's dsn_cell_stream), so the probability is V_m / T to 2^-14. Where T(p) = 0 (no
     weight at all) it picks material 0.
   - The point's weights: w_m(x) = floor(2^14 (V_0 + .. + V_m) / T) - floor(2^14 (V_0 + .. + V_m-1) / T)
     at the point (its continuous position, its lattice point in lattice mode), so they sum to 2^14;
     where T(x) = 0, w_0 = 2^14.
   Positions are taken on the torus as everywhere (p - origin modulo 2^32 texels, read as signed), so a
   clamped grid extends its edges for 2^31 texels each way; a periodic noise is evaluated with its
   impulses at their positions seen from the point (the mix is periodic when the grid is too).
   Making a grid from an image: one 8-bit channel per material, interleaved, sample (i, j) the pixel
   (i, j); spacing_shift 0 puts a sample on every texel, larger shifts stretch it (2^spacing_shift texels
   per pixel). dsn_mix_weight_from_float turns float weights into its bytes. dsn-render --mix renders a
   mix from a PNG of weights (README).

   Materials of different kinds. Grey and RGB materials mix: the mix has 3 channels if any material has,
   and a grey material adds its one value to each. 8- and 16-bit textons, lattice and bilinear bakes, any
   sizes mix. Materials with a histogram mapping are refused (DSN_ERR_UNSUPPORTED): configure them with
   DSN_FLAG_NO_HISTOGRAM. The continuous and filtered functions check every material as
   dsn_continuous_check does.

   Cost. Where every weight sample around a point (the samples its impulses and itself read) holds one
   material's weights alone, the point is that material's noise on material 0's impulses, and the mix
   calls that material's own evaluator (a tile whose reach is so: its own tile function, splatted or by
   strips): the mix then costs what one material costs, plus the check of the samples. Elsewhere one walk
   over the cells within the largest reach: each impulse within it reads its weights (four samples per
   material, once per point where the samples around it agree), a hash, and one texton. A lattice point
   whose materials' lattice textons share one size, channel count and value size takes the kernels'
   vector walk, as one noise's point does (16 impulses of a cell tested at once; where the samples agree,
   the AVX2 and AVX-512 copies hash the 16 impulses' materials at once too); so does a continuous point
   with 8-bit textons of one size and channel count, in the AVX2 and AVX-512 copies (the continuous
   point's vector evaluator, each of 8 or 16 candidates gathering its own material's texels: the textons
   must lie within 2^30 bytes of material 0's); other points walk in scalar code. Where the samples
   around a point differ, each impulse in reach reads its weights at its position: in those AVX2 and
   AVX-512 walks 8 or 16 impulses at once (the samples gathered from the caller's grid, never past its
   last byte), where the grid holds 4 bytes or more and a periodic axis's samples around the point do not
   wrap more than once (grid width or height at least the reach's span in samples, and the point not
   within the reach of the int32 wrap of x - origin), else one by one. Tiles and batches walk their points
   in groups. A lattice tile whose samples agree over its reach and whose
   impulses draw two materials of the mix's channel count, 8-bit textons that the x86 strip path holds
   (tile_render.h), goes by that path for both at once, with or without scratch: each rectangle's impulses
   listed per material (a hash test per impulse), each material's strips summed from its texton and
   normalized with its gains and weighted offset, the two added before they are stored. Other lattice
   tiles go in bands of up to 128 rows when `scratch` holds dsn_mix_lattice_tile_scratch_size() bytes
   (less scratch, fewer rows a band): a band whose samples agree over its reach by the same two-material
   strips where they take it, else as one lattice tile of each material that impulses draw, from those
   impulses alone, by that material's own tile code (strips or splats) normalized with its weighted
   offset, then each value the sum of the materials'; the other bands are walked in bands of up to 32
   rows (each impulse found once per band, its texton added to the points it reaches, 16 8-bit values a step).
   Without scratch a lattice tile's rows go in runs of up to 32 points (each impulse found once per run). A
   continuous tile whose samples agree over its reach, given dsn_mix_continuous_tile_scratch_size() bytes of
   scratch, is splatted as one material's tile is, block by block, each material's impulses (a hash test
   per impulse) into its own block sums with its texton, each normalized with its weighted offset, then
   each value the sum of the materials'. Other continuous tiles' rows and a batch's neighbours go in
   groups of up to 16
   points within 32 texels of each other (each impulse found once per group, read at the points it
   reaches; where the vector evaluator takes the mix and the group's samples agree, or its impulses read
   their weights 8 or 16 at once, each point by it instead, faster); other points go one by one. make bench's
   mix_bench reports both against one material, and the stack it paints: a lattice point call under 3 KB, a
   continuous one under 7 KB, a filtered one about 27 KB on x86 where the weights are uniform (a material's
   sifted walk, as one material's filtered point call, about 24 KB, which it makes where the weights are one
   material's), about 43 KB where two materials alike share that walk (both materials' candidates) and 18 KB
   where they vary, a mixed tile call under 4 KB but where a tile or band goes by
   material passes (then a material's tile call's, as dsn_lattice_tile_fixed's, and a copy of the material) or
   by the two-material strips (two materials' strip paths: about 128 KB on x86, twice one material's tile
   call), and a continuous tile splatted by materials (the cell records of two materials: about 160 KB on x86,
   under twice one material's). Gradients have no mix yet. Where the weights are uniform over its reach, the
   filtered mix sums each material as one material's filtered point does (every tap at once, the AVX2 and
   AVX-512 copies listing the candidates on vectors), over the impulses whose hashes draw that material (two
   materials with 8-bit levels of one size and channels in one walk there, each candidate listed into its
   material's list); where
   they vary, it finds each impulse once per tap (within the largest of the materials' reaches), picks the
   materials of a tap's impulses together (8 at a time from the control in the AVX2 and AVX-512 copies),
   then reads each material's impulses, on vectors for 8-bit levels in those copies. dsn/dsn.glsl
   evaluates the lattice and continuous mix per point with these bits, from the words of dsn_gpu_mix_pack
   (dsn/gpu.h). Not in the small build (DSN_MIXING). */
#if DSN_MIXING
#define DSN_MIX_MAX_MATERIALS 4
#define DSN_MIX_WORDS (DSN_MIX_MAX_MATERIALS * DSN_NOISE_WORDS + 4) /* 64-bit words */
/* The configured mix: caller-owned storage filled by dsn_mix_init, private like dsn_noise's. It holds
   copies of its materials (the noises may go after init; their assets' bytes must stay). */
typedef union dsn_mix {
    uint64_t words[DSN_MIX_WORDS];
    void *align_pointer;
} dsn_mix;

#define DSN_MIX_PERIODIC_X 1u /* the grid repeats along x (index modulo width); else its edge extends */
#define DSN_MIX_PERIODIC_Y 2u
typedef struct dsn_mix_control {
    const uint8_t *weights;     /* width * height samples, row-major, each `materials` bytes (one per
                                   material, in the mix's order) */
    uint32_t width, height;     /* samples per row and rows: 1 .. 65535 */
    uint32_t spacing_shift;     /* samples 2^spacing_shift texels apart: 0 .. 16 */
    int32_t origin_x, origin_y; /* the texel where sample (0, 0) lies */
    uint32_t flags;             /* DSN_MIX_PERIODIC_X | DSN_MIX_PERIODIC_Y; other bits are an error */
} dsn_mix_control;

/* Configures a mix of `count` (1 .. DSN_MIX_MAX_MATERIALS) configured noises, materials[0] leading (see
   above). Returns DSN_OK, DSN_ERR_NULL (null mix or materials, or a material not configured),
   DSN_ERR_ARGUMENT (count out of range), DSN_ERR_UNSUPPORTED (a material with a histogram mapping) or
   DSN_ERR_COST (the walk with the largest reach at material 0's density would examine more than
   DSN_MAX_POINT_IMPULSES impulses per point). On failure `mix` is zeroed and the functions refuse it. */
int dsn_mix_init(dsn_mix *mix, const dsn_noise *const *materials, uint32_t count);
/* The channels each evaluation writes per point (1 or 3); 0 for a mix not configured. */
uint32_t dsn_mix_channels(const dsn_mix *mix);
/* A float weight as the control's byte: round(255 w) for w in [0, 1]; 0 for negative weights and NaN,
   255 above 1. */
uint8_t dsn_mix_weight_from_float(float weight);

/* The mix at a point, as the noise functions of the same name (coordinates, outputs). Errors: DSN_ERR_NULL
   (null mix, control, weights or out, or a mix not configured), DSN_ERR_ARGUMENT (a control out of its
   ranges), DSN_ERR_CONTINUOUS_MISMATCH (continuous: a material that dsn_continuous_check refuses); on
   an error every channel of a configured mix (else out[0]) is zeroed. */
int dsn_mix_lattice_point_fixed(const dsn_mix *mix, const dsn_mix_control *control, int32_t x, int32_t y,
                                int32_t *out);
int dsn_mix_lattice_point_float(const dsn_mix *mix, const dsn_mix_control *control, int32_t x, int32_t y,
                                float *out);
int dsn_mix_continuous_point_fixed(const dsn_mix *mix, const dsn_mix_control *control, int64_t x, int64_t y,
                                   int32_t *out);
int dsn_mix_continuous_point_float(const dsn_mix *mix, const dsn_mix_control *control, double x, double y,
                                   float *out);
int dsn_mix_lattice_point_u8(const dsn_mix *mix, const dsn_mix_control *control, int32_t x, int32_t y,
                             uint8_t *out);
int dsn_mix_continuous_point_u8(const dsn_mix *mix, const dsn_mix_control *control, int64_t x, int64_t y,
                                uint8_t *out);
/* Batches: `count` points (xs[k], ys[k]), anywhere and in any order, into out[k * channels], each exactly
   the point function's (no scratch; point by point). The point functions' errors, null xs or ys with a
   count DSN_ERR_NULL, all `count` points zeroed. */
int dsn_mix_continuous_batch_fixed(const dsn_mix *mix, const dsn_mix_control *control, const int64_t *xs,
                                   const int64_t *ys, uint32_t count, int32_t *out);
int dsn_mix_continuous_batch_float(const dsn_mix *mix, const dsn_mix_control *control, const double *xs,
                                   const double *ys, uint32_t count, float *out);
int dsn_mix_continuous_batch_u8(const dsn_mix *mix, const dsn_mix_control *control, const int64_t *xs,
                                const int64_t *ys, uint32_t count, uint8_t *out);
/* Tiles: the lattice tile's and the continuous grid's pixels and layout (width, height 1 ..
   DSN_TILE_MAX_SIDE, else DSN_ERR_TILE_SIZE with the output untouched), each pixel exactly the point
   function's, with the point functions' other errors (the whole output zeroed). A tile whose reach has
   one material's weights alone is that material's tile, splatted or by strips as the noise's own, when
   `scratch` holds dsn_mix_*_tile_scratch_size() bytes (the largest of the materials' scratch sizes and,
   for a lattice tile, of the values of a band of up to 128 rows: 4 bytes per channel of every material
   per point; for a continuous one, of every material's block sums; 0 for an invalid mix or size); other tiles
   go by bands or groups of points (see "Cost" above), with too little scratch (null, 0 is fine) by runs or
   point by point. Any scratch gives the same bits. */
size_t dsn_mix_lattice_tile_scratch_size(const dsn_mix *mix, uint32_t width, uint32_t height);
size_t dsn_mix_continuous_tile_scratch_size(const dsn_mix *mix, const dsn_grid *grid, uint32_t width,
                                            uint32_t height);
int dsn_mix_lattice_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                               uint32_t width, uint32_t height, int32_t *out, void *scratch,
                               size_t scratch_size);
int dsn_mix_lattice_tile_float(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                               uint32_t width, uint32_t height, float *out, void *scratch,
                               size_t scratch_size);
int dsn_mix_continuous_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                                  uint32_t width, uint32_t height, int32_t *out, void *scratch,
                                  size_t scratch_size);
int dsn_mix_continuous_tile_float(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                                  uint32_t width, uint32_t height, float *out, void *scratch,
                                  size_t scratch_size);
int dsn_mix_lattice_tile_u8(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                            uint32_t width, uint32_t height, uint8_t *out, void *scratch,
                            size_t scratch_size);
int dsn_mix_continuous_tile_u8(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                               uint32_t width, uint32_t height, uint8_t *out, void *scratch,
                               size_t scratch_size);
#if DSN_FILTERING
/* The filtered evaluation of a mix (dsn.h's "Filtered evaluation" per material): each material's filtered
   value over the impulses that picked it, its offsets and mean weighted by its weight at the point (each
   floored to the offsets' units, as the unfiltered mix weights them), rounded as a noise's filtered value,
   then summed; a footprint of at most one texel gives the continuous mix's bits, and where the weights are
   one material's alone over the point's filtered reach (every tap and the reach of its levels) it is that
   material's own filtered point (tiles: its own filtered tile, with enough scratch). The filtered
   functions' errors (a bad footprint: DSN_ERR_NULL or DSN_ERR_ARGUMENT) and the mix's. Far minified, the
   mix fades to the weights' mixture of the means. */
int dsn_mix_filtered_point_fixed(const dsn_mix *mix, const dsn_mix_control *control, int64_t x, int64_t y,
                                 const dsn_footprint *footprint, int32_t *out);
int dsn_mix_filtered_point_float(const dsn_mix *mix, const dsn_mix_control *control, double x, double y,
                                 const dsn_footprint *footprint, float *out);
int dsn_mix_filtered_point_u8(const dsn_mix *mix, const dsn_mix_control *control, int64_t x, int64_t y,
                              const dsn_footprint *footprint, uint8_t *out);
size_t dsn_mix_filtered_tile_scratch_size(const dsn_mix *mix, const dsn_grid *grid, uint32_t max_taps,
                                          uint32_t width, uint32_t height);
int dsn_mix_filtered_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                                uint32_t max_taps, uint32_t width, uint32_t height, int32_t *out,
                                void *scratch, size_t scratch_size);
int dsn_mix_filtered_tile_float(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                                uint32_t max_taps, uint32_t width, uint32_t height, float *out, void *scratch,
                                size_t scratch_size);
int dsn_mix_filtered_tile_u8(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                             uint32_t max_taps, uint32_t width, uint32_t height, uint8_t *out, void *scratch,
                             size_t scratch_size);
#endif
#endif

/* ==== End of the mixing ============================================================================== */

/* ==== Surface noise (no parameterization) ==========================================================
   The noise on any surface, with no texture coordinates: no seam where a parameterization cuts, no
   pinch where it collapses (a sphere's poles), and meshes without an unwrap. As surface Gabor noise
   (Lagae, Lefebvre, Drettakis and Dutre, SIGGRAPH 2009) and Texton Noise (Galerne, Leclaire and Moisan,
   Computer Graphics Forum 2017) do, the impulses are scattered in 3-D space, and each one near the
   shading point is projected on the surface's tangent plane there, where its texton is read.

   Definition. Space is cut into cubes of side c = 2^cell_shift texels (the noise's cells: dsn_noise_init),
   cube (i, j, k) holding an exact Poisson number of impulses with the plane's cell mean lambda c^2 (the
   same table), at positions uniform in the cube with 16 - cell_shift fractional bits per axis, all from
   stateless hashes of (cube, seed, index) as in the plane. That is a 3-D Poisson process of intensity
   lambda / c per cubic texel. At a point p with a frame (tangent T, bitangent B = N x T, normal N), an
   impulse q at d = p - q contributes
       t(d . T, d . B) * W(|d . N| / H),
   t the texton read bilinearly as in the continuous mode (Q32.32 offsets along T and B), and W a window
   across the slab |d . N| < H:
       W(s) = 1 for s <= 1/2,   1 - (3 u^2 - 2 u^3) with u = 2 s - 1 for 1/2 < s < 1,   0 for s >= 1,
   which goes to 0 with zero slope at the slab's faces, so an impulse enters and leaves the sum smoothly
   as the surface curves. Its integrals are I1 = integral W = 3/2 and I2 = integral W^2 = 48/35 (s over
   [-1, 1]), and the slab's half-thickness is H = c / I2 = 35 c / 48 texels.
   Why these. On a plane, the impulses within the slab project to a 2-D Poisson process of intensity
   (lambda / c) 2H, each carrying the weight W of its height, uniform across the slab. Campbell's theorem
   then gives the expected sum lambda (H I1 / c) sum t and the covariance lambda (H I2 / c) (t * t~)(h):
   with H = c / I2 the covariance is exactly the plane noise's, lambda (t * t~)(h), so the plane
   noise's gain normalizes it; the expected sum is (I1 / I2) = 35/32 times the plane's, which the
   surface offset subtracts. So on any plane, in any orientation and with any tangent, the surface noise
   has the 2-D continuous noise's mean, variance, covariance between channels and spectrum (not its
   bits: the impulses are others). On a curved surface each point's value is still a sample of that
   noise (the process is invariant under rotations and translations), so the variance is the same
   everywhere, poles included; neighbours decorrelate slightly faster where the surface bends within a
   texton's reach.

   Arithmetic. Positions are Q32.32 texels per axis (every int64 a point: 3-D space is the torus of 2^32
   texels per axis, as the plane is); the frame is Q2.30 (2^30 = 1), from float vectors by
   dsn_surface_frame_from_float, computed from their bits with integer operations. For each impulse:
   d's components floored to 16 fractional bits, the three dot products taken exactly in 64-bit integers
   and floored to Q32.32 (u, v, w); the bilinear texton at (u, v) as the continuous mode reads it (its
   sums Q.32 per channel, then floored); s = floor(floor(|w| / 2^16) 89878 / 2^(16 + cell_shift)) in
   Q16 (89878 = 2^16 48/35 rounded); W in Q16 from s with the polynomial above (floors at each product
   by 2^16); the contribution floor(texton sum * W / 2^16) added to the channel sums modulo 2^64. The
   sums are normalized with the noise's gain (the continuous mode's normalization of Q.32 sums) and the
   surface offset offset_c - floor(3 (mean_c - offset_c) / 32) in the noise's gain units (mean_c the asset
   mean there), then mapped by the asset's histogram mapping if it has one. Periods (dsn_config) do not
   apply on surfaces. The same bits on every target.

   The frame. With a tangent, T is the tangent's part orthogonal to N, normalized (for anisotropic
   materials: the texton's x axis follows it). Without one, or where the tangent is within 2^-12 rad of
   the normal (zero, parallel), T is the x axis made orthogonal to N: (rho, -n_x c, -n_x s), with (c, s) the
   direction of (n_y, n_z) and rho its length, computed from the float normal's n_y and n_z at their own
   precision; T = (0, 0, -1) at N = (1, 0, 0) and (0, 0, 1) at N = (-1, 0, 0). On a ground whose normal is
   y (or z) the texton's x axis is then the world's x, as on the plane, and the frame turns continuously
   with N everywhere but next to N = (1, 0, 0) and (-1, 0, 0), around which it turns once (every frame made
   from the normal alone must have such points: the hairy ball theorem). An isotropic-looking material
   hides them; for an anisotropic one, pass a tangent field, or orient the scene so that they face away.
   The normal need not be unit (any finite non-zero vector: its direction), nor the tangent.

   Cost: the cubes within the reach of the point's oriented box (the texton's reach along T and B, H
   along N) are walked, each cube first tested against that box; a cube's impulses are placed and tested
   against the slab and the texton's reach 8 at a time on AVX-512 (4 on AVX2), and those kept, gathered
   from cube to cube (about 2 a cube), are read as many at a time (8-bit textons and levels), else one by
   one: make bench's surface_bench reports a point at 4-9 times a continuous point (a filtered one at 5-8
   times the plane's filtered point: its taps share one walk over a box that holds each one's, where they
   lie within a tap's reach of the point). Stack: under 2.5 KB, a filtered point under 4.5 KB (the sums of
   up to 16 taps). Not in the small build (DSN_SURFACE).
   dsn/dsn.glsl evaluates the unfiltered point and the frame in a shader with the same bits
   (dsn_surface_point, dsn_surface_frame_from_float_bits: dsn/gpu.h packs what they read). */
#ifndef DSN_SURFACE /* 1: the surface noise (this section); default 0 in the small build */
#define DSN_SURFACE (!DSN_SMALL_CODE)
#endif
#if DSN_SURFACE
#define DSN_FRAME_ONE (1 << 30) /* 1.0 in a frame's Q2.30 components */
typedef struct dsn_surface_frame {
    int32_t tangent[3], bitangent[3], normal[3]; /* Q2.30, each component in [-2^30, 2^30] */
} dsn_surface_frame;

/* The frame of a surface point from its normal (any finite non-zero vector) and an optional tangent
   (null: the frame from the normal alone, as above). Returns DSN_OK, DSN_ERR_NULL (null normal or
   frame) or DSN_ERR_ARGUMENT (a zero normal, or a NaN or infinite component of the normal or of the
   tangent); on an error a non-null *frame is zeroed. A tangent at most 2^-12 rad from the normal (or
   zero) counts as none. */
int dsn_surface_frame_from_float(const float *normal, const float *tangent, dsn_surface_frame *frame);

/* out[channels]: the surface noise at position[0 .. 2] (Q32.32 texels) in `frame`. Any frame with
   components in [-2^30, 2^30] has a defined value (the statistics above hold for the unit frames that
   dsn_surface_frame_from_float makes). Returns DSN_OK, DSN_ERR_NULL (null noise, position, frame or out,
   or a noise not configured), DSN_ERR_CONTINUOUS_MISMATCH (as dsn_continuous_check), DSN_ERR_ARGUMENT
   (a frame component out of range) or DSN_ERR_COST (the walk would visit more than
   DSN_MAX_POINT_IMPULSES cubes, or examine more impulses than that on average: a dense noise that
   dsn_noise_init accepts for the plane may be too dense for the slab); on an error every channel (out[0]
   for a noise not configured) is zeroed. */
int dsn_surface_point_fixed(const dsn_noise *noise, const int64_t *position, const dsn_surface_frame *frame,
                            int32_t *out);
/* The same from float64 positions (dsn_coordinate_from_double) and float vectors
   (dsn_surface_frame_from_float; null tangent allowed), output as float (exactly fixed / 65536 rounded);
   the errors of both. */
int dsn_surface_point_float(const dsn_noise *noise, const double *position, const float *normal,
                            const float *tangent, float *out);
/* The same at a Q32.32 position and a frame, as 8-bit values (dsn_fixed_to_u8). */
int dsn_surface_point_u8(const dsn_noise *noise, const int64_t *position, const dsn_surface_frame *frame,
                         uint8_t *out);
/* `count` points: positions[3 k .. 3 k + 2] and frames[k] into out[k * channels], each exactly the
   point function's; null arrays with a count are DSN_ERR_NULL, and every error zeroes all count points. */
int dsn_surface_batch_fixed(const dsn_noise *noise, const int64_t *positions, const dsn_surface_frame *frames,
                            uint32_t count, int32_t *out);
#if DSN_FILTERING
/* The surface noise filtered by a pixel's footprint in the tangent plane (needs the asset's pyramid, as
   dsn_filtered_point_fixed): `footprint` gives the texels per pixel along the frame's tangent (its x) and
   bitangent (its y), for the screen's x (column_step_x, column_step_y) and y (row_step_x, row_step_y); a
   renderer projects its position differentials (ray differentials, or ddx and ddy) on the tangent and
   bitangent. The filtered evaluation's plan, as "Filtered evaluation" states it (level of detail, up to
   max_taps taps along the long axis, two levels blended linearly, the mean past the pyramid), with tap k at
   the point moved by its offset along the tangent and bitangent (each floored to Q.16, projected, floored
   to Q32.32), each level read at the impulses of that tap's slab as the plane's filtered walk reads it,
   weighted by the window, and normalized from the level's offset less 3/32 of its expected sum, as the
   unfiltered surface offset. A footprint of at most a texel gives dsn_surface_point_fixed's bits. Errors:
   the point function's, and the filtered functions' for a bad footprint (DSN_ERR_NULL, DSN_ERR_ARGUMENT);
   DSN_ERR_COST when one tap's walk would visit more than DSN_MAX_POINT_IMPULSES cubes or examine more
   impulses than that (a coarse level of a dense noise). */
int dsn_surface_filtered_point_fixed(const dsn_noise *noise, const int64_t *position,
                                     const dsn_surface_frame *frame, const dsn_footprint *footprint,
                                     int32_t *out);
int dsn_surface_filtered_point_float(const dsn_noise *noise, const double *position, const float *normal,
                                     const float *tangent, const dsn_footprint *footprint, float *out);
#endif
#endif

/* ==== End of the surface noise ======================================================================= */

/* ==== Histogram-preserving output (format 1.2) =======================================================
   A spot noise is Gaussian: it keeps an exemplar's mean, colours' covariance and spectrum, but not the
   histogram of each colour (a bimodal or skewed exemplar comes out as a softer Gaussian one). An asset
   of format 1.2 carries the mapping of Heitz and Neyret ("High-Performance By-Example Noise using a
   Histogram-Preserving Blending Operator", HPG 2018): the baker decorrelated the exemplar's colours,
   Gaussianized each decorrelated channel through its empirical CDF and baked the texton of that
   Gaussianized exemplar; the runtime evaluates that Gaussian noise as always (g_k, "Gaussian-space"
   values), then maps each channel through a lookup table (the inverse CDF) and rotates the result back
   to colours: out_c = centre[c] + sum_k P[c][k] T_k(g_k). format.h states the integer arithmetic
   exactly; the asset's fields are in dsn_asset (histogram_*).

   How to call it: nothing changes. dsn_asset_load reads the mapping, dsn_noise_init keeps it in the
   noise, and every evaluation function applies it to its output: lattice and continuous, point, tile
   and batch, filtered, fixed, float and 8-bit, with the same guarantees (same bits everywhere, tiles
   and batches equal to their points, integer arithmetic only). Configure with DSN_FLAG_NO_HISTOGRAM to
   get the Gaussian-space values instead (the noise of the texton itself: for analysis, or for
   dsn.glsl, which does not apply the mapping; dsn_gpu_pack refuses a noise that has one with
   DSN_ERR_UNSUPPORTED). A runtime built with DSN_HISTOGRAM 0 (the small build's default) refuses such
   assets at load time, DSN_ERR_UNSUPPORTED, rather than show Gaussian-space values as colours.

   The filtered evaluation filters in Gaussian space and maps the result with tables prefiltered per
   level (Deliot and Heitz, "Procedural Stochastic Textures by Tiling and Blending", GPU Zen 2): a
   footprint that blends levels l and l + 1 with weight w maps its value g with (1 - w) T_l(g) +
   w T_(l+1)(g), the levels past the asset's tables being the constant `expected` (each channel's mean
   after the mapping), so that minified texture fades to centre + P expected (dsn_noise_mean_float):
   the exemplar's mean colour, which the mapping of the Gaussian mean is not when T is not linear.
   Unfiltered footprints give exactly the continuous mode's mapped bits.

   Cost: per pixel, a table read and interpolation per channel and a 3 x 3 rotation in 64-bit integers;
   lattice tiles then normalize pixel by pixel instead of in SIMD lanes (make bench reports the ratio). */

/* ==== End of the histogram-preserving output ========================================================= */

#ifdef __cplusplus
}
#endif

#endif /* DSN_DSN_H */
