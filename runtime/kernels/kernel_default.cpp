/* runtime/kernels/kernel_default.cpp - the default kernel: the evaluation code built with the runtime's own
   flags (on x86 the widest vectors those flags allow, simd.h), the one every build has. Built for AVX2, it
   has the vector per-point evaluator and filtered reads too. */
#include "kernels/kernels.h"
#include "kernels/tile_render.h"

#if DSN_CONTINUOUS_BATCH
#include "kernels/continuous_batch.h"
#define BATCH_ENTRY continuous_batch
#else
#define BATCH_ENTRY 0
#endif
#if !DSN_SMALL_CODE
#include "kernels/splat_row.h"
#define SPLAT_ROW_ENTRY continuous_splat_runs
#define SPLAT_NORMALIZE_ENTRY continuous_splat_normalize
#else
#define SPLAT_ROW_ENTRY 0
#define DSN_SPLAT_GRADIENT_ENTRY 0
#define SPLAT_NORMALIZE_ENTRY 0
#endif
#include "kernels/continuous_point_sift.h"
#include "kernels/filtered_candidates_vector.h"
#include "kernels/filtered_reads_vector.h"
#include "kernels/lattice_point_walk.h"
#include "kernels/surface_impulses.h"

extern const dsn_kernel_entries dsn_internal_entries_default = {render_tile,
                                                                lattice_strips_take,
                                                                DSN_LATTICE_POINT_ENTRY,
                                                                BATCH_ENTRY,
                                                                SPLAT_ROW_ENTRY,
                                                                DSN_SPLAT_GRADIENT_ENTRY,
                                                                SPLAT_NORMALIZE_ENTRY,
                                                                DSN_CONTINUOUS_POINT_ENTRY,
                                                                DSN_FILTER_READS_ENTRY,
                                                                DSN_FILTER_CANDIDATES_ENTRY,
                                                                DSN_SURFACE_IMPULSES_ENTRY,
                                                                DSN_SURFACE_READS_ENTRY,
                                                                DSN_LATTICE_MIX_TILE_ENTRY,
                                                                DSN_LATTICE_ROWS_ENTRY,
                                                                DSN_MIX_PICKS_ENTRY};
