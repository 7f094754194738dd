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
    "Validates a .dsnt asset with the runtime loader and prints its header. With --json, prints\n"
    "the header, mean, color_transform, support and texton (dequantized values, row-major,\n"
    "channels interleaved, top-left first) as one JSON object. bake_rme (RME in the text) is the\n"
    "relative model error of the stored texton that the baker recorded, summed over every frequency as\n"
    "Galerne, Leclaire and Moisan define it (dsn-bake --help says more).\n"
    "\n"
    "  --json                   print JSON instead of text\n"
    "  -h, --help               this help\n"
    "  --version                the version\n"
    "\n"
    "Errors are one line on stderr: exit 2 for a usage mistake (the line ends with \"(see --help)\"),\n"
    "exit 1 for a file that cannot be read or is not a valid asset (the loader's message).\n";

// Assets are at most 128 + 255 * 255 * 3 * 2 + 4 bytes; anything much larger is not one.
const long kMaxFileSize = 1 << 20;

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

double texton_value(const dsn_asset &asset, uint32_t row, uint32_t column, uint32_t channel) {
    return double(dsn_asset_texton_value(&asset, row, column, channel)) * double(asset.scale[channel]) /
           kScaleOne;
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
    std::printf("\n}\n");
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
