// tiny_renderer: a small software ray caster (a ground plane to the horizon and a sphere) whose surfaces
// are textured by the continuous-mode spot noise of one or two .dsnt assets, written to a PNG.
//
// What to copy into your own renderer is `sample_texture`: turn the surface point into texture
// coordinates in texels, hand them to dsn_continuous_point_float, and fade toward the texture's mean
// colour when one pixel covers many texels (the noise has no mip-maps, but its mean is known exactly).
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <stb_image_write.h>

#include "dsn/dsn.h"

namespace {

const char *const usage =
    "usage: dsn-tiny-renderer GROUND.dsnt [SPHERE.dsnt] -o OUT.png [--size WxH] [--seed S]\n"
    "Ray-casts a ground plane and a sphere textured with the continuous-mode noise of the\n"
    "assets (the ground's asset is used for both when only one is given).\n"
    "  -o, --output OUT.png   the picture to write\n"
    "  --size WxH             its size, 1..8192 per side (default 800x500)\n"
    "  --seed S               the noise's seed (default 1)\n"
    "  -h, --help, --version  this help, the version\n"
    "Flags take their value as --flag value or --flag=value. Errors are one line on stderr: exit 2 for\n"
    "a usage mistake (the line ends with \"(see --help)\"), exit 1 when an asset cannot be used or the\n"
    "picture cannot be written.\n";

// A mistake in the command line: exit 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Vec {
    double x, y, z;
};
Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator*(Vec a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec normalize(Vec a) { return a * (1 / std::sqrt(dot(a, a))); }

// A loaded asset and its configured noise (the noise points into `bytes`).
struct Texture {
    std::vector<unsigned char> bytes;
    dsn_asset asset;
    dsn_noise noise;
    double texels_per_unit;
};

void load_texture(Texture &texture, const std::string &path, uint32_t seed, double texels_per_unit) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("cannot read " + path);
    texture.bytes.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
    int err = dsn_asset_load(&texture.asset, texture.bytes.data(), texture.bytes.size());
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = seed;
    config.flags = DSN_FLAG_ALLOW_LATTICE_CONTINUOUS; // a lattice-baked asset is only slightly smoother
    if (err == DSN_OK) err = dsn_noise_init(&texture.noise, &texture.asset, &config);
    if (err != DSN_OK) throw std::runtime_error(path + ": " + dsn_error_message(err));
    texture.texels_per_unit = texels_per_unit;
}

// RGB colour of the texture at surface coordinates (u, v) in scene units, for a pixel that covers
// `footprint` scene units there.
Vec sample_texture(const Texture &texture, double u, double v, double footprint) {
    float value[3];
    dsn_continuous_point_float(&texture.noise, u * texture.texels_per_unit, v * texture.texels_per_unit,
                               value);
    Vec noise =
        texture.asset.channels == 3 ? Vec{value[0], value[1], value[2]} : Vec{value[0], value[0], value[0]};
    const double m0 = texture.asset.mean[0] / 16777216.0;
    Vec mean = texture.asset.channels == 3
                   ? Vec{m0, texture.asset.mean[1] / 16777216.0, texture.asset.mean[2] / 16777216.0}
                   : Vec{m0, m0, m0};
    // Beyond ~2 texels per pixel the samples alias: fade to the mean over the next 6 texels.
    const double texels = footprint * texture.texels_per_unit;
    const double fade = texels < 2 ? 0 : texels > 8 ? 1 : (texels - 2) / 6;
    return noise * (1 - fade) + mean * fade;
}

struct Scene {
    Vec eye{0, 2.2, -5.5}, sun = normalize(Vec{-0.6, 0.8, -0.3});
    Vec sphere_center{0.3, 1.2, 2.5};
    double sphere_radius = 1.2;
    const Texture *ground, *sphere;
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

// Colour seen along one camera ray; `pixel_angle` is the angle one pixel spans (for the footprint).
Vec trace(const Scene &scene, Vec direction, double pixel_angle) {
    const double t_sphere = hit_sphere(scene, scene.eye, direction);
    const double t_ground = direction.y < 0 ? -scene.eye.y / direction.y : -1;
    if (t_sphere > 0 && (t_ground < 0 || t_sphere < t_ground)) {
        const Vec point = scene.eye + direction * t_sphere;
        const Vec normal = normalize(point - scene.sphere_center);
        // Longitude and latitude as texture coordinates, in scene units along the surface.
        const double u = std::atan2(normal.z, normal.x) * scene.sphere_radius;
        const double v = std::acos(normal.y) * scene.sphere_radius;
        const double facing = std::fabs(dot(normal, direction));
        const Vec albedo =
            sample_texture(*scene.sphere, u, v, t_sphere * pixel_angle / (facing > 0.2 ? facing : 0.2));
        const double light = dot(normal, scene.sun);
        return albedo * (0.25 + 0.85 * (light > 0 ? light : 0));
    }
    if (t_ground > 0) {
        const Vec point = scene.eye + direction * t_ground;
        const double grazing = -direction.y;
        const Vec albedo = sample_texture(*scene.ground, point.x, point.z, t_ground * pixel_angle / grazing);
        const bool shadowed = hit_sphere(scene, point, scene.sun) > 0;
        Vec color = albedo * (0.3 + (shadowed ? 0 : 0.75 * scene.sun.y));
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

uint32_t parse_seed(const std::string &text) {
    char *end = nullptr;
    const unsigned long long value = std::strtoull(text.c_str(), &end, 10);
    if (text.empty() || text[0] == '-' || *end != '\0' || value > 0xFFFFFFFFull)
        throw UsageError("--seed needs a whole number 0..4294967295, not '" + text + "'");
    return uint32_t(value);
}

int run(int argc, char **argv) {
    std::vector<std::string> assets;
    std::string output;
    int width = 800, height = 500;
    uint32_t seed = 1;
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
        const bool takes_value = flag == "-o" || flag == "--output" || flag == "--size" || flag == "--seed";
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
        } else if (flag.size() > 1 && flag[0] == '-') {
            throw UsageError("unknown flag " + flag);
        } else {
            assets.push_back(flag);
        }
    }
    if (assets.empty() || assets.size() > 2) throw UsageError("give one or two assets");
    if (output.size() < 5 || output.compare(output.size() - 4, 4, ".png") != 0)
        throw UsageError("the output must be a .png: -o OUT.png");

    Texture ground, sphere;
    load_texture(ground, assets[0], seed, 40);
    load_texture(sphere, assets.back(), seed + 1, 40);
    Scene scene;
    scene.ground = &ground;
    scene.sphere = &sphere;

    // A pinhole camera looking slightly down, 60 degrees of horizontal field of view.
    const Vec forward = normalize(Vec{0, -0.2, 1}), right{1, 0, 0};
    const Vec up{0, forward.z, -forward.y};
    const double half_width = std::tan(30 * 3.14159265358979 / 180), pixel_angle = 2 * half_width / width;
    std::vector<uint8_t> pixels(size_t(width) * height * 3);
    // Rows are shared out to one thread per core as they come (a configured dsn_noise may be read by
    // several threads at once); every pixel is computed alone, so the picture does not depend on it.
    std::atomic<int> next_row{0};
    auto render_rows = [&] {
        for (int j; (j = next_row++) < height;)
            for (int i = 0; i < width; i++) {
                const double sx = ((i + 0.5) / width * 2 - 1) * half_width;
                const double sy = (1 - (j + 0.5) / height * 2) * half_width * height / width;
                const Vec color = trace(scene, normalize(forward + right * sx + up * sy), pixel_angle);
                uint8_t *pixel = &pixels[(size_t(j) * width + i) * 3];
                pixel[0] = to_byte(color.x), pixel[1] = to_byte(color.y), pixel[2] = to_byte(color.z);
            }
    };
    std::vector<std::thread> workers(
        std::thread::hardware_concurrency() > 1 ? std::thread::hardware_concurrency() - 1 : 0);
    for (std::thread &worker : workers) worker = std::thread(render_rows);
    render_rows();
    for (std::thread &worker : workers) worker.join();
    write_png(output, width, height, pixels);
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
