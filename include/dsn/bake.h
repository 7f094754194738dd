// dsn/bake.h - the offline baker: exemplar image -> synthesis-oriented texton (SOT) + colour transform
// -> compact .dsnt asset. Offline C++17 API of libdsn_bake.a (the maths is DESIGN.md section 2).
//
// What it does
//   Every step of the pipeline is one function, usable and testable on its own:
//     load_exemplar -> gaussian_model (periodic_component, mean, t_u) -> support_mask ->
//     sot_alternating_projections (RME of every iteration) -> luminance_texton (the baseline) ->
//     relative_model_error, dsn_excess_kurtosis -> color_transform -> quantize -> assemble_asset.
//   bake() runs them all and returns every figure the report needs plus the asset bytes.
//
// What it guarantees
//   - Reproducible: the same exemplar, options and seed give byte-identical assets on one machine (the
//     random-phase start comes from a counter-based generator seeded by the bake seed, no global state).
//   - Bad input throws: std::runtime_error for an unusable image (message names the problem: missing
//     file, not an image, too large, too small for the radius, constant), std::invalid_argument for an
//     option out of range. Nothing is written by this library except by write_file_atomically.
//   - Never NaN: a singular colour covariance is clamped (see color_transform), a zero spectrum gives a
//     zero phase.
//
// Conventions
//   An Image is planar: values[(c * height + y) * width + x], doubles, intensities in [0, 1].
//   A Spectrum is the unnormalized DFT over the width x height torus, planar per channel
//   (values[(c * height + xi2) * width + xi1]), stored as float complex (kissfft is float here; sums and
//   statistics are done in double).
//   A Texton is planar over its (2r+1) x (2r+1) window, top row (dy = -r) first, zero outside the support.
//
// How to call it
//       dsn::BakeOptions options;                 // r = 15, square, 1000 iterations, 8 bits
//       options.seed = 7;
//       dsn::Image exemplar = dsn::load_exemplar("stone.png", &warnings);
//       dsn::BakeResult result = dsn::bake(exemplar, options);
//       dsn::write_file_atomically("stone.dsnt", result.asset);
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

// Reads any image stb_image reads (8- and 16-bit PNG, JPEG, BMP, ...): grey stays one channel, grey+alpha
// becomes grey, RGB(A) becomes RGB; dropping alpha appends a warning to `warnings` (may be null). The size
// is checked with stbi_info before decoding. Throws std::runtime_error naming the problem.
Image load_exemplar(const std::string &path, std::vector<std::string> *warnings);

// The bytes of a PNG file of 8-bit pixels (rows from the top, channels interleaved, 1 to 4 channels).
// Throws std::invalid_argument for an impossible size, std::runtime_error if encoding fails.
std::vector<unsigned char> encode_png(int width, int height, int channels, const unsigned char *pixels);

// The largest image file accepted (checked before reading it).
constexpr uint64_t kMaxExemplarFileBytes = uint64_t(256) << 20;

// The same from an image file's bytes in memory; `name` prefixes the error messages. load_exemplar reads
// the file and calls this, so both refuse the same inputs the same way.
Image decode_exemplar(const unsigned char *bytes, size_t size, const std::string &name,
                      std::vector<std::string> *warnings);

// Unnormalized 2-D DFT of every channel and its inverse (divided by width * height, real part kept).
// Built from kiss_fftnd (complex): kiss_fftndr of this kissfft crashes on 2-D sizes from 64 x 64.
Spectrum forward_dft(const Image &image);
Image inverse_dft(const Spectrum &spectrum);

// ---- Gaussian model ----

// The periodic component p of u (Moisan): Lap p = Lap_int u, mean(p) = mean(u), solved in Fourier.
Image periodic_component(const Image &u);

struct GaussianModel {
    int width = 0, height = 0, channels = 0;
    std::array<double, 3> mean = {0, 0, 0};
    Image t_u;         // (p - mean) / sqrt(width * height)
    Spectrum spectrum; // DFT of t_u: the model's spectrum is |T_u|^2
};

// Mean and t_u of `u` (of its periodic component when `periodic`). Throws std::runtime_error for a
// constant image (no variance: every pixel equal in every channel).
GaussianModel gaussian_model(const Image &u, bool periodic);

// The spectrum a texton read with `interpolation` must have so that the noise sampled on the lattice has
// the spectrum of `model`: the model itself for lattice, |T_u| / sqrt(b) for bilinear, where
// b = (2/3 + cos(2 pi xi1 / M) / 3)(2/3 + cos(2 pi xi2 / N) / 3) is the sampled cubic B-spline.
Spectrum interpolation_target(const Spectrum &model, uint32_t interpolation);

// ---- Support and textons ----

struct Support {
    int radius = 0;
    uint32_t shape = DSN_SHAPE_RECTANGLE; // DSN_SHAPE_RECTANGLE (square) or DSN_SHAPE_DISK
    std::vector<unsigned char> mask;      // (2r+1)^2, row-major, 1 inside
    int side() const { return 2 * radius + 1; }
    int size() const; // number of points inside
};

// The square of side 2r+1 or the disk dx^2 + dy^2 <= r^2, centred on the origin. Throws
// std::invalid_argument unless 1 <= radius <= kMaxRadius and the shape is known.
constexpr int kMaxRadius = (int(DSN_FORMAT_MAX_SIDE) - 1) / 2;
Support support_mask(int radius, uint32_t shape);

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
    // Early stop: after at least `stop_window` iterations, stop when the RME improved by less than
    // `stop_tolerance` over the last `stop_window` iterations. 0 runs every iteration.
    double stop_tolerance = 0;
    int stop_window = 50;
    // Uses full-size 2-D FFTs per iteration instead of the pruned transforms: the slow reference.
    bool reference = false;
    // Called after every iteration with (iterations done, iterations asked, RME); may be empty.
    std::function<void(int, int, double)> progress;
};

struct SotResult {
    Texton texton;
    std::vector<double> rme_per_iteration; // [k] = RME of the texton after iteration k + 1
};

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

// RME = sqrt(sum(|T_u|^2 + |T|^2 - 2 |T_u^* T|) / sum |T_u|^2), T_u^* T summed over channels, over the
// frequencies xi != 0 (the texton's sum only moves the noise's mean, which the runtime subtracts).
double relative_model_error(const Spectrum &model, const Spectrum &texton);
double relative_model_error(const Spectrum &model, const Texton &texton);

// Per channel: excess kurtosis of the DSN marginal with `impacts_per_pixel` impacts per pixel,
// sum t^4 / (lambda (sum t^2)^2), lambda = impacts / |S|. 0 for a channel that is all zero.
std::vector<double> dsn_excess_kurtosis(const Texton &texton, double impacts_per_pixel);

// ---- Colour ----

using Matrix3 = std::array<double, 9>; // row-major

// Colour covariance sum_x t(x) t(x)^T of the noise made from the texton, as it is sampled on the
// lattice: for bilinear, the autocorrelation is weighted by the sampled cubic B-spline. Grey: [0] only.
Matrix3 texton_covariance(const Texton &texton, uint32_t interpolation);
// Colour covariance of the Gaussian model: sum_x t_u(x) t_u(x)^T.
Matrix3 model_covariance(const GaussianModel &model);

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations: matrix = V diag(values) V^T,
// eigenvectors in the columns of V.
void symmetric_eigen(const Matrix3 &matrix, std::array<double, 3> &values, Matrix3 &vectors);

// K = B^(1/2) A^(-1/2) (symmetric square roots), so that K A K^T = B. Identity for grey and when A is 0.
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

// ---- The whole bake ----

struct BakeOptions {
    int radius = 15;
    uint32_t shape = DSN_SHAPE_RECTANGLE;
    int iterations = 1000;
    uint32_t seed = 0;
    int bits = 8;
    bool periodic = true;
    bool use_color_transform = true;
    uint32_t interpolation = DSN_INTERPOLATION_LATTICE;
    double stop_tolerance = 0; // see SotOptions
    std::function<void(int, int, double)> progress;
};

struct BakeResult {
    GaussianModel model;
    Spectrum target; // the spectrum the texton aims at (interpolation_target of the model)
    SotResult sot;
    Texton luminance;
    Texton quantized_texton; // dequantized: what the runtime uses
    double rme = 0, rme_luminance = 0, rme_quantized = 0;
    std::vector<double> excess_kurtosis_30, excess_kurtosis_30_luminance;
    Matrix3 color_transform = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    AssetFields fields;
    std::vector<unsigned char> asset;
};

// Refuses what cannot be baked: options out of range (std::invalid_argument), an exemplar smaller than
// S - S (both sides at least 4r + 1; the message names the largest radius that fits) or constant
// (std::runtime_error).
void check_bake_input(const Image &exemplar, const BakeOptions &options);

// The asset fields of a bake (quantized texton, scales, mean and K in Q8.24, metadata).
AssetFields assemble_asset(const BakeResult &result, const BakeOptions &options, int exemplar_width,
                           int exemplar_height);

// Runs the whole pipeline; result.asset holds the encoded .dsnt bytes.
BakeResult bake(const Image &exemplar, const BakeOptions &options);

// ---- Preview ----

// One PNG (encoded in memory) a person reads at a glance: exemplar, its Gaussian version (spectral ADSN
// of t_u, same size), the texton scaled for display and a DSN synthesis of the baked asset by the
// runtime (dsn_lattice_tile_float), side by side. Throws std::runtime_error if the asset does not load.
std::vector<unsigned char> preview_png(const Image &exemplar, const BakeResult &result, uint32_t seed);

} // namespace dsn

#endif // DSN_BAKE_H
