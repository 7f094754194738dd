// filtered_bench.cpp - cost of the filtered evaluation as ratios to the continuous mode per point measured
// in the same run (RGB, 31 x 31 texton with the baker's pyramid, 30 impacts per pixel, one thread):
// isotropic per level of detail, anisotropic per tap, filtered tiles (splatted) against the same pixels
// point by point, and the asset's size with and without its pyramid.
// Beside each ratio, the expected number of impulses within reach of a tap at the coarser level read,
// lambda (2 (r_l + 1) 2^l)^2, against level 0's: the part of the cost that grows with the level; and, for
// the isotropic footprints, the cost of the same walks with no level read (the impulses listed alone).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench_timing.h"
#include "fixtures/continuous_fixtures.h"
#include "offline/bake_internal.h"
#include "painted_stack.h"
#include "runtime/core/filtered_internal.h"

namespace {

using bench::best_time;
const uint32_t kPoints = 20000;
const int kRounds = 5;
int64_t checksum = 0; // keeps the evaluations observable

int64_t q32(double texels) { return int64_t(std::floor(texels * 4294967296.0)); }

} // namespace

int main() {
    using namespace continuous_fixtures;
    dsn::AssetFields fields = random_texton_asset(3, 15, 8, 1);
    const size_t plain_size = dsn::encode_asset(fields).size();
    fields.pyramid = dsn::texton_pyramid(fields);
    auto noise = make_noise(fields, 1, 30u << 16);
    const dsn_noise *n = &noise->noise;
    std::printf("asset (31 x 31 RGB 8-bit): %zu bytes with its %zu-level pyramid, %zu without (%.2fx)\n",
                noise->bytes.size(), fields.pyramid.size(), plain_size,
                double(noise->bytes.size()) / double(plain_size));

    // Points on a rotated grid, as a renderer asks for them.
    auto point = [](uint32_t i, int64_t *x, int64_t *y) {
        *x = int64_t(i % 200) * q32(2.8191) - int64_t(i / 200) * q32(1.0261) + q32(1.0 / 3);
        *y = int64_t(i % 200) * q32(1.0261) + int64_t(i / 200) * q32(2.8191) + q32(1.0 / 7);
    };
    auto continuous = [&] {
        int32_t out[3];
        for (uint32_t i = 0; i < kPoints; i++) {
            int64_t x, y;
            point(i, &x, &y);
            dsn_continuous_point_fixed(n, x, y, out);
            checksum += out[0];
        }
    };
    // Each case is timed in rounds against the continuous per point (bench_timing.h): the ratio of the
    // median round, and of the best times.
    size_t point_stack = 0, tile_stack = 0; // the deepest painted stack of one call, over the cases
    auto filtered = [&](const dsn_footprint &f) {
        point_stack = std::max(point_stack, bench::painted_stack([&] {
                                   int32_t out[3];
                                   dsn_filtered_point_fixed(n, q32(1.0 / 3), q32(1.0 / 7), &f, out);
                               }));
        return bench::paired_ratio(kRounds, continuous, [&] {
            int32_t out[3];
            for (uint32_t i = 0; i < kPoints; i++) {
                int64_t x, y;
                point(i, &x, &y);
                dsn_filtered_point_fixed(n, x, y, &f, out);
                checksum += out[0];
            }
        });
    };
    // The same points' walks with no level read (dsn_internal_filter_listing_only): only the impulses
    // listed, what any filtered point of that footprint pays before it reads a value.
    auto listing_alone = [&](const dsn_footprint &f) {
        const dsn_noise_state *state = dsn_state(n);
        dsn_filter_plan plan;
        dsn_internal_filter_plan(&f, state->asset.pyramid_levels, &plan);
        dsn_walked_level walked[2];
        const uint32_t count = dsn_internal_filter_walked_levels(state, &plan, walked);
        return bench::paired_ratio(kRounds, continuous, [&] {
            for (uint32_t i = 0; i < kPoints; i++) {
                int64_t x, y;
                point(i, &x, &y);
                checksum += int64_t(
                    dsn_internal_filter_listing_only(state, uint64_t(x), uint64_t(y), &plan, walked, count));
            }
        });
    };
    std::printf("continuous per point: %.0f ns (the baseline, timed beside each case; ratios: median of %d "
                "rounds, then best over best)\n",
                best_time(3, continuous) / kPoints * 1e9, kRounds);
    // Impulses within reach of one tap reading level l (lambda = impacts / support size), with the
    // window the evaluation reads (its all-zero margins cut) or the stored one.
    const double lambda = 30.0 / noise->asset.support_size;
    auto impulses = [&](int32_t lod_q8, bool stored_window) {
        const uint32_t lower = uint32_t(lod_q8) >> 8, levels = noise->asset.pyramid_levels;
        const uint32_t level = (lod_q8 & 255) != 0 && lower < levels ? lower + 1 : lower;
        dsn_level stored;
        if (level > levels || dsn_asset_level(&noise->asset, level, &stored) != DSN_OK) return 0.0;
        const dsn_walked_level read = dsn_internal_walked_level(dsn_state(n), level);
        const double spacing = std::ldexp(1.0, int(level));
        return stored_window ? lambda * (stored.width + 1) * spacing * (stored.height + 1) * spacing
                             : lambda * (read.width + 1) * spacing * (read.height + 1) * spacing;
    };
    auto impulse_text = [&](int32_t lod_q8) {
        static char text[96];
        std::snprintf(text, sizeof text, "%.0f impulses in reach (%.2fx; stored window %.2fx)",
                      impulses(lod_q8, false), impulses(lod_q8, false) / impulses(0, false),
                      impulses(lod_q8, true) / impulses(0, false));
        return text;
    };
    std::printf("impulses within reach of a continuous point: %.0f\n", impulses(0, true));
    const double lods[] = {0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4, 4.5, 5};
    for (double lod : lods) {
        const double side = std::pow(2.0, lod);
        const dsn_footprint f{q32(side), 0, 0, q32(side), 1};
        int32_t lod_q8;
        uint32_t taps;
        dsn_filter_level(n, &f, &lod_q8, &taps);
        const bench::PairedRatio cost = filtered(f);
        std::printf("isotropic filtered, LOD %.1f: %.2fx (%.2fx) the continuous per point, %s", lod,
                    cost.median, cost.best, impulse_text(lod_q8));
        if ((uint32_t(lod_q8) >> 8) > noise->asset.pyramid_levels) {
            std::printf("\n");
            continue;
        }
        const bench::PairedRatio listing = listing_alone(f);
        std::printf("; the listing of its impulses alone %.2fx (%.2fx)\n", listing.median, listing.best);
    }
    const double ratios[] = {2, 4, 8, 16};
    const double minors[] = {1, 2, 4};
    // Along x, then along the diagonal (the taps' box is then widest for their reaches).
    for (int degrees : {0, 45})
        for (double minor : minors)
            for (double ratio : ratios) {
                const double c = std::cos(degrees * M_PI / 180), s = std::sin(degrees * M_PI / 180);
                const dsn_footprint f{q32(minor * ratio * c), q32(minor * ratio * s), q32(-minor * s),
                                      q32(minor * c), 16};
                int32_t lod_q8;
                uint32_t taps;
                dsn_filter_level(n, &f, &lod_q8, &taps);
                const bench::PairedRatio cost = filtered(f);
                std::printf(
                    "anisotropic %2.0f:1 at %2d degrees, minor %.0f texels (LOD %.2f, %2u taps): %.2fx the "
                    "continuous per point, %.2fx (%.2fx) per tap; a tap has %s\n",
                    ratio, degrees, minor, lod_q8 / 256.0, taps, cost.median, cost.median / taps,
                    cost.best / taps, impulse_text(lod_q8));
            }
    // Tiles of a rotated grid minified to a level of detail (isotropic, then 4:1 with the row step the
    // longer, then with the column step the longer, 4 taps), splatted where the runs are long enough
    // (transposed in the last case), against the same pixels evaluated by dsn_filtered_point_fixed one
    // by one.
    const uint32_t side = 128;
    std::vector<int32_t> tile(side * side * 3);
    const char *shapes[] = {"isotropic,", "4:1, the row step the longer (4 taps), minor axis at",
                            "4:1, the column step the longer (4 taps), minor axis at"};
    for (int shape = 0; shape < 3; shape++)
        for (double lod : {0.5, 1.0, 1.5, 2.0, 2.5, 3.0}) {
            const double zoom = std::pow(2.0, lod), c = std::cos(0.5) * zoom, s = std::sin(0.5) * zoom;
            const double rows = shape == 1 ? 4 : 1, columns = shape == 2 ? 4 : 1;
            const dsn_grid grid{q32(1.0 / 3),     q32(1.0 / 7),   q32(c * columns),
                                q32(s * columns), q32(-s * rows), q32(c * rows)};
            const uint32_t max_taps = shape != 0 ? 4 : 1;
            std::vector<unsigned char> scratch(
                dsn_filtered_tile_scratch_size(n, &grid, max_taps, side, side));
            const dsn_footprint f{grid.column_step_x, grid.column_step_y, grid.row_step_x, grid.row_step_y,
                                  max_taps};
            const bench::PairedRatio cost = bench::paired_ratio(
                kRounds,
                [&] {
                    int32_t out[3];
                    for (uint32_t j = 0; j < side; j++)
                        for (uint32_t i = 0; i < side; i++) {
                            dsn_filtered_point_fixed(
                                n, grid.origin_x + i * grid.column_step_x + j * grid.row_step_x,
                                grid.origin_y + i * grid.column_step_y + j * grid.row_step_y, &f, out);
                            checksum += out[0];
                        }
                },
                [&] {
                    dsn_filtered_tile_fixed(n, &grid, max_taps, side, side, tile.data(), scratch.data(),
                                            scratch.size());
                    checksum += tile[7];
                });
            tile_stack = std::max(tile_stack, bench::painted_stack([&] {
                                      dsn_filtered_tile_fixed(n, &grid, max_taps, side, side, tile.data(),
                                                              scratch.data(), scratch.size());
                                  }));
            const double pixel = cost.best * cost.baseline_best / (side * side);
            std::printf(
                "filtered tile %ux%u, %s LOD %.1f: %.0f ns/pixel, 1/%.1f (1/%.1f) of the filtered per "
                "point%s\n",
                side, side, shapes[shape], lod, pixel * 1e9, 1 / cost.median, 1 / cost.best,
                scratch.empty() ? " (point by point)" : "");
        }
    std::printf("stack (painted, deepest over the cases above) of a filtered per-point call: %zu bytes, of a "
                "filtered tile call: %zu bytes\n",
                point_stack, tile_stack);
    std::printf("(checksum %lld)\n", static_cast<long long>(checksum));
    return 0;
}
