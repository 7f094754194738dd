// mix_bench.cpp - the cost of a mix of two materials (dsn.h, "Mixing") over one material's noise, in the
// same run in paired rounds: per point (lattice and continuous, on a rotated grid off the lattice) and
// per tile (lattice, and a continuous grid rotated by 30 degrees at 0.7 texels per pixel), for a constant
// 50/50 mix, a transition (weights changing every 16 texels, so that most points read the weights per
// impulse) and all weight on one material; and the filtered point at a level of detail of 1.6. RGB, 31 x 31
// textons, 30 impacts per pixel, one thread. The target is 1.3x for a mix of two.
#include <algorithm>
#include <cstdio>
#include <functional>
#include <vector>

#include "bench_timing.h"
#include "fixtures/continuous_fixtures.h"
#include "offline/bake_internal.h"
#include "painted_stack.h"

namespace {

const uint32_t side = 192;
int64_t checksum = 0; // keeps the evaluations observable

} // namespace

int main() {
    using namespace continuous_fixtures;
    dsn::AssetFields fields_a = random_texton_asset(3, 15, 8, 1), fields_b = random_texton_asset(3, 15, 8, 2);
    fields_a.pyramid = dsn::texton_pyramid(fields_a);
    fields_b.pyramid = dsn::texton_pyramid(fields_b);
    auto a = make_noise(fields_a, 1, 30u << 16);
    auto b = make_noise(fields_b, 2, 30u << 16);
    const dsn_noise *materials[] = {&a->noise, &b->noise};
    dsn_mix mix;
    if (dsn_mix_init(&mix, materials, 2) != DSN_OK) return 1;
    const uint8_t half[] = {128, 128}, only_first[] = {255, 0};
    std::vector<uint8_t> ramp;
    for (uint32_t i = 0; i < 64; i++) ramp.insert(ramp.end(), {uint8_t(i * 4), uint8_t(255 - i * 4)});
    const dsn_mix_control controls[] = {{half, 1, 1, 0, 0, 0, 0},
                                        {ramp.data(), 64, 1, 4, 0, 0, DSN_MIX_PERIODIC_X},
                                        {only_first, 1, 1, 0, 0, 0, 0}};
    const char *control_names[] = {"50/50", "transition", "one material"};
    const double points = double(side) * side;
    const int64_t one = int64_t(1) << 32;
    const int64_t step_x = int64_t(0.6062 * double(one)), step_y = int64_t(0.35 * double(one)); // 0.7, 30 deg
    const dsn_grid grid = {one / 3, one / 7, step_x, step_y, -step_y, step_x};
    const int rounds = 7;
    std::vector<int32_t> out(static_cast<size_t>(points) * 3);
    // As much scratch as the tile functions ask for (the mixes' and one material's).
    std::vector<unsigned char> scratch(
        std::max({dsn_mix_lattice_tile_scratch_size(&mix, side, side),
                  dsn_mix_continuous_tile_scratch_size(&mix, &grid, side, side),
                  dsn_continuous_tile_scratch_size(&a->noise, &grid, side, side)}));

    std::printf("mix_bench: a mix of two materials over one material's noise (1.3x is the target)\n");
    auto lattice_points = [&](const dsn_mix_control *control) {
        return [&, control] {
            int32_t value[3];
            for (uint32_t y = 0; y < side; y++)
                for (uint32_t x = 0; x < side; x++) {
                    if (control)
                        dsn_mix_lattice_point_fixed(&mix, control, int32_t(x * 3), int32_t(y * 3), value);
                    else
                        dsn_lattice_point_fixed(&a->noise, int32_t(x * 3), int32_t(y * 3), value);
                    checksum += value[0];
                }
        };
    };
    auto continuous_points = [&](const dsn_mix_control *control) {
        return [&, control] {
            int32_t value[3];
            for (uint32_t y = 0; y < side; y++)
                for (uint32_t x = 0; x < side; x++) {
                    const int64_t px = int64_t(x) * step_x - int64_t(y) * step_y + one / 3;
                    const int64_t py = int64_t(x) * step_y + int64_t(y) * step_x + one / 7;
                    if (control)
                        dsn_mix_continuous_point_fixed(&mix, control, px, py, value);
                    else
                        dsn_continuous_point_fixed(&a->noise, px, py, value);
                    checksum += value[0];
                }
        };
    };
    // A lattice tile of one material takes a tenth of a millisecond: each round times 16, so that one
    // interruption or cache refill does not decide a round.
    const int lattice_tile_repeats = 16;
    auto tiles = [&](bool lattice, const dsn_mix_control *control) {
        return [&, lattice, control] {
            if (lattice && control)
                for (int k = 0; k < lattice_tile_repeats; k++)
                    dsn_mix_lattice_tile_fixed(&mix, control, 5, 9, side, side, out.data(), scratch.data(),
                                               scratch.size());
            else if (lattice)
                for (int k = 0; k < lattice_tile_repeats; k++)
                    dsn_lattice_tile_fixed(&a->noise, 5, 9, side, side, out.data(), nullptr, 0);
            else if (control)
                dsn_mix_continuous_tile_fixed(&mix, control, &grid, side, side, out.data(), scratch.data(),
                                              scratch.size());
            else
                dsn_continuous_tile_fixed(&a->noise, &grid, side, side, out.data(), scratch.data(),
                                          scratch.size());
            checksum += out[7];
        };
    };
    // Filtered points: a minification by 3 (level of detail about 1.6), a quarter of the points.
    const dsn_footprint footprint = {3 * one, 0, 0, 3 * one, 1};
    auto filtered_points = [&](const dsn_mix_control *control) {
        return [&, control] {
            int32_t value[3];
            for (uint32_t y = 0; y < side / 4; y++)
                for (uint32_t x = 0; x < side; x++) {
                    const int64_t px = int64_t(x) * 3 * one + one / 3, py = int64_t(y) * 3 * one + one / 7;
                    if (control)
                        dsn_mix_filtered_point_fixed(&mix, control, px, py, &footprint, value);
                    else
                        dsn_filtered_point_fixed(&a->noise, px, py, &footprint, value);
                    checksum += value[0];
                }
        };
    };
    for (int c = 0; c < 3; c++) {
        const dsn_mix_control *control = &controls[c];
        const struct {
            const char *name;
            std::function<void()> mixed, single;
            double pixels;
        } cases[] = {
            {"lattice point", lattice_points(control), lattice_points(nullptr), points},
            {"continuous point", continuous_points(control), continuous_points(nullptr), points},
            {"lattice tile", tiles(true, control), tiles(true, nullptr), points * lattice_tile_repeats},
            {"continuous tile (30 deg, 0.7 texel)", tiles(false, control), tiles(false, nullptr), points},
            {"filtered point (level of detail 1.6)", filtered_points(control), filtered_points(nullptr),
             points / 4},
        };
        std::printf(" %s:\n", control_names[c]);
        for (const auto &one_case : cases) {
            const auto times = bench::timed_rounds(rounds, {one_case.mixed, one_case.single});
            std::printf("  %-36s one material %7.1f ns/pixel   mix %7.1f ns/pixel   ratio %.2f (median of %d "
                        "rounds)\n",
                        one_case.name, 1e9 * bench::fastest(times[1]) / one_case.pixels,
                        1e9 * bench::fastest(times[0]) / one_case.pixels,
                        bench::median_ratio(times[0], times[1]), rounds);
        }
    }
    // The deepest of the mixing controls (50/50: the kernels' walks; the transition: each impulse's pick).
    size_t lattice_stack = 0, continuous_stack = 0, filtered_stack = 0, own_filtered_stack = 0;
    for (const dsn_mix_control *control : {&controls[0], &controls[1]}) {
        filtered_stack =
            std::max(filtered_stack, bench::painted_stack([&] {
                         int32_t value[3];
                         dsn_mix_filtered_point_fixed(&mix, control, one / 3, one / 5, &footprint, value);
                     }));
        lattice_stack = std::max(lattice_stack, bench::painted_stack([&] {
                                     int32_t value[3];
                                     dsn_mix_lattice_point_fixed(&mix, control, 3, 4, value);
                                 }));
        continuous_stack =
            std::max(continuous_stack, bench::painted_stack([&] {
                         int32_t value[3];
                         dsn_mix_continuous_point_fixed(&mix, control, one / 3, one / 5, value);
                     }));
    }
    own_filtered_stack = bench::painted_stack([&] {
        int32_t value[3];
        dsn_filtered_point_fixed(&a->noise, one / 3, one / 5, &footprint, value);
    });
    std::printf(
        "  stack (painted) of a mix point call: lattice %zu bytes, continuous %zu bytes, filtered %zu "
        "bytes (one material's filtered point: %zu bytes)\n",
        lattice_stack, continuous_stack, filtered_stack, own_filtered_stack);
    std::printf(
        "  stack (painted) of a mixed tile call, 16 x 4 pixels: lattice %zu bytes, continuous %zu bytes\n",
        bench::painted_stack([&] {
            static int32_t values[16 * 4 * 3];
            dsn_mix_lattice_tile_fixed(&mix, &controls[1], 3, 4, 16, 4, values, nullptr, 0);
        }),
        bench::painted_stack([&] {
            static int32_t values[16 * 4 * 3];
            dsn_mix_continuous_tile_fixed(&mix, &controls[1], &grid, 16, 4, values, nullptr, 0);
        }));
    // With scratch, a 50/50 lattice tile goes by the kernel's mixed strips: two materials' strip paths.
    std::printf(
        "  stack (painted) of a lattice tile call, 64 x 64 pixels with scratch: 50/50 mix %zu bytes, one "
        "material %zu bytes\n",
        bench::painted_stack([&] {
            dsn_mix_lattice_tile_fixed(&mix, &controls[0], 3, 4, 64, 64, out.data(), scratch.data(),
                                       scratch.size());
        }),
        bench::painted_stack(
            [&] { dsn_lattice_tile_fixed(&a->noise, 3, 4, 64, 64, out.data(), nullptr, 0); }));
    // And a 50/50 continuous tile splatted by materials (two materials' cell records).
    std::printf(
        "  stack (painted) of a continuous tile call, 64 x 64 pixels with scratch: 50/50 mix %zu bytes, "
        "one material %zu bytes\n",
        bench::painted_stack([&] {
            dsn_mix_continuous_tile_fixed(&mix, &controls[0], &grid, 64, 64, out.data(), scratch.data(),
                                          scratch.size());
        }),
        bench::painted_stack([&] {
            dsn_continuous_tile_fixed(&a->noise, &grid, 64, 64, out.data(), scratch.data(), scratch.size());
        }));
    std::printf("  (checksum %lld)\n", static_cast<long long>(checksum));
    return 0;
}
