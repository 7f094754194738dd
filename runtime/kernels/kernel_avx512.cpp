/* runtime/kernels/kernel_avx512.cpp - the AVX-512 kernel: the evaluation code built for AVX-512 F and BW, and
   DQ and VL where given (the Makefile compiles this file with -mavx512f -mavx512bw -mavx512dq -mavx512vl on
   x86-64: DQ's 64-bit multiply hashes the impulses, with VL on 128 bits too), 32 pixels per strip,
   summed two rows per load from paired planes of the texton (simd_avx512.h). Runs only where init found
   AVX-512 (kernel_table.cpp); its bits are those of every other kernel. Empty unless
   DSN_KERNEL_X86_COPIES. */
#include "kernels/kernels.h"

#if DSN_KERNEL_X86_COPIES
#if !defined(__AVX512BW__) || !defined(__AVX512F__)
#error                                                                                                       \
    "runtime/kernels/kernel_avx512.cpp must be compiled with -mavx512f -mavx512bw when DSN_X86_DISPATCH is set"
#endif

#include "kernels/continuous_batch.h"
#include "kernels/continuous_point_vector.h"
#include "kernels/filtered_candidates_vector.h"
#include "kernels/filtered_reads_vector.h"
#include "kernels/lattice_point_walk.h"
#include "kernels/splat_row.h"
#include "kernels/surface_impulses.h"
#include "kernels/tile_render.h"

extern const dsn_kernel_entries dsn_internal_entries_default;

extern const dsn_kernel_entries dsn_internal_entries_avx512 = {
    render_tile,
    lattice_strips_take,
    DSN_LATTICE_POINT_ENTRY,
    continuous_batch,
    continuous_splat_runs,
    DSN_SPLAT_GRADIENT_ENTRY,
    continuous_splat_normalize,
    continuous_point_or<&dsn_internal_entries_default>,
    DSN_FILTER_READS_ENTRY,
    DSN_FILTER_CANDIDATES_ENTRY,
    DSN_SURFACE_IMPULSES_ENTRY,
    DSN_SURFACE_READS_ENTRY,
    DSN_LATTICE_MIX_TILE_ENTRY,
    DSN_LATTICE_ROWS_ENTRY,
    DSN_MIX_PICKS_ENTRY};

extern const dsn_kernel_entries dsn_internal_entries_avx2;

namespace {

/* The lattice tiles of the kernel below: of RGB noises whose texton the AVX2 kernel's strips take, the
   AVX2 kernel's, every output kind; of the others (grey, or textons only this kernel's single copy has
   room for) this kernel's (kernel_table.cpp says where and why). A noise too dense for AVX2's rectangles is
   too dense for this kernel's (its widths are among AVX2's), so both would take the 32-bit path. */
int avx2_takes(const dsn_noise_state *noise) {
    return noise->asset.channels == 3 && dsn_internal_entries_avx2.lattice_strips_take(noise);
}
void lattice_tile_avx2_if_rgb(const dsn_noise_state *noise, uint32_t x0, uint32_t y0, uint32_t width,
                              uint32_t height, void *out, void *dx, void *dy, dsn_output_kind kind,
                              uint32_t *accumulator, const dsn_impulse_filter *filter) {
    if (avx2_takes(noise))
        dsn_internal_entries_avx2.lattice_tile(noise, x0, y0, width, height, out, dx, dy, kind, accumulator,
                                               filter);
    else
        render_tile(noise, x0, y0, width, height, out, dx, dy, kind, accumulator, filter);
}
int lattice_strips_take_avx2_if_rgb(const dsn_noise_state *noise) {
    return avx2_takes(noise) || lattice_strips_take(noise);
}

} // namespace

/* This kernel but for the lattice tiles of RGB noises, which take the AVX2 kernel's. */
extern const dsn_kernel_entries dsn_internal_entries_avx512_avx2_tiles = {
    lattice_tile_avx2_if_rgb,   lattice_strips_take_avx2_if_rgb,
    DSN_LATTICE_POINT_ENTRY,    continuous_batch,
    continuous_splat_runs,      DSN_SPLAT_GRADIENT_ENTRY,
    continuous_splat_normalize, continuous_point_or<&dsn_internal_entries_default>,
    DSN_FILTER_READS_ENTRY,     DSN_FILTER_CANDIDATES_ENTRY,
    DSN_SURFACE_IMPULSES_ENTRY, DSN_SURFACE_READS_ENTRY,
    DSN_LATTICE_MIX_TILE_ENTRY, DSN_LATTICE_ROWS_ENTRY,
    DSN_MIX_PICKS_ENTRY};
#endif
