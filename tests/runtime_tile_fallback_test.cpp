// runtime_tile_fallback_test.cpp - the strip path's safety net, white box: runtime/kernels/tile_render.h is
// compiled into this test with the test's flags (the default kernel's instruction set: SSE2 on x86) and given
// rectangles larger than choose_rectangle would pick, so that rectangles overflow the impulse list or put
// more than 255 impulses on a column (where 16-bit sums could wrap). Those must take the 32-bit path, their
// neighbours not, and the tile must still equal per-point evaluation bit for bit.
#include <doctest/doctest.h>

#include <vector>

#include "fixtures/test_assets.h"
#include "runtime/kernels/tile_render.h"

#if DSN_TILE_BLOCKS
namespace {

struct FallbackCase {
    uint32_t channels, side;
    double impacts;
    rectangle_size rectangle;
};

// How many of the rectangles of the window (x0, y0, width x height) would fall back, and how many not.
void count_fallbacks(const dsn_noise_state &noise, const strip_setup &setup, int32_t x0, int32_t y0,
                     uint32_t width, uint32_t height, uint32_t *fallbacks, uint32_t *strips) {
    *fallbacks = *strips = 0;
    for (uint32_t y = 0; y < height; y += setup.rectangle.height)
        for (uint32_t x = 0; x < width; x += setup.rectangle.width) {
            tile_run walk_x = {uint32_t(x0) + x, x, std::min(setup.rectangle.width, width - x)};
            tile_run walk_y = {uint32_t(y0) + y, y, std::min(setup.rectangle.height, height - y)};
            impulse_list list;
            list.clear(walk_x.length, walk_y.length);
            for_each_nearby_impulse(&noise, &walk_x, &walk_y, list, keep_every());
            (list.prepare(setup.texton.width, setup.texton.height) ? *strips : *fallbacks) += 1;
        }
}

} // namespace

TEST_CASE("rectangles over the list's capacity or the 16-bit column limit take the 32-bit path, same bits") {
    // Impacts per pixel from the mean impulses per rectangle, lambda (W + w - 1)(H + h - 1) with
    // lambda = impacts / (w h), or per column, lambda w (H + h - 1).
    const rectangle_size largest = {rectangle_width, rectangle_height}, narrow = {16, rectangle_height};
    const double reach_31 = double(largest.width + 30) * (largest.height + 30) / (31.0 * 31.0);
    const FallbackCase cases[] = {
        {3, 31, 1.5 * list_capacity / reach_31, largest}, // every rectangle overflows the list
        {3, 31, 1.0 * list_capacity / reach_31, largest}, // about half of them do
        // Far fewer impulses than the list holds, but 1.5 times the 16-bit limit on a column.
        {1, 33, 1.5 * coverage_limit / (33.0 * (narrow.height + 32) / (33.0 * 33.0)), narrow},
    };
    const int32_t x0 = -300, y0 = 1000;
    const uint32_t width = 200, height = 200;
    for (const FallbackCase &c : cases) {
        dsn_test::LoadedNoise loaded(
            dsn_test::synthetic_fields(c.channels, c.side, 8, DSN_SHAPE_RECTANGLE, 4),
            dsn_test::make_config(9, c.impacts));
        const dsn_noise_state &noise = *dsn_state(&loaded.noise);
        strip_setup setup;
        make_strip_setup(&noise, c.rectangle, uint64_t(width) * height, sizeof(int32_t), &setup);
        uint32_t fallbacks = 0, strips = 0;
        count_fallbacks(noise, setup, x0, y0, width, height, &fallbacks, &strips);
        CAPTURE(c.impacts);
        CHECK(fallbacks > 0);
        if (&c == &cases[1]) CHECK(strips > 0);

        std::vector<int32_t> tile(size_t(width) * height * c.channels);
        const tile_run run_x = {uint32_t(x0), 0, width}, run_y = {uint32_t(y0), 0, height};
        const tile_target target = {tile.data(), dsn_output_fixed,
                                    static_cast<uint32_t *>(static_cast<void *>(tile.data())),
                                    width * c.channels, nullptr};
        if (c.channels == 3)
            render_region<3, int32_t>(&noise, &setup, &run_x, &run_y, &target);
        else
            render_region<1, int32_t>(&noise, &setup, &run_x, &run_y, &target);
        // And the same window as this copy of the tile code cuts it by itself (choose_rectangle).
        std::vector<int32_t> chosen(tile.size());
        render_tile(&noise, uint32_t(x0), uint32_t(y0), width, height, chosen.data(), nullptr, nullptr,
                    dsn_output_fixed, static_cast<uint32_t *>(static_cast<void *>(chosen.data())), nullptr);
        size_t differences = 0, chosen_differences = 0;
        for (uint32_t j = 0; j < height; j++)
            for (uint32_t i = 0; i < width; i++) {
                int32_t point[3];
                dsn_lattice_point_fixed(&loaded.noise, int32_t(uint32_t(x0) + i), int32_t(uint32_t(y0) + j),
                                        point);
                for (uint32_t k = 0; k < c.channels; k++) {
                    differences += point[k] != tile[(size_t(j) * width + i) * c.channels + k];
                    chosen_differences += point[k] != chosen[(size_t(j) * width + i) * c.channels + k];
                }
            }
        CHECK(differences == 0);
        CHECK(chosen_differences == 0);
    }
}
#else
TEST_CASE("rectangles over the list's capacity or the 16-bit column limit take the 32-bit path, same bits") {
    MESSAGE("this target has no SSE2: tiles take the 32-bit path only, there is no strip path to fall back "
            "from (runtime/simd/simd.h)");
}
#endif
