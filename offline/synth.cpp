// synth.cpp - RPN and ADSN synthesis at any size (the spot extension, the 2-D DFT by blocks, the
// filtering of one white noise per image). See synth.h for the mathematics.
#include "synth.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bake_internal.h"
#include "kiss_plan.h"

namespace dsn {
namespace {

// Rows and columns are transformed this many at a time: a block of columns is gathered with whole
// cache lines, and progress is reported per block.
const int kBlock = 16;

bool is_constant(const Image &u) {
    const size_t plane = size_t(u.width) * size_t(u.height);
    for (int c = 0; c < u.channels; c++)
        for (size_t i = 1; i < plane; i++)
            if (u.values[size_t(c) * plane + i] != u.values[size_t(c) * plane]) return false;
    return true;
}

// The attenuation along one axis of an exemplar side of `size` pixels: 1 when not extended.
std::vector<double> border_profile(int size, bool extend, double alpha) {
    std::vector<double> profile(size_t(size), 1.0);
    if (!extend) return profile;
    for (int i = 0; i < size; i++) {
        const double distance = std::min(i + 0.5, size - i - 0.5);
        profile[size_t(i)] = smooth_transition(distance / (alpha * size));
    }
    return profile;
}

int extended_side(int exemplar, int output) {
    return output > exemplar ? kiss_fft_next_fast_size(output) : exemplar;
}

} // namespace

SynthesisDomain synthesis_domain(int exemplar_width, int exemplar_height, int output_width,
                                 int output_height) {
    SynthesisDomain domain;
    domain.width = extended_side(exemplar_width, output_width);
    domain.height = extended_side(exemplar_height, output_height);
    domain.extend_x = output_width > exemplar_width;
    domain.extend_y = output_height > exemplar_height;
    return domain;
}

uint64_t synthesis_memory_bytes(int exemplar_width, int exemplar_height, int channels, int output_width,
                                int output_height) {
    const SynthesisDomain domain =
        synthesis_domain(exemplar_width, exemplar_height, output_width, output_height);
    return uint64_t(domain.width) * uint64_t(domain.height) * 16 +
           uint64_t(output_width) * uint64_t(output_height) * uint64_t(channels) * 8;
}

double smooth_transition(double s) {
    if (s <= 0) return 0;
    if (s >= 1) return 1;
    const double rising = std::exp(-1 / s), falling = std::exp(-1 / (1 - s));
    return rising / (rising + falling);
}

void extended_spot_channel(const GaussianModel &model, const SynthesisDomain &domain, double alpha,
                           int channel, std::complex<float> *plane) {
    const int width = model.width, height = model.height;
    if (domain.width < width || domain.height < height)
        throw std::invalid_argument("the synthesis domain is smaller than the exemplar");
    if (channel < 0 || channel >= model.channels) throw std::invalid_argument("no such channel");
    const std::vector<double> profile_x = border_profile(width, domain.extend_x, alpha);
    const std::vector<double> profile_y = border_profile(height, domain.extend_y, alpha);
    // Recentre the attenuated spot (sum 0: the noise's mean stays the exemplar's), then give it back the
    // spot's sum of squares (the noise's variance).
    double weight_sum = 0, weighted_sum = 0, energy = 0;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const double weight = profile_x[size_t(x)] * profile_y[size_t(y)];
            const double value = model.t_u.at(x, y, channel);
            weight_sum += weight;
            weighted_sum += weight * value;
            energy += value * value;
        }
    const double centre = weighted_sum / weight_sum; // weight_sum > 0: the middle weights are 1
    double attenuated_energy = 0;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const double value =
                profile_x[size_t(x)] * profile_y[size_t(y)] * (model.t_u.at(x, y, channel) - centre);
            attenuated_energy += value * value;
        }
    const double gain = attenuated_energy > 0 ? std::sqrt(energy / attenuated_energy) : 0.0;
    const size_t domain_plane = size_t(domain.width) * size_t(domain.height);
    std::fill(plane, plane + domain_plane, std::complex<float>(0));
    const int offset_x = (domain.width - width) / 2, offset_y = (domain.height - height) / 2;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const double value =
                gain * profile_x[size_t(x)] * profile_y[size_t(y)] * (model.t_u.at(x, y, channel) - centre);
            plane[size_t(y + offset_y) * size_t(domain.width) + size_t(x + offset_x)] = float(value);
        }
}

Image extended_spot(const GaussianModel &model, const SynthesisDomain &domain, double alpha) {
    Image spot;
    spot.width = domain.width;
    spot.height = domain.height;
    spot.channels = model.channels;
    const size_t plane = size_t(domain.width) * size_t(domain.height);
    spot.values.resize(plane * size_t(model.channels));
    std::vector<std::complex<float>> values(plane);
    for (int c = 0; c < model.channels; c++) {
        extended_spot_channel(model, domain, alpha, c, values.data());
        for (size_t i = 0; i < plane; i++) spot.values[size_t(c) * plane + i] = values[i].real();
    }
    return spot;
}

int dft_2d_block_count(int width, int height) {
    return (height + kBlock - 1) / kBlock + (width + kBlock - 1) / kBlock;
}

void dft_2d_in_place(std::complex<float> *values, int width, int height, bool inverse,
                     const std::function<void(int blocks_done)> &step) {
    const size_t row_length = size_t(width);
    const int row_blocks = (height + kBlock - 1) / kBlock, column_blocks = (width + kBlock - 1) / kBlock;
    // Every block is transformed alone, so the result does not depend on the number of threads.
    const FftPlan row_plan = make_fft_plan(width, inverse), column_plan = make_fft_plan(height, inverse);
    std::atomic<int> next_block(0);
    std::mutex step_lock;
    int blocks_done = 0; // guarded by step_lock
    std::exception_ptr failure;
    auto pass = [&](bool rows) {
        const int count = rows ? row_blocks : column_blocks;
        auto worker = [&]() {
            try {
                std::vector<std::complex<float>> transformed(size_t(std::max(width, height)));
                std::vector<std::complex<float>> columns(size_t(kBlock) * size_t(height));
                for (int block; (block = next_block++) < count;) {
                    if (rows) {
                        for (int y = block * kBlock; y < std::min(height, (block + 1) * kBlock); y++) {
                            std::complex<float> *row = values + size_t(y) * row_length;
                            kiss_fft(row_plan.get(), as_kiss(row), as_kiss(transformed.data()));
                            std::copy(transformed.begin(), transformed.begin() + width, row);
                        }
                    } else {
                        const int x0 = block * kBlock, columns_here = std::min(kBlock, width - x0);
                        for (int y = 0; y < height; y++)
                            for (int k = 0; k < columns_here; k++)
                                columns[size_t(k) * size_t(height) + size_t(y)] =
                                    values[size_t(y) * row_length + size_t(x0 + k)];
                        for (int k = 0; k < columns_here; k++) {
                            std::complex<float> *column = &columns[size_t(k) * size_t(height)];
                            kiss_fft(column_plan.get(), as_kiss(column), as_kiss(transformed.data()));
                            std::copy(transformed.begin(), transformed.begin() + height, column);
                        }
                        for (int y = 0; y < height; y++)
                            for (int k = 0; k < columns_here; k++)
                                values[size_t(y) * row_length + size_t(x0 + k)] =
                                    columns[size_t(k) * size_t(height) + size_t(y)];
                    }
                    std::lock_guard<std::mutex> guard(step_lock);
                    ++blocks_done;
                    if (step) step(blocks_done);
                }
            } catch (...) {
                std::lock_guard<std::mutex> guard(step_lock);
                if (!failure) failure = std::current_exception();
                next_block = count;
            }
        };
        next_block = 0;
        const unsigned threads = std::min(std::max(1u, std::thread::hardware_concurrency()), unsigned(count));
        std::vector<std::thread> helpers;
        for (unsigned t = 1; t < threads; t++) helpers.emplace_back(worker);
        worker();
        for (std::thread &helper : helpers) helper.join();
        if (failure) std::rethrow_exception(failure);
    };
    pass(true);
    pass(false);
}

void check_synthesis_input(const Image &exemplar, const SynthesisOptions &options) {
    const std::string sides = "1.." + std::to_string(kMaxSynthesisSide);
    if (options.width < 1 || options.width > kMaxSynthesisSide)
        throw std::invalid_argument("output width " + std::to_string(options.width) + " out of range " +
                                    sides);
    if (options.height < 1 || options.height > kMaxSynthesisSide)
        throw std::invalid_argument("output height " + std::to_string(options.height) + " out of range " +
                                    sides);
    if (!(options.alpha > 0 && options.alpha <= 0.5))
        throw std::invalid_argument("alpha must be within (0, 0.5]");
    if (options.method != SynthesisMethod::adsn && options.method != SynthesisMethod::rpn)
        throw std::invalid_argument("unknown synthesis method");
    if (exemplar.width < 1 || exemplar.height < 1 || exemplar.channels < 1 ||
        exemplar.values.size() !=
            size_t(exemplar.width) * size_t(exemplar.height) * size_t(exemplar.channels))
        throw std::runtime_error("empty image");
    if (exemplar.width > kMaxExemplarSide || exemplar.height > kMaxExemplarSide)
        throw std::runtime_error("exemplar larger than the limit of " + std::to_string(kMaxExemplarSide) +
                                 " per side");
    if (is_constant(exemplar))
        throw std::runtime_error("constant image (no variance): nothing to synthesize");
}

Image synthesize(const Image &exemplar, const SynthesisOptions &options) {
    check_synthesis_input(exemplar, options);
    const GaussianModel model = gaussian_model(exemplar, true);
    const SynthesisDomain domain =
        synthesis_domain(exemplar.width, exemplar.height, options.width, options.height);
    const size_t plane = size_t(domain.width) * size_t(domain.height);

    // Progress: one noise transform, then a forward and an inverse transform per channel.
    const double total_blocks =
        double(dft_2d_block_count(domain.width, domain.height)) * double(1 + 2 * exemplar.channels);
    int blocks_before = 0, last_reported = -1;
    auto report = [&](int blocks_done) {
        if (!options.progress) return;
        const int permille = int(1000.0 * double(blocks_before + blocks_done) / total_blocks);
        if (permille / 5 > last_reported / 5) {
            last_reported = permille;
            options.progress(permille / 1000.0);
        }
    };
    auto transform = [&](std::complex<float> *values, bool inverse) {
        dft_2d_in_place(values, domain.width, domain.height, inverse, report);
        blocks_before += dft_2d_block_count(domain.width, domain.height);
    };

    // What every channel's spot spectrum is multiplied by: the white noise's DFT (ADSN), or its phase
    // times sqrt(domain size) (RPN). The zero frequency is 0: the mean is added back exactly.
    std::vector<std::complex<float>> multiplier(plane);
    {
        const Image noise = white_noise(domain.width, domain.height, options.seed);
        for (size_t i = 0; i < plane; i++) multiplier[i] = float(noise.values[i]);
    }
    transform(multiplier.data(), false);
    if (options.method == SynthesisMethod::rpn) {
        const double gain = std::sqrt(double(plane));
        for (std::complex<float> &value : multiplier) {
            const std::complex<double> precise = value;
            const double modulus = std::abs(precise);
            value =
                std::complex<float>(modulus > 0 ? precise * (gain / modulus) : std::complex<double>(gain));
        }
    }
    multiplier[0] = 0;

    Image output;
    output.width = options.width;
    output.height = options.height;
    output.channels = exemplar.channels;
    output.values.resize(size_t(options.width) * size_t(options.height) * size_t(exemplar.channels));
    std::vector<std::complex<float>> field(plane);
    const double normalization = 1.0 / double(plane);
    for (int c = 0; c < exemplar.channels; c++) {
        extended_spot_channel(model, domain, options.alpha, c, field.data());
        transform(field.data(), false);
        for (size_t i = 0; i < plane; i++) field[i] *= multiplier[i];
        transform(field.data(), true);
        for (int y = 0; y < options.height; y++)
            for (int x = 0; x < options.width; x++)
                output.at(x, y, c) =
                    double(field[size_t(y) * size_t(domain.width) + size_t(x)].real()) * normalization +
                    model.mean[size_t(c)];
    }
    if (options.progress && last_reported < 1000) options.progress(1.0);
    return output;
}

} // namespace dsn
