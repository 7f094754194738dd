// sot.cpp - synthesis-oriented texton by alternating projections: the random-phase start, the pruned
// fast iteration and the straightforward full-FFT reference it is tested against. The method is that of
// Galerne, Leclaire and Moisan, "A texton for fast and flexible Gaussian texture synthesis" (2014).
//
// The zero frequency is left free (neither projected nor counted in the RME): the model's T_u(0) is 0
// only because the exemplar's mean was subtracted, and the runtime subtracts the noise's own mean
// lambda sum t, so the texton's sum changes nothing but the noise's variation at scales beyond the
// exemplar. Forcing T(0) = 0 makes every compact texton lose the lowest frequencies of the exemplar.
//
// Why pruned: in each iteration the spatial side is non-zero only on the (2r+1)^2 support, and only the
// support is needed back from the inverse transform. The textons are real, so only half the spectrum
// (xi1 = 0..M/2) is kept, in columns. Inverse: column FFTs of the half spectrum keep only the 2r+1
// support rows, then row FFTs of those rows only, two real rows packed in one complex transform.
// Forward: the same in reverse. Per iteration that is about C (M + 2r + 1) transforms of one side instead
// of 2 C (M + N).
#include "bake_internal.h"
#include "kiss_plan.h"
#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dsn {
namespace {

using Complex = std::complex<float>;

size_t wrap(int offset, int size) { return size_t(((offset % size) + size) % size); }

// splitmix64: a counter-based generator, so the white noise depends on the seed only.
uint64_t mix(uint64_t state) {
    state += 0x9E3779B97F4A7C15ull;
    state = (state ^ (state >> 30)) * 0xBF58476D1CE4E5B9ull;
    state = (state ^ (state >> 27)) * 0x94D049BB133111EBull;
    return state ^ (state >> 31);
}

// Uniform in (0, 1): 53 random bits, never 0.
double uniform(uint64_t seed, uint64_t counter) {
    return (double(mix(seed * 0xD1B54A32D192ED03ull + counter) >> 11) + 0.5) / 9007199254740992.0;
}

// Sums of one projection step, for the RME (all in double).
struct ProjectionSums {
    double texton_energy = 0, cross = 0;
};

// For frequencies first..count-1 of `channels` planes (plane c starts at texton + c * stride): measures
// |T|^2 and |T_u^* T|, then imposes the modulus: T_c = T_u,c z/|z|, z = sum_c conj(T_u,c) T_c.
// Plain real arithmetic: std::complex products go through the slow NaN-checking __muldc3.
void project_modulus(Complex *texton, const Complex *model, size_t count, size_t stride, int channels,
                     double weight, bool impose, ProjectionSums &sums, size_t first) {
    double texton_energy = 0, cross = 0;
    for (size_t i = first; i < count; i++) {
        double inner_real = 0, inner_imag = 0;
        for (int c = 0; c < channels; c++) {
            const double t_real = texton[size_t(c) * stride + i].real(),
                         t_imag = texton[size_t(c) * stride + i].imag();
            const double u_real = model[size_t(c) * stride + i].real(),
                         u_imag = model[size_t(c) * stride + i].imag();
            texton_energy += t_real * t_real + t_imag * t_imag;
            inner_real += u_real * t_real + u_imag * t_imag;
            inner_imag += u_real * t_imag - u_imag * t_real;
        }
        const double modulus = std::sqrt(inner_real * inner_real + inner_imag * inner_imag);
        cross += modulus;
        if (!impose) continue;
        const double phase_real = modulus > 0 ? inner_real / modulus : 0,
                     phase_imag = modulus > 0 ? inner_imag / modulus : 0;
        for (int c = 0; c < channels; c++) {
            const double u_real = model[size_t(c) * stride + i].real(),
                         u_imag = model[size_t(c) * stride + i].imag();
            texton[size_t(c) * stride + i] = Complex(float(u_real * phase_real - u_imag * phase_imag),
                                                     float(u_real * phase_imag + u_imag * phase_real));
        }
    }
    sums.texton_energy += weight * texton_energy;
    sums.cross += weight * cross;
}

double rme_from_sums(double model_energy, const ProjectionSums &sums) {
    if (!(model_energy > 0)) return 0;
    return std::sqrt(std::max(0.0, model_energy + sums.texton_energy - 2 * sums.cross) / model_energy);
}

bool should_stop(const std::vector<double> &rme, const SotOptions &options) {
    if (!(options.stop_tolerance > 0) || options.stop_window < 1) return false;
    const size_t window = size_t(options.stop_window);
    if (rme.size() <= window || rme.size() < size_t(std::max(0, options.minimum_iterations))) return false;
    return rme[rme.size() - 1 - window] - rme.back() < options.stop_tolerance;
}

// The reference: full inverse and forward 2-D FFTs of every channel in every iteration.
class ReferenceIteration {
  public:
    ReferenceIteration(const Spectrum &target, const Support &support)
        : target_(target), support_(support), texton_(),
          inverse_(make_fft_plan_2d(target.width, target.height, true)),
          forward_(make_fft_plan_2d(target.width, target.height, false)), buffer_(target.plane_size()) {
        const size_t plane = target.plane_size();
        for (size_t i = 0; i < target.values.size(); i++)
            if (i % plane != 0) model_energy_ += std::norm(std::complex<double>(target.values[i]));
    }

    void start(uint32_t seed) { texton_ = random_phase_start(target_, seed); }

    // One iteration; returns the RME of the support-limited texton, imposes the modulus if asked.
    double step(bool impose) {
        const size_t plane = target_.plane_size();
        Image torus;
        torus.width = target_.width;
        torus.height = target_.height;
        torus.channels = 1;
        torus.values.resize(plane);
        cropped_.clear();
        for (int c = 0; c < target_.channels; c++) {
            Complex *channel = &texton_.values[size_t(c) * plane];
            kiss_fftnd(inverse_.get(), as_kiss(channel), as_kiss(buffer_.data()));
            for (size_t i = 0; i < plane; i++) torus.values[i] = buffer_[i].real() / double(plane);
            Texton cropped = crop_to_support(torus, support_);
            cropped_.insert(cropped_.end(), cropped.values.begin(), cropped.values.end());
            std::fill(buffer_.begin(), buffer_.end(), Complex(0));
            const int side = support_.side(), r = support_.radius;
            for (int dy = -r; dy <= r; dy++)
                for (int dx = -r; dx <= r; dx++)
                    buffer_[wrap(dy, target_.height) * size_t(target_.width) + wrap(dx, target_.width)] =
                        float(cropped.values[size_t(dy + r) * size_t(side) + size_t(dx + r)]);
            kiss_fftnd(forward_.get(), as_kiss(buffer_.data()), as_kiss(channel));
        }
        ProjectionSums sums;
        project_modulus(texton_.values.data(), target_.values.data(), plane, plane, target_.channels, 1.0,
                        impose, sums, 1);
        return rme_from_sums(model_energy_, sums);
    }

    const std::vector<double> &texton_values() const { return cropped_; }

  private:
    const Spectrum &target_;
    const Support &support_;
    Spectrum texton_;
    FftPlan2d inverse_, forward_;
    std::vector<Complex> buffer_;
    std::vector<double> cropped_;
    double model_energy_ = 0;
};

// The pruned iteration on the half spectrum (see the top of the file), in two parallel passes per
// iteration: row pairs (inverse row transform, crop to the support, forward row transform) and columns
// xi1 (forward column transforms of every channel, projection, inverse column transforms for the next
// iteration). Each column's RME sums are kept apart and added in column order, so the result is the same
// on any number of threads.
class PrunedIteration {
  public:
    PrunedIteration(const Spectrum &target, const Support &support)
        : width_(target.width), height_(target.height), channels_(target.channels), radius_(support.radius),
          side_(support.side()), half_(target.width / 2 + 1), mask_(support.mask),
          column_inverse_(make_fft_plan(target.height, true)),
          column_forward_(make_fft_plan(target.height, false)),
          row_inverse_(make_fft_plan(target.width, true)), row_forward_(make_fft_plan(target.width, false)),
          model_(half_of(target)), spectrum_(model_.size()), rows_(size_t(channels_ * side_ * half_)),
          texton_(size_t(channels_ * side_ * side_)), column_weight_(size_t(half_), 2.0),
          column_sums_(size_t(half_)) {
        column_weight_[0] = 1;
        if (width_ % 2 == 0) column_weight_[size_t(half_ - 1)] = 1; // xi1 = M/2 is its own conjugate
        for (size_t k = 0; k < size_t(half_); k++)
            for (size_t i = k == 0 ? 1 : 0; i < size_t(height_); i++) // xi = 0 left out
                for (int c = 0; c < channels_; c++)
                    model_energy_ +=
                        column_weight_[k] * std::norm(std::complex<double>(model_[column(c, k) + i]));
    }

    void start(const Spectrum &start) {
        spectrum_ = half_of(start);
        parallel_ranges(size_t(half_), column_items_per_thread(), [&](size_t first, size_t last) {
            std::vector<Complex> column_out(static_cast<size_t>(height_));
            for (size_t k = first; k < last; k++) inverse_columns(k, column_out);
        });
    }

    double step(bool impose) {
        const size_t pairs = (row_count() + 1) / 2;
        parallel_ranges(pairs, items_per_thread(size_t(width_)), [&](size_t first, size_t last) {
            std::vector<Complex> row_in(static_cast<size_t>(width_)), row_out(row_in.size());
            for (size_t pair = first; pair < last; pair++) row_pair(2 * pair, row_in, row_out);
        });
        const size_t stride = size_t(half_) * size_t(height_);
        parallel_ranges(size_t(half_), column_items_per_thread(), [&](size_t first, size_t last) {
            std::vector<Complex> column_in(static_cast<size_t>(height_)), column_out(column_in.size());
            for (size_t k = first; k < last; k++) {
                forward_columns(k, column_in);
                column_sums_[k] = ProjectionSums();
                project_modulus(&spectrum_[column(0, k)], &model_[column(0, k)], size_t(height_), stride,
                                channels_, 1.0, impose, column_sums_[k], k == 0 ? 1 : 0);
                if (impose) inverse_columns(k, column_out);
            }
        });
        ProjectionSums sums;
        for (size_t k = 0; k < size_t(half_); k++) {
            sums.texton_energy += column_weight_[k] * column_sums_[k].texton_energy;
            sums.cross += column_weight_[k] * column_sums_[k].cross;
        }
        return rme_from_sums(model_energy_, sums);
    }

    const std::vector<double> &texton_values() const { return texton_; }

  private:
    // A column of every channel per item, transformed both ways.
    size_t column_items_per_thread() const {
        return items_per_thread(2 * size_t(channels_) * size_t(height_));
    }

    size_t column(int c, size_t k) const { return (size_t(c) * size_t(half_) + k) * size_t(height_); }
    size_t row_count() const { return size_t(channels_) * size_t(side_); }
    // rows_ holds, for every channel and support row dy, the half row spectrum xi1 = 0..M/2.
    Complex &row_entry(size_t row, size_t k) { return rows_[row * size_t(half_) + k]; }

    // Columns xi1 = 0..M/2 of every channel, each column contiguous over xi2.
    std::vector<Complex> half_of(const Spectrum &full) const {
        std::vector<Complex> half(size_t(channels_) * size_t(half_) * size_t(height_));
        const size_t plane = full.plane_size();
        for (int c = 0; c < channels_; c++)
            for (size_t k = 0; k < size_t(half_); k++)
                for (size_t xi2 = 0; xi2 < size_t(height_); xi2++)
                    half[column(c, k) + xi2] = full.values[size_t(c) * plane + xi2 * size_t(width_) + k];
        return half;
    }

    // Column k of every channel -> its support rows (inverse transform, only 2r+1 outputs kept).
    void inverse_columns(size_t k, std::vector<Complex> &column_out) {
        for (int c = 0; c < channels_; c++) {
            kiss_fft(column_inverse_.get(), as_kiss(&spectrum_[column(c, k)]), as_kiss(column_out.data()));
            for (int dy = 0; dy < side_; dy++)
                row_entry(size_t(c) * size_t(side_) + size_t(dy), k) =
                    column_out[wrap(dy - radius_, height_)];
        }
    }

    // Support rows of column k of every channel -> column k of the spectrum (forward transform).
    void forward_columns(size_t k, std::vector<Complex> &column_in) {
        std::fill(column_in.begin(), column_in.end(), Complex(0));
        for (int c = 0; c < channels_; c++) {
            for (int dy = 0; dy < side_; dy++)
                column_in[wrap(dy - radius_, height_)] = row_entry(size_t(c) * size_t(side_) + size_t(dy), k);
            kiss_fft(column_forward_.get(), as_kiss(column_in.data()), as_kiss(&spectrum_[column(c, k)]));
        }
    }

    // Rows a and a + 1 (two real rows in one complex transform): half spectra -> support values
    // (masked, scaled by 1 / (M N)) -> half spectra of the cropped rows.
    void row_pair(size_t a, std::vector<Complex> &row_in, std::vector<Complex> &row_out) {
        const size_t b = a + 1;
        const bool second = b < row_count();
        pack_hermitian_rows(&rows_[a * size_t(half_)], second ? &rows_[b * size_t(half_)] : nullptr, row_in);
        kiss_fft(row_inverse_.get(), as_kiss(row_in.data()), as_kiss(row_out.data()));
        const float normalization = 1.0f / (float(width_) * float(height_));
        for (int dx = 0; dx < side_; dx++) {
            const Complex value = row_out[wrap(dx - radius_, width_)] * normalization;
            texton_[a * size_t(side_) + size_t(dx)] =
                mask_[(a % size_t(side_)) * size_t(side_) + size_t(dx)] ? value.real() : 0.0;
            if (second)
                texton_[b * size_t(side_) + size_t(dx)] =
                    mask_[(b % size_t(side_)) * size_t(side_) + size_t(dx)] ? value.imag() : 0.0;
        }
        std::fill(row_in.begin(), row_in.end(), Complex(0));
        for (int dx = 0; dx < side_; dx++)
            row_in[wrap(dx - radius_, width_)] =
                Complex(float(texton_[a * size_t(side_) + size_t(dx)]),
                        second ? float(texton_[b * size_t(side_) + size_t(dx)]) : 0.0f);
        kiss_fft(row_forward_.get(), as_kiss(row_in.data()), as_kiss(row_out.data()));
        for (size_t k = 0; k < size_t(half_); k++) {
            const Complex z = row_out[k], mirror = std::conj(row_out[(size_t(width_) - k) % size_t(width_)]);
            rows_[a * size_t(half_) + k] = (z + mirror) * 0.5f;
            if (second) {
                const Complex difference = z - mirror; // = 2i B
                rows_[b * size_t(half_) + k] = Complex(difference.imag() * 0.5f, -difference.real() * 0.5f);
            }
        }
    }

    // row_in = A + i B over the full row, A and B Hermitian spectra given by their halves.
    void pack_hermitian_rows(const Complex *first, const Complex *second,
                             std::vector<Complex> &row_in) const {
        for (size_t k = 0; k < size_t(width_); k++) {
            const bool upper = k >= size_t(half_);
            const size_t source = upper ? size_t(width_) - k : k;
            Complex a = first[source], b = second ? second[source] : Complex(0);
            if (upper) {
                a = std::conj(a);
                b = std::conj(b);
            } else if (k == 0 || (width_ % 2 == 0 && k == size_t(half_ - 1))) {
                a = a.real(); // self-conjugate frequencies are real for a real row
                b = b.real();
            }
            row_in[k] = Complex(a.real() - b.imag(), a.imag() + b.real());
        }
    }

    int width_, height_, channels_, radius_, side_, half_;
    std::vector<unsigned char> mask_;
    FftPlan column_inverse_, column_forward_, row_inverse_, row_forward_;
    std::vector<Complex> model_, spectrum_, rows_;
    std::vector<double> texton_;
    std::vector<double> column_weight_;
    std::vector<ProjectionSums> column_sums_;
    double model_energy_ = 0;
};

template <typename Iteration>
SotResult run_iterations(Iteration &iteration, const Spectrum &target, const Support &support,
                         const SotOptions &options) {
    SotResult result;
    for (int done = 0; done < options.iterations; done++) {
        const bool last = done + 1 == options.iterations;
        result.rme_per_iteration.push_back(iteration.step(!last));
        if (options.progress) options.progress(done + 1, options.iterations, result.rme_per_iteration.back());
        if (!last && should_stop(result.rme_per_iteration, options)) {
            result.stop = SotStop::Converged;
            break;
        }
    }
    result.texton.support = support;
    result.texton.channels = target.channels;
    result.texton.values = iteration.texton_values();
    return result;
}

} // namespace

Image white_noise(int width, int height, uint32_t seed) {
    Image noise;
    noise.width = width;
    noise.height = height;
    noise.channels = 1;
    noise.values.resize(size_t(width) * size_t(height));
    for (size_t i = 0; i < noise.values.size(); i++) // Box-Muller
        noise.values[i] = std::sqrt(-2 * std::log(uniform(seed, 2 * i))) *
                          std::cos(6.283185307179586 * uniform(seed, 2 * i + 1));
    return noise;
}

Spectrum random_phase_start(const Spectrum &target, uint32_t seed) {
    const Spectrum noise_spectrum = forward_dft(white_noise(target.width, target.height, seed));
    Spectrum start = target;
    const size_t plane = target.plane_size();
    for (size_t i = 0; i < plane; i++) {
        const std::complex<double> value = noise_spectrum.values[i];
        const double modulus = std::abs(value);
        const std::complex<double> phase = modulus > 0 ? value / modulus : 1.0;
        for (int c = 0; c < target.channels; c++) {
            Complex &entry = start.values[size_t(c) * plane + i];
            entry = Complex(std::complex<double>(entry) * phase);
        }
    }
    return start;
}

int early_stop_minimum_iterations(int width, int height) {
    const double pixels = std::max(1.0, double(width) * double(height));
    return int(std::min(1e6, std::ceil(kEarlyStopMinimumWork / pixels)));
}

SotResult sot_alternating_projections(const Spectrum &target, const Support &support,
                                      const SotOptions &options) {
    if (options.iterations < 1) throw std::invalid_argument("iterations must be at least 1");
    if (target.width < 2 * support.side() - 1 || target.height < 2 * support.side() - 1)
        throw std::invalid_argument("the spectrum is smaller than S - S");
    if (options.reference) {
        ReferenceIteration iteration(target, support);
        iteration.start(options.seed);
        return run_iterations(iteration, target, support, options);
    }
    PrunedIteration iteration(target, support);
    iteration.start(random_phase_start(target, options.seed));
    return run_iterations(iteration, target, support, options);
}

} // namespace dsn
