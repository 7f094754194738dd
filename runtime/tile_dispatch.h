/* runtime/tile_dispatch.h - which copy of the tile code runs. The Makefile builds tile_avx2.cpp with
   -mavx2 on x86-64 and defines DSN_TILE_AVX2=1 for the runtime; init then records in dsn_noise whether
   this CPU (and its OS) runs AVX2, and the tile API calls that copy when it does. Built any other way
   (other CPUs, other build systems, the small build), there is one copy and no CPU check. */
#ifndef DSN_TILE_DISPATCH_H
#define DSN_TILE_DISPATCH_H

#include "noise_internal.h"

/* DSN_TILE_AVX2_BUILT: tile_avx2.cpp holds the AVX2 copy. DSN_TILE_AVX2_DISPATCH: tile.cpp chooses
   between it and its own copy (not when the whole runtime is built for AVX2 anyway). */
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

/* The kernel init records: DSN_TILE_KERNEL_AVX2 when dispatch is built and CPUID says AVX2 with YMM
   state saved by the OS, else DSN_TILE_KERNEL_DEFAULT. */
#if DSN_TILE_AVX2_DISPATCH
uint32_t dsn_internal_tile_kernel(void);
#else
static inline uint32_t dsn_internal_tile_kernel(void) { return DSN_TILE_KERNEL_DEFAULT; }
#endif

#if DSN_TILE_AVX2_BUILT
/* tile_render.h's render_tile, built for AVX2 (tile_avx2.cpp). */
void dsn_internal_render_tile_avx2(const dsn_noise *noise, uint32_t x0, uint32_t y0, uint32_t width,
                                   uint32_t height, void *out, dsn_output_kind kind, uint32_t *accumulator);
#endif

#endif /* DSN_TILE_DISPATCH_H */
