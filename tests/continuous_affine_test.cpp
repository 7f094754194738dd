// continuous_affine_test.cpp - continuous tiles under any affine grid (rotations, zooms in and out, shear,
// mirror, periodic noises) give exactly the per-point values, bit for bit, in every kernel this CPU runs,
// including across the 32-bit wraps, on grids that fall back to per point, and on the textons the vector
// runs read from cell records as well as those they read pixel by pixel.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "fixtures/continuous_fixtures.h"
#include "runtime/kernels/kernels.h"
#include "runtime/kernels/splat_cells.h"

using namespace continuous_fixtures;

namespace {

const int64_t one = int64_t(1) << 32;

int64_t q32(double value) { return int64_t(std::llround(value * 4294967296.0)); }

// The grid of a rotation by `degrees`, then a scale of `zoom` texels per pixel, sheared by `shear`
// (added to the row step's x) and mirrored in x when asked.
dsn_grid affine_grid(int64_t origin_x, int64_t origin_y, double degrees, double zoom, double shear,
                     bool mirror) {
    const double angle = degrees * 3.14159265358979323846 / 180.0;
    const double c = std::cos(angle) * zoom, s = std::sin(angle) * zoom;
    dsn_grid grid;
    grid.origin_x = origin_x;
    grid.origin_y = origin_y;
    grid.column_step_x = q32(mirror ? -c : c);
    grid.column_step_y = q32(s);
    grid.row_step_x = q32(-s + shear * zoom);
    grid.row_step_y = q32(c);
    return grid;
}

// Evaluates the grid as a tile in every output type and checks each pixel against the per-point call.
// Returns whether the tile was splatted (asked for scratch).
bool tile_matches_points_in_kernel(const dsn_noise *noise, const dsn_grid &grid, uint32_t width,
                                   uint32_t height) {
    const uint32_t channels = dsn_noise_channels(noise);
    const size_t scratch_size = dsn_continuous_tile_scratch_size(noise, &grid, width, height);
    std::vector<unsigned char> buffer(scratch_size + 3);
    unsigned char *scratch = buffer.data() + 3; // no alignment needed
    std::vector<int32_t> tile(size_t(width) * height * channels);
    std::vector<float> tile_float(tile.size());
    std::vector<uint8_t> tile_u8(tile.size());
    if (scratch_size != 0) {
        CHECK(dsn_continuous_tile_fixed(noise, &grid, width, height, tile.data(), scratch,
                                        scratch_size - 1) == DSN_ERR_SCRATCH);
    }
    REQUIRE(dsn_continuous_tile_fixed(noise, &grid, width, height, tile.data(), scratch, scratch_size) ==
            DSN_OK);
    REQUIRE(dsn_continuous_tile_float(noise, &grid, width, height, tile_float.data(), scratch,
                                      scratch_size) == DSN_OK);
    REQUIRE(dsn_continuous_tile_u8(noise, &grid, width, height, tile_u8.data(), scratch, scratch_size) ==
            DSN_OK);
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            const int64_t x = int64_t(uint64_t(grid.origin_x) + uint64_t(grid.column_step_x) * i +
                                      uint64_t(grid.row_step_x) * j);
            const int64_t y = int64_t(uint64_t(grid.origin_y) + uint64_t(grid.column_step_y) * i +
                                      uint64_t(grid.row_step_y) * j);
            int32_t point[3];
            REQUIRE(dsn_continuous_point_fixed(noise, x, y, point) == DSN_OK);
            for (uint32_t c = 0; c < channels; c++) {
                const size_t at = (size_t(j) * width + i) * channels + c;
                CAPTURE(i);
                CAPTURE(j);
                REQUIRE(tile[at] == point[c]);
                REQUIRE(tile_float[at] == dsn_fixed_to_float(point[c]));
                REQUIRE(tile_u8[at] == dsn_fixed_to_u8(point[c]));
            }
        }
    return scratch_size != 0;
}

// The same in every kernel (copy of the splat's inner loop) that this CPU runs.
bool tile_matches_points(const dsn_noise *noise, const dsn_grid &grid, uint32_t width, uint32_t height) {
    bool splatted = false;
    for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_state(noise)->tile_kernel; kernel++) {
        dsn_noise copy = *noise;
        dsn_state(&copy)->tile_kernel = kernel;
        CAPTURE(kernel);
        splatted = tile_matches_points_in_kernel(&copy, grid, width, height);
    }
    return splatted;
}

// Origins across the wraps, 20 texels before them (tiles up to 60 pixels at up to 3.1 texels per pixel
// cross them).
int64_t origin_near_wraps(std::mt19937_64 &random, int which) {
    return continuous_fixtures::origin_near_wraps(random, which, 20);
}

// One grid at a random size up to max_width x max_height, counted in *total and, when splatted, in
// *splatted.
void check_random_size(const dsn_noise *noise, const dsn_grid &grid, std::mt19937_64 &random,
                       uint32_t max_width, uint32_t max_height, size_t *splatted, size_t *total) {
    CAPTURE(grid.origin_x);
    CAPTURE(grid.origin_y);
    *splatted += tile_matches_points(noise, grid, 1 + uint32_t(random() % max_width),
                                     1 + uint32_t(random() % max_height));
    ++*total;
}

// At least 7 in 10 of the grids were splatted (none in the small build).
void check_mostly_splatted(size_t splatted, size_t total) {
#if DSN_SMALL_CODE
    (void)total;
    CHECK(splatted == 0);
#else
    CHECK(splatted * 10 >= total * 7);
#endif
}

} // namespace

TEST_CASE("continuous affine: rotated, zoomed, sheared and mirrored tiles equal per point") {
    std::mt19937_64 random(15);
    auto rgb8 = make_noise(random_texton_asset(3, 5, 8, 3), 77);
    auto grey16 = make_noise(random_texton_asset(1, 4, 16, 4), 78, 12u << 16);
    auto rgb16 = make_noise(random_texton_asset(3, 6, 16, 5), 79, 60u << 16);
    auto grey8 = make_noise(random_texton_asset(1, 7, 8, 6), 80, 300u << 16); // dense, larger cells
    const double angles[] = {30, 0, 90, 45, 180, 217.5, -12, 333};
    const double zooms[] = {0.7, 1.7, 0.25, 4, 1, 0.05};
    size_t splatted = 0, total = 0;
    int which = 0;
    for (auto *noise : {&rgb8->noise, &grey16->noise, &rgb16->noise, &grey8->noise}) {
        for (double angle : angles)
            for (double zoom : zooms) {
                const double shear = (which % 3 == 0) ? 0.35 : 0.0;
                const bool mirror = which % 5 == 1;
                const dsn_grid grid =
                    affine_grid(origin_near_wraps(random, which), origin_near_wraps(random, which + 1), angle,
                                zoom, shear, mirror);
                const uint32_t width = 1 + uint32_t(random() % 45), height = 1 + uint32_t(random() % 40);
                CAPTURE(angle);
                CAPTURE(zoom);
                CAPTURE(shear);
                CAPTURE(mirror);
                CAPTURE(grid.origin_x);
                CAPTURE(grid.origin_y);
                splatted += tile_matches_points(noise, grid, width, height);
                total++;
                which++;
            }
    }
#if DSN_SMALL_CODE
    CHECK(splatted == 0);
#else
    CHECK(splatted * 10 >= total * 8); // nearly every one of these grids is splatted
#endif
}

TEST_CASE("continuous affine: periodic noises, also where the grid crosses the int32 wrap") {
    std::mt19937_64 random(16);
    const uint32_t periods[][2] = {{64, 64}, {37, 11}, {1, 300}, {0, 50}, {23, 0}, {3, 5}};
    size_t splatted = 0, fallbacks = 0;
    int which = 0;
    for (const auto &period : periods) {
        auto noise = make_noise(random_texton_asset(3, 4, 8, 6), 5, 0, period[0], period[1]);
        auto noise16 = make_noise(random_texton_asset(1, 3, 16, 7), 6, 20u << 16, period[0], period[1]);
        for (auto *n : {&noise->noise, &noise16->noise})
            for (double angle : {30.0, 0.0, 71.0, 200.0})
                for (double zoom : {0.7, 1.7, 0.25, 4.0}) {
                    const dsn_grid grid =
                        affine_grid(origin_near_wraps(random, which), origin_near_wraps(random, which + 2),
                                    angle, zoom, which % 2 ? 0.2 : 0.0, which % 3 == 0);
                    CAPTURE(period[0]);
                    CAPTURE(period[1]);
                    CAPTURE(angle);
                    CAPTURE(zoom);
                    const bool splat = tile_matches_points(n, grid, 1 + uint32_t(random() % 40),
                                                           1 + uint32_t(random() % 40));
                    splatted += splat;
                    fallbacks += !splat;
                    which++;
                }
    }
#if DSN_SMALL_CODE
    CHECK(splatted == 0);
#else
    CHECK(splatted >= 100);
    CHECK(fallbacks >= 5); // the grids across the int32 wrap of a periodic axis, and the sparse ones
#endif
}

TEST_CASE("continuous affine: degenerate, sparse and huge-step grids fall back or splat, always exact") {
    std::mt19937_64 random(17);
    auto noise = make_noise(random_texton_asset(3, 5, 8, 8), 81, 40u << 16);
    const dsn_noise *n = &noise->noise;
    const dsn_grid grids[] = {
        {one / 3, -one / 5, 0, 0, 0, 0},                          // every pixel the same point
        {one / 3, -one / 5, one / 2, one / 4, one, one / 2},      // collinear steps (zero area)
        {-7 * one, 5 * one, 0, one / 3, one / 5, 0},              // swapped axes
        {INT64_MIN + 3, INT64_MAX - 7, 40 * one, 0, 0, 40 * one}, // sparse: per point
        {5, 9, int64_t(1) << 50, 3, -7, int64_t(1) << 49},        // huge steps: per point
        {-one, one, 65536, -3, 7, 65536},                         // tiny steps, much zoomed in
        {one / 2, one / 2, -one / 3, 0, 0, -one / 2},             // mirrored in both axes
    };
    for (const dsn_grid &grid : grids) {
        CAPTURE(grid.column_step_x);
        tile_matches_points(n, grid, 1 + uint32_t(random() % 70), 1 + uint32_t(random() % 70));
    }
#if !DSN_SMALL_CODE
    CHECK(dsn_continuous_tile_scratch_size(n, &grids[3], 10, 10) == 0);
    CHECK(dsn_continuous_tile_scratch_size(n, &grids[4], 10, 10) == 0);
    CHECK(dsn_continuous_tile_scratch_size(n, &grids[1], 10, 10) == 10 * 10 * 3 * 8 + 7);
    // One block's sums (64 x 32 pixels, rows padded by 8), however large the tile.
    CHECK(dsn_continuous_tile_scratch_size(n, &grids[1], 4096, 4096) == 72 * 32 * 3 * 8 + 7);
    CHECK(dsn_continuous_tile_scratch_size(n, &grids[1], 100, 23) == 100 * 23 * 3 * 8 + 7);
#endif
}

TEST_CASE(
    "continuous affine: random grids (any angle, unequal axes, shear, near-degenerate) equal per point") {
    // Rotated and sheared blocks take the splat's footprint test (the impulses and rows of the block's
    // box that no pixel reaches are skipped): grids at every angle, 0.1 to 6 texels per pixel, unequal
    // axes, shears and nearly collinear steps, on three noises (one periodic), check every row it keeps.
    std::mt19937_64 random(31);
    auto rgb = make_noise(random_texton_asset(3, 15, 8, 1), 1, 30u << 16);
    auto grey16 = make_noise(random_texton_asset(1, 4, 16, 4), 78, 12u << 16);
    auto periodic = make_noise(random_texton_asset(3, 6, 8, 5), 79, 60u << 16, 37, 11);
    const dsn_noise *noises[] = {&rgb->noise, &grey16->noise, &periodic->noise};
    std::uniform_real_distribution<double> unit(0, 1);
    size_t splatted = 0, total = 0;
    for (int t = 0; t < 90; t++) {
        const double degrees = unit(random) * 360, zoom = 0.1 * std::pow(60.0, unit(random));
        const double shear = t % 2 ? unit(random) - 0.5 : 0;
        dsn_grid grid = affine_grid(origin_near_wraps(random, t), origin_near_wraps(random, t + 1), degrees,
                                    zoom, shear, t % 5 == 2);
        const double stretch = 0.3 + 2 * unit(random); // unequal axes: the row step scaled
        grid.row_step_x = int64_t(double(grid.row_step_x) * stretch);
        grid.row_step_y = int64_t(double(grid.row_step_y) * stretch);
        if (t % 7 == 3)
            grid.row_step_x = grid.column_step_x / 3 + int64_t(random() % 1000); // nearly collinear
        CAPTURE(t);
        CAPTURE(degrees);
        CAPTURE(zoom);
        check_random_size(noises[t % 3], grid, random, 120, 80, &splatted, &total);
    }
    check_mostly_splatted(splatted, total);
}

TEST_CASE("continuous affine: larger tiles across several blocks") {
    std::mt19937_64 random(18);
    auto noise = make_noise(random_texton_asset(3, 15, 8, 9), 1, 30u << 16);
    for (double zoom : {0.7, 1.7}) {
        const dsn_grid rotated = affine_grid(-one / 3, INT64_MAX - 40 * one, 30, zoom, 0, false);
        tile_matches_points(&noise->noise, rotated, 100, 70);
    }
    const dsn_grid aligned = affine_grid(one / 7, one / 9, 0, 1.7, 0, false);
    tile_matches_points(&noise->noise, aligned, 90, 65);
}

namespace {

// An 8- or 16-bit texton of (2 radius_x + 1) x (2 radius_y + 1) texels: the rows of a square random one,
// or, `extreme`, every texel at an end of the 8-bit range (the cell records' widest words).
dsn::AssetFields texton_asset(uint32_t channels, uint32_t radius_x, uint32_t radius_y, uint32_t bits,
                              uint32_t seed, bool extreme = false) {
    dsn::AssetFields fields =
        random_texton_asset(channels, radius_x > radius_y ? radius_x : radius_y, bits, seed);
    const uint32_t side = fields.width;
    std::vector<int32_t> texton;
    std::mt19937 random(seed);
    for (uint32_t row = 0; row < 2 * radius_y + 1; row++)
        for (uint32_t column = 0; column < 2 * radius_x + 1; column++)
            for (uint32_t c = 0; c < channels; c++)
                texton.push_back(extreme ? ((random() & 1) ? 127 : -127)
                                         : fields.texton[(row * side + column) * channels + c]);
    fields.width = 2 * radius_x + 1;
    fields.height = 2 * radius_y + 1;
    fields.texton = texton;
    return fields;
}

} // namespace

TEST_CASE("continuous affine: the vector runs of every kernel, every run length, edge cells and fallbacks") {
    std::mt19937_64 random(19);
    struct Case {
        uint32_t channels, radius_x, radius_y, bits;
        uint32_t impacts; // per pixel; 0: the default density
        bool extreme;
        bool records; // read from the cell records (8-bit and small enough), else pixel by pixel
    };
    const Case cases[] = {
        {3, 6, 3, 8, 0, false, true},    {1, 2, 9, 8, 0, false, true},   {3, 4, 4, 8, 0, true, true},
        {1, 5, 5, 8, 0, true, true},     {3, 0, 2, 8, 0, false, true},   {3, 3, 5, 8, 400, false, true},
        {1, 3, 2, 8, 500, true, true},   {3, 26, 2, 8, 0, false, true},  {3, 24, 25, 8, 0, false, false},
        {1, 47, 46, 8, 0, false, false}, {3, 4, 6, 16, 0, false, false}, {1, 1, 1, 8, 1, false, true},
    };
    size_t splatted = 0, total = 0;
    int which = 0;
    for (const Case &c : cases) {
        const dsn::AssetFields fields =
            texton_asset(c.channels, c.radius_x, c.radius_y, c.bits, 20 + which, c.extreme);
        auto noise = make_noise(fields, 90 + which, c.impacts << 16);
        CAPTURE(c.channels);
        CAPTURE(c.radius_x);
        CAPTURE(c.radius_y);
        CAPTURE(c.bits);
        CAPTURE(c.impacts);
#if DSN_SPLAT_CELLS
        static uint64_t cells[splat_cell_capacity];
        uint32_t cell_row = 0;
        const dsn_asset &asset = dsn_state(&noise->noise)->asset;
        const dsn_splat_texture texton = {
            asset.texton, asset.width, asset.height, asset.width, asset.channels, asset.bits, 0};
        CHECK((make_splat_cells(texton, cells, splat_cell_capacity, &cell_row, 0) != 0) == c.records);
#endif
        for (double angle : {30.0, 0.0, 90.0, 163.0, 271.0})
            for (double zoom : {0.7, 1.7, 0.3, 3.1}) {
                const dsn_grid grid =
                    affine_grid(origin_near_wraps(random, which), origin_near_wraps(random, which + 1), angle,
                                zoom, which % 4 == 0 ? 0.3 : 0.0, which % 3 == 1);
                CAPTURE(angle);
                CAPTURE(zoom);
                // Up to two blocks across and down: runs of every length up to a block's side.
                check_random_size(&noise->noise, grid, random, 60, 45, &splatted, &total);
                which++;
            }
    }
    check_mostly_splatted(splatted, total);
}

TEST_CASE("continuous affine: axis-aligned grids (zoomed, mirrored, periodic, dense) equal per point") {
    std::mt19937_64 random(21);
    struct Case {
        uint32_t channels, radius, impacts, period_x, period_y;
    };
    const Case cases[] = {
        {3, 5, 0, 0, 0},   {1, 7, 0, 0, 0},  {3, 4, 400, 0, 0}, {1, 3, 600, 0, 0},
        {3, 4, 0, 37, 11}, {1, 6, 0, 0, 50}, {3, 15, 30, 0, 0}, {1, 2, 0, 64, 64},
    };
    // Texels per pixel along x and y: zoomed in and out, unequal, each sign (mirrored on each axis).
    const double steps[][2] = {{0.7, 0.7},  {1.7, 1.7},   {0.3, 2.2},   {3.1, 0.45}, {-0.7, 0.7},
                               {1.7, -1.7}, {-1.3, -0.6}, {0.05, 0.05}, {1.0, -1.0}};
    size_t splatted = 0, total = 0;
    int which = 0;
    for (const Case &c : cases) {
        auto noise = make_noise(random_texton_asset(c.channels, c.radius, 8, 30 + uint32_t(which)),
                                100 + uint32_t(which), c.impacts << 16, c.period_x, c.period_y);
        CAPTURE(c.channels);
        CAPTURE(c.radius);
        CAPTURE(c.impacts);
        CAPTURE(c.period_x);
        CAPTURE(c.period_y);
        for (const auto &step : steps) {
            const dsn_grid grid = {origin_near_wraps(random, which),
                                   origin_near_wraps(random, which + 1),
                                   q32(step[0]),
                                   0,
                                   0,
                                   q32(step[1])};
            CAPTURE(step[0]);
            CAPTURE(step[1]);
            // Up to three blocks across and down: runs cut at the blocks' edges.
            check_random_size(&noise->noise, grid, random, 150, 80, &splatted, &total);
            which++;
        }
    }
    check_mostly_splatted(splatted, total);
}

TEST_CASE("continuous affine: the splat's normalization of every kernel, saturated values included") {
    // Sums from small to far past int32 once normalized (either sign), every count of pixels up to past
    // two vectors: each kernel's normalize entry equals normalize_q32_unmapped pixel by pixel.
    std::mt19937_64 random(23);
    for (uint32_t channels : {1u, 3u}) {
        auto noise = make_noise(random_texton_asset(channels, 4, 8, 40 + channels), 7 + channels);
        const size_t plane = 40;
        std::vector<uint64_t> sums(plane * channels);
        for (uint32_t round = 0; round < 20; round++) {
            for (uint64_t &sum : sums) {
                const uint32_t magnitude = uint32_t(random() % 5); // 2^20 .. 2^62 around 0
                sum = random() >> (2 + 10 * magnitude);
                if (random() & 1) sum = 0u - sum;
            }
            for (uint32_t count = 1; count <= 19; count++) {
                std::vector<int32_t> expected(count * channels);
                for (uint32_t p = 0; p < count; p++) {
                    uint64_t pixel[3];
                    for (uint32_t c = 0; c < channels; c++) pixel[c] = sums[c * plane + p];
                    normalize_q32_unmapped(dsn_state(&noise->noise), pixel, &expected[p * channels]);
                }
                for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_state(&noise->noise)->tile_kernel;
                     kernel++) {
                    const dsn_kernel_entries *entries = dsn_kernel_entries_of(kernel);
                    if (entries->continuous_splat_normalize == 0) continue;
                    std::vector<int32_t> got(count * channels);
                    entries->continuous_splat_normalize(dsn_state(&noise->noise), sums.data(), plane, count,
                                                        got.data());
                    CAPTURE(kernel);
                    CAPTURE(count);
                    CHECK(got == expected);
                }
            }
        }
        // The sums reach both int32 bounds (the test is not vacuous).
        bool low = false, high = false;
        for (uint32_t p = 0; p < plane; p++) {
            uint64_t pixel[3];
            int32_t value[3] = {0, 0, 0};
            for (uint32_t c = 0; c < channels; c++) pixel[c] = sums[c * plane + p];
            normalize_q32_unmapped(dsn_state(&noise->noise), pixel, value);
            for (uint32_t c = 0; c < channels; c++) {
                low = low || value[c] == INT32_MIN;
                high = high || value[c] == INT32_MAX;
            }
        }
        CHECK(low);
        CHECK(high);
    }
}
