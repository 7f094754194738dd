// dsn-synth - command-line front end of the spectral synthesis (offline/synth.h): an exemplar image ->
// a random phase noise (RPN) or asymptotic discrete spot noise (ADSN) image of any size, written as PNG
// (8 or 16 bits) or raw float32.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

#include "command_line.h"
#include "dsn/bake.h"
#include "file_output.h"
#include "offline/synth.h"
#include "png_output.h"
#include "runtime/setup/format_bytes.h"

namespace {

const char *const kUsage =
    "usage: dsn-synth IN -o OUT.png|OUT.f32 --size WxH [--method adsn|rpn] [--seed S] [--alpha A]\n"
    "                 [--bits 8|16] [--quiet]\n"
    "\n"
    "Synthesizes a W x H texture image from an exemplar image (PNG 8/16-bit, JPEG, binary PGM/PPM; grey\n"
    "or RGB; alpha is ignored; at most 2048 pixels per side; other formats are refused, as dsn-bake\n"
    "--help lists) by the spectral methods of Galerne, Gousseau and Morel (Random phase textures,\n"
    "2011), from the exemplar's periodic component: ADSN filters one Gaussian white noise by the\n"
    "exemplar's spot, RPN gives the spectrum one random phase; the channels share the noise or the\n"
    "phase, so colours keep their correlations. An output larger than the exemplar uses the spot\n"
    "extension: the spot, pasted at the centre of a mean-valued image of the output's size, fades out\n"
    "over its border and is scaled to keep each channel's variance.\n"
    "\n"
    "  -o, --output OUT       the image to write (atomically: never a partial file): OUT.png or OUT.f32\n"
    "  --size WxH             the output, 1..16384 pixels per side\n"
    "  --method adsn|rpn      the random field (default adsn)\n"
    "  --seed S               seed of the white noise, 0..4294967295 (default 0)\n"
    "  --alpha A              the spot's faded border, a fraction of each exemplar side in (0, 0.5]\n"
    "                         (default 0.2); only for sides larger than the exemplar's\n"
    "  --bits 8|16            PNG sample depth (default 8)\n"
    "  --quiet                no progress bar, warnings or summary\n"
    "  -h, --help             this help\n"
    "  --version              the version\n"
    "\n"
    "The FFTs run on the output's size rounded up to a product of 2, 3 and 5 (the exemplar's own size\n"
    "when the output is not larger); memory is about 16 bytes per pixel of that size plus 8 per channel\n"
    "per output pixel, plus the file: about 12 GiB for 16384x16384 RGB, 0.2 GiB for 2048x2048 RGB.\n"
    "OUT.png is grey or RGB, values clamped to [0, 1]; OUT.f32 is raw little-endian float32, channels\n"
    "interleaved, row-major, top row first (exemplar units, 1.0 = white, not clamped).\n"
    "The summary line goes to stdout; warnings, and a progress bar for outputs of 4 Mpixels or more\n"
    "when stderr is a terminal, to stderr.\n"
    "Flags take their value as --flag value or --flag=value. Errors are one line on stderr and write\n"
    "nothing: exit 2 for a usage mistake (the line ends with \"(see --help)\"), exit 1 when synthesis\n"
    "fails (unreadable or constant image, out of memory, cannot write).\n";

struct Arguments {
    std::string input, output;
    dsn::SynthesisOptions options;
    int bits = 8;
    bool quiet = false;
};

Arguments parse_arguments(dsn::CommandLine &command_line) {
    Arguments arguments;
    bool size_given = false;
    while (command_line.next()) {
        const std::string flag = command_line.current();
        if (command_line.is("--quiet")) {
            command_line.no_value();
            arguments.quiet = true;
        } else if (command_line.is_positional()) {
            if (!arguments.input.empty()) throw dsn::UsageError("more than one input image: " + flag);
            arguments.input = flag;
        } else if (command_line.is("-o") || command_line.is("--output")) {
            arguments.output = command_line.path_value();
        } else if (command_line.is("--size")) {
            const std::string text = command_line.value();
            const size_t at = text.find('x');
            if (at == std::string::npos || at == 0 || at + 1 == text.size())
                throw dsn::UsageError("--size needs WxH, not '" + text + "'");
            arguments.options.width =
                int(dsn::parse_integer("--size width", text.substr(0, at), 1, dsn::kMaxSynthesisSide));
            arguments.options.height =
                int(dsn::parse_integer("--size height", text.substr(at + 1), 1, dsn::kMaxSynthesisSide));
            size_given = true;
        } else if (command_line.is("--method")) {
            const std::string method = command_line.value();
            if (method == "adsn")
                arguments.options.method = dsn::SynthesisMethod::adsn;
            else if (method == "rpn")
                arguments.options.method = dsn::SynthesisMethod::rpn;
            else
                throw dsn::UsageError("--method must be adsn or rpn, not '" + method + "'");
        } else if (command_line.is("--seed")) {
            arguments.options.seed = uint32_t(dsn::parse_integer(command_line, 0, 0xFFFFFFFFll));
        } else if (command_line.is("--alpha")) {
            arguments.options.alpha = dsn::parse_real(flag, command_line.value());
            if (!(arguments.options.alpha > 0 && arguments.options.alpha <= 0.5))
                throw dsn::UsageError("--alpha must be within (0, 0.5]");
        } else if (command_line.is("--bits")) {
            const std::string bits = command_line.value();
            if (bits != "8" && bits != "16")
                throw dsn::UsageError("--bits must be 8 or 16, not '" + bits + "'");
            arguments.bits = bits == "8" ? 8 : 16;
        } else {
            command_line.unknown();
        }
    }
    if (arguments.input.empty()) throw dsn::UsageError("no input image given");
    if (arguments.output.empty()) throw dsn::UsageError("no output given (-o OUT.png|OUT.f32)");
    if (!dsn::ends_with(arguments.output, ".png") && !dsn::ends_with(arguments.output, ".f32"))
        throw dsn::UsageError("the output must end in .png or .f32: " + arguments.output);
    if (arguments.bits == 16 && !dsn::ends_with(arguments.output, ".png"))
        throw dsn::UsageError("--bits is for a .png output");
    if (!size_given) throw dsn::UsageError("no size given (--size WxH)");
    dsn::check_outputs({{"the input image", arguments.input}}, {{"-o", arguments.output}});
    return arguments;
}

// Interleaved samples of the planar image, each value made by `convert`.
template <typename Sample, typename Convert>
std::vector<Sample> interleave(const dsn::Image &image, Convert convert) {
    const size_t plane = size_t(image.width) * size_t(image.height), channels = size_t(image.channels);
    std::vector<Sample> samples(plane * channels);
    for (size_t c = 0; c < channels; c++)
        for (size_t i = 0; i < plane; i++) samples[i * channels + c] = convert(image.values[c * plane + i]);
    return samples;
}

double clamp_unit(double value) { return std::min(1.0, std::max(0.0, value)); }

std::vector<unsigned char> encode(const dsn::Image &image, const std::string &path, int bits) {
    if (dsn::ends_with(path, ".f32")) {
        const std::vector<uint32_t> words = interleave<uint32_t>(image, [](double value) {
            const float narrow = float(value);
            uint32_t word;
            std::memcpy(&word, &narrow, 4);
            return word;
        });
        std::vector<unsigned char> bytes(words.size() * 4);
        for (size_t i = 0; i < words.size(); i++) dsn_write_u32le(&bytes[i * 4], words[i]);
        return bytes;
    }
    if (bits == 16) {
        const std::vector<uint16_t> samples = interleave<uint16_t>(
            image, [](double value) { return uint16_t(std::lround(clamp_unit(value) * 65535.0)); });
        return dsn::encode_png_16(image.width, image.height, image.channels, samples.data());
    }
    const std::vector<unsigned char> samples = interleave<unsigned char>(image, [](double value) {
        return static_cast<unsigned char>(std::lround(clamp_unit(value) * 255.0));
    });
    return dsn::encode_png(image.width, image.height, image.channels, samples.data());
}

int run(const Arguments &arguments) {
    std::vector<std::string> warnings;
    const dsn::Image exemplar = dsn::load_exemplar(arguments.input, &warnings);
    if (!arguments.quiet)
        for (const std::string &warning : warnings)
            std::fprintf(stderr, "dsn-synth: warning: %s\n", warning.c_str());
    dsn::SynthesisOptions options = arguments.options;
    const dsn::SynthesisDomain domain =
        dsn::synthesis_domain(exemplar.width, exemplar.height, options.width, options.height);
    const bool large = uint64_t(domain.width) * uint64_t(domain.height) >= (uint64_t(1) << 22);
    const bool bar = !arguments.quiet && large && isatty(STDERR_FILENO) != 0;
    if (bar)
        options.progress = [](double fraction) {
            const int width = 40, filled = int(fraction * width + 0.5);
            std::fprintf(stderr, "\rdsn-synth: [%s%s] %3d%%", std::string(size_t(filled), '#').c_str(),
                         std::string(size_t(width - filled), ' ').c_str(), int(fraction * 100 + 0.5));
            std::fflush(stderr);
        };
    const auto start = std::chrono::steady_clock::now();
    dsn::Image image;
    try {
        image = dsn::synthesize(exemplar, options);
    } catch (const std::invalid_argument &error) {
        throw dsn::UsageError(error.what());
    } catch (...) {
        if (bar) std::fprintf(stderr, "\n");
        throw;
    }
    if (bar) std::fprintf(stderr, "\n");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    dsn::write_file_atomically(arguments.output, encode(image, arguments.output, arguments.bits));
    if (!arguments.quiet)
        std::printf("dsn-synth: %s %dx%d from %dx%d (FFT %dx%d), %d channel(s): %.3f s -> %s\n",
                    options.method == dsn::SynthesisMethod::rpn ? "rpn" : "adsn", image.width, image.height,
                    exemplar.width, exemplar.height, domain.width, domain.height, image.channels, seconds,
                    arguments.output.c_str());
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    return dsn::run_tool("dsn-synth", kUsage, argc, argv,
                         [](dsn::CommandLine &command_line) { return run(parse_arguments(command_line)); });
}
