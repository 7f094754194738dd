/* runtime/setup/noise_state.h - what dsn_noise_init stores in the caller's dsn_noise: the configured noise as
   the runtime reads it. Public code sees only DSN_NOISE_WORDS opaque words (dsn.h); this is their layout.
   Internal to libdsn (and to white-box tests); not installed. */
#ifndef DSN_NOISE_STATE_H
#define DSN_NOISE_STATE_H

#include <stdint.h>

#include "dsn/dsn.h"
#include "setup/format_bytes.h" /* the evaluators read texton values with these */

struct dsn_noise_state {
    uint32_t seed;
    uint32_t seed_column, seed_row; /* hashes of the seed mixed into the cell keys */
    uint32_t flags;
    uint32_t tile_kernel; /* the copy of the tile code this CPU runs (set by init; the bits are the same) */
    uint32_t impacts_q16;
    uint32_t period[2];  /* 0 = not periodic */
    uint32_t cell_shift; /* cells are (1 << cell_shift) lattice points wide */
    uint32_t radius[2];  /* (width - 1) / 2, (height - 1) / 2 */
    uint32_t gain_shift; /* fraction bits of gain and offset */
    /* The asset after the small fields that every evaluation reads: on Thumb-1 (the small build) a load
       reaches 124 bytes past a pointer, so what sits first costs the least code. */
    dsn_asset asset;
    int64_t gain[9];           /* fixed-point K * scale / sqrt(lambda), see runtime/setup/normalize.cpp */
    int64_t offset[3];         /* fixed-point mean minus the expected sum */
    uint32_t poisson_parts;    /* a cell's count is the sum of this many draws from the table */
    uint32_t poisson_size;     /* entries used in poisson_cdf */
    uint32_t poisson_cdf[96];  /* inverse-CDF thresholds of one draw, 32-bit */
    uint8_t poisson_guide[64]; /* first candidate count per top-6-bit bucket of the uniform */
    /* The filtered evaluation (DSN_FILTERING): offset of pyramid level l + 1, as `offset` is level 0's
       (the mean minus the level's own expected sum; zero without DSN_FILTERING or without a pyramid). */
    int64_t level_offset[8][3];
    /* The filtered evaluation: per level 0 .. 8, the all-zero columns (x) and rows (y) on each side of
       its window, read as if absent (the same values, a shorter reach). */
    uint8_t level_margin[9][2];
    /* dsn_internal_state_check of the fields above, stored last by dsn_noise_init (DSN_NOISE_CHECK). */
    uint32_t check;
};

static_assert(sizeof(dsn_noise_state) <= sizeof(dsn_noise), "dsn_noise must hold dsn_noise_state");
static_assert(alignof(dsn_noise_state) <= alignof(dsn_noise),
              "dsn_noise must be aligned for dsn_noise_state");

/* The state inside a caller's dsn_noise (null stays null). The caller's words are only ever written and
   read as this struct, by the runtime. */
inline const dsn_noise_state *dsn_state(const dsn_noise *noise) {
    return static_cast<const dsn_noise_state *>(static_cast<const void *>(noise));
}
inline dsn_noise_state *dsn_state(dsn_noise *noise) {
    return static_cast<dsn_noise_state *>(static_cast<void *>(noise));
}

/* DSN_NOISE_CHECK 1: init stores a check value over the state's key fields and every entry point
   verifies it, so that a dsn_noise never configured (garbage bytes) is refused rather than read, unless
   its garbage happens to match (one chance in 2^32). The small build (DSN_SMALL_CODE) leaves it out for
   its 8 KB: there a noise is refused only when zeroed (its texton null). */
#ifndef DSN_NOISE_CHECK
#define DSN_NOISE_CHECK (!DSN_SMALL_CODE)
#endif

#if DSN_NOISE_CHECK
/* A 32-bit hash of the fields the evaluators index or size with (the asset's pointers and sizes, the
   cells, the periods, the tables' sizes), never of where the noise lies, so a memcpy of a
   configured noise stays configured (noise_init.cpp). */
uint32_t dsn_internal_state_check(const dsn_noise_state *noise);
#endif

/* Whether `noise` is a configured noise that the evaluators may read: not null, a texton (a zeroed noise
   has none: init failed, or the caller zeroed it) and, with DSN_NOISE_CHECK, its check value. */
inline bool dsn_configured(const dsn_noise_state *noise) {
#if DSN_NOISE_CHECK
    return noise != 0 && noise->asset.texton != 0 && noise->check == dsn_internal_state_check(noise);
#else
    return noise != 0 && noise->asset.texton != 0;
#endif
}

/* The values per point that an evaluator zeroes on an error: the channels of a configured noise, else the
   one value that every caller's array holds (a garbage channel count must not size a write). */
inline uint32_t dsn_values_per_point(const dsn_noise_state *noise) {
    return dsn_configured(noise) ? noise->asset.channels : 1u;
}

/* The texton a lattice walk reads, by itself: its values (channels and bits as the asset's), its window
   and its radius. */
typedef struct dsn_texton_window {
    const unsigned char *values;
    uint32_t width, height, radius[2];
} dsn_texton_window;

/* The continuous evaluators' texton: the asset's texton. */
inline dsn_texton_window dsn_continuous_texton_window(const dsn_noise_state *noise) {
    const dsn_asset *asset = &noise->asset;
    const dsn_texton_window texton = {
        asset->texton, asset->width, asset->height, {noise->radius[0], noise->radius[1]}};
    return texton;
}

/* The lattice evaluators' texton: the asset's lattice texton (format 1.3) where it has one, else its
   texton. The per-point walk reads it so, without a copy of the noise (dsn_internal_lattice_view). */
inline dsn_texton_window dsn_lattice_texton_window(const dsn_noise_state *noise) {
    const dsn_asset *asset = &noise->asset;
    if (asset->lattice_texton == 0) return dsn_continuous_texton_window(noise);
    const dsn_texton_window lattice = {asset->lattice_texton,
                                       asset->lattice_width,
                                       asset->lattice_height,
                                       {(asset->lattice_width - 1) / 2, (asset->lattice_height - 1) / 2}};
    return lattice;
}

/* A build with neither the filtered evaluation nor the histogram mapping (the small build) reads no
   section of an asset (format.h), the lattice texton of format 1.3 included. */
#define DSN_READS_SECTIONS (DSN_FILTERING || DSN_HISTOGRAM)

#if DSN_READS_SECTIONS
/* The noise as the lattice evaluators read it: the noise itself, or, for an asset that carries a lattice
   texton (format 1.3: a bilinear bake), a copy in `view` whose texton is that one (its window, a
   rectangle, and its radius). Everything else stays: the cells, the Poisson table, the density of the
   asset's own support and the normalization (the two textons' sums are equal, format.h). In
   noise_init.cpp. */
const dsn_noise_state *dsn_internal_lattice_view(const dsn_noise_state *noise, dsn_noise_state *view);
#else
/* A 1.3 bilinear asset has a lattice texton that this build has not read: its lattice evaluators refuse
   it (DSN_ERR_UNSUPPORTED) rather than read the bilinear texton. */
inline int dsn_lattice_texton_unread(const dsn_noise_state *noise) {
    return noise->asset.interpolation == DSN_INTERPOLATION_BILINEAR &&
           noise->asset.version_minor >= DSN_FORMAT_LATTICE_TEXTON_MINOR;
}
#endif

#endif /* DSN_NOISE_STATE_H */
