// gaussian_model.cpp - periodic component, mean and t_u of an exemplar; the interpolation target. The
// model is that of Galerne, Gousseau and Morel, "Random phase textures: theory and synthesis" (2011).
#include "bake_internal.h"

#include <cmath>
#include <stdexcept>

namespace dsn {
namespace {

const double kTwoPi = 6.283185307179586;

// Lap_int u: the 4-neighbour Laplacian using only the neighbours inside the image.
Image interior_laplacian(const Image &u) {
    Image laplacian = u;
    const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
    for (int c = 0; c < u.channels; c++)
        for (int y = 0; y < u.height; y++)
            for (int x = 0; x < u.width; x++) {
                double sum = 0;
                for (int n = 0; n < 4; n++) {
                    const int nx = x + dx[n], ny = y + dy[n];
                    if (nx >= 0 && nx < u.width && ny >= 0 && ny < u.height)
                        sum += u.at(nx, ny, c) - u.at(x, y, c);
                }
                laplacian.at(x, y, c) = sum;
            }
    return laplacian;
}

bool is_constant(const Image &u) {
    for (int c = 0; c < u.channels; c++) {
        const double first = u.at(0, 0, c);
        for (int y = 0; y < u.height; y++)
            for (int x = 0; x < u.width; x++)
                if (u.at(x, y, c) != first) return false;
    }
    return true;
}

} // namespace

Image periodic_component(const Image &u) {
    Spectrum spectrum = forward_dft(interior_laplacian(u));
    const size_t plane = spectrum.plane_size();
    for (int c = 0; c < u.channels; c++) {
        double mean = 0;
        for (size_t i = 0; i < plane; i++) mean += u.values[size_t(c) * plane + i];
        for (int xi2 = 0; xi2 < u.height; xi2++)
            for (int xi1 = 0; xi1 < u.width; xi1++) {
                std::complex<float> &value =
                    spectrum.values[size_t(c) * plane + size_t(xi2) * size_t(u.width) + size_t(xi1)];
                if (xi1 == 0 && xi2 == 0) {
                    value = float(mean); // p^(0) = u^(0): the same mean
                    continue;
                }
                // The periodic Laplacian multiplies the spectrum by 2cos + 2cos - 4 (< 0 off the origin).
                const double multiplier =
                    2 * std::cos(kTwoPi * xi1 / u.width) + 2 * std::cos(kTwoPi * xi2 / u.height) - 4;
                value = std::complex<float>(std::complex<double>(value) / multiplier);
            }
    }
    return inverse_dft(spectrum);
}

GaussianModel gaussian_model(const Image &u, bool periodic) {
    if (u.width <= 0 || u.height <= 0 || u.channels <= 0) throw std::runtime_error("empty image");
    if (is_constant(u)) throw std::runtime_error("constant image (no variance): nothing to synthesize");
    GaussianModel model;
    model.width = u.width;
    model.height = u.height;
    model.channels = u.channels;
    model.t_u = periodic ? periodic_component(u) : u;
    const size_t plane = size_t(u.width) * size_t(u.height);
    const double normalization = 1.0 / std::sqrt(double(plane));
    for (int c = 0; c < u.channels; c++) {
        double sum = 0;
        for (size_t i = 0; i < plane; i++) sum += u.values[size_t(c) * plane + i];
        model.mean[size_t(c)] = sum / double(plane);
        for (size_t i = 0; i < plane; i++) {
            double &value = model.t_u.values[size_t(c) * plane + i];
            value = (value - model.mean[size_t(c)]) * normalization;
        }
    }
    model.spectrum = forward_dft(model.t_u);
    return model;
}

Spectrum interpolation_target(const Spectrum &model, uint32_t interpolation) {
    if (interpolation == DSN_INTERPOLATION_LATTICE) return model;
    if (interpolation != DSN_INTERPOLATION_BILINEAR) throw std::invalid_argument("unknown interpolation");
    Spectrum target = model;
    const size_t plane = model.plane_size();
    for (int xi2 = 0; xi2 < model.height; xi2++)
        for (int xi1 = 0; xi1 < model.width; xi1++) {
            const double spline = (2.0 / 3 + std::cos(kTwoPi * xi1 / model.width) / 3) *
                                  (2.0 / 3 + std::cos(kTwoPi * xi2 / model.height) / 3);
            const double gain = 1 / std::sqrt(spline); // spline >= 1/9: gain <= 3
            for (int c = 0; c < model.channels; c++) {
                std::complex<float> &value =
                    target.values[size_t(c) * plane + size_t(xi2) * size_t(model.width) + size_t(xi1)];
                value = std::complex<float>(std::complex<double>(value) * gain);
            }
        }
    return target;
}

} // namespace dsn
