// bake.cpp - the whole pipeline: input checks, model, SOT, baseline, measures, colour, quantization, pyramid,
// asset.
#include "bake_internal.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dsn {
namespace {

const double kKurtosisImpacts = 30;

int32_t to_q24(double value) {
    return int32_t(std::clamp(std::round(value * double(DSN_Q24_ONE)), -2147483647.0, 2147483647.0));
}

void check_options(const BakeOptions &options) {
    if (options.radius < 1 || options.radius > kMaxRadius)
        throw std::invalid_argument("radius " + std::to_string(options.radius) + " out of range 1.." +
                                    std::to_string(kMaxRadius));
    if (options.shape != DSN_SHAPE_RECTANGLE && options.shape != DSN_SHAPE_DISK)
        throw std::invalid_argument("unknown shape");
    if (options.iterations < 1 || options.iterations > 1000000)
        throw std::invalid_argument("iterations must be in 1..1000000");
    if (options.bits != 8 && options.bits != 16) throw std::invalid_argument("bits must be 8 or 16");
    if (options.interpolation != DSN_INTERPOLATION_LATTICE &&
        options.interpolation != DSN_INTERPOLATION_BILINEAR)
        throw std::invalid_argument("unknown interpolation");
    if (options.interpolation == DSN_INTERPOLATION_BILINEAR && options.radius > kMaxBilinearRadius)
        throw std::invalid_argument("radius " + std::to_string(options.radius) +
                                    " is for lattice bakes only: " + "a bilinear bake's radius is at most " +
                                    std::to_string(kMaxBilinearRadius) +
                                    " (its lattice texton is 2 texels wider, at most 255)");
    if (!(options.stop_tolerance >= 0) || !std::isfinite(options.stop_tolerance))
        throw std::invalid_argument("stop tolerance must be finite and non-negative");
}

} // namespace

void check_bake_input(const Image &exemplar, const BakeOptions &options) {
    check_options(options);
    // The exemplar must contain S - S: both sides at least 2(2r+1) - 1 = 4r + 1.
    const int needed = 4 * options.radius + 1;
    const int smaller = std::min(exemplar.width, exemplar.height);
    if (exemplar.width < needed || exemplar.height < needed) {
        const int fitting = (smaller - 1) / 4;
        throw std::runtime_error("image " + std::to_string(exemplar.width) + "x" +
                                 std::to_string(exemplar.height) + " is too small for radius " +
                                 std::to_string(options.radius) + " (both sides must be at least " +
                                 std::to_string(needed) + "); " +
                                 (fitting >= 1 ? "radius " + std::to_string(fitting) + " would fit"
                                               : std::string("no radius fits")));
    }
}

AssetFields assemble_asset(const BakeResult &result, const BakeOptions &options, int exemplar_width,
                           int exemplar_height) {
    const QuantizedTexton quantized = quantize(result.sot.texton, options.bits);
    AssetFields fields;
    const int channels = result.model.channels;
    fields.channels = uint32_t(channels);
    fields.bits = uint32_t(options.bits);
    fields.shape = options.shape;
    fields.interpolation = options.interpolation;
    fields.width = fields.height = uint32_t(result.sot.texton.support.side());
    fields.default_impacts_q16 = DSN_IMPACTS_DEFAULT_Q16;
    for (int c = 0; c < channels; c++) {
        fields.scale[c] = quantized.scale_raw[size_t(c)];
        fields.mean[c] = to_q24(result.model.mean[size_t(c)]);
    }
    set_identity_color_transform(fields);
    for (int row = 0; row < channels; row++)
        for (int column = 0; column < channels; column++)
            fields.color_transform[row * 3 + column] =
                to_q24(result.color_transform[size_t(row * 3 + column)]);
    fields.bake_iterations = uint32_t(result.sot.rme_per_iteration.size());
    fields.bake_seed = options.seed;
    fields.bake_rme_q24 = uint32_t(to_q24(std::min(result.rme_quantized, 127.0)));
    fields.exemplar_width = uint32_t(exemplar_width);
    fields.exemplar_height = uint32_t(exemplar_height);
    fields.texton = quantized.values;
    if (options.pyramid) fields.pyramid = texton_pyramid(fields);
    if (options.interpolation == DSN_INTERPOLATION_BILINEAR) set_lattice_texton(fields);
    return fields;
}

BakeResult bake(const Image &exemplar, const BakeOptions &options) {
    check_bake_input(exemplar, options);
    const Support support = support_mask(options.radius, options.shape);
    BakeResult result;
    // The histogram-preserving mode bakes the Gaussianized exemplar; the verdict still judges the exemplar.
    if (options.histogram) result.histogram = histogram_model(exemplar);
    result.model = gaussian_model(options.histogram ? gaussianize(exemplar, result.histogram) : exemplar,
                                  options.periodic);
    result.target = interpolation_target(result.model.spectrum, options.interpolation);

    SotOptions sot_options;
    sot_options.iterations = options.iterations;
    sot_options.seed = options.seed;
    sot_options.stop_tolerance = options.stop_tolerance;
    sot_options.minimum_iterations = early_stop_minimum_iterations(exemplar.width, exemplar.height);
    sot_options.progress = options.progress;
    result.sot = sot_alternating_projections(result.target, support, sot_options);
    result.rme = relative_model_error(result.target, result.sot.texton);
    result.rme_without_zero_frequency =
        relative_model_error_without_zero_frequency(result.target, result.sot.texton);

    result.luminance = luminance_texton(result.target, support);
    result.rme_luminance = relative_model_error(result.target, result.luminance);
    result.excess_kurtosis_30 = excess_kurtosis(result.sot.texton, kKurtosisImpacts);
    result.excess_kurtosis_30_luminance = excess_kurtosis(result.luminance, kKurtosisImpacts);

    if (options.use_color_transform)
        result.color_transform = color_transform(texton_covariance(result.sot.texton, options.interpolation),
                                                 model_covariance(result.model), exemplar.channels);
    else if (exemplar.channels == 1)
        result.color_transform = {1, 0, 0, 0, 0, 0, 0, 0, 0};

    result.quantized_texton =
        dequantize(quantize(result.sot.texton, options.bits), support, exemplar.channels);
    result.rme_quantized = relative_model_error(result.target, result.quantized_texton);
    result.fields = assemble_asset(result, options, exemplar.width, exemplar.height);
    if (options.histogram) {
        result.fields.histogram = histogram_mapping(result.histogram, result.fields);
        for (uint32_t l = 0; l < result.fields.histogram.level_count; l++)
            result.gaussian_deviations.push_back(gaussian_space_deviation(result.fields, int(l)));
    }
    Matrix3 stored_transform{};
    for (size_t i = 0; i < stored_transform.size(); i++)
        stored_transform[i] = double(result.fields.color_transform[i]) / double(DSN_Q24_ONE);
    result.rme_effective = effective_model_error(result.model.spectrum, result.quantized_texton,
                                                 stored_transform, options.interpolation);
    result.asset = encode_asset(result.fields);
    result.verdict = bake_verdict(exemplar, result, options);
    return result;
}

} // namespace dsn
