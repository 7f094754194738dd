/* runtime/kernels/kernel_avx2.cpp - the AVX2 kernel: the evaluation code built for AVX2 (the Makefile
   compiles this file with -mavx2 on x86-64), 16 pixels per strip. Runs only where init found AVX2
   (kernel_table.cpp); its bits are those of every other kernel. Empty unless DSN_KERNEL_X86_COPIES. */
#include "kernels/kernels.h"

#if DSN_KERNEL_X86_COPIES
#if !defined(__AVX2__)
#error "runtime/kernels/kernel_avx2.cpp must be compiled with -mavx2 when DSN_X86_DISPATCH is set"
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

extern const dsn_kernel_entries dsn_internal_entries_avx2 = {
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
#endif
