// gpu_golden.cpp - the cross test's golden program evaluated on a GPU: tests/cross/golden.cpp compiled as
// it is, with every evaluation it makes (lattice and continuous points, tiles, grids, float and 8-bit
// conversions, coordinate conversions) done by include/dsn/dsn.glsl in a shader instead of the C runtime.
// It must print exactly tests/cross/golden.txt (less its h-* kinds: the shaders have no histogram
// mapping). The gradients (d-* kinds) and the mixes (m-* kinds, packed by dsn_gpu_mix_pack) are dsn.glsl's
// too: every invocation returns a value and, for a gradient, its two derivatives. The filtered kinds
// (f-*, and the filtered mix in m-f-point) stay the C runtime's: dsn.glsl has no filtering.
//
// The golden program asks for one value at a time and hashes it at once; a GPU wants batches. So it runs
// twice: the first run records every request (answering zeros, printing nothing; nothing it does depends
// on the values), the requests then go to the GPU in one batch per configured noise (tiles and grids as
// their own dispatch or draw, each invocation computing its point from the tile's origin and steps; on
// the compute APIs a noise's tiles and grids of values go through dsn.glsl's workgroup tiles, 8 x 8
// pixels a workgroup, so the golden proves them against the C runtime too), and
// the second run replays them in the same order with the GPU's answers, checking that each request is
// the one recorded. The configuration (dsn_asset_load, dsn_noise_init) stays on the CPU: dsn_gpu_pack
// copies the configured noise into the words the shader reads.
//
//   dsn-gpu-golden [--api gl45|gles31|gles30] [--limbs] [--cpu-mixes] [--cpu-surfaces] [--dump-shaders DIR]
//     gl45    OpenGL 4.5 core, GLSL 4.30 compute shader (shader storage buffers)
//     gles31  OpenGL ES 3.1, GLSL ES 3.10 compute shader
//     gles30  OpenGL ES 3.0, GLSL ES 3.00 fragment shader (WebGL2's language: no umulExtended, no SSBO):
//             noise and queries in integer textures, results rendered into an RGBA32UI target
//     --limbs         16-bit limb multiplications (the GLSL ES 3.00 code) whatever the API
//     --cpu-mixes     the mixes (m-* kinds) from the C runtime, not the shaders: for softpipe's GLSL ES 3.00
//                     run, which interprets a mix's fragments at about a minute and a half per mix
//     --cpu-surfaces  the surface noise (s-* kinds) from the C runtime, not the shaders (the same reason)
//     --dump-shaders  write the shaders of every API to DIR (for glslangValidator) and exit
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "dsn/dsn.h"
#include "dsn/gpu.h"
#include "headless_gl.h"

namespace gpu_golden {

void lattice_point_fixed(const dsn_noise *noise, int32_t x, int32_t y, int32_t *out);
void lattice_point_float(const dsn_noise *noise, int32_t x, int32_t y, float *out);
void lattice_point_u8(const dsn_noise *noise, int32_t x, int32_t y, uint8_t *out);
int lattice_tile_fixed(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                       int32_t *out, void *scratch, size_t scratch_size);
int lattice_tile_float(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                       float *out, void *scratch, size_t scratch_size);
int lattice_tile_u8(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                    uint8_t *out, void *scratch, size_t scratch_size);
int continuous_point_fixed(const dsn_noise *noise, int64_t x, int64_t y, int32_t *out);
int continuous_point_float(const dsn_noise *noise, double x, double y, float *out);
int continuous_tile_fixed(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                          int32_t *out, void *scratch, size_t scratch_size);
int continuous_tile_float(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                          float *out, void *scratch, size_t scratch_size);
int continuous_tile_u8(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                       uint8_t *out, void *scratch, size_t scratch_size);
int lattice_gradient_fixed(const dsn_noise *noise, int32_t x, int32_t y, int32_t *out, int32_t *dx,
                           int32_t *dy);
int lattice_gradient_float(const dsn_noise *noise, int32_t x, int32_t y, float *out, float *dx, float *dy);
int lattice_tile_gradient_fixed(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width,
                                uint32_t height, int32_t *out, int32_t *dx, int32_t *dy);
int lattice_tile_gradient_float(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width,
                                uint32_t height, float *out, float *dx, float *dy);
int continuous_gradient_fixed(const dsn_noise *noise, int64_t x, int64_t y, int32_t *out, int32_t *dx,
                              int32_t *dy);
int continuous_gradient_float(const dsn_noise *noise, double x, double y, float *out, float *dx, float *dy);
int continuous_tile_gradient_fixed(const dsn_noise *noise, const dsn_grid *grid, uint32_t width,
                                   uint32_t height, int32_t *out, int32_t *dx, int32_t *dy);
int continuous_tile_gradient_float(const dsn_noise *noise, const dsn_grid *grid, uint32_t width,
                                   uint32_t height, float *out, float *dx, float *dy);
int continuous_batch_gradient_fixed(const dsn_noise *noise, const int64_t *xs, const int64_t *ys,
                                    uint32_t count, int32_t *out, int32_t *dx, int32_t *dy);
int continuous_batch_gradient_float(const dsn_noise *noise, const double *xs, const double *ys,
                                    uint32_t count, float *out, float *dx, float *dy);
int64_t coordinate_from_double(double value);
int64_t coordinate_from_float(float value);
int mix_lattice_point_fixed(const dsn_mix *mix, const dsn_mix_control *control, int32_t x, int32_t y,
                            int32_t *out);
int mix_continuous_point_fixed(const dsn_mix *mix, const dsn_mix_control *control, int64_t x, int64_t y,
                               int32_t *out);
int mix_continuous_point_float(const dsn_mix *mix, const dsn_mix_control *control, double x, double y,
                               float *out);
int mix_continuous_batch_u8(const dsn_mix *mix, const dsn_mix_control *control, const int64_t *xs,
                            const int64_t *ys, uint32_t count, uint8_t *out);
int mix_lattice_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                           uint32_t width, uint32_t height, int32_t *out, void *scratch, size_t scratch_size);
int mix_lattice_tile_float(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                           uint32_t width, uint32_t height, float *out, void *scratch, size_t scratch_size);
int mix_continuous_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                              uint32_t width, uint32_t height, int32_t *out, void *scratch,
                              size_t scratch_size);
int mix_continuous_tile_u8(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                           uint32_t width, uint32_t height, uint8_t *out, void *scratch, size_t scratch_size);
int surface_frame_from_float(const float *normal, const float *tangent, dsn_surface_frame *frame);
int surface_point_fixed(const dsn_noise *noise, const int64_t *position, const dsn_surface_frame *frame,
                        int32_t *out);
int surface_point_float(const dsn_noise *noise, const double *position, const float *normal,
                        const float *tangent, float *out);
int surface_point_u8(const dsn_noise *noise, const int64_t *position, const dsn_surface_frame *frame,
                     uint8_t *out);
int surface_batch_fixed(const dsn_noise *noise, const int64_t *positions, const dsn_surface_frame *frames,
                        uint32_t count, int32_t *out);

} // namespace gpu_golden

// The golden program, its evaluators replaced by the GPU's (its header declarations are already seen).
#define dsn_lattice_point_fixed gpu_golden::lattice_point_fixed
#define dsn_lattice_point_float gpu_golden::lattice_point_float
#define dsn_lattice_point_u8 gpu_golden::lattice_point_u8
#define dsn_lattice_tile_fixed gpu_golden::lattice_tile_fixed
#define dsn_lattice_tile_float gpu_golden::lattice_tile_float
#define dsn_lattice_tile_u8 gpu_golden::lattice_tile_u8
#define dsn_continuous_point_fixed gpu_golden::continuous_point_fixed
#define dsn_continuous_point_float gpu_golden::continuous_point_float
#define dsn_continuous_tile_fixed gpu_golden::continuous_tile_fixed
#define dsn_continuous_tile_float gpu_golden::continuous_tile_float
#define dsn_continuous_tile_u8 gpu_golden::continuous_tile_u8
#define dsn_lattice_gradient_fixed gpu_golden::lattice_gradient_fixed
#define dsn_lattice_gradient_float gpu_golden::lattice_gradient_float
#define dsn_lattice_tile_gradient_fixed gpu_golden::lattice_tile_gradient_fixed
#define dsn_lattice_tile_gradient_float gpu_golden::lattice_tile_gradient_float
#define dsn_continuous_gradient_fixed gpu_golden::continuous_gradient_fixed
#define dsn_continuous_gradient_float gpu_golden::continuous_gradient_float
#define dsn_continuous_tile_gradient_fixed gpu_golden::continuous_tile_gradient_fixed
#define dsn_continuous_tile_gradient_float gpu_golden::continuous_tile_gradient_float
#define dsn_continuous_batch_gradient_fixed gpu_golden::continuous_batch_gradient_fixed
#define dsn_continuous_batch_gradient_float gpu_golden::continuous_batch_gradient_float
#define dsn_coordinate_from_double gpu_golden::coordinate_from_double
#define dsn_coordinate_from_float gpu_golden::coordinate_from_float
#define dsn_mix_lattice_point_fixed gpu_golden::mix_lattice_point_fixed
#define dsn_mix_continuous_point_fixed gpu_golden::mix_continuous_point_fixed
#define dsn_mix_continuous_point_float gpu_golden::mix_continuous_point_float
#define dsn_mix_continuous_batch_u8 gpu_golden::mix_continuous_batch_u8
#define dsn_mix_lattice_tile_fixed gpu_golden::mix_lattice_tile_fixed
#define dsn_mix_lattice_tile_float gpu_golden::mix_lattice_tile_float
#define dsn_mix_continuous_tile_fixed gpu_golden::mix_continuous_tile_fixed
#define dsn_mix_continuous_tile_u8 gpu_golden::mix_continuous_tile_u8
#define dsn_surface_frame_from_float gpu_golden::surface_frame_from_float
#define dsn_surface_point_fixed gpu_golden::surface_point_fixed
#define dsn_surface_point_float gpu_golden::surface_point_float
#define dsn_surface_point_u8 gpu_golden::surface_point_u8
#define dsn_surface_batch_fixed gpu_golden::surface_batch_fixed
#define main golden_main
#define GOLDEN_WITHOUT_HISTOGRAM 1 /* dsn.glsl has no histogram mapping: the h-* kinds are left out */
#include "cross/golden.cpp"
#undef main
/* The mixes' own functions again: each replacement takes its error code from the C function (the GPU
   gives the values). */
#undef dsn_mix_lattice_point_fixed
#undef dsn_mix_continuous_point_fixed
#undef dsn_mix_continuous_point_float
#undef dsn_mix_continuous_batch_u8
#undef dsn_mix_lattice_tile_fixed
#undef dsn_mix_lattice_tile_float
#undef dsn_mix_continuous_tile_fixed
#undef dsn_mix_continuous_tile_u8
#undef dsn_surface_frame_from_float
#undef dsn_surface_point_fixed
#undef dsn_surface_point_float
#undef dsn_surface_point_u8
#undef dsn_surface_batch_fixed

namespace gpu_golden {

using headless_gl::Api;

const char *const dsn_glsl =
#include "include/dsn/dsn.glsl.inc"
    ;
const char *const kernel_glsl =
#include "tests/gpu/golden_kernel.glsl.inc"
    ;

/* ---- Requests ---- */

enum TaskKind : uint32_t { task_queries = 0, task_lattice_tile = 1, task_grid = 2 };
enum Conversion : uint32_t { as_fixed = 0, as_float = 1, as_u8 = 2 };
const uint32_t with_gradient = 1u << 16; /* in a query's mode */
const uint32_t of_mix = 1u << 17;        /* in a query's mode: the words are a mix's */
/* Words per value of a result: the value, then the x and y derivatives (0 but for a gradient), each a
   uvec4 of the shader. */
const uint32_t result_words = 12;
enum Point : uint32_t {
    point_lattice = 0,
    point_continuous = 1,
    point_continuous_doubles = 2,
    point_coordinate_double = 3,
    point_coordinate_float = 4,
    point_surface = 5,
    point_surface_doubles = 6,
    surface_frame = 7
};
/* Words of a query: four uvec4 of the shader (golden_kernel.glsl). */
const uint32_t query_words = 16;

/* One thing the golden program asked for: a query (one value) or a tile (width x height values). */
struct Request {
    size_t noise = 0; /* index into Recorder::noises */
    uint32_t kind = task_queries;
    uint32_t query[query_words] = {}; /* mode (point | conversion << 8), x low, x high, y low, y high, ... */
    uint32_t conversion = as_fixed, gradient = 0, mix = 0, width = 1, height = 1;
    uint32_t origin[4] = {0, 0, 0, 0}, column_step[4] = {0, 0, 0, 0}, row_step[4] = {0, 0, 0, 0};
    std::vector<uint32_t> result; /* result_words per value */

    bool same_as(const Request &other) const {
        return noise == other.noise && kind == other.kind && !memcmp(query, other.query, sizeof query) &&
               conversion == other.conversion && gradient == other.gradient && mix == other.mix &&
               width == other.width && height == other.height &&
               !memcmp(origin, other.origin, sizeof origin) &&
               !memcmp(column_step, other.column_step, sizeof column_step) &&
               !memcmp(row_step, other.row_step, sizeof row_step);
    }
};

struct Recorder {
    bool replaying = false, printing = false, cpu_mixes = false, cpu_surfaces = false;
    std::vector<Request> requests;
    size_t cursor = 0;
    std::vector<std::vector<uint32_t>> noises;    /* packed words */
    std::map<std::string, size_t> noise_by_words; /* packed words (as bytes) -> index */
};

Recorder recorder;

/* The index of these packed words (a noise's or a mix's) among the recorded ones. */
size_t words_index(const std::vector<uint32_t> &words) {
    const std::string bytes(reinterpret_cast<const char *>(words.data()), words.size() * sizeof words[0]);
    auto found = recorder.noise_by_words.find(bytes);
    if (found != recorder.noise_by_words.end()) return found->second;
    recorder.noises.push_back(words);
    recorder.noise_by_words[bytes] = recorder.noises.size() - 1;
    return recorder.noises.size() - 1;
}

/* The same configuration packs to the same words (a dsn_noise's own bytes may differ: init leaves the
   words it does not use as they were). */
size_t noise_index(const dsn_noise *noise) {
    std::vector<uint32_t> words(dsn_gpu_word_count(noise));
    const int err = dsn_gpu_pack(noise, words.data(), words.size());
    if (err != DSN_OK) throw std::runtime_error(std::string("dsn_gpu_pack: ") + dsn_error_message(err));
    return words_index(words);
}

size_t mix_index(const dsn_mix *mix, const dsn_mix_control *control) {
    std::vector<uint32_t> words(dsn_gpu_mix_word_count(mix, control));
    const int err = dsn_gpu_mix_pack(mix, control, words.data(), words.size());
    if (err != DSN_OK) throw std::runtime_error(std::string("dsn_gpu_mix_pack: ") + dsn_error_message(err));
    return words_index(words);
}

/* Records the request (answering zeros) or returns the GPU's answer to it. */
const std::vector<uint32_t> &answer(const Request &request) {
    static const std::vector<uint32_t> zeros(result_words * 65536u, 0u);
    if (!recorder.replaying) {
        recorder.requests.push_back(request);
        return zeros;
    }
    if (recorder.cursor >= recorder.requests.size() || !recorder.requests[recorder.cursor].same_as(request))
        throw std::runtime_error("the replay differs from the recording at request " +
                                 std::to_string(recorder.cursor));
    return recorder.requests[recorder.cursor++].result;
}

Request query(const dsn_noise *noise, uint32_t point, uint32_t conversion, uint64_t x, uint64_t y) {
    Request request;
    request.noise = noise ? noise_index(noise) : 0;
    request.query[0] = point | conversion << 8;
    request.query[1] = static_cast<uint32_t>(x);
    request.query[2] = static_cast<uint32_t>(x >> 32);
    request.query[3] = static_cast<uint32_t>(y);
    request.query[4] = static_cast<uint32_t>(y >> 32);
    return request;
}

/* part 0: the values; 1 and 2: the x and y derivatives of a gradient. */
template <typename Value>
void store(const std::vector<uint32_t> &result, uint32_t values, uint32_t channels, Value *out,
           uint32_t part = 0) {
    for (uint32_t v = 0; v < values; v++)
        for (uint32_t c = 0; c < channels; c++) {
            const uint32_t word = result[result_words * v + 4 * part + c];
            if (sizeof(Value) == 1) {
                out[v * channels + c] = static_cast<Value>(word);
            } else {
                memcpy(&out[v * channels + c], &word, sizeof word);
            }
        }
}

void put_pair(uint32_t *words, int64_t value) {
    words[0] = static_cast<uint32_t>(static_cast<uint64_t>(value));
    words[1] = static_cast<uint32_t>(static_cast<uint64_t>(value) >> 32);
}

/* The request of a lattice tile of the words at `index`: width x height points from (x0, y0). */
Request lattice_tile_request(size_t index, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                             uint32_t conversion) {
    Request request;
    request.noise = index;
    request.kind = task_lattice_tile;
    request.conversion = conversion;
    request.width = width;
    request.height = height;
    request.origin[0] = static_cast<uint32_t>(x0);
    request.origin[2] = static_cast<uint32_t>(y0);
    return request;
}

/* The request of a continuous grid of the words at `index`. */
Request grid_request(size_t index, const dsn_grid *grid, uint32_t width, uint32_t height,
                     uint32_t conversion) {
    Request request;
    request.noise = index;
    request.kind = task_grid;
    request.conversion = conversion;
    request.width = width;
    request.height = height;
    put_pair(request.origin, grid->origin_x);
    put_pair(request.origin + 2, grid->origin_y);
    put_pair(request.column_step, grid->column_step_x);
    put_pair(request.column_step + 2, grid->column_step_y);
    put_pair(request.row_step, grid->row_step_x);
    put_pair(request.row_step + 2, grid->row_step_y);
    return request;
}

/* ---- The replacements of the runtime's evaluators ---- */

void lattice_point_fixed(const dsn_noise *noise, int32_t x, int32_t y, int32_t *out) {
    const Request request =
        query(noise, point_lattice, as_fixed, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
    store(answer(request), 1, dsn_noise_channels(noise), out);
}

void lattice_point_float(const dsn_noise *noise, int32_t x, int32_t y, float *out) {
    const Request request =
        query(noise, point_lattice, as_float, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
    store(answer(request), 1, dsn_noise_channels(noise), out);
}

void lattice_point_u8(const dsn_noise *noise, int32_t x, int32_t y, uint8_t *out) {
    const Request request =
        query(noise, point_lattice, as_u8, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
    store(answer(request), 1, dsn_noise_channels(noise), out);
}

template <typename Value>
int lattice_tile(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height, Value *out,
                 uint32_t conversion) {
    if (noise == nullptr || out == nullptr) return DSN_ERR_NULL;
    if (dsn_gpu_word_count(noise) == 0) return DSN_ERR_ARGUMENT;
    if (width == 0 || height == 0 || width > 65536 || height > 65536 || width * height > 65536)
        return DSN_ERR_TILE_SIZE;
    Request request = lattice_tile_request(noise_index(noise), x0, y0, width, height, conversion);
    store(answer(request), width * height, dsn_noise_channels(noise), out);
    return DSN_OK;
}

int lattice_tile_fixed(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                       int32_t *out, void *, size_t) {
    return lattice_tile(noise, x0, y0, width, height, out, as_fixed);
}

int lattice_tile_float(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                       float *out, void *, size_t) {
    return lattice_tile(noise, x0, y0, width, height, out, as_float);
}

int lattice_tile_u8(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                    uint8_t *out, void *, size_t) {
    return lattice_tile(noise, x0, y0, width, height, out, as_u8);
}

/* The continuous mode's argument check is the C API's (a property of the configuration). */
int continuous_point_fixed(const dsn_noise *noise, int64_t x, int64_t y, int32_t *out) {
    const int err = dsn_continuous_check(noise);
    if (out == nullptr) return DSN_ERR_NULL;
    const Request request =
        query(noise, point_continuous, as_fixed, static_cast<uint64_t>(x), static_cast<uint64_t>(y));
    store(answer(request), 1, dsn_noise_channels(noise), out);
    return err;
}

int continuous_point_float(const dsn_noise *noise, double x, double y, float *out) {
    const int err = dsn_continuous_check(noise);
    if (out == nullptr) return DSN_ERR_NULL;
    uint64_t x_bits, y_bits;
    memcpy(&x_bits, &x, sizeof x_bits);
    memcpy(&y_bits, &y, sizeof y_bits);
    const Request request = query(noise, point_continuous_doubles, as_float, x_bits, y_bits);
    store(answer(request), 1, dsn_noise_channels(noise), out);
    return err;
}

template <typename Value>
int continuous_tile(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height, Value *out,
                    uint32_t conversion) {
    const int err = dsn_continuous_check(noise);
    if (err != DSN_OK) return err;
    if (grid == nullptr || out == nullptr) return DSN_ERR_NULL;
    if (width == 0 || height == 0 || width > 65536 || height > 65536 || width * height > 65536)
        return DSN_ERR_TILE_SIZE;
    Request request = grid_request(noise_index(noise), grid, width, height, conversion);
    store(answer(request), width * height, dsn_noise_channels(noise), out);
    return DSN_OK;
}

int continuous_tile_fixed(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                          int32_t *out, void *, size_t) {
    return continuous_tile(noise, grid, width, height, out, as_fixed);
}

int continuous_tile_float(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                          float *out, void *, size_t) {
    return continuous_tile(noise, grid, width, height, out, as_float);
}

int continuous_tile_u8(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                       uint8_t *out, void *, size_t) {
    return continuous_tile(noise, grid, width, height, out, as_u8);
}

/* Coordinate conversions need no noise: they go with the first noise's batch (or alone). */
int64_t coordinate(uint32_t point, uint64_t bits) {
    Request request = query(nullptr, point, as_fixed, bits, 0);
    const std::vector<uint32_t> &result = answer(request);
    return static_cast<int64_t>(static_cast<uint64_t>(result[0]) | static_cast<uint64_t>(result[1]) << 32);
}

int64_t coordinate_from_double(double value) {
    uint64_t bits;
    memcpy(&bits, &value, sizeof bits);
    return coordinate(point_coordinate_double, bits);
}

int64_t coordinate_from_float(float value) {
    uint32_t bits;
    memcpy(&bits, &value, sizeof bits);
    return coordinate(point_coordinate_float, bits);
}

/* ---- The replacements of the runtime's gradient functions: each point's value and derivatives ---- */

template <typename Value>
void store_gradient(const std::vector<uint32_t> &result, uint32_t values, uint32_t channels, Value *out,
                    Value *dx, Value *dy) {
    store(result, values, channels, out, 0);
    store(result, values, channels, dx, 1);
    store(result, values, channels, dy, 2);
}

template <typename Value>
int lattice_gradient(const dsn_noise *noise, int32_t x, int32_t y, Value *out, Value *dx, Value *dy,
                     uint32_t conversion) {
    if (noise == nullptr || out == nullptr || dx == nullptr || dy == nullptr) return DSN_ERR_NULL;
    Request request =
        query(noise, point_lattice, conversion, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
    request.query[0] |= with_gradient;
    store_gradient(answer(request), 1, dsn_noise_channels(noise), out, dx, dy);
    return DSN_OK;
}

int lattice_gradient_fixed(const dsn_noise *noise, int32_t x, int32_t y, int32_t *out, int32_t *dx,
                           int32_t *dy) {
    return lattice_gradient(noise, x, y, out, dx, dy, as_fixed);
}

int lattice_gradient_float(const dsn_noise *noise, int32_t x, int32_t y, float *out, float *dx, float *dy) {
    return lattice_gradient(noise, x, y, out, dx, dy, as_float);
}

template <typename Value>
int lattice_tile_gradient(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                          Value *out, Value *dx, Value *dy, uint32_t conversion) {
    if (noise == nullptr || out == nullptr || dx == nullptr || dy == nullptr) return DSN_ERR_NULL;
    if (dsn_gpu_word_count(noise) == 0) return DSN_ERR_ARGUMENT;
    if (width == 0 || height == 0 || width > 65536 || height > 65536 || width * height > 65536)
        return DSN_ERR_TILE_SIZE;
    Request request = lattice_tile_request(noise_index(noise), x0, y0, width, height, conversion);
    request.gradient = 1;
    store_gradient(answer(request), width * height, dsn_noise_channels(noise), out, dx, dy);
    return DSN_OK;
}

int lattice_tile_gradient_fixed(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width,
                                uint32_t height, int32_t *out, int32_t *dx, int32_t *dy) {
    return lattice_tile_gradient(noise, x0, y0, width, height, out, dx, dy, as_fixed);
}

int lattice_tile_gradient_float(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width,
                                uint32_t height, float *out, float *dx, float *dy) {
    return lattice_tile_gradient(noise, x0, y0, width, height, out, dx, dy, as_float);
}

/* A continuous point: Q32.32 coordinates (point_continuous) or the IEEE bits of two doubles
   (point_continuous_doubles). The argument check is the C API's. */
template <typename Value>
int continuous_gradient(const dsn_noise *noise, uint32_t point, uint64_t x, uint64_t y, Value *out, Value *dx,
                        Value *dy, uint32_t conversion) {
    const int err = dsn_continuous_check(noise);
    if (out == nullptr || dx == nullptr || dy == nullptr) return DSN_ERR_NULL;
    Request request = query(noise, point, conversion, x, y);
    request.query[0] |= with_gradient;
    store_gradient(answer(request), 1, dsn_noise_channels(noise), out, dx, dy);
    return err;
}

uint64_t double_bits(double value) {
    uint64_t bits;
    memcpy(&bits, &value, sizeof bits);
    return bits;
}

int continuous_gradient_fixed(const dsn_noise *noise, int64_t x, int64_t y, int32_t *out, int32_t *dx,
                              int32_t *dy) {
    return continuous_gradient(noise, point_continuous, static_cast<uint64_t>(x), static_cast<uint64_t>(y),
                               out, dx, dy, as_fixed);
}

int continuous_gradient_float(const dsn_noise *noise, double x, double y, float *out, float *dx, float *dy) {
    return continuous_gradient(noise, point_continuous_doubles, double_bits(x), double_bits(y), out, dx, dy,
                               as_float);
}

template <typename Value>
int continuous_tile_gradient(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                             Value *out, Value *dx, Value *dy, uint32_t conversion) {
    const int err = dsn_continuous_check(noise);
    if (err != DSN_OK) return err;
    if (grid == nullptr || out == nullptr || dx == nullptr || dy == nullptr) return DSN_ERR_NULL;
    if (width == 0 || height == 0 || width > 65536 || height > 65536 || width * height > 65536)
        return DSN_ERR_TILE_SIZE;
    Request request = grid_request(noise_index(noise), grid, width, height, conversion);
    request.gradient = 1;
    store_gradient(answer(request), width * height, dsn_noise_channels(noise), out, dx, dy);
    return DSN_OK;
}

int continuous_tile_gradient_fixed(const dsn_noise *noise, const dsn_grid *grid, uint32_t width,
                                   uint32_t height, int32_t *out, int32_t *dx, int32_t *dy) {
    return continuous_tile_gradient(noise, grid, width, height, out, dx, dy, as_fixed);
}

int continuous_tile_gradient_float(const dsn_noise *noise, const dsn_grid *grid, uint32_t width,
                                   uint32_t height, float *out, float *dx, float *dy) {
    return continuous_tile_gradient(noise, grid, width, height, out, dx, dy, as_float);
}

/* A batch: its points as queries (they join the noise's batch of queries). */
uint64_t batch_bits(int64_t value) { return static_cast<uint64_t>(value); }
uint64_t batch_bits(double value) { return double_bits(value); }

template <typename Coordinate, typename Value>
int continuous_batch_gradient(const dsn_noise *noise, const Coordinate *xs, const Coordinate *ys,
                              uint32_t count, Value *out, Value *dx, Value *dy, uint32_t point,
                              uint32_t conversion) {
    const int err = dsn_continuous_check(noise);
    if (err != DSN_OK) return err;
    if (count != 0 && (xs == nullptr || ys == nullptr || out == nullptr || dx == nullptr || dy == nullptr))
        return DSN_ERR_NULL;
    const uint32_t channels = dsn_noise_channels(noise);
    for (uint32_t k = 0; k < count; k++)
        continuous_gradient(noise, point, batch_bits(xs[k]), batch_bits(ys[k]), out + k * channels,
                            dx + k * channels, dy + k * channels, conversion);
    return DSN_OK;
}

int continuous_batch_gradient_fixed(const dsn_noise *noise, const int64_t *xs, const int64_t *ys,
                                    uint32_t count, int32_t *out, int32_t *dx, int32_t *dy) {
    return continuous_batch_gradient(noise, xs, ys, count, out, dx, dy, point_continuous, as_fixed);
}

int continuous_batch_gradient_float(const dsn_noise *noise, const double *xs, const double *ys,
                                    uint32_t count, float *out, float *dx, float *dy) {
    return continuous_batch_gradient(noise, xs, ys, count, out, dx, dy, point_continuous_doubles, as_float);
}

/* ---- The replacements of the mixing functions: the C function's error, the GPU's values ---- */

/* With --cpu-mixes the C function's values stand (the replacements below return them as they are). */
Request mix_query(const dsn_mix *mix, const dsn_mix_control *control, uint32_t point, uint32_t conversion,
                  uint64_t x, uint64_t y) {
    Request request = query(nullptr, point | of_mix, conversion, x, y);
    request.noise = mix_index(mix, control);
    return request;
}

int mix_lattice_point_fixed(const dsn_mix *mix, const dsn_mix_control *control, int32_t x, int32_t y,
                            int32_t *out) {
    const int err = dsn_mix_lattice_point_fixed(mix, control, x, y, out);
    if (err != DSN_OK || recorder.cpu_mixes) return err;
    store(answer(mix_query(mix, control, point_lattice, as_fixed, static_cast<uint32_t>(x),
                           static_cast<uint32_t>(y))),
          1, dsn_mix_channels(mix), out);
    return DSN_OK;
}

int mix_continuous_point_fixed(const dsn_mix *mix, const dsn_mix_control *control, int64_t x, int64_t y,
                               int32_t *out) {
    const int err = dsn_mix_continuous_point_fixed(mix, control, x, y, out);
    if (err != DSN_OK || recorder.cpu_mixes) return err;
    store(answer(mix_query(mix, control, point_continuous, as_fixed, static_cast<uint64_t>(x),
                           static_cast<uint64_t>(y))),
          1, dsn_mix_channels(mix), out);
    return DSN_OK;
}

int mix_continuous_point_float(const dsn_mix *mix, const dsn_mix_control *control, double x, double y,
                               float *out) {
    const int err = dsn_mix_continuous_point_float(mix, control, x, y, out);
    if (err != DSN_OK || recorder.cpu_mixes) return err;
    store(answer(mix_query(mix, control, point_continuous_doubles, as_float, double_bits(x), double_bits(y))),
          1, dsn_mix_channels(mix), out);
    return DSN_OK;
}

int mix_continuous_batch_u8(const dsn_mix *mix, const dsn_mix_control *control, const int64_t *xs,
                            const int64_t *ys, uint32_t count, uint8_t *out) {
    const int err = dsn_mix_continuous_batch_u8(mix, control, xs, ys, count, out);
    if (err != DSN_OK || recorder.cpu_mixes) return err;
    const uint32_t channels = dsn_mix_channels(mix);
    for (uint32_t k = 0; k < count; k++)
        store(answer(mix_query(mix, control, point_continuous, as_u8, static_cast<uint64_t>(xs[k]),
                               static_cast<uint64_t>(ys[k]))),
              1, channels, out + k * channels);
    return DSN_OK;
}

template <typename Value>
void mix_lattice_tile(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                      uint32_t width, uint32_t height, Value *out, uint32_t conversion) {
    Request request = lattice_tile_request(mix_index(mix, control), x0, y0, width, height, conversion);
    request.mix = 1;
    store(answer(request), width * height, dsn_mix_channels(mix), out);
}

int mix_lattice_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                           uint32_t width, uint32_t height, int32_t *out, void *scratch,
                           size_t scratch_size) {
    const int err =
        dsn_mix_lattice_tile_fixed(mix, control, x0, y0, width, height, out, scratch, scratch_size);
    if (err == DSN_OK && !recorder.cpu_mixes)
        mix_lattice_tile(mix, control, x0, y0, width, height, out, as_fixed);
    return err;
}

int mix_lattice_tile_float(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                           uint32_t width, uint32_t height, float *out, void *scratch, size_t scratch_size) {
    const int err =
        dsn_mix_lattice_tile_float(mix, control, x0, y0, width, height, out, scratch, scratch_size);
    if (err == DSN_OK && !recorder.cpu_mixes)
        mix_lattice_tile(mix, control, x0, y0, width, height, out, as_float);
    return err;
}

template <typename Value>
void mix_continuous_tile(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                         uint32_t width, uint32_t height, Value *out, uint32_t conversion) {
    Request request = grid_request(mix_index(mix, control), grid, width, height, conversion);
    request.mix = 1;
    store(answer(request), width * height, dsn_mix_channels(mix), out);
}

int mix_continuous_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                              uint32_t width, uint32_t height, int32_t *out, void *scratch,
                              size_t scratch_size) {
    const int err =
        dsn_mix_continuous_tile_fixed(mix, control, grid, width, height, out, scratch, scratch_size);
    if (err == DSN_OK && !recorder.cpu_mixes)
        mix_continuous_tile(mix, control, grid, width, height, out, as_fixed);
    return err;
}

int mix_continuous_tile_u8(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                           uint32_t width, uint32_t height, uint8_t *out, void *scratch,
                           size_t scratch_size) {
    const int err = dsn_mix_continuous_tile_u8(mix, control, grid, width, height, out, scratch, scratch_size);
    if (err == DSN_OK && !recorder.cpu_mixes)
        mix_continuous_tile(mix, control, grid, width, height, out, as_u8);
    return err;
}

/* ---- The replacements of the surface functions: the C function's error, the GPU's values ---- */

/* With --cpu-surfaces the C function's values stand (the replacements below return them as they are). The
   filtered surface stays the C runtime's: dsn.glsl has no filtering. */
uint32_t float_bits(float value) {
    uint32_t bits;
    memcpy(&bits, &value, sizeof bits);
    return bits;
}

int surface_frame_from_float(const float *normal, const float *tangent, dsn_surface_frame *frame) {
    const int err = dsn_surface_frame_from_float(normal, tangent, frame);
    if (err != DSN_OK || recorder.cpu_surfaces) return err;
    Request request = query(nullptr, surface_frame, as_fixed, 0, 0);
    for (int i = 0; i < 3; i++) {
        request.query[1 + i] = float_bits(normal[i]);
        request.query[4 + i] = tangent ? float_bits(tangent[i]) : 0u;
    }
    request.query[7] = tangent ? 1u : 0u;
    const std::vector<uint32_t> &result = answer(request);
    if (!recorder.replaying) return err; /* the C frame: the recorded queries that use it are the replay's */
    int32_t *const vectors[3] = {frame->tangent, frame->bitangent, frame->normal};
    for (int v = 0; v < 3; v++) memcpy(vectors[v], &result[4 * v], 3 * sizeof(int32_t));
    return result[3] == 1u ? err : DSN_ERR_ARGUMENT;
}

/* The words of a surface query: the position's (3 pairs) from word 1, then nine more from word 7. */
Request surface_query(const dsn_noise *noise, uint32_t point, uint32_t conversion, const uint64_t *position,
                      const uint32_t *rest) {
    Request request = query(noise, point, conversion, position[0], position[1]);
    request.query[5] = static_cast<uint32_t>(position[2]);
    request.query[6] = static_cast<uint32_t>(position[2] >> 32);
    memcpy(request.query + 7, rest, 9 * sizeof(uint32_t));
    return request;
}

template <typename Value>
void surface_fixed_query(const dsn_noise *noise, const int64_t *position, const dsn_surface_frame *frame,
                         uint32_t conversion, Value *out) {
    const uint64_t bits[3] = {static_cast<uint64_t>(position[0]), static_cast<uint64_t>(position[1]),
                              static_cast<uint64_t>(position[2])};
    uint32_t rest[9];
    memcpy(rest, frame->tangent, 3 * sizeof(uint32_t));
    memcpy(rest + 3, frame->bitangent, 3 * sizeof(uint32_t));
    memcpy(rest + 6, frame->normal, 3 * sizeof(uint32_t));
    store(answer(surface_query(noise, point_surface, conversion, bits, rest)), 1, dsn_noise_channels(noise),
          out);
}

int surface_point_fixed(const dsn_noise *noise, const int64_t *position, const dsn_surface_frame *frame,
                        int32_t *out) {
    const int err = dsn_surface_point_fixed(noise, position, frame, out);
    if (err == DSN_OK && !recorder.cpu_surfaces) surface_fixed_query(noise, position, frame, as_fixed, out);
    return err;
}

int surface_point_u8(const dsn_noise *noise, const int64_t *position, const dsn_surface_frame *frame,
                     uint8_t *out) {
    const int err = dsn_surface_point_u8(noise, position, frame, out);
    if (err == DSN_OK && !recorder.cpu_surfaces) surface_fixed_query(noise, position, frame, as_u8, out);
    return err;
}

int surface_batch_fixed(const dsn_noise *noise, const int64_t *positions, const dsn_surface_frame *frames,
                        uint32_t count, int32_t *out) {
    const int err = dsn_surface_batch_fixed(noise, positions, frames, count, out);
    if (err != DSN_OK || recorder.cpu_surfaces) return err;
    const uint32_t channels = dsn_noise_channels(noise);
    for (uint32_t k = 0; k < count; k++)
        surface_fixed_query(noise, positions + 3 * k, frames + k, as_fixed, out + k * channels);
    return err;
}

int surface_point_float(const dsn_noise *noise, const double *position, const float *normal,
                        const float *tangent, float *out) {
    const int err = dsn_surface_point_float(noise, position, normal, tangent, out);
    if (err != DSN_OK || recorder.cpu_surfaces) return err;
    const uint64_t bits[3] = {double_bits(position[0]), double_bits(position[1]), double_bits(position[2])};
    uint32_t rest[9] = {};
    for (int i = 0; i < 3; i++) {
        rest[i] = float_bits(normal[i]);
        rest[3 + i] = tangent ? float_bits(tangent[i]) : 0u;
    }
    rest[6] = tangent ? 1u : 0u;
    store(answer(surface_query(noise, point_surface_doubles, as_float, bits, rest)), 1,
          dsn_noise_channels(noise), out);
    return err;
}

/* ---- Running the requests on the GPU ---- */

struct Task {
    uint32_t kind = task_queries, conversion = as_fixed, gradient = 0, mix = 0, width = 1, count = 0;
    const uint32_t *origin = nullptr, *column_step = nullptr, *row_step = nullptr;
};

const uint32_t no_words[4] = {0, 0, 0, 0};

/* Compute shaders (GL 4.5, GLES 3.1): noise, queries and results in shader storage buffers. */
/* With --cpu-mixes the shaders leave the mix functions out (a smaller program for softpipe to interpret). */
std::string golden_defines(bool limbs) {
    return std::string(limbs ? "#define DSN_GLSL_LIMBS 1\n" : "") +
           (recorder.cpu_mixes ? "#define GOLDEN_CPU_MIXES 1\n" : "#define GOLDEN_CPU_MIXES 0\n") +
           (recorder.cpu_surfaces ? "#define GOLDEN_CPU_SURFACES 1\n" : "#define GOLDEN_CPU_SURFACES 0\n");
}

std::string compute_shader(const headless_gl::Context &context, bool limbs) {
    return context.shader_preamble() + golden_defines(limbs) +
           "layout(local_size_x = 64) in;\n"
           "layout(std430, binding = 0) readonly buffer NoiseWords { uint noise_words[]; };\n"
           "layout(std430, binding = 1) readonly buffer Queries { uvec4 queries[]; };\n"
           "layout(std430, binding = 2) writeonly buffer Results { uvec4 results[]; };\n"
           "uniform uint task_count;\n"
           "uvec4 golden_query(uint index, uint part) { return queries[4u * index + part]; }\n" +
           dsn_glsl + "uint dsn_word(uint index) { return noise_words[dsn_word_base + index]; }\n" +
           kernel_glsl +
           "void main() {\n"
           "    uint index = gl_GlobalInvocationID.x;\n"
           "    if (index >= task_count) return;\n"
           "    uvec4 value, dx, dy;\n"
           "    golden_evaluate(index, value, dx, dy);\n"
           "    results[3u * index] = value;\n"
           "    results[3u * index + 1u] = dx;\n"
           "    results[3u * index + 2u] = dy;\n"
           "}\n";
}

/* The compute APIs' lattice tiles and continuous grids (values alone, of a noise): dsn.glsl's workgroup
   tiles, 8 x 8 pixels a workgroup, each workgroup listing the impulses that reach its pixels once. */
const uint32_t tile_side = 8;

std::string tile_shader(const headless_gl::Context &context, bool limbs) {
    return context.shader_preamble() + golden_defines(limbs) + "#define DSN_GLSL_TILES 1\n" +
           "layout(local_size_x = " + std::to_string(tile_side) +
           ", local_size_y = " + std::to_string(tile_side) +
           ") in;\n"
           "layout(std430, binding = 0) readonly buffer NoiseWords { uint noise_words[]; };\n"
           "layout(std430, binding = 2) writeonly buffer Results { uvec4 results[]; };\n"
           "uniform uint task_height;\n"
           "uvec4 golden_query(uint index, uint part) { return uvec4(0u); }\n" +
           dsn_glsl + "uint dsn_word(uint index) { return noise_words[dsn_word_base + index]; }\n" +
           kernel_glsl +
           "void main() {\n"
           "    uvec2 pixel = gl_GlobalInvocationID.xy, first = gl_WorkGroupID.xy * gl_WorkGroupSize.xy;\n"
           "    uvec2 size = min(gl_WorkGroupSize.xy, uvec2(task_width, task_height) - first);\n"
           "    ivec2 origin = ivec2(uvec2(task_origin.x, task_origin.z) + first);\n"
           "    ivec2 p = ivec2(uvec2(task_origin.x, task_origin.z) + pixel);\n"
           "    uvec2 low_x, low_y, extent;\n"
           "    dsn_grid_tile_box(task_origin, task_column_step, task_row_step, first, size, low_x, low_y, "
           "extent);\n"
           "    dsn_tile_begin();\n"
           "    barrier();\n"
           "    if (task_kind == 1u)\n"
           "        dsn_lattice_tile_list(origin, size);\n"
           "    else\n"
           "        dsn_continuous_tile_list(low_x, low_y, extent);\n"
           "    barrier();\n"
           "    uvec2 x = dsn_add64(task_origin.xy, dsn_add64(dsn_multiply64(uvec2(pixel.x, 0u), "
           "task_column_step.xy),\n"
           "                                                 dsn_multiply64(uvec2(pixel.y, 0u), "
           "task_row_step.xy)));\n"
           "    uvec2 y = dsn_add64(task_origin.zw, dsn_add64(dsn_multiply64(uvec2(pixel.x, 0u), "
           "task_column_step.zw),\n"
           "                                                 dsn_multiply64(uvec2(pixel.y, 0u), "
           "task_row_step.zw)));\n"
           "    ivec3 value = task_kind == 1u ? dsn_lattice_tile_point_fixed(origin, size, p)\n"
           "                                  : dsn_continuous_tile_point_fixed(low_x, low_y, extent, x, "
           "y);\n"
           "    if (pixel.x >= task_width || pixel.y >= task_height) return;\n"
           "    uint index = pixel.y * task_width + pixel.x;\n"
           "    results[3u * index] = golden_convert(value, task_output);\n"
           "    results[3u * index + 1u] = uvec4(0u);\n"
           "    results[3u * index + 2u] = uvec4(0u);\n"
           "}\n";
}

/* GLSL ES 3.00 (fragment): noise and queries in integer textures, one fragment per value, the value and
   the two derivatives in three RGBA32UI targets. */
const char *const fullscreen_vertex_shader = "#version 300 es\n"
                                             "void main() {\n"
                                             "    gl_Position = vec4(float((gl_VertexID & 1) << 2) - 1.0, "
                                             "float((gl_VertexID & 2) << 1) - 1.0, 0.0, 1.0);\n"
                                             "}\n";

std::string fragment_shader(const headless_gl::Context &context, bool limbs) {
    return context.shader_preamble() + golden_defines(limbs) +
           "uniform highp usampler2D noise_texture;\n"
           "uniform highp usampler2D query_texture;\n"
           "uniform uint target_width;\n"
           "layout(location = 0) out uvec4 result_value;\n"
           "layout(location = 1) out uvec4 result_dx;\n"
           "layout(location = 2) out uvec4 result_dy;\n"
           "uvec4 golden_query(uint index, uint part) {\n"
           "    uint texel = 4u * index + part;\n"
           "    return texelFetch(query_texture, ivec2(int(texel & 1023u), int(texel >> 10u)), 0);\n"
           "}\n" +
           dsn_glsl +
           "uint dsn_word(uint index) {\n"
           "    uint word = dsn_word_base + index;\n"
           "    return texelFetch(noise_texture, ivec2(int(word & 1023u), int(word >> 10u)), 0).x;\n"
           "}\n" +
           kernel_glsl +
           "void main() {\n"
           "    uvec2 pixel = uvec2(gl_FragCoord.xy);\n"
           "    golden_evaluate(pixel.y * target_width + pixel.x, result_value, result_dx, result_dy);\n"
           "}\n";
}

class Runner {
  public:
    Runner(headless_gl::Context &context, bool limbs) : context_(context), gl_(context.gl) {
        if (context.api() == Api::gles30) {
            program_ = context.render_program(fullscreen_vertex_shader, fragment_shader(context, limbs));
            gl_.glGenVertexArrays(1, &vertex_array_);
        } else {
            program_ = context.compute_program(compute_shader(context, limbs));
            tile_program_ = context.compute_program(tile_shader(context, limbs));
        }
        gl_.glUseProgram(program_);
        context.check("program");
    }
    ~Runner() {
        release_noise();
        if (vertex_array_) gl_.glDeleteVertexArrays(1, &vertex_array_);
        gl_.glDeleteProgram(program_);
        if (tile_program_) gl_.glDeleteProgram(tile_program_);
    }

    void set_noise(const std::vector<uint32_t> &words) {
        release_noise();
        if (context_.api() == Api::gles30)
            noise_ = context_.word_texture(words, 1);
        else
            noise_ = context_.storage_buffer(words.data(), words.size() * 4);
    }

    /* result_words per value. */
    std::vector<uint32_t> run(const Task &task, const std::vector<uint32_t> &queries) {
        const bool tiled = tile_program_ != 0 && task.kind != task_queries && !task.gradient && !task.mix;
        current_ = tiled ? tile_program_ : program_;
        gl_.glUseProgram(current_);
        gl_.glUniform1ui(location("task_kind"), task.kind);
        gl_.glUniform1ui(location("task_output"), task.conversion);
        gl_.glUniform1ui(location("task_gradient"), task.gradient);
        gl_.glUniform1ui(location("task_mix"), task.mix);
        gl_.glUniform1ui(location("task_width"), task.width);
        const uint32_t *origin = task.origin ? task.origin : no_words;
        const uint32_t *column = task.column_step ? task.column_step : no_words;
        const uint32_t *row = task.row_step ? task.row_step : no_words;
        gl_.glUniform4ui(location("task_origin"), origin[0], origin[1], origin[2], origin[3]);
        gl_.glUniform4ui(location("task_column_step"), column[0], column[1], column[2], column[3]);
        gl_.glUniform4ui(location("task_row_step"), row[0], row[1], row[2], row[3]);
        std::vector<uint32_t> result(result_words * task.count);
        if (context_.api() == Api::gles30)
            render(task, queries, result);
        else
            dispatch(task, queries, result, tiled);
        return result;
    }

  private:
    GLint location(const char *name) { return gl_.glGetUniformLocation(current_, name); }

    void release_noise() {
        if (!noise_) return;
        if (context_.api() == Api::gles30)
            gl_.glDeleteTextures(1, &noise_);
        else
            gl_.glDeleteBuffers(1, &noise_);
        noise_ = 0;
    }

    void dispatch(const Task &task, const std::vector<uint32_t> &queries, std::vector<uint32_t> &result,
                  bool tiled) {
        GLuint query_buffer = context_.storage_buffer(queries.empty() ? no_words : queries.data(),
                                                      queries.empty() ? sizeof no_words : queries.size() * 4);
        GLuint result_buffer = context_.storage_buffer(nullptr, result.size() * 4);
        gl_.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, noise_);
        gl_.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, query_buffer);
        gl_.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, result_buffer);
        if (tiled) {
            const uint32_t height = task.count / task.width;
            gl_.glUniform1ui(location("task_height"), height);
            gl_.glDispatchCompute((task.width + tile_side - 1) / tile_side,
                                  (height + tile_side - 1) / tile_side, 1);
        } else {
            gl_.glUniform1ui(location("task_count"), task.count);
            gl_.glDispatchCompute((task.count + 63) / 64, 1, 1);
        }
        gl_.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        context_.check("dispatch");
        context_.read_buffer(result_buffer, result.data(), result.size() * 4);
        gl_.glDeleteBuffers(1, &query_buffer);
        gl_.glDeleteBuffers(1, &result_buffer);
    }

    void render(const Task &task, const std::vector<uint32_t> &queries, std::vector<uint32_t> &result) {
        const uint32_t width = task.count < 256 ? task.count : 256, height = (task.count + width - 1) / width;
        GLuint query_texture =
            context_.word_texture(queries.empty() ? std::vector<uint32_t>(query_words, 0u) : queries, 4);
        /* three targets: the value, dx, dy */
        GLuint targets[3] = {0, 0, 0}, framebuffer = 0;
        const GLenum attachments[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        gl_.glGenTextures(3, targets);
        gl_.glGenFramebuffers(1, &framebuffer);
        gl_.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        for (int part = 0; part < 3; part++) {
            gl_.glBindTexture(GL_TEXTURE_2D, targets[part]);
            gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            gl_.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32UI, static_cast<GLsizei>(width),
                             static_cast<GLsizei>(height), 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, nullptr);
            gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, attachments[part], GL_TEXTURE_2D, targets[part], 0);
        }
        gl_.glDrawBuffers(3, attachments);
        if (gl_.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("the RGBA32UI render targets are incomplete");
        gl_.glActiveTexture(GL_TEXTURE0);
        gl_.glBindTexture(GL_TEXTURE_2D, noise_);
        gl_.glActiveTexture(GL_TEXTURE1);
        gl_.glBindTexture(GL_TEXTURE_2D, query_texture);
        gl_.glActiveTexture(GL_TEXTURE0);
        gl_.glUniform1i(location("noise_texture"), 0);
        gl_.glUniform1i(location("query_texture"), 1);
        gl_.glUniform1ui(location("target_width"), width);
        gl_.glViewport(0, 0, static_cast<GLsizei>(width), static_cast<GLsizei>(height));
        gl_.glBindVertexArray(vertex_array_);
        gl_.glDrawArrays(GL_TRIANGLES, 0, 3);
        std::vector<uint32_t> pixels(4u * width * height);
        gl_.glPixelStorei(GL_PACK_ALIGNMENT, 4);
        for (uint32_t part = 0; part < 3; part++) {
            gl_.glReadBuffer(attachments[part]);
            gl_.glReadPixels(0, 0, static_cast<GLsizei>(width), static_cast<GLsizei>(height), GL_RGBA_INTEGER,
                             GL_UNSIGNED_INT, pixels.data());
            context_.check("render");
            for (uint32_t v = 0; v < task.count; v++)
                std::copy(pixels.begin() + static_cast<std::ptrdiff_t>(4 * v),
                          pixels.begin() + static_cast<std::ptrdiff_t>(4 * v + 4),
                          result.begin() + static_cast<std::ptrdiff_t>(result_words * v + 4 * part));
        }
        gl_.glBindFramebuffer(GL_FRAMEBUFFER, 0);
        gl_.glDeleteFramebuffers(1, &framebuffer);
        gl_.glDeleteTextures(3, targets);
        gl_.glDeleteTextures(1, &query_texture);
    }

    headless_gl::Context &context_;
    const headless_gl::Functions &gl_;
    GLuint program_ = 0, tile_program_ = 0, current_ = 0, vertex_array_ = 0, noise_ = 0;
};

/* Every request of each noise: its queries in one batch, each tile or grid on its own. */
void run_requests(Runner &runner) {
    if (recorder.noises.empty()) recorder.noises.push_back(std::vector<uint32_t>(no_words, no_words + 4));
    for (size_t noise = 0; noise < recorder.noises.size(); noise++) {
        runner.set_noise(recorder.noises[noise]);
        std::vector<size_t> batch;
        std::vector<uint32_t> queries;
        for (size_t r = 0; r < recorder.requests.size(); r++) {
            Request &request = recorder.requests[r];
            if (request.noise != noise) continue;
            if (request.kind == task_queries) {
                batch.push_back(r);
                queries.insert(queries.end(), request.query, request.query + query_words);
                continue;
            }
            Task task;
            task.kind = request.kind;
            task.conversion = request.conversion;
            task.gradient = request.gradient;
            task.mix = request.mix;
            task.width = request.width;
            task.count = request.width * request.height;
            task.origin = request.origin;
            task.column_step = request.column_step;
            task.row_step = request.row_step;
            request.result = runner.run(task, {});
        }
        if (batch.empty()) continue;
        Task task;
        task.count = static_cast<uint32_t>(batch.size());
        task.width = task.count;
        const std::vector<uint32_t> results = runner.run(task, queries);
        for (size_t b = 0; b < batch.size(); b++)
            recorder.requests[batch[b]].result.assign(
                results.begin() + static_cast<std::ptrdiff_t>(result_words * b),
                results.begin() + static_cast<std::ptrdiff_t>(result_words * (b + 1)));
    }
}

} // namespace gpu_golden

extern "C" void golden_write(const char *text) {
    if (gpu_golden::recorder.printing) fputs(text, stdout);
}

namespace {

const char *const usage =
    "usage: dsn-gpu-golden [--api gl45|gles31|gles30] [--limbs] [--cpu-mixes] [--cpu-surfaces]\n"
    "                      [--dump-shaders DIR] "
    "[--quiet]\n"
    "Runs the cross test's golden program with every evaluation done by include/dsn/dsn.glsl on the GPU\n"
    "(EGL surfaceless: llvmpipe when there is no GPU) and prints its lines (tests/cross/golden.txt).\n"
    "  --api gl45     OpenGL 4.5 core, GLSL 4.30 compute shader (default)\n"
    "  --api gles31   OpenGL ES 3.1, GLSL ES 3.10 compute shader\n"
    "  --api gles30   OpenGL ES 3.0, GLSL ES 3.00 fragment shader into an RGBA32UI target\n"
    "  --limbs        16-bit limb multiplications (the GLSL ES 3.00 code) on any API\n"
    "  --cpu-mixes    the mixes (m-* lines) from the C runtime instead of the shaders\n"
    "  --cpu-surfaces the surface noise (s-* lines) from the C runtime instead of the shaders\n"
    "  --dump-shaders DIR  write every API's shaders to DIR (golden-API.comp/.frag) and exit\n"
    "  --quiet        no renderer line on stderr\n";

void write_file(const std::string &path, const std::string &text) {
    FILE *file = fopen(path.c_str(), "wb");
    if (!file || fwrite(text.data(), 1, text.size(), file) != text.size() || fclose(file) != 0)
        throw std::runtime_error("cannot write " + path);
}

} // namespace

int main(int argc, char **argv) {
    using namespace gpu_golden;
    Api api = Api::gl45;
    bool limbs = false, quiet = false;
    std::string dump_directory;
    try {
        for (int i = 1; i < argc; i++) {
            const std::string argument = argv[i];
            if (argument == "--help" || argument == "-h") {
                fputs(usage, stdout);
                return 0;
            } else if (argument == "--api" && i + 1 < argc) {
                const std::string name = argv[++i];
                if (name == "gl45")
                    api = Api::gl45;
                else if (name == "gles31")
                    api = Api::gles31;
                else if (name == "gles30")
                    api = Api::gles30;
                else
                    throw std::runtime_error("--api: unknown API '" + name + "'");
            } else if (argument == "--limbs") {
                limbs = true;
            } else if (argument == "--cpu-mixes") {
                recorder.cpu_mixes = true;
            } else if (argument == "--cpu-surfaces") {
                recorder.cpu_surfaces = true;
            } else if (argument == "--quiet") {
                quiet = true;
            } else if (argument == "--dump-shaders" && i + 1 < argc) {
                dump_directory = argv[++i];
            } else {
                throw std::runtime_error("unknown argument '" + argument + "' (see --help)");
            }
        }
        if (!dump_directory.empty()) {
            for (Api each : {Api::gl45, Api::gles31, Api::gles30}) {
                headless_gl::Context context(each);
                const std::string name = dump_directory + "/golden-" + headless_gl::api_name(each);
                if (each == Api::gles30) {
                    write_file(name + ".frag", fragment_shader(context, false));
                    write_file(name + ".vert", fullscreen_vertex_shader);
                } else {
                    write_file(name + ".comp", compute_shader(context, false));
                    write_file(name + "-limbs.comp", compute_shader(context, true));
                    write_file(name + "-tiles.comp", tile_shader(context, false));
                }
            }
            return 0;
        }
        headless_gl::Context context(api);
        if (!quiet)
            fprintf(stderr, "dsn-gpu-golden: %s%s on %s\n", headless_gl::api_name(api),
                    limbs ? " (limbs)" : "", context.description().c_str());
        Runner runner(context, limbs);
        golden_main(); /* records */
        run_requests(runner);
        recorder.replaying = true;
        recorder.printing = true;
        const int status = golden_main();
        if (recorder.cursor != recorder.requests.size())
            throw std::runtime_error("the replay made fewer requests than the recording");
        return status;
    } catch (const std::exception &error) {
        fflush(stdout);
        fprintf(stderr, "dsn-gpu-golden: %s\n", error.what());
        return 1;
    }
}
