// dsn-inspect - prints what a .dsnt asset holds, as validated by the runtime loader (text or JSON).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "asset_file.h"
#include "command_line.h"
#include "dsn/dsn.h"
#include "json_output.h"
#include "runtime/setup/format_bytes.h"

namespace {

const char *const kUsage =
    "usage: dsn-inspect A.dsnt [--json]\n"
    "\n"
    "Validates a .dsnt asset with the runtime loader and prints its header, the levels of its texton\n"
    "pyramid (format 1.1: side, spacing, exponent and bytes of each) and its size with and without the\n"
    "pyramid, and the histogram-preserving output of a format 1.2 asset (its table's entries, levels,\n"
    "step and input range in Gaussian space, the rotation P and centre back to colours, the expected\n"
    "value the mapping fades to and the exemplar's mean colour centre + P expected, which the filtered\n"
    "evaluation fades to, beside the Gaussian-space mean of the header), and the lattice texton of a\n"
    "format 1.3 bilinear asset (what the lattice evaluators read). With --json, prints the header, mean,\n"
    "color_transform, support, texton, lattice_texton (null without one), pyramid levels (dequantized\n"
    "values, row-major, channels interleaved, top-left first) and histogram (null without one) as one\n"
    "JSON object. bake_rme\n"
    "(RME in the text) is the relative model error of the stored texton that the baker recorded, summed\n"
    "over every frequency as Galerne, Leclaire and Moisan define it (dsn-bake --help says more).\n"
    "\n"
    "  --json                   print JSON instead of text\n"
    "  -h, --help               this help\n"
    "  --version                the version\n"
    "\n"
    "Errors are one line on stderr: exit 2 for a usage mistake (the line ends with \"(see --help)\"),\n"
    "exit 1 for a file that cannot be read or is not a valid asset (the loader's message).\n";

const double kQ24 = 16777216.0;
const double kQ16 = 65536.0;
const double kScaleOne = 1099511627776.0; // 2^40

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

// The asset as its lattice texton (format 1.3): its values, window and bytes in place of the texton's.
dsn_asset lattice_view(const dsn_asset &asset) {
    dsn_asset lattice = asset;
    lattice.texton = asset.lattice_texton;
    lattice.width = asset.lattice_width;
    lattice.height = asset.lattice_height;
    lattice.shape = DSN_SHAPE_RECTANGLE;
    return lattice;
}

// The dequantized values of a texton, row-major, channels interleaved.
std::vector<double> texton_values(const dsn_asset &asset) {
    std::vector<double> values;
    for (uint32_t row = 0; row < asset.height; row++)
        for (uint32_t column = 0; column < asset.width; column++)
            for (uint32_t c = 0; c < asset.channels; c++)
                values.push_back(texton_value(asset, row, column, c));
    return values;
}

void print_lattice_texton_text(const dsn_asset &asset) {
    if (asset.lattice_texton != nullptr)
        std::printf("lattice texton  %ux%u, %u bytes (format 1.3: what the lattice evaluators read)\n",
                    asset.lattice_width, asset.lattice_height,
                    asset.lattice_width * asset.lattice_height * asset.channels * asset.bits / 8);
    else if (asset.interpolation == DSN_INTERPOLATION_BILINEAR)
        std::printf(
            "lattice texton  none: written before format 1.3, too grainy on the lattice (re-bake it)\n");
    else
        std::printf("lattice texton  none (the lattice evaluators read the texton)\n");
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

// The histogram-preserving output of a 1.2 asset (format.h, section kind 2), as the numbers it stands for.
struct Histogram {
    double step, input_low, input_high; // Gaussian space: entry i stands for input_low + i step
    std::vector<double> rotation, centre, expected;
    std::vector<double> mean_colour;   // centre + P expected, exactly as the runtime fades to it
    std::vector<double> gaussian_mean; // the header's mean: the noise's mean before the mapping
};

Histogram histogram_of(const char *path, const dsn_asset &asset) {
    Histogram histogram;
    histogram.step = std::ldexp(1.0, -int(asset.histogram_step_shift));
    histogram.input_low = asset.histogram_input_low_q16 / kQ16;
    histogram.input_high = histogram.input_low + (asset.histogram_entries - 1) * histogram.step;
    const uint32_t rows = asset.channels == 3 ? 3 : 1;
    for (uint32_t row = 0; row < rows; row++)
        for (uint32_t column = 0; column < rows; column++)
            histogram.rotation.push_back(asset.histogram_rotation[row * 3 + column] / kQ24);
    // The runtime's own fade colour (dsn_noise_mean_float), rather than this program's arithmetic.
    dsn_config config;
    dsn_config_defaults(&config);
    dsn_noise noise;
    float fade[DSN_MAX_CHANNELS] = {0, 0, 0};
    // The default configuration: the asset's own density (30 per pixel if none), no period.
    int err = dsn_noise_init(&noise, &asset, &config);
    if (err == DSN_ERR_COST) {
        char density[64];
        std::snprintf(density, sizeof density, "%.4g impacts per pixel%s",
                      (asset.default_impacts_q16 ? asset.default_impacts_q16 : 30u * 65536u) / 65536.0,
                      asset.default_impacts_q16 ? "" : " (the runtime default)");
        throw std::runtime_error(std::string(path) + ": its default configuration (" + density +
                                 ", no period) is too costly: " + dsn_error_message(err) + " (more than " +
                                 std::to_string(DSN_MAX_POINT_IMPULSES) +
                                 " per point); its mean colour needs a configured noise");
    }
    if (err != DSN_OK) throw std::runtime_error(std::string(path) + ": " + dsn_error_message(err));
    if ((err = dsn_noise_mean_float(&noise, fade)) != DSN_OK)
        throw std::runtime_error(std::string(path) +
                                 ": the runtime gives no mean colour of its histogram "
                                 "mapping: " +
                                 dsn_error_message(err));
    for (uint32_t c = 0; c < asset.channels; c++) {
        histogram.centre.push_back(asset.histogram_centre[c] / kQ24);
        histogram.expected.push_back(asset.histogram_expected_q16[c] / kQ16);
        histogram.mean_colour.push_back(fade[c]);
        histogram.gaussian_mean.push_back(asset.mean[c] / kQ24);
    }
    return histogram;
}

void print_row(const char *label, const std::vector<double> &values, size_t first, size_t count) {
    std::printf("%s", label);
    for (size_t i = first; i < first + count; i++) std::printf(" %9.6f", values[i]);
    std::printf("\n");
}

void print_histogram_text(const char *path, const dsn_asset &asset) {
    if (asset.histogram_table == nullptr) {
        std::printf("histogram       none (Gaussian output)\n");
        return;
    }
    const Histogram histogram = histogram_of(path, asset);
    std::printf("histogram       %u entries, %u levels, step %.6g, input %.6f .. %.6f (Gaussian space)\n",
                asset.histogram_entries, asset.histogram_levels, histogram.step, histogram.input_low,
                histogram.input_high);
    const size_t rows = asset.channels == 3 ? 3 : 1;
    for (size_t row = 0; row < rows; row++)
        print_row(row ? "               " : "  rotation     ", histogram.rotation, row * rows, rows);
    print_row("  centre       ", histogram.centre, 0, asset.channels);
    print_row("  expected     ", histogram.expected, 0, asset.channels);
    print_row("  mean colour  ", histogram.mean_colour, 0, asset.channels);
    print_row("  gaussian mean", histogram.gaussian_mean, 0, asset.channels);
}

void print_text(const char *path, size_t size, const dsn_asset &asset) {
    std::printf("file            %s (%zu bytes)\n", path, size);
    std::printf("version         1.%u\n", asset.version_minor);
    std::printf("channels        %u (%s)\n", asset.channels, asset.channels == 3 ? "RGB" : "grey");
    std::printf("bits            %u\n", asset.bits);
    std::printf("texton          %ux%u, %s support of %u points\n", asset.width, asset.height,
                shape_name(asset.shape), asset.support_size);
    std::printf("interpolation   %s\n", interpolation_name(asset.interpolation));
    print_lattice_texton_text(asset);
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
    print_histogram_text(path, asset);
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

void print_histogram_json(const char *path, const dsn_asset &asset) {
    if (asset.histogram_table == nullptr) {
        std::printf("null");
        return;
    }
    const Histogram histogram = histogram_of(path, asset);
    std::printf(
        "{\"entries\": %u, \"levels\": %u, \"step_shift\": %u, \"step\": %.17g, \"input_low\": %.17g, "
        "\"input_high\": %.17g,\n    \"rotation\": ",
        asset.histogram_entries, asset.histogram_levels, asset.histogram_step_shift, histogram.step,
        histogram.input_low, histogram.input_high);
    print_numbers(histogram.rotation);
    std::printf(", \"centre\": ");
    print_numbers(histogram.centre);
    std::printf(",\n    \"expected\": ");
    print_numbers(histogram.expected);
    std::printf(", \"mean_color\": ");
    print_numbers(histogram.mean_colour);
    std::printf(", \"gaussian_mean\": ");
    print_numbers(histogram.gaussian_mean);
    std::printf("}");
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
    std::vector<double> mask;
    for (uint32_t row = 0; row < asset.height; row++)
        for (uint32_t column = 0; column < asset.width; column++)
            mask.push_back(dsn_in_support(asset.shape, asset.width, row, column) ? 1 : 0);
    std::printf(
        ",\n  \"support\": {\"shape\": \"%s\", \"width\": %u, \"height\": %u, \"points\": %u, \"mask\": ",
        shape_name(asset.shape), asset.width, asset.height, asset.support_size);
    print_numbers(mask);
    std::printf("},\n  \"texton\": ");
    print_numbers(texton_values(asset));
    if (asset.lattice_texton != nullptr) {
        std::printf(",\n  \"lattice_texton\": {\"width\": %u, \"height\": %u, \"values\": ",
                    asset.lattice_width, asset.lattice_height);
        print_numbers(texton_values(lattice_view(asset)));
        std::printf("}");
    } else {
        std::printf(",\n  \"lattice_texton\": null");
    }
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
    std::printf("%s],\n  \"histogram\": ", levels.empty() ? "" : "\n  ");
    print_histogram_json(path, asset);
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
    dsn_asset asset;
    const std::vector<unsigned char> bytes = dsn::load_asset_file(path, asset);
    if (json)
        print_json(path.c_str(), bytes.size(), asset);
    else
        print_text(path.c_str(), bytes.size(), asset);
    return 0;
}

} // namespace

int main(int argc, char **argv) { return dsn::run_tool("dsn-inspect", kUsage, argc, argv, inspect); }
