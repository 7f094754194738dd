// runtime_tile_test.cpp - tile evaluation gives exactly the per-point bits, on any window: negative and
// huge origins, windows straddling the 2^32 wrap, periods (including 1 and non-divisors of 2^32).
#include <doctest/doctest.h>

#include <vector>

#include "fixtures/test_assets.h"

namespace {

using dsn_test::LoadedNoise;

} // namespace

TEST_CASE("tile == per point, bit for bit, on random windows, seeds, sizes and periods") {
    dsn_test::TestRandom random(2024);
    const uint32_t periods[] = {0, 0, 1, 2, 7, 31, 64, 100, 1000, 4294967295u, 2147483648u};
    const int32_t interesting[] = {0, -1, -20, INT32_MIN, INT32_MAX - 10, INT32_MAX, -2147483600, 123456789};
    // What the random draws covered, so that a change of generator or tables cannot quietly drop a case
    // the test's name promises.
    int wrapping_windows = 0, negative_origins = 0, unit_periods = 0, odd_periods = 0, varying_windows = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u})
            for (uint32_t shape : {uint32_t(DSN_SHAPE_RECTANGLE), uint32_t(DSN_SHAPE_DISK)}) {
                uint32_t side = 1 + 2 * (random.next() % 12);
                auto fields = dsn_test::synthetic_fields(channels, side, bits, shape, random.next());
                for (int round = 0; round < 6; round++) {
                    uint32_t period_x = periods[random.next() % 11], period_y = periods[random.next() % 11];
                    double impacts = (random.next() % 2) ? 30 : 5 + random.next() % 200;
                    LoadedNoise loaded(fields,
                                       dsn_test::make_config(random.next(), impacts, period_x, period_y));
                    int32_t x0 = (round % 2)
                                     ? int32_t(uint32_t(interesting[random.next() % 8]) - random.next() % 20)
                                     : int32_t(random.next());
                    int32_t y0 = (round % 3) ? interesting[random.next() % 8] : int32_t(random.next());
                    uint32_t width = 1 + random.next() % 40, height = 1 + random.next() % 40;
                    CAPTURE(channels);
                    CAPTURE(bits);
                    CAPTURE(side);
                    CAPTURE(period_x);
                    CAPTURE(period_y);
                    CAPTURE(x0);
                    CAPTURE(y0);
                    CHECK(dsn_test::tile_point_differences(loaded.noise, x0, y0, width, height) == 0);
                    // The 2^32 wrap: INT32_MAX -> INT32_MIN inside the window, in x or y.
                    const uint64_t wrap = 0x80000000u;
                    wrapping_windows += (uint64_t(uint32_t(x0) ^ wrap) + width > 0xFFFFFFFFu) ||
                                        (uint64_t(uint32_t(y0) ^ wrap) + height > 0xFFFFFFFFu);
                    negative_origins += x0 < 0 || y0 < 0;
                    unit_periods += period_x == 1 || period_y == 1;
                    for (uint32_t period : {period_x, period_y})
                        odd_periods += period > 1 && (period & (period - 1)) != 0; // not a divisor of 2^32
                    // A window of one repeated value would compare nothing worth comparing.
                    int32_t first[3], last[3];
                    dsn_lattice_point_fixed(&loaded.noise, x0, y0, first);
                    dsn_lattice_point_fixed(&loaded.noise, int32_t(uint32_t(x0) + width - 1),
                                            int32_t(uint32_t(y0) + height - 1), last);
                    varying_windows += first[0] != last[0];
                }
            }
    MESSAGE("windows: " << wrapping_windows << " wrapping, " << negative_origins << " at negative origins, "
                        << unit_periods << " with period 1, " << odd_periods << " odd periods, "
                        << varying_windows << " varying");
    CHECK(wrapping_windows >= 4);
    CHECK(negative_origins >= 4);
    CHECK(unit_periods >= 2);
    CHECK(odd_periods >= 4);
    CHECK(varying_windows >= 24);
}
