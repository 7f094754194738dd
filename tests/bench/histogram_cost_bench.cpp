// histogram_cost_bench.cpp - cost of the histogram-preserving output (format 1.2) as ratios to the same noise
// without it (DSN_FLAG_NO_HISTOGRAM) measured in the same run: RGB, 31 x 31 texton with the baker's
// pyramid, 30 impacts per pixel, a 65-entry table per level and channel, one thread; every evaluation
// kind (lattice point and tile, continuous point, tile and batch, filtered point).
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench_timing.h"
#include "fixtures/continuous_fixtures.h"
#include "offline/bake_internal.h"

namespace {

using bench::best_time;
int64_t checksum = 0; // keeps the evaluations observable

int64_t q32(double texels) { return int64_t(std::floor(texels * 4294967296.0)); }

// An increasing table per level and channel over [-4, 4] in steps of 1/8, a rotation using every entry.
dsn::HistogramMapping mapping(uint32_t levels) {
    dsn::HistogramMapping m;
    m.level_count = levels;
    for (uint32_t l = 0; l < levels; l++)
        for (uint32_t k = 0; k < 3; k++)
            for (uint32_t i = 0; i < m.entry_count; i++) {
                const double x = -4.0 + i / 8.0;
                m.tables.push_back(int32_t(std::lround((0.3 * x + 0.05 * x * x * x) * (1 - 0.1 * l) * 4096)));
            }
    const double P[9] = {0.8, -0.3, 0.2, 0.35, 0.9, -0.1, -0.25, 0.15, 1.05};
    for (int i = 0; i < 9; i++) m.rotation[i] = int32_t(std::lround(P[i] * DSN_Q24_ONE));
    for (int c = 0; c < 3; c++) m.centre[c] = DSN_Q24_ONE / 2;
    return m;
}

} // namespace

int main() {
    using namespace continuous_fixtures;
    dsn::AssetFields fields = random_texton_asset(3, 15, 8, 1);
    fields.pyramid = dsn::texton_pyramid(fields);
    fields.histogram = mapping(uint32_t(1 + fields.pyramid.size()));
    auto mapped_noise = make_noise(fields, 1, 30u << 16, 0, 0, DSN_FLAG_ALLOW_LATTICE_CONTINUOUS);
    auto gaussian_noise =
        make_noise(fields, 1, 30u << 16, 0, 0, DSN_FLAG_ALLOW_LATTICE_CONTINUOUS | DSN_FLAG_NO_HISTOGRAM);
    const dsn_noise *mapped = &mapped_noise->noise, *gaussian = &gaussian_noise->noise;

    const uint32_t side = 256, points = 20000;
    std::vector<int32_t> fixed(size_t(side) * side * 3);
    std::vector<uint8_t> bytes(fixed.size());
    dsn_grid grid{q32(0.3), q32(0.7), q32(0.37), q32(0.05), q32(-0.05), q32(0.37)};
    std::vector<unsigned char> scratch(std::max({dsn_lattice_tile_scratch_size(mapped, side, side),
                                                 dsn_continuous_tile_scratch_size(mapped, &grid, side, side),
                                                 dsn_continuous_batch_scratch_size(mapped)}));
    std::vector<int64_t> xs(points), ys(points);
    for (uint32_t i = 0; i < points; i++) {
        xs[i] = int64_t(i % 200) * q32(2.8191) - int64_t(i / 200) * q32(1.0261) + q32(1.0 / 3);
        ys[i] = int64_t(i % 200) * q32(1.0261) + int64_t(i / 200) * q32(2.8191) + q32(1.0 / 7);
    }
    const dsn_footprint footprint{q32(2.8), 0, 0, q32(2.8), 1};

    struct Case {
        const char *name;
        void (*run)(const dsn_noise *, std::vector<int32_t> &, std::vector<uint8_t> &,
                    std::vector<unsigned char> &, const dsn_grid &, const std::vector<int64_t> &,
                    const std::vector<int64_t> &, const dsn_footprint &);
    };
    const Case cases[] = {
        {"lattice point (20000)",
         [](const dsn_noise *n, std::vector<int32_t> &, std::vector<uint8_t> &, std::vector<unsigned char> &,
            const dsn_grid &, const std::vector<int64_t> &, const std::vector<int64_t> &,
            const dsn_footprint &) {
             int32_t out[3];
             for (int32_t i = 0; i < 20000; i++)
                 dsn_lattice_point_fixed(n, i % 200, i / 200, out), checksum += out[0];
         }},
        {"lattice tile 256 x 256 fixed",
         [](const dsn_noise *n, std::vector<int32_t> &f, std::vector<uint8_t> &, std::vector<unsigned char> &,
            const dsn_grid &, const std::vector<int64_t> &, const std::vector<int64_t> &,
            const dsn_footprint &) {
             dsn_lattice_tile_fixed(n, 5, 7, 256, 256, f.data(), nullptr, 0);
             checksum += f[1000];
         }},
        {"lattice tile 256 x 256 u8",
         [](const dsn_noise *n, std::vector<int32_t> &, std::vector<uint8_t> &b,
            std::vector<unsigned char> &s, const dsn_grid &, const std::vector<int64_t> &,
            const std::vector<int64_t> &, const dsn_footprint &) {
             dsn_lattice_tile_u8(n, 5, 7, 256, 256, b.data(), s.data(), s.size());
             checksum += b[1000];
         }},
        {"continuous point (20000)",
         [](const dsn_noise *n, std::vector<int32_t> &, std::vector<uint8_t> &, std::vector<unsigned char> &,
            const dsn_grid &, const std::vector<int64_t> &x, const std::vector<int64_t> &y,
            const dsn_footprint &) {
             int32_t out[3];
             for (size_t i = 0; i < x.size(); i++)
                 dsn_continuous_point_fixed(n, x[i], y[i], out), checksum += out[0];
         }},
        {"continuous tile 256 x 256 (splat)",
         [](const dsn_noise *n, std::vector<int32_t> &f, std::vector<uint8_t> &,
            std::vector<unsigned char> &s, const dsn_grid &g, const std::vector<int64_t> &,
            const std::vector<int64_t> &, const dsn_footprint &) {
             dsn_continuous_tile_fixed(n, &g, 256, 256, f.data(), s.data(), s.size());
             checksum += f[1000];
         }},
        {"continuous batch (20000)",
         [](const dsn_noise *n, std::vector<int32_t> &f, std::vector<uint8_t> &,
            std::vector<unsigned char> &s, const dsn_grid &, const std::vector<int64_t> &x,
            const std::vector<int64_t> &y, const dsn_footprint &) {
             dsn_continuous_batch_fixed(n, x.data(), y.data(), uint32_t(x.size()), f.data(), s.data(),
                                        s.size());
             checksum += f[1000];
         }},
        {"filtered point, LOD 1.5 (20000)",
         [](const dsn_noise *n, std::vector<int32_t> &, std::vector<uint8_t> &, std::vector<unsigned char> &,
            const dsn_grid &, const std::vector<int64_t> &x, const std::vector<int64_t> &y,
            const dsn_footprint &fp) {
             int32_t out[3];
             for (size_t i = 0; i < x.size(); i++)
                 dsn_filtered_point_fixed(n, x[i], y[i], &fp, out), checksum += out[0];
         }},
    };
    for (const Case &c : cases) {
        // Alternate the two noises so that both see the same machine load; keep each one's best.
        double with = 1e30, without = 1e30;
        for (int round = 0; round < 5; round++) {
            without = std::min(without, best_time(1, [&] {
                                   c.run(gaussian, fixed, bytes, scratch, grid, xs, ys, footprint);
                               }));
            with = std::min(
                with, best_time(1, [&] { c.run(mapped, fixed, bytes, scratch, grid, xs, ys, footprint); }));
        }
        std::printf("%-36s %.2fx the Gaussian-space noise (%.2f ms vs %.2f ms)\n", c.name, with / without,
                    with * 1e3, without * 1e3);
    }
    std::printf("(checksum %lld)\n", static_cast<long long>(checksum));
    return 0;
}
