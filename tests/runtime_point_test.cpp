// runtime_point_test.cpp - the per-point path for 16 x 16 cells without a period (each x86 kernel's fast
// walk: 16 impulses per vector, batched hits) against the tile path, which draws the same impulses
// through the generic helpers: every channel count and value width, several texton sizes, windows across
// the 32-bit wrap, and cells with more than 16 impulses (the fast walk's one-by-one rest).
#include <doctest/doctest.h>

#include <vector>

#include "fixtures/test_assets.h"
#include "runtime/core/poisson_count.h"
#include "runtime/kernels/kernels.h"

namespace {

using dsn_test::LoadedNoise;

// Cells of side 16 around the window holding more than 16 impulses.
int crowded_cells(const dsn_noise &noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height) {
    int crowded = 0;
    const uint32_t first_x = (uint32_t(x0) - dsn_state(&noise)->radius[0]) >> 4,
                   first_y = (uint32_t(y0) - dsn_state(&noise)->radius[1]) >> 4;
    const uint32_t columns = ((width + 2 * dsn_state(&noise)->radius[0]) >> 4) + 2,
                   rows = ((height + 2 * dsn_state(&noise)->radius[1]) >> 4) + 2;
    for (uint32_t j = 0; j < rows; j++)
        for (uint32_t i = 0; i < columns; i++) {
            uint32_t key =
                dsn_cell_key(dsn_state(&noise), (first_x + i) & 0x0FFFFFFFu, (first_y + j) & 0x0FFFFFFFu);
            crowded += dsn_cell_impulse_count(dsn_state(&noise), key) > 16;
        }
    return crowded;
}

} // namespace

TEST_CASE("per point, 16 x 16 cells, no period: equals the tile on every channel count, width and size") {
    dsn_test::TestRandom random(77);
    const int32_t origins[] = {0, -12, INT32_MAX - 10, INT32_MIN, 2000000000, -1999999990};
    int windows = 0, crowded = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u})
            for (uint32_t side : {1u, 9u, 31u, 45u, 255u}) {
                auto fields =
                    dsn_test::synthetic_fields(channels, side, bits, DSN_SHAPE_RECTANGLE, random.next());
                // A density that makes the init choose 16 x 16 cells (lambda 16^2 = 8; 3.9 for the largest
                // texton, whose texton indices pass 2^16 when scaled: the lanes' modular arithmetic).
                const double impacts = side == 255 ? 1000.0 : 8.0 * double(side * side) / 256.0;
                if (impacts * 65536.0 < DSN_IMPACTS_MIN_Q16 || impacts > 1024) continue;
                LoadedNoise loaded(fields, dsn_test::make_config(random.next(), impacts));
                CAPTURE(channels);
                CAPTURE(bits);
                CAPTURE(side);
                if (dsn_state(&loaded.noise)->cell_shift != 4) continue;
                dsn_noise_state *state = dsn_state(&loaded.noise);
                const uint32_t chosen = state->tile_kernel;
                for (int32_t origin : origins) {
                    const int32_t x0 = int32_t(uint32_t(origin) + random.next() % 16), y0 = origin;
                    CAPTURE(x0);
                    // every kernel this CPU runs: each has its copy of the walk
                    for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= chosen; kernel++) {
                        CAPTURE(kernel);
                        state->tile_kernel = kernel;
                        CHECK(dsn_test::tile_point_differences(loaded.noise, x0, y0, 40, 24) == 0);
                    }
                    state->tile_kernel = chosen;
                    crowded += crowded_cells(loaded.noise, x0, y0, 40, 24);
                    windows++;
                }
            }
    CHECK(windows >= 72); // side 1 needs fewer than 1/16 impact per pixel: skipped
    CHECK(crowded > 0);
}
