// tiny_renderer: a small software ray caster (a ground plane to the horizon and a sphere) whose surfaces
// are textured by the continuous-mode spot noise of one or two .dsnt assets, written to a PNG.
//
// What to copy into your own renderer is `sample_texture`: turn the surface point into texture
// coordinates in texels and the pixel's footprint into the Jacobian of those coordinates per pixel (here
// from ray differentials: ray_differentials.h), and hand both to dsn_filtered_point_float. A pixel that
// covers many texels then shows the texture filtered over its footprint, down to the exact mean colour
// far away, instead of aliased noise.
//
// With --shading bump the surfaces are also bump-mapped: the texture's luminance is a relief (a height in
// texels), whose exact gradient per texel dsn_continuous_gradient_float (or, filtered,
// dsn_filtered_gradient_float) gives with the value; the chain rule carries it to the surface
// (`height_gradient`, with the coordinates' surface gradients from ray_differentials.h) and the normal is
// bent by it (`bumped_normal`) before the light is applied.
//
// With --mapping surface there are no texture coordinates at all: every surface (the ground, the sphere and
// a torus beside it) reads the surface noise at its 3-D point and normal (`sample_surface`), filtered by
// the pixel's footprint projected on the tangent plane, with no seam, no pinched pole, and the same look on
// the ground as the planar noise's.
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <stb_image_write.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dsn/dsn.h"
#include "ray_differentials.h"

namespace {

const char *const usage =
    "usage: dsn-tiny-renderer GROUND.dsnt [SPHERE.dsnt] -o OUT.png|OUT.f32 [--size WxH] [--seed S]\n"
    "                         [--filter none|iso|aniso] [--supersample N] [--crop X,Y,WxH]\n"
    "                         [--shading flat|bump] [--bump B] [--mapping uv|surface] [--time-limit S]\n"
    "Ray-casts a ground plane and a sphere textured with the continuous-mode noise of the\n"
    "assets (the ground's asset is used for both when only one is given).\n"
    "  -o, --output OUT       the picture to write: .png (8-bit RGB), or .f32 (raw little-endian float32,\n"
    "                         RGB interleaved, row-major, top row first, unclamped, as dsn-render writes)\n"
    "  --size WxH             its size, 1..8192 per side (default 800x500)\n"
    "  --seed S               the noise's seed (default 1)\n"
    "  --filter F             how a pixel reads the texture: aniso (default: filtered over the pixel's\n"
    "                         footprint from ray differentials, up to 16 taps along its long axis),\n"
    "                         iso (one tap, blurrier on slanted surfaces) or none (one unfiltered\n"
    "                         sample: aliases where a pixel covers many texels)\n"
    "  --supersample N        N x N unfiltered samples per pixel, averaged (a reference for the\n"
    "                         filters, N*N times slower; 1..16, needs --filter none)\n"
    "  --crop X,Y,WxH         render only the W x H pixels at (X, Y) of the --size picture\n"
    "  --shading S            flat (default: the texture's colour lit by the surface's own normal) or\n"
    "                         bump (bump mapping: the texture's luminance is a relief whose exact\n"
    "                         gradient, from dsn_continuous_gradient_float, bends the normal)\n"
    "  --bump B               the relief's height in texels per unit of luminance (1.0 = white), 0..64\n"
    "                         (default 8; implies --shading bump). With --filter iso or aniso the\n"
    "                         gradient is the filtered noise's (dsn_filtered_gradient_float): the relief\n"
    "                         fades with the texture's detail far away instead of aliasing; --filter\n"
    "                         none and --supersample keep it whole (the latter averages it: the\n"
    "                         reference)\n"
    "  --mapping M            uv (default: the ground's x and z and the sphere's longitude and latitude\n"
    "                         as texture coordinates) or surface (no coordinates: the surface noise of\n"
    "                         each 3-D point and normal on the ground, the sphere and a torus,\n"
    "                         dsn_surface_filtered_point_fixed with the footprint on the tangent plane,\n"
    "                         or dsn_surface_point_fixed with --filter none; flat shading only)\n"
    "  --time-limit S         refuse a picture estimated to take more than S seconds (default 600;\n"
    "                         0 = no limit), from 64 probe pixels spread over it, timed first\n"
    "  -h, --help, --version  this help, the version\n"
    "Flags take their value as --flag value or --flag=value. Errors are one line on stderr: exit 2 for\n"
    "a usage mistake (the line ends with \"(see --help)\"), exit 1 when an asset cannot be used, the\n"
    "picture is estimated over --time-limit, or it cannot be written.\n";

// A mistake in the command line: exit 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

using tiny::Vec;

enum class Filter { none, iso, aniso };

// How surfaces are lit: by their own normal, or by the normal of a relief made of the texture (bump).
enum class Shading { flat, bump };

// How surfaces find their texture: by texture coordinates, or by their 3-D point and normal.
enum class Mapping { uv, surface };

struct Shade {
    Shading shading = Shading::flat;
    double bump = 8; // the relief's height in texels per unit of luminance
};

// A loaded asset and its configured noise (the noise points into `bytes`).
struct Texture {
    std::vector<unsigned char> bytes;
    dsn_asset asset;
    dsn_noise noise;
    double texels_per_unit;
};

// The largest .dsnt file of the format this runtime reads (dsn/format.h): the header, the texton, every
// section of a known kind at its largest, the CRC (the same number as the dsn tools' limit). A larger file
// is not an asset, so a renderer need never read more.
size_t largest_asset_bytes() {
    const auto section = [](size_t payload) {
        return DSN_SECTION_HEADER_SIZE +
               (payload + DSN_SECTION_ALIGNMENT - 1) / DSN_SECTION_ALIGNMENT * DSN_SECTION_ALIGNMENT;
    };
    const size_t texton = size_t(DSN_FORMAT_MAX_SIDE) * DSN_FORMAT_MAX_SIDE * DSN_MAX_CHANNELS * 2;
    const size_t pyramid =
        section(DSN_PYRAMID_HEADER_SIZE + DSN_PYRAMID_MAX_LEVELS * (DSN_PYRAMID_RECORD_SIZE + texton));
    const size_t histogram =
        section(DSN_HISTOGRAM_HEADER_SIZE +
                size_t(2) * DSN_HISTOGRAM_MAX_LEVELS * DSN_HISTOGRAM_MAX_ENTRIES * DSN_MAX_CHANNELS);
    const size_t lattice_texton = section(DSN_LATTICE_TEXTON_HEADER_SIZE + texton);
    return DSN_FORMAT_HEADER_SIZE + pyramid + histogram + lattice_texton + texton + DSN_FORMAT_CRC_SIZE;
}

// The file's bytes, in the words the dsn tools use when it cannot be read ("cannot read x.dsnt: No such
// file or directory"). This program links the runtime alone, as a renderer of yours would, so it reads
// files itself rather than through the tools' library, and as carefully: only a regular file (opened
// without blocking, so a FIFO is refused instead of waiting for a writer forever), and never more than
// the largest asset (so /dev/zero or a huge file is refused instead of filling the memory).
std::vector<unsigned char> read_asset_file(const std::string &path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
    struct stat status;
    if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
        ::close(fd);
        throw std::runtime_error("cannot read " + path + ": not a regular file");
    }
    const size_t limit = largest_asset_bytes();
    const std::runtime_error too_large(path + " is too large: larger than the limit of " +
                                       std::to_string(limit) + " bytes for a dsn asset");
    if (uint64_t(status.st_size) > limit) {
        ::close(fd);
        throw too_large;
    }
    std::vector<unsigned char> bytes(limit + 1); // one byte past the limit tells a file grown since fstat
    size_t size = 0;
    while (size < bytes.size()) {
        const ssize_t count = ::read(fd, bytes.data() + size, bytes.size() - size);
        if (count < 0 && errno == EINTR) continue;
        if (count <= 0) {
            if (count < 0) {
                const int error = errno;
                ::close(fd);
                throw std::runtime_error("cannot read " + path + ": " + std::strerror(error));
            }
            break;
        }
        size += size_t(count);
    }
    ::close(fd);
    if (size > limit) throw too_large;
    bytes.resize(size);
    return bytes;
}

void load_texture(Texture &texture, const std::string &path, uint32_t seed, double texels_per_unit) {
    texture.bytes = read_asset_file(path);
    int err = dsn_asset_load(&texture.asset, texture.bytes.data(), texture.bytes.size());
    if (err != DSN_OK) throw std::runtime_error(path + " is not a dsn asset: " + dsn_error_message(err));
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = seed;
    config.flags = DSN_FLAG_ALLOW_LATTICE_CONTINUOUS; // a lattice-baked asset is only slightly smoother
    err = dsn_noise_init(&texture.noise, &texture.asset, &config);
    if (err == DSN_ERR_COST)
        throw std::runtime_error(path + ": " + dsn_error_message(err) +
                                 " (too dense for its texton and pyramid: bake it with fewer impacts)");
    if (err != DSN_OK) throw std::runtime_error(path + ": " + dsn_error_message(err));
    texture.texels_per_unit = texels_per_unit;
}

// What a surface point reads from its texture: the RGB colour, and the slope of the relief (texels of
// height per texel along u and v; zero in flat shading).
struct TextureSample {
    Vec albedo;
    double height_du, height_dv;
};

// The relief's height per unit of a point's value: its luminance (Rec. 709 weights), or its one channel.
double luminance(const float *value, uint32_t channels) {
    return channels == 3 ? 0.2126 * value[0] + 0.7152 * value[1] + 0.0722 * value[2] : double(value[0]);
}

// The texture at texture coordinates (u, v) in texels, for a pixel whose footprint there is `jacobian`
// (texels per pixel along the screen's x and y).
TextureSample sample_texture(const Texture &texture, double u, double v,
                             const tiny::TextureJacobian &jacobian, Filter filter, const Shade &shade) {
    float value[3], dx[3] = {0, 0, 0}, dy[3] = {0, 0, 0};
    dsn_footprint footprint;
    const bool filtered =
        filter != Filter::none &&
        dsn_footprint_from_float(&footprint, jacobian.du_dx, jacobian.dv_dx, jacobian.du_dy, jacobian.dv_dy,
                                 filter == Filter::aniso ? 16 : 1) == DSN_OK;
    const bool bump = shade.shading == Shading::bump && shade.bump > 0;
    // The value and its gradient in one call: out is the value function's. Filtered, the gradient is the
    // filtered noise's own (dsn_filtered_gradient_float), so the relief fades with the texture's detail
    // where a pixel covers many texels instead of aliasing.
    if (filtered && bump)
        dsn_filtered_gradient_float(&texture.noise, u, v, &footprint, value, dx, dy);
    else if (filtered)
        dsn_filtered_point_float(&texture.noise, u, v, &footprint, value);
    else if (bump)
        dsn_continuous_gradient_float(&texture.noise, u, v, value, dx, dy);
    else
        dsn_continuous_point_float(&texture.noise, u, v, value);
    const uint32_t channels = texture.asset.channels;
    const double height = bump ? shade.bump : 0;
    return {channels == 3 ? Vec{value[0], value[1], value[2]} : Vec{value[0], value[0], value[0]},
            height * luminance(dx, channels), height * luminance(dy, channels)};
}

// The relief's gradient along the surface, in scene units of height per scene unit: the height is
// h / texels_per_unit scene units (h in texels), and h moves by dh/du du + dh/dv dv, so by the chain rule
// grad H = (dh/du grad u + dh/dv grad v) / texels_per_unit (grad u and grad v in texels per scene unit:
// on the ground, texels_per_unit along x and z, and the factor cancels, a slope being a ratio).
Vec height_gradient(const TextureSample &sample, const tiny::CoordinateGradients &coordinates,
                    double texels_per_unit) {
    return (coordinates.u * sample.height_du + coordinates.v * sample.height_dv) * (1 / texels_per_unit);
}

// The shading normal of the surface of unit normal n raised along n by a height H: to first order in
// the slope (Blinn, "Simulation of wrinkled surfaces", SIGGRAPH 1978), n - grad H, normalized; a surface
// rising toward +x leans its normal toward -x. No relief leaves the normal as it is, bit for bit.
Vec bumped_normal(Vec normal, Vec height_gradient) {
    if (height_gradient.x == 0 && height_gradient.y == 0 && height_gradient.z == 0) return normal;
    return normalize(normal - height_gradient);
}

struct Scene {
    Vec sun = normalize(Vec{-0.6, 0.8, -0.3});
    Vec sphere_center{0.3, 1.2, 2.5};
    double sphere_radius = 1.2;
    Vec torus_center{-1.9, 0.45, 2.2};
    double torus_ring = 0.8, torus_tube = 0.45; // lying on the ground, its axis along y
    const Texture *ground, *sphere;
    Shade shade;
    Mapping mapping = Mapping::uv;
};

// Distance along the ray to the sphere, or -1.
double hit_sphere(const Scene &scene, Vec origin, Vec direction) {
    const Vec to = origin - scene.sphere_center;
    const double b = dot(to, direction), c = dot(to, to) - scene.sphere_radius * scene.sphere_radius;
    const double discriminant = b * b - c;
    if (discriminant < 0) return -1;
    const double t = -b - std::sqrt(discriminant);
    return t > 1e-6 ? t : -1;
}

Vec sky(Vec direction) {
    const double up = direction.y < 0 ? 0 : direction.y;
    return Vec{0.75, 0.82, 0.92} * (1 - up) + Vec{0.35, 0.52, 0.85} * up;
}

// Signed distance to the torus, and its normal at a point on it (the gradient of that distance).
double torus_distance(const Scene &scene, Vec p) {
    const Vec q = p - scene.torus_center;
    const double ring = std::sqrt(q.x * q.x + q.z * q.z) - scene.torus_ring;
    return std::sqrt(ring * ring + q.y * q.y) - scene.torus_tube;
}

Vec torus_normal(const Scene &scene, Vec p) {
    const Vec q = p - scene.torus_center;
    const double across = std::sqrt(q.x * q.x + q.z * q.z);
    const Vec ring_point = Vec{q.x, 0, q.z} * (scene.torus_ring / across);
    return normalize(q - ring_point);
}

// Distance along the ray to the torus (sphere tracing its distance, which never overshoots), or -1. Only
// in the surface mapping's scene.
double hit_torus(const Scene &scene, Vec origin, Vec direction) {
    if (scene.mapping != Mapping::surface) return -1;
    double t = 0;
    for (int step = 0; step < 256 && t < 40; step++) {
        const double distance = torus_distance(scene, origin + direction * t);
        if (distance < 1e-5) return t > 1e-4 ? t : -1;
        t += distance;
    }
    return -1;
}

// The surface noise at a scene point with its unit normal: no texture coordinates, the point in texels.
// Filtered, the pixel's footprint is its motion on the surface (ray differentials) projected on the
// frame's tangent and bitangent, in texels per pixel.
Vec sample_surface(const Texture &texture, Vec point, Vec normal, const tiny::SurfaceDifferential &motion,
                   Filter filter) {
    const double scale = texture.texels_per_unit;
    const double position[3] = {point.x * scale, point.y * scale, point.z * scale};
    const float n[3] = {float(normal.x), float(normal.y), float(normal.z)};
    float value[3] = {0, 0, 0};
    dsn_surface_frame frame;
    dsn_footprint footprint;
    if (dsn_surface_frame_from_float(n, nullptr, &frame) == DSN_OK) {
        const auto axis = [](const int32_t *v) {
            return Vec{v[0] / 1073741824.0, v[1] / 1073741824.0, v[2] / 1073741824.0};
        };
        const Vec tangent = axis(frame.tangent), bitangent = axis(frame.bitangent);
        const int64_t at[3] = {dsn_coordinate_from_double(position[0]),
                               dsn_coordinate_from_double(position[1]),
                               dsn_coordinate_from_double(position[2])};
        int32_t fixed[3] = {0, 0, 0};
        if (filter != Filter::none &&
            dsn_footprint_from_float(
                &footprint, dot(motion.along_x, tangent) * scale, dot(motion.along_x, bitangent) * scale,
                dot(motion.along_y, tangent) * scale, dot(motion.along_y, bitangent) * scale,
                filter == Filter::aniso ? 16 : 1) == DSN_OK)
            dsn_surface_filtered_point_fixed(&texture.noise, at, &frame, &footprint, fixed);
        else
            dsn_surface_point_fixed(&texture.noise, at, &frame, fixed);
        for (int c = 0; c < 3; c++) value[c] = dsn_fixed_to_float(fixed[c]);
    }
    return texture.asset.channels == 3 ? Vec{value[0], value[1], value[2]}
                                       : Vec{value[0], value[0], value[0]};
}

// Colour seen through the continuous pixel position (px, py); `filter` says how the texture is read.
Vec trace(const Scene &scene, const tiny::Camera &camera, double px, double py, Filter filter) {
    const tiny::RayDifferential ray = tiny::ray_differential(camera, px, py);
    const Vec direction = ray.direction;
    const double t_sphere = hit_sphere(scene, camera.eye, direction);
    const double t_ground = direction.y < 0 ? -camera.eye.y / direction.y : -1;
    const double t_torus = hit_torus(scene, camera.eye, direction);
    if (t_torus > 0 && (t_sphere < 0 || t_torus < t_sphere) && (t_ground < 0 || t_torus < t_ground)) {
        const Vec point = camera.eye + direction * t_torus;
        const Vec normal = torus_normal(scene, point);
        const double light = dot(normal, scene.sun);
        return sample_surface(*scene.sphere, point, normal, tiny::transfer(ray, t_torus, normal), filter) *
               (0.25 + 0.85 * (light > 0 ? light : 0));
    }
    if (t_sphere > 0 && (t_ground < 0 || t_sphere < t_ground)) {
        const Vec point = camera.eye + direction * t_sphere;
        const Vec normal = normalize(point - scene.sphere_center);
        if (scene.mapping == Mapping::surface) {
            const double light = dot(normal, scene.sun);
            return sample_surface(*scene.sphere, point, normal, tiny::transfer(ray, t_sphere, normal),
                                  filter) *
                   (0.25 + 0.85 * (light > 0 ? light : 0));
        }
        // Longitude and latitude as texture coordinates, in texels along the surface.
        double u, v;
        tiny::sphere_coordinates(normal, scene.sphere_radius, scene.sphere->texels_per_unit, u, v);
        const tiny::TextureJacobian jacobian = tiny::sphere_jacobian(tiny::transfer(ray, t_sphere, normal),
                                                                     normal, scene.sphere->texels_per_unit);
        const TextureSample sample = sample_texture(*scene.sphere, u, v, jacobian, filter, scene.shade);
        const Vec shading_normal = bumped_normal(
            normal, height_gradient(sample, tiny::sphere_gradients(normal, scene.sphere->texels_per_unit),
                                    scene.sphere->texels_per_unit));
        const double light = dot(shading_normal, scene.sun);
        return sample.albedo * (0.25 + 0.85 * (light > 0 ? light : 0));
    }
    if (t_ground > 0) {
        const Vec point = camera.eye + direction * t_ground;
        const double scale = scene.ground->texels_per_unit;
        const tiny::TextureJacobian jacobian =
            tiny::plane_jacobian(tiny::transfer(ray, t_ground, Vec{0, 1, 0}), scale);
        const bool surface = scene.mapping == Mapping::surface;
        const TextureSample sample =
            surface ? TextureSample{sample_surface(*scene.ground, point, Vec{0, 1, 0},
                                                   tiny::transfer(ray, t_ground, Vec{0, 1, 0}), filter),
                                    0, 0}
                    : sample_texture(*scene.ground, point.x * scale, point.z * scale, jacobian, filter,
                                     scene.shade);
        const bool shadowed =
            hit_sphere(scene, point, scene.sun) > 0 || hit_torus(scene, point, scene.sun) > 0;
        const Vec shading_normal =
            bumped_normal(Vec{0, 1, 0}, height_gradient(sample, tiny::plane_gradients(scale), scale));
        const double light = dot(shading_normal, scene.sun); // scene.sun.y where the ground is flat
        Vec color = sample.albedo * (0.3 + (shadowed ? 0 : 0.75 * (light > 0 ? light : 0)));
        // Aerial perspective: far ground melts into the sky colour at the horizon.
        const double haze = 1 - std::exp(-t_ground / 60);
        return color * (1 - haze) + sky(Vec{0, 0, 1}) * haze;
    }
    return sky(direction);
}

uint8_t to_byte(double value) {
    const double clamped = value < 0 ? 0 : value > 1 ? 1 : value;
    return uint8_t(std::lround(clamped * 255));
}

// Writes the picture next to its destination, then renames it over it: never a partial PNG.
void write_png(const std::string &path, int width, int height, const std::vector<uint8_t> &pixels) {
    const std::string temporary = path + ".tmp";
    if (!stbi_write_png(temporary.c_str(), width, height, 3, pixels.data(), width * 3) ||
        std::rename(temporary.c_str(), path.c_str()) != 0) {
        std::remove(temporary.c_str());
        throw std::runtime_error("cannot write " + path);
    }
}

// The colours as raw little-endian float32, RGB interleaved, row-major (dsn-render's .f32), written
// next to the destination and renamed over it as the PNG.
void write_f32(const std::string &path, const std::vector<float> &values) {
    std::vector<unsigned char> bytes(values.size() * 4);
    for (size_t k = 0; k < values.size(); k++) {
        uint32_t bits;
        std::memcpy(&bits, &values[k], 4);
        for (int b = 0; b < 4; b++) bytes[k * 4 + size_t(b)] = uint8_t(bits >> (8 * b));
    }
    const std::string temporary = path + ".tmp";
    FILE *file = std::fopen(temporary.c_str(), "wb");
    bool written = file && std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    if (file && std::fclose(file) != 0) written = false;
    if (!written || std::rename(temporary.c_str(), path.c_str()) != 0) {
        std::remove(temporary.c_str());
        throw std::runtime_error("cannot write " + path);
    }
}

uint32_t parse_seed(const std::string &text) {
    char *end = nullptr;
    const unsigned long long value = std::strtoull(text.c_str(), &end, 10);
    if (text.empty() || text[0] == '-' || *end != '\0' || value > 0xFFFFFFFFull)
        throw UsageError("--seed needs a whole number 0..4294967295, not '" + text + "'");
    return uint32_t(value);
}

// A time budget, for assets you do not trust: the runtime bounds the work of one point, but its
// costliest accepted point takes about 20 ms, so a whole picture of them could take hours. `pixel`
// renders one pixel; 8 x 8 probe pixels spread over the picture are timed, each on the thread that
// renders it, and their mean time times the picture's pixels over the threads is the estimate (seconds).
template <typename RenderPixel>
double estimate_seconds(int width, int height, unsigned thread_count, const RenderPixel &pixel) {
    const int side = 8, probes = side * side;
    std::atomic<int> next{0};
    std::vector<double> seconds(probes);
    auto probe = [&] {
        for (int k; (k = next++) < probes;) {
            const auto begin = std::chrono::steady_clock::now();
            pixel(int((2 * (k % side) + 1) * int64_t(width) / (2 * side)),
                  int((2 * (k / side) + 1) * int64_t(height) / (2 * side)));
            seconds[size_t(k)] =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
        }
    };
    std::vector<std::thread> workers(thread_count > 1 ? thread_count - 1 : 0);
    for (std::thread &worker : workers) worker = std::thread(probe);
    probe();
    for (std::thread &worker : workers) worker.join();
    double total = 0;
    for (double one : seconds) total += one;
    return total / probes * double(width) * height / thread_count;
}

int run(int argc, char **argv) {
    std::vector<std::string> assets;
    std::string output;
    int width = 800, height = 500;
    uint32_t seed = 1;
    Filter filter = Filter::aniso;
    int supersample = 1, crop_x = 0, crop_y = 0, crop_width = 0, crop_height = 0;
    bool filter_given = false, crop_given = false, shading_given = false, bump_given = false;
    Mapping mapping = Mapping::uv;
    Shade shade;
    double time_limit = 600; // seconds; 0: no limit
    for (int i = 1; i < argc; i++) {
        std::string flag = argv[i], value;
        const size_t equals = flag.find('=');
        const bool inline_value = flag.compare(0, 2, "--") == 0 && equals != std::string::npos;
        if (inline_value) value = flag.substr(equals + 1), flag = flag.substr(0, equals);
        if (flag == "--help" || flag == "-h") {
            std::fputs(usage, stdout);
            return 0;
        }
        if (flag == "--version") {
            std::printf("dsn-tiny-renderer %s\n", dsn_version());
            return 0;
        }
        const bool takes_value = flag == "-o" || flag == "--output" || flag == "--size" || flag == "--seed" ||
                                 flag == "--filter" || flag == "--supersample" || flag == "--crop" ||
                                 flag == "--time-limit" || flag == "--shading" || flag == "--bump" ||
                                 flag == "--mapping";
        if (takes_value && !inline_value) {
            if (i + 1 >= argc) throw UsageError(flag + " needs a value");
            value = argv[++i];
        }
        if (flag == "-o" || flag == "--output") {
            output = value;
        } else if (flag == "--size") {
            char rest = 0;
            if (std::sscanf(value.c_str(), "%dx%d%c", &width, &height, &rest) != 2 || width < 1 ||
                height < 1 || width > 8192 || height > 8192)
                throw UsageError("--size needs WxH within 1..8192, not '" + value + "'");
        } else if (flag == "--seed") {
            seed = parse_seed(value);
        } else if (flag == "--filter") {
            filter_given = true;
            if (value == "none")
                filter = Filter::none;
            else if (value == "iso")
                filter = Filter::iso;
            else if (value == "aniso")
                filter = Filter::aniso;
            else
                throw UsageError("--filter must be none, iso or aniso, not '" + value + "'");
        } else if (flag == "--supersample") {
            char rest = 0;
            if (std::sscanf(value.c_str(), "%d%c", &supersample, &rest) != 1 || supersample < 1 ||
                supersample > 16)
                throw UsageError("--supersample needs a whole number 1..16, not '" + value + "'");
        } else if (flag == "--crop") {
            char rest = 0;
            if (std::sscanf(value.c_str(), "%d,%d,%dx%d%c", &crop_x, &crop_y, &crop_width, &crop_height,
                            &rest) != 4 ||
                crop_x < 0 || crop_y < 0 || crop_width < 1 || crop_height < 1)
                throw UsageError("--crop needs X,Y,WxH (whole numbers, W and H at least 1), not '" + value +
                                 "'");
            crop_given = true;
        } else if (flag == "--shading") {
            shading_given = true;
            if (value == "flat")
                shade.shading = Shading::flat;
            else if (value == "bump")
                shade.shading = Shading::bump;
            else
                throw UsageError("--shading must be flat or bump, not '" + value + "'");
        } else if (flag == "--bump") {
            char *end = nullptr;
            shade.bump = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !(shade.bump >= 0 && shade.bump <= 64))
                throw UsageError("--bump needs a height in texels within 0..64, not '" + value + "'");
            bump_given = true;
        } else if (flag == "--mapping") {
            if (value == "uv")
                mapping = Mapping::uv;
            else if (value == "surface")
                mapping = Mapping::surface;
            else
                throw UsageError("--mapping must be uv or surface, not '" + value + "'");
        } else if (flag == "--time-limit") {
            char *end = nullptr;
            time_limit = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !(time_limit >= 0 && time_limit <= 1e9))
                throw UsageError("--time-limit needs seconds within 0..1e9 (0: no limit), not '" + value +
                                 "'");
        } else if (flag.size() > 1 && flag[0] == '-') {
            throw UsageError("unknown flag " + flag);
        } else {
            assets.push_back(flag);
        }
    }
    if (assets.empty() || assets.size() > 2) throw UsageError("give one or two assets");
    const auto ends_with = [&](const char *extension) {
        return output.size() > 4 && output.compare(output.size() - 4, 4, extension) == 0;
    };
    if (!ends_with(".png") && !ends_with(".f32"))
        throw UsageError("the output must be a .png or a .f32: -o OUT.png");
    const bool raw_output = ends_with(".f32");
    // Checked before the render, not found when the picture is written: an output that would replace an
    // input, or that has no folder to go to.
    struct stat output_status, folder_status;
    const bool output_exists = ::stat(output.c_str(), &output_status) == 0;
    for (const std::string &asset : assets) {
        struct stat asset_status;
        if (asset == output ||
            (output_exists && ::stat(asset.c_str(), &asset_status) == 0 &&
             asset_status.st_dev == output_status.st_dev && asset_status.st_ino == output_status.st_ino))
            throw UsageError("output " + output + " is the input asset");
    }
    const size_t slash = output.find_last_of('/');
    const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : output.substr(0, slash);
    if (::stat(folder.c_str(), &folder_status) != 0 || !S_ISDIR(folder_status.st_mode) ||
        ::access(folder.c_str(), W_OK | X_OK) != 0)
        throw UsageError("-o " + output + ": cannot write in its folder " + folder);
    if (supersample > 1 && filter_given && filter != Filter::none)
        throw UsageError("--supersample averages unfiltered samples: it takes --filter none or no --filter");
    if (supersample > 1) filter = Filter::none;
    if (bump_given && shading_given && shade.shading == Shading::flat)
        throw UsageError("--bump is the relief of --shading bump: not with --shading flat");
    if (bump_given) shade.shading = Shading::bump;
    if (mapping == Mapping::surface && shade.shading == Shading::bump)
        throw UsageError("--mapping surface has no gradient: it takes flat shading");
    if (!crop_given) crop_width = width, crop_height = height;
    if (crop_x > width - crop_width || crop_y > height - crop_height)
        throw UsageError("--crop reaches outside the " + std::to_string(width) + "x" +
                         std::to_string(height) + " picture");

    Texture ground, sphere;
    load_texture(ground, assets[0], seed, 40);
    load_texture(sphere, assets.back(), seed + 1, 40);
    Scene scene;
    scene.ground = &ground;
    scene.sphere = &sphere;
    scene.shade = shade;
    scene.mapping = mapping;

    // A pinhole camera looking slightly down, 60 degrees of horizontal field of view.
    const tiny::Camera camera(Vec{0, 2.2, -5.5}, Vec{0, -0.2, 1}, 60, width, height);
    std::vector<uint8_t> pixels(raw_output ? 0 : size_t(crop_width) * crop_height * 3);
    std::vector<float> values(raw_output ? size_t(crop_width) * crop_height * 3 : 0);
    // Pixel (i, j) of the crop; supersampled: the average of samples at the centres of an N x N grid of
    // sub-pixels.
    auto render_pixel = [&](int i, int j) {
        Vec color{0, 0, 0};
        for (int b = 0; b < supersample; b++)
            for (int a = 0; a < supersample; a++)
                color = color + trace(scene, camera, crop_x + i + (a + 0.5) / supersample,
                                      crop_y + j + (b + 0.5) / supersample, filter);
        color = color * (1.0 / (supersample * supersample));
        const size_t at = (size_t(j) * size_t(crop_width) + size_t(i)) * 3;
        if (raw_output)
            values[at] = float(color.x), values[at + 1] = float(color.y), values[at + 2] = float(color.z);
        else
            pixels[at] = to_byte(color.x), pixels[at + 1] = to_byte(color.y),
            pixels[at + 2] = to_byte(color.z);
    };
    const unsigned thread_count =
        std::thread::hardware_concurrency() > 1 ? std::thread::hardware_concurrency() : 1;
    if (time_limit > 0) {
        const double estimate = estimate_seconds(crop_width, crop_height, thread_count, render_pixel);
        if (estimate > time_limit) {
            char line[300];
            std::snprintf(line, sizeof line,
                          "this picture would take about %.0f s (64 probe pixels, %dx%d pixels, %u "
                          "thread(s)), over --time-limit %g s: use assets with fewer impacts, a smaller "
                          "--size or --crop, or a higher --time-limit (0: no limit)",
                          estimate, crop_width, crop_height, thread_count, time_limit);
            throw std::runtime_error(line);
        }
    }
    // Rows are shared out to one thread per core as they come (a configured dsn_noise may be read by
    // several threads at once); every pixel is computed alone, so the picture does not depend on it.
    std::atomic<int> next_row{0};
    auto render_rows = [&] {
        for (int j; (j = next_row++) < crop_height;)
            for (int i = 0; i < crop_width; i++) render_pixel(i, j);
    };
    std::vector<std::thread> workers(thread_count - 1);
    for (std::thread &worker : workers) worker = std::thread(render_rows);
    render_rows();
    for (std::thread &worker : workers) worker.join();
    if (raw_output)
        write_f32(output, values);
    else
        write_png(output, crop_width, crop_height, pixels);
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    try {
        return run(argc, argv);
    } catch (const UsageError &error) {
        std::fprintf(stderr, "dsn-tiny-renderer: %s (see --help)\n", error.what());
        return 2;
    } catch (const std::exception &error) {
        std::fprintf(stderr, "dsn-tiny-renderer: %s\n", error.what());
        return 1;
    }
}
