// surface_bench.cpp - the cost of a surface noise point (dsn.h, "Surface noise") over a continuous point of
// the same noise, in the same run in paired rounds: on the plane z = 0 in its own frame, on a tilted plane
// with a tangent, and on a sphere (a frame per point, made once; then the float function, which makes the
// frame from the normal at each call); and the filtered surface point over the plane's filtered point under
// the same footprint (4 texels a pixel, isotropic, and 2 x 8 anisotropic). RGB 31 x 31 and 11 x 11 textons
// (with the baker's pyramid), 30 impacts per pixel, one thread. The target is 3x for the point.
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench_timing.h"
#include "fixtures/continuous_fixtures.h"
#include "offline/bake_internal.h"
#include "painted_stack.h"

namespace {

const int side = 128;
int64_t checksum = 0; // keeps the evaluations observable

struct SurfacePoint {
    int64_t position[3];
    double position_float[3];
    float normal[3];
    dsn_surface_frame frame;
};

SurfacePoint surface_point(double x, double y, double z, double nx, double ny, double nz,
                           const float *tangent) {
    SurfacePoint point;
    const double p[3] = {x, y, z};
    for (int i = 0; i < 3; i++) {
        point.position[i] = dsn_coordinate_from_double(p[i]);
        point.position_float[i] = p[i];
    }
    point.normal[0] = float(nx), point.normal[1] = float(ny), point.normal[2] = float(nz);
    dsn_surface_frame_from_float(point.normal, tangent, &point.frame);
    return point;
}

} // namespace

int main() {
    using namespace continuous_fixtures;
    const int rounds = 7;
    const double one = 4294967296.0, pi = 3.14159265358979323846;
    std::printf("surface_bench: a surface noise point over a continuous point (3x is the target)\n");
    for (uint32_t radius : {15u, 5u}) {
        dsn::AssetFields fields = random_texton_asset(3, radius, 8, 1);
        fields.pyramid = dsn::texton_pyramid(fields);
        auto noise = make_noise(fields, 1, 30u << 16);
        std::vector<SurfacePoint> plane, tilted, sphere;
        const float tangent[3] = {1, 0.25f, 0};
        for (int j = 0; j < side; j++)
            for (int i = 0; i < side; i++) {
                const double a = i * 0.61 + 0.3, b = j * 0.61 + 0.7; // 0.61 texel apart
                plane.push_back(surface_point(a, b, 5.25, 0, 0, 1, nullptr));
                // The tilted plane through the origin with normal (0.3, -0.5, 0.8): a point of it at (a, b).
                tilted.push_back(surface_point(a, b, (0.5 * b - 0.3 * a) / 0.8, 0.3, -0.5, 0.8, tangent));
                const double theta = pi * (j + 0.5) / side, phi = 2 * pi * (i + 0.5) / side, r = 40;
                const double n[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                     std::cos(theta)};
                sphere.push_back(surface_point(r * n[0], r * n[1], r * n[2], n[0], n[1], n[2], nullptr));
            }
        auto continuous = [&] {
            int32_t value[3];
            for (int j = 0; j < side; j++)
                for (int i = 0; i < side; i++) {
                    dsn_continuous_point_fixed(&noise->noise, int64_t((i * 0.61 + 0.3) * one),
                                               int64_t((j * 0.61 + 0.7) * one), value);
                    checksum += value[0];
                }
        };
        auto fixed = [&](const std::vector<SurfacePoint> &points) {
            return [&] {
                int32_t value[3];
                for (const SurfacePoint &p : points) {
                    dsn_surface_point_fixed(&noise->noise, p.position, &p.frame, value);
                    checksum += value[0];
                }
            };
        };
        auto from_float = [&] {
            float value[3];
            for (const SurfacePoint &p : sphere) {
                dsn_surface_point_float(&noise->noise, p.position_float, p.normal, nullptr, value);
                checksum += int64_t(value[0] * 65536);
            }
        };
        const struct {
            const char *name;
            std::function<void()> work;
        } cases[] = {{"plane z = 0, its own frame", fixed(plane)},
                     {"tilted plane, with a tangent", fixed(tilted)},
                     {"sphere, a frame per point", fixed(sphere)},
                     {"sphere, float (frame per call)", from_float}};
        std::printf(" RGB %u x %u texton:\n", 2 * radius + 1, 2 * radius + 1);
        for (const auto &c : cases) {
            const bench::PairedRatio ratio = bench::paired_ratio(rounds, continuous, c.work);
            const double points = double(side) * side;
            std::printf(
                "  %-32s continuous %6.0f ns/point   surface %6.0f ns/point   ratio %.2f (median of %d "
                "rounds; best %.2f)\n",
                c.name, ratio.baseline_best / points * 1e9, ratio.baseline_best * ratio.best / points * 1e9,
                ratio.median, rounds, ratio.best);
        }
        const double footprints[2][4] = {{4, 0, 0, 4}, {2, 0, 0, 8}}; /* texels per pixel, as dsn_footprint */
        for (const double *steps : footprints) {
            dsn_footprint footprint;
            dsn_footprint_from_float(&footprint, steps[0], steps[1], steps[2], steps[3], 16);
            const int count = side * side / 16; // every 16th point: filtered points cost more
            auto plane_filtered = [&] {
                int32_t value[3];
                for (int k = 0; k < count; k++) {
                    dsn_filtered_point_fixed(&noise->noise, tilted[size_t(16 * k)].position[0],
                                             tilted[size_t(16 * k)].position[1], &footprint, value);
                    checksum += value[0];
                }
            };
            auto surface_filtered = [&] {
                int32_t value[3];
                for (int k = 0; k < count; k++) {
                    const SurfacePoint &p = tilted[size_t(16 * k)];
                    dsn_surface_filtered_point_fixed(&noise->noise, p.position, &p.frame, &footprint, value);
                    checksum += value[0];
                }
            };
            const bench::PairedRatio ratio = bench::paired_ratio(rounds, plane_filtered, surface_filtered);
            std::printf("  filtered, %g x %g texels a pixel:    plane %6.0f ns/point   surface %6.0f "
                        "ns/point   ratio %.2f "
                        "(median of %d rounds; best %.2f)\n",
                        steps[0], steps[3], ratio.baseline_best / count * 1e9,
                        ratio.baseline_best * ratio.best / count * 1e9, ratio.median, rounds, ratio.best);
        }
        const SurfacePoint &p = sphere[size_t(side * side / 3)];
        int32_t value[3];
        std::printf("  stack (painted) of a surface point call: %zu bytes\n", bench::painted_stack([&] {
                        dsn_surface_point_fixed(&noise->noise, p.position, &p.frame, value);
                    }));
        dsn_footprint wide;
        dsn_footprint_from_float(&wide, 2, 0, 0, 16, 16);
        std::printf("  stack (painted) of a filtered surface point call (2 x 16 texels): %zu bytes\n",
                    bench::painted_stack([&] {
                        dsn_surface_filtered_point_fixed(&noise->noise, p.position, &p.frame, &wide, value);
                    }));
    }
    std::printf("  (checksum %lld)\n", static_cast<long long>(checksum));
    return 0;
}
