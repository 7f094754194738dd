// runtime_tile_strips_test.cpp - the strip path of tiles (16-bit sums in registers, split normalization,
// per-strip output conversion; runtime/kernels/tile_strips.h) against per-point evaluation, on windows
// spanning many rectangles: every output type, origins at the 32-bit wrap, periods, densities and texton
// sizes (down to those that take the 32-bit path), and textons at full scale (the largest sums the 16-bit
// path accepts). Every check runs each kernel this CPU can run (on x86-64: the default SSE2 kernel, with AVX2
// the AVX2 kernel, and with AVX-512 the AVX-512 kernel; runtime/kernels/kernels.h).
#include <doctest/doctest.h>

#include <cstring>
#include <string>
#include <vector>

#if defined(__x86_64__)
#include <cpuid.h>
#endif

#include "fixtures/test_assets.h"
#include "runtime/kernels/kernels.h"

namespace {

using dsn_test::LoadedNoise;

struct Window {
    int32_t x0, y0;
    uint32_t width, height;
};

int32_t coordinate(int32_t origin, uint32_t offset) { return int32_t(uint32_t(origin) + offset); }

// Values of the three tile functions that differ from per-point evaluation (fixed, float bits, u8), with
// the kernel the noise's tile_kernel names.
size_t kernel_differences(const dsn_noise &noise, const Window &w) {
    const uint32_t channels = dsn_noise_channels(&noise);
    const size_t values = size_t(w.width) * w.height * channels;
    std::vector<int32_t> fixed(values);
    std::vector<float> floats(values);
    std::vector<uint8_t> bytes(values);
    std::vector<unsigned char> scratch(dsn_lattice_tile_scratch_size(&noise, w.width, w.height));
    REQUIRE(dsn_lattice_tile_fixed(&noise, w.x0, w.y0, w.width, w.height, fixed.data(), nullptr, 0) ==
            DSN_OK);
    REQUIRE(dsn_lattice_tile_float(&noise, w.x0, w.y0, w.width, w.height, floats.data(), scratch.data(),
                                   scratch.size()) == DSN_OK);
    REQUIRE(dsn_lattice_tile_u8(&noise, w.x0, w.y0, w.width, w.height, bytes.data(), scratch.data(),
                                scratch.size()) == DSN_OK);
    size_t count = 0;
    for (uint32_t j = 0; j < w.height; j++)
        for (uint32_t i = 0; i < w.width; i++) {
            int32_t point[3];
            float point_float[3];
            uint8_t point_u8[3];
            dsn_lattice_point_fixed(&noise, coordinate(w.x0, i), coordinate(w.y0, j), point);
            dsn_lattice_point_float(&noise, coordinate(w.x0, i), coordinate(w.y0, j), point_float);
            dsn_lattice_point_u8(&noise, coordinate(w.x0, i), coordinate(w.y0, j), point_u8);
            for (uint32_t c = 0; c < channels; c++) {
                size_t index = (size_t(j) * w.width + i) * channels + c;
                count += fixed[index] != point[c];
                count += std::memcmp(&floats[index], &point_float[c], sizeof(float)) != 0;
                count += bytes[index] != point_u8[c];
            }
        }
    return count;
}

// kernel_differences summed over every kernel this CPU runs.
size_t differences(const dsn_noise &noise, const Window &w) {
    size_t count = 0;
    for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_state(&noise)->tile_kernel; kernel++) {
        dsn_noise copy = noise;
        dsn_state(&copy)->tile_kernel = kernel;
        CAPTURE(kernel);
        count += kernel_differences(copy, w);
    }
    return count;
}

} // namespace

TEST_CASE("the kernel table: row i is kernel i, with its entry points; every row but the default has a CPU "
          "check") {
    REQUIRE(dsn_internal_kernel_count >= 1);
    for (uint32_t i = 0; i < dsn_internal_kernel_count; i++) {
        const dsn_kernel &kernel = dsn_internal_kernels[i];
        CAPTURE(i);
        CHECK(uint32_t(kernel.id) == i);
        CHECK(kernel.name != nullptr);
        REQUIRE(kernel.entries != nullptr);
        const bool has_lattice_tile = kernel.entries->lattice_tile != nullptr;
        CHECK(has_lattice_tile);
        const bool has_cpu_check = kernel.cpu_runs != nullptr;
        CHECK(has_cpu_check == (i != 0));
    }
    // An id outside the table (a dsn_noise not set by init) falls back to the default kernel.
    CHECK(dsn_kernel_entries_of(dsn_internal_kernel_count) == dsn_internal_kernels[0].entries);
}

#if defined(__x86_64__)
// The CPU's family as /proc/cpuinfo shows it on AMD (base family, plus the extended one when the base is
// 15), 0 on other vendors.
static uint32_t amd_family() {
    unsigned int eax = 0, ebx = 0, ecx = 0, edx = 0;
    char vendor[13] = {};
    __get_cpuid(0, &eax, &ebx, &ecx, &edx);
    std::memcpy(vendor, &ebx, 4), std::memcpy(vendor + 4, &edx, 4), std::memcpy(vendor + 8, &ecx, 4);
    if (std::string(vendor) != "AuthenticAMD") return 0;
    __get_cpuid(1, &eax, &ebx, &ecx, &edx);
    const uint32_t base = (eax >> 8) & 0xF;
    return base == 0xF ? base + ((eax >> 20) & 0xFF) : base;
}
#endif

TEST_CASE("the AVX-512 kernel with AVX2 lattice tiles is the AVX-512 kernel but for its lattice tile") {
    if (dsn_internal_kernel_count < 4) return;
    const dsn_kernel_entries *mixed = dsn_internal_kernels[DSN_KERNEL_AVX512_AVX2_TILES].entries,
                             *avx512 = dsn_internal_kernels[DSN_KERNEL_AVX512].entries;
    // Function pointers compared as bools (doctest prints neither side of a pointer comparison).
    const bool other_tile = mixed->lattice_tile != avx512->lattice_tile,
               same_rest = mixed->continuous_batch == avx512->continuous_batch &&
                           mixed->continuous_splat_runs == avx512->continuous_splat_runs &&
                           mixed->continuous_splat_normalize == avx512->continuous_splat_normalize &&
                           mixed->continuous_point == avx512->continuous_point &&
                           mixed->filter_level_reads == avx512->filter_level_reads &&
                           mixed->filter_candidates == avx512->filter_candidates;
    CHECK(other_tile);
    CHECK(same_rest);
}

TEST_CASE("the AVX2 strips take the RGB textons the AVX-512 kernel with AVX2 lattice tiles hands them, not "
          "those only the AVX-512 strips hold") {
    if (dsn_internal_kernel_count < 4) return;
    dsn_lattice_strips_take_entry *avx2 = dsn_internal_kernels[DSN_KERNEL_AVX2].entries->lattice_strips_take,
                                  *avx512 =
                                      dsn_internal_kernels[DSN_KERNEL_AVX512].entries->lattice_strips_take;
    auto small = dsn_test::synthetic_fields(3, 31, 8, DSN_SHAPE_RECTANGLE, 7);
    LoadedNoise small_noise(small, dsn_test::make_config(1, 30));
    CHECK(avx2(dsn_state(&small_noise.noise)) == 1);
    CHECK(avx512(dsn_state(&small_noise.noise)) == 1);
    // 63 x 63 RGB: three 16-bit planes of 63 + 2 rows exceed the AVX2 copy's room (a 31 x 31 RGB texton
    // twice); the AVX-512 copy keeps one copy only (its windows are whole cache lines) and has room for the
    // largest texton once.
    auto large = dsn_test::synthetic_fields(3, 63, 8, DSN_SHAPE_RECTANGLE, 7);
    LoadedNoise large_noise(large, dsn_test::make_config(1, 30));
    CHECK(avx2(dsn_state(&large_noise.noise)) == 0);
    CHECK(avx512(dsn_state(&large_noise.noise)) == 1);
}

TEST_CASE("init records the last kernel this CPU runs: the widest, or on AMD Zen 4 AVX-512 with AVX2 RGB "
          "lattice tiles") {
    auto fields = dsn_test::synthetic_fields(3, 31, 8, DSN_SHAPE_RECTANGLE, 3);
    LoadedNoise loaded(fields, dsn_test::make_config(1));
    uint32_t expected = DSN_KERNEL_DEFAULT;
#if defined(__x86_64__)
    if (dsn_internal_kernel_count > 1) {
        // The Makefile builds the AVX2 and AVX-512 kernels on every x86-64 host (DSN_X86_DISPATCH): the
        // widest must be chosen exactly when the CPU (as libgcc reads CPUID and XCR0) runs it.
        REQUIRE(dsn_internal_kernel_count == 4);
        // Both x86 kernels also need what -mavx2 implies (the popcnt instruction among them).
        __builtin_cpu_init();
        const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("sse3") &&
                          __builtin_cpu_supports("ssse3") && __builtin_cpu_supports("sse4.1") &&
                          __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("popcnt");
        if (avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
            __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
            expected = amd_family() == 0x19 ? DSN_KERNEL_AVX512_AVX2_TILES : DSN_KERNEL_AVX512;
        else if (avx2)
            expected = DSN_KERNEL_AVX2;
        if (expected < DSN_KERNEL_AVX512)
            MESSAGE("this CPU has no AVX-512 (F, BW, DQ and VL)"
                    << (expected == DSN_KERNEL_AVX2 ? "" : " nor AVX2")
                    << ": the kernel for it is not tested");
    } else {
        MESSAGE("the runtime is built without the x86 kernels (DSN_X86_DISPATCH): only the default one is "
                "tested");
    }
#endif
    CHECK(dsn_state(&loaded.noise)->tile_kernel == expected);
}

TEST_CASE("strip tiles == per point for fixed, float and u8 output on windows of many rectangles") {
    dsn_test::TestRandom random(77);
    const Window windows[] = {{-1000, 5000, 150, 70},
                              {INT32_MAX - 60, -40, 131, 67},
                              {INT32_MIN + 3, INT32_MAX - 33, 97, 65},
                              {-3, -2, 200, 33},
                              {123456789, -987654321, 65, 100}};
    // Side 45: a 1-channel texton takes the strip path with AVX2 (16-pixel strips) and AVX-512 and the
    // 32-bit path with SSE2 (where it could reach 6 strips of 8); an RGB one takes the strip path with
    // AVX-512 (its one copy has room for it) and the 32-bit path otherwise (no room for it).
    for (uint32_t channels : {1u, 3u})
        for (uint32_t side : {31u, 9u, 1u, 45u}) {
            auto fields = dsn_test::synthetic_fields(channels, side, 8, DSN_SHAPE_RECTANGLE, random.next());
            for (const Window &window : windows) {
                const uint32_t periods[][2] = {{0, 0}, {100, 0}, {0, 37}, {1, 2}, {2147483648u, 1000}};
                const uint32_t *period = periods[random.next() % 5];
                LoadedNoise loaded(fields, dsn_test::make_config(random.next(), 30, period[0], period[1]));
                CAPTURE(channels);
                CAPTURE(side);
                CAPTURE(window.x0);
                CAPTURE(window.y0);
                CAPTURE(period[0]);
                CAPTURE(period[1]);
                CHECK(differences(loaded.noise, window) == 0);
            }
        }
}

TEST_CASE("strip tiles == per point at densities around the 16-bit limit and at full-scale texton values") {
    // Denser noises get smaller rectangles (choose_rectangle in runtime/kernels/tile_strips.h): a 31 x 31
    // texton at 60 and 120 impacts per pixel, and at 300, where no rectangle of 4+ rows meets few enough
    // impulses and the whole tile takes the 32-bit path (runtime_tile_fallback_test.cpp makes single
    // rectangles fall back). The constant texton (every value +127 or -127)
    // gives the largest sums the 16-bit path meets.
    dsn_test::TestRandom random(78);
    auto varied = dsn_test::synthetic_fields(3, 31, 8, DSN_SHAPE_RECTANGLE, 5);
    auto full_scale = varied;
    for (size_t i = 0; i < full_scale.texton.size(); i++) full_scale.texton[i] = (i % 3 == 1) ? -127 : 127;
    for (const auto *fields : {&varied, &full_scale})
        for (double impacts : {60.0, 120.0, 300.0}) {
            LoadedNoise loaded(*fields, dsn_test::make_config(random.next(), impacts));
            Window window = {int32_t(random.next()), int32_t(random.next()), 130, 66};
            CAPTURE(impacts);
            CHECK(differences(loaded.noise, window) == 0);
        }
}

TEST_CASE("a tile written past the caches (16 MB or more) equals the same window in smaller tiles") {
    // 1200 x 1200 RGB is 17.3 MB of fixed or float output (streamed, runtime/kernels/tile_render.h); the same
    // window in 8 bands of 150 rows stays under the threshold. Origins and widths keep some strips off
    // the 16-byte alignment streaming needs, so both kinds of store meet; a copy written one value further
    // on starts its rows 4 bytes past where the first does within their cache lines.
    auto fields = dsn_test::synthetic_fields(3, 31, 8, DSN_SHAPE_RECTANGLE, 14);
    LoadedNoise loaded(fields, dsn_test::make_config(3, 30));
    const uint32_t side = 1200, band = 150;
    std::vector<int32_t> whole(size_t(side) * side * 3), bands(whole.size()), shifted(whole.size() + 1);
    std::vector<float> whole_float(whole.size()), bands_float(whole.size());
    std::vector<unsigned char> scratch(dsn_lattice_tile_scratch_size(&loaded.noise, side, side));
    for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_state(&loaded.noise)->tile_kernel; kernel++) {
        dsn_noise noise = loaded.noise;
        dsn_state(&noise)->tile_kernel = kernel;
        CAPTURE(kernel);
        REQUIRE(dsn_lattice_tile_fixed(&noise, -7, 3, side, side, whole.data(), nullptr, 0) == DSN_OK);
        REQUIRE(dsn_lattice_tile_float(&noise, -7, 3, side, side, whole_float.data(), scratch.data(),
                                       scratch.size()) == DSN_OK);
        REQUIRE(dsn_lattice_tile_fixed(&noise, -7, 3, side, side, shifted.data() + 1, nullptr, 0) == DSN_OK);
        for (uint32_t y = 0; y < side; y += band) {
            const size_t first = size_t(y) * side * 3;
            REQUIRE(dsn_lattice_tile_fixed(&noise, -7, int32_t(3 + y), side, band, bands.data() + first,
                                           nullptr, 0) == DSN_OK);
            REQUIRE(dsn_lattice_tile_float(&noise, -7, int32_t(3 + y), side, band, bands_float.data() + first,
                                           scratch.data(), scratch.size()) == DSN_OK);
        }
        CHECK(std::memcmp(whole.data(), bands.data(), whole.size() * sizeof(int32_t)) == 0);
        CHECK(std::memcmp(whole.data(), shifted.data() + 1, whole.size() * sizeof(int32_t)) == 0);
        CHECK(std::memcmp(whole_float.data(), bands_float.data(), whole.size() * sizeof(float)) == 0);
    }
}

TEST_CASE("strip tiles == per point when the normalization cannot be split into 32-bit lanes") {
    // A sparse noise (1/4 impact per pixel) and a strong colour transform make the gains so large that
    // init keeps fewer than 16 fraction bits: the strips' sums are then normalized one pixel at a time.
    auto fields = dsn_test::synthetic_fields(3, 31, 8, DSN_SHAPE_RECTANGLE, 9);
    for (int i = 0; i < 9; i++) fields.color_transform[i] = (i % 4 == 0 ? 100 : 7) * int32_t(DSN_Q24_ONE);
    for (uint32_t c = 0; c < 3; c++) fields.scale[c] = 0xFFFFFFFFu;
    LoadedNoise loaded(fields, dsn_test::make_config(11, 0.25));
    REQUIRE(dsn_state(&loaded.noise)->gain_shift < 16);
    Window window = {-70, 1234567, 140, 70};
    CHECK(differences(loaded.noise, window) == 0);
}
