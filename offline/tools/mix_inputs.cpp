// mix_inputs.cpp - the rendering tools' mixing options: parsed, checked, and configured into a dsn_mix
// with its weights from an image (mix_inputs.h).
#include "mix_inputs.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "asset_file.h"
#include "dsn/bake.h"

namespace dsn {

const char *const mix_usage =
    "  --mix B.dsnt[,C.dsnt,D.dsnt]\n"
    "                       mix the asset A (material 0, whose seed, density and cells the mix\n"
    "                       takes) with these materials, each impulse carrying one of them, drawn\n"
    "                       from --weights at its position (the runtime's dsn_mix)\n"
    "  --weights W.png      the mixing weights, one image pixel per weight sample: a grey image for\n"
    "                       two materials (black: A, white: B, grey between), else one channel per\n"
    "                       material (R: A, G: B, B: C; PNG, JPEG or PGM/PPM; alpha ignored)\n"
    "  --weights-shift S    each weight pixel covers 2^S x 2^S texels, S in 0..16 (default 0), the\n"
    "                       image's top-left corner at texel (0, 0)\n"
    "  --weights-periodic   repeat the weight image (else its edge pixels extend it)\n";

bool parse_mix_flag(CommandLine &command_line, MixOptions &options) {
    if (command_line.is("--weights-periodic")) {
        command_line.no_value();
        options.weights_periodic = true;
    } else if (command_line.is("--mix")) {
        const std::string list = command_line.value();
        options.paths.clear();
        for (size_t start = 0;;) {
            const size_t comma = list.find(',', start);
            const std::string path = list.substr(start, comma == std::string::npos ? comma : comma - start);
            if (path.empty())
                throw UsageError("--mix needs asset paths separated by ',', not '" + list + "'");
            options.paths.push_back(path);
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
        if (options.paths.size() > DSN_MIX_MAX_MATERIALS - 1)
            throw UsageError("--mix takes at most " + std::to_string(DSN_MIX_MAX_MATERIALS - 1) +
                             " assets (the asset itself is the first material)");
    } else if (command_line.is("--weights")) {
        options.weights_path = command_line.path_value();
    } else if (command_line.is("--weights-shift")) {
        options.weights_shift = static_cast<uint32_t>(parse_integer(command_line, 0, 16));
    } else {
        return false;
    }
    return true;
}

void check_mix_options(const MixOptions &options, std::vector<NamedPath> &inputs) {
    if (options.paths.empty() != options.weights_path.empty())
        throw UsageError(options.paths.empty() ? "--weights needs --mix (the other materials)"
                                               : "--mix needs --weights (where each material lies)");
    for (const std::string &path : options.paths) inputs.push_back({"--mix", path});
    if (!options.weights_path.empty()) inputs.push_back({"--weights", options.weights_path});
}

namespace {

// The weight samples of `count` materials from the image at options.weights_path.
void load_weights(const MixOptions &options, uint32_t count, MixInputs &inputs) {
    const Image image = load_exemplar(options.weights_path, nullptr);
    if (image.channels == 1 && count != 2)
        throw std::runtime_error(options.weights_path + ": a grey weight image mixes two materials, not " +
                                 std::to_string(count) + ": give one channel per material (RGB)");
    if (image.channels != 1 && uint32_t(image.channels) < count)
        throw std::runtime_error(options.weights_path + ": " + std::to_string(image.channels) +
                                 " channels for " + std::to_string(count) + " materials");
    const auto byte = [](double value) {
        return uint8_t(std::lround(std::min(1.0, std::max(0.0, value)) * 255));
    };
    inputs.weights.clear();
    for (int y = 0; y < image.height; y++)
        for (int x = 0; x < image.width; x++)
            for (uint32_t m = 0; m < count; m++) {
                const uint8_t grey = byte(image.at(x, y, 0));
                inputs.weights.push_back(image.channels == 1 ? (m == 0 ? uint8_t(255 - grey) : grey)
                                                             : byte(image.at(x, y, int(m))));
            }
    inputs.control.weights = inputs.weights.data();
    inputs.control.width = uint32_t(image.width);
    inputs.control.height = uint32_t(image.height);
    inputs.control.spacing_shift = options.weights_shift;
    inputs.control.flags = options.weights_periodic ? DSN_MIX_PERIODIC_X | DSN_MIX_PERIODIC_Y : 0u;
}

} // namespace

void configure_mix(const MixOptions &options, const dsn_noise &noise, const dsn_config &config,
                   bool continuous,
                   const std::function<void(const std::string &, const dsn_asset &)> &check_asset,
                   MixInputs &inputs) {
    const size_t count = options.paths.size() + 1;
    inputs.bytes.resize(count);
    inputs.assets.resize(count);
    inputs.noises.resize(count);
    inputs.noises[0] = noise;
    for (size_t m = 1; m < count; m++) {
        const std::string &path = options.paths[m - 1];
        inputs.bytes[m] = load_asset_file(path, inputs.assets[m]);
        check_asset(path, inputs.assets[m]);
        int err = dsn_noise_init(&inputs.noises[m], &inputs.assets[m], &config);
        if (err == DSN_OK && continuous) err = dsn_continuous_check(&inputs.noises[m]);
        if (err != DSN_OK) throw std::runtime_error(path + ": " + dsn_error_message(err));
    }
    std::vector<const dsn_noise *> materials;
    for (const dsn_noise &one : inputs.noises) materials.push_back(&one);
    const int err = dsn_mix_init(&inputs.mix, materials.data(), uint32_t(count));
    if (err == DSN_ERR_UNSUPPORTED)
        throw std::runtime_error(
            "a mix applies no histogram mapping: re-bake the materials without --histogram");
    if (err != DSN_OK) throw std::runtime_error(std::string("--mix: ") + dsn_error_message(err));
    load_weights(options, uint32_t(count), inputs);
}

} // namespace dsn
