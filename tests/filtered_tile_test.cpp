// filtered_tile_test.cpp - filtered tiles (dsn_filtered_tile_*) splatted level by level and tap by tap
// give exactly the filtered per-point values, bit for bit, in every kernel this CPU runs: grey and RGB, 8-
// and 16-bit textons (read from cell records and pixel by pixel), one level blended with the mean or two
// levels (level 0 among them), anisotropic taps, rotations, shear, mirror, periodic noises, origins across
// the 32-bit wraps, tiles of one to three blocks across; and the scratch they ask for.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "fixtures/continuous_fixtures.h"
#include "fixtures/test_assets.h"
#include "offline/bake_internal.h"
#include "runtime/kernels/kernels.h"

using namespace dsn_test;

namespace {

const int64_t one = int64_t(1) << 32;

int64_t q32(double value) { return int64_t(std::llround(value * 4294967296.0)); }

// A synthetic square texton of `side` texels with the baker's pyramid.
dsn::AssetFields pyramid_fields(uint32_t channels, uint32_t side, uint32_t bits, uint64_t seed) {
    dsn::AssetFields fields = synthetic_fields(channels, side, bits, DSN_SHAPE_RECTANGLE, seed);
    fields.interpolation = DSN_INTERPOLATION_BILINEAR;
    fields.pyramid = dsn::texton_pyramid(fields);
    return fields;
}

// A grid rotated by `degrees`, `zoom` texels per pixel along the rows and `zoom * stretch` down the
// columns (anisotropic when stretch is not 1), sheared and mirrored when asked.
dsn_grid filtered_grid(int64_t origin_x, int64_t origin_y, double degrees, double zoom, double stretch,
                       double shear, bool mirror) {
    const double angle = degrees * 3.14159265358979323846 / 180.0;
    const double c = std::cos(angle), s = std::sin(angle), down = zoom * stretch;
    return dsn_grid{
        origin_x,     origin_y, q32((mirror ? -c : c) * zoom), q32(s * zoom), q32(-s * down + shear * zoom),
        q32(c * down)};
}

// Origins across the wraps, 90 texels before them (tiles up to 150 pixels at 1.1 to 10.5 texels per pixel
// cross them).
int64_t origin_near_wraps(std::mt19937_64 &random, int which) {
    return continuous_fixtures::origin_near_wraps(random, which, 90);
}

// The tile of `grid` in every kernel and output type against the filtered points; returns whether it
// was splatted (asked for scratch).
bool tile_matches_points(const dsn_noise *noise, const dsn_grid &grid, uint32_t max_taps, uint32_t width,
                         uint32_t height) {
    const uint32_t channels = dsn_noise_channels(noise);
    const dsn_footprint footprint{grid.column_step_x, grid.column_step_y, grid.row_step_x, grid.row_step_y,
                                  max_taps};
    std::vector<int32_t> points(size_t(width) * height * channels);
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++)
            REQUIRE(
                dsn_filtered_point_fixed(noise,
                                         int64_t(uint64_t(grid.origin_x) + uint64_t(grid.column_step_x) * i +
                                                 uint64_t(grid.row_step_x) * j),
                                         int64_t(uint64_t(grid.origin_y) + uint64_t(grid.column_step_y) * i +
                                                 uint64_t(grid.row_step_y) * j),
                                         &footprint, &points[(size_t(j) * width + i) * channels]) == DSN_OK);
    const size_t scratch_size = dsn_filtered_tile_scratch_size(noise, &grid, max_taps, width, height);
    std::vector<unsigned char> buffer(scratch_size + 5);
    unsigned char *scratch = buffer.data() + 5; // no alignment needed
    for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_state(noise)->tile_kernel; kernel++) {
        dsn_noise copy = *noise;
        dsn_state(&copy)->tile_kernel = kernel;
        CAPTURE(kernel);
        std::vector<int32_t> tile(points.size());
        std::vector<float> tile_float(points.size());
        std::vector<uint8_t> tile_u8(points.size());
        if (scratch_size != 0) {
            CHECK(dsn_filtered_tile_fixed(&copy, &grid, max_taps, width, height, tile.data(), nullptr, 0) ==
                  DSN_ERR_SCRATCH);
            CHECK(dsn_filtered_tile_fixed(&copy, &grid, max_taps, width, height, tile.data(), scratch,
                                          scratch_size - 1) == DSN_ERR_SCRATCH);
        }
        REQUIRE(dsn_filtered_tile_fixed(&copy, &grid, max_taps, width, height, tile.data(), scratch,
                                        scratch_size) == DSN_OK);
        REQUIRE(dsn_filtered_tile_float(&copy, &grid, max_taps, width, height, tile_float.data(), scratch,
                                        scratch_size) == DSN_OK);
        REQUIRE(dsn_filtered_tile_u8(&copy, &grid, max_taps, width, height, tile_u8.data(), scratch,
                                     scratch_size) == DSN_OK);
        size_t differences = 0;
        for (size_t k = 0; k < points.size(); k++)
            differences += (tile[k] != points[k]) + (tile_float[k] != dsn_fixed_to_float(points[k])) +
                           (tile_u8[k] != dsn_fixed_to_u8(points[k]));
        CHECK(differences == 0);
    }
    return scratch_size != 0;
}

} // namespace

TEST_CASE("filtered tiles: splatted levels and taps equal the filtered points in every kernel") {
    struct Case {
        uint32_t channels, side, bits, period_x, period_y;
    };
    // 8-bit RGB up to 49 texels and grey up to 89 have cell records; 61-texel RGB level 0 and 16-bit
    // textons go pixel by pixel (the coarser levels of the 61-texel one have records again).
    const Case cases[] = {{3, 31, 8, 0, 0},   {1, 31, 8, 0, 0}, {3, 31, 16, 0, 0},
                          {1, 21, 16, 40, 0}, {3, 61, 8, 0, 0}, {3, 31, 8, 48, 32}};
    // Levels of detail about 0.5, 1, 1.5 and 2 (two levels, level 0 among them, or one), anisotropic ones
    // (2 to 16 taps) stretched down the columns, and stretched along the rows (splatted transposed), all
    // splatted; with a 31-texel texton, coarser ones (impulses reaching too few pixels of a row) and one
    // past the pyramid (the fade) go point by point.
    const struct {
        double zoom, stretch;
        uint32_t max_taps;
        bool splatted;
    } footprints[] = {{1.41, 1, 1, true},  {2.0, 1, 1, true},  {2.83, 1, 4, true},   {4.0, 1, 1, true},
                      {1.2, 4, 8, true},   {2.2, 3, 4, true},  {1.1, 16, 16, true},  {5.6, 1, 1, false},
                      {10.5, 1, 1, false}, {300, 1, 1, false}, {6.4, 0.25, 4, true}, {12.0, 0.25, 4, true}};
    std::mt19937_64 random(77);
    size_t splatted = 0, total = 0; // tiles splatted, of all
    int which = 0;
    for (const Case &c : cases) {
        LoadedNoise loaded(pyramid_fields(c.channels, c.side, c.bits, 40 + uint64_t(which)),
                           make_config(5 + uint32_t(which), 30, c.period_x, c.period_y));
        CAPTURE(c.channels);
        CAPTURE(c.side);
        CAPTURE(c.bits);
        CAPTURE(c.period_x);
        for (const auto &f : footprints) {
            const double degrees = double(random() % 360);
            const dsn_grid grid =
                filtered_grid(origin_near_wraps(random, which), origin_near_wraps(random, which + 1), degrees,
                              f.zoom, f.stretch, which % 3 == 0 ? 0.25 : 0.0, which % 5 == 1);
            CAPTURE(degrees);
            CAPTURE(f.zoom);
            CAPTURE(f.stretch);
            CAPTURE(grid.origin_x);
            CAPTURE(grid.origin_y);
            // Up to three blocks across and two down.
            const uint32_t width = 1 + uint32_t(random() % 150), height = 1 + uint32_t(random() % 50);
            CAPTURE(width);
            CAPTURE(height);
            const bool splat = tile_matches_points(&loaded.noise, grid, f.max_taps, width, height);
            // As planned for the 31-texel textons (a larger one reaches longer runs), but for periodic grids
            // crossing the int32 wrap (point by point).
            if (c.side == 31 && c.period_x == 0 && c.period_y == 0)
                CHECK(splat == (f.splatted && !DSN_SMALL_CODE));
            splatted += splat;
            total++;
            which++;
        }
        // Axis-aligned grids take the kernels' aligned runs.
        const dsn_grid aligned =
            filtered_grid(origin_near_wraps(random, which), -7 * one, 0, 2.9, 1, 0, false);
        splatted += tile_matches_points(&loaded.noise, aligned, 1, 70, 33);
        total++;
    }
    CHECK(splatted >= (DSN_SMALL_CODE ? 0 : total / 2));
#if !DSN_SMALL_CODE
    // A block's sums and totals (twice the continuous tile's), however large the tile.
    LoadedNoise loaded(pyramid_fields(3, 31, 8, 3), make_config(1));
    const dsn_grid minified = filtered_grid(0, 0, 30, 2.0, 1, 0, false);
    CHECK(dsn_filtered_tile_scratch_size(&loaded.noise, &minified, 1, 4096, 4096) ==
          2 * (72 * 32 * 3 * 8 + 7));
#endif
}
