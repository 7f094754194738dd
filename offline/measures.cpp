// measures.cpp - relative model error (OT distance between Gaussian models) and DSN excess kurtosis.
#include "bake_internal.h"

#include <cmath>
#include <stdexcept>

namespace dsn {

double relative_model_error(const Spectrum &model, const Spectrum &texton) {
    if (model.width != texton.width || model.height != texton.height || model.channels != texton.channels)
        throw std::invalid_argument("relative_model_error: spectra of different shapes");
    const size_t plane = model.plane_size();
    double model_energy = 0, texton_energy = 0, cross = 0;
    for (size_t i = 1; i < plane; i++) { // xi = 0 left out: the runtime subtracts the noise's mean
        std::complex<double> inner = 0;
        for (int c = 0; c < model.channels; c++) {
            const std::complex<double> u = model.values[size_t(c) * plane + i];
            const std::complex<double> t = texton.values[size_t(c) * plane + i];
            model_energy += std::norm(u);
            texton_energy += std::norm(t);
            inner += std::conj(u) * t;
        }
        cross += std::abs(inner);
    }
    if (!(model_energy > 0)) return 0;
    return std::sqrt(std::max(0.0, model_energy + texton_energy - 2 * cross) / model_energy);
}

double relative_model_error(const Spectrum &model, const Texton &texton) {
    return relative_model_error(model, texton_spectrum(texton, model.width, model.height));
}

std::vector<double> excess_kurtosis(const Texton &texton, double impacts_per_pixel) {
    if (!(impacts_per_pixel > 0)) throw std::invalid_argument("impacts per pixel must be positive");
    const double lambda = impacts_per_pixel / texton.support.size();
    const size_t plane = texton.support.mask.size();
    std::vector<double> kurtosis(size_t(texton.channels), 0.0);
    for (int c = 0; c < texton.channels; c++) {
        double square_sum = 0, fourth_sum = 0;
        for (size_t i = 0; i < plane; i++) {
            const double square = texton.values[size_t(c) * plane + i] * texton.values[size_t(c) * plane + i];
            square_sum += square;
            fourth_sum += square * square;
        }
        if (square_sum > 0) kurtosis[size_t(c)] = fourth_sum / (lambda * square_sum * square_sum);
    }
    return kurtosis;
}

} // namespace dsn
