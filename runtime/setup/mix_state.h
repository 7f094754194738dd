/* runtime/setup/mix_state.h - what dsn_mix_init stores in the caller's dsn_mix (dsn.h, "Mixing"): each
   material as a copy of its configured noise, normalized for the density of material 0, and the reach of
   the mix's walks. Internal to libdsn; not installed. */
#ifndef DSN_MIX_STATE_H
#define DSN_MIX_STATE_H

#include <stdint.h>

#include "setup/noise_state.h"

#if DSN_MIXING

#if !DSN_READS_SECTIONS
#error "DSN_MIXING needs a build that reads sections (DSN_FILTERING or DSN_HISTOGRAM): the lattice textons"
#endif

struct dsn_mix_state {
    uint32_t count;             /* materials, 1 .. DSN_MIX_MAX_MATERIALS */
    uint32_t channels;          /* 3 when any material has 3, else 1 */
    uint32_t radius[2];         /* the continuous walk's reach: the largest texton radius per axis */
    uint32_t lattice_radius[2]; /* the lattice walk's: the largest lattice texton radius per axis */
    uint32_t check;             /* dsn_internal_mix_check, stored last by dsn_mix_init */
    uint32_t alike;             /* dsn_mix_alike_* bits: what the kernels' mixed points need of the textons */
    /* Material 0 leads: its seed, cells, Poisson table and periods are the mix's impulse process. Each
       material is a copy of its noise on that process (those fields material 0's), normalized for its
       density (gain, gain_shift and offset), with its check value over them: a noise that the evaluators
       take as it is where the weights are that material's alone. */
    dsn_noise_state material[DSN_MIX_MAX_MATERIALS];
};

/* The materials' textons (continuous) and lattice textons all of one window (size and radius), channel
   count and value size: each kernels' mixed point then reads any material's texton as the lead's. */
enum { dsn_mix_alike_textons = 1u, dsn_mix_alike_lattice_textons = 2u };

static_assert(sizeof(dsn_mix_state) <= sizeof(dsn_mix), "dsn_mix must hold dsn_mix_state");
static_assert(alignof(dsn_mix_state) <= alignof(dsn_mix), "dsn_mix must be aligned for dsn_mix_state");

inline const dsn_mix_state *dsn_mix_state_of(const dsn_mix *mix) {
    return static_cast<const dsn_mix_state *>(static_cast<const void *>(mix));
}
inline dsn_mix_state *dsn_mix_state_of(dsn_mix *mix) {
    return static_cast<dsn_mix_state *>(static_cast<void *>(mix));
}

/* Material m as a noise (its own evaluators and dsn_gpu_pack take it). */
inline const dsn_noise *dsn_mix_material_noise(const dsn_mix_state *mix, uint32_t m) {
    return static_cast<const dsn_noise *>(static_cast<const void *>(&mix->material[m]));
}

/* A 32-bit hash of the counts, reaches, flags and the materials' check values (mix_init.cpp). */
uint32_t dsn_internal_mix_check(const dsn_mix_state *mix);

/* Whether `mix` is a mix that dsn_mix_init configured (not null, a count in range, its check value), as
   dsn_configured tells a noise. Init checked each material's own check value and hashed it into the mix's,
   so garbage passes with the chance a noise's garbage does (about 2^-32) without each material's hash
   being recomputed on every call. */
inline bool dsn_mix_configured(const dsn_mix_state *mix) {
    if (mix == 0 || mix->count == 0 || mix->count > DSN_MIX_MAX_MATERIALS) return false;
    for (uint32_t m = 0; m < mix->count; m++)
        if (mix->material[m].asset.texton == 0) return false; /* all a small build's noise check reads */
    return mix->check == dsn_internal_mix_check(mix);
}

#endif /* DSN_MIXING */

#endif /* DSN_MIX_STATE_H */
