// measures.cpp - relative model error (OT distance between Gaussian models, over every frequency as
// Galerne, Leclaire and Moisan define it, or without the zero frequency) and DSN excess kurtosis.
#include "bake_internal.h"

#include <cmath>
#include <stdexcept>

namespace dsn {

namespace {

// sqrt(sum (|T_u|^2 + |T|^2 - 2 |sum_c conj(T_u,c) T_c|) / sum |T_u|^2) over the frequencies from `first`
// (0: every frequency; 1: all but xi = 0, the first value of each plane).
double model_error_from(const Spectrum &model, const Spectrum &texton, size_t first) {
    if (model.width != texton.width || model.height != texton.height || model.channels != texton.channels)
        throw std::invalid_argument("relative_model_error: spectra of different shapes");
    const size_t plane = model.plane_size();
    double model_energy = 0, texton_energy = 0, cross = 0;
    for (size_t i = first; i < plane; i++) {
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

} // namespace

double relative_model_error(const Spectrum &model, const Spectrum &texton) {
    return model_error_from(model, texton, 0);
}

double relative_model_error_without_zero_frequency(const Spectrum &model, const Spectrum &texton) {
    return model_error_from(model, texton, 1);
}

double relative_model_error(const Spectrum &model, const Texton &texton) {
    return relative_model_error(model, texton_spectrum(texton, model.width, model.height));
}

double relative_model_error_without_zero_frequency(const Spectrum &model, const Texton &texton) {
    return relative_model_error_without_zero_frequency(model,
                                                       texton_spectrum(texton, model.width, model.height));
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
