// dsn-bake - command-line front end of the baker: exemplar image -> .dsnt asset (+ JSON report, preview).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "bake_progress.h"
#include "command_line.h"
#include "dsn/bake.h"
#include "file_output.h"
#include "json_output.h"
#include "offline/bake_internal.h"

namespace {

const char *const kUsage =
    "usage: dsn-bake IN -o OUT.dsnt [--radius R] [--shape square|disk] [--iterations N] [--stop-tolerance "
    "T]\n"
    "                [--seed S]\n"
    "                [--bits 8|16] [--interpolation bilinear|lattice] [--no-periodic] "
    "[--no-color-transform]\n"
    "                [--no-pyramid] [--histogram] [--report R.json] [--preview P.png] [--quiet]\n"
    "\n"
    "Bakes an exemplar image into a compact .dsnt asset: a synthesis-oriented texton of radius R, its\n"
    "colour transform, the exemplar mean and the texton's pyramid of prefiltered levels (for the\n"
    "filtered evaluation of minified textures). Every bake ends with a verdict: how well a Gaussian\n"
    "model holds the exemplar, and what to try (a larger radius, ...), from measured signals (README).\n"
    "\n"
    "Images read: PNG (8 or 16 bits), JPEG (baseline and progressive) and binary PGM/PPM (P5/P6, any\n"
    "maxval), grey or RGB; alpha is ignored (with a warning unless it is opaque). BMP, GIF, PSD, TGA,\n"
    "Radiance HDR, PIC, TIFF, WebP and plain-text PNM are refused: convert them to PNG. Limits: at most\n"
    "2048 pixels per side and 256 MiB of file; a truncated file or one whose data expands beyond its\n"
    "declared size is refused. Crop or downscale a larger photo first (the error says how).\n"
    "Cost: memory grows with the exemplar's pixels: about 160 bytes per pixel for RGB, 0.7 GB at the\n"
    "2048x2048 limit (the preview adds 0.3 GB). Time grows with pixels x iterations run (about 50 ns\n"
    "per pixel and iteration for RGB on one core of a current x86-64, split among the cores; set\n"
    "DSN_BAKE_THREADS=1 for one thread). The early stop usually ends a bake of a photo after 50 to 300\n"
    "iterations: seconds for 1024x1024. A run estimated at more than 10 minutes prints a warning first.\n"
    "\n"
    "  -o, --output OUT.dsnt    the asset to write (atomically: never a partial file); must end in .dsnt\n"
    "  --radius R               texton radius, 1..127; the texton is (2R+1)x(2R+1) (default 15);\n"
    "                           the exemplar needs both sides >= 4R+1\n"
    "  --shape square|disk      support shape (default square)\n"
    "  --iterations N           the most alternating-projection iterations, 1..1000000 (default 1000)\n"
    "  --stop-tolerance T       stop when the RME the iterations minimize (rme_per_iteration in the\n"
    "                           report) improved by less than T over the last 50 iterations,\n"
    "                           after at least 2^22 / (width x height) iterations (default 0.002; 0 runs\n"
    "                           every iteration)\n"
    "  --seed S                 seed of the random-phase start, 0..4294967295 (default 0)\n"
    "  --bits 8|16              quantization of the texton (default 8)\n"
    "  --interpolation bilinear|lattice\n"
    "                           how the runtime reads the texton (default bilinear): bilinear bakes a\n"
    "                           texton corrected for the interpolation of the continuous mode (dsn-render\n"
    "                           --mode continuous, what renderers use); lattice suits only the integer\n"
    "                           lattice (--mode tile or point)\n"
    "  --no-periodic            use the exemplar as is, not its periodic component\n"
    "  --no-color-transform     store the identity colour transform\n"
    "  --no-pyramid             leave out the texton pyramid: a format 1.0 asset, 43% smaller\n"
    "                           for a 31x31 texton, that the filtered evaluation fades to the mean\n"
    "  --histogram              histogram-preserving output (a format 1.2 asset; Heitz and Neyret,\n"
    "                           HPG 2018): the texton is baked on the exemplar's tones mapped to a\n"
    "                           Gaussian, and the asset maps the noise back through per-channel tables\n"
    "                           (about 4 KB for RGB), so speckles, veins and two-level patterns keep\n"
    "                           their histogram instead of turning into soft blotches. Off by default:\n"
    "                           it needs a runtime built with the mapping (DSN_HISTOGRAM), a Gaussian\n"
    "                           exemplar gains nothing from it, and the mapping keeps each decorrelated\n"
    "                           channel's histogram, not their joint distribution; the verdict suggests\n"
    "                           it when the tones are far from Gaussian\n"
    "  --report R.json          write a JSON report (RMEs, kurtosis, RME of every iteration, why the\n"
    "                           iterations stopped, the verdict and its signals, ...; its asset_crc32 is\n"
    "                           the CRC stored at the end of the asset it describes)\n"
    "  --preview P.png          write a labelled sheet: exemplar | Gaussian reference | texton | runtime\n"
    "                           synthesis, and the verdict\n"
    "  --quiet                  no progress bar, warnings or summary\n"
    "  -h, --help               this help\n"
    "  --version                the version\n"
    "\n"
    "Flags take their value as --flag value or --flag=value. Errors are one line on stderr and write\n"
    "nothing: exit 2 for a usage mistake (the line ends with \"(see --help)\"), exit 1 when the bake\n"
    "fails (unreadable or unusable image, cannot write). The outputs are checked before the bake (each\n"
    "a different file, none the input, each in a folder that exists and can be written). The asset,\n"
    "report and preview are written together: all of them or none; two bakes to the same files leave\n"
    "one bake's whole set (they commit one after the other, under a lock on the folder), so the\n"
    "report's asset_crc32 is the asset's; a signal that ends the bake (SIGTERM, SIGINT, SIGHUP...)\n"
    "leaves no temporary file. Numbers are decimal. The summary goes to stdout; warnings, and the\n"
    "progress bar when stderr is a terminal, to stderr.\n"
    "\n"
    "RME, the relative model error (0 is perfect): the optimal-transport distance between the Gaussian\n"
    "model of the noise made from the texton and the exemplar's, relative to the exemplar's, summed over\n"
    "every frequency as Galerne, Leclaire and Moisan define it: a texton whose values do not sum to zero\n"
    "adds power at the zero frequency (slow variation over scales beyond the exemplar). It is the summary's\n"
    "RME, the report's rme, rme_luminance and rme_quantized, and the asset's bake_rme (of the quantized\n"
    "texton). The same sum without the zero frequency, which the iterations minimize, is the report's\n"
    "rme_without_zero_frequency and rme_per_iteration, and the progress bar's RME(xi!=0).\n";

struct Arguments {
    std::string input, output, report, preview;
    dsn::BakeOptions options;
    bool quiet = false;
};

Arguments parse_arguments(dsn::CommandLine &command_line) {
    Arguments arguments;
    while (command_line.next()) {
        if (command_line.is("-o") || command_line.is("--output")) {
            arguments.output = command_line.path_value();
        } else if (command_line.is("--radius")) {
            arguments.options.radius = int(dsn::parse_integer(command_line, 1, dsn::kMaxRadius));
        } else if (command_line.is("--shape")) {
            const std::string shape = command_line.value();
            if (shape != "square" && shape != "disk")
                throw dsn::UsageError("--shape must be square or disk, not '" + shape + "'");
            arguments.options.shape = shape == "disk" ? DSN_SHAPE_DISK : DSN_SHAPE_RECTANGLE;
        } else if (command_line.is("--iterations")) {
            arguments.options.iterations = int(dsn::parse_integer(command_line, 1, 1000000));
        } else if (command_line.is("--stop-tolerance")) {
            const std::string text = command_line.value();
            char *end = nullptr;
            const double tolerance = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != '\0' || !(tolerance >= 0) || !(tolerance <= 1))
                throw dsn::UsageError("--stop-tolerance must be a number in 0..1, not '" + text + "'");
            arguments.options.stop_tolerance = tolerance;
        } else if (command_line.is("--seed")) {
            arguments.options.seed = uint32_t(dsn::parse_integer(command_line, 0, 4294967295ll));
        } else if (command_line.is("--bits")) {
            const long long bits = dsn::parse_integer(command_line, 8, 16);
            if (bits != 8 && bits != 16) throw dsn::UsageError("--bits must be 8 or 16");
            arguments.options.bits = int(bits);
        } else if (command_line.is("--interpolation")) {
            const std::string mode = command_line.value();
            if (mode != "lattice" && mode != "bilinear")
                throw dsn::UsageError("--interpolation must be bilinear or lattice, not '" + mode + "'");
            arguments.options.interpolation =
                mode == "bilinear" ? DSN_INTERPOLATION_BILINEAR : DSN_INTERPOLATION_LATTICE;
        } else if (command_line.is("--no-periodic")) {
            command_line.no_value();
            arguments.options.periodic = false;
        } else if (command_line.is("--no-color-transform")) {
            command_line.no_value();
            arguments.options.use_color_transform = false;
        } else if (command_line.is("--no-pyramid")) {
            command_line.no_value();
            arguments.options.pyramid = false;
        } else if (command_line.is("--histogram")) {
            command_line.no_value();
            arguments.options.histogram = true;
        } else if (command_line.is("--report")) {
            arguments.report = command_line.path_value();
        } else if (command_line.is("--preview")) {
            arguments.preview = command_line.path_value();
        } else if (command_line.is("--quiet")) {
            command_line.no_value();
            arguments.quiet = true;
        } else if (command_line.is_positional() && arguments.input.empty()) {
            arguments.input = command_line.current();
        } else if (command_line.is_positional()) {
            throw dsn::UsageError("more than one input image ('" + arguments.input + "', '" +
                                  command_line.current() + "')");
        } else {
            command_line.unknown();
        }
    }
    if (arguments.input.empty()) throw dsn::UsageError("no input image given");
    if (arguments.output.empty()) throw dsn::UsageError("no output given (-o OUT.dsnt)");
    // Every output is checked now, not after minutes of baking.
    std::vector<dsn::NamedPath> outputs = {{"-o", arguments.output}};
    if (!arguments.report.empty()) outputs.push_back({"--report", arguments.report});
    if (!arguments.preview.empty()) outputs.push_back({"--preview", arguments.preview});
    dsn::check_outputs({{"the input image", arguments.input}}, outputs);
    // An asset written as out.png is a mistake that shows only when the file is opened: refuse it.
    if (!dsn::ends_with(arguments.output, ".dsnt"))
        throw dsn::UsageError("the output " + arguments.output +
                              " must end in .dsnt (the preview is --preview)");
    return arguments;
}

// The progress bar: one line on a terminal's stderr, redrawn at each percent of the run (its iterations or
// its early stop, whichever ends it: bake_progress_fraction), and ended by a newline at 100%.
dsn::BakeProgress progress_bar(const dsn::Image &exemplar, const dsn::BakeOptions &options) {
    dsn::EarlyStopRule rule;
    rule.tolerance = options.stop_tolerance;
    rule.window = dsn::SotOptions().stop_window;
    rule.minimum_iterations = dsn::early_stop_minimum_iterations(exemplar.width, exemplar.height);
    auto rme_so_far = std::make_shared<std::vector<double>>();
    auto shown = std::make_shared<double>(-1); // the fraction drawn last: the bar never moves back
    return [rule, rme_so_far, shown](int done, int total, double rme) {
        rme_so_far->push_back(rme);
        const double fraction = std::max(*shown, dsn::bake_progress_fraction(*rme_so_far, total, rule));
        const int percent = int(fraction * 100);
        if (percent == int(*shown * 100)) return;
        *shown = fraction;
        const int width = 40, filled = int(fraction * width);
        std::fprintf(stderr, "\r[%s%s] %3d%%  %d/%d  RME(xi!=0) %.4f",
                     std::string(size_t(filled), '#').c_str(),
                     std::string(size_t(width - filled), '.').c_str(), percent, done, total, rme);
        if (percent == 100) std::fputc('\n', stderr);
        std::fflush(stderr);
    };
}

std::string json_number(double value) {
    if (!std::isfinite(value)) return "null";
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

std::string json_array(const std::vector<double> &values) {
    std::string array = "[";
    for (size_t i = 0; i < values.size(); i++) array += (i ? ", " : "") + json_number(values[i]);
    return array + "]";
}

// The texton interleaved, row-major, top-left first (the layout of dsn-inspect --json).
std::vector<double> interleaved(const dsn::Texton &texton) {
    const size_t plane = texton.support.mask.size();
    std::vector<double> values;
    for (size_t i = 0; i < plane; i++)
        for (size_t c = 0; c < size_t(texton.channels); c++) values.push_back(texton.values[c * plane + i]);
    return values;
}

// "converged" or "iteration_limit".
const char *stop_reason(const dsn::BakeResult &result) {
    return result.sot.stop == dsn::SotStop::Converged ? "converged" : "iteration_limit";
}

std::string stop_description(const dsn::BakeResult &result, const dsn::BakeOptions &options) {
    if (result.sot.stop != dsn::SotStop::Converged) return "ran every iteration asked for";
    char text[96];
    std::snprintf(text, sizeof text, "stopped: RME improved by less than %g over the last 50",
                  options.stop_tolerance);
    return text;
}

std::string verdict_json(const dsn::BakeVerdict &verdict) {
    std::string findings = "[", suggestions = "[", channels = "[";
    for (size_t i = 0; i < verdict.findings.size(); i++)
        findings += (i ? ", " : "") + dsn::json_string(dsn::verdict_finding_name(verdict.findings[i]));
    for (size_t i = 0; i < verdict.suggestions.size(); i++)
        suggestions += (i ? ", " : "") + dsn::json_string(verdict.suggestions[i]);
    for (size_t i = 0; i < verdict.channels.size(); i++) {
        const dsn::ChannelMarginal &channel = verdict.channels[i];
        channels += std::string(i ? ", " : "") + "{\"variance\": " + json_number(channel.variance) +
                    ", \"skewness\": " + json_number(channel.skewness) +
                    ", \"skewness_error\": " + json_number(channel.skewness_error) +
                    ", \"excess_kurtosis\": " + json_number(channel.excess_kurtosis) +
                    ", \"kurtosis_error\": " + json_number(channel.kurtosis_error) + "}";
    }
    return "{\"summary\": " + dsn::json_string(verdict.summary) + ", \"findings\": " + findings +
           "], \"suggestions\": " + suggestions + "], \"decorrelated_channels\": " + channels +
           "], \"structure_beyond_reach\": " + json_number(verdict.structure_beyond_reach) +
           ", \"structure_error\": " + json_number(verdict.structure_error) +
           ", \"correlation_beyond_reach\": " + json_number(verdict.correlation_beyond_reach) +
           ", \"suggested_radius\": " + std::to_string(verdict.suggested_radius) +
           ", \"largest_fitting_radius\": " + std::to_string(verdict.largest_fitting_radius) +
           ", \"rme_effective\": " + json_number(verdict.rme_effective) +
           ", \"shape_ratio\": " + json_number(verdict.shape_ratio) +
           ", \"shape_error\": " + json_number(verdict.shape_error) +
           ", \"shape_channel\": " + std::to_string(verdict.shape_channel) +
           ", \"impacts\": " + json_number(verdict.impacts) +
           ", \"noise_skewness\": " + json_array(verdict.noise_skewness) +
           ", \"noise_excess_kurtosis\": " + json_array(verdict.noise_excess_kurtosis) +
           ", \"suggested_impacts\": " + json_number(verdict.suggested_impacts) + "}";
}

// The histogram mapping's signals: null without --histogram, else the Gaussian-space standard deviation
// of every channel at every level (level 0 first) and the tables' shape.
std::string histogram_json(const dsn::BakeResult &result) {
    if (result.fields.histogram.tables.empty()) return "null";
    const dsn::HistogramMapping &mapping = result.fields.histogram;
    std::string deviations = "[";
    for (size_t l = 0; l < result.gaussian_deviations.size(); l++)
        deviations +=
            (l ? ", " : "") +
            json_array(std::vector<double>(result.gaussian_deviations[l].begin(),
                                           result.gaussian_deviations[l].begin() + result.fields.channels));
    return "{\"levels\": " + std::to_string(mapping.level_count) +
           ", \"entries\": " + std::to_string(mapping.entry_count) +
           ", \"input_low\": " + json_number(mapping.input_low_q16 / 65536.0) +
           ", \"step\": " + json_number(std::ldexp(1.0, -int(mapping.step_shift))) +
           ", \"gaussian_deviations\": " + deviations + "]}";
}

std::string report_json(const Arguments &arguments, const dsn::Image &exemplar, const dsn::BakeResult &result,
                        double seconds) {
    const dsn::BakeOptions &options = arguments.options;
    std::vector<double> mean(result.model.mean.begin(), result.model.mean.begin() + exemplar.channels);
    std::vector<double> transform(result.color_transform.begin(), result.color_transform.end());
    std::string json = "{\n";
    auto field = [&json](const char *name, const std::string &value, bool last = false) {
        json += std::string("  \"") + name + "\": " + value + (last ? "\n" : ",\n");
    };
    field("input", dsn::json_string(arguments.input));
    field("output", dsn::json_string(arguments.output));
    field("width", std::to_string(exemplar.width));
    field("height", std::to_string(exemplar.height));
    field("channels", std::to_string(exemplar.channels));
    field("radius", std::to_string(options.radius));
    field("shape", options.shape == DSN_SHAPE_DISK ? "\"disk\"" : "\"square\"");
    field("interpolation",
          options.interpolation == DSN_INTERPOLATION_BILINEAR ? "\"bilinear\"" : "\"lattice\"");
    field("iterations", std::to_string(result.sot.rme_per_iteration.size()));
    field("iterations_limit", std::to_string(options.iterations));
    field("stop_tolerance", json_number(options.stop_tolerance));
    field("stop_reason", dsn::json_string(stop_reason(result)));
    field("seed", std::to_string(options.seed));
    field("bits", std::to_string(options.bits));
    field("periodic", options.periodic ? "true" : "false");
    field("rme", json_number(result.rme));
    field("rme_luminance", json_number(result.rme_luminance));
    field("rme_quantized", json_number(result.rme_quantized));
    field("rme_without_zero_frequency", json_number(result.rme_without_zero_frequency));
    field("rme_effective", json_number(result.rme_effective));
    field("excess_kurtosis_30", json_array(result.excess_kurtosis_30));
    field("excess_kurtosis_30_luminance", json_array(result.excess_kurtosis_30_luminance));
    field("mean", json_array(mean));
    field("color_transform", json_array(transform));
    field("texton", json_array(interleaved(result.sot.texton)));
    field("rme_per_iteration", json_array(result.sot.rme_per_iteration));
    field("pyramid_levels", std::to_string(result.fields.pyramid.size()));
    field("histogram", histogram_json(result));
    field("bytes", std::to_string(result.asset.size()));
    field("verdict", verdict_json(result.verdict));
    // The CRC the asset ends with: it tells which asset this report describes.
    char crc[16];
    const size_t size = result.asset.size();
    std::snprintf(crc, sizeof crc, "\"%08x\"",
                  size < 4
                      ? 0u
                      : unsigned(result.asset[size - 4]) | unsigned(result.asset[size - 3]) << 8 |
                            unsigned(result.asset[size - 2]) << 16 | unsigned(result.asset[size - 1]) << 24);
    field("asset_crc32", crc);
    field("seconds", json_number(seconds), true);
    return json + "}\n";
}

std::string channel_list(const std::vector<double> &values, const char *format) {
    std::string list;
    for (double value : values) {
        char text[32];
        std::snprintf(text, sizeof text, format, value);
        list += (list.empty() ? "" : " ") + std::string(text);
    }
    return list;
}

void print_summary(const Arguments &arguments, const dsn::Image &exemplar, const dsn::BakeResult &result,
                   double seconds) {
    const dsn::BakeOptions &options = arguments.options;
    const int side = 2 * options.radius + 1;
    std::printf("dsn-bake: %s (%dx%d %s) -> %s\n", arguments.input.c_str(), exemplar.width, exemplar.height,
                exemplar.channels == 3 ? "RGB" : "grey", arguments.output.c_str());
    std::printf("  texton        %dx%d %s, seed %u, %d-bit, %s\n", side, side,
                options.shape == DSN_SHAPE_DISK ? "disk" : "square", options.seed, options.bits,
                options.interpolation == DSN_INTERPOLATION_BILINEAR ? "bilinear" : "lattice");
    std::printf("  iterations    %zu of at most %d (%s)\n", result.sot.rme_per_iteration.size(),
                options.iterations, stop_description(result, options).c_str());
    std::printf(
        "  RME           SOT %.4f   luminance texton %.4f   SOT quantized %.4f   (SOT without the zero "
        "frequency %.4f)\n",
        result.rme, result.rme_luminance, result.rme_quantized, result.rme_without_zero_frequency);
    std::printf(
        "  RME rendered  %.4f (quantized texton, colour transform and %s read applied: the one judged)\n",
        result.rme_effective, options.interpolation == DSN_INTERPOLATION_BILINEAR ? "bilinear" : "lattice");
    std::printf("  kurtosis @30  SOT %s   luminance texton %s\n",
                channel_list(result.excess_kurtosis_30, "%.3f").c_str(),
                channel_list(result.excess_kurtosis_30_luminance, "%.3f").c_str());
    std::printf(
        "  noise @%-5g  skewness %s   excess kurtosis %s   (as rendered, per output channel; exact)\n",
        result.verdict.impacts, channel_list(result.verdict.noise_skewness, "%.3f").c_str(),
        channel_list(result.verdict.noise_excess_kurtosis, "%.3f").c_str());
    std::printf("  shape         total variation %.3f of a random-phase copy's (standard error %.3f; 1 for a "
                "Gaussian texture, %.3f for Laplace-sparse edges)\n",
                result.verdict.shape_ratio, result.verdict.shape_error, dsn::kVerdictShapeRatio);
    if (result.fields.pyramid.empty()) {
        std::printf("  asset         %zu bytes (format 1.0, no pyramid), %.2f s\n", result.asset.size(),
                    seconds);
    } else {
        dsn::AssetFields plain = result.fields;
        plain.pyramid.clear();
        if (!plain.histogram.tables.empty()) { // without a pyramid, level 0's tables alone
            plain.histogram.level_count = 1;
            plain.histogram.tables.resize(size_t(plain.channels) * plain.histogram.entry_count);
        }
        std::printf("  asset         %zu bytes with a %zu-level pyramid (%zu without), %.2f s\n",
                    result.asset.size(), result.fields.pyramid.size(), dsn::encode_asset(plain).size(),
                    seconds);
    }
    if (!result.fields.histogram.tables.empty())
        std::printf(
            "  histogram     preserved (format 1.2): %u tables of %u entries per channel, Gaussian-space "
            "deviation %s\n",
            result.fields.histogram.level_count, result.fields.histogram.entry_count,
            channel_list(std::vector<double>(result.gaussian_deviations[0].begin(),
                                             result.gaussian_deviations[0].begin() + exemplar.channels),
                         "%.3f")
                .c_str());
    std::printf("  verdict       %s\n", result.verdict.summary.c_str());
    for (const std::string &suggestion : result.verdict.suggestions)
        std::printf("    - %s\n", suggestion.c_str());
}

std::vector<unsigned char> as_bytes(const std::string &text) {
    return std::vector<unsigned char>(text.begin(), text.end());
}

// An RGBA image whose picture lives in its alpha channel bakes as a constant: say why.
dsn::BakeResult bake_explaining_alpha(const dsn::Image &exemplar, const dsn::BakeOptions &options,
                                      bool alpha_dropped) {
    try {
        return dsn::bake(exemplar, options);
    } catch (const std::runtime_error &error) {
        if (!alpha_dropped) throw;
        throw std::runtime_error(std::string(error.what()) + " (its alpha channel is ignored)");
    }
}

// About 40 ns per pixel and iteration on one core of a current x86-64 (2048x2048 x 1000 iterations:
// 2.5 minutes): a run that would take far longer than expected says so before it starts.
void warn_if_long(const Arguments &arguments, const dsn::Image &exemplar) {
    const double seconds =
        40e-9 * double(exemplar.width) * double(exemplar.height) * double(arguments.options.iterations);
    if (arguments.quiet || seconds < 600) return;
    const bool hours = seconds >= 5400;
    std::fprintf(stderr,
                 "dsn-bake: warning: %dx%d at %d iterations takes roughly %.0f %s (about 40 ns per pixel and "
                 "iteration); fewer --iterations shorten it\n",
                 exemplar.width, exemplar.height, arguments.options.iterations,
                 hours ? seconds / 3600 : seconds / 60, hours ? "hours" : "minutes");
}

int run(const Arguments &arguments) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::string> warnings;
    const dsn::Image exemplar = dsn::load_exemplar(arguments.input, &warnings);
    if (!arguments.quiet)
        for (const std::string &warning : warnings)
            std::fprintf(stderr, "dsn-bake: warning: %s\n", warning.c_str());
    dsn::BakeOptions options = arguments.options;
    warn_if_long(arguments, exemplar);
    if (!arguments.quiet && isatty(STDERR_FILENO)) options.progress = progress_bar(exemplar, options);
    const dsn::BakeResult result = bake_explaining_alpha(exemplar, options, !warnings.empty());
    // Everything is computed before anything is written: a failure leaves no output at all.
    const std::vector<unsigned char> preview = arguments.preview.empty()
                                                   ? std::vector<unsigned char>()
                                                   : dsn::preview_png(exemplar, result, options.seed);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::vector<dsn::FileToWrite> outputs = {{arguments.output, result.asset}};
    if (!arguments.report.empty())
        outputs.push_back({arguments.report, as_bytes(report_json(arguments, exemplar, result, seconds))});
    if (!arguments.preview.empty()) outputs.push_back({arguments.preview, preview});
    dsn::write_files_atomically(outputs);
    if (!arguments.quiet) print_summary(arguments, exemplar, result, seconds);
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    return dsn::run_tool("dsn-bake", kUsage, argc, argv,
                         [](dsn::CommandLine &command_line) { return run(parse_arguments(command_line)); });
}
