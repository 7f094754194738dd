// dsn-gpu-render: renders a window of the spot noise on the GPU with include/dsn/dsn.glsl and writes the
// PNG that dsn-render writes for the same asset, seed and window, byte for byte.
//
// Headless: EGL on Mesa's surfaceless platform, an OpenGL ES 3.0 context and a GLSL ES 3.00 fragment
// shader (the language of WebGL2), as a renderer would use it: the packed noise (dsn_gpu_pack) in an R32UI
// texture, one fragment per pixel writing dsn_color() to an ordinary RGBA8 colour target. With no GPU (or
// LIBGL_ALWAYS_SOFTWARE=1) Mesa runs it on llvmpipe, a software GPU. With --mix, a mix of materials
// (dsn_gpu_mix_pack, dsn.glsl's dsn_mix_* functions), as dsn-render --mix renders it. With --mode sphere,
// the surface noise (dsn.glsl's dsn_surface_*) on a sphere, from a G-buffer of float positions and normals
// as a deferred renderer has them; --compare-cpu checks it against dsn_surface_point_u8.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "dsn/dsn.h"
#include "dsn/gpu.h"
#include "headless_gl.h"
#include "offline/tools/asset_file.h"
#include "offline/tools/command_line.h"
#include "offline/tools/file_output.h"
#include "offline/tools/mix_inputs.h"
#include "offline/tools/png_output.h"
#include "offline/tools/render_window.h"

namespace {

const char *const dsn_glsl =
#include "include/dsn/dsn.glsl.inc"
    ;

const char *const usage_head =
    "usage: dsn-gpu-render A.dsnt -o OUT.png --size WxH [options]\n"
    "Renders the spot noise of asset A.dsnt over a window of W x H pixels in a GLSL ES 3.00 fragment\n"
    "shader (EGL surfaceless; Mesa's llvmpipe, a software GPU, when there is no GPU). The PNG is the one\n"
    "dsn-render writes with the same options.\n"
    "  --origin X,Y       top-left point in texels (default 0,0): integers in tile mode, reals in\n"
    "                     continuous mode; values wrap modulo 2^32\n"
    "  --seed S           32-bit seed (default 0)\n"
    "  --mode M           tile (default: the lattice), continuous, or sphere: the surface noise on a\n"
    "                     sphere filling the window (no texture coordinates: dsn_surface_point per\n"
    "                     pixel from a G-buffer of float positions and normals; black around it)\n"
    "  --scale F          continuous and sphere modes: magnification (default 1)\n"
    "  --rotate DEG       continuous mode: rotation of the texture, counterclockwise (default 0)\n"
    "  --api A            gles30 (default): OpenGL ES 3.0 and GLSL ES 3.00, as in WebGL2; gl45: OpenGL 4.5\n"
    "                     core and GLSL 4.30 (the same shader with umulExtended instead of 16-bit limbs)\n"
    "  --compare-cpu      also render with the C runtime (tiles, one thread), check that the pixels are\n"
    "                     identical and print both speeds\n";
// then dsn::mix_usage, then
const char *const usage_tail =
    "  --dump-shaders DIR write the shaders to DIR (for glslangValidator) and exit\n"
    "  --quiet            no summary line (on stdout)\n"
    "Flags take --flag value or --flag=value; --version prints the version.\n"
    "Exit status: 0 on success; exit 2 for a usage mistake (the message ends with \"(see --help)\");\n"
    "exit 1 for a failure while running (bad asset, no OpenGL context, cannot write); no partial output.\n";

enum class Mode { tile, continuous, sphere };

struct Options {
    std::string asset_path, output_path, dump_directory;
    uint32_t width = 0, height = 0, seed = 0;
    std::string origin_x = "0", origin_y = "0";
    Mode mode = Mode::tile;
    double scale = 1.0, rotate_degrees = 0.0;
    bool compare_cpu = false, quiet = false;
    headless_gl::Api api = headless_gl::Api::gles30;
    dsn::MixOptions mix;
};

std::pair<std::string, std::string> split_pair(const std::string &flag, const std::string &text,
                                               char separator) {
    const size_t at = text.find(separator);
    if (at == std::string::npos)
        throw dsn::UsageError(flag + ": expected two values separated by '" + std::string(1, separator) +
                              "'");
    return {text.substr(0, at), text.substr(at + 1)};
}

Options parse_options(dsn::CommandLine &arguments) {
    Options options;
    bool size_given = false;
    while (arguments.next()) {
        const std::string flag = arguments.current();
        if (arguments.is("--quiet")) {
            arguments.no_value(), options.quiet = true;
        } else if (arguments.is("--compare-cpu")) {
            arguments.no_value(), options.compare_cpu = true;
        } else if (arguments.is_positional()) {
            if (!options.asset_path.empty()) arguments.unknown();
            options.asset_path = flag;
        } else if (arguments.is("-o") || arguments.is("--output")) {
            options.output_path = arguments.path_value();
        } else if (arguments.is("--api")) {
            const std::string value = arguments.value();
            if (value != "gles30" && value != "gl45") throw dsn::UsageError("--api must be gles30 or gl45");
            options.api = value == "gl45" ? headless_gl::Api::gl45 : headless_gl::Api::gles30;
        } else if (arguments.is("--dump-shaders")) {
            options.dump_directory = arguments.value();
        } else if (arguments.is("--size")) {
            const auto sides = split_pair(flag, arguments.value(), 'x');
            options.width = static_cast<uint32_t>(dsn::parse_integer(flag, sides.first, 1, 16384));
            options.height = static_cast<uint32_t>(dsn::parse_integer(flag, sides.second, 1, 16384));
            size_given = true;
        } else if (arguments.is("--origin")) {
            const auto origin = split_pair(flag, arguments.value(), ',');
            options.origin_x = origin.first;
            options.origin_y = origin.second;
        } else if (arguments.is("--seed")) {
            options.seed = static_cast<uint32_t>(dsn::parse_integer(arguments, 0, 0xFFFFFFFFll));
        } else if (arguments.is("--mode")) {
            const std::string value = arguments.value();
            if (value != "tile" && value != "continuous" && value != "sphere")
                throw dsn::UsageError("--mode must be tile, continuous or sphere");
            options.mode = value == "tile" ? Mode::tile : value == "sphere" ? Mode::sphere : Mode::continuous;
        } else if (arguments.is("--scale")) {
            options.scale = dsn::parse_real(flag, arguments.value());
            if (!(options.scale >= 1.0 / 65536 && options.scale <= 65536))
                throw dsn::UsageError("--scale must be within [1/65536, 65536]");
        } else if (arguments.is("--rotate")) {
            options.rotate_degrees = dsn::parse_real(flag, arguments.value());
        } else if (dsn::parse_mix_flag(arguments, options.mix)) {
        } else {
            arguments.unknown();
        }
    }
    if (!options.dump_directory.empty()) return options;
    if (options.asset_path.empty()) throw dsn::UsageError("no asset given");
    if (options.output_path.empty()) throw dsn::UsageError("no output given: -o OUT.png");
    if (options.output_path.size() < 4 ||
        options.output_path.compare(options.output_path.size() - 4, 4, ".png"))
        throw dsn::UsageError("the output must end in .png: " + options.output_path);
    if (!size_given) throw dsn::UsageError("no size given: --size WxH");
    if (options.mode == Mode::tile && options.scale != 1.0)
        throw dsn::UsageError("--scale needs --mode continuous or sphere");
    if (options.mode != Mode::continuous && options.rotate_degrees != 0.0)
        throw dsn::UsageError("--rotate needs --mode continuous");
    if (options.mode == Mode::sphere &&
        (!options.mix.paths.empty() || options.origin_x != "0" || options.origin_y != "0"))
        throw dsn::UsageError("--mode sphere takes neither --mix nor --origin");
    // Before the GPU context and the render: an output that is an input or has no folder to go to.
    std::vector<dsn::NamedPath> inputs = {{"the input asset", options.asset_path}};
    dsn::check_mix_options(options.mix, inputs);
    dsn::check_outputs(inputs, {{"-o", options.output_path}});
    return options;
}

// The fragment shader: what a renderer writes, with the window's mapping as uniforms.
const char *const fragment_main = R"glsl(
uniform highp usampler2D noise_words;
uniform uint continuous_mode;
uniform uint mix_mode;     // 1: the words are a mix's (dsn_gpu_mix_pack)
uniform uint sphere_mode;  // 1: the surface noise at the G-buffer's points
uniform highp usampler2D gbuffer; // per pixel: position bits xyz and 1 on the sphere; normal bits xyz
uniform uint target_width;
uniform uvec4 origin;      // lattice: (x, -, y, -); continuous: Q32.32 (x low, x high, y low, y high)
uniform uvec4 column_step; // continuous: pixel (i, j) -> (i + 1, j), Q32.32 x then y
uniform uvec4 row_step;    // continuous: pixel (i, j) -> (i, j + 1)
layout(location = 0) out vec4 color;

uint dsn_word(uint index) {
    uint word = dsn_word_base + index; // a mix reads each material's words in turn
    return texelFetch(noise_words, ivec2(int(word & 1023u), int(word >> 10u)), 0).x;
}

uvec4 gbuffer_texel(uint texel) { return texelFetch(gbuffer, ivec2(int(texel & 1023u), int(texel >> 10u)), 0); }

void main() {
    uvec2 pixel = uvec2(gl_FragCoord.xy); // row 0 is the image's top row: glReadPixels returns it first
    ivec3 value = ivec3(0);
    if (sphere_mode != 0u) {
        uint texel = 2u * (pixel.y * target_width + pixel.x);
        uvec4 position = gbuffer_texel(texel), normal = gbuffer_texel(texel + 1u);
        ivec3 t, b, n;
        if (position.w != 0u && dsn_surface_frame_from_float_bits(normal.xyz, uvec3(0u), false, t, b, n))
            value = dsn_surface_point_fixed(dsn_coordinate_from_float_bits(position.x),
                                            dsn_coordinate_from_float_bits(position.y),
                                            dsn_coordinate_from_float_bits(position.z), t, b, n);
    } else if (continuous_mode == 0u) {
        ivec2 p = ivec2(int(origin.x + pixel.x), int(origin.z + pixel.y));
        value = mix_mode != 0u ? dsn_mix_lattice_point_fixed(p) : dsn_lattice_point_fixed(p);
    } else {
        uvec2 x = dsn_add64(origin.xy, dsn_add64(dsn_multiply64(uvec2(pixel.x, 0u), column_step.xy),
                                                 dsn_multiply64(uvec2(pixel.y, 0u), row_step.xy)));
        uvec2 y = dsn_add64(origin.zw, dsn_add64(dsn_multiply64(uvec2(pixel.x, 0u), column_step.zw),
                                                 dsn_multiply64(uvec2(pixel.y, 0u), row_step.zw)));
        value = mix_mode != 0u ? dsn_mix_continuous_point_fixed(x, y) : dsn_continuous_point_fixed(x, y);
    }
    color = vec4(mix_mode != 0u ? dsn_mix_color(value) : dsn_color(value), 1.0);
}
)glsl";

std::string vertex_shader(const headless_gl::Context &context) {
    return context.shader_preamble() +
           "void main() {\n"
           "    gl_Position = vec4(float((gl_VertexID & 1) << 2) - 1.0,\n"
           "                       float((gl_VertexID & 2) << 1) - 1.0, 0.0, 1.0);\n"
           "}\n";
}

std::string fragment_shader(const headless_gl::Context &context) {
    return context.shader_preamble() + dsn_glsl + fragment_main;
}

void write_file(const std::string &path, const std::string &text) {
    FILE *file = std::fopen(path.c_str(), "wb");
    if (!file || std::fwrite(text.data(), 1, text.size(), file) != text.size() || std::fclose(file) != 0)
        throw std::runtime_error("cannot write " + path);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// What the window shows: a noise, or a mix (with its control) where `mix` is set.
struct Source {
    const dsn_noise *noise;
    const dsn_mix *mix;
    const dsn_mix_control *control;
    uint32_t channels;
};

// The words the shader reads.
std::vector<uint32_t> packed_words(const Source &source) {
    std::vector<uint32_t> words(source.mix ? dsn_gpu_mix_word_count(source.mix, source.control)
                                           : dsn_gpu_word_count(source.noise));
    const int err = source.mix ? dsn_gpu_mix_pack(source.mix, source.control, words.data(), words.size())
                               : dsn_gpu_pack(source.noise, words.data(), words.size());
    if (err != DSN_OK)
        throw std::runtime_error(std::string("packing for the GPU: ") + dsn_error_message(err));
    return words;
}

// The sphere's G-buffer: per pixel, the float bits of its point's position (texels) and 1 where the pixel's
// centre is on the sphere, then those of its normal. The sphere fills the window (radius 0.45 of its
// smaller side), seen along -z; a pixel is 1/scale texel.
std::vector<uint32_t> sphere_gbuffer(const Options &options) {
    std::vector<uint32_t> words(static_cast<size_t>(options.width) * options.height * 8, 0u);
    const double centre_x = options.width / 2.0, centre_y = options.height / 2.0;
    const double radius = 0.45 * std::min(options.width, options.height);
    for (uint32_t j = 0; j < options.height; j++)
        for (uint32_t i = 0; i < options.width; i++) {
            const double x = i + 0.5 - centre_x, y = centre_y - (j + 0.5), across = x * x + y * y;
            if (across >= radius * radius) continue;
            const double point[3] = {x, y, std::sqrt(radius * radius - across)};
            uint32_t *at = &words[(static_cast<size_t>(j) * options.width + i) * 8];
            for (int k = 0; k < 3; k++) {
                const float position = static_cast<float>(point[k] / options.scale),
                            normal = static_cast<float>(point[k] / radius);
                std::memcpy(&at[k], &position, 4);
                std::memcpy(&at[4 + k], &normal, 4);
            }
            at[3] = 1;
        }
    return words;
}

// Renders the window on the GPU; returns the pixels (channels per pixel) and the seconds of the draw.
std::vector<uint8_t> render_gpu(headless_gl::Context &context, const Options &options, const Source &source,
                                double *seconds) {
    const headless_gl::Functions &gl = context.gl;
    const uint32_t channels = source.channels;
    const std::vector<uint32_t> words = packed_words(source);

    GLuint program = context.render_program(vertex_shader(context), fragment_shader(context));
    gl.glUseProgram(program);
    GLuint texture = context.word_texture(words, 1), target = 0, framebuffer = 0, vertex_array = 0;
    gl.glActiveTexture(GL_TEXTURE0);
    gl.glBindTexture(GL_TEXTURE_2D, texture);
    gl.glUniform1i(gl.glGetUniformLocation(program, "noise_words"), 0);
    uint32_t origin[4] = {0, 0, 0, 0}, column[4] = {0, 0, 0, 0}, row[4] = {0, 0, 0, 0};
    if (options.mode == Mode::continuous) {
        const dsn_grid grid =
            dsn::rotated_grid(options.origin_x, options.origin_y, options.scale, options.rotate_degrees);
        const int64_t values[12] = {grid.origin_x,
                                    grid.origin_y,
                                    grid.column_step_x,
                                    grid.column_step_y,
                                    grid.row_step_x,
                                    grid.row_step_y,
                                    0,
                                    0,
                                    0,
                                    0,
                                    0,
                                    0};
        uint32_t *pairs[3] = {origin, column, row};
        for (int v = 0; v < 6; v++) {
            const uint64_t bits = static_cast<uint64_t>(values[v]);
            pairs[v / 2][2 * (v % 2)] = static_cast<uint32_t>(bits);
            pairs[v / 2][2 * (v % 2) + 1] = static_cast<uint32_t>(bits >> 32);
        }
    } else {
        origin[0] = static_cast<uint32_t>(dsn::lattice_origin(options.origin_x));
        origin[2] = static_cast<uint32_t>(dsn::lattice_origin(options.origin_y));
    }
    gl.glUniform1ui(gl.glGetUniformLocation(program, "continuous_mode"), options.mode == Mode::continuous);
    gl.glUniform1ui(gl.glGetUniformLocation(program, "mix_mode"), source.mix != nullptr);
    gl.glUniform1ui(gl.glGetUniformLocation(program, "sphere_mode"), options.mode == Mode::sphere);
    gl.glUniform1ui(gl.glGetUniformLocation(program, "target_width"), options.width);
    GLuint gbuffer = 0;
    if (options.mode == Mode::sphere) {
        gl.glActiveTexture(GL_TEXTURE1);
        gbuffer = context.word_texture(sphere_gbuffer(options), 4);
        gl.glActiveTexture(GL_TEXTURE0);
    }
    gl.glUniform1i(gl.glGetUniformLocation(program, "gbuffer"), 1);
    gl.glUniform4ui(gl.glGetUniformLocation(program, "origin"), origin[0], origin[1], origin[2], origin[3]);
    gl.glUniform4ui(gl.glGetUniformLocation(program, "column_step"), column[0], column[1], column[2],
                    column[3]);
    gl.glUniform4ui(gl.glGetUniformLocation(program, "row_step"), row[0], row[1], row[2], row[3]);

    gl.glGenTextures(1, &target);
    gl.glBindTexture(GL_TEXTURE_2D, target);
    gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, static_cast<GLsizei>(options.width),
                    static_cast<GLsizei>(options.height), 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    gl.glBindTexture(GL_TEXTURE_2D, texture);
    gl.glGenFramebuffers(1, &framebuffer);
    gl.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target, 0);
    if (gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the RGBA8 render target is incomplete");
    gl.glGenVertexArrays(1, &vertex_array);
    gl.glBindVertexArray(vertex_array);

    // A one-pixel draw first, so that the timing leaves out the shader's compilation.
    gl.glViewport(0, 0, 1, 1);
    gl.glDrawArrays(GL_TRIANGLES, 0, 3);
    gl.glFinish();
    const auto start = std::chrono::steady_clock::now();
    gl.glViewport(0, 0, static_cast<GLsizei>(options.width), static_cast<GLsizei>(options.height));
    gl.glDrawArrays(GL_TRIANGLES, 0, 3);
    gl.glFinish();
    *seconds = seconds_since(start);

    std::vector<uint8_t> rgba(static_cast<size_t>(options.width) * options.height * 4);
    gl.glPixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.glReadPixels(0, 0, static_cast<GLsizei>(options.width), static_cast<GLsizei>(options.height), GL_RGBA,
                    GL_UNSIGNED_BYTE, rgba.data());
    context.check("render");
    gl.glDeleteVertexArrays(1, &vertex_array);
    gl.glDeleteFramebuffers(1, &framebuffer);
    gl.glDeleteTextures(1, &target);
    gl.glDeleteTextures(1, &texture);
    if (gbuffer) gl.glDeleteTextures(1, &gbuffer);
    gl.glDeleteProgram(program);

    std::vector<uint8_t> pixels(static_cast<size_t>(options.width) * options.height * channels);
    for (size_t p = 0; p < static_cast<size_t>(options.width) * options.height; p++)
        for (uint32_t c = 0; c < channels; c++) pixels[p * channels + c] = rgba[p * 4 + c];
    return pixels;
}

// The sphere with the C runtime, point by point from the same G-buffer.
int render_sphere_cpu(const Options &options, const dsn_noise *noise, uint8_t *pixels) {
    const std::vector<uint32_t> words = sphere_gbuffer(options);
    const uint32_t channels = dsn_noise_channels(noise);
    for (size_t p = 0; p < static_cast<size_t>(options.width) * options.height; p++) {
        const uint32_t *at = &words[p * 8];
        if (at[3] == 0) continue;
        float position[3], normal[3];
        std::memcpy(position, at, sizeof position);
        std::memcpy(normal, at + 4, sizeof normal);
        dsn_surface_frame frame;
        int err = dsn_surface_frame_from_float(normal, nullptr, &frame);
        const int64_t point[3] = {dsn_coordinate_from_float(position[0]),
                                  dsn_coordinate_from_float(position[1]),
                                  dsn_coordinate_from_float(position[2])};
        if (err == DSN_OK) err = dsn_surface_point_u8(noise, point, &frame, pixels + p * channels);
        if (err != DSN_OK) return err;
    }
    return DSN_OK;
}

// The same window with the C runtime's tiles (one thread), for --compare-cpu.
std::vector<uint8_t> render_cpu(const Options &options, const Source &source, double *seconds) {
    std::vector<uint8_t> pixels(static_cast<size_t>(options.width) * options.height * source.channels);
    std::vector<unsigned char> scratch;
    const auto start = std::chrono::steady_clock::now();
    const uint32_t width = options.width, height = options.height;
    int err;
    if (options.mode == Mode::sphere) {
        err = render_sphere_cpu(options, source.noise, pixels.data());
    } else if (options.mode == Mode::continuous) {
        const dsn_grid grid =
            dsn::rotated_grid(options.origin_x, options.origin_y, options.scale, options.rotate_degrees);
        scratch.resize(source.mix ? dsn_mix_continuous_tile_scratch_size(source.mix, &grid, width, height)
                                  : dsn_continuous_tile_scratch_size(source.noise, &grid, width, height));
        err = source.mix ? dsn_mix_continuous_tile_u8(source.mix, source.control, &grid, width, height,
                                                      pixels.data(), scratch.data(), scratch.size())
                         : dsn_continuous_tile_u8(source.noise, &grid, width, height, pixels.data(),
                                                  scratch.data(), scratch.size());
    } else {
        const int32_t x0 = dsn::lattice_origin(options.origin_x), y0 = dsn::lattice_origin(options.origin_y);
        scratch.resize(source.mix ? dsn_mix_lattice_tile_scratch_size(source.mix, width, height)
                                  : dsn_lattice_tile_scratch_size(source.noise, width, height));
        err = source.mix ? dsn_mix_lattice_tile_u8(source.mix, source.control, x0, y0, width, height,
                                                   pixels.data(), scratch.data(), scratch.size())
                         : dsn_lattice_tile_u8(source.noise, x0, y0, width, height, pixels.data(),
                                               scratch.data(), scratch.size());
    }
    *seconds = seconds_since(start);
    if (err != DSN_OK) throw std::runtime_error(std::string("CPU tile: ") + dsn_error_message(err));
    return pixels;
}

void run(const Options &options) {
    if (!options.dump_directory.empty()) {
        for (headless_gl::Api api : {headless_gl::Api::gles30, headless_gl::Api::gl45}) {
            headless_gl::Context context(api);
            const std::string name = options.dump_directory + "/gpu-render-" + headless_gl::api_name(api);
            write_file(name + ".frag", fragment_shader(context));
            write_file(name + ".vert", vertex_shader(context));
        }
        return;
    }
    dsn_asset asset;
    const std::vector<unsigned char> bytes = dsn::load_asset_file(options.asset_path, asset);
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = options.seed;
    dsn_noise noise;
    int err = dsn_noise_init(&noise, &asset, &config);
    if (err == DSN_OK && options.mode != Mode::tile) err = dsn_continuous_check(&noise);
    if (err != DSN_OK) throw std::runtime_error(options.asset_path + ": " + dsn_error_message(err));
    Source source = {&noise, nullptr, nullptr, asset.channels};
    dsn::MixInputs mix_inputs;
    if (!options.mix.paths.empty()) {
        dsn::configure_mix(
            options.mix, noise, config, options.mode == Mode::continuous,
            [](const std::string &, const dsn_asset &) {}, mix_inputs);
        source = {&noise, &mix_inputs.mix, &mix_inputs.control, dsn_mix_channels(&mix_inputs.mix)};
    }

    headless_gl::Context context(options.api);
    double gpu_seconds = 0;
    const std::vector<uint8_t> pixels = render_gpu(context, options, source, &gpu_seconds);
    const double megapixels = options.width * static_cast<double>(options.height) / 1e6;
    if (options.compare_cpu) {
        double cpu_seconds = 0;
        const std::vector<uint8_t> cpu = render_cpu(options, source, &cpu_seconds);
        if (cpu != pixels) throw std::runtime_error("the GPU's pixels differ from the C runtime's");
        std::printf("dsn-gpu-render: identical to the C runtime; CPU %s (1 thread): %.3f s, %.2f Mpixel/s\n",
                    options.mode == Mode::sphere ? "points" : "tile", cpu_seconds, megapixels / cpu_seconds);
    }
    const std::vector<unsigned char> png =
        dsn::encode_png(static_cast<int>(options.width), static_cast<int>(options.height),
                        static_cast<int>(source.channels), pixels.data());
    dsn::write_file_atomically(options.output_path, png);
    if (!options.quiet)
        std::printf("dsn-gpu-render: %ux%u on %s: %.3f s, %.2f Mpixel/s -> %s\n", options.width,
                    options.height, context.description().c_str(), gpu_seconds, megapixels / gpu_seconds,
                    options.output_path.c_str());
}

} // namespace

int main(int argc, char **argv) {
    const std::string usage = std::string(usage_head) + dsn::mix_usage + usage_tail;
    return dsn::run_tool("dsn-gpu-render", usage.c_str(), argc, argv, [](dsn::CommandLine &arguments) {
        run(parse_options(arguments));
        return 0;
    });
}
