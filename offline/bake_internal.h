// bake_internal.h - the steps of the baker's pipeline, one function each (internal to libdsn_bake.a;
// the tests, benchmarks and demo programs call them one by one). The public API is dsn/bake.h.
//
//   gaussian_model (periodic_component, mean, t_u) -> interpolation_target -> support_mask ->
//   sot_alternating_projections (RME of every iteration) -> luminance_texton (the baseline) ->
//   relative_model_error, excess_kurtosis -> color_transform -> quantize -> assemble_asset (with
//   texton_pyramid: the prefiltered levels of format 1.1).
//
// The Gaussian model, the periodic component and the spectral ADSN are those of Galerne, Gousseau and
// Morel, "Random phase textures: theory and synthesis" (IEEE TIP 2011); the alternating projections and
// the relative model error those of Galerne, Leclaire and Moisan, "A texton for fast and flexible Gaussian
// texture synthesis" (EUSIPCO 2014).
#ifndef DSN_OFFLINE_BAKE_INTERNAL_H
#define DSN_OFFLINE_BAKE_INTERNAL_H

#include "dsn/bake.h"

namespace dsn {

// ---- Spectra ----

// Unnormalized 2-D DFT of every channel and its inverse (divided by width * height, real part kept).
// Built from kiss_fftnd (complex): kiss_fftndr of this kissfft crashes on 2-D sizes from 64 x 64.
Spectrum forward_dft(const Image &image);
Image inverse_dft(const Spectrum &spectrum);

// ---- Gaussian model ----

// The periodic component p of u (Moisan's periodic plus smooth decomposition, as Galerne, Gousseau and
// Morel use it): Lap p = Lap_int u, mean(p) = mean(u), solved in Fourier.
Image periodic_component(const Image &u);

// Mean and t_u of `u` (of its periodic component when `periodic`). Throws std::runtime_error for a
// constant image (no variance: every pixel equal in every channel).
GaussianModel gaussian_model(const Image &u, bool periodic);

// The spectrum a texton read with `interpolation` must have so that the noise sampled on the lattice has
// the spectrum of `model`: the model itself for lattice, |T_u| / sqrt(b) for bilinear, where
// b = (2/3 + cos(2 pi xi1 / M) / 3)(2/3 + cos(2 pi xi2 / N) / 3) is the sampled cubic B-spline.
Spectrum interpolation_target(const Spectrum &model, uint32_t interpolation);

// ---- Support and textons ----

// Throws std::invalid_argument unless 1 <= radius <= kMaxRadius and the shape is known.
Support support_mask(int radius, uint32_t shape);

// The values of a torus image at the support points around the origin (zero elsewhere).
Texton crop_to_support(const Image &torus_image, const Support &support);

// The texton's DFT on the width x height torus (the texton wraps around the origin).
Spectrum texton_spectrum(const Texton &texton, int width, int height);

// ---- Synthesis-oriented texton ----

// A standard Gaussian white noise image (one channel) drawn from `seed` by a counter-based generator:
// the same seed gives the same image, whatever else ran before.
Image white_noise(int width, int height, uint32_t seed);

// Spectrum with the modulus of `target` and the phase of the DFT of a real white noise drawn from `seed`
// (so its inverse DFT is real): the random-phase start. Same seed, same start.
Spectrum random_phase_start(const Spectrum &target, uint32_t seed);

struct SotOptions {
    int iterations = 1000;
    uint32_t seed = 0;
    // Early stop: after more than `stop_window` iterations and at least `minimum_iterations`, stop when
    // the RME improved by less than `stop_tolerance` over the last `stop_window` iterations. 0 runs every
    // iteration.
    double stop_tolerance = 0;
    int stop_window = 50;
    int minimum_iterations = 0;
    // Uses full-size 2-D FFTs per iteration instead of the pruned transforms: the slow reference.
    bool reference = false;
    BakeProgress progress; // may be empty
};

// The fewest iterations the bake runs before its early stop may end the run: kEarlyStopMinimumWork /
// (width x height), the work of four iterations on a one-megapixel exemplar. Small exemplars cost little
// per iteration, and their error curves (a large texton on a small torus) descend slowly or sit on a
// plateau and then drop, which a window of 50 iterations mistakes for convergence.
constexpr double kEarlyStopMinimumWork = 4194304;
int early_stop_minimum_iterations(int width, int height);

// Alternating projections between the textons supported on `support` and the textons whose spectrum
// modulus is |target| (one common phase per frequency for all channels), from random_phase_start.
// The zero frequency is left free: the texton's sum is not constrained (the runtime subtracts the mean).
// Returns the texton after the last iteration and the RME of every iteration.
SotResult sot_alternating_projections(const Spectrum &target, const Support &support,
                                      const SotOptions &options);

// The baseline: T_u,c conj(L)/|L| with L = T_u,R/3 + T_u,G/2 + T_u,B/6 (L = T_u for grey), inverse DFT,
// cropped to the support.
Texton luminance_texton(const Spectrum &model, const Support &support);

// ---- Measures ----

// RME = sqrt(sum(|T_u|^2 + |T|^2 - 2 |T_u^* T|) / sum |T_u|^2), T_u^* T summed over channels: the
// 2-Wasserstein distance between the Gaussian models of t_u and t relative to the exemplar's, summed over
// every frequency as Galerne, Leclaire and Moisan define it (section 3). T_u(0) = 0 (the exemplar's mean
// is subtracted), so a texton with a non-zero sum adds |T(0)|^2: its spot noise has that much more power
// at the lowest frequencies (variation over scales beyond the exemplar), which the runtime's subtraction
// of the noise's mean does not remove.
double relative_model_error(const Spectrum &model, const Spectrum &texton);
double relative_model_error(const Spectrum &model, const Texton &texton);
// The same sums over the frequencies xi != 0 only: the figure the alternating projections minimize and
// report per iteration (they leave T(0) free). RME^2 = this^2 + sum_c |T_c(0)|^2 / sum |T_u|^2.
double relative_model_error_without_zero_frequency(const Spectrum &model, const Spectrum &texton);
double relative_model_error_without_zero_frequency(const Spectrum &model, const Texton &texton);

// Per channel: excess kurtosis of the spot-noise marginal with `impacts_per_pixel` impacts per pixel,
// sum t^4 / (lambda (sum t^2)^2), lambda = impacts / |S|. 0 for a channel that is all zero.
std::vector<double> excess_kurtosis(const Texton &texton, double impacts_per_pixel);

// ---- Colour ----

// Colour covariance sum_x t(x) t(x)^T of the noise made from the texton, as it is sampled on the
// lattice: for bilinear, the autocorrelation is weighted by the sampled cubic B-spline. Grey: [0] only.
Matrix3 texton_covariance(const Texton &texton, uint32_t interpolation);
// Colour covariance of the Gaussian model: sum_x t_u(x) t_u(x)^T.
Matrix3 model_covariance(const GaussianModel &model);

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations: matrix = V diag(values) V^T,
// eigenvectors in the columns of V.
void symmetric_eigen(const Matrix3 &matrix, std::array<double, 3> &values, Matrix3 &vectors);

// K = B^(1/2) A^(-1/2) (symmetric square roots), so that K A K^T = B: for grey, the gain sqrt(b / a)
// (K[0]; 1 when a is 0). Identity when A is 0.
// Guard: eigenvalues of B below 0 are taken as 0, eigenvalues of A below kColorEigenFloor * max eig(A)
// are raised to that floor, so a (near-)singular A gives a bounded K and never NaN; entries are then
// clamped to +-kColorTransformLimit (what Q8.24 stores).
constexpr double kColorEigenFloor = 1e-4;
constexpr double kColorTransformLimit = 127.0;
Matrix3 color_transform(const Matrix3 &a, const Matrix3 &b, int channels);

// ---- Quantization and the asset ----

struct QuantizedTexton {
    int bits = 8;
    std::array<uint32_t, 3> scale_raw = {0, 0, 0}; // value = q * scale_raw / 2^40
    std::vector<int32_t> values;                   // interleaved, row-major, top row first (format.h)
};

// Per channel, the scale puts max |t| at 127 (8 bits) or 32767 (16 bits); the raw scale is
// round(scale * 2^40), clamped to [1, 2^32 - 1], and values are rounded with that stored scale.
QuantizedTexton quantize(const Texton &texton, int bits);
// The texton the runtime sees: q * scale_raw / 2^40.
Texton dequantize(const QuantizedTexton &quantized, const Support &support, int channels);

// ---- Texton pyramid (format 1.1, dsn/format.h) ----

// The number of levels for a texton of these radii: floor(log2(max radius)) + 1, 0 for a 1 x 1 texton.
int pyramid_level_count(int radius_x, int radius_y);
// A level's radius along an axis of texton radius `radius`: ceil((radius + 1 + 3 sigma) / 2^level),
// sigma = 2^(level-1). The window keeps the spill of the blurred texton; its truncation loses well under
// 1% of the energy of the texton convolved with the Gaussian (tests/bake_pyramid_test.cpp measures it).
int pyramid_level_radius(int radius, int level);
// kappa_l(u) = (hat_1 * g_sigma * hat_(2^l))(u), sigma = 2^(l-1): the inner product of a texel's tent,
// blurred, with a level tent at distance u (per axis).
double pyramid_kappa(int level, double u);

// Level l before quantization: s_l, the L2 projection of t0 * G_l (t0 the bilinear texton of the
// quantized values q * scale / 2^40) onto the tents of spacing 2^l centred on the texton's centre.
struct PrefilteredLevel {
    int level = 0;
    int width = 0, height = 0;
    std::vector<double> values; // s_l, row-major, channels interleaved
};
PrefilteredLevel prefiltered_level(const AssetFields &fields, int level);
// The stored level: q_l = round(s_l 2^40 / (scale[c] 2^e)) with e the smallest exponent in -24..24 that
// keeps every |q_l| within the texton's quantization range.
PyramidLevel quantize_level(const PrefilteredLevel &level, const AssetFields &fields);
// Every level of a texton (the fields' texton, scales, channels and bits), quantized.
std::vector<PyramidLevel> texton_pyramid(const AssetFields &fields);

// ---- Histogram mapping (format 1.2; the functions are in dsn/bake.h) ----

// The Gaussianized exemplar whose noise, mapped through the exemplar's marginals, has the exemplar's
// correlations (a translation process): each decorrelated channel of gaussianize(exemplar) keeps its phase
// and its variance and takes the latent spectrum, the DFT of rho(tau) = R^-1(r(tau)), r the autocorrelation
// of the exemplar's channel v_k (of its periodic component when `periodic`) and R(rho) = Cov(T(X), T(Y)) /
// Var T for X, Y standard normal of correlation rho, T the channel's quantile function on the normal scale
// (Mehler's expansion: 256 Hermite terms, the rest spread as a jump's); the spectrum's negative values (rho
// need not be positive definite) are cut, then 30 iterations of S *= S_r / S_out (Yamazaki and Shinozuka,
// 1988; S_out the DFT of R(rho_S)) bring the mapped noise's spectrum back towards the exemplar's. Pixel by
// pixel, the Gaussianization keeps an edge's sharpness or a noise's share where the tones are compressed; a
// noise with that spectrum has those high frequencies everywhere, and the mapping turns them into speckle
// (a threshold of a rough field: salt-and-pepper) or a fine pixel noise. A Gaussian channel (T linear)
// keeps its own spectrum. dsn::bake does not call it yet: its model is built on gaussianize.
Image latent_gaussianize(const Image &exemplar, const HistogramModel &model, bool periodic);

// The tables dsn-bake writes: 129 entries 1/16 apart from -4 (fine enough to keep the steps of a quantized
// exemplar's quantile function sharp), which cover the Gaussian-space
// values within four standard deviations of a unit-variance channel (all but 6e-5 of them; beyond, the
// table's ends hold the exemplar's extreme values).
constexpr int kHistogramEntries = 129;
constexpr int kHistogramStepShift = 4;
constexpr double kHistogramInputLow = -4;

// The asset fields of a bake (quantized texton, scales, mean and K in Q8.24, metadata, and the pyramid
// unless options.pyramid is false).
AssetFields assemble_asset(const BakeResult &result, const BakeOptions &options, int exemplar_width,
                           int exemplar_height);

} // namespace dsn

#endif // DSN_OFFLINE_BAKE_INTERNAL_H
