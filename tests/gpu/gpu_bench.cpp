// gpu_bench.cpp - dsn-gpu-bench: the throughput of include/dsn/dsn.glsl on whatever OpenGL the machine has
// (EGL surfaceless: llvmpipe when there is no GPU), against an anchor timed in the same run: Texton Noise
// (tests/gpu/texton_noise.glsl, the published GPU algorithm) on the same asset and density. Each variant
// is a compute shader (GL 4.5, one invocation per pixel, 16 x 16 workgroups, results in a storage
// buffer) and a fragment shader (GLSL ES 3.00 by default, one fragment per pixel, into an RGBA8 target),
// and its Mpixel/s is compared with the anchor's of the same kind. The dsn variants: the lattice per
// point, the continuous per point on axis-aligned grids of 0.59 and 1.7 texels per pixel, and the tiled
// compute variants (dsn.glsl's workgroup tiles: a workgroup lists the impulses of its window once).
//
// Every variant runs once per round, the rounds one after another, and reports its best round (the
// machine may be shared). It checks what it times: the compute dsn images against the C runtime (every
// 163rd pixel), the tiled ones against the per-point ones (every pixel), the fragment ones against the C
// runtime to one 8-bit step, and the anchor against the CPU Texton Noise of
// tests/bench/texton_noise_baseline.h (to a tolerance: it is float, filtered by the GPU). It exits
// non-zero when a check fails.
//
//   dsn-gpu-bench [--fragment-api gles30|gl45] [--runs N] [--no-tiled] [--dump-shaders DIR]
#include <EGL/egl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/texton_noise_baseline.h"
#include "dsn/gpu.h"
#include "fixtures/continuous_fixtures.h"
#include "headless_gl.h"

namespace {

using headless_gl::Api;

const char *const dsn_glsl =
#include "include/dsn/dsn.glsl.inc"
    ;
const char *const texton_noise_glsl =
#include "tests/gpu/texton_noise.glsl.inc"
    ;

// The workload: renderer_bench's asset and density (RGB 31 x 31 8-bit bilinear texton, 30 impacts per
// pixel). Sizes keep a whole run on llvmpipe with two cores under a minute (about 35 s with the tiled
// variants, 3 runs); every side is a multiple of the 16 x 16 workgroup, so no invocation falls outside
// the image (the tiled shaders' barriers need every invocation).
const double impacts_per_pixel = 30;
const uint32_t noise_seed = 1, anchor_seed_offset = 1;
const uint32_t dsn_side = 512, anchor_side = 1024;
const uint32_t workgroup_side = 16;
const double grid_origin_x = 1000.0 + 1.0 / 3, grid_origin_y = 2000.0 + 1.0 / 7; // texels
const int64_t q32_one = int64_t(1) << 32;
const uint32_t check_stride = 163; // prime: the checked pixels fall at every place of a workgroup

// GL entry points headless_gl does not load.
#define GPU_BENCH_FUNCTIONS(FUNCTION)                                                                        \
    FUNCTION(glUniform1f)                                                                                    \
    FUNCTION(glUniform2f)                                                                                    \
    FUNCTION(glUniform3fv)                                                                                   \
    FUNCTION(glUniformMatrix3fv)
struct MoreFunctions {
#define GPU_BENCH_DECLARE(name) decltype(&::name) name = nullptr;
    GPU_BENCH_FUNCTIONS(GPU_BENCH_DECLARE)
#undef GPU_BENCH_DECLARE
    MoreFunctions() {
#define GPU_BENCH_LOAD(name)                                                                                 \
    name = reinterpret_cast<decltype(name)>(eglGetProcAddress(#name));                                       \
    if (!name) throw std::runtime_error("GL: no " #name);
        GPU_BENCH_FUNCTIONS(GPU_BENCH_LOAD)
#undef GPU_BENCH_LOAD
    }
};

enum class Evaluation { anchor, lattice, continuous, lattice_tiled, continuous_tiled };

bool is_tiled(Evaluation evaluation) {
    return evaluation == Evaluation::lattice_tiled || evaluation == Evaluation::continuous_tiled;
}

bool is_lattice(Evaluation evaluation) {
    return evaluation == Evaluation::lattice || evaluation == Evaluation::lattice_tiled;
}

// ---- The shaders ----

// Uniforms of the dsn shaders, and the point of a pixel: lattice (x, -, y, -) from grid_origin, or the
// continuous grid's origin + i column_step + j row_step, each (x low, x high, y low, y high) Q32.32.
const char *const dsn_grid_glsl =
    "uniform uvec4 grid_origin;\n"
    "uniform uvec4 grid_column_step;\n"
    "uniform uvec4 grid_row_step;\n"
    "ivec2 bench_lattice_point(uvec2 pixel) {\n"
    "    return ivec2(int(grid_origin.x + pixel.x), int(grid_origin.z + pixel.y));\n"
    "}\n"
    "void bench_grid_point(uvec2 pixel, out uvec2 x, out uvec2 y) {\n"
    "    x = dsn_add64(grid_origin.xy, dsn_add64(dsn_multiply64(uvec2(pixel.x, 0u), grid_column_step.xy),\n"
    "                                            dsn_multiply64(uvec2(pixel.y, 0u), grid_row_step.xy)));\n"
    "    y = dsn_add64(grid_origin.zw, dsn_add64(dsn_multiply64(uvec2(pixel.x, 0u), grid_column_step.zw),\n"
    "                                            dsn_multiply64(uvec2(pixel.y, 0u), grid_row_step.zw)));\n"
    "}\n";

const char *const anchor_grid_glsl = "uniform vec2 grid_origin;\n"
                                     "uniform float grid_step;\n";

// The value of a pixel in the per-point shaders (compute and fragment alike).
const char *dsn_point_value_glsl(bool lattice) {
    return lattice ? "    ivec3 value = dsn_lattice_point_fixed(bench_lattice_point(pixel));\n"
                   : "    uvec2 x, y;\n"
                     "    bench_grid_point(pixel, x, y);\n"
                     "    ivec3 value = dsn_continuous_point_fixed(x, y);\n";
}

std::string compute_shader(const headless_gl::Context &context, Evaluation evaluation) {
    std::string source = context.shader_preamble();
    if (is_tiled(evaluation)) source += "#define DSN_GLSL_TILES 1\n";
    source += "layout(local_size_x = 16, local_size_y = 16) in;\n"
              "uniform uint image_width;\n";
    if (evaluation == Evaluation::anchor)
        return source + "layout(std430, binding = 1) writeonly buffer Pixels { vec4 pixels[]; };\n" +
               anchor_grid_glsl + texton_noise_glsl +
               "void main() {\n"
               "    uvec2 pixel = gl_GlobalInvocationID.xy;\n"
               "    vec3 value = texton_noise_evaluate(grid_origin + vec2(pixel) * grid_step);\n"
               "    pixels[pixel.y * image_width + pixel.x] = vec4(value, 1.0);\n"
               "}\n";
    source += "layout(std430, binding = 0) readonly buffer NoiseWords { uint noise_words[]; };\n"
              "layout(std430, binding = 1) writeonly buffer Pixels { uvec4 pixels[]; };\n"
              "uint dsn_word(uint index) { return noise_words[index]; }\n";
    source += dsn_glsl;
    source += dsn_grid_glsl;
    source += "void main() {\n"
              "    uvec2 pixel = gl_GlobalInvocationID.xy;\n";
    switch (evaluation) {
    case Evaluation::lattice:
    case Evaluation::continuous:
        source += dsn_point_value_glsl(is_lattice(evaluation));
        break;
    // The tiled variants (dsn.glsl's workgroup tiles).
    case Evaluation::lattice_tiled:
        // The workgroup's window of lattice points; barrier() is the caller's, between the phases.
        source += "    ivec2 window = bench_lattice_point(gl_WorkGroupID.xy * 16u);\n"
                  "    uvec2 window_size = uvec2(16u);\n"
                  "    dsn_tile_begin();\n"
                  "    barrier();\n"
                  "    dsn_lattice_tile_list(window, window_size);\n"
                  "    barrier();\n"
                  "    ivec3 value = dsn_lattice_tile_point_fixed(window, window_size, "
                  "bench_lattice_point(pixel));\n";
        break;
    case Evaluation::continuous_tiled:
        source +=
            "    uvec2 low_x, low_y, extent;\n"
            "    dsn_grid_tile_box(grid_origin, grid_column_step, grid_row_step, gl_WorkGroupID.xy * 16u,\n"
            "                      uvec2(16u), low_x, low_y, extent);\n"
            "    dsn_tile_begin();\n"
            "    barrier();\n"
            "    dsn_continuous_tile_list(low_x, low_y, extent);\n"
            "    barrier();\n"
            "    uvec2 x, y;\n"
            "    bench_grid_point(pixel, x, y);\n"
            "    ivec3 value = dsn_continuous_tile_point_fixed(low_x, low_y, extent, x, y);\n";
        break;
    case Evaluation::anchor:
        break;
    }
    return source + "    pixels[pixel.y * image_width + pixel.x] = uvec4(uvec3(value), 0u);\n"
                    "}\n";
}

std::string vertex_shader(Api api) {
    return std::string(api == Api::gl45 ? "#version 430 core\n" : "#version 300 es\n") +
           "void main() {\n"
           "    gl_Position = vec4(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0, "
           "0.0, 1.0);\n"
           "}\n";
}

// One fragment per pixel (gl_FragCoord is the pixel's centre), its colour into an RGBA8 target; the dsn
// variants read the packed words from an R32UI texture, 1024 words a row.
std::string fragment_shader(const headless_gl::Context &context, Evaluation evaluation) {
    std::string source = context.shader_preamble() + "layout(location = 0) out vec4 colour;\n";
    if (evaluation == Evaluation::anchor)
        return source + anchor_grid_glsl + texton_noise_glsl +
               "void main() {\n"
               "    vec2 pixel = floor(gl_FragCoord.xy);\n"
               "    colour = vec4(texton_noise_evaluate(grid_origin + pixel * grid_step), 1.0);\n"
               "}\n";
    source += "uniform highp usampler2D noise_texture;\n"
              "uint dsn_word(uint index) {\n"
              "    return texelFetch(noise_texture, ivec2(int(index & 1023u), int(index >> 10u)), 0).x;\n"
              "}\n";
    source += dsn_glsl;
    source += dsn_grid_glsl;
    return source + "void main() {\n    uvec2 pixel = uvec2(gl_FragCoord.xy);\n" +
           dsn_point_value_glsl(is_lattice(evaluation)) +
           "    colour = vec4(vec3(value) / 65536.0, 1.0);\n"
           "}\n";
}

// ---- The workload ----

// The anchor's texture and uniforms, computed as texton_noise::Baseline computes them (its float
// rounding included) from the same asset and density.
struct Anchor {
    uint32_t padded_side = 0;
    std::vector<float> texels; // RGBA, padded_side^2, zero border
    float side = 0, cell_side = 0, cells_per_texel = 0, cell_mean = 0, cell_deviation = 0;
    float expected[3] = {0, 0, 0}, mean[3] = {0, 0, 0}, transform[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};

    explicit Anchor(const dsn_asset &asset) : padded_side(asset.width + 2), side(float(asset.width)) {
        texels.assign(size_t(padded_side) * padded_side * 4, 0.0f);
        float sums[3] = {0, 0, 0};
        for (uint32_t row = 0; row < asset.height; row++)
            for (uint32_t column = 0; column < asset.width; column++)
                for (uint32_t c = 0; c < asset.channels; c++) {
                    const float value = float(dsn_asset_texton_value(&asset, row, column, c)) *
                                        float(double(asset.scale[c]) / 1099511627776.0); // 2^40
                    texels[(size_t(row + 1) * padded_side + column + 1) * 4 + c] = value;
                    sums[c] += value;
                }
        const double lambda = impacts_per_pixel / double(asset.support_size);
        cell_side = float(double(asset.width) / 1.6);
        cells_per_texel = 1.0f / cell_side;
        cell_mean = float(lambda * double(cell_side) * double(cell_side));
        cell_deviation = std::sqrt(cell_mean);
        const float inverse_root = float(1.0 / std::sqrt(lambda));
        for (uint32_t c = 0; c < asset.channels; c++) {
            expected[c] = float(lambda) * sums[c];
            mean[c] = float(double(asset.mean[c]) / DSN_Q24_ONE);
            for (uint32_t k = 0; k < 3; k++)
                transform[c * 3 + k] =
                    asset.channels == 3
                        ? float(double(asset.color_transform[c * 3 + k]) / DSN_Q24_ONE) * inverse_root
                        : (k == 0 ? inverse_root : 0.0f);
        }
    }
};

// One timed image: what is evaluated, over which grid.
struct Variant {
    Evaluation evaluation;
    double texels_per_pixel; // the grid's step; 1 for the lattice
    uint32_t side;
    std::string name;
};

std::vector<Variant> variants_of_kind(bool compute) {
    std::vector<Variant> variants = {
        {Evaluation::anchor, 1.0, anchor_side, "Texton Noise anchor, 1 texel/pixel"},
        {Evaluation::anchor, 0.59, anchor_side, "Texton Noise anchor, 0.59 texel/pixel"},
        {Evaluation::anchor, 1.7, anchor_side, "Texton Noise anchor, 1.7 texel/pixel"},
        {Evaluation::lattice, 1.0, dsn_side, "dsn lattice per point"},
        {Evaluation::continuous, 0.59, dsn_side, "dsn continuous per point, 0.59 texel/pixel"},
        {Evaluation::continuous, 1.7, dsn_side, "dsn continuous per point, 1.7 texel/pixel"}};
    if (compute) {
        variants.push_back({Evaluation::lattice_tiled, 1.0, dsn_side, "dsn lattice tiled"});
        variants.push_back(
            {Evaluation::continuous_tiled, 0.59, dsn_side, "dsn continuous tiled, 0.59 texel/pixel"});
        variants.push_back(
            {Evaluation::continuous_tiled, 1.7, dsn_side, "dsn continuous tiled, 1.7 texel/pixel"});
    }
    return variants;
}

// The grid of a variant in the C runtime's terms (Q32.32), and its point at pixel (i, j).
struct Grid {
    int64_t origin_x, origin_y, step;
    int32_t lattice_x, lattice_y;

    explicit Grid(double texels_per_pixel)
        : origin_x(int64_t(std::llround(grid_origin_x * double(q32_one)))),
          origin_y(int64_t(std::llround(grid_origin_y * double(q32_one)))),
          step(int64_t(std::llround(texels_per_pixel * double(q32_one)))), lattice_x(int32_t(grid_origin_x)),
          lattice_y(int32_t(grid_origin_y)) {}

    // Modulo 2^64, as the shader adds.
    int64_t x(uint32_t i) const { return int64_t(uint64_t(origin_x) + uint64_t(i) * uint64_t(step)); }
    int64_t y(uint32_t j) const { return int64_t(uint64_t(origin_y) + uint64_t(j) * uint64_t(step)); }
};

// ---- The checks ----

struct Checks {
    int failures = 0;
    void report(bool passed, const std::string &what) {
        std::printf("  check: %s: %s\n", what.c_str(), passed ? "ok" : "FAILED");
        if (!passed) failures++;
    }
};

// The C runtime's value at pixel (i, j) of a dsn variant.
void runtime_value(const dsn_noise *noise, const Variant &variant, uint32_t i, uint32_t j, int32_t *out) {
    const Grid grid(variant.texels_per_pixel);
    if (is_lattice(variant.evaluation))
        dsn_lattice_point_fixed(noise, grid.lattice_x + int32_t(i), grid.lattice_y + int32_t(j), out);
    else
        dsn_continuous_point_fixed(noise, grid.x(i), grid.y(j), out);
}

// The 8-bit value a unorm target stores for `value` (GL allows either neighbour of the exact product).
bool unorm8_matches(float value, uint8_t stored) {
    const float exact = std::min(1.0f, std::max(0.0f, value)) * 255.0f;
    return std::fabs(exact - float(stored)) <= 1.0f;
}

// ---- The runs ----

struct Workload {
    const dsn_noise *noise;
    std::vector<uint32_t> words;
    Anchor anchor;
    texton_noise::Baseline baseline;
    bool tiled;
    int runs;
};

// A variant ready to run: its program and where it writes, its timings, then its image (the compute
// ones 4 words a pixel, uvec4 or vec4; the fragment ones one RGBA8 word a pixel).
struct Prepared {
    Variant variant;
    GLuint program = 0, pixel_buffer = 0, framebuffer = 0, target = 0;
    std::vector<double> seconds;
    std::vector<uint32_t> image;

    double best() const { return *std::min_element(seconds.begin(), seconds.end()); }
    double median() const {
        std::vector<double> sorted = seconds;
        std::sort(sorted.begin(), sorted.end());
        return sorted[sorted.size() / 2];
    }
    double mpixels_per_second(double seconds_per_image) const {
        return double(variant.side) * variant.side / seconds_per_image * 1e-6;
    }
};

// Runs every variant of one kind (compute or fragment) on one context. The machine may be shared, and
// its load changes over seconds: so every variant runs once per round, the rounds one after another
// (the order rotating), and each reports its best round; a slow phase then falls on all alike.
class Bench {
  public:
    Bench(headless_gl::Context &context, const Workload &workload, bool compute)
        : context_(context), gl_(context.gl), workload_(workload), compute_(compute) {
        texton_ = anchor_texture();
        if (compute_) {
            noise_buffer_ = context_.storage_buffer(workload_.words.data(), workload_.words.size() * 4);
        } else {
            noise_texture_ = context_.word_texture(workload_.words, 1);
            gl_.glGenVertexArrays(1, &vertex_array_);
        }
    }
    ~Bench() {
        for (Prepared &prepared : prepared_) {
            gl_.glDeleteProgram(prepared.program);
            if (prepared.pixel_buffer) gl_.glDeleteBuffers(1, &prepared.pixel_buffer);
            if (prepared.framebuffer) gl_.glDeleteFramebuffers(1, &prepared.framebuffer);
            if (prepared.target) gl_.glDeleteTextures(1, &prepared.target);
        }
        gl_.glDeleteTextures(1, &texton_);
        if (noise_buffer_) gl_.glDeleteBuffers(1, &noise_buffer_);
        if (noise_texture_) gl_.glDeleteTextures(1, &noise_texture_);
        if (vertex_array_) gl_.glDeleteVertexArrays(1, &vertex_array_);
    }

    // Every variant of the kind: builds, warms up and times them, then prints and checks each.
    void run_all(Checks &checks) {
        const char *kind = compute_ ? "compute" : "fragment";
        std::vector<std::string> unavailable;
        for (const Variant &variant : variants_of_kind(compute_)) {
            if (is_tiled(variant.evaluation) && !workload_.tiled)
                unavailable.push_back(variant.name);
            else
                prepared_.push_back(compute_ ? prepare_compute(variant) : prepare_fragment(variant));
        }
        // The warm-up: llvmpipe builds a fragment shader's code at its first draw.
        for (Prepared &prepared : prepared_) run(prepared);
        for (int round = 0; round < workload_.runs; round++)
            for (size_t k = 0; k < prepared_.size(); k++) {
                Prepared &prepared = prepared_[(k + size_t(round)) % prepared_.size()];
                prepared.seconds.push_back(run(prepared));
            }
        for (Prepared &prepared : prepared_) read_image(prepared);

        for (const Prepared &prepared : prepared_) {
            const Variant &variant = prepared.variant;
            // The anchor of the same kind at the same texels per pixel (the lattice's is 1).
            double anchor_seconds_per_pixel = 0;
            for (const Prepared &anchor : prepared_)
                if (anchor.variant.evaluation == Evaluation::anchor &&
                    anchor.variant.texels_per_pixel == variant.texels_per_pixel)
                    anchor_seconds_per_pixel =
                        anchor.best() / (double(anchor.variant.side) * anchor.variant.side);
            const double rate = prepared.mpixels_per_second(prepared.best());
            const std::string label = std::string(kind) + "  " + variant.name;
            std::printf("%-56s %4ux%-4u %8.3f Mpixel/s (median %7.3f)  %6.3fx the anchor\n", label.c_str(),
                        variant.side, variant.side, rate, prepared.mpixels_per_second(prepared.median()),
                        rate * anchor_seconds_per_pixel * 1e6);
            check(prepared, checks);
        }
        for (const std::string &name : unavailable)
            std::printf("%-56s not run (--no-tiled)\n", (std::string(kind) + "  " + name).c_str());
        std::fflush(stdout);
    }

  private:
    GLint location(GLuint program, const char *name) const { return gl_.glGetUniformLocation(program, name); }

    // OpenGL ES 3.0 filters 32-bit float textures only with OES_texture_float_linear; 16-bit ones always.
    bool float_filtering() const {
        if (context_.api() == Api::gl45) return true;
        const GLubyte *extensions = gl_.glGetString(GL_EXTENSIONS);
        return extensions &&
               strstr(reinterpret_cast<const char *>(extensions), "GL_OES_texture_float_linear") != nullptr;
    }

    GLuint anchor_texture() const {
        if (!float_filtering())
            std::printf("note: no GL_OES_texture_float_linear: the anchor's texton is RGBA16F here\n");
        GLuint texture = 0;
        gl_.glGenTextures(1, &texture);
        gl_.glBindTexture(GL_TEXTURE_2D, texture);
        gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        gl_.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        const GLsizei side = GLsizei(workload_.anchor.padded_side);
        gl_.glTexImage2D(GL_TEXTURE_2D, 0, float_filtering() ? GL_RGBA32F : GL_RGBA16F, side, side, 0,
                         GL_RGBA, GL_FLOAT, workload_.anchor.texels.data());
        context_.check("the anchor's texture");
        return texture;
    }

    // Uniforms stay with their program: set once, before the runs.
    void set_uniforms(GLuint program, const Variant &variant) const {
        gl_.glUseProgram(program);
        if (variant.evaluation == Evaluation::anchor) {
            const Anchor &anchor = workload_.anchor;
            gl_.glUniform1i(location(program, "texton_noise_texton"), 0);
            more_.glUniform1f(location(program, "texton_noise_side"), anchor.side);
            more_.glUniform1f(location(program, "texton_noise_cell_side"), anchor.cell_side);
            more_.glUniform1f(location(program, "texton_noise_cells_per_texel"), anchor.cells_per_texel);
            more_.glUniform1f(location(program, "texton_noise_cell_mean"), anchor.cell_mean);
            more_.glUniform1f(location(program, "texton_noise_cell_deviation"), anchor.cell_deviation);
            gl_.glUniform1ui(location(program, "texton_noise_seed_offset"), anchor_seed_offset);
            more_.glUniform3fv(location(program, "texton_noise_expected"), 1, anchor.expected);
            more_.glUniform3fv(location(program, "texton_noise_mean"), 1, anchor.mean);
            // Row-major in memory: GL transposes it into its column-major mat3.
            more_.glUniformMatrix3fv(location(program, "texton_noise_transform"), 1, GL_TRUE,
                                     anchor.transform);
            more_.glUniform2f(location(program, "grid_origin"), float(grid_origin_x), float(grid_origin_y));
            more_.glUniform1f(location(program, "grid_step"), float(variant.texels_per_pixel));
        } else {
            const Grid grid(variant.texels_per_pixel);
            const auto low = [](int64_t value) { return uint32_t(uint64_t(value)); };
            const auto high = [](int64_t value) { return uint32_t(uint64_t(value) >> 32); };
            if (is_lattice(variant.evaluation))
                gl_.glUniform4ui(location(program, "grid_origin"), uint32_t(grid.lattice_x), 0u,
                                 uint32_t(grid.lattice_y), 0u);
            else
                gl_.glUniform4ui(location(program, "grid_origin"), low(grid.origin_x), high(grid.origin_x),
                                 low(grid.origin_y), high(grid.origin_y));
            // Axis-aligned: a column steps along x only, a row along y only.
            gl_.glUniform4ui(location(program, "grid_column_step"), low(grid.step), high(grid.step), 0u, 0u);
            gl_.glUniform4ui(location(program, "grid_row_step"), 0u, 0u, low(grid.step), high(grid.step));
            if (!compute_) gl_.glUniform1i(location(program, "noise_texture"), 0);
        }
        gl_.glUniform1ui(location(program, "image_width"), variant.side);
        context_.check("uniforms");
    }

    Prepared prepare_compute(const Variant &variant) const {
        Prepared prepared;
        prepared.variant = variant;
        prepared.program = context_.compute_program(compute_shader(context_, variant.evaluation));
        prepared.pixel_buffer = context_.storage_buffer(nullptr, size_t(variant.side) * variant.side * 16);
        set_uniforms(prepared.program, variant);
        return prepared;
    }

    Prepared prepare_fragment(const Variant &variant) const {
        Prepared prepared;
        prepared.variant = variant;
        prepared.program = context_.render_program(vertex_shader(context_.api()),
                                                   fragment_shader(context_, variant.evaluation));
        gl_.glGenTextures(1, &prepared.target);
        gl_.glBindTexture(GL_TEXTURE_2D, prepared.target);
        gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        const GLsizei side = GLsizei(variant.side);
        gl_.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, side, side, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        gl_.glGenFramebuffers(1, &prepared.framebuffer);
        gl_.glBindFramebuffer(GL_FRAMEBUFFER, prepared.framebuffer);
        gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, prepared.target, 0);
        const GLenum attachment = GL_COLOR_ATTACHMENT0;
        gl_.glDrawBuffers(1, &attachment);
        if (gl_.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("the RGBA8 render target is incomplete");
        set_uniforms(prepared.program, variant);
        return prepared;
    }

    // One dispatch or draw of the variant, waited for: its wall-clock seconds (binding not counted).
    double run(const Prepared &prepared) const {
        const Variant &variant = prepared.variant;
        gl_.glUseProgram(prepared.program);
        gl_.glActiveTexture(GL_TEXTURE0);
        const bool anchor = variant.evaluation == Evaluation::anchor;
        if (compute_) {
            if (anchor) gl_.glBindTexture(GL_TEXTURE_2D, texton_);
            gl_.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, noise_buffer_);
            gl_.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, prepared.pixel_buffer);
        } else {
            gl_.glBindTexture(GL_TEXTURE_2D, anchor ? texton_ : noise_texture_);
            gl_.glBindFramebuffer(GL_FRAMEBUFFER, prepared.framebuffer);
            gl_.glViewport(0, 0, GLsizei(variant.side), GLsizei(variant.side));
            gl_.glBindVertexArray(vertex_array_);
        }
        gl_.glFinish();
        const auto start = std::chrono::steady_clock::now();
        if (compute_)
            gl_.glDispatchCompute(variant.side / workgroup_side, variant.side / workgroup_side, 1);
        else
            gl_.glDrawArrays(GL_TRIANGLES, 0, 3);
        gl_.glFinish();
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        context_.check(compute_ ? "dispatch" : "draw");
        return seconds;
    }

    void read_image(Prepared &prepared) const {
        const size_t pixels = size_t(prepared.variant.side) * prepared.variant.side;
        if (compute_) {
            gl_.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
            prepared.image.resize(4 * pixels);
            context_.read_buffer(prepared.pixel_buffer, prepared.image.data(), prepared.image.size() * 4);
            return;
        }
        prepared.image.resize(pixels);
        const GLsizei side = GLsizei(prepared.variant.side);
        gl_.glBindFramebuffer(GL_FRAMEBUFFER, prepared.framebuffer);
        gl_.glPixelStorei(GL_PACK_ALIGNMENT, 4);
        gl_.glReadBuffer(GL_COLOR_ATTACHMENT0);
        gl_.glReadPixels(0, 0, side, side, GL_RGBA, GL_UNSIGNED_BYTE, prepared.image.data());
        context_.check("read the target");
    }

    // The reference colour of pixel (i, j), as float: the C runtime's value for dsn, the CPU Texton Noise
    // for the anchor.
    void reference(const Variant &variant, uint32_t i, uint32_t j, float *colour) const {
        colour[0] = colour[1] = colour[2] = 0;
        if (variant.evaluation == Evaluation::anchor) {
            const float step = float(variant.texels_per_pixel);
            workload_.baseline.evaluate(float(grid_origin_x) + float(i) * step,
                                        float(grid_origin_y) + float(j) * step, colour);
            return;
        }
        int32_t value[3] = {0, 0, 0};
        runtime_value(workload_.noise, variant, i, j, value);
        for (int c = 0; c < 3; c++) colour[c] = float(value[c]) / 65536.0f;
    }

    // The per-point compute variant of the same grid as a tiled one.
    const Prepared *per_point_of(const Variant &tiled) const {
        const Evaluation evaluation =
            is_lattice(tiled.evaluation) ? Evaluation::lattice : Evaluation::continuous;
        for (const Prepared &prepared : prepared_)
            if (prepared.variant.evaluation == evaluation &&
                prepared.variant.texels_per_pixel == tiled.texels_per_pixel)
                return &prepared;
        return nullptr;
    }

    void check(const Prepared &prepared, Checks &checks) const {
        const Variant &variant = prepared.variant;
        const std::vector<uint32_t> &image = prepared.image;
        if (is_tiled(variant.evaluation)) {
            const Prepared *per_point = per_point_of(variant);
            checks.report(per_point && per_point->image == image,
                          variant.name + ": every pixel's bits equal the per-point variant's");
            return;
        }
        const uint32_t channels = dsn_noise_channels(workload_.noise);
        const bool anchor = variant.evaluation == Evaluation::anchor;
        size_t checked = 0, matched = 0;
        double largest_error = 0;
        for (size_t index = 0; index < image.size() / (compute_ ? 4 : 1); index += check_stride, checked++) {
            const uint32_t i = uint32_t(index % variant.side), j = uint32_t(index / variant.side);
            float colour[3];
            reference(variant, i, j, colour);
            bool same = true;
            for (uint32_t c = 0; c < channels; c++) {
                const uint32_t word = image[compute_ ? 4 * index + c : index];
                if (!compute_) {
                    same = same && unorm8_matches(colour[c], uint8_t(word >> (8 * c)));
                } else if (anchor) {
                    float gpu;
                    std::memcpy(&gpu, &word, sizeof gpu);
                    const double error = std::fabs(double(gpu) - double(colour[c]));
                    largest_error = std::max(largest_error, error);
                    same = same && error <= anchor_tolerance;
                } else {
                    int32_t gpu;
                    std::memcpy(&gpu, &word, sizeof gpu);
                    same = same && int32_t(std::lround(double(colour[c]) * 65536.0)) == gpu;
                }
            }
            matched += same ? 1 : 0;
        }
        char what[256];
        if (anchor && compute_)
            std::snprintf(what, sizeof what,
                          "%s: %zu of %zu pixels within %g of the CPU Texton Noise (largest difference %.2g)",
                          variant.name.c_str(), matched, checked, anchor_tolerance, largest_error);
        else
            std::snprintf(what, sizeof what, "%s: %zu of %zu pixels equal %s%s", variant.name.c_str(),
                          matched, checked, anchor ? "the CPU Texton Noise" : "the C runtime's",
                          compute_ ? "" : " to one 8-bit step");
        // The anchor is float: hardware filtering may round its weights, and a count drawn at a rounding
        // edge of log or cos may differ from the CPU's, so most pixels, not all, must agree.
        checks.report(anchor ? double(matched) >= 0.95 * double(checked) : matched == checked, what);
    }

    static constexpr double anchor_tolerance = 1e-3;
    headless_gl::Context &context_;
    const headless_gl::Functions &gl_;
    const Workload &workload_;
    const bool compute_;
    MoreFunctions more_;
    GLuint texton_ = 0, noise_buffer_ = 0, noise_texture_ = 0, vertex_array_ = 0;
    std::vector<Prepared> prepared_;
};

const char *const usage =
    "usage: dsn-gpu-bench [--fragment-api gles30|gl45] [--runs N] [--no-tiled] [--dump-shaders DIR]\n"
    "Times include/dsn/dsn.glsl (lattice and continuous per point, and tiled when dsn.glsl has its tile\n"
    "functions) against Texton Noise (Galerne, Leclaire, Moisan 2017) on the same asset, as GL 4.5 compute\n"
    "shaders and as fragment shaders (EGL surfaceless: llvmpipe when there is no GPU), checks their\n"
    "outputs, and prints Mpixel/s and the ratio to the anchor of the same kind.\n"
    "  --fragment-api API  the fragment shaders' context: gles30 (GLSL ES 3.00, default) or gl45\n"
    "  --runs N            timed runs of each variant after its warm-up (default 3; the best is reported)\n"
    "  --no-tiled          skip the tiled variants even where dsn.glsl has the tile functions\n"
    "  --dump-shaders DIR  write the shaders (gpu-bench-*.comp, .vert, .frag) to DIR and exit\n";

void write_file(const std::string &path, const std::string &text) {
    FILE *file = std::fopen(path.c_str(), "wb");
    if (!file || std::fwrite(text.data(), 1, text.size(), file) != text.size() || std::fclose(file) != 0)
        throw std::runtime_error("cannot write " + path);
}

const char *evaluation_name(Evaluation evaluation) {
    switch (evaluation) {
    case Evaluation::anchor:
        return "anchor";
    case Evaluation::lattice:
        return "lattice";
    case Evaluation::continuous:
        return "continuous";
    case Evaluation::lattice_tiled:
        return "lattice-tiled";
    case Evaluation::continuous_tiled:
        return "continuous-tiled";
    }
    return "?";
}

// One context at a time: each one's destructor terminates the EGL display the next would share.
void dump_shaders(const std::string &directory, bool tiled) {
    {
        headless_gl::Context context(Api::gl45);
        for (Evaluation evaluation : {Evaluation::anchor, Evaluation::lattice, Evaluation::continuous,
                                      Evaluation::lattice_tiled, Evaluation::continuous_tiled})
            if (!is_tiled(evaluation) || tiled)
                write_file(directory + "/gpu-bench-" + evaluation_name(evaluation) + ".comp",
                           compute_shader(context, evaluation));
    }
    for (Api api : {Api::gles30, Api::gl45}) {
        headless_gl::Context context(api);
        const std::string prefix = directory + "/gpu-bench-" + headless_gl::api_name(api);
        write_file(prefix + ".vert", vertex_shader(api));
        for (Evaluation evaluation : {Evaluation::anchor, Evaluation::lattice, Evaluation::continuous})
            write_file(prefix + "-" + evaluation_name(evaluation) + ".frag",
                       fragment_shader(context, evaluation));
    }
}

} // namespace

int main(int argc, char **argv) {
    Api fragment_api = Api::gles30;
    int runs = 3;
    bool tiled = true;
    std::string dump_directory;
    try {
        for (int i = 1; i < argc; i++) {
            const std::string argument = argv[i];
            if (argument == "--help" || argument == "-h") {
                std::fputs(usage, stdout);
                return 0;
            } else if (argument == "--fragment-api" && i + 1 < argc) {
                const std::string name = argv[++i];
                if (name == "gles30")
                    fragment_api = Api::gles30;
                else if (name == "gl45")
                    fragment_api = Api::gl45;
                else
                    throw std::runtime_error("--fragment-api: unknown API '" + name + "'");
            } else if (argument == "--runs" && i + 1 < argc) {
                runs = std::atoi(argv[++i]);
                if (runs < 1 || runs > 100) throw std::runtime_error("--runs: 1 to 100");
            } else if (argument == "--no-tiled") {
                tiled = false;
            } else if (argument == "--dump-shaders" && i + 1 < argc) {
                dump_directory = argv[++i];
            } else {
                throw std::runtime_error("unknown argument '" + argument + "' (see --help)");
            }
        }
        if (!dump_directory.empty()) {
            dump_shaders(dump_directory, tiled);
            return 0;
        }

        auto made = continuous_fixtures::make_noise(continuous_fixtures::random_texton_asset(3, 15, 8, 1),
                                                    noise_seed, uint32_t(impacts_per_pixel * 65536));
        std::vector<uint32_t> words(dsn_gpu_word_count(&made->noise));
        const int err = dsn_gpu_pack(&made->noise, words.data(), words.size());
        if (err != DSN_OK) throw std::runtime_error(std::string("dsn_gpu_pack: ") + dsn_error_message(err));
        const Workload workload = {&made->noise,
                                   words,
                                   Anchor(made->asset),
                                   texton_noise::Baseline(made->asset, impacts_per_pixel, anchor_seed_offset),
                                   tiled,
                                   runs};

        Checks checks;
        {
            headless_gl::Context context(Api::gl45);
            const GLubyte *renderer = context.gl.glGetString(GL_RENDERER);
            std::printf("GL_RENDERER: %s\n", renderer ? reinterpret_cast<const char *>(renderer) : "?");
            std::printf(
                "dsn-gpu-bench: RGB 31x31 8-bit bilinear texton, %g impacts per pixel; Mpixel/s of the "
                "best of %d runs after a warm-up\n",
                impacts_per_pixel, runs);
            std::printf("compute: %s, 16x16 workgroups, one invocation per pixel\n",
                        context.description().c_str());
            Bench bench(context, workload, true);
            bench.run_all(checks);
        }
        {
            headless_gl::Context context(fragment_api);
            std::printf("fragment: %s (%s), one fragment per pixel into RGBA8\n",
                        context.description().c_str(), headless_gl::api_name(fragment_api));
            Bench bench(context, workload, false);
            bench.run_all(checks);
        }
        if (checks.failures) {
            std::printf("dsn-gpu-bench: %d checks FAILED\n", checks.failures);
            return 1;
        }
        std::printf("dsn-gpu-bench: every check passed\n");
        return 0;
    } catch (const std::exception &error) {
        std::fflush(stdout);
        std::fprintf(stderr, "dsn-gpu-bench: %s\n", error.what());
        return 1;
    }
}
