// dsn/bake.h - the offline baker: exemplar image -> synthesis-oriented texton (SOT) + colour transform
// -> compact .dsnt asset. Offline C++17 API of libdsn_bake.a.
//
// The mathematics: the exemplar's Gaussian model and its periodic component are those of Galerne,
// Gousseau and Morel, "Random phase textures: theory and synthesis" (IEEE TIP 2011), which also defines
// the random-phase and asymptotic discrete spot noise (RPN, ADSN); the synthesis-oriented texton is
// computed by the alternating projections of Galerne, Leclaire and Moisan, "A texton for fast and
// flexible Gaussian texture synthesis" (EUSIPCO 2014).
//
// What it does
//   load_exemplar (a file) or decode_exemplar (bytes in memory) -> bake -> BakeResult, whose `asset`
//   holds the .dsnt bytes, ready to be written; preview_png draws a sheet to look at the result.
//
// What it guarantees
//   - Reproducible: the same exemplar, options and seed give byte-identical assets on one machine (the
//     random-phase start comes from a counter-based generator seeded by the bake seed, no global state).
//   - Bad input throws: std::runtime_error for an unusable image (message names the problem: missing
//     file, not an image, too large, too small for the radius, constant), std::invalid_argument for an
//     option out of range. The library writes no file: the caller writes result.asset.
//   - Never NaN: a singular colour covariance is clamped, a zero spectrum gives a zero phase.
//
// Conventions
//   An Image is planar: values[(c * height + y) * width + x], doubles, intensities in [0, 1].
//   A Spectrum is the unnormalized DFT over the width x height torus, planar per channel
//   (values[(c * height + xi2) * width + xi1]), stored as float complex (kissfft is float here; sums and
//   statistics are done in double).
//   A Texton is planar over its (2r+1) x (2r+1) window, top row (dy = -r) first, zero outside the support.
//
// How to call it
//       dsn::BakeOptions options;                 // r = 15, square, 1000 iterations, 8 bits, bilinear
//       options.seed = 7;
//       std::vector<std::string> warnings;
//       dsn::Image exemplar = dsn::load_exemplar("stone.png", &warnings);
//       dsn::BakeResult result = dsn::bake(exemplar, options);
//       // write result.asset (result.asset.size() bytes) to stone.dsnt
#ifndef DSN_BAKE_H
#define DSN_BAKE_H

#include <array>
#include <complex>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "dsn/asset_writer.h"
#include "dsn/format.h"

namespace dsn {

// ---- Images and spectra ----

struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<double> values; // planar
    double &at(int x, int y, int c) {
        return values[(size_t(c) * size_t(height) + size_t(y)) * size_t(width) + size_t(x)];
    }
    double at(int x, int y, int c) const {
        return values[(size_t(c) * size_t(height) + size_t(y)) * size_t(width) + size_t(x)];
    }
};

struct Spectrum {
    int width = 0, height = 0, channels = 0;
    std::vector<std::complex<float>> values; // planar, unnormalized DFT
    size_t plane_size() const { return size_t(width) * size_t(height); }
};

// The largest exemplar side accepted (memory and time of the FFTs grow with the area).
constexpr int kMaxExemplarSide = 2048;
// The largest image file accepted (checked before reading it).
constexpr uint64_t kMaxExemplarFileBytes = uint64_t(256) << 20;

// Reads 8- and 16-bit PNG, JPEG and binary PGM/PPM (any maxval); other formats are refused by name. Grey
// stays one channel, grey+alpha becomes grey, RGB(A) becomes RGB; dropping an alpha channel that is not
// opaque appends a warning to `warnings` (may be null). The size is checked from the header before
// decoding, and decoding never allocates more than that size needs. Throws std::runtime_error naming the
// problem (truncated file, corrupt data, size beyond the limit).
Image load_exemplar(const std::string &path, std::vector<std::string> *warnings);

// The same from an image file's bytes in memory; `name` prefixes the error messages. load_exemplar reads
// the file and calls this, so both refuse the same inputs the same way.
Image decode_exemplar(const unsigned char *bytes, size_t size, const std::string &name,
                      std::vector<std::string> *warnings);

// ---- What a bake produces ----

// The exemplar's Gaussian model: its mean and t_u = (p - mean) / sqrt(width * height), p the periodic
// component of the exemplar (or the exemplar itself without BakeOptions::periodic).
struct GaussianModel {
    int width = 0, height = 0, channels = 0;
    std::array<double, 3> mean = {0, 0, 0};
    Image t_u;
    Spectrum spectrum; // DFT of t_u: the model's spectrum is |T_u|^2
};

// The texton's support: the square of side 2r+1 or the disk dx^2 + dy^2 <= r^2 around the origin.
constexpr int kMaxRadius = (int(DSN_FORMAT_MAX_SIDE) - 1) / 2;
// A bilinear bake also writes its lattice texton (format 1.3), 2 texels wider than the texton.
constexpr int kMaxBilinearRadius = kMaxRadius - 1;
struct Support {
    int radius = 0;
    uint32_t shape = DSN_SHAPE_RECTANGLE; // DSN_SHAPE_RECTANGLE (square) or DSN_SHAPE_DISK
    std::vector<unsigned char> mask;      // (2r+1)^2, row-major, 1 inside
    int side() const { return 2 * radius + 1; }
    int size() const; // number of points inside
};

struct Texton {
    Support support;
    int channels = 0;
    std::vector<double> values; // planar: values[(c * side + row) * side + column], row 0 is dy = -r
    double at(int dx, int dy, int c) const {
        const int side = support.side();
        return values[(size_t(c) * size_t(side) + size_t(dy + support.radius)) * size_t(side) +
                      size_t(dx + support.radius)];
    }
};

// Why the texton's optimization ended: every iteration asked for ran, or the early stop found that the
// error had stopped improving (BakeOptions::stop_tolerance).
enum class SotStop { IterationLimit, Converged };

struct SotResult {
    Texton texton;
    // [k] = relative model error without the zero frequency (BakeResult's rme_without_zero_frequency) of
    // the texton after iteration k + 1: the figure the iterations minimize, T(0) being left free.
    std::vector<double> rme_per_iteration;
    SotStop stop = SotStop::IterationLimit;
};

using Matrix3 = std::array<double, 9>; // row-major

// ---- The bake ----

// Called after every iteration of the texton's optimization with (iterations done, iterations asked,
// relative model error of the current texton without the zero frequency, as in rme_per_iteration).
using BakeProgress = std::function<void(int done, int total, double rme)>;

// The default early stop: an improvement below 0.002 over 50 iterations (4e-5 per iteration).
constexpr double kDefaultStopTolerance = 0.002;

struct BakeOptions {
    int radius = 15; // 1..kMaxRadius; the exemplar needs both sides >= 4 radius + 1
    uint32_t shape = DSN_SHAPE_RECTANGLE;
    int iterations = 1000; // the most iterations; the early stop usually ends the run sooner
    uint32_t seed = 0;
    int bits = 8; // 8 or 16
    bool periodic = true;
    bool use_color_transform = true;
    // How the runtime reads the texton. Bilinear (the continuous mode, what renderers use) bakes a
    // texton corrected for the interpolation's smoothing; lattice suits the integer-lattice evaluators.
    uint32_t interpolation = DSN_INTERPOLATION_BILINEAR;
    // Early stop: stop when the relative model error improved by less than this over the last 50
    // iterations, once at least 2^22 / (width x height) iterations ran (small exemplars run longer: their
    // error curves descend slowly, see the README). 0 runs every iteration.
    double stop_tolerance = kDefaultStopTolerance;
    // Writes the texton pyramid (a format 1.1 asset) that the filtered evaluation reads; false writes a
    // 1.0 asset, byte for byte what bakes without a pyramid always wrote.
    bool pyramid = true;
    // The histogram-preserving output (a format 1.2 asset, Heitz and Neyret, HPG 2018): the texton is
    // baked on the Gaussianized exemplar (see HistogramModel) and the asset maps the Gaussian noise back
    // through the exemplar's own marginals, so binary, speckled or skewed tones keep their histogram.
    bool histogram = false;
    BakeProgress progress; // may be empty
};

// ---- The histogram-preserving mode (offline/histogram.cpp) ----

// The principal components of an image's colours: mean, covariance eigenvalues (strongest first) and
// eigenvectors in the columns of `vectors`, each with its largest-magnitude entry positive (the first
// of equal ones), so the same image always gives the same basis. Grey: the identity, one variance.
struct ColourBasis {
    int channels = 1;
    std::array<double, 3> mean = {0, 0, 0};
    std::array<double, 3> variances = {0, 0, 0};
    Matrix3 vectors = {1, 0, 0, 0, 1, 0, 0, 0, 1};
};
ColourBasis principal_components(const Image &image);

// What the mapping needs of the exemplar: its colour basis and, per decorrelated channel
// v_k = P^T (u - mean), the channel's values sorted (its empirical distribution).
struct HistogramModel {
    ColourBasis basis;
    std::vector<std::vector<double>> sorted; // [k]: the n values of v_k, ascending
};
HistogramModel histogram_model(const Image &exemplar);

// The standard normal distribution function and its inverse (p in (0, 1); relative error ~1e-15).
double normal_cdf(double x);
double normal_quantile(double p);

// The empirical quantile of sorted values: the value of rank i stands for probability (i + 0.5) / n,
// linear in between, the extreme values beyond.
double empirical_quantile(const std::vector<double> &sorted, double probability);

// The Gaussianized exemplar w: each decorrelated channel through its empirical distribution
// function, g = normal_quantile((rank + 0.5) / n) with tied values given their average rank, then
// scaled to zero mean and the channel's share of the variance, sqrt(variance_k / variance_0) of the
// strongest channel's unit deviation (ties leave fewer distinct values and less variance): weak, mostly
// noise components then weigh by their size in the texton's shared phase.
Image gaussianize(const Image &exemplar, const HistogramModel &model);

// The standard deviation of Gaussian-space channel k (the 1.0 output of format.h) of the noise these
// asset fields give, by Campbell's theorem: sqrt((K C K^T)_kk), C_km the integral of t_k t_m (lattice:
// the sum over the texels; bilinear: weighted by the sampled cubic B-spline). Level 0 is the texton,
// level l >= 1 the pyramid level l (bilinear tents at spacing 2^l, so its integral carries 4^l).
std::array<double, 3> gaussian_space_deviation(const AssetFields &fields, int level);

// E[f(y + rho Z)], Z standard normal, for f the piecewise-linear table (values at low + i step,
// constant beyond both ends): exact, from the normal distribution and density at the nodes.
double smoothed_table_value(const std::vector<double> &table, double low, double step, double y, double rho);

// The mapping of format 1.2 for an asset baked on gaussianize(exemplar): level 0's table
// T_0(y) = empirical quantile of v_k at normal_cdf((y - mean_k) / sigma_0k), the prefiltered tables
// T_l(y) = E[T_0(y + rho_l Z)] with rho_l^2 = sigma_0k^2 - sigma_lk^2 (sigma from
// gaussian_space_deviation) for each pyramid level, expected_k = E[T_0(mean_k + sigma_0k Z)], and the
// rotation P and centre (the basis' mean): 129 entries over [-4, 4] (1/16 apart), Q3.12.
HistogramMapping histogram_mapping(const HistogramModel &model, const AssetFields &fields);

// ---- What renders (offline/measures.cpp) ----

// The relative model error of what the runtime renders: the model's spectrum against the texton's (the
// quantized texton, as the runtime reads it) with the colour transform K applied and, for a bilinear read,
// multiplied by the square root of the sampled cubic B-spline b (the noise's spectrum is K T T^* K^T b),
// over every frequency as relative_model_error. `model` is GaussianModel::spectrum (not the target).
double effective_model_error(const Spectrum &model, const Texton &texton, const Matrix3 &color_transform,
                             uint32_t interpolation);

// Skewness and excess kurtosis of every output channel of the runtime's noise at `impacts_per_pixel`,
// exact by Campbell's theorem: the n-th cumulant of a shot noise of intensity lambda = impacts / |S| is
// lambda times the integral of s^n, s_c = sum_k K_ck t_k the spot the channel sees (lattice: the sum over
// the texels; bilinear: the integral of the bilinear interpolant over the plane, impulses placed
// uniformly), so skewness = I3 / (sqrt(lambda) I2^1.5) and excess kurtosis = I4 / (lambda I2^2): both
// shrink as the density grows (as 1/sqrt(impacts) and 1/impacts), to 0 for a Gaussian.
struct NoiseMoments {
    std::vector<double> skewness, excess_kurtosis; // per output channel
};
NoiseMoments noise_moments(const Texton &texton, const Matrix3 &color_transform, uint32_t interpolation,
                           double impacts_per_pixel);

// The shape signal of one channel of a torus image (a periodic component): its total variation (the sum of
// |u(p + e_x) - u(p)| + |u(p + e_y) - u(p)|) over the expected total variation of a Gaussian field with
// the same spectrum, sqrt(2/pi) N (sigma_x + sigma_y), sigma the deviations of the two differences: 1 for
// a Gaussian texture; below 1 when the gradient is sparse, flat regions bounded by sharp edges (the
// global phase coherence of Blanchet, Moisan and Rouge, ICIP 2008, and the sharpness index of Leclaire
// and Moisan, JMIV 2015: a random-phase copy of such an image has a larger total variation). `error` is
// the ratio's standard deviation for a Gaussian field with this image's autocorrelation (the delta method:
// (1/N) sum over the lags and the pairs of directions of w_a w_b h(c_ab), h(c) = c asin(c) +
// sqrt(1 - c^2) - 1 - c^2 / 2, c_ab the correlation of the two differences, w_a = sigma_a / (sigma_x +
// sigma_y)).
struct ShapeSignal {
    double ratio = 1, error = 0;
};
ShapeSignal shape_signal(const Image &image, int channel);

// ---- The verdict ----

// The marginal of one decorrelated channel of the exemplar (principal components of its colours,
// strongest first): variance, sample skewness and excess kurtosis (0 for a Gaussian), and their standard
// errors for a Gaussian field with the exemplar's own autocorrelation rho: sqrt(6 sum rho^3 / N) and
// sqrt(24 sum rho^4 / N) (N pixels; 6/N and 24/N for independent samples).
struct ChannelMarginal {
    double variance = 0, skewness = 0, excess_kurtosis = 0, skewness_error = 0, kurtosis_error = 0;
};

enum class VerdictFinding {
    StructureBeyondRadius,   // correlations reach beyond the texton; a radius that fits would hold them
    StructureBeyondGaussian, // they reach beyond any radius that fits the exemplar
    NonGaussianMarginal,     // the tones are far from Gaussian: the output cannot keep the histogram
    HighModelError,          // the spectrum that renders stays far from the exemplar's
    ShapeBeyondSpectrum,     // sharp shapes (flagstones, facets, stripes, discs) the spectrum does not hold
    SparseNoise,             // at the asset's density the noise is visibly non-Gaussian: more impacts
};
const char *verdict_finding_name(VerdictFinding finding); // "structure_beyond_radius", ...

// The thresholds (the README says where they come from):
//  - a decorrelated channel with at least a tenth of the strongest one's variance is non-Gaussian when
//    |skewness| > 1 (Bulmer's "highly skewed") or |excess kurtosis| > 1 (flatter than a uniform's -1.2
//    is two-level; a Laplace's 3 is speckled), each also beyond 3 of its standard errors;
//  - structure lies beyond the texton when more than 10% of the exemplar's autocorrelation energy (sum
//    of the squared autocorrelation over the lags, less the sampling noise Bartlett's formula puts at each
//    lag) lies beyond lag 2r, the farthest lag the noise of a texton of radius r correlates, and either
//    the autocorrelation there reaches 0.2 of the variance or, however weak it is, that energy is beyond
//    3 standard deviations of what sampling noise leaves there ((4/N) (M/N) sqrt(sum S^4), M of the N
//    lags beyond reach, S the spectrum of the autocorrelation cut at the reach: the periodogram is about
//    S times an exponential variable);
//  - the model error is high above an effective RME (what renders: effective_model_error) of 0.6: a
//    texton that fits a photo's spectrum up to its sampling noise (the periodogram of a Gaussian field is
//    exponentially distributed about its mean, which leaves RME = sqrt(1 - pi/4) = 0.46 to a smooth
//    spectrum) stays below it, and no RME below it is flagged, whatever the luminance texton's;
//  - the exemplar has shapes its spectrum does not hold when, on its Gaussianized form (so that tones
//    alone, which the tones finding covers, do not count), the shape signal of a visible decorrelated
//    channel is below kVerdictShapeRatio and beyond 3 of its standard errors below 1;
//  - the noise is sparse when, at the asset's density, an output channel's |skewness| exceeds
//    kVerdictNoiseSkewness or its |excess kurtosis| kVerdictNoiseKurtosis; the verdict names the density
//    (impacts per pixel, at most 1024) that brings both under them.
constexpr double kVerdictSkewness = 1.0;
constexpr double kVerdictExcessKurtosis = 1.0;
constexpr double kVerdictStructureShare = 0.10;
constexpr double kVerdictCorrelation = 0.2;
constexpr double kVerdictModelError = 0.6;
// sqrt(pi) / 2: the shape signal of a field whose differences have a Laplace distribution (E|g| / rms g =
// 1 / sqrt 2, against sqrt(2 / pi) for a Gaussian): the sparse gradient of natural images' edges.
constexpr double kVerdictShapeRatio = 0.886226925452758;
constexpr double kVerdictNoiseSkewness = 0.25;
constexpr double kVerdictNoiseKurtosis = 0.25;

struct BakeVerdict {
    std::string summary;                  // one line: "good: ...", "fair: ...", "limited: ..."
    std::vector<VerdictFinding> findings; // empty: good
    std::vector<std::string> suggestions; // one per finding, each with what to do
    // The signals.
    double rme = 0, rme_luminance = 0;
    double rme_effective = 0; // what renders (BakeResult::rme_effective): the one judged
    std::vector<ChannelMarginal> channels;
    // The shape signal (shape_signal) of the visible decorrelated channel of the Gaussianized exemplar
    // whose ratio is the smallest, that channel's index and the ratio's standard error.
    double shape_ratio = 1, shape_error = 0;
    int shape_channel = 0;
    // The noise at the asset's density (impacts per pixel): skewness and excess kurtosis per output
    // channel (noise_moments), and the density that brings them under the bounds (0: the asset's is enough).
    double impacts = 0;
    std::vector<double> noise_skewness, noise_excess_kurtosis;
    double suggested_impacts = 0;
    double structure_beyond_reach = 0;   // share of the autocorrelation energy beyond lag 2r
    double structure_error = 0;          // its standard deviation from sampling noise alone
    double correlation_beyond_reach = 0; // the largest autocorrelation beyond lag 2r, over the variance
    int suggested_radius = 0;            // 0: none (no structure beyond reach, or none fits)
    int largest_fitting_radius = 0;
};

// The verdict on a bake of `exemplar` with `options` (bake() stores it in result.verdict).
BakeVerdict bake_verdict(const Image &exemplar, const struct BakeResult &result, const BakeOptions &options);

struct BakeResult {
    GaussianModel model;
    Spectrum target; // the spectrum the texton aims at (the model's, corrected for the interpolation)
    SotResult sot;
    Texton luminance;        // the baseline texton (the luminance texton), for comparison
    Texton quantized_texton; // dequantized: what the runtime uses
    // Relative model errors (0 is perfect) of the texton, of the luminance texton and of the quantized
    // texton, summed over every frequency as Galerne, Leclaire and Moisan define it: the 2-Wasserstein
    // distance between the Gaussian models of the texton's noise and of the exemplar, relative to the
    // exemplar's; a texton with a non-zero sum counts the power it adds at the zero frequency. The texton's
    // without the zero frequency (what the iterations minimize: rme_per_iteration's last value) is
    // rme_without_zero_frequency. Excess kurtosis per channel of the noise at 30 impacts per pixel (0 is
    // Gaussian).
    // rme_effective is that of what renders (effective_model_error: the quantized texton, the stored colour
    // transform and the bilinear read applied), against the model's spectrum.
    double rme = 0, rme_luminance = 0, rme_quantized = 0, rme_without_zero_frequency = 0, rme_effective = 0;
    std::vector<double> excess_kurtosis_30, excess_kurtosis_30_luminance;
    Matrix3 color_transform = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    AssetFields fields;
    // With BakeOptions::histogram: the exemplar's marginals that fields.histogram maps back to, and the
    // Gaussian-space standard deviation of every channel at every level (level 0 first).
    HistogramModel histogram;
    std::vector<std::array<double, 3>> gaussian_deviations;
    std::vector<unsigned char> asset; // the encoded .dsnt file
    BakeVerdict verdict;              // how well the model holds the exemplar, and what to try
};

// Refuses what cannot be baked: options out of range (std::invalid_argument), an exemplar smaller than
// S - S (both sides at least 4r + 1; the message names the largest radius that fits) or constant
// (std::runtime_error). bake() calls it first; call it to check an input without baking.
void check_bake_input(const Image &exemplar, const BakeOptions &options);

// Runs the whole pipeline; result.asset holds the encoded .dsnt bytes.
BakeResult bake(const Image &exemplar, const BakeOptions &options);

// ---- Preview ----

// One PNG (encoded in memory) a person reads at a glance, labelled: exemplar, its Gaussian reference
// (spectral ADSN of t_u, same size), the texton scaled for display and a DSN synthesis of the baked asset by
// the runtime (dsn_lattice_tile_float), side by side. Throws std::runtime_error if the asset does not load.
std::vector<unsigned char> preview_png(const Image &exemplar, const BakeResult &result, uint32_t seed);

} // namespace dsn

#endif // DSN_BAKE_H
