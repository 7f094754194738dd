// preview.cpp - the preview sheet: exemplar | Gaussian reference (spectral ADSN) | texton | runtime DSN
// (and, for a histogram-preserving bake, the same noise through the asset's mapping), each labelled, and
// the bake's verdict below. The only offline file that calls the runtime: the
// synthesis is what the baked asset really gives.
#include "bake_internal.h"
#include "dsn/dsn.h"
#include "label.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <stb_image_write.h>

namespace dsn {
namespace {

const int kGap = 4;
const unsigned char kBackground = 40, kText = 225;

void append_bytes(void *context, void *data, int size) {
    auto *bytes = static_cast<std::vector<unsigned char> *>(context);
    const auto *begin = static_cast<const unsigned char *>(data);
    bytes->insert(bytes->end(), begin, begin + size);
}

// An RGB 8-bit canvas.
struct Sheet {
    int width, height;
    std::vector<unsigned char> pixels;
    void put(int x, int y, const double rgb[3]) {
        for (int c = 0; c < 3; c++)
            pixels[(size_t(y) * size_t(width) + size_t(x)) * 3 + size_t(c)] =
                (unsigned char)std::lround(std::clamp(rgb[c], 0.0, 1.0) * 255);
    }
};

// Draws a planar image (grey or RGB) at (left, top).
void draw(Sheet &sheet, const Image &image, int left, int top) {
    for (int y = 0; y < image.height; y++)
        for (int x = 0; x < image.width; x++) {
            double rgb[3];
            for (int c = 0; c < 3; c++) rgb[c] = image.at(x, y, image.channels == 3 ? c : 0);
            sheet.put(left + x, top + y, rgb);
        }
}

// The Gaussian version of the exemplar: mean + t_u convolved with a white noise (spectral ADSN).
Image gaussian_version(const GaussianModel &model, uint32_t seed) {
    const Spectrum noise = forward_dft(white_noise(model.width, model.height, seed));
    Spectrum product = model.spectrum;
    const size_t plane = product.plane_size();
    for (int c = 0; c < model.channels; c++)
        for (size_t i = 0; i < plane; i++) product.values[size_t(c) * plane + i] *= noise.values[i];
    Image image = inverse_dft(product);
    for (int c = 0; c < model.channels; c++)
        for (size_t i = 0; i < plane; i++) image.values[size_t(c) * plane + i] += model.mean[size_t(c)];
    return image;
}

// The texton at 0.5 + t / (2 max |t|), enlarged by an integer factor and centred in a width x height panel.
Image texton_panel(const Texton &texton, int width, int height) {
    const int side = texton.support.side();
    const int factor = std::max(1, std::min(width, height) / side);
    double largest = 0;
    for (double value : texton.values) largest = std::max(largest, std::fabs(value));
    Image panel;
    panel.width = width, panel.height = height, panel.channels = texton.channels;
    panel.values.assign(size_t(width) * size_t(height) * size_t(texton.channels), kBackground / 255.0);
    const int left = (width - side * factor) / 2, top = (height - side * factor) / 2;
    for (int y = 0; y < side * factor; y++)
        for (int x = 0; x < side * factor; x++)
            for (int c = 0; c < texton.channels; c++) {
                if (left + x < 0 || left + x >= width || top + y < 0 || top + y >= height) continue;
                const double value =
                    texton.at(x / factor - texton.support.radius, y / factor - texton.support.radius, c);
                panel.at(left + x, top + y, c) = largest > 0 ? 0.5 + value / (2 * largest) : 0.5;
            }
    return panel;
}

// A DSN synthesis of the asset by the runtime's tile evaluation, exemplar-sized: continuous for a bilinear
// asset (what it was baked for), lattice otherwise; `flags` as dsn_config's.
Image runtime_synthesis(const std::vector<unsigned char> &asset_bytes, int width, int height, uint32_t seed,
                        uint32_t flags = 0) {
    dsn_asset asset;
    dsn_noise noise;
    dsn_config config;
    int error = dsn_asset_load(&asset, asset_bytes.data(), asset_bytes.size());
    if (error == DSN_OK) {
        dsn_config_defaults(&config);
        config.seed = seed;
        config.flags = flags;
        error = dsn_noise_init(&noise, &asset, &config);
    }
    if (error != DSN_OK) throw std::runtime_error(std::string("preview: ") + dsn_error_message(error));
    const int channels = int(asset.channels);
    std::vector<float> values(size_t(width) * size_t(height) * size_t(channels));
    if (asset.interpolation == DSN_INTERPOLATION_BILINEAR) {
        const int64_t one = int64_t(1) << 32;
        const dsn_grid grid = {0, 0, one, 0, 0, one};
        std::vector<unsigned char> scratch(std::max<size_t>(
            1, dsn_continuous_tile_scratch_size(&noise, &grid, uint32_t(width), uint32_t(height))));
        error = dsn_continuous_tile_float(&noise, &grid, uint32_t(width), uint32_t(height), values.data(),
                                          scratch.data(), scratch.size());
    } else {
        std::vector<unsigned char> scratch(
            dsn_lattice_tile_scratch_size(&noise, uint32_t(width), uint32_t(height)));
        error = dsn_lattice_tile_float(&noise, 0, 0, uint32_t(width), uint32_t(height), values.data(),
                                       scratch.data(), scratch.size());
    }
    if (error != DSN_OK) throw std::runtime_error(std::string("preview: ") + dsn_error_message(error));
    Image image;
    image.width = width, image.height = height, image.channels = channels;
    image.values.resize(values.size());
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            for (int c = 0; c < channels; c++)
                image.at(x, y, c) =
                    values[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c)];
    return image;
}

// Gaussian-space values (a histogram-preserving bake's model and noise: decorrelated channels of mean
// `mean` and standard deviation `deviation`) as colours with the exemplar's mean and covariance: the
// plain Gaussian output, mu + P diag(sqrt(variance_k)) (g_k - mean_k) / deviation_k.
Image gaussian_colours(const Image &gaussian, const ColourBasis &basis, const std::array<double, 3> &mean,
                       const std::array<double, 3> &deviation) {
    Image image = gaussian;
    const size_t plane = size_t(image.width) * size_t(image.height);
    for (size_t i = 0; i < plane; i++) {
        std::array<double, 3> v = {0, 0, 0};
        for (int k = 0; k < image.channels; k++)
            v[size_t(k)] = std::sqrt(basis.variances[size_t(k)]) *
                           (gaussian.values[size_t(k) * plane + i] - mean[size_t(k)]) / deviation[size_t(k)];
        for (int c = 0; c < image.channels; c++) {
            double value = basis.mean[size_t(c)];
            for (int k = 0; k < image.channels; k++) value += basis.vectors[size_t(c * 3 + k)] * v[size_t(k)];
            image.values[size_t(c) * plane + i] = value;
        }
    }
    return image;
}

// `text` cut into lines of at most `columns` characters, at spaces where it can.
std::vector<std::string> wrap(const std::string &text, size_t columns) {
    std::vector<std::string> lines;
    std::string rest = text;
    while (rest.size() > columns) {
        size_t cut = rest.rfind(' ', columns);
        if (cut == std::string::npos || cut == 0) cut = columns;
        lines.push_back(rest.substr(0, cut));
        rest = rest.substr(rest[cut] == ' ' ? cut + 1 : cut);
    }
    lines.push_back(rest);
    return lines;
}

} // namespace

std::vector<unsigned char> preview_png(const Image &exemplar, const BakeResult &result, uint32_t seed) {
    const int width = exemplar.width, height = exemplar.height;
    std::vector<Image> panels = {exemplar, gaussian_version(result.model, seed),
                                 texton_panel(result.quantized_texton, width, height),
                                 runtime_synthesis(result.asset, width, height, seed)};
    std::vector<std::string> labels = {"exemplar", "Gaussian reference", "texton (SOT)", "runtime synthesis"};
    if (!result.fields.histogram.tables.empty()) {
        // The model and the noise are Gaussian-space: shown as the plain Gaussian output would be, beside
        // the same noise through the asset's mapping.
        const ColourBasis &basis = result.histogram.basis;
        const Matrix3 covariance = model_covariance(result.model);
        std::array<double, 3> model_deviation = {1, 1, 1}, noise_mean = {0, 0, 0};
        for (int k = 0; k < exemplar.channels; k++) {
            model_deviation[size_t(k)] = std::sqrt(covariance[size_t(k * 4)]);
            noise_mean[size_t(k)] = double(result.fields.mean[k]) / double(DSN_Q24_ONE);
        }
        panels[1] = gaussian_colours(panels[1], basis, result.model.mean, model_deviation);
        panels[3] =
            gaussian_colours(runtime_synthesis(result.asset, width, height, seed, DSN_FLAG_NO_HISTOGRAM),
                             basis, noise_mean, result.gaussian_deviations[0]);
        panels.push_back(runtime_synthesis(result.asset, width, height, seed));
        labels.push_back("histogram-preserving");
    }
    const int count = int(panels.size());
    const int scale = width >= 160 ? 2 : 1, line = 12 * scale;
    std::vector<int> columns(panels.size());
    int sheet_width = (count - 1) * kGap;
    for (int i = 0; i < count; i++) {
        columns[size_t(i)] = std::max(width, label_width(labels[size_t(i)], scale) + kGap);
        sheet_width += columns[size_t(i)];
    }
    // The verdict under the panels, wrapped to the sheet's width (a character is 6 font units wide).
    std::vector<std::string> text;
    const size_t characters = size_t(std::max(20, sheet_width / (6 * scale) - 1));
    for (const std::string &part : wrap("verdict: " + result.verdict.summary, characters))
        text.push_back(part);
    for (const std::string &suggestion : result.verdict.suggestions)
        for (const std::string &part : wrap("- " + suggestion, characters)) text.push_back(part);
    Sheet sheet;
    sheet.width = sheet_width;
    sheet.height = line + kGap + height + kGap + int(text.size()) * line;
    sheet.pixels.assign(size_t(sheet.width) * size_t(sheet.height) * 3, kBackground);
    int left = 0;
    for (size_t i = 0; i < size_t(count); i++) {
        draw_label(sheet.pixels, sheet.width, sheet.height, left, 0, labels[i], scale, kText);
        draw(sheet, panels[i], left + (columns[i] - width) / 2, line + kGap);
        left += columns[i] + kGap;
    }
    for (size_t i = 0; i < text.size(); i++)
        draw_label(sheet.pixels, sheet.width, sheet.height, 0, line + 2 * kGap + height + int(i) * line,
                   text[i], scale, kText);
    std::vector<unsigned char> png;
    if (!stbi_write_png_to_func(append_bytes, &png, sheet.width, sheet.height, 3, sheet.pixels.data(),
                                sheet.width * 3))
        throw std::runtime_error("preview: PNG encoding failed");
    return png;
}

} // namespace dsn
