// dsn-render: renders a window of the spot noise of a .dsnt asset to a PNG or raw float32 file.
//
// The image is cut into blocks rendered by a pool of threads, each block by one call of the runtime
// (lattice tile, lattice per-point loop, or continuous grid tile), so the result does not depend on the
// block size or the thread count: windows rendered separately stitch exactly into the whole.
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "../../runtime/format_bytes.h"
#include "dsn/asset_writer.h"
#include "dsn/bake.h"
#include "dsn/dsn.h"

namespace {

const char *const usage =
    "usage: dsn-render A.dsnt -o OUT.png|OUT.f32 --size WxH [options]\n"
    "Renders the spot noise of asset A.dsnt over a window of W x H pixels.\n"
    "  --origin X,Y         top-left point in texels (default 0,0); integers in tile/point mode,\n"
    "                       any real number in continuous mode; values wrap modulo 2^32\n"
    "  --seed S             32-bit seed (default 0)\n"
    "  --impacts N          impacts per pixel (default: the asset's, 30 if none)\n"
    "  --period PXxPY       make the output periodic with that period (0 = not periodic on that axis)\n"
    "  --mode M             tile (default), point (per-point lattice, same bits as tile) or continuous\n"
    "  --scale F            continuous mode: magnification, one pixel steps 1/F texels (default 1)\n"
    "  --rotate DEG         continuous mode: rotation of the texture, counterclockwise (default 0)\n"
    "  --allow-lattice      continuous mode on a lattice-baked asset (its spectrum is then smoothed)\n"
    "  --no-color-transform use the identity colour transform\n"
    "  --threads N          worker threads (default: the number of cores)\n"
    "  --quiet              no progress or timing line on stderr\n"
    "OUT.png is 8-bit grey or RGB; OUT.f32 is raw little-endian float32, channels interleaved,\n"
    "row-major, top row first (values in exemplar units, 1.0 = white, not clamped).\n";

enum class Mode { tile, point, continuous };

struct Options {
    std::string asset_path, output_path;
    uint32_t width = 0, height = 0;
    std::string origin_x = "0", origin_y = "0";
    uint32_t seed = 0, impacts_q16 = 0, period_x = 0, period_y = 0, flags = 0;
    Mode mode = Mode::tile;
    double scale = 1.0, rotate_degrees = 0.0;
    unsigned threads = 0;
    bool quiet = false;
};

bool ends_with(const std::string &text, const std::string &suffix) {
    return text.size() >= suffix.size() &&
           text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

uint64_t parse_u64(const std::string &flag, const std::string &text, uint64_t high) {
    char *end = nullptr;
    errno = 0;
    unsigned long long value = std::strtoull(text.c_str(), &end, 10);
    if (text.empty() || text[0] == '-' || *end != '\0' || errno != 0 || value > high)
        throw std::runtime_error(flag + ": '" + text + "' is not an integer in [0, " + std::to_string(high) +
                                 "]");
    return value;
}

double parse_real(const std::string &flag, const std::string &text) {
    char *end = nullptr;
    double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(value))
        throw std::runtime_error(flag + ": '" + text + "' is not a finite number");
    return value;
}

// "AxB" or "A,B" -> the two halves.
std::pair<std::string, std::string> split_pair(const std::string &flag, const std::string &text,
                                               char separator) {
    size_t at = text.find(separator);
    if (at == std::string::npos || at == 0 || at + 1 == text.size())
        throw std::runtime_error(flag + ": expected two values separated by '" + separator + "', got '" +
                                 text + "'");
    return {text.substr(0, at), text.substr(at + 1)};
}

Options parse_options(int argc, char **argv) {
    Options options;
    bool size_given = false;
    for (int i = 1; i < argc; i++) {
        std::string flag = argv[i];
        if (flag == "--help" || flag == "-h") {
            std::fputs(usage, stdout);
            std::exit(0);
        }
        if (flag == "--quiet") {
            options.quiet = true;
            continue;
        }
        if (flag == "--allow-lattice") {
            options.flags |= DSN_FLAG_ALLOW_LATTICE_CONTINUOUS;
            continue;
        }
        if (flag == "--no-color-transform") {
            options.flags |= DSN_FLAG_NO_COLOR_TRANSFORM;
            continue;
        }
        if (flag.size() < 2 || flag[0] != '-') {
            if (!options.asset_path.empty()) throw std::runtime_error("more than one asset given: " + flag);
            options.asset_path = flag;
            continue;
        }
        if (i + 1 >= argc) throw std::runtime_error(flag + " needs a value (see --help)");
        std::string value = argv[++i];
        if (flag == "-o" || flag == "--output") {
            options.output_path = value;
        } else if (flag == "--size") {
            auto sides = split_pair(flag, value, 'x');
            options.width = static_cast<uint32_t>(parse_u64(flag, sides.first, DSN_TILE_MAX_SIDE));
            options.height = static_cast<uint32_t>(parse_u64(flag, sides.second, DSN_TILE_MAX_SIDE));
            if (options.width == 0 || options.height == 0)
                throw std::runtime_error("--size: sides must be >= 1");
            size_given = true;
        } else if (flag == "--origin") {
            auto origin = split_pair(flag, value, ',');
            options.origin_x = origin.first;
            options.origin_y = origin.second;
        } else if (flag == "--seed") {
            options.seed = static_cast<uint32_t>(parse_u64(flag, value, 0xFFFFFFFFu));
        } else if (flag == "--impacts") {
            double impacts = parse_real(flag, value);
            if (impacts * 65536.0 < DSN_IMPACTS_MIN_Q16 || impacts * 65536.0 > DSN_IMPACTS_MAX_Q16)
                throw std::runtime_error("--impacts must be within [1/16, 1024]");
            options.impacts_q16 = static_cast<uint32_t>(std::lround(impacts * 65536.0));
        } else if (flag == "--period") {
            auto period = split_pair(flag, value, 'x');
            options.period_x = static_cast<uint32_t>(parse_u64(flag, period.first, 0xFFFFFFFFu));
            options.period_y = static_cast<uint32_t>(parse_u64(flag, period.second, 0xFFFFFFFFu));
        } else if (flag == "--mode") {
            if (value == "tile")
                options.mode = Mode::tile;
            else if (value == "point")
                options.mode = Mode::point;
            else if (value == "continuous")
                options.mode = Mode::continuous;
            else
                throw std::runtime_error("--mode must be tile, point or continuous");
        } else if (flag == "--scale") {
            options.scale = parse_real(flag, value);
            if (!(options.scale >= 1.0 / 65536 && options.scale <= 65536))
                throw std::runtime_error("--scale must be within [1/65536, 65536]");
        } else if (flag == "--rotate") {
            options.rotate_degrees = parse_real(flag, value);
        } else if (flag == "--threads") {
            options.threads = static_cast<unsigned>(parse_u64(flag, value, 256));
            if (options.threads == 0) throw std::runtime_error("--threads must be >= 1");
        } else {
            throw std::runtime_error("unknown option " + flag + " (see --help)");
        }
    }
    if (options.asset_path.empty()) throw std::runtime_error("no asset given (see --help)");
    if (options.output_path.empty()) throw std::runtime_error("no output given: -o OUT.png|OUT.f32");
    if (!ends_with(options.output_path, ".png") && !ends_with(options.output_path, ".f32"))
        throw std::runtime_error("the output must end in .png or .f32: " + options.output_path);
    if (!size_given) throw std::runtime_error("no size given: --size WxH");
    if (options.mode != Mode::continuous && (options.scale != 1.0 || options.rotate_degrees != 0.0))
        throw std::runtime_error("--scale and --rotate need --mode continuous");
    return options;
}

std::vector<unsigned char> read_file(const std::string &path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    if (file.bad()) throw std::runtime_error("cannot read " + path);
    return bytes;
}

// A lattice origin: an integer, taken modulo 2^32 (so -1 and 4294967295 are the same point).
int32_t lattice_coordinate(const std::string &text) {
    char *end = nullptr;
    errno = 0;
    long long value = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0 || value < -4294967296LL || value > 4294967295LL)
        throw std::runtime_error("--origin: '" + text +
                                 "' is not an integer (use --mode continuous for reals)");
    uint32_t wrapped = static_cast<uint32_t>(static_cast<unsigned long long>(value));
    return wrapped >= 0x80000000u ? static_cast<int32_t>(wrapped - 0x80000000u) + INT32_MIN
                                  : static_cast<int32_t>(wrapped);
}

int64_t q32_step(double texels) { return static_cast<int64_t>(std::llround(texels * 4294967296.0)); }

// Pixel (i, j) samples origin + (i cos a - j sin a, i sin a + j cos a) / scale (a = the rotation).
dsn_grid continuous_grid(const Options &options) {
    const double radians = options.rotate_degrees * 3.14159265358979323846 / 180.0;
    const double cosine = std::cos(radians) / options.scale, sine = std::sin(radians) / options.scale;
    dsn_grid grid;
    grid.origin_x = dsn_coordinate_from_double(parse_real("--origin", options.origin_x));
    grid.origin_y = dsn_coordinate_from_double(parse_real("--origin", options.origin_y));
    grid.column_step_x = q32_step(cosine);
    grid.column_step_y = q32_step(sine);
    grid.row_step_x = q32_step(-sine);
    grid.row_step_y = q32_step(cosine);
    return grid;
}

// What every worker shares: the configured noise and where each block goes.
struct Job {
    const dsn_noise *noise;
    Mode mode;
    int32_t lattice_x0, lattice_y0;
    dsn_grid grid;
    uint32_t width, height, channels, block;
};

// The fixed-point values of the block at pixel (bx, by), bw x bh, into `values`.
void render_block(const Job &job, uint32_t bx, uint32_t by, uint32_t bw, uint32_t bh,
                  std::vector<int32_t> &values, std::vector<unsigned char> &scratch) {
    int err = DSN_OK;
    if (job.mode == Mode::tile) {
        int32_t x0 = static_cast<int32_t>(static_cast<uint32_t>(job.lattice_x0) + bx);
        int32_t y0 = static_cast<int32_t>(static_cast<uint32_t>(job.lattice_y0) + by);
        scratch.resize(dsn_lattice_tile_scratch_size(job.noise, bw, bh));
        err =
            dsn_lattice_tile_fixed(job.noise, x0, y0, bw, bh, values.data(), scratch.data(), scratch.size());
    } else if (job.mode == Mode::point) {
        for (uint32_t j = 0; j < bh; j++)
            for (uint32_t i = 0; i < bw; i++) {
                int32_t x = static_cast<int32_t>(static_cast<uint32_t>(job.lattice_x0) + bx + i);
                int32_t y = static_cast<int32_t>(static_cast<uint32_t>(job.lattice_y0) + by + j);
                dsn_lattice_point_fixed(job.noise, x, y, &values[(j * bw + i) * job.channels]);
            }
    } else {
        // The block's own grid: the whole grid's origin moved by (bx, by) steps, in modulo-2^64 arithmetic.
        dsn_grid grid = job.grid;
        auto advance = [](int64_t origin, int64_t step, uint32_t count) {
            return static_cast<int64_t>(static_cast<uint64_t>(origin) + static_cast<uint64_t>(step) * count);
        };
        grid.origin_x = advance(advance(grid.origin_x, grid.column_step_x, bx), grid.row_step_x, by);
        grid.origin_y = advance(advance(grid.origin_y, grid.column_step_y, bx), grid.row_step_y, by);
        scratch.resize(dsn_continuous_tile_scratch_size(job.noise, &grid, bw, bh));
        err = dsn_continuous_tile_fixed(job.noise, &grid, bw, bh, values.data(), scratch.data(),
                                        scratch.size());
    }
    if (err != DSN_OK) throw std::runtime_error(dsn_error_message(err));
}

// Renders the whole window into `pixels` (one of u8 or float, per `to_u8`) with `thread_count` workers.
template <typename Pixel>
void render(const Job &job, unsigned thread_count, bool show_progress, std::vector<Pixel> &pixels,
            Pixel (*convert)(int32_t)) {
    const uint32_t blocks_x = (job.width + job.block - 1) / job.block;
    const uint32_t blocks_y = (job.height + job.block - 1) / job.block;
    const uint32_t block_count = blocks_x * blocks_y;
    std::atomic<uint32_t> next_block(0), done_blocks(0);
    std::mutex report_lock;
    std::string failure;
    auto worker = [&]() {
        std::vector<int32_t> values(static_cast<size_t>(job.block) * job.block * job.channels);
        std::vector<unsigned char> scratch;
        for (uint32_t index; (index = next_block++) < block_count;) {
            const uint32_t bx = index % blocks_x * job.block, by = index / blocks_x * job.block;
            const uint32_t bw = std::min(job.block, job.width - bx),
                           bh = std::min(job.block, job.height - by);
            try {
                render_block(job, bx, by, bw, bh, values, scratch);
            } catch (const std::exception &error) {
                std::lock_guard<std::mutex> guard(report_lock);
                failure = error.what();
                next_block = block_count;
                return;
            }
            for (uint32_t j = 0; j < bh; j++) {
                Pixel *row = &pixels[((static_cast<size_t>(by) + j) * job.width + bx) * job.channels];
                const int32_t *source = &values[static_cast<size_t>(j) * bw * job.channels];
                for (uint32_t k = 0; k < bw * job.channels; k++) row[k] = convert(source[k]);
            }
            uint32_t done = ++done_blocks;
            if (show_progress && done * 100 / block_count != (done - 1) * 100 / block_count) {
                std::lock_guard<std::mutex> guard(report_lock);
                std::fprintf(stderr, "\rdsn-render: %3u%%", done * 100 / block_count);
                if (done == block_count) std::fputc('\n', stderr);
            }
        }
    };
    std::vector<std::thread> threads;
    for (unsigned t = 1; t < thread_count; t++) threads.emplace_back(worker);
    worker();
    for (std::thread &thread : threads) thread.join();
    if (!failure.empty()) throw std::runtime_error(failure);
}

std::vector<unsigned char> encode_png(const std::vector<uint8_t> &pixels, uint32_t width, uint32_t height,
                                      uint32_t channels) {
    return dsn::encode_png(static_cast<int>(width), static_cast<int>(height), static_cast<int>(channels),
                           pixels.data());
}

// Raw little-endian float32, whatever the host's byte order.
std::vector<unsigned char> encode_f32(const std::vector<float> &values) {
    std::vector<unsigned char> bytes(values.size() * 4);
    for (size_t i = 0; i < values.size(); i++) {
        uint32_t bits;
        std::memcpy(&bits, &values[i], 4);
        dsn_write_u32le(&bytes[i * 4], bits);
    }
    return bytes;
}

void run(const Options &options) {
    std::vector<unsigned char> asset_bytes = read_file(options.asset_path);
    dsn_asset asset;
    int err = dsn_asset_load(&asset, asset_bytes.data(), asset_bytes.size());
    if (err != DSN_OK) throw std::runtime_error(options.asset_path + ": " + dsn_error_message(err));
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = options.seed;
    config.impacts_q16 = options.impacts_q16;
    config.period_x = options.period_x;
    config.period_y = options.period_y;
    config.flags = options.flags;
    dsn_noise noise;
    err = dsn_noise_init(&noise, &asset, &config);
    if (err != DSN_OK) throw std::runtime_error(dsn_error_message(err));
    if (options.mode == Mode::continuous && (err = dsn_continuous_check(&noise)) != DSN_OK)
        throw std::runtime_error(options.asset_path + ": " + dsn_error_message(err) +
                                 " (see --allow-lattice)");

    Job job{&noise, options.mode, 0, 0, {}, options.width, options.height, asset.channels, 128};
    if (options.mode == Mode::continuous)
        job.grid = continuous_grid(options);
    else
        job.lattice_x0 = lattice_coordinate(options.origin_x),
        job.lattice_y0 = lattice_coordinate(options.origin_y);

    const size_t value_count = static_cast<size_t>(options.width) * options.height * asset.channels;
    unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    bool show_progress =
        !options.quiet && static_cast<uint64_t>(options.width) * options.height >= (1u << 22);
    auto start = std::chrono::steady_clock::now();
    auto elapsed = [&start]() {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    double seconds = 0;
    std::vector<unsigned char> file_bytes;
    if (ends_with(options.output_path, ".png")) {
        std::vector<uint8_t> pixels(value_count);
        render<uint8_t>(job, threads, show_progress, pixels, dsn_fixed_to_u8);
        seconds = elapsed();
        file_bytes = encode_png(pixels, options.width, options.height, asset.channels);
    } else {
        std::vector<float> pixels(value_count);
        render<float>(job, threads, show_progress, pixels, dsn_fixed_to_float);
        seconds = elapsed();
        file_bytes = encode_f32(pixels);
    }
    dsn::write_file_atomically(options.output_path, file_bytes);
    if (!options.quiet)
        std::fprintf(stderr, "dsn-render: %ux%u, %u channel(s), %u thread(s): %.3f s, %.1f Mpixel/s -> %s\n",
                     options.width, options.height, asset.channels, threads, seconds,
                     options.width * static_cast<double>(options.height) / seconds / 1e6,
                     options.output_path.c_str());
}

} // namespace

int main(int argc, char **argv) {
    try {
        run(parse_options(argc, argv));
    } catch (const std::bad_alloc &) {
        std::fprintf(stderr, "dsn-render: out of memory (try a smaller --size)\n");
        return 1;
    } catch (const std::exception &error) {
        std::fprintf(stderr, "dsn-render: %s\n", error.what());
        return 1;
    }
    return 0;
}
