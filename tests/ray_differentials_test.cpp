// ray_differentials_test.cpp - dsn-tiny-renderer's pixel footprints (examples/tiny_renderer/
// ray_differentials.h): the Jacobian of the texture coordinates from ray differentials against central
// finite differences of really traced neighbouring rays, on the ground plane and on a sphere.
#include <doctest/doctest.h>

#include <cmath>

#include "examples/tiny_renderer/ray_differentials.h"

using namespace tiny;

namespace {

const double kScale = 40; // texels per scene unit, as the renderer's

// Texture coordinates where the ray through (px, py) meets the ground plane y = 0.
void ground_hit(const Camera &camera, double px, double py, double &u, double &v) {
    const Vec d = camera.direction(px, py);
    const double t = -camera.eye.y / d.y;
    u = (camera.eye.x + d.x * t) * kScale;
    v = (camera.eye.z + d.z * t) * kScale;
}

// Distance along the ray to the sphere (first hit), or -1.
double sphere_distance(Vec origin, Vec direction, Vec center, double radius) {
    const Vec to = origin - center;
    const double b = dot(to, direction), c = dot(to, to) - radius * radius, disc = b * b - c;
    return disc < 0 ? -1 : -b - std::sqrt(disc);
}

// The largest difference between the differential Jacobian and central differences of step h pixels,
// relative to the Jacobian's largest entry.
double relative_mismatch(const TextureJacobian &j, const double fd[4]) {
    const double entries[4] = {j.du_dx, j.dv_dx, j.du_dy, j.dv_dy};
    double largest = 0, worst = 0;
    for (int k = 0; k < 4; k++) {
        largest = std::fmax(largest, std::fabs(entries[k]));
        worst = std::fmax(worst, std::fabs(entries[k] - fd[k]));
    }
    return worst / largest;
}

} // namespace

TEST_CASE("ground plane: the ray-differential Jacobian is the derivative of the traced hits") {
    const Camera camera(Vec{0, 2.2, -5.5}, Vec{0.1, -0.2, 1}, 60, 800, 500);
    const double h = 1e-3;
    int checked = 0;
    for (int j = 0; j < 500; j += 23)
        for (int i = 0; i < 800; i += 37) {
            const double px = i + 0.5, py = j + 0.5;
            const RayDifferential ray = ray_differential(camera, px, py);
            // Far enough below the horizon that the neighbours at +-h hit the ground too.
            if (ray.direction.y > -0.02) continue;
            const double t = -camera.eye.y / ray.direction.y;
            const TextureJacobian jacobian = plane_jacobian(transfer(ray, t, Vec{0, 1, 0}), kScale);
            double u0, v0, u1, v1, fd[4];
            ground_hit(camera, px - h, py, u0, v0);
            ground_hit(camera, px + h, py, u1, v1);
            fd[0] = (u1 - u0) / (2 * h), fd[1] = (v1 - v0) / (2 * h);
            ground_hit(camera, px, py - h, u0, v0);
            ground_hit(camera, px, py + h, u1, v1);
            fd[2] = (u1 - u0) / (2 * h), fd[3] = (v1 - v0) / (2 * h);
            CHECK(relative_mismatch(jacobian, fd) < 1e-5);
            checked++;
        }
    CHECK(checked > 100);
}

TEST_CASE("ground plane: footprints grow toward the horizon and stretch along the view") {
    const Camera camera(Vec{0, 2.2, -5.5}, Vec{0, -0.2, 1}, 60, 800, 500);
    double previous_area = 0;
    for (int j = 499; j >= 0; j -= 20) {
        const RayDifferential ray = ray_differential(camera, 400.5, j + 0.5);
        if (ray.direction.y > -0.01) break;
        const TextureJacobian jac =
            plane_jacobian(transfer(ray, -camera.eye.y / ray.direction.y, Vec{0, 1, 0}), kScale);
        const double area = std::fabs(jac.du_dx * jac.dv_dy - jac.dv_dx * jac.du_dy);
        CHECK(area > previous_area);
        previous_area = area;
        // In the middle column a step along x moves along u only, a step down the screen comes nearer
        // (v falls) and it is the longer one: the footprint is stretched toward the horizon.
        CHECK(std::fabs(jac.dv_dx) < 1e-9 * std::fabs(jac.du_dx));
        CHECK(jac.dv_dy < 0);
        CHECK(std::fabs(jac.dv_dy) > std::fabs(jac.du_dx));
    }
    CHECK(previous_area > 10); // the far rows see more than 10 texels per pixel
}

TEST_CASE("sphere: the ray-differential Jacobian is the derivative of the traced hits") {
    const Camera camera(Vec{0, 2.2, -5.5}, Vec{0, -0.2, 1}, 60, 800, 500);
    const Vec center{0.3, 1.2, 2.5};
    const double radius = 1.2, h = 1e-3;
    auto coordinates = [&](double px, double py, double &u, double &v) {
        const Vec d = camera.direction(px, py);
        const Vec normal =
            normalize(camera.eye + d * sphere_distance(camera.eye, d, center, radius) - center);
        sphere_coordinates(normal, radius, kScale, u, v);
    };
    int checked = 0;
    for (int j = 0; j < 500; j += 11)
        for (int i = 0; i < 800; i += 13) {
            const double px = i + 0.5, py = j + 0.5;
            const RayDifferential ray = ray_differential(camera, px, py);
            const double t = sphere_distance(camera.eye, ray.direction, center, radius);
            if (t < 0) continue;
            const Vec normal = normalize(camera.eye + ray.direction * t - center);
            // Away from the silhouette (neighbours must hit too), the poles and the longitude's seam.
            if (-dot(normal, ray.direction) < 0.2 || std::fabs(normal.y) > 0.95 ||
                (normal.x < 0 && std::fabs(normal.z) < 0.05))
                continue;
            const TextureJacobian jacobian = sphere_jacobian(transfer(ray, t, normal), normal, kScale);
            double u0, v0, u1, v1, fd[4];
            coordinates(px - h, py, u0, v0);
            coordinates(px + h, py, u1, v1);
            fd[0] = (u1 - u0) / (2 * h), fd[1] = (v1 - v0) / (2 * h);
            coordinates(px, py - h, u0, v0);
            coordinates(px, py + h, u1, v1);
            fd[2] = (u1 - u0) / (2 * h), fd[3] = (v1 - v0) / (2 * h);
            CHECK(relative_mismatch(jacobian, fd) < 1e-5);
            checked++;
        }
    CHECK(checked > 100);
}

TEST_CASE("the camera keeps the renderer's framing") {
    // forward (0, -0.2, 1): right is +x, up is forward turned up by 90 degrees, pixel centres are
    // symmetric about the axis.
    const Camera camera(Vec{0, 2.2, -5.5}, Vec{0, -0.2, 1}, 60, 800, 500);
    CHECK(camera.right.x == doctest::Approx(1));
    CHECK(camera.up.y == doctest::Approx(camera.forward.z));
    CHECK(camera.up.z == doctest::Approx(-camera.forward.y));
    CHECK(camera.screen_x(400) == doctest::Approx(0));
    CHECK(camera.screen_x(800) == doctest::Approx(std::tan(3.14159265358979323846 / 6)));
    CHECK(camera.screen_y(0) == doctest::Approx(std::tan(3.14159265358979323846 / 6) * 500 / 800));
}

TEST_CASE("sphere and plane: the coordinates' surface gradients are their derivatives along the surface") {
    // sphere_gradients against central differences of sphere_coordinates along tangent motions, and
    // against sphere_jacobian: dot(grad, motion) is the Jacobian's entry for that motion.
    const double radius = 1.2, h = 1e-6;
    int checked = 0;
    for (int i = 0; i < 40; i++) {
        const double theta = 0.2 + 2.7 * i / 40.0, phi = -3.0 + 0.15 * i; // away from the poles and the seam
        const Vec normal{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
        if (normal.x < 0 && std::fabs(normal.z) < 0.05) continue;
        const CoordinateGradients gradients = sphere_gradients(normal, kScale);
        const Vec tangents[2] = {normalize(Vec{-normal.z, 0, normal.x}),
                                 normalize(Vec{0, 1, 0} - normal * normal.y)};
        for (const Vec &tangent : tangents) {
            double u0, v0, u1, v1;
            sphere_coordinates(normalize(normal - tangent * (h / radius)), radius, kScale, u0, v0);
            sphere_coordinates(normalize(normal + tangent * (h / radius)), radius, kScale, u1, v1);
            CHECK(dot(gradients.u, tangent) == doctest::Approx((u1 - u0) / (2 * h)).epsilon(1e-5));
            CHECK(dot(gradients.v, tangent) == doctest::Approx((v1 - v0) / (2 * h)).epsilon(1e-5));
            const SurfaceDifferential motion = {tangent, tangent * 0.5};
            const TextureJacobian jacobian = sphere_jacobian(motion, normal, kScale);
            CHECK(dot(gradients.u, tangent) == doctest::Approx(jacobian.du_dx).epsilon(1e-12));
            CHECK(dot(gradients.v, tangent) == doctest::Approx(jacobian.dv_dx).epsilon(1e-12));
            checked++;
        }
    }
    CHECK(checked > 60);
    const CoordinateGradients plane = plane_gradients(kScale);
    const SurfaceDifferential motion = {Vec{0.3, 0, -0.7}, Vec{-1.1, 0, 0.2}};
    const TextureJacobian jacobian = plane_jacobian(motion, kScale);
    CHECK(dot(plane.u, motion.along_x) == doctest::Approx(jacobian.du_dx));
    CHECK(dot(plane.v, motion.along_x) == doctest::Approx(jacobian.dv_dx));
    CHECK(dot(plane.u, motion.along_y) == doctest::Approx(jacobian.du_dy));
    CHECK(dot(plane.v, motion.along_y) == doctest::Approx(jacobian.dv_dy));
}
