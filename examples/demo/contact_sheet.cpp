// dsn-contact-sheet: one labelled PNG that shows a bake at a glance: the exemplar, its Gaussian
// reference (a random-phase synthesis of the exemplar's Gaussian model), the runtime synthesis, the
// texton, the renderer scene (and, when given, the same scene bump-mapped under it), and (when given) the
// scene's ground toward the horizon read three ways: unfiltered, filtered and supersampled, enlarged so
// the pixels show. Labels are drawn by the baker's draw_label (offline/label.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <stb_image.h>

#include "dsn/dsn.h"
#include "offline/bake_internal.h"
#include "offline/file_input.h"
#include "offline/label.h"
#include "offline/tools/asset_file.h"
#include "offline/tools/command_line.h"
#include "offline/tools/file_output.h"
#include "offline/tools/png_output.h"

namespace {

const char *const usage =
    "usage: dsn-contact-sheet --exemplar E.png --asset A.dsnt --synthesis S.png --scene R.png -o SHEET.png\n"
    "                         [--seed S] [--scene-bump B.png [--scene-bump-note TEXT]]\n"
    "                         [--scene-surface S.png [--scene-surface-note TEXT]]\n"
    "                         [--horizon-unfiltered U.png --horizon-filtered F.png\n"
    "                          --horizon-supersampled S.png [--horizon-note TEXT]]\n"
    "                         [--mix M.png --mix-first A.png --mix-second B.png]\n"
    "       dsn-contact-sheet --print-size IMAGE     (prints \"WIDTH HEIGHT\")\n"
    "Lays out exemplar | Gaussian reference | runtime synthesis | texton, and the scene below, labelled;\n"
    "under it, given --scene-bump, the same scene with bump mapping (dsn-tiny-renderer --shading bump),\n"
    "and given --scene-surface, the scene with no texture coordinates (dsn-tiny-renderer --mapping\n"
    "surface), each under its TEXT;\n"
    "then, given all three --horizon images (the same crop of the scene rendered unfiltered, filtered\n"
    "and supersampled), those side by side, enlarged by a whole factor, under TEXT;\n"
    "then, given the three --mix images (a mix of two materials whose weights go from the first at the\n"
    "left edge to the second at the right edge, and each material alone), the mix above the crossfade\n"
    "of the two, computed here with the same weights.\n"
    "Flags take --flag value or --flag=value; -h, --help, --version. Errors: one line on stderr, exit 2\n"
    "for a usage mistake (ending \"(see --help)\"), exit 1 when an input cannot be read or written.\n";

const int kPanel = 256, kGap = 12, kLabel = 30;
const int kSheetWidth = 4 * kPanel + 5 * kGap;
const int kHorizonPanel = (kSheetWidth - 4 * kGap) / 3, kHorizonHeight = 240;

// An 8-bit RGB picture.
struct Picture {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    unsigned char *at(int x, int y) { return &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
};

Picture blank(int width, int height, unsigned char grey) {
    Picture picture;
    picture.width = width;
    picture.height = height;
    picture.rgb.assign(size_t(width) * size_t(height) * 3, grey);
    return picture;
}

// The PNGs this program reads are the demo's own renders, read as carefully as every input (a regular
// file, bounded like an exemplar).
std::vector<unsigned char> read_image_file(const std::string &path) {
    return dsn::read_input_file(path, dsn::kMaxExemplarFileBytes, "an image");
}

Picture load_png(const std::string &path) {
    const std::vector<unsigned char> bytes = read_image_file(path);
    int width, height, channels;
    unsigned char *data =
        stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 3);
    if (!data) throw std::runtime_error("cannot read image " + path + ": " + stbi_failure_reason());
    Picture picture;
    picture.width = width;
    picture.height = height;
    picture.rgb.assign(data, data + size_t(width) * size_t(height) * 3);
    stbi_image_free(data);
    return picture;
}

// A planar dsn::Image in [0, 1] -> picture (grey repeated).
Picture from_image(const dsn::Image &image) {
    Picture picture = blank(image.width, image.height, 0);
    for (int y = 0; y < image.height; y++)
        for (int x = 0; x < image.width; x++)
            for (int c = 0; c < 3; c++) {
                double v = image.at(x, y, image.channels == 3 ? c : 0);
                picture.at(x, y)[c] = static_cast<unsigned char>(std::lround(std::clamp(v, 0.0, 1.0) * 255));
            }
    return picture;
}

// Copies `source` centred into the w x h box at (x0, y0) of `sheet`, cropping what does not fit.
void paste(Picture &sheet, const Picture &source, int x0, int y0, int w, int h) {
    const int sx0 = std::max(0, (source.width - w) / 2), sy0 = std::max(0, (source.height - h) / 2);
    const int dx0 = x0 + std::max(0, (w - source.width) / 2), dy0 = y0 + std::max(0, (h - source.height) / 2);
    const int cw = std::min(w, source.width), ch = std::min(h, source.height);
    for (int y = 0; y < ch; y++)
        for (int x = 0; x < cw; x++) {
            const unsigned char *from =
                &source.rgb[(size_t(sy0 + y) * size_t(source.width) + size_t(sx0 + x)) * 3];
            std::copy(from, from + 3, sheet.at(dx0 + x, dy0 + y));
        }
}

// `source` enlarged by the largest whole factor that fits a w x h box (pixels repeated, so they show).
Picture enlarged(const Picture &source, int w, int h) {
    const int factor = std::max(1, std::min(w / source.width, h / source.height));
    Picture picture = blank(source.width * factor, source.height * factor, 0);
    for (int y = 0; y < picture.height; y++)
        for (int x = 0; x < picture.width; x++) {
            const unsigned char *from =
                &source.rgb[(size_t(y / factor) * size_t(source.width) + size_t(x / factor)) * 3];
            std::copy(from, from + 3, picture.at(x, y));
        }
    return picture;
}

// Text at (x, y), `scale` pixels per font unit, in a dark grey (the bake preview's label drawing).
void draw_label(Picture &sheet, int x, int y, const std::string &text, int scale) {
    dsn::draw_label(sheet.rgb, sheet.width, sheet.height, x, y, text, scale, 40);
}

// A random-phase synthesis of the exemplar's Gaussian model: the reference the DSN approximates.
Picture gaussian_reference(const dsn::Image &exemplar, uint32_t seed) {
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, true);
    dsn::Image synthesis = dsn::inverse_dft(dsn::random_phase_start(model.spectrum, seed));
    const double gain = std::sqrt(double(model.width) * model.height); // t_u = (p - m) / sqrt(MN)
    for (int c = 0; c < synthesis.channels; c++)
        for (int y = 0; y < synthesis.height; y++)
            for (int x = 0; x < synthesis.width; x++)
                synthesis.at(x, y, c) = model.mean[size_t(c)] + gain * synthesis.at(x, y, c);
    return from_image(synthesis);
}

// The texton after the colour transform (what one impulse adds), mid-grey = 0, enlarged by an integer
// factor to fill the panel.
Picture texton_picture(const std::string &asset_path) {
    dsn_asset asset;
    const std::vector<unsigned char> bytes = dsn::load_asset_file(asset_path, asset); // asset points into it
    const int w = int(asset.width), h = int(asset.height), channels = int(asset.channels);
    std::vector<double> values(size_t(w * h * 3), 0.0);
    double peak = 1e-30;
    for (int row = 0; row < h; row++)
        for (int column = 0; column < w; column++)
            for (int c = 0; c < 3; c++) {
                double sum = 0;
                for (int k = 0; k < channels; k++)
                    sum += asset.color_transform[(channels == 3 ? c : 0) * 3 + k] / 16777216.0 *
                           dsn_asset_texton_value(&asset, uint32_t(row), uint32_t(column), uint32_t(k)) *
                           std::ldexp(double(asset.scale[k]), -40);
                values[size_t((row * w + column) * 3 + c)] = sum;
                peak = std::max(peak, std::fabs(sum));
            }
    const int zoom = std::max(1, kPanel / std::max(w, h));
    Picture picture = blank(w * zoom, h * zoom, 0);
    for (int y = 0; y < h * zoom; y++)
        for (int x = 0; x < w * zoom; x++)
            for (int c = 0; c < 3; c++)
                picture.at(x, y)[c] = static_cast<unsigned char>(
                    std::lround(127.5 + 127.5 * values[size_t(((y / zoom) * w + x / zoom) * 3 + c)] / peak));
    return picture;
}

int run(dsn::CommandLine &command_line) {
    std::string exemplar_path, asset_path, synthesis_path, scene_path, output;
    std::string horizon_paths[3], horizon_note = "the ground toward the horizon";
    std::string mix_paths[3]; // the mix, the first material alone, the second alone
    // The scene again, below it: bump-mapped, and with the surface noise (no texture coordinates).
    struct ExtraScene {
        std::string path, note;
        Picture picture;
    } extra[2] = {{"", "the same scene bump-mapped (dsn-tiny-renderer --shading bump)", {}},
                  {"", "no texture coordinates: the surface noise, a torus added (--mapping surface)", {}}};
    uint32_t seed = 1;
    while (command_line.next()) {
        if (command_line.is("--print-size")) {
            const std::string image = command_line.value();
            const std::vector<unsigned char> bytes = read_image_file(image);
            int width, height, channels;
            if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels))
                throw std::runtime_error("cannot read image " + image);
            std::printf("%d %d\n", width, height);
            return 0;
        } else if (command_line.is("--exemplar")) {
            exemplar_path = command_line.value();
        } else if (command_line.is("--asset")) {
            asset_path = command_line.value();
        } else if (command_line.is("--synthesis")) {
            synthesis_path = command_line.value();
        } else if (command_line.is("--scene")) {
            scene_path = command_line.value();
        } else if (command_line.is("--scene-bump")) {
            extra[0].path = command_line.value();
        } else if (command_line.is("--scene-bump-note")) {
            extra[0].note = command_line.value();
        } else if (command_line.is("--scene-surface")) {
            extra[1].path = command_line.value();
        } else if (command_line.is("--scene-surface-note")) {
            extra[1].note = command_line.value();
        } else if (command_line.is("--horizon-unfiltered")) {
            horizon_paths[0] = command_line.value();
        } else if (command_line.is("--horizon-filtered")) {
            horizon_paths[1] = command_line.value();
        } else if (command_line.is("--horizon-supersampled")) {
            horizon_paths[2] = command_line.value();
        } else if (command_line.is("--mix")) {
            mix_paths[0] = command_line.value();
        } else if (command_line.is("--mix-first")) {
            mix_paths[1] = command_line.value();
        } else if (command_line.is("--mix-second")) {
            mix_paths[2] = command_line.value();
        } else if (command_line.is("--horizon-note")) {
            horizon_note = command_line.value();
        } else if (command_line.is("-o") || command_line.is("--output")) {
            output = command_line.path_value();
        } else if (command_line.is("--seed")) {
            seed = uint32_t(dsn::parse_integer(command_line, 0, 4294967295ll));
        } else {
            command_line.unknown();
        }
    }
    if (exemplar_path.empty() || asset_path.empty() || synthesis_path.empty() || scene_path.empty() ||
        output.empty())
        throw dsn::UsageError("--exemplar, --asset, --synthesis, --scene and -o are all needed");
    const int horizon_given =
        int(!horizon_paths[0].empty()) + int(!horizon_paths[1].empty()) + int(!horizon_paths[2].empty());
    if (horizon_given != 0 && horizon_given != 3)
        throw dsn::UsageError(
            "--horizon-unfiltered, --horizon-filtered and --horizon-supersampled go together");

    const int mix_given =
        int(!mix_paths[0].empty()) + int(!mix_paths[1].empty()) + int(!mix_paths[2].empty());
    if (mix_given != 0 && mix_given != 3)
        throw dsn::UsageError("--mix, --mix-first and --mix-second go together");
    std::vector<dsn::NamedPath> inputs = {{"the --exemplar input", exemplar_path},
                                          {"the --asset input", asset_path},
                                          {"the --synthesis input", synthesis_path},
                                          {"the --scene input", scene_path}};
    if (!extra[0].path.empty()) inputs.push_back({"the --scene-bump input", extra[0].path});
    if (!extra[1].path.empty()) inputs.push_back({"the --scene-surface input", extra[1].path});
    for (const std::string &horizon : horizon_paths)
        if (!horizon.empty()) inputs.push_back({"a --horizon-* input", horizon});
    for (const std::string &mix : mix_paths)
        if (!mix.empty()) inputs.push_back({"a --mix input", mix});
    dsn::check_outputs(inputs, {{"-o", output}});

    const dsn::Image exemplar = dsn::load_exemplar(exemplar_path, nullptr);
    const Picture scene = load_png(scene_path);
    const int scene_height = std::min(scene.height, 480);
    int extra_height = 0; // the extra scenes' height, labels and gaps included
    for (ExtraScene &scene_again : extra)
        if (!scene_again.path.empty()) {
            scene_again.picture = load_png(scene_again.path);
            extra_height += kLabel + std::min(scene_again.picture.height, 480) + kGap;
        }
    const int horizon_height = horizon_given ? 2 * kLabel + kHorizonHeight + kGap : 0;
    Picture mixes[3];
    for (int p = 0; p < 3 && mix_given; p++) mixes[p] = load_png(mix_paths[p]);
    if (mix_given && (mixes[1].width != mixes[0].width || mixes[2].width != mixes[0].width ||
                      mixes[1].height != mixes[0].height || mixes[2].height != mixes[0].height))
        throw std::runtime_error("the --mix images differ in size");
    const int mix_rows = mix_given ? std::min(mixes[0].height, 200) : 0;
    const int mix_height = mix_given ? 2 * (kLabel + mix_rows) + 2 * kGap : 0;
    Picture sheet = blank(
        kSheetWidth,
        2 * kLabel + kPanel + scene_height + 3 * kGap + extra_height + horizon_height + mix_height, 235);
    const Picture panels[4] = {from_image(exemplar), gaussian_reference(exemplar, seed),
                               load_png(synthesis_path), texton_picture(asset_path)};
    const char *labels[4] = {"exemplar", "Gaussian reference", "runtime synthesis", "texton (SOT)"};
    for (int p = 0; p < 4; p++) {
        const int x = kGap + p * (kPanel + kGap);
        draw_label(sheet, x, kGap, labels[p], 2);
        Picture box = blank(kPanel, kPanel, 200);
        paste(box, panels[p], 0, 0, kPanel, kPanel);
        paste(sheet, box, x, kGap + kLabel, kPanel, kPanel);
    }
    const int scene_top = 2 * kGap + kLabel + kPanel;
    draw_label(sheet, kGap, scene_top,
               extra[0].path.empty()
                   ? "renderer scene (continuous mode, filtered, dsn-tiny-renderer)"
                   : "renderer scene, flat shading (continuous mode, filtered, dsn-tiny-renderer)",
               2);
    paste(sheet, scene, kGap, scene_top + kLabel, kSheetWidth - 2 * kGap, scene_height);
    int extra_top = scene_top + kLabel + scene_height + kGap;
    for (const ExtraScene &scene_again : extra)
        if (!scene_again.path.empty()) {
            draw_label(sheet, kGap, extra_top, scene_again.note, 2);
            const int height = std::min(scene_again.picture.height, 480);
            paste(sheet, scene_again.picture, kGap, extra_top + kLabel, kSheetWidth - 2 * kGap, height);
            extra_top += kLabel + height + kGap;
        }
    if (horizon_given) {
        const int top = scene_top + kLabel + scene_height + kGap + extra_height;
        Picture crops[3];
        for (int p = 0; p < 3; p++) crops[p] = load_png(horizon_paths[p]);
        const int factor =
            std::max(1, std::min(kHorizonPanel / crops[0].width, kHorizonHeight / crops[0].height));
        draw_label(sheet, kGap, top, horizon_note + ", enlarged " + std::to_string(factor) + "x", 2);
        const char *horizon_labels[3] = {"unfiltered (1 sample)", "filtered (anisotropic)",
                                         "supersampled (8x8 samples)"};
        for (int p = 0; p < 3; p++) {
            const int x = kGap + p * (kHorizonPanel + kGap);
            draw_label(sheet, x, top + kLabel, horizon_labels[p], 2);
            Picture box = blank(kHorizonPanel, kHorizonHeight, 200);
            paste(box, enlarged(crops[p], kHorizonPanel, kHorizonHeight), 0, 0, kHorizonPanel,
                  kHorizonHeight);
            paste(sheet, box, x, top + 2 * kLabel, kHorizonPanel, kHorizonHeight);
        }
    }
    if (mix_given) {
        const int top = scene_top + kLabel + scene_height + kGap + extra_height + horizon_height;
        // The crossfade of the two materials with the mix's weights: the second's w = x / width.
        Picture crossfade = mixes[1];
        for (int y = 0; y < crossfade.height; y++)
            for (int x = 0; x < crossfade.width; x++)
                for (int c = 0; c < 3; c++) {
                    const double w = double(x) / crossfade.width;
                    crossfade.at(x, y)[c] = static_cast<unsigned char>(
                        std::lround((1 - w) * mixes[1].at(x, y)[c] + w * mixes[2].at(x, y)[c]));
                }
        draw_label(sheet, kGap, top,
                   "two materials mixed (dsn-render --mix): each impulse carries one, full contrast across",
                   2);
        paste(sheet, mixes[0], kGap, top + kLabel, kSheetWidth - 2 * kGap, mix_rows);
        const int lower = top + kLabel + mix_rows + kGap;
        draw_label(sheet, kGap, lower,
                   "the crossfade of the same two noises: greyer and blurred in the middle", 2);
        paste(sheet, crossfade, kGap, lower + kLabel, kSheetWidth - 2 * kGap, mix_rows);
    }

    dsn::write_file_atomically(output, dsn::encode_png(sheet.width, sheet.height, 3, sheet.rgb.data()));
    return 0;
}

} // namespace

int main(int argc, char **argv) { return dsn::run_tool("dsn-contact-sheet", usage, argc, argv, run); }
