// ray_differentials.h - how far the texture coordinates move when the pixel moves by one: the 2x2
// Jacobian a filtered texture read needs (the pixel's footprint in texels), from ray differentials
// (H. Igehy, "Tracing Ray Differentials", SIGGRAPH 1999), and the texture coordinates' surface gradients
// that carry a relief's slope to the surface for bump mapping. Header-only, for dsn-tiny-renderer and its
// test.
//
// A camera ray through the continuous pixel position (px, py) has the direction D = d / |d|, with
// d = forward + right * sx(px) + up * sy(py). Its differential along a screen axis is
//     dD = (dd (d.d) - d (d.dd)) / (d.d)^(3/2),
// dd = right * dsx/dpx or up * dsy/dpy. A pinhole camera's rays share their origin, so at a hit at
// distance t on a surface of normal n the hit point moves by (Igehy's transfer to the tangent plane)
//     dP = t (dD - D (dD.n) / (D.n)),
// and the texture coordinates by their surface gradient times dP. This is the first-order view of the
// neighbouring pixel's ray meeting the hit's tangent plane, so it needs no second ray trace and has no
// trouble at silhouettes, where the neighbour's ray may miss the surface.
#ifndef DSN_TINY_RENDERER_RAY_DIFFERENTIALS_H
#define DSN_TINY_RENDERER_RAY_DIFFERENTIALS_H

#include <cmath>

namespace tiny {

struct Vec {
    double x, y, z;
};
inline Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec operator*(Vec a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec normalize(Vec a) { return a * (1 / std::sqrt(dot(a, a))); }

// A pinhole camera at `eye` looking along `forward` (unit, not vertical), level (its right vector is
// horizontal), `field_of_view_degrees` across the picture's width of `width` x `height` pixels.
// Pixel (i, j) covers [i, i + 1) x [j, j + 1), j downwards; its centre is (i + 0.5, j + 0.5).
struct Camera {
    Vec eye, forward, right, up;
    double half_width; // tan(half the horizontal field of view)
    int width, height;

    Camera(Vec eye_, Vec forward_, double field_of_view_degrees, int width_, int height_)
        : eye(eye_), forward(normalize(forward_)), width(width_), height(height_) {
        right = normalize(Vec{forward.z, 0, -forward.x});
        up = Vec{forward.y * right.z - forward.z * right.y, forward.z * right.x - forward.x * right.z,
                 forward.x * right.y - forward.y * right.x};
        half_width = std::tan(field_of_view_degrees / 2 * 3.14159265358979323846 / 180);
    }
    // The screen-plane offsets of the continuous pixel position (px, py), and their steps per pixel.
    double screen_x(double px) const { return (px / width * 2 - 1) * half_width; }
    double screen_y(double py) const { return (1 - py / height * 2) * half_width * height / width; }
    double screen_step() const { return 2 * half_width / width; } // the same on both axes: square pixels
    // The unnormalized direction d through (px, py), and the unit one.
    Vec unnormalized(double px, double py) const {
        return forward + right * screen_x(px) + up * screen_y(py);
    }
    Vec direction(double px, double py) const { return normalize(unnormalized(px, py)); }
};

// The unit ray direction through (px, py) and its derivatives per pixel along the screen's x and y.
struct RayDifferential {
    Vec direction, along_x, along_y;
};

inline RayDifferential ray_differential(const Camera &camera, double px, double py) {
    const Vec d = camera.unnormalized(px, py);
    const double dd = dot(d, d), length = std::sqrt(dd);
    // d moves by right * step along x and by -up * step along y (rows go down).
    auto differentiate = [&](Vec moved) { return (moved * dd - d * dot(d, moved)) * (1 / (dd * length)); };
    return {d * (1 / length), differentiate(camera.right * camera.screen_step()),
            differentiate(camera.up * -camera.screen_step())};
}

// The hit point's motion per pixel along x and y, for a hit at distance t on a surface of unit normal n.
struct SurfaceDifferential {
    Vec along_x, along_y;
};

inline SurfaceDifferential transfer(const RayDifferential &ray, double t, Vec normal) {
    const double facing = dot(ray.direction, normal);
    auto onto_plane = [&](Vec d_direction) {
        return (d_direction - ray.direction * (dot(d_direction, normal) / facing)) * t;
    };
    return {onto_plane(ray.along_x), onto_plane(ray.along_y)};
}

// The 2x2 Jacobian of the texture coordinates (u, v) per pixel: (du/dx, dv/dx) is the step of one
// pixel along the screen's x, (du/dy, dv/dy) along its y (downwards).
struct TextureJacobian {
    double du_dx, dv_dx, du_dy, dv_dy;
};

// The ground plane y = 0 textured by (u, v) = (x, z) * scale.
inline TextureJacobian plane_jacobian(const SurfaceDifferential &motion, double scale) {
    return {motion.along_x.x * scale, motion.along_x.z * scale, motion.along_y.x * scale,
            motion.along_y.z * scale};
}

// The sphere's texture coordinates at the unit normal n: longitude and latitude times its radius (scene
// units along the surface), times `scale`: u = atan2(n.z, n.x) R scale, v = acos(n.y) R scale.
inline void sphere_coordinates(Vec normal, double radius, double scale, double &u, double &v) {
    u = std::atan2(normal.z, normal.x) * radius * scale;
    v = std::acos(normal.y < -1 ? -1 : normal.y > 1 ? 1 : normal.y) * radius * scale;
}

// Their derivatives along the hit's motion (n moves by dP / R, and the coordinates carry a factor R:
// the radius cancels). At the poles the longitude squeezes to a
// point and du grows without bound: the gradient's denominators are kept above 1e-12 so the footprint
// stays finite (huge footprints read the texture's mean).
inline TextureJacobian sphere_jacobian(const SurfaceDifferential &motion, Vec normal, double scale) {
    const double around = normal.x * normal.x + normal.z * normal.z;
    const double ring = around > 1e-12 ? around : 1e-12, ring_radius = std::sqrt(ring);
    auto du = [&](Vec dp) { return (normal.x * dp.z - normal.z * dp.x) / ring * scale; };
    auto dv = [&](Vec dp) { return -dp.y / ring_radius * scale; };
    return {du(motion.along_x), dv(motion.along_x), du(motion.along_y), dv(motion.along_y)};
}

// The surface gradients of the texture coordinates: the vectors, tangent to the surface, whose dot
// product with a motion dP along it is how far u and v move (texels per scene unit). The same
// derivatives as the Jacobians above, before the pixel's motion is put in; bump mapping carries a
// height's texel gradient to the surface with them (the chain rule: grad H = dH/du grad u + dH/dv grad v).
struct CoordinateGradients {
    Vec u, v;
};

// The ground plane: u = x scale, v = z scale.
inline CoordinateGradients plane_gradients(double scale) { return {{scale, 0, 0}, {0, 0, scale}}; }

// The sphere at the unit normal n: u = atan2(n.z, n.x) R scale moves by (n.x dP.z - n.z dP.x) / ring
// scale, so grad u = (-n.z, 0, n.x) scale / ring (ring = n.x^2 + n.z^2, kept above 1e-12 as in
// sphere_jacobian: longitude squeezes toward the poles); v = acos(n.y) R scale moves by
// -dP.y / sqrt(ring) scale, so grad v is -(0, 1, 0) projected on the tangent plane, (0, 1, 0) - n n.y,
// times scale / sqrt(ring): a vector of length `scale`, along the meridian.
inline CoordinateGradients sphere_gradients(Vec normal, double scale) {
    const double around = normal.x * normal.x + normal.z * normal.z;
    const double ring = around > 1e-12 ? around : 1e-12, ring_radius = std::sqrt(ring);
    return {Vec{-normal.z, 0, normal.x} * (scale / ring),
            (Vec{0, 1, 0} - normal * normal.y) * (-scale / ring_radius)};
}

} // namespace tiny

#endif // DSN_TINY_RENDERER_RAY_DIFFERENTIALS_H
