// gradient_bench.cpp - the cost of the gradient (value and derivatives together, dsn.h "Gradients") over
// the value alone, measured in the same run in paired rounds: per point (lattice and continuous, on a
// rotated grid off the lattice), per tile (lattice, and a continuous grid rotated by 30 degrees at 0.7
// texels per pixel, which the value's tile splats) and per batch; RGB, 31 x 31 texton, 30 impacts per
// pixel, one thread; and the filtered point and tile at a level of detail of 1.6 (the point at 3.5 too).
// The target is 1.6x.
#include <algorithm>
#include <cstdio>
#include <functional>
#include <vector>

#include "bench_timing.h"
#include "fixtures/continuous_fixtures.h"
#include "offline/bake_internal.h"
#include "painted_stack.h"

namespace {

const uint32_t side = 256;
int64_t checksum = 0; // keeps the evaluations observable

void report(const char *what, const std::vector<double> &gradient, const std::vector<double> &value,
            double points) {
    std::printf(
        "  %-34s value %7.1f ns/pixel   gradient %7.1f ns/pixel   ratio %.2f (median of %zu rounds)\n", what,
        1e9 * bench::fastest(value) / points, 1e9 * bench::fastest(gradient) / points,
        bench::median_ratio(gradient, value), value.size());
}

} // namespace

int main() {
    using namespace continuous_fixtures;
    dsn::AssetFields fields = random_texton_asset(3, 15, 8, 1);
    fields.pyramid = dsn::texton_pyramid(fields);
    auto made = make_noise(fields, 1, 30u << 16);
    const dsn_noise *noise = &made->noise;
    const double points = double(side) * side;
    const int64_t one = int64_t(1) << 32;
    const int64_t step_x = int64_t(0.6062 * double(one)), step_y = int64_t(0.35 * double(one)); // 0.7, 30 deg
    const int rounds = 7;
    std::vector<int32_t> out(static_cast<size_t>(points) * 3), dx(out.size()), dy(out.size());
    std::vector<unsigned char> scratch(64 * 1024);

    std::printf("gradient_bench: value and gradient together over the value alone (1.6x is the target)\n");

    auto lattice_points = [&](bool gradient) {
        return [&, gradient] {
            int32_t value[3], gx[3], gy[3];
            for (uint32_t y = 0; y < side; y++)
                for (uint32_t x = 0; x < side; x++) {
                    if (gradient)
                        dsn_lattice_gradient_fixed(noise, int32_t(x * 3), int32_t(y * 3), value, gx, gy);
                    else
                        dsn_lattice_point_fixed(noise, int32_t(x * 3), int32_t(y * 3), value);
                    checksum += value[0];
                }
        };
    };
    auto continuous_points = [&](bool gradient) {
        return [&, gradient] {
            int32_t value[3], gx[3], gy[3];
            for (uint32_t y = 0; y < side; y++)
                for (uint32_t x = 0; x < side; x++) {
                    const int64_t px = int64_t(x) * step_x - int64_t(y) * step_y + one / 3;
                    const int64_t py = int64_t(x) * step_y + int64_t(y) * step_x + one / 7;
                    if (gradient)
                        dsn_continuous_gradient_fixed(noise, px, py, value, gx, gy);
                    else
                        dsn_continuous_point_fixed(noise, px, py, value);
                    checksum += value[0];
                }
        };
    };
    const dsn_grid grid = {one / 3, one / 7, step_x, step_y, -step_y, step_x};
    // A lattice tile takes a fifth of a millisecond: each round times 16, so that one interruption or cache
    // refill does not decide a round.
    const int lattice_tile_repeats = 16;
    auto tiles = [&](bool lattice, bool gradient) {
        return [&, lattice, gradient] {
            if (lattice && gradient)
                for (int k = 0; k < lattice_tile_repeats; k++)
                    dsn_lattice_tile_gradient_fixed(noise, 5, 9, side, side, out.data(), dx.data(),
                                                    dy.data());
            else if (lattice)
                for (int k = 0; k < lattice_tile_repeats; k++)
                    dsn_lattice_tile_fixed(noise, 5, 9, side, side, out.data(), nullptr, 0);
            else if (gradient)
                dsn_continuous_tile_gradient_fixed(noise, &grid, side, side, out.data(), dx.data(),
                                                   dy.data());
            else
                dsn_continuous_tile_fixed(noise, &grid, side, side, out.data(), scratch.data(),
                                          scratch.size());
            checksum += out[7];
        };
    };
    std::vector<int64_t> xs(static_cast<size_t>(points)), ys(xs.size());
    for (size_t k = 0; k < xs.size(); k++) {
        xs[k] = int64_t(k % side) * step_x * 5 + int64_t(k / side) * one * 3 + int64_t(k * 977);
        ys[k] = int64_t(k % side) * step_y * 7 - int64_t(k / side) * one * 2 + int64_t(k * 131);
    }
    std::vector<unsigned char> batch_scratch(dsn_continuous_batch_scratch_size(noise));
    auto batch = [&](bool gradient) {
        return [&, gradient] {
            if (gradient)
                dsn_continuous_batch_gradient_fixed(noise, xs.data(), ys.data(), uint32_t(xs.size()),
                                                    out.data(), dx.data(), dy.data());
            else
                dsn_continuous_batch_fixed(noise, xs.data(), ys.data(), uint32_t(xs.size()), out.data(),
                                           batch_scratch.data(), batch_scratch.size());
            checksum += out[3];
        };
    };

    // isotropic minifications by `scale` (3: level of detail about 1.6; 11.3: 3.5, the coarse levels that
    // the AVX-512 copy reads from tables in registers)
    auto filtered_points = [&](bool gradient, double scale) {
        return [&, gradient, scale] {
            const int64_t step = int64_t(scale * double(one));
            const dsn_footprint footprint = {step, 0, 0, step, 1};
            int32_t value[3], gx[3], gy[3];
            for (uint32_t y = 0; y < side / 4; y++)
                for (uint32_t x = 0; x < side; x++) {
                    const int64_t px = int64_t(x) * step + one / 3, py = int64_t(y) * step + one / 7;
                    if (gradient)
                        dsn_filtered_gradient_fixed(noise, px, py, &footprint, value, gx, gy);
                    else
                        dsn_filtered_point_fixed(noise, px, py, &footprint, value);
                    checksum += value[0];
                }
        };
    };
    // Filtered tiles of the point case's footprint (a minification by 3) and of a magnification by 4
    // (unfiltered: the continuous gradient's splat), side x side / 4 pixels.
    const dsn_grid minified = {one / 3, one / 7, 3 * one, 0, 0, 3 * one},
                   magnified = {one / 3, one / 7, one / 4, 0, 0, one / 4};
    std::vector<unsigned char> filtered_scratch(
        std::max(dsn_filtered_tile_scratch_size(noise, &minified, 1, side, side / 4),
                 dsn_filtered_tile_scratch_size(noise, &magnified, 1, side, side / 4)));
    auto filtered_tiles = [&](const dsn_grid *filter_grid, bool gradient) {
        return [&, filter_grid, gradient] {
            if (gradient)
                dsn_filtered_tile_gradient_fixed(noise, filter_grid, 1, side, side / 4, out.data(), dx.data(),
                                                 dy.data());
            else
                dsn_filtered_tile_fixed(noise, filter_grid, 1, side, side / 4, out.data(),
                                        filtered_scratch.data(), filtered_scratch.size());
            checksum += out[5];
        };
    };
    const struct {
        const char *name;
        std::function<void()> gradient, value;
        double gradient_points;
    } cases[] = {
        {"lattice point", lattice_points(true), lattice_points(false), points},
        {"continuous point", continuous_points(true), continuous_points(false), points},
        {"lattice tile", tiles(true, true), tiles(true, false), points * lattice_tile_repeats},
        {"continuous tile (30 deg, 0.7 texel)", tiles(false, true), tiles(false, false), points},
        {"continuous batch (random points)", batch(true), batch(false), points},
        {"filtered point (level of detail 1.6)", filtered_points(true, 3), filtered_points(false, 3),
         points / 4},
        {"filtered point (level of detail 3.5)", filtered_points(true, 11.3), filtered_points(false, 11.3),
         points / 4},
        {"filtered tile (level of detail 1.6)", filtered_tiles(&minified, true),
         filtered_tiles(&minified, false), points / 4},
        {"filtered tile (magnified 4x)", filtered_tiles(&magnified, true), filtered_tiles(&magnified, false),
         points / 4},
    };
    for (const auto &c : cases) {
        const auto times = bench::timed_rounds(rounds, {c.gradient, c.value});
        report(c.name, times[0], times[1], c.gradient_points);
    }
    std::printf(
        "  stack (painted) of a gradient tile call: lattice %zu bytes, continuous %zu bytes (the value's: "
        "%zu bytes), filtered %zu bytes (the value's: %zu bytes)\n",
        bench::painted_stack(cases[2].gradient), bench::painted_stack(cases[3].gradient),
        bench::painted_stack(cases[3].value), bench::painted_stack(cases[7].gradient),
        bench::painted_stack(cases[7].value));
    std::printf("  stack (painted) of a gradient batch call: %zu bytes (the value's: %zu bytes)\n",
                bench::painted_stack(cases[4].gradient), bench::painted_stack(cases[4].value));
    std::printf("  stack (painted) of a filtered gradient point call: %zu bytes (the value's: %zu bytes)\n",
                std::max(bench::painted_stack(cases[5].gradient), bench::painted_stack(cases[6].gradient)),
                std::max(bench::painted_stack(cases[5].value), bench::painted_stack(cases[6].value)));
    std::printf("  (checksum %lld)\n", static_cast<long long>(checksum));
    return 0;
}
