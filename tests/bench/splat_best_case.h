// splat_best_case.h - the continuous grid splat's kernel timed in its best case, to set the tile figures
// against: one impulse added to a block's 32 rows of 64 pixels each (every vector lane used, no run
// shorter than a block, none of the per-impulse setup of grid_splat.cpp), the pixels on a grid rotated by
// 30 degrees at 0.45 texel/pixel so that the lanes read different records, as on any rotated grid. What
// a tile costs beyond it per impulse and pixel is the runs' setup and their partly used vectors.
#ifndef DSN_BENCH_SPLAT_BEST_CASE_H
#define DSN_BENCH_SPLAT_BEST_CASE_H

#include <cmath>
#include <vector>

#include "bench_timing.h"
#include "runtime/kernels/kernels.h"
#include "runtime/kernels/splat_cells.h"
#include "runtime/setup/noise_state.h"

namespace bench {

// Seconds per impulse and pixel of the splat kernel `kernel` (a row of the kernel table) in its best case.
inline double splat_best_case(const dsn_noise *handle, uint32_t kernel) {
    const dsn_asset &asset = dsn_state(handle)->asset;
    const int64_t one = int64_t(1) << 32;
    const uint32_t columns = dsn_splat_run_longest, rows = dsn_splat_runs_most, stride = columns + 8;
    dsn_splat_setup setup = {};
    setup.texture.values = asset.texton;
    setup.texture.width = setup.texture.stride = asset.width;
    setup.texture.height = asset.height;
    setup.texture.channels = asset.channels;
    setup.texture.bits = asset.bits;
    setup.texture.level = 0;
    setup.reach_x = int64_t((asset.width - 1) / 2 + 1) * one;
    setup.reach_y = int64_t((asset.height - 1) / 2 + 1) * one;
    // The geometry below is drawn for a reach of 16 texels (a 31 x 31 texton) and blocks of 32 rows of 64
    // pixels, and scaled to the texton's reach and the block's sides.
    const double scale_x = double(setup.reach_x) / double(16 * one),
                 scale_y = double(setup.reach_y) / double(16 * one);
    const double step = 0.45 * 64 / columns, cosine = std::cos(M_PI / 6), sine = std::sin(M_PI / 6);
    setup.step_x = int64_t(step * cosine * scale_x * double(one));
    setup.step_y = int64_t(step * sine * scale_y * double(one));
    // The records on 64-byte boundaries, as the tile keeps them (continuous_tile.cpp): RGB cells whole
    // within a cache line.
    struct alignas(64) Records {
        uint64_t values[splat_cell_capacity];
    };
    std::vector<Records> cells(1);
#if DSN_SPLAT_CELLS
    if (make_splat_cells(setup.texture, cells[0].values, splat_cell_capacity, &setup.cell_row, 0) != 0)
        setup.cells = cells[0].values;
#endif
    std::vector<uint64_t> sums(size_t(asset.channels) * stride * rows);
    setup.plane = size_t(stride) * rows;
    setup.sums_end = sums.data() + sums.size();
    // The rows' first pixels: a run spans 64 steps, 25 texels across and 14.4 down, centred across and
    // moving down half a texel a row, so that every pixel stays within reach of the impulse (the kernel's
    // condition: offsets in (-reach, reach)).
    dsn_splat_run runs[dsn_splat_runs_most];
    const double span_x = step * cosine * scale_x * columns;
    for (uint32_t r = 0; r < rows; r++) {
        runs[r].offset_x = int64_t(-span_x / 2 * double(one));
        runs[r].offset_y = int64_t((-15.5 + 16.0 * r / rows) * scale_y * double(one));
        runs[r].sums = sums.data() + size_t(r) * stride;
        runs[r].count = columns;
    }
    dsn_splat_runs_entry *const splat = dsn_kernel_entries_of(kernel)->continuous_splat_runs;
    const int calls = 2000;
    const double seconds = best_time(5, [&] {
        for (int c = 0; c < calls; c++) splat(&setup, runs, rows);
    });
    return seconds / (double(calls) * rows * columns);
}

} // namespace bench

#endif // DSN_BENCH_SPLAT_BEST_CASE_H
