// dsn-render: renders a window of the spot noise of a .dsnt asset to a PNG or raw float32 file.
//
// The image is cut into strips of whole rows rendered by a pool of threads, each strip by one call of the
// runtime (lattice tile, lattice per-point loop, continuous grid tile, or filtered grid tile) straight into
// the image, so the
// result does not depend on the strip size or the thread count: windows rendered separately stitch
// exactly into the whole.
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <sys/mman.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "asset_file.h"
#include "command_line.h"
#include "dsn/bake.h"
#include "dsn/dsn.h"
#include "file_output.h"
#include "mix_inputs.h"
#include "png_output.h"
#include "render_window.h"
#include "runtime/setup/format_bytes.h"

namespace {

// The usage, around the asset size limit, which comes from the code that applies it
// (dsn::largest_asset_bytes) rather than from a copy of its value.
const char *const kUsageHead =
    "usage: dsn-render A.dsnt -o OUT.png|OUT.f32 --size WxH [options]\n"
    "Renders the spot noise of asset A.dsnt over a window of W x H pixels.\n"
    "  -o, --output OUT     the image to write (atomically): OUT.png or OUT.f32\n"
    "  --size WxH           the window, 1..65536 pixels per side and at most 67108864 pixels in all\n"
    "                       (8192x8192); render larger images as windows (--origin), which stitch\n"
    "                       exactly\n"
    "  --origin X,Y         top-left point in texels (default 0,0); integers in tile/point mode,\n"
    "                       any real number in continuous mode; values wrap modulo 2^32\n"
    "  --seed S             32-bit seed (default 0)\n"
    "  --impacts N          impacts per pixel (default: the asset's, 30 if none)\n"
    "  --period PXxPY       make the output periodic with that period (0 = not periodic on that axis)\n"
    "  --mode M             continuous (the noise at real points: zoom, rotation, filtering), tile\n"
    "                       or point (the integer lattice; point: per-point calls, the same bits as\n"
    "                       tile). Default: the asset's own, continuous for a bilinear bake (dsn-bake's\n"
    "                       default) and tile for a lattice bake (dsn-bake --interpolation lattice);\n"
    "                       continuous whenever --scale, --rotate, --filter or --max-taps is given.\n"
    "                       A lattice bake is refused in continuous mode, and a bilinear bake in\n"
    "                       tile/point mode when it carries no lattice texton (dsn-bake before\n"
    "                       format 1.3): the line says what to do\n"
    "  --scale F|FX,FY      continuous mode: magnification, one pixel steps 1/F texels (default 1);\n"
    "                       FX,FY: 1/FX texels along the window's x, 1/FY along its y (before\n"
    "                       --rotate): a slanted view, whose footprint --filter aniso follows\n"
    "  --rotate DEG         continuous mode: rotation of the texture, counterclockwise (default 0);\n"
    "                       taken modulo 360 exactly, so any finite angle means what it says\n"
    "  --filter F           continuous mode: how each pixel reads the noise. aniso (default): filtered\n"
    "                       over the pixel's footprint (its grid steps), up to --max-taps taps along\n"
    "                       the longer step; iso: one tap, sized by the longer step; none: one\n"
    "                       unfiltered sample, which aliases when --scale is below 1. Filtered pixels\n"
    "                       fade to the exact mean colour as the scale falls; at --scale 1 and above\n"
    "                       they are the unfiltered bits\n"
    "  --max-taps N         --filter aniso: at most N taps, 1..16 (default 16; rounded down to a\n"
    "                       power of two)\n"
    "  --allow-lattice      continuous mode on a lattice-baked asset anyway (its spectrum is then\n"
    "                       smoothed; the fix is to bake with dsn-bake --interpolation bilinear, the\n"
    "                       default)\n"
    "  --no-color-transform use the identity colour transform\n";
// then dsn::mix_usage (the mix is read in every mode, filtered too), then
const char *const kUsageOptions =
    "  --threads N          worker threads, 1..256 (default: the number of cores)\n"
    "  --time-limit S       refuse a render estimated to take more than S seconds (default 600;\n"
    "                       0 = no limit): a few probe pixels spread over the window are rendered\n"
    "                       first, timed, and extrapolated to the whole window and the threads (an\n"
    "                       asset's points can cost up to ~20 ms each)\n"
    "  --quiet              no progress or summary line\n"
    "  -h, --help           this help\n"
    "  --version            the version\n"
    "OUT.png is 8-bit grey or RGB; OUT.f32 is raw little-endian float32, channels interleaved,\n"
    "row-major, top row first (values in exemplar units, 1.0 = white, not clamped).\n"
    "Numbers are decimal (no hexadecimal, no inf or nan).\n"
    "Limits: the asset is read up to ";
const char *const kUsageTail =
    " KiB), the largest a .dsnt can be (its\n"
    "texton and every section that the format knows at their largest); the output may not be the asset.\n"
    "Memory: about 4 bytes per pixel and channel for .f32, about 3 for .png (8192x8192 RGB: 768 MiB\n"
    "for .f32, about 600 MiB for .png).\n"
    "Output: the summary line (size, time, speed, file) on stdout; progress of a large render on\n"
    "stderr, redrawn on a terminal, at most one line per 10% on a file or pipe.\n"
    "Flags take their value as --flag value or --flag=value. Errors are one line on stderr and write\n"
    "nothing: exit 2 for a usage mistake (the line ends with \"(see --help)\"), exit 1 when rendering\n"
    "fails (unreadable or invalid asset, an asset the mode cannot read, a configuration the runtime\n"
    "refuses as too costly, a render estimated over --time-limit, cannot write).\n";

std::string usage() {
    const size_t limit = dsn::largest_asset_bytes();
    return kUsageHead + std::string(dsn::mix_usage) + kUsageOptions + std::to_string(limit) + " bytes (" +
           std::to_string(limit / 1024) + kUsageTail;
}

enum class Mode { tile, point, continuous };
enum class Filter { none, iso, aniso };

// The largest window rendered in one run: its pixels are held in memory, and stb's PNG writer counts
// bytes in an int.
const uint64_t kMaxRenderPixels = uint64_t(1) << 26;

struct Options {
    std::string asset_path, output_path;
    uint32_t width = 0, height = 0;
    std::string origin_x = "0", origin_y = "0";
    uint32_t seed = 0, impacts_q16 = 0, period_x = 0, period_y = 0, flags = 0;
    Mode mode = Mode::tile;
    bool mode_known = false;       // --mode given, or implied by a continuous-only flag; else the asset's own
    Filter filter = Filter::aniso; // continuous mode only
    uint32_t max_taps = 16;
    bool filter_given = false, max_taps_given = false, scale_given = false, rotate_given = false;
    double scale_x = 1.0, scale_y = 1.0, rotate_degrees = 0.0;
    unsigned threads = 0;
    double time_limit = 600; // seconds; 0: no limit
    bool quiet = false;
    dsn::MixOptions mix;
};

// "AxB" or "A,B" -> the two halves.
std::pair<std::string, std::string> split_pair(const std::string &flag, const std::string &text,
                                               char separator) {
    size_t at = text.find(separator);
    if (at == std::string::npos || at == 0 || at + 1 == text.size())
        throw dsn::UsageError(flag + " needs two values separated by '" + separator + "', not '" + text +
                              "'");
    return {text.substr(0, at), text.substr(at + 1)};
}

Options parse_options(dsn::CommandLine &command_line) {
    Options options;
    bool size_given = false;
    while (command_line.next()) {
        const std::string flag = command_line.current();
        if (command_line.is("--quiet")) {
            command_line.no_value();
            options.quiet = true;
        } else if (command_line.is("--allow-lattice")) {
            command_line.no_value();
            options.flags |= DSN_FLAG_ALLOW_LATTICE_CONTINUOUS;
        } else if (command_line.is("--no-color-transform")) {
            command_line.no_value();
            options.flags |= DSN_FLAG_NO_COLOR_TRANSFORM;
        } else if (dsn::parse_mix_flag(command_line, options.mix)) {
        } else if (command_line.is_positional()) {
            if (!options.asset_path.empty()) throw dsn::UsageError("more than one asset given: " + flag);
            options.asset_path = flag;
        } else if (command_line.is("-o") || command_line.is("--output")) {
            options.output_path = command_line.path_value();
        } else if (command_line.is("--size")) {
            auto sides = split_pair(flag, command_line.value(), 'x');
            options.width =
                static_cast<uint32_t>(dsn::parse_integer(flag, sides.first, 1, DSN_TILE_MAX_SIDE));
            options.height =
                static_cast<uint32_t>(dsn::parse_integer(flag, sides.second, 1, DSN_TILE_MAX_SIDE));
            size_given = true;
        } else if (command_line.is("--origin")) {
            auto origin = split_pair(flag, command_line.value(), ',');
            options.origin_x = origin.first;
            options.origin_y = origin.second;
        } else if (command_line.is("--seed")) {
            options.seed = static_cast<uint32_t>(dsn::parse_integer(command_line, 0, 0xFFFFFFFFll));
        } else if (command_line.is("--impacts")) {
            const double impacts = dsn::parse_real(flag, command_line.value());
            if (impacts * 65536.0 < DSN_IMPACTS_MIN_Q16 || impacts * 65536.0 > DSN_IMPACTS_MAX_Q16)
                throw dsn::UsageError("--impacts must be within [1/16, 1024]");
            options.impacts_q16 = static_cast<uint32_t>(std::lround(impacts * 65536.0));
        } else if (command_line.is("--period")) {
            auto period = split_pair(flag, command_line.value(), 'x');
            options.period_x = static_cast<uint32_t>(dsn::parse_integer(flag, period.first, 0, 0xFFFFFFFFll));
            options.period_y =
                static_cast<uint32_t>(dsn::parse_integer(flag, period.second, 0, 0xFFFFFFFFll));
        } else if (command_line.is("--mode")) {
            const std::string mode = command_line.value();
            if (mode == "tile")
                options.mode = Mode::tile;
            else if (mode == "point")
                options.mode = Mode::point;
            else if (mode == "continuous")
                options.mode = Mode::continuous;
            else
                throw dsn::UsageError("--mode must be tile, point or continuous, not '" + mode + "'");
            options.mode_known = true;
        } else if (command_line.is("--scale")) {
            const std::string scale = command_line.value();
            if (scale.find(',') == std::string::npos) {
                options.scale_x = options.scale_y = dsn::parse_real(flag, scale);
            } else {
                auto scales = split_pair(flag, scale, ',');
                options.scale_x = dsn::parse_real(flag, scales.first);
                options.scale_y = dsn::parse_real(flag, scales.second);
            }
            for (double one_scale : {options.scale_x, options.scale_y})
                if (!(one_scale >= 1.0 / 65536 && one_scale <= 65536))
                    throw dsn::UsageError("--scale must be within [1/65536, 65536]");
            options.scale_given = true;
        } else if (command_line.is("--filter")) {
            const std::string filter = command_line.value();
            if (filter == "none")
                options.filter = Filter::none;
            else if (filter == "iso")
                options.filter = Filter::iso;
            else if (filter == "aniso")
                options.filter = Filter::aniso;
            else
                throw dsn::UsageError("--filter must be none, iso or aniso, not '" + filter + "'");
            options.filter_given = true;
        } else if (command_line.is("--max-taps")) {
            options.max_taps = static_cast<uint32_t>(dsn::parse_integer(command_line, 1, 16));
            options.max_taps_given = true;
        } else if (command_line.is("--rotate")) {
            options.rotate_degrees = dsn::parse_real(flag, command_line.value());
            options.rotate_given = true;
        } else if (command_line.is("--time-limit")) {
            options.time_limit = dsn::parse_real(flag, command_line.value());
            if (!(options.time_limit >= 0 && options.time_limit <= 1e9))
                throw dsn::UsageError("--time-limit must be within [0, 1e9] seconds (0: no limit)");
        } else if (command_line.is("--threads")) {
            options.threads = static_cast<unsigned>(dsn::parse_integer(command_line, 1, 256));
        } else {
            command_line.unknown();
        }
    }
    if (options.asset_path.empty()) throw dsn::UsageError("no asset given");
    if (options.output_path.empty()) throw dsn::UsageError("no output given (-o OUT.png|OUT.f32)");
    if (!dsn::ends_with(options.output_path, ".png") && !dsn::ends_with(options.output_path, ".f32"))
        throw dsn::UsageError("the output must end in .png or .f32: " + options.output_path);
    if (!size_given) throw dsn::UsageError("no size given (--size WxH)");
    if (uint64_t(options.width) * options.height > kMaxRenderPixels)
        throw dsn::UsageError("--size " + std::to_string(options.width) + "x" +
                              std::to_string(options.height) + " is more than the limit of " +
                              std::to_string(kMaxRenderPixels) +
                              " pixels (8192x8192); render it as windows with --origin");
    std::vector<dsn::NamedPath> inputs = {{"the input asset", options.asset_path}};
    dsn::check_mix_options(options.mix, inputs);
    dsn::check_outputs(inputs, {{"-o", options.output_path}});
    const char *continuous_flag = options.scale_given      ? "--scale"
                                  : options.rotate_given   ? "--rotate"
                                  : options.filter_given   ? "--filter"
                                  : options.max_taps_given ? "--max-taps"
                                                           : nullptr;
    if (continuous_flag && options.mode_known && options.mode != Mode::continuous)
        throw dsn::UsageError(std::string(continuous_flag) + " reads the continuous mode, not --mode " +
                              (options.mode == Mode::tile ? "tile" : "point") +
                              " (the lattice is neither scaled, rotated nor filtered): leave --mode out");
    if (continuous_flag) options.mode = Mode::continuous, options.mode_known = true;
    if (options.max_taps_given && options.filter != Filter::aniso)
        throw dsn::UsageError("--max-taps needs --filter aniso");
    // A mode still unknown follows the asset, read later: its origin is checked again then.
    if (!options.mode_known || options.mode == Mode::continuous) {
        dsn::parse_real("--origin", options.origin_x);
        dsn::parse_real("--origin", options.origin_y);
    } else {
        dsn::lattice_origin(options.origin_x);
        dsn::lattice_origin(options.origin_y);
    }
    return options;
}

// The mode a render reads `asset` with: the one given or implied on the command line, else the asset's
// own (what it was baked for). Throws, with what to do, where that mode cannot read the asset.
Mode render_mode(const Options &options, const dsn_asset &asset) {
    const bool bilinear = asset.interpolation == DSN_INTERPOLATION_BILINEAR;
    const Mode mode = options.mode_known ? options.mode : bilinear ? Mode::continuous : Mode::tile;
    const std::string &path = options.asset_path;
    if (mode == Mode::continuous && !bilinear && (options.flags & DSN_FLAG_ALLOW_LATTICE_CONTINUOUS) == 0)
        throw std::runtime_error(
            path + " was baked for the lattice: re-bake it with dsn-bake --interpolation "
                   "bilinear (the default) to read it in continuous mode, or use --mode tile|point");
    if (mode != Mode::continuous && bilinear && asset.lattice_texton == nullptr)
        throw std::runtime_error(path + " was baked by an older dsn-bake for bilinear reads only: re-bake it "
                                        "to read it on the lattice, or use --mode continuous");
    if (mode != Mode::continuous && !options.mode_known) {
        dsn::lattice_origin(options.origin_x); // the asset chose the lattice: integers only
        dsn::lattice_origin(options.origin_y);
    }
    return mode;
}

// What every worker shares: the configured noise, where the image lies, and its cut into strips.
struct Job {
    const dsn_noise *noise;
    Mode mode;
    int32_t lattice_x0, lattice_y0;
    dsn_grid grid;
    uint32_t width, height, channels, strip_rows;
    uint32_t max_taps;            // continuous mode: 0 unfiltered, else filtered with at most that many taps
    const dsn_mix *mix = nullptr; // --mix: the mix and its weights, read instead of `noise`
    const dsn_mix_control *control = nullptr;
};

// Memory mapped but not touched: it is not zeroed first, and each worker faults in the pages it writes;
// on Linux with transparent huge pages, in 2 MB pages (faults of 4 KB pages cost here about as much as
// computing the noise in them). For the output image and the workers' scratch.
class MappedMemory {
  public:
    explicit MappedMemory(size_t bytes) : bytes_(std::max<size_t>(bytes, 1)) {
        void *mapped = mmap(nullptr, bytes_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (mapped == MAP_FAILED) throw std::runtime_error("out of memory");
#ifdef MADV_HUGEPAGE
        madvise(mapped, bytes_, MADV_HUGEPAGE); // advice only: failing it changes nothing
#endif
        memory_ = mapped;
    }
    ~MappedMemory() { munmap(memory_, bytes_); }
    MappedMemory(const MappedMemory &) = delete;
    MappedMemory &operator=(const MappedMemory &) = delete;
    void *data() const { return memory_; }
    size_t size() const { return bytes_; }

  private:
    size_t bytes_;
    void *memory_ = nullptr;
};

// A worker's scratch: mapped once at the size the first strip needs, remapped only to grow.
class Scratch {
  public:
    void *reserve(size_t bytes) {
        if (!memory_ || memory_->size() < bytes) memory_.reset(new MappedMemory(bytes));
        return memory_->data();
    }

  private:
    std::unique_ptr<MappedMemory> memory_;
};

// The runtime's calls for each output type: the values come converted from the runtime (the same
// values as dsn_fixed_to_u8 / dsn_fixed_to_float of the fixed ones), written straight into the image.
int lattice_tile(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                 uint8_t *out, void *scratch, size_t scratch_size) {
    return dsn_lattice_tile_u8(noise, x0, y0, width, height, out, scratch, scratch_size);
}
int lattice_tile(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height, float *out,
                 void *scratch, size_t scratch_size) {
    return dsn_lattice_tile_float(noise, x0, y0, width, height, out, scratch, scratch_size);
}
void lattice_point(const dsn_noise *noise, int32_t x, int32_t y, uint8_t *out) {
    dsn_lattice_point_u8(noise, x, y, out);
}
void lattice_point(const dsn_noise *noise, int32_t x, int32_t y, float *out) {
    dsn_lattice_point_float(noise, x, y, out);
}
int continuous_tile(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height,
                    uint8_t *out, void *scratch, size_t scratch_size) {
    return dsn_continuous_tile_u8(noise, grid, width, height, out, scratch, scratch_size);
}
int continuous_tile(const dsn_noise *noise, const dsn_grid *grid, uint32_t width, uint32_t height, float *out,
                    void *scratch, size_t scratch_size) {
    return dsn_continuous_tile_float(noise, grid, width, height, out, scratch, scratch_size);
}
int filtered_tile(const dsn_noise *noise, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                  uint32_t height, uint8_t *out, void *scratch, size_t scratch_size) {
    return dsn_filtered_tile_u8(noise, grid, max_taps, width, height, out, scratch, scratch_size);
}
int filtered_tile(const dsn_noise *noise, const dsn_grid *grid, uint32_t max_taps, uint32_t width,
                  uint32_t height, float *out, void *scratch, size_t scratch_size) {
    return dsn_filtered_tile_float(noise, grid, max_taps, width, height, out, scratch, scratch_size);
}

// Rows first_row .. first_row + rows - 1 of the image, whole rows, into `out` (their place in the image:
// a strip of whole rows is contiguous there, so the runtime writes the final pixels with no copy).
void store_values(const std::vector<int32_t> &values, uint8_t *out) {
    for (size_t i = 0; i < values.size(); i++) out[i] = dsn_fixed_to_u8(values[i]);
}
void store_values(const std::vector<int32_t> &values, float *out) {
    for (size_t i = 0; i < values.size(); i++) out[i] = dsn_fixed_to_float(values[i]);
}

// A strip of a mix: the runtime's fixed-point tile (lattice or the continuous grid), then converted.
template <typename Pixel>
int render_mix_strip(const Job &job, uint32_t first_row, const dsn_grid &grid, uint32_t rows, Pixel *out,
                     Scratch &scratch) {
    std::vector<int32_t> values(static_cast<size_t>(job.width) * rows * job.channels);
    int err;
    if (job.mode == Mode::continuous && job.max_taps == 0) {
        const size_t size = dsn_mix_continuous_tile_scratch_size(job.mix, &grid, job.width, rows);
        err = dsn_mix_continuous_tile_fixed(job.mix, job.control, &grid, job.width, rows, values.data(),
                                            scratch.reserve(size), size);
    } else if (job.mode == Mode::continuous) {
        const size_t size = dsn_mix_filtered_tile_scratch_size(job.mix, &grid, job.max_taps, job.width, rows);
        err = dsn_mix_filtered_tile_fixed(job.mix, job.control, &grid, job.max_taps, job.width, rows,
                                          values.data(), scratch.reserve(size), size);
    } else {
        const int32_t y0 = static_cast<int32_t>(static_cast<uint32_t>(job.lattice_y0) + first_row);
        const size_t size = dsn_mix_lattice_tile_scratch_size(job.mix, job.width, rows);
        err = dsn_mix_lattice_tile_fixed(job.mix, job.control, job.lattice_x0, y0, job.width, rows,
                                         values.data(), scratch.reserve(size), size);
    }
    store_values(values, out);
    return err;
}

template <typename Pixel>
void render_strip(const Job &job, uint32_t first_row, uint32_t rows, Pixel *out, Scratch &scratch) {
    int err = DSN_OK;
    if (job.mix != nullptr) {
        dsn_grid grid = job.grid; // the strip's own grid: moved by first_row rows, modulo 2^64
        grid.origin_x = static_cast<int64_t>(static_cast<uint64_t>(grid.origin_x) +
                                             static_cast<uint64_t>(grid.row_step_x) * first_row);
        grid.origin_y = static_cast<int64_t>(static_cast<uint64_t>(grid.origin_y) +
                                             static_cast<uint64_t>(grid.row_step_y) * first_row);
        err = render_mix_strip(job, first_row, grid, rows, out, scratch);
    } else if (job.mode == Mode::tile) {
        int32_t y0 = static_cast<int32_t>(static_cast<uint32_t>(job.lattice_y0) + first_row);
        const size_t size = dsn_lattice_tile_scratch_size(job.noise, job.width, rows);
        err = lattice_tile(job.noise, job.lattice_x0, y0, job.width, rows, out, scratch.reserve(size), size);
    } else if (job.mode == Mode::point) {
        for (uint32_t j = 0; j < rows; j++)
            for (uint32_t i = 0; i < job.width; i++) {
                int32_t x = static_cast<int32_t>(static_cast<uint32_t>(job.lattice_x0) + i);
                int32_t y = static_cast<int32_t>(static_cast<uint32_t>(job.lattice_y0) + first_row + j);
                lattice_point(job.noise, x, y, out + (static_cast<size_t>(j) * job.width + i) * job.channels);
            }
    } else {
        // The strip's own grid: the whole grid's origin moved by first_row rows, modulo 2^64.
        dsn_grid grid = job.grid;
        grid.origin_x = static_cast<int64_t>(static_cast<uint64_t>(grid.origin_x) +
                                             static_cast<uint64_t>(grid.row_step_x) * first_row);
        grid.origin_y = static_cast<int64_t>(static_cast<uint64_t>(grid.origin_y) +
                                             static_cast<uint64_t>(grid.row_step_y) * first_row);
        if (job.max_taps == 0) {
            const size_t size = dsn_continuous_tile_scratch_size(job.noise, &grid, job.width, rows);
            err = continuous_tile(job.noise, &grid, job.width, rows, out, scratch.reserve(size), size);
        } else {
            // The footprint of a pixel is the grid's steps: the same in every strip.
            const size_t size =
                dsn_filtered_tile_scratch_size(job.noise, &grid, job.max_taps, job.width, rows);
            err = filtered_tile(job.noise, &grid, job.max_taps, job.width, rows, out, scratch.reserve(size),
                                size);
        }
    }
    if (err != DSN_OK) throw std::runtime_error(dsn_error_message(err));
}

// The time budget. The runtime bounds the work of one point (DSN_MAX_POINT_IMPULSES) but not cheaply:
// the costliest point it accepts takes about 20 ms, so a whole window of them could take hours. Before
// rendering, a few probe segments of one row spread over the window are rendered as the render will
// (same job: mode, filter, taps, grid steps), each timed by the thread that renders it; their time per
// pixel, times the window's pixels, divided by the threads that can run at once, is the estimate.
// A first single pixel chooses the segments' width: up to 64 pixels (about 1 ms each), so that the
// runtime's cost per call does not swell the estimate of a cheap asset, one pixel when points are costly.
struct Estimate {
    double seconds;       // the whole render's
    double pixel_seconds; // one pixel's, on one thread
    uint32_t probe_pixels;
};

Estimate estimate_render(const Job &job, unsigned thread_count) {
    using Clock = std::chrono::steady_clock;
    const uint32_t probe_rows = 4, probe_columns = 4;
    auto segment = [&job](uint32_t x, uint32_t y, uint32_t width, std::vector<float> &out, Scratch &scratch) {
        Job probe = job;
        probe.width = width;
        probe.height = probe.strip_rows = 1;
        if (job.mode == Mode::continuous) {
            probe.grid.origin_x = static_cast<int64_t>(static_cast<uint64_t>(job.grid.origin_x) +
                                                       static_cast<uint64_t>(job.grid.column_step_x) * x +
                                                       static_cast<uint64_t>(job.grid.row_step_x) * y);
            probe.grid.origin_y = static_cast<int64_t>(static_cast<uint64_t>(job.grid.origin_y) +
                                                       static_cast<uint64_t>(job.grid.column_step_y) * x +
                                                       static_cast<uint64_t>(job.grid.row_step_y) * y);
        } else {
            probe.lattice_x0 = static_cast<int32_t>(static_cast<uint32_t>(job.lattice_x0) + x);
            probe.lattice_y0 = static_cast<int32_t>(static_cast<uint32_t>(job.lattice_y0) + y);
        }
        out.resize(static_cast<size_t>(width) * job.channels);
        const auto begin = Clock::now();
        render_strip(probe, 0, 1, out.data(), scratch);
        return std::chrono::duration<double>(Clock::now() - begin).count();
    };
    std::vector<float> first;
    Scratch first_scratch;
    const double first_seconds = segment(job.width / 2, job.height / 2, 1, first, first_scratch);
    const uint32_t widest = std::min(job.width, 64u);
    const uint32_t width =
        first_seconds * widest <= 1e-3
            ? widest
            : std::max(1u, static_cast<uint32_t>(std::min<double>(widest, 1e-3 / first_seconds)));
    const uint32_t segment_count = probe_rows * probe_columns;
    std::atomic<uint32_t> next(0);
    std::mutex lock;
    double busy = first_seconds; // guarded by lock
    std::string failure;
    auto worker = [&]() {
        std::vector<float> out;
        Scratch scratch;
        for (uint32_t index; (index = next++) < segment_count;) {
            // The centre of one of 4 x 4 equal cells of the window.
            const uint32_t column = index % probe_columns, row = index / probe_columns;
            const uint64_t centre_x = (2 * column + 1) * uint64_t(job.width) / (2 * probe_columns);
            const uint32_t x = static_cast<uint32_t>(
                std::min<uint64_t>(centre_x > width / 2 ? centre_x - width / 2 : 0, job.width - width));
            const uint32_t y = static_cast<uint32_t>((2 * row + 1) * uint64_t(job.height) / (2 * probe_rows));
            try {
                const double seconds = segment(x, y, width, out, scratch);
                std::lock_guard<std::mutex> guard(lock);
                busy += seconds;
            } catch (const std::exception &error) {
                std::lock_guard<std::mutex> guard(lock);
                failure = error.what();
                next = segment_count;
                return;
            }
        }
    };
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const unsigned parallel = std::min(thread_count, cores); // the render's threads that run at once
    std::vector<std::thread> threads;
    for (unsigned t = 1; t < std::min(parallel, segment_count); t++) threads.emplace_back(worker);
    worker();
    for (std::thread &thread : threads) thread.join();
    if (!failure.empty()) throw std::runtime_error(failure);
    Estimate estimate;
    estimate.probe_pixels = 1 + segment_count * width;
    estimate.pixel_seconds = busy / estimate.probe_pixels;
    estimate.seconds = estimate.pixel_seconds * job.width * static_cast<double>(job.height) / parallel;
    return estimate;
}

// Rows per strip: about 2^18 pixels (the runtime's tiles cut themselves into 128 x 128 rectangles, so
// 128 rows of a 2048-pixel image are whole rectangles), fewer when that leaves under 8 strips per thread
// (the strips are shared out as the threads finish, and progress counts them).
uint32_t strip_rows_for(uint32_t width, uint32_t height, unsigned thread_count) {
    uint32_t rows = std::max(1u, std::min(128u, (1u << 18) / width));
    while (rows > 16 && (height + rows - 1) / rows < 8u * thread_count) rows /= 2;
    return std::min(rows, height);
}

// How progress is shown: none, one line redrawn per percent (a terminal), or at most one line per 10%
// (a log file or pipe, where redrawn lines would pile up).
enum class Progress { none, redrawn, lines };

// Renders the whole image into `pixels` (u8 or float) with `thread_count` workers, every mode alike:
// the workers take the strips in turn, each strip one runtime call (or one loop of per-point calls).
template <typename Pixel>
void render(const Job &job, unsigned thread_count, Progress progress, Pixel *pixels) {
    const uint32_t strip_count = (job.height + job.strip_rows - 1) / job.strip_rows;
    std::atomic<uint32_t> next_strip(0), done_strips(0);
    std::mutex report_lock;
    std::string failure;
    const uint32_t percent_step = progress == Progress::lines ? 10 : 1;
    uint32_t percent_shown = 0; // guarded by report_lock
    auto worker = [&]() {
        Scratch scratch;
        for (uint32_t index; (index = next_strip++) < strip_count;) {
            const uint32_t first_row = index * job.strip_rows;
            const uint32_t rows = std::min(job.strip_rows, job.height - first_row);
            try {
                render_strip(job, first_row, rows,
                             pixels + static_cast<size_t>(first_row) * job.width * job.channels, scratch);
            } catch (const std::exception &error) {
                std::lock_guard<std::mutex> guard(report_lock);
                failure = error.what();
                next_strip = strip_count;
                return;
            }
            uint32_t done = ++done_strips;
            const uint32_t percent = static_cast<uint32_t>(uint64_t(done) * 100 / strip_count);
            if (progress != Progress::none) {
                std::lock_guard<std::mutex> guard(report_lock);
                if (percent / percent_step > percent_shown / percent_step) {
                    percent_shown = percent;
                    if (progress == Progress::redrawn)
                        std::fprintf(stderr, "\rdsn-render: %3u%%%s", percent, percent == 100 ? "\n" : "");
                    else
                        std::fprintf(stderr, "dsn-render: %u%%\n", percent / percent_step * percent_step);
                    std::fflush(stderr);
                }
            }
        }
    };
    std::vector<std::thread> threads;
    for (unsigned t = 1; t < thread_count; t++) threads.emplace_back(worker);
    worker();
    for (std::thread &thread : threads) thread.join();
    if (!failure.empty()) throw std::runtime_error(failure);
}

std::vector<unsigned char> encode_png(const uint8_t *pixels, uint32_t width, uint32_t height,
                                      uint32_t channels) {
    return dsn::encode_png(static_cast<int>(width), static_cast<int>(height), static_cast<int>(channels),
                           pixels);
}

// The rendered floats as the bytes of a .f32 file (raw little-endian float32, whatever the host's byte
// order), rewritten in place so that the image is held once.
void float32_to_little_endian(float *values, size_t count) {
    unsigned char *bytes = static_cast<unsigned char *>(static_cast<void *>(values));
    for (size_t i = 0; i < count; i++) {
        uint32_t bits;
        std::memcpy(&bits, &values[i], 4);
        dsn_write_u32le(&bytes[i * 4], bits);
    }
}

void run(const Options &options) {
    dsn_asset asset;
    const std::vector<unsigned char> asset_bytes = dsn::load_asset_file(options.asset_path, asset);
    const Mode mode = render_mode(options, asset);
    dsn_config config;
    dsn_config_defaults(&config);
    config.seed = options.seed;
    config.impacts_q16 = options.impacts_q16;
    config.period_x = options.period_x;
    config.period_y = options.period_y;
    config.flags = options.flags;
    dsn_noise noise;
    int err = dsn_noise_init(&noise, &asset, &config);
    if (err == DSN_ERR_COST)
        throw std::runtime_error(
            options.asset_path + ": " + dsn_error_message(err) + ": more than " +
            std::to_string(DSN_MAX_POINT_IMPULSES) + " impulses per point; use a lower --impacts" +
            (options.period_x || options.period_y ? " or a larger --period (or none)" : ""));
    if (err != DSN_OK) throw std::runtime_error(options.asset_path + ": " + dsn_error_message(err));
    if (mode == Mode::continuous && (err = dsn_continuous_check(&noise)) != DSN_OK)
        throw std::runtime_error(options.asset_path + ": " + dsn_error_message(err));
    dsn::MixInputs mix_inputs;
    uint32_t channels = asset.channels;
    if (!options.mix.paths.empty()) {
        dsn::configure_mix(
            options.mix, noise, config, mode == Mode::continuous,
            [&options](const std::string &path, const dsn_asset &material) {
                Options as_material = options;
                as_material.asset_path = path;
                render_mode(as_material, material); // throws where the mode cannot read it
            },
            mix_inputs);
        channels = dsn_mix_channels(&mix_inputs.mix);
    }

    const uint32_t max_taps = mode != Mode::continuous || options.filter == Filter::none ? 0
                              : options.filter == Filter::iso                            ? 1
                                                                                         : options.max_taps;
    Job job{&noise, mode, 0, 0, {}, options.width, options.height, channels, 0, max_taps};
    if (!options.mix.paths.empty()) job.mix = &mix_inputs.mix, job.control = &mix_inputs.control;
    if (mode == Mode::continuous)
        job.grid = dsn::rotated_grid(options.origin_x, options.origin_y, options.scale_x, options.scale_y,
                                     options.rotate_degrees);
    else
        job.lattice_x0 = dsn::lattice_origin(options.origin_x),
        job.lattice_y0 = dsn::lattice_origin(options.origin_y);

    const size_t value_count = static_cast<size_t>(options.width) * options.height * channels;
    unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    job.strip_rows = strip_rows_for(options.width, options.height, threads);
    // Only a large render takes long enough to need progress.
    const bool large = static_cast<uint64_t>(options.width) * options.height >= (1u << 22);
    const Progress progress = options.quiet || !large      ? Progress::none
                              : isatty(STDERR_FILENO) != 0 ? Progress::redrawn
                                                           : Progress::lines;
    if (options.time_limit > 0) {
        const Estimate estimate = estimate_render(job, threads);
        if (estimate.seconds > options.time_limit) {
            char line[400];
            std::snprintf(line, sizeof line,
                          "%s: this render would take about %.0f s (%u probe pixels: %.3g ms per pixel on "
                          "one thread, %ux%u pixels, %u thread(s)), over --time-limit %g s: use a lower "
                          "--impacts, a smaller --size, a larger --scale, or a higher --time-limit (0: no "
                          "limit)",
                          options.asset_path.c_str(), estimate.seconds, estimate.probe_pixels,
                          estimate.pixel_seconds * 1e3, options.width, options.height, threads,
                          options.time_limit);
            throw std::runtime_error(line);
        }
    }
    auto start = std::chrono::steady_clock::now();
    auto elapsed = [&start]() {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    double seconds = 0;
    if (dsn::ends_with(options.output_path, ".png")) {
        MappedMemory pixels(value_count);
        render(job, threads, progress, static_cast<uint8_t *>(pixels.data()));
        seconds = elapsed();
        dsn::write_file_atomically(
            options.output_path,
            encode_png(static_cast<const uint8_t *>(pixels.data()), options.width, options.height, channels));
    } else {
        MappedMemory pixels(value_count * sizeof(float));
        float *values = static_cast<float *>(pixels.data());
        render(job, threads, progress, values);
        seconds = elapsed();
        float32_to_little_endian(values, value_count);
        dsn::write_file_atomically(options.output_path, static_cast<const unsigned char *>(pixels.data()),
                                   value_count * sizeof(float));
    }
    if (!options.quiet)
        std::printf("dsn-render: %ux%u, %u channel(s), %u thread(s): %.3f s, %.1f Mpixel/s -> %s\n",
                    options.width, options.height, channels, threads, seconds,
                    options.width * static_cast<double>(options.height) / seconds / 1e6,
                    options.output_path.c_str());
}

} // namespace

int main(int argc, char **argv) {
    const std::string text = usage();
    return dsn::run_tool("dsn-render", text.c_str(), argc, argv, [](dsn::CommandLine &command_line) {
        run(parse_options(command_line));
        return 0;
    });
}
