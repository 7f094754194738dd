// dsn-example-asset: writes a small synthetic .dsnt asset from fixed integers, without the FFT baker.
//
// The examples and their smoke tests use it so that they run before (and independently of) dsn-bake:
// the texton is an anisotropic spot (a stretched, rotated bump with a grain across it) computed in
// integer arithmetic, so the same command writes the same bytes on every machine.
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "command_line.h"
#include "dsn/asset_writer.h"
#include "file_output.h"

namespace {

const char *const kUsage =
    "usage: dsn-example-asset OUT.dsnt [--channels 1|3] [--radius R] [--bits 8|16]\n"
    "                         [--shape square|disk] [--interpolation bilinear|lattice] [--impacts N]\n"
    "Writes a synthetic anisotropic-spot asset (no exemplar, no FFT): for tests and examples.\n"
    "Defaults: 3 channels, radius 7, 8 bits, square, bilinear, 30 impacts per pixel.\n"
    "A bilinear asset carries its lattice texton (format 1.3), as dsn-bake writes it, up to radius 126\n"
    "(radius 127 writes none: an asset as an older dsn-bake wrote it).\n"
    "  -h, --help, --version   this help, the version\n"
    "Flags take their value as --flag value or --flag=value. Errors are one line on stderr: exit 2 for a\n"
    "usage mistake (the line ends with \"(see --help)\"), exit 1 when the file cannot be written.\n";

struct Options {
    std::string output;
    uint32_t channels = 3;
    uint32_t radius = 7;
    uint32_t bits = 8;
    uint32_t shape = DSN_SHAPE_RECTANGLE;
    uint32_t interpolation = DSN_INTERPOLATION_BILINEAR;
    uint32_t impacts = 30;
};

Options parse_options(dsn::CommandLine &command_line) {
    Options options;
    while (command_line.next()) {
        if (command_line.is_positional()) {
            if (!options.output.empty()) throw dsn::UsageError("more than one output file given");
            options.output = command_line.current();
        } else if (command_line.is("--channels")) {
            options.channels = uint32_t(dsn::parse_integer(command_line, 1, 3));
            if (options.channels == 2) throw dsn::UsageError("--channels must be 1 or 3");
        } else if (command_line.is("--radius")) {
            options.radius = uint32_t(dsn::parse_integer(command_line, 0, 127));
        } else if (command_line.is("--bits")) {
            options.bits = uint32_t(dsn::parse_integer(command_line, 8, 16));
            if (options.bits != 8 && options.bits != 16) throw dsn::UsageError("--bits must be 8 or 16");
        } else if (command_line.is("--impacts")) {
            options.impacts = uint32_t(dsn::parse_integer(command_line, 1, 1024));
        } else if (command_line.is("--shape")) {
            const std::string value = command_line.value();
            if (value == "square")
                options.shape = DSN_SHAPE_RECTANGLE;
            else if (value == "disk")
                options.shape = DSN_SHAPE_DISK;
            else
                throw dsn::UsageError("--shape must be square or disk");
        } else if (command_line.is("--interpolation")) {
            const std::string value = command_line.value();
            if (value == "lattice")
                options.interpolation = DSN_INTERPOLATION_LATTICE;
            else if (value == "bilinear")
                options.interpolation = DSN_INTERPOLATION_BILINEAR;
            else
                throw dsn::UsageError("--interpolation must be bilinear or lattice");
        } else {
            command_line.unknown();
        }
    }
    if (options.output.empty()) throw dsn::UsageError("no output file given");
    return options;
}

// The spot of channel c at offset (dx, dy), in [-peak, peak]: a bump stretched along the direction
// (4, 1), times a triangle wave of period 5 texels across it (an oriented grain); each channel has a
// different length so that the colours vary. Integer arithmetic only: a rational bump 1 / (1 + 4 d^2).
int32_t spot_value(int32_t dx, int32_t dy, uint32_t channel, uint32_t radius, int32_t peak) {
    const int32_t along = 4 * dx + dy, across = -dx + 4 * dy; // both scaled by |(4, 1)|^2 = 17
    const int64_t length = 17 * static_cast<int64_t>(radius + 1) * (3 + static_cast<int64_t>(channel)) / 3;
    const int64_t width = 17 * static_cast<int64_t>(radius + 1) / 3;
    const int64_t distance = static_cast<int64_t>(along) * along * width * width +
                             static_cast<int64_t>(across) * across * length * length;
    const int64_t unit = length * length * width * width;
    const int64_t phase = ((across + 43) % 85 + 85) % 85;               // period 85 / 17 = 5 texels
    const int64_t wave = phase < 43 ? 2 * phase - 42 : 128 - 2 * phase; // triangle in [-42, 44]
    const int64_t bump = peak * unit / (unit + 4 * distance);
    return static_cast<int32_t>(bump * wave / 44);
}

dsn::AssetFields make_fields(const Options &options) {
    dsn::AssetFields fields;
    fields.channels = options.channels;
    fields.bits = options.bits;
    fields.shape = options.shape;
    fields.interpolation = options.interpolation;
    fields.width = fields.height = 2 * options.radius + 1;
    fields.default_impacts_q16 = options.impacts << 16;
    dsn::set_identity_color_transform(fields);
    const int32_t peak = options.bits == 8 ? 127 : 32767;
    const int32_t r = static_cast<int32_t>(options.radius);
    const int32_t means_q24[3] = {9 << 20, 7 << 20, 5 << 20}; // 0.5625, 0.4375, 0.3125
    for (uint32_t c = 0; c < options.channels; c++) fields.mean[c] = means_q24[c];
    double energy[3] = {0, 0, 0};
    for (int32_t dy = -r; dy <= r; dy++)
        for (int32_t dx = -r; dx <= r; dx++)
            for (uint32_t c = 0; c < options.channels; c++) {
                bool inside = options.shape != DSN_SHAPE_DISK || dx * dx + dy * dy <= r * r;
                int32_t q = inside ? spot_value(dx, dy, c, options.radius, peak) : 0;
                if (q < -peak) q = -peak;
                fields.texton.push_back(q);
                energy[c] += static_cast<double>(q) * q;
            }
    // Scale so that the noise has a standard deviation of about 0.15 per channel (its variance is
    // sum t^2); the scale is a fixed value per energy, rounded once.
    for (uint32_t c = 0; c < options.channels; c++) {
        double scale = energy[c] > 0 ? 0.15 / std::sqrt(energy[c]) * 1099511627776.0 : 1.0;
        fields.scale[c] = scale >= 4294967295.0 ? 4294967295u : static_cast<uint32_t>(scale < 1 ? 1 : scale);
    }
    // As dsn-bake writes a bilinear asset: with the lattice texton the lattice evaluators read (format
    // 1.3), where it fits (it is 2 texels wider than the texton).
    if (fields.interpolation == DSN_INTERPOLATION_BILINEAR && fields.width + 2 <= DSN_FORMAT_MAX_SIDE)
        dsn::set_lattice_texton(fields);
    return fields;
}

} // namespace

int main(int argc, char **argv) {
    return dsn::run_tool("dsn-example-asset", kUsage, argc, argv, [](dsn::CommandLine &command_line) {
        const Options options = parse_options(command_line);
        dsn::write_file_atomically(options.output, dsn::encode_asset(make_fields(options)));
        return 0;
    });
}
