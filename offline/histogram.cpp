// histogram.cpp - the baker's side of the histogram-preserving output (format 1.2, Heitz and Neyret,
// "High-Performance By-Example Noise using a Histogram-Preserving Blending Operator", HPG 2018): the
// exemplar's colour basis, its Gaussianization, and the lookup tables that map the baked noise back.
#include "bake_internal.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace dsn {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTableOne = double(1 << DSN_HISTOGRAM_VALUE_FRACTION_BITS);
constexpr double kQ16One = 65536; // input_low and expected: Q16.16

double normal_density(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2 * kPi); }

int32_t rounded(double value, double one, double limit) {
    return int32_t(std::clamp(std::round(value * one), -limit, limit));
}

// K of the fields as the runtime reads it (Q8.24; grey uses K[0] alone).
Matrix3 stored_transform(const AssetFields &fields) {
    Matrix3 transform{};
    for (int i = 0; i < 9; i++)
        transform[size_t(i)] = double(fields.color_transform[i]) / double(DSN_Q24_ONE);
    return transform;
}

// A square window of interleaved values (q * scale * 2^exponent / 2^40) as a planar Texton.
Texton window_texton(const std::vector<int32_t> &values, uint32_t width, uint32_t height, int exponent,
                     const AssetFields &fields) {
    if (width != height) throw std::invalid_argument("histogram mapping: the texton must be square");
    Texton texton;
    texton.support.radius = int(width - 1) / 2;
    texton.support.mask.assign(size_t(width) * width, 1);
    texton.channels = int(fields.channels);
    const size_t plane = texton.support.mask.size(), channels = fields.channels;
    texton.values.resize(plane * channels);
    for (size_t c = 0; c < channels; c++)
        for (size_t i = 0; i < plane; i++)
            texton.values[c * plane + i] =
                std::ldexp(double(values[i * channels + c]) * double(fields.scale[c]), exponent - 40);
    return texton;
}

} // namespace

ColourBasis principal_components(const Image &image) {
    ColourBasis basis;
    basis.channels = image.channels;
    const size_t plane = size_t(image.width) * size_t(image.height);
    for (int c = 0; c < image.channels; c++) {
        double sum = 0;
        for (size_t i = 0; i < plane; i++) sum += image.values[size_t(c) * plane + i];
        basis.mean[size_t(c)] = sum / double(plane);
    }
    Matrix3 covariance{};
    for (int a = 0; a < image.channels; a++)
        for (int b = 0; b < image.channels; b++) {
            double sum = 0;
            for (size_t i = 0; i < plane; i++)
                sum += (image.values[size_t(a) * plane + i] - basis.mean[size_t(a)]) *
                       (image.values[size_t(b) * plane + i] - basis.mean[size_t(b)]);
            covariance[size_t(a * 3 + b)] = sum / double(plane);
        }
    if (image.channels == 1) {
        basis.variances[0] = covariance[0];
        return basis;
    }
    std::array<double, 3> values;
    Matrix3 vectors;
    symmetric_eigen(covariance, values, vectors);
    std::array<int, 3> order = {0, 1, 2};
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return values[size_t(a)] > values[size_t(b)]; });
    for (int k = 0; k < 3; k++) {
        const int from = order[size_t(k)];
        basis.variances[size_t(k)] = std::max(0.0, values[size_t(from)]);
        int largest = 0;
        for (int c = 1; c < 3; c++)
            if (std::fabs(vectors[size_t(c * 3 + from)]) > std::fabs(vectors[size_t(largest * 3 + from)]))
                largest = c;
        const double sign = vectors[size_t(largest * 3 + from)] < 0 ? -1 : 1;
        for (int c = 0; c < 3; c++) basis.vectors[size_t(c * 3 + k)] = sign * vectors[size_t(c * 3 + from)];
    }
    return basis;
}

HistogramModel histogram_model(const Image &exemplar) {
    HistogramModel model;
    model.basis = principal_components(exemplar);
    const size_t plane = size_t(exemplar.width) * size_t(exemplar.height);
    for (int k = 0; k < exemplar.channels; k++) {
        std::vector<double> values(plane, 0.0);
        for (int c = 0; c < exemplar.channels; c++) {
            const double weight = model.basis.vectors[size_t(c * 3 + k)];
            const double mean = model.basis.mean[size_t(c)];
            for (size_t i = 0; i < plane; i++)
                values[i] += weight * (exemplar.values[size_t(c) * plane + i] - mean);
        }
        std::sort(values.begin(), values.end());
        model.sorted.push_back(std::move(values));
    }
    return model;
}

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

double normal_quantile(double p) {
    if (!(p > 0 && p < 1)) throw std::invalid_argument("normal_quantile: probability outside (0, 1)");
    // Acklam's rational approximation (relative error 1.2e-9), then one Halley step on erfc.
    static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                               1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
    static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                               6.680131188771972e+01, -1.328068155288572e+01};
    static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                               -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
    static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                               3.754408661907416e+00};
    const double low = 0.02425;
    double x;
    if (p < low || p > 1 - low) {
        const double q = std::sqrt(-2 * std::log(p < low ? p : 1 - p));
        x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
        if (p > 1 - low) x = -x;
    } else {
        const double q = p - 0.5, r = q * q;
        x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
            (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
    }
    const double error = normal_cdf(x) - p, u = error * std::sqrt(2 * kPi) * std::exp(0.5 * x * x);
    return x - u / (1 + 0.5 * x * u);
}

double empirical_quantile(const std::vector<double> &sorted, double probability) {
    if (sorted.empty()) throw std::invalid_argument("empirical_quantile: no values");
    const double position =
        std::clamp(probability * double(sorted.size()) - 0.5, 0.0, double(sorted.size() - 1));
    const size_t below = size_t(position);
    const size_t above = std::min(below + 1, sorted.size() - 1);
    const double fraction = position - double(below);
    return sorted[below] + fraction * (sorted[above] - sorted[below]);
}

Image gaussianize(const Image &exemplar, const HistogramModel &model) {
    Image gaussian;
    gaussian.width = exemplar.width, gaussian.height = exemplar.height, gaussian.channels = exemplar.channels;
    const size_t plane = size_t(exemplar.width) * size_t(exemplar.height);
    gaussian.values.assign(plane * size_t(exemplar.channels), 0.0);
    std::vector<double> values(plane);
    std::vector<size_t> order(plane);
    for (int k = 0; k < exemplar.channels; k++) {
        std::fill(values.begin(), values.end(), 0.0);
        for (int c = 0; c < exemplar.channels; c++) {
            const double weight = model.basis.vectors[size_t(c * 3 + k)];
            const double mean = model.basis.mean[size_t(c)];
            for (size_t i = 0; i < plane; i++)
                values[i] += weight * (exemplar.values[size_t(c) * plane + i] - mean);
        }
        std::iota(order.begin(), order.end(), size_t(0));
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return values[a] < values[b]; });
        double *out = &gaussian.values[size_t(k) * plane];
        for (size_t first = 0; first < plane;) {
            size_t end = first + 1;
            while (end < plane && values[order[end]] == values[order[first]]) end++;
            const double rank = 0.5 * double(first + end - 1); // the tie group's average rank
            const double g = normal_quantile((rank + 0.5) / double(plane));
            for (size_t i = first; i < end; i++) out[order[i]] = g;
            first = end;
        }
        double mean = 0, square = 0;
        for (size_t i = 0; i < plane; i++) mean += out[i];
        mean /= double(plane);
        for (size_t i = 0; i < plane; i++) square += (out[i] - mean) * (out[i] - mean);
        // The component keeps its share of the variance: a weak, mostly-noise component at unit variance
        // would weigh as much as the strongest one in the shared phase of the texton, and the colour
        // transform would mix its noise into the visible channels.
        const double share = model.basis.variances[0] > 0
                                 ? std::sqrt(model.basis.variances[size_t(k)] / model.basis.variances[0])
                                 : 1.0;
        const double deviation = std::sqrt(square / double(plane));
        for (size_t i = 0; i < plane; i++) out[i] = deviation > 0 ? share * (out[i] - mean) / deviation : 0.0;
    }
    return gaussian;
}

namespace {

constexpr int kHermiteTerms = 256;
constexpr int kLatentIterations = 30;

// The weights w_n of R(rho) = Cov(T(X), T(Y)) / Var T = sum_n w_n rho^n (Mehler's expansion), X and Y
// standard normal with correlation rho and T(z) the empirical quantile of `sorted` at normal_cdf(z), for
// n = 1..kHermiteTerms: w_n = c_n^2 / Var T, c_n = E[T(Z) h_n(Z)] with the normalized Hermite polynomials,
// from E[T h_n] = E[T' h_(n-1)] / sqrt(n) with T a step of s_(i+1) - s_i between ranks i and i + 1, at
// z_i = normal_quantile((i + 1) / n) (the empirical quantile's ramp between them is 1/n wide). The weights
// sum to 1 with the last one: the variance beyond the terms. Empty when T is constant.
std::vector<double> hermite_weights(const std::vector<double> &sorted) {
    const size_t count = sorted.size();
    std::vector<double> coefficients(kHermiteTerms + 1, 0.0), h(kHermiteTerms + 1);
    for (size_t i = 0; i + 1 < count; i++) {
        const double jump = sorted[i + 1] - sorted[i];
        if (!(jump > 0)) continue;
        const double z = normal_quantile(double(i + 1) / double(count)), weight = jump * normal_density(z);
        h[0] = 1, h[1] = z;
        for (int n = 1; n < kHermiteTerms; n++)
            h[size_t(n + 1)] =
                (z * h[size_t(n)] - std::sqrt(double(n)) * h[size_t(n - 1)]) / std::sqrt(n + 1.0);
        for (int n = 1; n <= kHermiteTerms; n++)
            coefficients[size_t(n)] += weight * h[size_t(n - 1)] / std::sqrt(double(n));
    }
    double sum = 0, square = 0;
    for (double value : sorted) sum += value, square += value * value;
    const double variance = square / double(count) - (sum / double(count)) * (sum / double(count));
    if (!(variance > 0)) return {};
    std::vector<double> weights(kHermiteTerms + 1, 0.0);
    double kept = 0;
    for (int n = 1; n <= kHermiteTerms; n++)
        kept += weights[size_t(n)] = coefficients[size_t(n)] * coefficients[size_t(n)] / variance;
    weights[0] = std::max(0.0, 1 - kept); // the rest, beyond the terms (see correlation_function)
    return weights;
}

// R(rho) from the weights: the terms, and the rest spread beyond them as a step's weights decay, n^(-3/2)
// (the slowest decay of a monotone T: a jump), over the next 63 kHermiteTerms terms (`tail`: those
// decays, summing to 1).
double correlation_function(const std::vector<double> &weights, const std::vector<double> &tail, double rho) {
    double sum = 0, power = 1;
    for (size_t n = 1; n < weights.size(); n++) sum += weights[n] * (power *= rho);
    if (weights[0] > 0) {
        double rest = 0;
        for (double decay : tail) {
            rest += decay * (power *= rho);
            if (std::fabs(power) < 1e-12) break;
        }
        sum += weights[0] * rest;
    }
    return sum;
}

std::vector<double> tail_decays() {
    std::vector<double> tail;
    double norm = 0;
    for (int n = kHermiteTerms + 1; n < 64 * (kHermiteTerms + 1); n++)
        tail.push_back(std::pow(double(n), -1.5)), norm += tail.back();
    for (double &decay : tail) decay /= norm;
    return tail;
}

} // namespace

Image latent_gaussianize(const Image &exemplar, const HistogramModel &model, bool periodic) {
    const Image gaussian = gaussianize(exemplar, model);
    const int channels = exemplar.channels;
    const size_t plane = size_t(exemplar.width) * size_t(exemplar.height);
    // The decorrelated channels v_k of the exemplar and their correlations, and the phases of the
    // Gaussianized ones (of the periodic components when the bake takes them, as the plain bake does).
    Image decorrelated = gaussian;
    for (int k = 0; k < channels; k++) {
        double *out = &decorrelated.values[size_t(k) * plane];
        std::fill(out, out + plane, 0.0);
        for (int c = 0; c < channels; c++) {
            const double weight = model.basis.vectors[size_t(c * 3 + k)], mean = model.basis.mean[size_t(c)];
            for (size_t i = 0; i < plane; i++)
                out[i] += weight * (exemplar.values[size_t(c) * plane + i] - mean);
        }
    }
    Spectrum power = forward_dft(periodic ? periodic_component(decorrelated) : decorrelated);
    const Spectrum phases = forward_dft(periodic ? periodic_component(gaussian) : gaussian);
    for (std::complex<float> &value : power.values) value = std::norm(value);
    const Image correlation = inverse_dft(power); // N times the autocovariance
    Image latent = gaussian;
    latent.values.assign(gaussian.values.size(), 0.0);
    const std::vector<double> tail = tail_decays();
    for (int k = 0; k < channels; k++) {
        const std::vector<double> weights = hermite_weights(model.sorted[size_t(k)]);
        const double *r = &correlation.values[size_t(k) * plane];
        if (weights.empty() || !(r[0] > 0)) continue; // a constant channel stays 0
        // R on a grid of rho over [-1, 1], dense towards 1 (rho = 1 - 2 (1 - j / grid)^2, where R is
        // steepest: a jump's R is 1 - O(sqrt(1 - rho))), made non-decreasing, inverted by interpolation.
        const int grid = 4096;
        std::vector<double> grid_rho(grid + 1), table(grid + 1);
        for (int j = 0; j <= grid; j++) {
            const double from_one = 1 - double(j) / grid;
            grid_rho[size_t(j)] = 1 - 2 * from_one * from_one;
            const double value = j == grid ? 1.0 : correlation_function(weights, tail, grid_rho[size_t(j)]);
            table[size_t(j)] = j > 0 ? std::max(value, table[size_t(j - 1)]) : value;
        }
        Image rho_image;
        rho_image.width = exemplar.width, rho_image.height = exemplar.height, rho_image.channels = 1;
        rho_image.values.resize(plane);
        for (size_t i = 0; i < plane; i++) {
            const double target = std::clamp(r[i] / r[0], table.front(), table.back());
            const size_t above = size_t(std::lower_bound(table.begin(), table.end(), target) - table.begin());
            double rho = grid_rho[above];
            if (above > 0 && table[above] > table[above - 1])
                rho -= (grid_rho[above] - grid_rho[above - 1]) * (table[above] - target) /
                       (table[above] - table[above - 1]);
            rho_image.values[i] = i == 0 ? 1.0 : rho;
        }
        // The latent spectrum: the DFT of rho, whose negative values (rho need not be positive definite) are
        // cut, then refined by the iteration of Yamazaki and Shinozuka (1988): S *= S_target / S_out, S_out
        // the DFT of R(rho_S), rho_S the correlation of S, so that the mapped noise's spectrum approaches
        // the exemplar's where the cut moved it.
        const auto mapped_correlation = [&](double rho) {
            const size_t above =
                size_t(std::lower_bound(grid_rho.begin(), grid_rho.end(), rho) - grid_rho.begin());
            if (above == 0) return table[0];
            const double fraction = (rho - grid_rho[above - 1]) / (grid_rho[above] - grid_rho[above - 1]);
            return table[above - 1] + fraction * (table[above] - table[above - 1]);
        };
        Image wanted_correlation = rho_image;
        for (size_t i = 0; i < plane; i++) wanted_correlation.values[i] = r[i] / r[0];
        const Spectrum target_spectrum = forward_dft(wanted_correlation);
        Spectrum latent_spectrum = forward_dft(rho_image);
        for (std::complex<float> &value : latent_spectrum.values) value = std::max(0.0f, value.real());
        latent_spectrum.values[0] = 0;
        for (int iteration = 0; iteration < kLatentIterations; iteration++) {
            const Image current = inverse_dft(latent_spectrum);
            const double variance = current.values[0];
            if (!(variance > 0)) break;
            Image mapped = current;
            for (size_t i = 0; i < plane; i++)
                mapped.values[i] = mapped_correlation(std::clamp(current.values[i] / variance, -1.0, 1.0));
            const Spectrum output = forward_dft(mapped);
            for (size_t i = 1; i < plane; i++) {
                const double out = output.values[i].real(),
                             wanted = std::max(0.0f, target_spectrum.values[i].real());
                const double ratio = out > 0 ? std::clamp(wanted / out, 0.1, 10.0) : 1.0;
                latent_spectrum.values[i] = float(latent_spectrum.values[i].real() * ratio);
            }
        }
        double energy = 0;
        for (const std::complex<float> &value : latent_spectrum.values) energy += value.real();
        double share = 0;
        for (size_t i = 0; i < plane; i++) share += std::pow(gaussian.values[size_t(k) * plane + i], 2);
        share = std::sqrt(share / double(plane));
        Spectrum channel = latent_spectrum;
        for (size_t i = 0; i < plane; i++) {
            const std::complex<double> phase = phases.values[size_t(k) * plane + i];
            const double modulus = std::abs(phase);
            const double amplitude =
                i == 0 || !(energy > 0)
                    ? 0.0
                    : share * double(plane) * std::sqrt(latent_spectrum.values[i].real() / energy);
            channel.values[i] = std::complex<float>(modulus > 0 ? amplitude * phase / modulus : amplitude);
        }
        const Image field = inverse_dft(channel);
        std::copy(field.values.begin(), field.values.end(), latent.values.begin() + long(size_t(k) * plane));
    }
    return latent;
}

std::array<double, 3> gaussian_space_deviation(const AssetFields &fields, int level) {
    Texton texton;
    uint32_t interpolation = DSN_INTERPOLATION_BILINEAR;
    double area = 1;
    if (level == 0) {
        texton = window_texton(fields.texton, fields.width, fields.height, 0, fields);
        interpolation = fields.interpolation;
    } else {
        if (level < 0 || size_t(level) > fields.pyramid.size())
            throw std::invalid_argument("gaussian_space_deviation: no such pyramid level");
        const PyramidLevel &stored = fields.pyramid[size_t(level - 1)];
        texton = window_texton(stored.values, stored.width, stored.height, stored.exponent, fields);
        area = std::ldexp(1.0, 2 * level);
    }
    const Matrix3 covariance = texton_covariance(texton, interpolation);
    const Matrix3 transform = stored_transform(fields);
    const int channels = int(fields.channels);
    std::array<double, 3> deviation = {0, 0, 0};
    for (int c = 0; c < channels; c++) {
        double variance = 0;
        for (int k = 0; k < channels; k++)
            for (int m = 0; m < channels; m++)
                variance += transform[size_t(c * 3 + k)] * covariance[size_t(k * 3 + m)] *
                            transform[size_t(c * 3 + m)];
        deviation[size_t(c)] = std::sqrt(std::max(0.0, variance * area));
    }
    return deviation;
}

double smoothed_table_value(const std::vector<double> &table, double low, double step, double y, double rho) {
    const size_t n = table.size();
    if (n == 0) throw std::invalid_argument("smoothed_table_value: empty table");
    if (!(rho > 0)) { // f(y) itself
        const double position = std::clamp((y - low) / step, 0.0, double(n - 1));
        const size_t i = std::min(size_t(position), n - 1), j = std::min(i + 1, n - 1);
        return table[i] + (position - double(i)) * (table[j] - table[i]);
    }
    const auto z = [&](size_t i) { return (low + double(i) * step - y) / rho; };
    double sum = table[0] * normal_cdf(z(0)) + table[n - 1] * (1 - normal_cdf(z(n - 1)));
    for (size_t i = 0; i + 1 < n; i++) {
        // f(y + rho z) = T_i + slope (y + rho z - x_i) on [z_i, z_(i+1)].
        const double slope = (table[i + 1] - table[i]) / step;
        const double a = z(i), b = z(i + 1);
        sum += (table[i] + slope * (y - (low + double(i) * step))) * (normal_cdf(b) - normal_cdf(a)) +
               slope * rho * (normal_density(a) - normal_density(b));
    }
    return sum;
}

HistogramMapping histogram_mapping(const HistogramModel &model, const AssetFields &fields) {
    const int channels = int(fields.channels);
    if (model.basis.channels != channels || model.sorted.size() != size_t(channels))
        throw std::invalid_argument("histogram mapping: the model's channels differ from the asset's");
    HistogramMapping mapping;
    mapping.entry_count = kHistogramEntries;
    mapping.step_shift = kHistogramStepShift;
    mapping.input_low_q16 = int32_t(kHistogramInputLow * kQ16One);
    mapping.level_count = uint32_t(std::min<size_t>(1 + fields.pyramid.size(), DSN_HISTOGRAM_MAX_LEVELS));
    const double step = std::ldexp(1.0, -kHistogramStepShift);
    const double q24 = double(DSN_Q24_ONE), limit_q24 = 2147483647.0;
    for (int i = 0; i < 9; i++) mapping.rotation[i] = 0;
    for (int c = 0; c < channels; c++) {
        mapping.centre[c] = rounded(model.basis.mean[size_t(c)], q24, limit_q24);
        for (int k = 0; k < channels; k++)
            mapping.rotation[c * 3 + k] = rounded(model.basis.vectors[size_t(c * 3 + k)], q24, limit_q24);
    }

    std::vector<std::array<double, 3>> deviations;
    for (uint32_t l = 0; l < mapping.level_count; l++)
        deviations.push_back(gaussian_space_deviation(fields, int(l)));
    mapping.tables.assign(size_t(mapping.level_count) * size_t(channels) * kHistogramEntries, 0);
    const auto entry = [&](uint32_t l, int k, int i) -> int32_t & {
        return mapping.tables[(size_t(l) * size_t(channels) + size_t(k)) * kHistogramEntries + size_t(i)];
    };
    for (int k = 0; k < channels; k++) {
        const double mean = double(fields.mean[k]) / q24, sigma = deviations[0][size_t(k)];
        // Level 0, quantized: the later levels smooth the table the runtime really reads. A channel
        // without variance (grey stored as RGB) maps everything to its median.
        std::vector<double> base(kHistogramEntries);
        for (int i = 0; i < kHistogramEntries; i++) {
            const double y = kHistogramInputLow + i * step;
            const double probability = sigma > 0 ? normal_cdf((y - mean) / sigma) : 0.5;
            const double value = empirical_quantile(model.sorted[size_t(k)], probability);
            entry(0, k, i) = rounded(value, kTableOne, 32767);
            base[size_t(i)] = entry(0, k, i) / kTableOne;
        }
        for (uint32_t l = 1; l < mapping.level_count; l++) {
            const double level_sigma = deviations[l][size_t(k)];
            const double rho = std::sqrt(std::max(0.0, sigma * sigma - level_sigma * level_sigma));
            for (int i = 0; i < kHistogramEntries; i++)
                entry(l, k, i) = rounded(
                    smoothed_table_value(base, kHistogramInputLow, step, kHistogramInputLow + i * step, rho),
                    kTableOne, 32767);
        }
        mapping.expected_q16[k] =
            rounded(smoothed_table_value(base, kHistogramInputLow, step, mean, sigma), kQ16One, limit_q24);
    }
    return mapping;
}

} // namespace dsn
