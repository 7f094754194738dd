/* runtime/tile_dispatch.h - which copy of the tile code runs. The Makefile builds tile_avx2.cpp with
   -mavx2 and tile_avx512.cpp with -mavx512f -mavx512bw on x86-64 and defines DSN_TILE_AVX2=1 for the
   runtime; init then records in dsn_noise the widest of them this CPU (and its OS) runs, and the tile
   API calls that copy. Built any other way (other CPUs, other build systems, the small build), there is
   one copy and no CPU check. */
#ifndef DSN_TILE_DISPATCH_H
#define DSN_TILE_DISPATCH_H

#include "noise_internal.h"

/* DSN_TILE_AVX2_BUILT: tile_avx2.cpp and tile_avx512.cpp hold the AVX2 and AVX-512 copies.
   DSN_TILE_AVX2_DISPATCH: tile.cpp chooses between them and its own copy (not when the whole runtime is
   built for AVX2 anyway: its own copy then takes the widest vectors it was built for). */
#if defined(DSN_TILE_AVX2) && DSN_TILE_AVX2 && defined(__x86_64__) && !DSN_SMALL_CODE
#define DSN_TILE_AVX2_BUILT 1
#else
#define DSN_TILE_AVX2_BUILT 0
#endif
#if DSN_TILE_AVX2_BUILT && !defined(__AVX2__)
#define DSN_TILE_AVX2_DISPATCH 1
#else
#define DSN_TILE_AVX2_DISPATCH 0
#endif

/* Values of dsn_noise.tile_kernel. */
#define DSN_TILE_KERNEL_DEFAULT 0u /* the copy built with the runtime's own flags */
#define DSN_TILE_KERNEL_AVX2 1u
#define DSN_TILE_KERNEL_AVX512 2u /* AVX-512 F and BW */

/* The kernel init records when dispatch is built: DSN_TILE_KERNEL_AVX512 when CPUID says AVX-512 F and
   BW with the ZMM state saved by the OS, else DSN_TILE_KERNEL_AVX2 when it says AVX2 with the YMM state
   saved, else DSN_TILE_KERNEL_DEFAULT. */
#if DSN_TILE_AVX2_DISPATCH
uint32_t dsn_internal_tile_kernel(void);
#else
static inline uint32_t dsn_internal_tile_kernel(void) { return DSN_TILE_KERNEL_DEFAULT; }
#endif

#if DSN_TILE_AVX2_BUILT
/* tile_render.h's render_tile, built for AVX2 (tile_avx2.cpp). */
void dsn_internal_render_tile_avx2(const dsn_noise_state *noise, uint32_t x0, uint32_t y0, uint32_t width,
                                   uint32_t height, void *out, dsn_output_kind kind, uint32_t *accumulator);
/* The same, built for AVX-512 (tile_avx512.cpp). */
void dsn_internal_render_tile_avx512(const dsn_noise_state *noise, uint32_t x0, uint32_t y0, uint32_t width,
                                     uint32_t height, void *out, dsn_output_kind kind, uint32_t *accumulator);
#endif

#endif /* DSN_TILE_DISPATCH_H */
