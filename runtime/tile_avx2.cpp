/* runtime/tile_avx2.cpp - the tile code of tile_render.h built for AVX2 (the Makefile compiles this file
   with -mavx2 on x86-64): 16 values per splat vector instead of 8. tile.cpp calls it only when init found
   AVX2 (tile_dispatch.h); the bits are those of every other path. */
#include "tile_dispatch.h"

#if DSN_TILE_AVX2_BUILT
#if !defined(__AVX2__)
#error "runtime/tile_avx2.cpp must be compiled with -mavx2 when DSN_TILE_AVX2 is set"
#endif

#include "tile_render.h"

void dsn_internal_render_tile_avx2(const dsn_noise_state *noise, uint32_t x0, uint32_t y0, uint32_t width,
                                   uint32_t height, void *out, dsn_output_kind kind, uint32_t *accumulator) {
    render_tile(noise, x0, y0, width, height, out, kind, accumulator);
}
#endif
