// synth.h - spectral texture synthesis at any size: random phase noise (RPN) and asymptotic discrete spot
// noise (ADSN) of an exemplar, as Galerne, Gousseau and Morel define them in "Random phase textures:
// theory and synthesis" (IEEE TIP 2011). Part of libdsn_bake.a (offline, C++17); dsn-synth is its
// command-line front end.
//
// What it does
//   exemplar u (M x N) -> periodic component p, mean m, spot t = (p - m) / sqrt(MN) -> the spot on the
//   synthesis domain (extended when the output is larger than the exemplar) -> one random field:
//     ADSN: f = m + t * W, W a standard Gaussian white noise, * the circular convolution; the same W for
//           every channel (colour ADSN);
//     RPN:  f^ = m MN delta + sqrt(MN) t^ e^(i theta), theta the phase of the DFT of a white noise
//           (uniform, odd); the same theta for every channel (colour RPN).
//   At the exemplar size, RPN keeps the spectrum modulus of p exactly and ADSN its autocorrelation in
//   expectation; both keep the mean exactly (the spot sums to zero).
//
// Larger outputs (the spot extension)
//   On an axis where the output is larger than the exemplar, the spot is pasted at the centre of a
//   domain of the output's size (rounded up to a size the FFT factors well) that is zero (the mean)
//   elsewhere, and attenuated near its border on that axis by the smooth transition
//   h(s) = g(s) / (g(s) + g(1 - s)), g(s) = exp(-1/s) for s > 0, 0 otherwise, with s the distance to the
//   border in units of alpha times the exemplar's side: 1 further in than alpha * side. The attenuated spot
//   is then recentred (its sum is 0 again) and multiplied per channel so that its sum of squares, the
//   noise's variance, is that of the spot it came from. On an axis where the output is not larger, the
//   spot is left whole (it is periodic there) and the output is the top-left part of the domain.
//
// Limits
//   Output sides 1..kMaxSynthesisSide. Memory: 16 bytes per pixel of the FFT domain (two complex float
//   planes: the noise's spectrum and the channel being filtered) plus 8 per channel per output pixel (the
//   result, in doubles): a 16384 x 16384 RGB output needs about 10 GiB. synthesis_memory_bytes says.
#ifndef DSN_OFFLINE_SYNTH_H
#define DSN_OFFLINE_SYNTH_H

#include <complex>
#include <cstdint>
#include <functional>

#include "dsn/bake.h"

namespace dsn {

enum class SynthesisMethod { adsn, rpn };

constexpr int kMaxSynthesisSide = 16384;
constexpr double kDefaultSpotAlpha = 0.2;

// Called with the fraction of the work done, in [0, 1], a few hundred times at most per synthesis.
using SynthesisProgress = std::function<void(double fraction)>;

struct SynthesisOptions {
    int width = 0, height = 0; // the output, 1..kMaxSynthesisSide each
    SynthesisMethod method = SynthesisMethod::adsn;
    uint32_t seed = 0;
    double alpha = kDefaultSpotAlpha; // (0, 0.5]: the attenuated border, as a fraction of each side
    SynthesisProgress progress;       // may be empty
};

// Where the field is computed: domain_width x domain_height (the output is its top-left part), and on
// which axes the spot is extended.
struct SynthesisDomain {
    int width = 0, height = 0;
    bool extend_x = false, extend_y = false;
};
SynthesisDomain synthesis_domain(int exemplar_width, int exemplar_height, int output_width,
                                 int output_height);

// Bytes the synthesis allocates at most (for the limits stated in --help).
uint64_t synthesis_memory_bytes(int exemplar_width, int exemplar_height, int channels, int output_width,
                                int output_height);

// The smooth transition h above: 0 for s <= 0, 1 for s >= 1, infinitely differentiable.
double smooth_transition(double s);

// The spot of `model` (its t_u) on `domain`: pasted at the centre, attenuated and renormalized on the
// extended axes as described above. Sums to 0 per channel; per channel, sum of squares = that of t_u.
// extended_spot_channel writes channel `channel` of it into a row-major complex plane of the domain.
Image extended_spot(const GaussianModel &model, const SynthesisDomain &domain, double alpha);
void extended_spot_channel(const GaussianModel &model, const SynthesisDomain &domain, double alpha,
                           int channel, std::complex<float> *plane);

// Refuses what cannot be synthesized: options out of range (std::invalid_argument, naming the option),
// an empty or constant exemplar (std::runtime_error).
void check_synthesis_input(const Image &exemplar, const SynthesisOptions &options);

// The synthesized image, options.width x options.height, the exemplar's channels, in exemplar units
// (not clamped). The same exemplar, options and seed give the same image.
Image synthesize(const Image &exemplar, const SynthesisOptions &options);

// In-place unnormalized 2-D DFT (inverse: conjugate exponent, not divided) of a row-major height x width
// array, by 1-D KissFFT transforms of the rows then of blocks of columns (KissFFT's own 2-D real
// transform crashes from 64 x 64 in the packaged version; its complex one allocates a whole plane more).
// The blocks are shared among as many threads as the machine has cores; `step` (may be empty) is called
// after each block of rows or columns, one call at a time, dft_2d_block_count calls in all.
void dft_2d_in_place(std::complex<float> *values, int width, int height, bool inverse,
                     const std::function<void(int blocks_done)> &step);
int dft_2d_block_count(int width, int height);

} // namespace dsn

#endif // DSN_OFFLINE_SYNTH_H
