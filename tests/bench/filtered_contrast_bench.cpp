// filtered_contrast_bench.cpp - the contrast of the filtered evaluation against the box-supersampled
// reference of the same noise (fixtures/pyramid_fixture.h, filtered_contrast): an axis-aligned grid of
// pixels px x py texels, each the mean of the continuous noise over its rectangle, against the filtered
// value at its centre with its footprint (up to 16 taps). Per footprint: the filtered render's standard
// deviation over the reference's (1: the same contrast) and the RMSE between them in units of the
// unfiltered noise's standard deviation, for the baker's pyramid (levels of standard deviation 2^(l-1))
// and for box-wide levels (standard deviation 2^l / sqrt(12), a box 2^l wide's, each scaled to keep the
// energy of t0 * G_l; computed by the fixture). Then the mean frame-to-frame change of a 20 x 20 render
// moving by (0.3, 0.1) pixel per frame: unfiltered, box reference, baker's levels, box-wide levels.
// Two grey 141 x 141 bilinear textons (7 levels, so 64x is read from level 6): a random one under a tent
// envelope (a broad spectrum) and the same smoothed by a 5 x 5 box (most of its power at low
// frequencies); and filtered_test's 31 x 31 test asset, a bump times a wave of 0.7 radians per texel (a
// narrow band, which a box's side lobes pass where a Gaussian does not; 4 levels, footprints up to 16
// texels). 30 impacts per pixel.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fixtures/continuous_fixtures.h"
#include "fixtures/pyramid_fixture.h"
#include "fixtures/test_assets.h"
#include "offline/bake_internal.h"

namespace {

dsn::AssetFields smoothed(dsn::AssetFields fields) {
    const int side = int(fields.width), reach = 2;
    std::vector<double> sums(fields.texton.size());
    for (int y = 0; y < side; y++)
        for (int x = 0; x < side; x++) {
            double sum = 0;
            for (int v = -reach; v <= reach; v++)
                for (int u = -reach; u <= reach; u++)
                    if (x + u >= 0 && x + u < side && y + v >= 0 && y + v < side)
                        sum += fields.texton[size_t((y + v) * side + x + u)];
            sums[size_t(y * side + x)] = sum;
        }
    double largest = 0;
    for (double sum : sums) largest = std::max(largest, std::fabs(sum));
    for (size_t i = 0; i < sums.size(); i++) fields.texton[i] = int32_t(std::lround(sums[i] * 127 / largest));
    return fields;
}

double frame_change(const dsn_noise &noise, double pixel, int mode) {
    dsn_footprint f;
    dsn_footprint_from_float(&f, pixel, 0, 0, pixel, 16);
    std::vector<double> previous, current;
    double change = 0;
    for (int frame = 0; frame < 4; frame++) {
        current.clear();
        if (mode == 2)
            dsn_test::filtered_contrast(noise, pixel, pixel, int(2 * pixel), 20, 20, 1, 0,
                                        3000 + (0.3 * frame - 0.5) * pixel,
                                        5000 + (0.1 * frame - 0.5) * pixel, &current);
        else
            for (int j = 0; j < 20; j++)
                for (int i = 0; i < 20; i++) {
                    const double x = 3000 + (i + 0.3 * frame) * pixel, y = 5000 + (j + 0.1 * frame) * pixel;
                    float out[3];
                    if (mode == 1)
                        dsn_filtered_point_float(&noise, x, y, &f, out);
                    else
                        dsn_continuous_point_float(&noise, x, y, out);
                    current.push_back(out[0]);
                }
        for (size_t p = 0; p < previous.size(); p++) change += std::fabs(current[p] - previous[p]);
        previous = current;
    }
    return change / (3 * 400);
}

} // namespace

int main() {
    using namespace continuous_fixtures;
    dsn::AssetFields narrow = dsn_test::synthetic_fields(1, 31, 8, DSN_SHAPE_RECTANGLE, 61);
    narrow.interpolation = DSN_INTERPOLATION_BILINEAR;
    const dsn::AssetFields textons[3] = {random_texton_asset(1, 70, 8, 5),
                                         smoothed(random_texton_asset(1, 70, 8, 5)), narrow};
    const char *names[3] = {"broad (141 x 141", "smooth (141 x 141", "narrow-band (31 x 31"};
    struct Case {
        double px, py;
    };
    const Case cases[] = {{4, 4},   {6, 6},   {8, 8},  {12, 12}, {16, 16}, {24, 24}, {32, 32},
                          {48, 48}, {64, 64}, {2, 16}, {4, 32},  {16, 4},  {3, 24}};
    for (int t = 0; t < 3; t++) {
        dsn::AssetFields baked = textons[t], box_wide = textons[t];
        baked.pyramid = dsn::texton_pyramid(baked);
        dsn_test::add_test_pyramid(box_wide, 1 / std::sqrt(12.0), true);
        auto noise = make_noise(baked, 7, 30u << 16);
        auto box_noise = make_noise(box_wide, 7, 30u << 16);
        std::printf("%s texton, %zu levels):\n", names[t], baked.pyramid.size());
        std::printf("  pixel (texels)  lod   taps  std / box reference      rmse / unfiltered std  "
                    "box reference std\n");
        std::printf("                              baker's  box-wide        baker's  box-wide      "
                    "/ unfiltered\n");
        for (const Case &c : cases) {
            const double longer = std::max(c.px, c.py);
            if (t == 2 && longer > 16) continue; // past the test asset's coarsest level
            const int samples = int(std::max(8.0, 2 * longer)), pixels = longer <= 16 ? 48 : 32;
            const auto now =
                dsn_test::filtered_contrast(noise->noise, c.px, c.py, samples, pixels, pixels, 16, 0);
            const auto matched =
                dsn_test::filtered_contrast(box_noise->noise, c.px, c.py, samples, pixels, pixels, 16, 0);
            dsn_footprint f;
            dsn_footprint_from_float(&f, c.px, 0, 0, c.py, 16);
            int32_t lod = 0;
            uint32_t taps = 0;
            dsn_filter_level(&noise->noise, &f, &lod, &taps);
            std::printf("  %5.0f x %-5.0f   %5.2f  %4u  %7.3f  %8.3f        %7.4f  %8.4f      %6.3f\n", c.px,
                        c.py, lod / 256.0, taps, now.ratio(), matched.ratio(), now.rmse / now.deviation,
                        matched.rmse / matched.deviation, now.reference_deviation / now.deviation);
        }
        std::printf("  frame-to-frame change: pixel  unfiltered  box reference  baker's  box-wide\n");
        for (double pixel : {4.0, 8.0, 16.0})
            std::printf("                         %5.0f  %10.4f  %13.4f  %7.4f  %8.4f\n", pixel,
                        frame_change(noise->noise, pixel, 0), frame_change(noise->noise, pixel, 2),
                        frame_change(noise->noise, pixel, 1), frame_change(box_noise->noise, pixel, 1));
    }
    return 0;
}
