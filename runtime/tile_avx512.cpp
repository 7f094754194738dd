/* runtime/tile_avx512.cpp - the tile code of tile_render.h built for AVX-512 F and BW (the Makefile
   compiles this file with -mavx512f -mavx512bw on x86-64): strips of 32 pixels, summed from the texton's
   bytes widened as they are loaded. tile.cpp calls it only when init found AVX-512 (tile_dispatch.h); the
   bits are those of every other path. */
#include "tile_dispatch.h"

#if DSN_TILE_AVX2_BUILT
#if !defined(__AVX512BW__) || !defined(__AVX512F__)
#error "runtime/tile_avx512.cpp must be compiled with -mavx512f -mavx512bw when DSN_TILE_AVX2 is set"
#endif

#include "tile_render.h"

void dsn_internal_render_tile_avx512(const dsn_noise_state *noise, uint32_t x0, uint32_t y0, uint32_t width,
                                     uint32_t height, void *out, dsn_output_kind kind,
                                     uint32_t *accumulator) {
    render_tile(noise, x0, y0, width, height, out, kind, accumulator);
}
#endif
