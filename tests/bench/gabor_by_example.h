// gabor_by_example.h - Gabor noise by example (Galerne, Lagae, Lefebvre and Drettakis, "Gabor noise by
// example", SIGGRAPH 2012), the procedural baseline gabor_bench measures our noise against. Float and the
// standard library are fine here: this is a measuring stick, not a product.
//
// The method, as the paper builds it:
//   - the exemplar's power spectrum P = |DFT of its periodic component|^2, mean removed (here normalized
//     so that it sums to the exemplar's variance: |T_u|^2 of the baker's Gaussian model);
//   - bandwidth-quantized Gabor noise: a sum of independent sparse-convolution noises, one per bandwidth
//     q = 2 .. floor(log2(sqrt(M^2 + N^2))) of an M x N exemplar. The power spectrum of level q is a
//     non-negative sum of Gaussians G_q(xi - f) + G_q(xi + f) of full width at half maximum 2^-q cycles
//     per pixel, centred on a grid of the DFT's frequencies whose step k_q is the smallest that makes two
//     neighbouring Gaussians (normalized) correlate by at most 0.95. Its Gabor kernels
//     exp(-pi a^2 |x|^2) cos(2 pi f.x + phase), uniform phase, have a = 2 sigma_q sqrt(pi): their
//     expected power spectrum is (G_q(xi - f) + G_q(xi + f)) / (4 a^4);
//   - the weights by non-negative basis pursuit denoising over that bank of Gaussians: w >= 0 minimizing
//     |B w - P|^2 + lambda sum w, lambda = lambda_max / 8 (lambda_max: the smallest lambda for which w = 0
//     is optimal), by FISTA with a constant step until the relative duality gap is at most 0.02. B w is
//     evaluated without forming B: each level's weights, spread on their grid, are convolved by the
//     separable Gaussian on the exemplar's frequency plane (no wrap, as in the paper);
//   - colour: the channels are made independent by a linear colour transform, found by whitening the
//     colour covariance and then jointly diagonalizing the real parts of the whitened cross-spectral
//     matrices of every frequency by Jacobi rotations (Cardoso and Souloumiac, "Jacobi angles for
//     simultaneous diagonalization", 1996, which the paper cites for this); each decorrelated channel is
//     fitted as a grey noise, and a sample is the exemplar's mean plus the inverse transform of the three;
//   - evaluation by sparse convolution, per point and on a grid per bandwidth (the paper's multi-grid
//     evaluation): level q has cells of side 1/a_q (the kernel's truncation radius), a Poisson number of
//     impulses per cell seeded by a hash of the cell, each with a uniform position, a uniform phase and a
//     frequency drawn with probability proportional to its weight (importance sampling, by an alias
//     table); a point sums the impulses of the 3 x 3 cells around it.
#ifndef DSN_BENCH_GABOR_BY_EXAMPLE_H
#define DSN_BENCH_GABOR_BY_EXAMPLE_H

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <vector>

#include "offline/bake_internal.h"

namespace gabor {

const double kPi = 3.14159265358979323846;

// ---- The bank of Gaussians on the M x N frequency plane ----

// Frequencies are centred integers: i in [-(M / 2), M - 1 - M / 2] stands for i / M cycles per pixel.
struct Level {
    int q = 0;
    double sigma = 0; // cycles per pixel
    int step = 1;     // grid step k_q, in DFT samples
    int reach_x = 0, reach_y = 0;
    std::vector<double> gx, gy; // exp(-(d / M)^2 / (2 sigma^2)), d in [-reach, reach], normalized below
    std::vector<std::array<int, 2>> atoms; // one of each +-f pair, f != 0
};

struct Bank {
    int width = 0, height = 0;
    std::vector<Level> levels;
    size_t atom_count() const {
        size_t count = 0;
        for (const Level &level : levels) count += level.atoms.size();
        return count;
    }
};

inline Bank make_bank(int width, int height) {
    Bank bank;
    bank.width = width;
    bank.height = height;
    const int highest =
        int(std::floor(std::log2(std::sqrt(double(width) * width + double(height) * height))));
    const int extreme_x = (width - 1) / 2, extreme_y = (height - 1) / 2;
    for (int q = 2; q <= highest; q++) {
        Level level;
        level.q = q;
        level.sigma = std::pow(2.0, -q) / (2 * std::sqrt(2 * std::log(2.0)));
        // The Gaussian's discrete values on the paper's 2M x 2N plane, and its L2 norm there.
        auto gaussian = [&](int d, int size) {
            const double f = double(d) / size;
            return std::exp(-f * f / (2 * level.sigma * level.sigma));
        };
        double norm_x = 0, norm_y = 0;
        for (int d = -width; d < width; d++) norm_x += gaussian(d, width) * gaussian(d, width);
        for (int d = -height; d < height; d++) norm_y += gaussian(d, height) * gaussian(d, height);
        // Grid step: the first shift whose normalized correlation is at most 1 - 0.05 along both axes.
        int step = 0;
        for (double correlation = 1; correlation > 0.95;) {
            step++;
            double cx = 0, cy = 0;
            for (int d = -width; d < width; d++) cx += gaussian(d, width) * gaussian(d + step, width);
            for (int d = -height; d < height; d++) cy += gaussian(d, height) * gaussian(d + step, height);
            correlation = std::max(cx / norm_x, cy / norm_y);
        }
        level.step = step;
        level.reach_x = std::min(width, int(std::ceil(5 * level.sigma * width)));
        level.reach_y = std::min(height, int(std::ceil(5 * level.sigma * height)));
        // Unit L2 norm of the 2-D Gaussian, split over the two factors.
        const double scale = 1 / std::sqrt(std::sqrt(norm_x * norm_y));
        for (int d = -level.reach_x; d <= level.reach_x; d++) level.gx.push_back(gaussian(d, width) * scale);
        for (int d = -level.reach_y; d <= level.reach_y; d++) level.gy.push_back(gaussian(d, height) * scale);
        for (int j = 0; j <= extreme_y; j += step)
            for (int i = -(extreme_x / step) * step; i <= extreme_x; i += step)
                if (j > 0 || i > 0) level.atoms.push_back({i, j});
        bank.levels.push_back(level);
    }
    return bank;
}

// Centred frequency plane: value of (i, j) at [(j + height / 2) * width + i + width / 2].
struct Plane {
    int width, height;
    size_t at(int i, int j) const { return size_t(j + height / 2) * size_t(width) + size_t(i + width / 2); }
    bool inside(int i, int j) const {
        return i >= -(width / 2) && i < width - width / 2 && j >= -(height / 2) && j < height - height / 2;
    }
};

// out = B w (the centred plane), w in the order of the bank's atoms.
inline void apply_bank(const Bank &bank, const std::vector<double> &weights, std::vector<double> &out) {
    const Plane plane{bank.width, bank.height};
    out.assign(size_t(bank.width) * size_t(bank.height), 0.0);
    std::vector<double> rows; // per grid row (centred j), the horizontal convolution
    size_t first = 0;
    for (const Level &level : bank.levels) {
        const int grid_rows = 2 * ((bank.height - 1) / 2 / level.step) + 1, row_origin = grid_rows / 2;
        rows.assign(size_t(grid_rows) * size_t(bank.width), 0.0);
        bool any = false;
        for (size_t a = 0; a < level.atoms.size(); a++) {
            const double w = weights[first + a];
            if (w == 0) continue;
            any = true;
            for (int sign = -1; sign <= 1; sign += 2) { // f and -f
                const int i = sign * level.atoms[a][0], j = sign * level.atoms[a][1];
                double *row = &rows[size_t(j / level.step + row_origin) * size_t(bank.width)];
                for (int d = -level.reach_x; d <= level.reach_x; d++) {
                    const int x = i + d;
                    if (x >= -(bank.width / 2) && x < bank.width - bank.width / 2)
                        row[x + bank.width / 2] += w * level.gx[size_t(d + level.reach_x)];
                }
            }
        }
        first += level.atoms.size();
        if (!any) continue;
        for (int y = -(bank.height / 2); y < bank.height - bank.height / 2; y++)
            for (int r = 0; r < grid_rows; r++) {
                const int d = y - (r - row_origin) * level.step;
                if (d < -level.reach_y || d > level.reach_y) continue;
                const double g = level.gy[size_t(d + level.reach_y)];
                const double *row = &rows[size_t(r) * size_t(bank.width)];
                double *target = &out[plane.at(-(bank.width / 2), y)];
                for (int x = 0; x < bank.width; x++) target[x] += g * row[x];
            }
    }
}

// out = B^T r.
inline void apply_bank_transposed(const Bank &bank, const std::vector<double> &residual,
                                  std::vector<double> &out) {
    const Plane plane{bank.width, bank.height};
    out.assign(bank.atom_count(), 0.0);
    std::vector<double> rows;
    size_t first = 0;
    for (const Level &level : bank.levels) {
        const int grid_rows = 2 * ((bank.height - 1) / 2 / level.step) + 1, row_origin = grid_rows / 2;
        rows.assign(size_t(grid_rows) * size_t(bank.width), 0.0);
        for (int r = 0; r < grid_rows; r++) {
            const int j = (r - row_origin) * level.step;
            double *row = &rows[size_t(r) * size_t(bank.width)];
            for (int d = -level.reach_y; d <= level.reach_y; d++) {
                const int y = j + d;
                if (y < -(bank.height / 2) || y >= bank.height - bank.height / 2) continue;
                const double g = level.gy[size_t(d + level.reach_y)];
                const double *source = &residual[plane.at(-(bank.width / 2), y)];
                for (int x = 0; x < bank.width; x++) row[x] += g * source[x];
            }
        }
        for (size_t a = 0; a < level.atoms.size(); a++) {
            double sum = 0;
            for (int sign = -1; sign <= 1; sign += 2) {
                const int i = sign * level.atoms[a][0], j = sign * level.atoms[a][1];
                const double *row = &rows[size_t(j / level.step + row_origin) * size_t(bank.width)];
                for (int d = -level.reach_x; d <= level.reach_x; d++) {
                    const int x = i + d;
                    if (x >= -(bank.width / 2) && x < bank.width - bank.width / 2)
                        sum += level.gx[size_t(d + level.reach_x)] * row[x + bank.width / 2];
                }
            }
            out[first + a] = sum;
        }
        first += level.atoms.size();
    }
}

// ---- Non-negative basis pursuit denoising ----

struct Fit {
    std::vector<double> weights;
    int iterations = 0;
    double relative_gap = 0;
    size_t nonzero = 0;
};

// `power`: the centred plane of the spectrum to fit. The gap is checked every 5 iterations.
inline Fit fit_weights(const Bank &bank, const std::vector<double> &power) {
    const size_t atoms = bank.atom_count();
    std::vector<double> gradient, bw;
    // lambda_max = max (2 B^T P): above it, w = 0 is optimal.
    apply_bank_transposed(bank, power, gradient);
    double lambda_max = 0;
    for (double value : gradient) lambda_max = std::max(lambda_max, 2 * value);
    const double lambda = lambda_max / 8;
    // Lipschitz constant of the gradient 2 B^T (B w - P): 2 |B|^2, by power iteration (with a margin).
    std::vector<double> v(atoms, 1.0);
    double lipschitz = 1;
    for (int iteration = 0; iteration < 40; iteration++) {
        apply_bank(bank, v, bw);
        apply_bank_transposed(bank, bw, gradient);
        double norm = 0;
        for (double value : gradient) norm += value * value;
        norm = std::sqrt(norm);
        lipschitz = 2 * norm * 1.02;
        for (size_t k = 0; k < atoms; k++) v[k] = gradient[k] / norm;
    }
    Fit fit;
    std::vector<double> &w = fit.weights;
    w.assign(atoms, 0.0);
    std::vector<double> y = w, previous, residual;
    double t = 1, best_dual = 0;
    const double power_norm = [&] {
        double sum = 0;
        for (double value : power) sum += value * value;
        return sum;
    }();
    for (fit.iterations = 0; fit.iterations < 2000; fit.iterations++) {
        if (fit.iterations % 5 == 0) {
            // The relative duality gap of w (Kim, Koh, Lustig, Boyd and Gorinevsky's bound for l1-regularized
            // least squares): the dual point is 2 (B w - P), scaled to be feasible.
            apply_bank(bank, w, residual);
            double primal = 0, penalty = 0;
            for (size_t i = 0; i < residual.size(); i++) primal += (residual[i] -= power[i]) * residual[i];
            for (double value : w) penalty += value;
            primal += lambda * penalty;
            apply_bank_transposed(bank, residual, gradient);
            double rho = 0;
            for (double value : gradient) rho = std::max(rho, -2 * value);
            const double scale = rho > lambda ? lambda / rho : 1.0;
            double dual = 0;
            for (size_t i = 0; i < residual.size(); i++) {
                const double nu = 2 * residual[i] * scale;
                dual += -0.25 * nu * nu - nu * power[i];
            }
            best_dual = std::max(best_dual, dual);
            fit.relative_gap = best_dual > 0 ? (primal - best_dual) / best_dual : 1;
            if (fit.relative_gap <= 0.02 || !(power_norm > 0)) break;
        }
        // One FISTA step from y.
        apply_bank(bank, y, residual);
        for (size_t i = 0; i < residual.size(); i++) residual[i] -= power[i];
        apply_bank_transposed(bank, residual, gradient);
        previous = w;
        for (size_t k = 0; k < atoms; k++)
            w[k] = std::max(0.0, y[k] - (2 * gradient[k] + lambda) / lipschitz);
        const double next_t = (1 + std::sqrt(1 + 4 * t * t)) / 2;
        for (size_t k = 0; k < atoms; k++) y[k] = w[k] + (t - 1) / next_t * (w[k] - previous[k]);
        t = next_t;
    }
    for (double value : w) fit.nonzero += value > 0;
    return fit;
}

// ---- One grey noise: the parameters of each bandwidth's sparse convolution ----

struct AliasTable { // Walker/Vose: O(1) draws from a discrete distribution
    std::vector<float> threshold;
    std::vector<uint32_t> alias;
    void build(const std::vector<double> &weights) {
        const size_t n = weights.size();
        double total = 0;
        for (double value : weights) total += value;
        std::vector<double> scaled(n);
        std::vector<uint32_t> small, large;
        for (size_t i = 0; i < n; i++) {
            scaled[i] = weights[i] / total * double(n);
            (scaled[i] < 1 ? small : large).push_back(uint32_t(i));
        }
        threshold.assign(n, 1.0f);
        alias.resize(n);
        for (size_t i = 0; i < n; i++) alias[i] = uint32_t(i);
        while (!small.empty() && !large.empty()) {
            const uint32_t s = small.back(), l = large.back();
            small.pop_back();
            threshold[s] = float(scaled[s]);
            alias[s] = l;
            scaled[l] -= 1 - scaled[s];
            if (scaled[l] < 1) {
                large.pop_back();
                small.push_back(l);
            }
        }
    }
};

struct LevelNoise {
    float a = 0, cell = 0; // Gaussian width; cell side = truncation radius = 1 / a
    float impulses_per_cell = 0, amplitude = 0;
    float poisson_limit = 0;   // exp(-impulses_per_cell), for Knuth's draw
    std::vector<float> fx, fy; // cycles per pixel
    AliasTable pick;
};

struct GreyNoise {
    std::vector<LevelNoise> levels;
    uint32_t seed = 0;
};

// The noise whose power spectrum is B w at `impacts_per_kernel` kernels overlapping a point per level.
// P = |T_u|^2 (unnormalized DFT of t_u = (u - mean) / sqrt(M N)) sums to M N times the variance: it is
// the continuous power spectrum itself at the DFT's frequencies. A sparse convolution of density lambda
// has the spectrum lambda amplitude^2 E|FT kernel|^2, so for level q with weights w_k summing to W_q (on
// Gaussians of unit norm: G_q / |G_q|), amplitude^2 = 4 a^4 W_q / (lambda |G_q|).
inline GreyNoise make_grey_noise(const Bank &bank, const std::vector<double> &weights,
                                 double impacts_per_kernel, uint32_t seed) {
    GreyNoise noise;
    noise.seed = seed;
    size_t first = 0;
    for (const Level &level : bank.levels) {
        std::vector<double> level_weights(weights.begin() + long(first),
                                          weights.begin() + long(first + level.atoms.size()));
        first += level.atoms.size();
        double total = 0;
        for (double value : level_weights) total += value;
        if (!(total > 0)) continue;
        LevelNoise out;
        const double a = 2 * level.sigma * std::sqrt(kPi), radius = 1 / a;
        const double lambda = impacts_per_kernel / (kPi * radius * radius);
        out.a = float(a);
        out.cell = float(radius);
        out.impulses_per_cell = float(lambda * radius * radius);
        out.poisson_limit = std::exp(-out.impulses_per_cell);
        const double inverse_norm = level.gx[size_t(level.reach_x)] * level.gy[size_t(level.reach_y)];
        out.amplitude = float(std::sqrt(4 * a * a * a * a * total * inverse_norm / lambda));
        for (const auto &atom : level.atoms) {
            out.fx.push_back(float(double(atom[0]) / bank.width));
            out.fy.push_back(float(double(atom[1]) / bank.height));
        }
        out.pick.build(level_weights);
        noise.levels.push_back(std::move(out));
    }
    return noise;
}

inline uint32_t hash(uint32_t value) { // lowbias32
    value ^= value >> 16;
    value *= 0x7feb352du;
    value ^= value >> 15;
    value *= 0x846ca68bu;
    value ^= value >> 16;
    return value;
}

struct CellRandom {
    uint32_t state;
    float uniform() { return float((state = hash(state + 0x9e3779b9u)) >> 8) * (1.0f / 16777216.0f); }
};

inline float grey_point(const GreyNoise &noise, double x, double y) {
    float sum = 0;
    for (size_t l = 0; l < noise.levels.size(); l++) {
        const LevelNoise &level = noise.levels[l];
        const double cx = std::floor(x / level.cell), cy = std::floor(y / level.cell);
        // Coordinates relative to the centre cell's corner, small enough for float.
        const float px = float(x - cx * level.cell), py = float(y - cy * level.cell);
        const float a2 = level.a * level.a, limit = level.cell * level.cell;
        float level_sum = 0;
        for (int j = -1; j <= 1; j++)
            for (int i = -1; i <= 1; i++) {
                CellRandom random{hash(uint32_t(int32_t(cx) + i) * 73856093u ^
                                       uint32_t(int32_t(cy) + j) * 19349663u ^
                                       (noise.seed + uint32_t(l) * 83492791u))};
                int impulses = 0; // Knuth: the mean is about 10
                for (float product = random.uniform(); product > level.poisson_limit;
                     product *= random.uniform())
                    impulses++;
                for (int n = 0; n < impulses; n++) {
                    const float dx = px - (float(i) + random.uniform()) * level.cell;
                    const float dy = py - (float(j) + random.uniform()) * level.cell;
                    const float pick = random.uniform() * float(level.pick.threshold.size());
                    const float phase = random.uniform();
                    const size_t column = std::min(size_t(pick), level.pick.threshold.size() - 1);
                    const size_t k = pick - float(column) < level.pick.threshold[column]
                                         ? column
                                         : level.pick.alias[column];
                    const float r2 = dx * dx + dy * dy;
                    if (r2 >= limit) continue; // truncated at the radius 1/a
                    level_sum += std::exp(-float(kPi) * a2 * r2) *
                                 std::cos(2 * float(kPi) * (level.fx[k] * dx + level.fy[k] * dy + phase));
                }
            }
        sum += level_sum * level.amplitude;
    }
    return sum;
}

// The expected power spectrum of the noise sampled on the pixel grid, in DFT order (index y * M + x for
// the frequency (x / M, y / N)): B w with every Gaussian periodized (sampling folds the continuous
// spectrum onto the torus). The truncation of the kernels at 1/a (which keeps 99.8% of their energy) is
// left out.
inline std::vector<double> sampled_spectrum(const Bank &bank, const std::vector<double> &weights) {
    const int width = bank.width, height = bank.height;
    std::vector<double> out(size_t(width) * size_t(height), 0.0);
    std::vector<double> px(static_cast<size_t>(width)), py(static_cast<size_t>(height));
    size_t first = 0;
    for (const Level &level : bank.levels) {
        const double norm = level.gx[size_t(level.reach_x)] * level.gy[size_t(level.reach_y)]; // 1 / |G_q|
        for (size_t a = 0; a < level.atoms.size(); a++) {
            const double w = weights[first + a];
            if (w == 0) continue;
            for (int sign = -1; sign <= 1; sign += 2) {
                const double fx = sign * double(level.atoms[a][0]) / width;
                const double fy = sign * double(level.atoms[a][1]) / height;
                auto periodized = [&](double d) {
                    double sum = 0;
                    for (int m = -2; m <= 2; m++)
                        sum += std::exp(-(d + m) * (d + m) / (2 * level.sigma * level.sigma));
                    return sum;
                };
                for (int x = 0; x < width; x++) px[size_t(x)] = periodized(double(x) / width - fx);
                for (int y = 0; y < height; y++)
                    py[size_t(y)] = periodized(double(y) / height - fy) * w * norm;
                for (int y = 0; y < height; y++)
                    for (int x = 0; x < width; x++)
                        out[size_t(y) * size_t(width) + size_t(x)] += py[size_t(y)] * px[size_t(x)];
            }
        }
        first += level.atoms.size();
    }
    return out;
}

// Excess kurtosis and variance of the noise's marginal: the cumulants of a sparse convolution add over
// the levels, kappa_n = lambda amplitude^n E integral kernel^n, with E over the uniform phase:
// E cos^2 = 1/2, E cos^4 = 3/8, and the truncated Gaussian's integrals (1 - e^(-n pi)) / (n a^2).
struct Cumulants {
    double variance = 0, fourth = 0;
};
inline Cumulants cumulants(const GreyNoise &noise) {
    Cumulants out;
    for (const LevelNoise &level : noise.levels) {
        const double a2 = double(level.a) * level.a,
                     lambda = level.impulses_per_cell / (double(level.cell) * level.cell);
        const double amplitude2 = double(level.amplitude) * level.amplitude;
        out.variance += lambda * amplitude2 * 0.5 * (1 - std::exp(-2 * kPi)) / (2 * a2);
        out.fourth += lambda * amplitude2 * amplitude2 * 0.375 * (1 - std::exp(-4 * kPi)) / (4 * a2);
    }
    return out;
}

// ---- Colour: decorrelated channels ----

struct ColourNoise {
    int channels = 1;
    std::array<double, 3> mean = {0, 0, 0};
    dsn::Matrix3 mixing = {1, 0, 0, 0, 1, 0, 0, 0, 1}; // RGB = mean + mixing * (decorrelated noises)
    dsn::Matrix3 unmixing = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    Bank bank;
    std::array<Fit, 3> fits;
    std::array<GreyNoise, 3> noises;
    std::array<std::vector<double>, 3> spectra; // expected sampled spectrum of each noise, DFT order
    double off_diagonal_before = 0, off_diagonal_after = 0; // of the whitened real cross-spectra
};

inline dsn::Matrix3 multiply(const dsn::Matrix3 &a, const dsn::Matrix3 &b) {
    dsn::Matrix3 out{};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) out[size_t(i * 3 + j)] += a[size_t(i * 3 + k)] * b[size_t(k * 3 + j)];
    return out;
}

// The colour transform: W = C^(-1/2) whitens the colour covariance C, then rotations V jointly
// diagonalize Re(W T(xi) (W T(xi))^*) over every frequency; unmixing = V^T W, mixing = C^(1/2) V.
inline void decorrelate(const dsn::GaussianModel &model, ColourNoise &noise) {
    const dsn::Matrix3 covariance = dsn::model_covariance(model);
    std::array<double, 3> values;
    dsn::Matrix3 vectors;
    dsn::symmetric_eigen(covariance, values, vectors);
    const double largest = std::max({values[0], values[1], values[2]});
    dsn::Matrix3 whiten{}, colour{};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) {
                const double value = std::max(values[size_t(k)], 1e-6 * largest);
                whiten[size_t(i * 3 + j)] +=
                    vectors[size_t(i * 3 + k)] * vectors[size_t(j * 3 + k)] / std::sqrt(value);
                colour[size_t(i * 3 + j)] +=
                    vectors[size_t(i * 3 + k)] * vectors[size_t(j * 3 + k)] * std::sqrt(value);
            }
    const size_t plane = model.spectrum.plane_size();
    std::vector<std::array<double, 6>> matrices(plane); // 00 11 22 01 02 12
    for (size_t i = 1; i < plane; i++) {
        std::complex<double> z[3];
        for (int r = 0; r < 3; r++) {
            z[r] = 0;
            for (int c = 0; c < 3; c++)
                z[r] += whiten[size_t(r * 3 + c)] *
                        std::complex<double>(model.spectrum.values[size_t(c) * plane + i]);
        }
        auto re = [&](int p, int q) { return (z[p] * std::conj(z[q])).real(); };
        matrices[i] = {re(0, 0), re(1, 1), re(2, 2), re(0, 1), re(0, 2), re(1, 2)};
    }
    auto off_diagonal = [&] {
        double sum = 0;
        for (const auto &m : matrices) sum += 2 * (m[3] * m[3] + m[4] * m[4] + m[5] * m[5]);
        return sum;
    };
    auto entry = [](std::array<double, 6> &m, int p, int q) -> double & {
        static const int index[3][3] = {{0, 3, 4}, {3, 1, 5}, {4, 5, 2}};
        return m[size_t(index[p][q])];
    };
    noise.off_diagonal_before = off_diagonal();
    dsn::Matrix3 rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int sweep = 0; sweep < 100; sweep++) {
        bool moved = false;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                // (cos 2 theta, sin 2 theta): the leading eigenvector of sum h h^T, h = (m_pp - m_qq, 2
                // m_pq), minimizes the sum of the squared new m_pq.
                double g11 = 0, g12 = 0, g22 = 0;
                for (auto &m : matrices) {
                    const double h1 = entry(m, p, p) - entry(m, q, q), h2 = 2 * entry(m, p, q);
                    g11 += h1 * h1, g12 += h1 * h2, g22 += h2 * h2;
                }
                const double theta = 0.25 * std::atan2(2 * g12, g11 - g22);
                const double c = std::cos(theta), s = std::sin(theta);
                if (std::fabs(s) < 1e-12) continue;
                moved = true;
                for (auto &m : matrices) { // m <- J^T m J, J's columns p, q: (c e_p + s e_q, -s e_p + c e_q)
                    double full[3][3];
                    for (int r = 0; r < 3; r++)
                        for (int k = 0; k < 3; k++) full[r][k] = entry(m, r, k);
                    for (int r = 0; r < 3; r++) { // columns
                        const double mp = full[r][p], mq = full[r][q];
                        full[r][p] = c * mp + s * mq;
                        full[r][q] = -s * mp + c * mq;
                    }
                    for (int k = 0; k < 3; k++) { // rows
                        const double mp = full[p][k], mq = full[q][k];
                        full[p][k] = c * mp + s * mq;
                        full[q][k] = -s * mp + c * mq;
                    }
                    for (int r = 0; r < 3; r++)
                        for (int k = r; k < 3; k++) entry(m, r, k) = full[r][k];
                }
                for (int r = 0; r < 3; r++) {
                    const double vp = rotation[size_t(r * 3 + p)], vq = rotation[size_t(r * 3 + q)];
                    rotation[size_t(r * 3 + p)] = c * vp + s * vq;
                    rotation[size_t(r * 3 + q)] = -s * vp + c * vq;
                }
            }
        if (!moved) break;
    }
    noise.off_diagonal_after = off_diagonal();
    dsn::Matrix3 transposed{};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) transposed[size_t(i * 3 + j)] = rotation[size_t(j * 3 + i)];
    noise.unmixing = multiply(transposed, whiten);
    noise.mixing = multiply(colour, rotation);
}

// The evaluated noises of the fitted weights at `impacts_per_kernel` kernels overlapping a point per
// bandwidth and channel (the spectrum does not depend on it, the Gaussianity and the cost do).
inline void set_density(ColourNoise &noise, double impacts_per_kernel, uint32_t seed) {
    for (int k = 0; k < noise.channels; k++)
        noise.noises[size_t(k)] = make_grey_noise(noise.bank, noise.fits[size_t(k)].weights,
                                                  impacts_per_kernel, seed + 7919u * uint32_t(k));
}

// Gabor noise by example of `model` (the baker's Gaussian model of the exemplar, periodic component).
inline ColourNoise fit_colour_noise(const dsn::GaussianModel &model, double impacts_per_kernel,
                                    uint32_t seed) {
    ColourNoise noise;
    noise.channels = model.channels;
    for (int c = 0; c < model.channels; c++) noise.mean[size_t(c)] = model.mean[size_t(c)];
    if (model.channels == 3) decorrelate(model, noise);
    const int width = model.spectrum.width, height = model.spectrum.height;
    noise.bank = make_bank(width, height);
    const Plane plane{width, height};
    const size_t size = model.spectrum.plane_size();
    for (int k = 0; k < model.channels; k++) {
        // The decorrelated channel's power spectrum on the centred plane; the paper's Shannon condition
        // drops the frequencies -M/2 and -N/2 of even sides, and the mean is 0.
        std::vector<double> power(size, 0.0);
        for (int y = 0; y < height; y++)
            for (int x = 0; x < width; x++) {
                const int i = x < width - width / 2 ? x : x - width,
                          j = y < height - height / 2 ? y : y - height;
                if ((width % 2 == 0 && i == -(width / 2)) || (height % 2 == 0 && j == -(height / 2)))
                    continue;
                std::complex<double> value = 0;
                for (int c = 0; c < model.channels; c++)
                    value +=
                        noise.unmixing[size_t(k * 3 + c)] *
                        std::complex<double>(
                            model.spectrum.values[size_t(c) * size + size_t(y) * size_t(width) + size_t(x)]);
                power[plane.at(i, j)] = std::norm(value);
            }
        power[plane.at(0, 0)] = 0;
        noise.fits[size_t(k)] = fit_weights(noise.bank, power);

        noise.spectra[size_t(k)] = sampled_spectrum(noise.bank, noise.fits[size_t(k)].weights);
    }
    set_density(noise, impacts_per_kernel, seed);
    return noise;
}

inline void colour_point(const ColourNoise &noise, double x, double y, float *out) {
    float decorrelated[3];
    for (int k = 0; k < noise.channels; k++) decorrelated[k] = grey_point(noise.noises[size_t(k)], x, y);
    for (int c = 0; c < noise.channels; c++) {
        double value = noise.mean[size_t(c)];
        for (int k = 0; k < noise.channels; k++) value += noise.mixing[size_t(c * 3 + k)] * decorrelated[k];
        out[c] = float(value);
    }
}

} // namespace gabor

#endif // DSN_BENCH_GABOR_BY_EXAMPLE_H
