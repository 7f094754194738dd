// surface_test.cpp - the surface noise (dsn.h, "Surface noise"): its frames, its statistics on planes of any
// orientation against the plane noise's theory, no pinch and no seam on a sphere, continuity over a curved
// surface, and its API's errors.
//
// Theory. On a plane with frame (T, B, N), the surface noise at p + a T + b B has the continuous noise's
// mean and covariance at lag (a, b) (dsn.h derives it from Campbell's theorem): the bilinear theory of
// continuous_statistics_test.cpp, Cov(out_c, out_d at lag h) = sum_kl K_ck K_dl integral t~_k t~_l(. + h).
// Samples are taken at sites 24 texels apart on the plane (farther than two reaches plus the largest lag),
// so they are independent; covariances are averaged over 20 batches and checked within 4 standard errors,
// which are themselves under 4% of the variances.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "fixtures/continuous_fixtures.h"
#include "fixtures/noise_theory.h"
#include "offline/bake_internal.h"
#include "runtime/core/bilinear_texton.h"
#include "runtime/core/cell_hash.h"
#include "runtime/core/level_read.h"
#include "runtime/core/surface_walk.h"
#include "runtime/kernels/kernels.h"

using namespace continuous_fixtures;

namespace {

const int kRadius = 5;

struct Vector {
    double x, y, z;
};

Vector operator+(Vector a, Vector b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vector operator*(double s, Vector a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vector a, Vector b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vector cross(Vector a, Vector b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vector unit(Vector a) { return (1 / std::sqrt(dot(a, a))) * a; }

Vector frame_vector(const int32_t *v) {
    return {v[0] / 1073741824.0, v[1] / 1073741824.0, v[2] / 1073741824.0};
}

dsn_surface_frame make_frame(Vector normal, const Vector *tangent) {
    const float n[3] = {float(normal.x), float(normal.y), float(normal.z)};
    float t[3] = {0, 0, 0};
    if (tangent) t[0] = float(tangent->x), t[1] = float(tangent->y), t[2] = float(tangent->z);
    dsn_surface_frame frame;
    REQUIRE(dsn_surface_frame_from_float(n, tangent ? t : nullptr, &frame) == DSN_OK);
    return frame;
}

std::array<double, 3> surface_value(const dsn_noise &noise, Vector p, const dsn_surface_frame &frame) {
    const int64_t position[3] = {dsn_coordinate_from_double(p.x), dsn_coordinate_from_double(p.y),
                                 dsn_coordinate_from_double(p.z)};
    int32_t out[3] = {0, 0, 0};
    REQUIRE(dsn_surface_point_fixed(&noise, position, &frame, out) == DSN_OK);
    return {out[0] / 65536.0, out[1] / 65536.0, out[2] / 65536.0};
}

// Cov(out_c(x), out_d(x + h)) of the continuous noise: K (t~ * t~) K^T at the real lag h.
double theory_covariance(const dsn::AssetFields &fields, uint32_t c, uint32_t d, double hx, double hy) {
    const auto t = texton_values(fields);
    auto transform = [&](uint32_t row, uint32_t k) {
        return fields.color_transform[row * 3 + k] / 16777216.0;
    };
    double sum = 0;
    for (uint32_t k = 0; k < fields.channels; k++)
        for (uint32_t l = 0; l < fields.channels; l++)
            sum += transform(c, k) * transform(d, l) *
                   bilinear_correlation(t[k], t[l], int(fields.width), hx, hy);
    return sum;
}

// Mean and standard error of per-batch values.
void batch_mean(const std::vector<double> &values, double *mean, double *error) {
    double sum = 0, square = 0;
    for (double v : values) sum += v;
    *mean = sum / double(values.size());
    for (double v : values) square += (v - *mean) * (v - *mean);
    *error = std::sqrt(square / double(values.size() - 1) / double(values.size()));
}

const double kLags[][2] = {{0, 0}, {1, 0}, {0, 1}, {3, 2}, {0.5, 0.25}};
const int kLagCount = 5;

// The plane through `origin` with this frame: mean and covariances at the lags against the theory.
void check_plane(const dsn::AssetFields &fields, const dsn_noise &noise, Vector origin,
                 const dsn_surface_frame &frame, uint64_t seed) {
    const Vector T = frame_vector(frame.tangent), B = frame_vector(frame.bitangent);
    const uint32_t channels = fields.channels;
    const int batches = 20, sites = 2000;
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> jitter(0.0, 1.0);
    std::vector<double> means[3], covariances[kLagCount][3][3];
    for (int batch = 0; batch < batches; batch++) {
        std::vector<std::array<double, 3>> values[kLagCount];
        for (int s = 0; s < sites; s++) {
            const int site = batch * sites + s;
            const double a = (site % 200) * 24.0 + jitter(random), b = (site / 200) * 24.0 + jitter(random);
            for (int h = 0; h < kLagCount; h++)
                values[h].push_back(
                    surface_value(noise, origin + (a + kLags[h][0]) * T + (b + kLags[h][1]) * B, frame));
        }
        for (uint32_t c = 0; c < channels; c++) {
            double sum = 0;
            for (const auto &v : values[0]) sum += v[c];
            means[c].push_back(sum / sites);
        }
        for (int h = 0; h < kLagCount; h++)
            for (uint32_t c = 0; c < channels; c++)
                for (uint32_t d = 0; d < channels; d++) {
                    double mean_c = 0, mean_d = 0, sum = 0;
                    for (int s = 0; s < sites; s++)
                        mean_c += values[0][size_t(s)][c], mean_d += values[h][size_t(s)][d];
                    mean_c /= sites, mean_d /= sites;
                    for (int s = 0; s < sites; s++)
                        sum += (values[0][size_t(s)][c] - mean_c) * (values[h][size_t(s)][d] - mean_d);
                    covariances[h][c][d].push_back(sum / (sites - 1));
                }
    }
    for (uint32_t c = 0; c < channels; c++) {
        double mean, error;
        batch_mean(means[c], &mean, &error);
        CAPTURE(c);
        CHECK(std::fabs(mean - fields.mean[c] / 16777216.0) <= 4 * error);
    }
    for (int h = 0; h < kLagCount; h++)
        for (uint32_t c = 0; c < channels; c++)
            for (uint32_t d = 0; d < channels; d++) {
                double covariance, error;
                batch_mean(covariances[h][c][d], &covariance, &error);
                const double expected = theory_covariance(fields, c, d, kLags[h][0], kLags[h][1]);
                CAPTURE(h);
                CAPTURE(c);
                CAPTURE(d);
                CAPTURE(covariance);
                CAPTURE(expected);
                CHECK(std::fabs(covariance - expected) <= 4 * error);
                CHECK(4 * error <= 0.04 * std::sqrt(theory_covariance(fields, c, c, 0, 0) *
                                                    theory_covariance(fields, d, d, 0, 0)));
            }
}

// Largest change between neighbouring samples of a path: points(k) for k = 0 .. count - 1.
template <typename Path>
double largest_step(const dsn_noise &noise, int count, Path path) {
    double largest = 0;
    std::array<double, 3> previous{};
    for (int k = 0; k < count; k++) {
        Vector p, normal;
        path(k, &p, &normal);
        const auto value = surface_value(noise, p, make_frame(normal, nullptr));
        if (k > 0)
            for (int c = 0; c < 3; c++)
                largest = std::max(largest, std::fabs(value[size_t(c)] - previous[size_t(c)]));
        previous = value;
    }
    return largest;
}

} // namespace

TEST_CASE("surface frames: unit, orthogonal and right-handed; scale-free; the frame from the normal alone") {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> component(-1, 1);
    for (int i = 0; i < 2000; i++) {
        const float normal[3] = {component(random), component(random), component(random)};
        const float tangent[3] = {component(random), component(random), component(random)};
        dsn_surface_frame frame;
        REQUIRE(dsn_surface_frame_from_float(normal, i % 2 ? tangent : nullptr, &frame) == DSN_OK);
        // Each component is within a few units of 2^-30 of the exact frame's (floors, an integer square
        // root, and the products of the frame from the normal alone).
        const double tolerance = 16.0 / 1073741824.0;
        const Vector T = frame_vector(frame.tangent), B = frame_vector(frame.bitangent),
                     N = frame_vector(frame.normal);
        CHECK(std::fabs(dot(T, T) - 1) < tolerance);
        CHECK(std::fabs(dot(B, B) - 1) < tolerance);
        CHECK(std::fabs(dot(N, N) - 1) < tolerance);
        CHECK(std::fabs(dot(T, N)) < tolerance);
        CHECK(std::fabs(dot(B, N)) < tolerance);
        CHECK(std::fabs(dot(T, B)) < tolerance);
        CHECK(dot(cross(T, B), N) > 1 - tolerance);
        const Vector n = unit({normal[0], normal[1], normal[2]});
        CHECK(dot(N, n) > 1 - tolerance);
        if (i % 2) { // T is the tangent's part orthogonal to the normal
            const Vector t = {tangent[0], tangent[1], tangent[2]};
            CHECK(dot(T, unit(t + (-dot(t, n)) * n)) > 1 - tolerance);
        }
        // A power-of-two scale of the vectors changes no bit.
        const float scaled[3] = {std::ldexp(normal[0], 40), std::ldexp(normal[1], 40),
                                 std::ldexp(normal[2], 40)};
        const float small[3] = {std::ldexp(tangent[0], -100), std::ldexp(tangent[1], -100),
                                std::ldexp(tangent[2], -100)};
        dsn_surface_frame again;
        REQUIRE(dsn_surface_frame_from_float(scaled, i % 2 ? small : nullptr, &again) == DSN_OK);
        CHECK(memcmp(&again, &frame, sizeof frame) == 0);
    }
    // The frame from the normal alone: x made orthogonal to the normal, and its two fixed frames on the x
    // axis.
    const float up[3] = {0, 0, 1}, down[3] = {0, -2, 0}, along[3] = {3, 0, 0}, against[3] = {-1, 0, 0};
    const float tilted[3] = {0.25f, -0.5f, 1};
    dsn_surface_frame frame, alone;
    REQUIRE(dsn_surface_frame_from_float(up, nullptr, &frame) == DSN_OK);
    CHECK(frame.tangent[0] == DSN_FRAME_ONE);
    CHECK(frame.bitangent[1] == DSN_FRAME_ONE);
    REQUIRE(dsn_surface_frame_from_float(down, nullptr, &frame) == DSN_OK);
    CHECK(frame.tangent[0] == DSN_FRAME_ONE);
    CHECK(frame.bitangent[2] == DSN_FRAME_ONE);
    REQUIRE(dsn_surface_frame_from_float(along, nullptr, &frame) == DSN_OK);
    CHECK(frame.tangent[2] == -DSN_FRAME_ONE);
    REQUIRE(dsn_surface_frame_from_float(against, nullptr, &frame) == DSN_OK);
    CHECK(frame.tangent[2] == DSN_FRAME_ONE);
    REQUIRE(dsn_surface_frame_from_float(tilted, tilted, &frame) == DSN_OK);
    REQUIRE(dsn_surface_frame_from_float(tilted, nullptr, &alone) == DSN_OK);
    CHECK(memcmp(&frame, &alone, sizeof frame) == 0);
    // Continuous in the normal away from the x axis: a turn of the normal by 1e-4 turns the frame by at most
    // about 1e-4 / rho (rho = sqrt(n_y^2 + n_z^2), the rate of the direction of (n_y, n_z)).
    for (int i = 0; i < 500; i++) {
        Vector n = unit({component(random), component(random), component(random)});
        const double rho = std::sqrt(n.y * n.y + n.z * n.z);
        if (rho < 0.1) continue;
        const Vector m = unit(n + 1e-4 * Vector{component(random), component(random), component(random)});
        const dsn_surface_frame a = make_frame(n, nullptr), b = make_frame(m, nullptr);
        const Vector ta = frame_vector(a.tangent), tb = frame_vector(b.tangent);
        CHECK(std::sqrt(dot(ta + (-1) * tb, ta + (-1) * tb)) < 4e-4 / rho);
    }
}

TEST_CASE("surface frames and points: bad inputs get an error code and zeroed outputs") {
    const float nan = std::nanf(""), inf = INFINITY;
    const float zero[3] = {0, 0, 0}, up[3] = {0, 0, 1}, with_nan[3] = {0, nan, 1}, with_inf[3] = {inf, 0, 1};
    dsn_surface_frame frame;
    memset(&frame, 0x55, sizeof frame);
    CHECK(dsn_surface_frame_from_float(zero, nullptr, &frame) == DSN_ERR_ARGUMENT);
    CHECK(frame.normal[2] == 0);
    CHECK(dsn_surface_frame_from_float(with_nan, nullptr, &frame) == DSN_ERR_ARGUMENT);
    CHECK(dsn_surface_frame_from_float(with_inf, nullptr, &frame) == DSN_ERR_ARGUMENT);
    CHECK(dsn_surface_frame_from_float(up, with_nan, &frame) == DSN_ERR_ARGUMENT);
    CHECK(dsn_surface_frame_from_float(nullptr, nullptr, &frame) == DSN_ERR_NULL);
    CHECK(dsn_surface_frame_from_float(up, nullptr, nullptr) == DSN_ERR_NULL);
    CHECK(dsn_surface_frame_from_float(up, zero, &frame) == DSN_OK); // a zero tangent counts as none

    auto noise = make_noise(random_texton_asset(3, kRadius, 8, 42), 3);
    const int64_t position[3] = {1, 2, 3};
    int32_t out[3] = {7, 7, 7};
    CHECK(dsn_surface_point_fixed(&noise->noise, nullptr, &frame, out) == DSN_ERR_NULL);
    CHECK((out[0] == 0 && out[1] == 0 && out[2] == 0));
    CHECK(dsn_surface_point_fixed(&noise->noise, position, nullptr, out) == DSN_ERR_NULL);
    CHECK(dsn_surface_point_fixed(nullptr, position, &frame, out) == DSN_ERR_NULL);
    dsn_surface_frame wide = frame;
    wide.tangent[1] = DSN_FRAME_ONE + 1;
    out[0] = 7;
    CHECK(dsn_surface_point_fixed(&noise->noise, position, &wide, out) == DSN_ERR_ARGUMENT);
    CHECK(out[0] == 0);
    float values[3] = {7, 7, 7};
    const double point[3] = {1, 2, 3};
    CHECK(dsn_surface_point_float(&noise->noise, point, with_nan, nullptr, values) == DSN_ERR_ARGUMENT);
    CHECK((values[0] == 0 && values[1] == 0 && values[2] == 0));
    CHECK(dsn_surface_point_float(&noise->noise, nullptr, up, nullptr, values) == DSN_ERR_NULL);
    CHECK(dsn_surface_batch_fixed(&noise->noise, nullptr, &frame, 1, out) == DSN_ERR_NULL);
    CHECK(dsn_surface_batch_fixed(&noise->noise, nullptr, nullptr, 0, nullptr) == DSN_OK);

    // A lattice-baked asset is refused as the continuous functions refuse it.
    dsn::AssetFields lattice = random_texton_asset(1, kRadius, 8, 5);
    lattice.interpolation = DSN_INTERPOLATION_LATTICE;
    auto strict = make_noise(lattice, 3);
    CHECK(dsn_surface_point_fixed(&strict->noise, position, &frame, out) == DSN_ERR_CONTINUOUS_MISMATCH);
}

TEST_CASE(
    "surface points: the float, 8-bit and batch functions give the fixed values; huge coordinates wrap") {
    auto noise = make_noise(random_texton_asset(3, kRadius, 16, 9), 11);
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> coordinate(-300, 300);
    std::uniform_real_distribution<float> component(-1, 1);
    std::vector<int64_t> positions;
    std::vector<dsn_surface_frame> frames;
    std::vector<int32_t> expected;
    for (int k = 0; k < 300; k++) {
        // Multiples of 2^-8 texel: plus 2^40 texels they stay exact in a double.
        const double p[3] = {std::ldexp(std::round(std::ldexp(coordinate(random), 8)), -8),
                             std::ldexp(std::round(std::ldexp(coordinate(random), 8)), -8),
                             std::ldexp(std::round(std::ldexp(coordinate(random), 8)), -8)};
        const float n[3] = {component(random), component(random), component(random)};
        dsn_surface_frame frame;
        if (dsn_surface_frame_from_float(n, nullptr, &frame) != DSN_OK) continue;
        const int64_t q[3] = {dsn_coordinate_from_double(p[0]), dsn_coordinate_from_double(p[1]),
                              dsn_coordinate_from_double(p[2])};
        int32_t fixed[3];
        float floats[3];
        uint8_t bytes[3];
        REQUIRE(dsn_surface_point_fixed(&noise->noise, q, &frame, fixed) == DSN_OK);
        REQUIRE(dsn_surface_point_float(&noise->noise, p, n, nullptr, floats) == DSN_OK);
        REQUIRE(dsn_surface_point_u8(&noise->noise, q, &frame, bytes) == DSN_OK);
        // 2^40 texels is a whole number of turns of the torus: the same point.
        const double far[3] = {p[0] + 1099511627776.0, p[1] - 1099511627776.0, p[2] + 3298534883328.0};
        float wrapped[3];
        REQUIRE(dsn_surface_point_float(&noise->noise, far, n, nullptr, wrapped) == DSN_OK);
        for (int c = 0; c < 3; c++) {
            CHECK(floats[c] == dsn_fixed_to_float(fixed[c]));
            CHECK(bytes[c] == dsn_fixed_to_u8(fixed[c]));
            CHECK(wrapped[c] == floats[c]);
            expected.push_back(fixed[c]);
        }
        positions.insert(positions.end(), q, q + 3);
        frames.push_back(frame);
    }
    std::vector<int32_t> batch(expected.size());
    REQUIRE(dsn_surface_batch_fixed(&noise->noise, positions.data(), frames.data(), uint32_t(frames.size()),
                                    batch.data()) == DSN_OK);
    CHECK(batch == expected);
}

// The impulses of one cube as dsn.h defines them: impulse index's 16-bit fields times 2^cell_shift, dotted
// with each frame vector and subtracted from the origin's dot product (Q.46, as listed); those with every
// offset floored to Q32.32 within its reach, in index order.
std::vector<std::array<int64_t, 3>> defined_impulses(const dsn_surface_cube &cube) {
    std::vector<std::array<int64_t, 3>> kept;
    const int64_t reaches[3] = {cube.reach_u, cube.reach_v, cube.reach_across};
    for (uint32_t k = 0; k < cube.count; k++) {
        const uint64_t pair = dsn_position_pair(cube.key, cube.first + k);
        std::array<int64_t, 3> offsets;
        bool within = true;
        for (int v = 0; v < 3; v++) {
            int64_t dot = 0;
            for (int i = 0; i < 3; i++)
                dot += int64_t(((pair >> (16 * i)) & 0xFFFFu) << cube.cell_shift) * cube.frame[v][i];
            const int64_t offset = int64_t(uint64_t(cube.origin_dot[v]) - uint64_t(dot));
            const int64_t floored = offset >= 0 ? offset / 16384 : -((-(offset + 1)) / 16384) - 1;
            offsets[size_t(v)] = offset;
            within = within && floored < reaches[v] && floored > -reaches[v];
        }
        if (within) kept.push_back(offsets);
    }
    return kept;
}

TEST_CASE(
    "surface kernels: every kernel this CPU runs lists a cube's impulses as defined, and gives the same "
    "points") {
    dsn::AssetFields fields = random_texton_asset(3, kRadius, 8, 4);
    fields.pyramid = dsn::texton_pyramid(fields);
    auto noise = make_noise(fields, 3);
    std::mt19937_64 random(17);
    std::uniform_int_distribution<int64_t> component(-(int64_t(1) << 30), int64_t(1) << 30);
    size_t listed = 0, left_out = 0;
    for (int round = 0; round < 4000; round++) {
        dsn_surface_cube cube;
        cube.cell_shift = uint32_t(random() % 9);
        cube.key = uint32_t(random());
        cube.first = uint32_t(random() % 300);
        cube.count = 1 + uint32_t(random() % dsn_surface_impulses_most);
        for (int v = 0; v < 3; v++) {
            // Origins within a few cubes of the point (Q.46), some at the extremes of a frame's range.
            cube.origin_dot[v] = int64_t(random() % (uint64_t(1) << (48 + cube.cell_shift))) -
                                 (int64_t(1) << (47 + cube.cell_shift));
            for (int i = 0; i < 3; i++)
                cube.frame[v][i] =
                    int32_t(round % 7 == 0 ? (random() & 1 ? 1 : -1) * (1 << 30) : component(random));
        }
        // Reaches of a texton, of a cube (3/4 across), and none (2^62).
        const int64_t reach_choices[3] = {int64_t(1 + random() % 16) << 32,
                                          int64_t(3) << (30 + cube.cell_shift), int64_t(1) << 62};
        cube.reach_u = reach_choices[random() % 3];
        cube.reach_v = reach_choices[random() % 3];
        cube.reach_across = reach_choices[random() % 3];
        const std::vector<std::array<int64_t, 3>> expected = defined_impulses(cube);
        listed += expected.size();
        left_out += cube.count - expected.size();
        for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_state(&noise->noise)->tile_kernel;
             kernel++) {
            dsn_surface_impulses_entry *entry = dsn_kernel_entries_of(kernel)->surface_impulses;
            const bool has_entry = entry != nullptr;
            REQUIRE(has_entry);
            dsn_surface_impulses out;
            const uint32_t kept = entry(&cube, &out);
            CAPTURE(kernel);
            CAPTURE(round);
            REQUIRE(kept == expected.size());
            for (uint32_t k = 0; k < kept; k++) {
                CHECK(out.along_tangent[k] == expected[k][0]);
                CHECK(out.along_bitangent[k] == expected[k][1]);
                CHECK(out.across[k] == expected[k][2]);
            }
        }
    }
    CHECK(listed > 4000); // both outcomes are common
    CHECK(left_out > 4000);

    // Whole points, plain and filtered, in every kernel: the default kernel's values.
    std::uniform_real_distribution<double> coordinate(-200, 200);
    std::uniform_real_distribution<float> direction(-1, 1);
    dsn_footprint footprint;
    dsn_footprint_from_float(&footprint, 3, 0.5, 0, 2, 16);
    for (int k = 0; k < 200; k++) {
        const double p[3] = {coordinate(random), coordinate(random), coordinate(random)};
        const float n[3] = {direction(random), direction(random), direction(random)};
        dsn_surface_frame frame;
        if (dsn_surface_frame_from_float(n, nullptr, &frame) != DSN_OK) continue;
        const int64_t q[3] = {dsn_coordinate_from_double(p[0]), dsn_coordinate_from_double(p[1]),
                              dsn_coordinate_from_double(p[2])};
        int32_t expected[3], expected_filtered[3];
        dsn_noise reference = noise->noise;
        dsn_state(&reference)->tile_kernel = DSN_KERNEL_DEFAULT;
        REQUIRE(dsn_surface_point_fixed(&reference, q, &frame, expected) == DSN_OK);
        REQUIRE(dsn_surface_filtered_point_fixed(&reference, q, &frame, &footprint, expected_filtered) ==
                DSN_OK);
        for (uint32_t kernel = DSN_KERNEL_DEFAULT + 1; kernel <= dsn_state(&noise->noise)->tile_kernel;
             kernel++) {
            dsn_noise copy = noise->noise;
            dsn_state(&copy)->tile_kernel = kernel;
            int32_t value[3], filtered[3];
            REQUIRE(dsn_surface_point_fixed(&copy, q, &frame, value) == DSN_OK);
            REQUIRE(dsn_surface_filtered_point_fixed(&copy, q, &frame, &footprint, filtered) == DSN_OK);
            CAPTURE(kernel);
            for (int c = 0; c < 3; c++) {
                CHECK(value[c] == expected[c]);
                CHECK(filtered[c] == expected_filtered[c]);
            }
        }
    }
}

TEST_CASE("surface kernels: the reads of listed impulses are the walks' windowed bilinear reads, of the "
          "texton and of a level") {
    // The texton as the unfiltered point reads it (level 0, its whole window), and as a filtered point reads
    // a level: divided by 2^level, a window inside it (a margin left out, so rows are wider than the window),
    // offsets out to twice its reach (a filtered walk lists impulses for the widest level). The listed
    // offsets are Q.46, read moved by a tap's move (none in some rounds) and floored to Q32.32: the offsets
    // below are those floored ones.
    std::mt19937_64 random(29);
    size_t compared = 0;
    for (const uint32_t channels : {1u, 3u})
        for (const uint32_t radius : {0u, 2u, 7u, 15u})
            for (const uint32_t level : {0u, 1u, 3u}) {
                auto noise = make_noise(random_texton_asset(channels, radius, 8, 5 + radius), 3);
                const dsn_asset &asset = dsn_state(&noise->noise)->asset;
                const uint32_t margin = radius > 0 && level > 0 ? 1u : 0u;
                dsn_walked_level walked;
                walked.values = asset.texton + (margin * asset.width + margin) * channels;
                walked.width = asset.width - 2 * margin;
                walked.height = asset.height - 2 * margin;
                walked.stride = asset.width;
                walked.radius_x = (walked.width - 1) / 2;
                walked.radius_y = (walked.height - 1) / 2;
                walked.level = level;
                walked.exponent = 0;
                const dsn_surface_texels texels = {walked.values, walked.width, walked.height,
                                                   walked.stride, channels,     level};
                const int64_t reach = int64_t(walked.radius_x + 1) << (32 + level);
                const int64_t listed_reach = level == 0 ? reach : 2 * reach;
                for (int round = 0; round < 300; round++) {
                    const uint32_t cell_shift = uint32_t(random() % 9);
                    const int64_t across_reach = int64_t(3) << (30 + cell_shift);
                    dsn_surface_impulses listed;
                    const uint32_t count = 1 + uint32_t(random() % dsn_surface_impulses_most);
                    int64_t moved[3] = {0, 0, 0};
                    if (round % 2 == 1)
                        for (int64_t &move : moved)
                            move = int64_t(random() % (uint64_t(1) << 48)) - (int64_t(1) << 47);
                    int64_t floored[3][dsn_surface_impulses_most];
                    for (uint32_t k = 0; k < count; k++) {
                        // Offsets anywhere within the reaches, on texel edges, and at their ends.
                        int64_t *offsets[3] = {&floored[0][k], &floored[1][k], &floored[2][k]};
                        const int64_t reaches[3] = {listed_reach, listed_reach, across_reach};
                        for (int v = 0; v < 3; v++) {
                            const int64_t span = 2 * reaches[v] - 1;
                            int64_t offset = int64_t(random() % uint64_t(span)) - (reaches[v] - 1);
                            if (random() % 8 == 0) offset &= ~int64_t(0xFFFFFFFF); // a texel edge
                            if (offset <= -reaches[v]) offset += int64_t(1) << 32;
                            if (random() % 16 == 0) offset = random() & 1 ? reaches[v] - 1 : 1 - reaches[v];
                            *offsets[v] = offset;
                        }
                        int64_t *listed_offsets[3] = {&listed.along_tangent[k], &listed.along_bitangent[k],
                                                      &listed.across[k]};
                        for (int v = 0; v < 3; v++) // any Q.46 offset that floors to it once moved
                            *listed_offsets[v] = int64_t(uint64_t(*offsets[v]) * 16384u +
                                                         (random() & 0x3FFFu) - uint64_t(moved[v]));
                    }
                    uint64_t expected[3] = {0, 0, 0};
                    for (uint32_t k = 0; k < count; k++) {
                        const uint32_t window = slab_window(floored[2][k], cell_shift);
                        uint64_t texton[3] = {0, 0, 0};
                        if (level == 0) {
                            uint32_t row = 0, row_weight = 0, column = 0, column_weight = 0;
                            REQUIRE(bracket(floored[0][k], radius, &column, &column_weight));
                            REQUIRE(bracket(floored[1][k], radius, &row, &row_weight));
                            add_bilinear(&asset, row, row_weight, column, column_weight, texton);
                        } else {
                            add_level<false>(walked, channels, 8, floored[0][k], floored[1][k], texton,
                                             nullptr);
                        }
                        for (uint32_t c = 0; c < channels; c++) expected[c] += windowed(texton[c], window);
                    }
                    for (uint32_t kernel = DSN_KERNEL_DEFAULT;
                         kernel <= dsn_state(&noise->noise)->tile_kernel; kernel++) {
                        dsn_surface_reads_entry *reads = dsn_kernel_entries_of(kernel)->surface_reads;
                        if (reads == nullptr) continue;
                        uint64_t sums[3] = {7, 8, 9};
                        reads(&texels, &listed, count, cell_shift, moved, sums);
                        CAPTURE(kernel);
                        CAPTURE(channels);
                        CAPTURE(radius);
                        CAPTURE(level);
                        for (uint32_t c = 0; c < channels; c++) CHECK(sums[c] == 7 + c + expected[c]);
                        compared++;
                    }
                }
            }
    MESSAGE("read batches compared with a kernel's: " << compared);
}

TEST_CASE("surface statistics: on planes of any orientation, the plane noise's mean and covariance") {
    const dsn::AssetFields rgb = random_texton_asset(3, kRadius, 8, 42);
    auto noise = make_noise(rgb, 21, 30u << 16);
    SUBCASE("the plane z = 0, its own axes") {
        const Vector tangent = {1, 0, 0};
        check_plane(rgb, noise->noise, {10.25, -3.5, 0.125}, make_frame({0, 0, 1}, &tangent), 1);
    }
    SUBCASE("a tilted plane with a tangent") {
        const Vector tangent = {1, 0.25, 0};
        check_plane(rgb, noise->noise, {-1000.5, 77.25, 31.75}, make_frame({0.3, -0.5, 0.8}, &tangent), 2);
    }
    SUBCASE("a steep plane, the frame from its normal alone") {
        check_plane(rgb, noise->noise, {5, 6, 7}, make_frame({-1, 2, 0.5}, nullptr), 3);
    }
    SUBCASE("next to the x axis, where the frame from the normal alone turns around") {
        check_plane(rgb, noise->noise, {0, 0, 0}, make_frame({-1, 0.001, -0.002}, nullptr), 4);
    }
}

TEST_CASE("surface statistics: a sphere has the same variance at its poles as at its equator") {
    // Sites on spheres of radius 300 texels, their centres 40 texels apart (so samples are independent):
    // within a degree of the north pole, of the south pole and of the equator, and of the point on the
    // equator where the frame from the normal alone turns around (x). The variance is the plane's
    // everywhere, within 4 standard errors.
    const dsn::AssetFields rgb = random_texton_asset(3, kRadius, 8, 42);
    auto noise = make_noise(rgb, 8, 30u << 16);
    const Vector poles[4] = {{0, 0, 1}, {0, 0, -1}, {0.6, 0.8, 0}, {1, 0, 0}};
    std::mt19937_64 random(17);
    std::uniform_real_distribution<double> offset(-0.0087, 0.0087); // half a degree per axis
    for (int p = 0; p < 4; p++) {
        std::vector<double> samples[3];
        for (int site = 0; site < 20000; site++) {
            const Vector centre = {(site % 150) * 40.0, (site / 150) * 40.0, 0};
            const Vector direction = unit(poles[p] + Vector{offset(random), offset(random), offset(random)});
            const auto value =
                surface_value(noise->noise, centre + 300.0 * direction, make_frame(direction, nullptr));
            for (int c = 0; c < 3; c++) samples[c].push_back(value[size_t(c)]);
        }
        for (uint32_t c = 0; c < 3; c++) {
            double mean = 0, square = 0, fourth = 0;
            const double n = double(samples[c].size());
            for (double v : samples[c]) mean += v / n;
            for (double v : samples[c])
                square += (v - mean) * (v - mean) / n, fourth += std::pow(v - mean, 4) / n;
            const double error = std::sqrt((fourth - square * square) / n); // the sample variance's
            const double expected = theory_covariance(rgb, c, c, 0, 0);
            CAPTURE(p);
            CAPTURE(c);
            CAPTURE(square);
            CAPTURE(expected);
            CHECK(std::fabs(square - expected) <= 4 * error);
            CHECK(4 * error <= 0.05 * expected);
        }
    }
}

TEST_CASE("surface noise: no seam along great circles, continuous over a curved surface") {
    auto noise = make_noise(random_texton_asset(3, kRadius, 8, 42), 12, 30u << 16);
    const Vector centre = {123.5, -45.25, 67.75};
    const double radius = 60, pi = 3.14159265358979323846;
    // Quarters of great circles through both poles (meridians), the equator and a tilted circle, the frame
    // from the normal alone (those starting next to the x axis pass 0.1 rad from it, where the frame turns
    // fastest); a circle at angle t is centre + radius (cos t u + sin t v).
    const Vector circles[][2] = {{{1, 0, 0}, {0, 0, 1}},
                                 {{0.6, 0.8, 0}, {0, 0, -1}},
                                 {{1, 0, 0}, {0, 1, 0}},
                                 {{0.8, 0, 0.6}, {0, 1, 0}}};
    for (const auto &circle : circles) {
        // Steps of about 1/16 and 1/64 texel: a seam (a jump of the value) would show as a change that
        // does not shrink with the step; a continuous noise's largest change shrinks about 4 times.
        double largest[2];
        for (int fine = 0; fine < 2; fine++) {
            const int count = fine ? 24000 : 6000; // a quarter of the circle from angle 0.1
            const double step = (pi / 2) / count;
            largest[fine] = largest_step(noise->noise, count, [&](int k, Vector *p, Vector *normal) {
                const double t = 0.1 + step * k;
                *normal = std::cos(t) * circle[0] + std::sin(t) * circle[1];
                *p = centre + radius * *normal;
            });
        }
        CAPTURE(circle[0].x);
        CAPTURE(circle[1].z);
        CAPTURE(largest[0]);
        CAPTURE(largest[1]);
        CHECK(largest[1] <= 0.5 * largest[0]);
    }
    // A path around the tube of a torus (tube radius 20, ring radius 50) whose axis is tilted 30 degrees
    // from y: its normals turn through a whole great circle that passes 60 degrees from the x axis.
    const Vector axis = {0.5, std::sqrt(0.75), 0}, radial = {0, 0, 1};
    double largest[2];
    for (int fine = 0; fine < 2; fine++) {
        const int count = fine ? 24000 : 6000;
        const double step = 2 * pi / count;
        largest[fine] = largest_step(noise->noise, count, [&](int k, Vector *p, Vector *normal) {
            *normal = std::cos(step * k) * radial + std::sin(step * k) * axis;
            *p = centre + 50.0 * radial + 20.0 * *normal;
        });
    }
    CAPTURE(largest[0]);
    CAPTURE(largest[1]);
    CHECK(largest[1] <= 0.5 * largest[0]);
}

namespace {

// A tilted plane's point at (a, b) texels along its frame's tangent and bitangent.
Vector on_plane(const dsn_surface_frame &frame, double a, double b) {
    return Vector{-1000.5, 77.25, 31.75} + a * frame_vector(frame.tangent) +
           b * frame_vector(frame.bitangent);
}

double filtered_surface_value(const dsn_noise &noise, Vector p, const dsn_surface_frame &frame,
                              const dsn_footprint &footprint) {
    const int64_t position[3] = {dsn_coordinate_from_double(p.x), dsn_coordinate_from_double(p.y),
                                 dsn_coordinate_from_double(p.z)};
    int32_t out[3] = {0, 0, 0};
    REQUIRE(dsn_surface_filtered_point_fixed(&noise, position, &frame, &footprint, out) == DSN_OK);
    return out[0] / 65536.0;
}

} // namespace

namespace {

// The filtered surface as dsn.h states it, tap by tap: each tap's own walk around its position (the point
// moved along the tangent and bitangent, floored to Q.16, projected, floored to Q32.32), each level read one
// impulse at a time (level_read.h's add_level) and weighted by the window, in the default kernel.
struct ReferenceLevels {
    const dsn_noise_state *noise;
    const dsn_walked_level *levels;
    uint32_t count;
    uint64_t sums[2][DSN_MAX_CHANNELS];

    void visit_listed(const dsn_surface_impulses &listed, uint32_t listed_count, uint32_t cell_shift) {
        const int64_t unmoved[3] = {0, 0, 0};
        visit_each(this, listed, listed_count, cell_shift, unmoved);
    }
    void visit(int64_t along_tangent, int64_t along_bitangent, uint32_t window) {
        for (uint32_t l = 0; l < count; l++) {
            uint64_t level[DSN_MAX_CHANNELS] = {0, 0, 0};
            add_level<false>(levels[l], noise->asset.channels, noise->asset.bits, along_tangent,
                             along_bitangent, level, nullptr);
            for (uint32_t c = 0; c < noise->asset.channels; c++) sums[l][c] += windowed(level[c], window);
        }
    }
};

int reference_filtered(const dsn_noise &handle, const int64_t *position, const dsn_surface_frame &frame,
                       const dsn_footprint &footprint, int32_t *out) {
    dsn_noise copy = handle;
    dsn_noise_state *noise = dsn_state(&copy);
    noise->tile_kernel = DSN_KERNEL_DEFAULT;
    dsn_filter_plan plan;
    REQUIRE(dsn_internal_filter_plan(&footprint, noise->asset.pyramid_levels, &plan) == DSN_OK);
    REQUIRE(plan.taps > 1); // (the footprints below: minified)
    if (dsn_internal_filter_fade(noise, &plan, out)) return DSN_ERR_UNSUPPORTED; // past the pyramid: no walk
    dsn_walked_level walked[2];
    const uint32_t count = dsn_internal_filter_walked_levels(noise, &plan, walked);
    uint32_t radius_x, radius_y;
    dsn_filter_walk_radii(walked, count, &radius_x, &radius_y);
    int64_t offsets[2][DSN_MAX_CHANNELS], totals[DSN_MAX_CHANNELS] = {0, 0, 0};
    for (uint32_t l = 0; l < count; l++)
        surface_offset(noise, dsn_internal_level_offset(noise, walked[l].level), offsets[l]);
    for (uint32_t tap = 0; tap < plan.taps; tap++) {
        const int64_t u = plan.offset_x[tap] >> 16, v = plan.offset_y[tap] >> 16; // floors
        int64_t at[3];
        for (int i = 0; i < 3; i++)
            at[i] = int64_t(uint64_t(position[i]) +
                            uint64_t((u * frame.tangent[i] + v * frame.bitangent[i]) >> 14));
        SurfaceWalk walk;
        surface_walk(noise, at, &frame, radius_x + 1u, radius_y + 1u, &walk);
        if (walk_too_costly(noise, &walk)) return DSN_ERR_COST;
        ReferenceLevels levels = {noise, walked, count, {{0, 0, 0}, {0, 0, 0}}};
        visit_impulses(noise, &walk, &levels);
        for (uint32_t l = 0; l < count; l++) {
            int64_t values[DSN_MAX_CHANNELS] = {0, 0, 0};
            dsn_internal_filter_level_values_from(noise, &walked[l], levels.sums[l], offsets[l], values);
            dsn_internal_filter_add_level(noise, &plan, l, values, totals);
        }
        if (count == 1) dsn_internal_filter_add_mean(noise, &plan, totals);
    }
    dsn_internal_filter_finish(noise, &plan, totals, out);
    return DSN_OK;
}

} // namespace

TEST_CASE("filtered surface: several taps read from one walk give the tap-by-tap walks' bits") {
    // Anisotropic footprints in every direction of the tangent plane, 2 to 16 taps, their spread within
    // one tap's reach (one walk for all) and wider (a walk per tap), at random points and frames; grey and
    // RGB, 8-bit (the kernels' level reads) and 16-bit (one by one).
    std::mt19937_64 random(41);
    std::uniform_real_distribution<double> coordinate(-400, 400), angle(0, 6.283185307179586);
    std::uniform_real_distribution<float> direction(-1, 1);
    int compared = 0;
    for (const uint32_t channels : {1u, 3u})
        for (const uint32_t bits : {8u, 16u}) {
            dsn::AssetFields fields = random_texton_asset(channels, 7, bits, 60 + channels + bits);
            fields.pyramid = dsn::texton_pyramid(fields);
            auto noise = make_noise(fields, 11, 20u << 16);
            for (int k = 0; k < 60; k++) {
                const float n[3] = {direction(random), direction(random), direction(random)};
                dsn_surface_frame frame;
                if (dsn_surface_frame_from_float(n, nullptr, &frame) != DSN_OK) continue;
                const int64_t position[3] = {dsn_coordinate_from_double(coordinate(random)),
                                             dsn_coordinate_from_double(coordinate(random)),
                                             dsn_coordinate_from_double(coordinate(random))};
                const double minor = 1.5 + 2 * (k % 3), major = minor * (2 + k % 7) * (k % 4 == 3 ? 8 : 1);
                const double a = angle(random), c = std::cos(a), s = std::sin(a);
                dsn_footprint footprint;
                REQUIRE(dsn_footprint_from_float(&footprint, major * c, major * s, -minor * s, minor * c,
                                                 2 + uint32_t(k % 15)) == DSN_OK);
                int32_t expected[3] = {0, 0, 0}, value[3] = {0, 0, 0};
                const int expected_err =
                    reference_filtered(noise->noise, position, frame, footprint, expected);
                if (expected_err == DSN_ERR_UNSUPPORTED) continue;
                CAPTURE(k);
                CAPTURE(channels);
                CAPTURE(bits);
                CHECK(dsn_surface_filtered_point_fixed(&noise->noise, position, &frame, &footprint, value) ==
                      expected_err);
                for (uint32_t ch = 0; ch < channels; ch++) CHECK(value[ch] == expected[ch]);
                compared++;
            }
        }
    MESSAGE("filtered surface points compared with the tap-by-tap walks: " << compared);
    CHECK(compared > 160); // most footprints lie within the pyramid
}

TEST_CASE("filtered surface: a texel's footprint is the point; minified, it follows the box-filtered noise") {
    dsn::AssetFields fields = random_texton_asset(1, 15, 8, 77);
    fields.pyramid = dsn::texton_pyramid(fields);
    auto noise = make_noise(fields, 5, 30u << 16);
    const Vector tangent = {1, 0.25, 0};
    const dsn_surface_frame frame = make_frame({0.3, -0.5, 0.8}, &tangent);
    std::mt19937_64 random(9);
    std::uniform_real_distribution<double> coordinate(-500, 500);
    // Footprints of at most a texel: the unfiltered point's bits.
    dsn_footprint unit;
    REQUIRE(dsn_footprint_from_float(&unit, 1, 0, 0, 1, 16) == DSN_OK);
    for (int k = 0; k < 200; k++) {
        const Vector p = on_plane(frame, coordinate(random), coordinate(random));
        const int64_t position[3] = {dsn_coordinate_from_double(p.x), dsn_coordinate_from_double(p.y),
                                     dsn_coordinate_from_double(p.z)};
        int32_t point[1], filtered[1];
        REQUIRE(dsn_surface_point_fixed(&noise->noise, position, &frame, point) == DSN_OK);
        REQUIRE(dsn_surface_filtered_point_fixed(&noise->noise, position, &frame, &unit, filtered) == DSN_OK);
        CHECK(point[0] == filtered[0]);
    }
    // Minified k times (a pixel of k x k texels in the tangent plane, and a slanted one k x 4k), against the
    // mean of 8 x 8 unfiltered samples over the pixel: the filtered value's error is at most half one
    // sample's, and within the plane's own: the plane's filtered noise against the same kind of reference
    // (8 x 8 continuous samples over the same pixels) errs about as much, the pyramid's Gaussians being no
    // box. Each RMSE over 150 pixels has a relative standard error of about 1 / sqrt(300), 6%: the two
    // within 4 standard errors of their difference, 35%.
    const double sizes[][2] = {{4, 4}, {16, 16}, {4, 16}};
    for (const auto &size : sizes) {
        dsn_footprint footprint;
        REQUIRE(dsn_footprint_from_float(&footprint, size[0], 0, 0, size[1], 16) == DSN_OK);
        double filtered_error = 0, sample_error = 0, plane_error = 0;
        const int pixels = 150;
        for (int k = 0; k < pixels; k++) {
            const double a = coordinate(random), b = coordinate(random);
            double box = 0, plane_box = 0;
            for (int j = 0; j < 8; j++)
                for (int i = 0; i < 8; i++) {
                    const double u = a + size[0] * ((i + 0.5) / 8 - 0.5),
                                 v = b + size[1] * ((j + 0.5) / 8 - 0.5);
                    float plane[1];
                    REQUIRE(dsn_continuous_point_float(&noise->noise, u, v, plane) == DSN_OK);
                    box += surface_value(noise->noise, on_plane(frame, u, v), frame)[0] / 64;
                    plane_box += plane[0] / 64.0;
                }
            const double filtered =
                filtered_surface_value(noise->noise, on_plane(frame, a, b), frame, footprint);
            const double sample = surface_value(noise->noise, on_plane(frame, a, b), frame)[0];
            float plane_filtered[1];
            REQUIRE(dsn_filtered_point_float(&noise->noise, a, b, &footprint, plane_filtered) == DSN_OK);
            filtered_error += (filtered - box) * (filtered - box) / pixels;
            sample_error += (sample - box) * (sample - box) / pixels;
            plane_error += (plane_filtered[0] - plane_box) * (plane_filtered[0] - plane_box) / pixels;
        }
        filtered_error = std::sqrt(filtered_error), sample_error = std::sqrt(sample_error);
        plane_error = std::sqrt(plane_error);
        MESSAGE("filtered surface, pixel " << size[0] << " x " << size[1] << " texels: rmse "
                                           << filtered_error << " (" << filtered_error / sample_error
                                           << "x one sample's; the plane's " << plane_error << ")");
        CHECK(filtered_error <= 0.5 * sample_error);
        CHECK(filtered_error <= 1.35 * plane_error);
    }
    // Past the pyramid the mean colour, exactly; and the footprint's errors.
    dsn_footprint far;
    REQUIRE(dsn_footprint_from_float(&far, 1e6, 0, 0, 1e6, 1) == DSN_OK);
    const int64_t origin[3] = {0, 0, 0};
    int32_t out[1] = {7};
    REQUIRE(dsn_surface_filtered_point_fixed(&noise->noise, origin, &frame, &far, out) == DSN_OK);
    CHECK(out[0] == fields.mean[0] / 256);
    CHECK(dsn_surface_filtered_point_fixed(&noise->noise, origin, &frame, nullptr, out) == DSN_ERR_NULL);
    CHECK(out[0] == 0);
    dsn_footprint no_taps = unit;
    no_taps.max_taps = 0;
    CHECK(dsn_surface_filtered_point_fixed(&noise->noise, origin, &frame, &no_taps, out) == DSN_ERR_ARGUMENT);
    float floats[1];
    const double position[3] = {1, 2, 3};
    const float normal[3] = {0.3f, -0.5f, 0.8f}, along[3] = {1, 0.25f, 0};
    REQUIRE(dsn_surface_filtered_point_float(&noise->noise, position, normal, along, &unit, floats) ==
            DSN_OK);
    float point[1];
    REQUIRE(dsn_surface_point_float(&noise->noise, position, normal, along, point) == DSN_OK);
    CHECK(floats[0] == point[0]);
}

TEST_CASE("filtered surface: a walk too costly for the slab is refused, the plane's accepted") {
    // A 255 x 255 texton at 1024 impacts, read at a coarse level over 16 taps: the plane's filtered point
    // stays within the bound dsn_noise_init checked, the slab's walk (its cubes, several along the normal
    // and the tilted box's) does not.
    dsn::AssetFields fields = random_texton_asset(1, 127, 16, 77);
    fields.pyramid = dsn::texton_pyramid(fields);
    auto noise = make_noise(fields, 5, 1024u << 16);
    dsn_footprint footprint;
    REQUIRE(dsn_footprint_from_float(&footprint, 128, 0, 0, 2048, 16) == DSN_OK);
    const float normal[3] = {0.577f, 0.577f, 0.577f};
    const double position[3] = {1, 2, 3};
    float out[1] = {7}, plane[1];
    CHECK(dsn_surface_filtered_point_float(&noise->noise, position, normal, nullptr, &footprint, out) ==
          DSN_ERR_COST);
    CHECK(out[0] == 0);
    CHECK(dsn_filtered_point_float(&noise->noise, 1, 2, &footprint, plane) == DSN_OK);
}
