// dsn-inspect - prints what a .dsnt asset holds, as validated by the runtime loader (text or JSON).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../runtime/format_bytes.h"
#include "command_line.h"
#include "dsn/dsn.h"
#include "json_output.h"

namespace {

const char *const kUsage =
    "usage: dsn-inspect A.dsnt [--json]\n"
    "\n"
    "Validates a .dsnt asset with the runtime loader and prints its header, the levels of its texton\n"
    "pyramid (format 1.1: side, spacing, exponent and bytes of each) and its size with and without the\n"
    "pyramid. With --json, prints the header, mean, color_transform, support, texton and pyramid levels\n"
    "(dequantized values, row-major, channels interleaved, top-left first) as one JSON object. bake_rme\n"
    "(RME in the text) is the relative model error of the stored texton that the baker recorded, summed\n"
    "over every frequency as Galerne, Leclaire and Moisan define it (dsn-bake --help says more).\n"
    "\n"
    "  --json                   print JSON instead of text\n"
    "  -h, --help               this help\n"
    "  --version                the version\n"
    "\n"
    "Errors are one line on stderr: exit 2 for a usage mistake (the line ends with \"(see --help)\"),\n"
    "exit 1 for a file that cannot be read or is not a valid asset (the loader's message).\n";

// Assets are at most about 3.5 MB (a 255 x 255 RGB 16-bit texton and 8 pyramid levels as large);
// anything larger is not one.
const long kMaxFileSize = 4 << 20;

const double kQ24 = 16777216.0;
const double kScaleOne = 1099511627776.0; // 2^40

bool read_file(const char *path, std::vector<unsigned char> &bytes, std::string &problem) {
    FILE *file = std::fopen(path, "rb");
    if (!file) {
        problem = std::strerror(errno);
        return false;
    }
    unsigned char buffer[65536];
    size_t count;
    while ((count = std::fread(buffer, 1, sizeof buffer, file)) > 0) {
        bytes.insert(bytes.end(), buffer, buffer + count);
        if (bytes.size() > size_t(kMaxFileSize)) break;
    }
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed)
        problem = "read error (is it a folder?)";
    else if (bytes.size() > size_t(kMaxFileSize))
        problem = "file too large to be an asset";
    return problem.empty();
}

const char *shape_name(uint32_t shape) { return shape == DSN_SHAPE_DISK ? "disk" : "square"; }
const char *interpolation_name(uint32_t mode) {
    return mode == DSN_INTERPOLATION_BILINEAR ? "bilinear" : "lattice";
}

size_t level_bytes(const dsn_asset &asset, const dsn_level &level) {
    return size_t(level.width) * level.height * asset.channels * (asset.bits / 8);
}

// A pyramid level's values as the numbers they stand for: q * scale[c] * 2^exponent / 2^40.
std::vector<double> level_values(const dsn_asset &asset, const dsn_level &level) {
    std::vector<double> values;
    const size_t count = size_t(level.width) * level.height * asset.channels;
    for (size_t i = 0; i < count; i++) {
        const int32_t q =
            asset.bits == 8 ? dsn_read_i8(level.values + i) : dsn_read_i16le(level.values + 2 * i);
        values.push_back(
            std::ldexp(double(q) * double(asset.scale[i % asset.channels]), level.exponent - 40));
    }
    return values;
}

double texton_value(const dsn_asset &asset, uint32_t row, uint32_t column, uint32_t channel) {
    return double(dsn_asset_texton_value(&asset, row, column, channel)) * double(asset.scale[channel]) /
           kScaleOne;
}

// The levels 1 .. pyramid_levels, and the bytes the pyramid's section takes in the file (0 without one).
std::vector<dsn_level> pyramid_levels(const dsn_asset &asset, size_t &section_bytes) {
    std::vector<dsn_level> levels;
    size_t payload = DSN_PYRAMID_HEADER_SIZE;
    for (uint32_t l = 1; l <= asset.pyramid_levels; l++) {
        dsn_level level;
        if (dsn_asset_level(&asset, l, &level) != DSN_OK) break;
        levels.push_back(level);
        payload += DSN_PYRAMID_RECORD_SIZE + level_bytes(asset, level);
    }
    section_bytes = levels.empty() ? 0 : DSN_SECTION_HEADER_SIZE + (payload + 3) / 4 * 4;
    return levels;
}

void print_text(const char *path, size_t size, const dsn_asset &asset) {
    std::printf("file            %s (%zu bytes)\n", path, size);
    std::printf("version         1.%u\n", asset.version_minor);
    std::printf("channels        %u (%s)\n", asset.channels, asset.channels == 3 ? "RGB" : "grey");
    std::printf("bits            %u\n", asset.bits);
    std::printf("texton          %ux%u, %s support of %u points\n", asset.width, asset.height,
                shape_name(asset.shape), asset.support_size);
    std::printf("interpolation   %s\n", interpolation_name(asset.interpolation));
    if (asset.default_impacts_q16)
        std::printf("impacts         %.4g per pixel\n", asset.default_impacts_q16 / 65536.0);
    else
        std::printf("impacts         none given (runtime default 30)\n");
    std::printf("scale          ");
    for (uint32_t c = 0; c < asset.channels; c++) std::printf(" %.6g", asset.scale[c] / kScaleOne);
    std::printf("\nmean           ");
    for (uint32_t c = 0; c < asset.channels; c++) std::printf(" %.6f", asset.mean[c] / kQ24);
    std::printf("\ncolor_transform");
    const uint32_t rows = asset.channels == 3 ? 3 : 1;
    for (uint32_t row = 0; row < rows; row++) {
        std::printf(row ? "\n               " : "");
        for (uint32_t column = 0; column < rows; column++)
            std::printf(" %9.6f", asset.color_transform[row * 3 + column] / kQ24);
    }
    std::printf("\nbake            %u iterations, seed %u, RME %.6f\n", asset.bake_iterations,
                asset.bake_seed, asset.bake_rme_q24 / kQ24);
    std::printf("exemplar        %ux%u\n", asset.exemplar_width, asset.exemplar_height);
    size_t section_bytes;
    const std::vector<dsn_level> levels = pyramid_levels(asset, section_bytes);
    if (levels.empty()) {
        std::printf("pyramid         none (the filtered evaluation fades to the mean)\n");
        return;
    }
    std::printf("pyramid         %zu levels, %zu bytes; the asset is %zu bytes without it\n", levels.size(),
                section_bytes, size - section_bytes);
    for (size_t l = 0; l < levels.size(); l++)
        std::printf("  level %zu       %ux%u at spacing %u, exponent %d, %zu bytes\n", l + 1, levels[l].width,
                    levels[l].height, 1u << (l + 1), levels[l].exponent, level_bytes(asset, levels[l]));
}

void print_numbers(const std::vector<double> &values) {
    std::printf("[");
    for (size_t i = 0; i < values.size(); i++) std::printf("%s%.17g", i ? ", " : "", values[i]);
    std::printf("]");
}

void print_json(const char *path, size_t size, const dsn_asset &asset) {
    std::printf("{\n  \"file\": %s", dsn::json_string(path).c_str());
    std::printf(",\n  \"bytes\": %zu,\n  \"version\": \"1.%u\",\n", size, asset.version_minor);
    std::printf("  \"channels\": %u,\n  \"bits\": %u,\n  \"shape\": \"%s\",\n  \"interpolation\": \"%s\",\n",
                asset.channels, asset.bits, shape_name(asset.shape), interpolation_name(asset.interpolation));
    std::printf("  \"width\": %u,\n  \"height\": %u,\n  \"default_impacts\": %.17g,\n", asset.width,
                asset.height, asset.default_impacts_q16 / 65536.0);
    std::vector<double> scale, mean, transform;
    for (uint32_t c = 0; c < asset.channels; c++) {
        scale.push_back(asset.scale[c] / kScaleOne);
        mean.push_back(asset.mean[c] / kQ24);
    }
    for (uint32_t i = 0; i < 9; i++) transform.push_back(asset.color_transform[i] / kQ24);
    std::printf("  \"scale\": ");
    print_numbers(scale);
    std::printf(",\n  \"bake_iterations\": %u,\n  \"bake_seed\": %u,\n  \"bake_rme\": %.17g,\n",
                asset.bake_iterations, asset.bake_seed, asset.bake_rme_q24 / kQ24);
    std::printf("  \"exemplar_width\": %u,\n  \"exemplar_height\": %u,\n  \"mean\": ", asset.exemplar_width,
                asset.exemplar_height);
    print_numbers(mean);
    std::printf(",\n  \"color_transform\": ");
    print_numbers(transform);
    std::vector<double> mask, texton;
    for (uint32_t row = 0; row < asset.height; row++)
        for (uint32_t column = 0; column < asset.width; column++) {
            mask.push_back(dsn_in_support(asset.shape, asset.width, row, column) ? 1 : 0);
            for (uint32_t c = 0; c < asset.channels; c++)
                texton.push_back(texton_value(asset, row, column, c));
        }
    std::printf(
        ",\n  \"support\": {\"shape\": \"%s\", \"width\": %u, \"height\": %u, \"points\": %u, \"mask\": ",
        shape_name(asset.shape), asset.width, asset.height, asset.support_size);
    print_numbers(mask);
    std::printf("},\n  \"texton\": ");
    print_numbers(texton);
    size_t section_bytes;
    const std::vector<dsn_level> levels = pyramid_levels(asset, section_bytes);
    std::printf(",\n  \"bytes_without_pyramid\": %zu,\n  \"pyramid\": [", size - section_bytes);
    for (size_t l = 0; l < levels.size(); l++) {
        std::printf(
            "%s\n    {\"level\": %zu, \"width\": %u, \"height\": %u, \"spacing\": %u, \"exponent\": %d, "
            "\"bytes\": %zu, \"values\": ",
            l ? "," : "", l + 1, levels[l].width, levels[l].height, 1u << (l + 1), levels[l].exponent,
            level_bytes(asset, levels[l]));
        print_numbers(level_values(asset, levels[l]));
        std::printf("}");
    }
    std::printf("%s]\n}\n", levels.empty() ? "" : "\n  ");
}

int inspect(dsn::CommandLine &command_line) {
    std::string path;
    bool json = false;
    while (command_line.next()) {
        if (command_line.is("--json")) {
            command_line.no_value();
            json = true;
        } else if (command_line.is_positional() && path.empty()) {
            path = command_line.current();
        } else if (command_line.is_positional()) {
            throw dsn::UsageError("more than one file given");
        } else {
            command_line.unknown();
        }
    }
    if (path.empty()) throw dsn::UsageError("no asset given");
    std::vector<unsigned char> bytes;
    std::string problem;
    if (!read_file(path.c_str(), bytes, problem)) throw std::runtime_error(path + ": " + problem);
    dsn_asset asset;
    const int error = dsn_asset_load(&asset, bytes.data(), bytes.size());
    if (error != DSN_OK) throw std::runtime_error(path + ": " + dsn_error_message(error));
    if (json)
        print_json(path.c_str(), bytes.size(), asset);
    else
        print_text(path.c_str(), bytes.size(), asset);
    return 0;
}

} // namespace

int main(int argc, char **argv) { return dsn::run_tool("dsn-inspect", kUsage, argc, argv, inspect); }
