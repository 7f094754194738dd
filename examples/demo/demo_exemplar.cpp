// dsn-demo-exemplar: writes the demo's own exemplar, a wood-like material that is exactly a Gaussian
// texture of known spots, so the demo needs no photo and the right answer is known.
//
// The image is a random-phase texture on the torus: mean + sum over components of colour_k * (spot_k
// filtered by one shared random phase), so its spectrum modulus is exactly that of the coloured spots and
// its Gaussian model is known. Component 1 is a long,
// thin, slightly tilted spot (the grain), component 2 a round blob (slow colour variation), component 3
// a small dot (fine speckle). The convolutions are circular, so the image tiles seamlessly.
#include <cmath>
#include <complex>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "offline/bake_internal.h"
#include "offline/tools/command_line.h"
#include "offline/tools/file_output.h"
#include "offline/tools/png_output.h"

namespace {

const char *const usage =
    "usage: dsn-demo-exemplar OUT.png [--size N] [--seed S]\n"
    "Writes an N x N (default 256, 64..2048) RGB wood-like Gaussian texture made from known spots.\n"
    "Flags take --flag value or --flag=value; -h, --help, --version. Errors: one line on stderr, exit 2\n"
    "for a usage mistake (ending \"(see --help)\"), exit 1 when the file cannot be written.\n";

struct Component {
    double length, width, angle_degrees; // Gaussian spot: standard deviations along and across
    double wave;                         // period of a cosine across the spot (0: none), in pixels
    double color[3];                     // RGB amplitude
};

const Component kComponents[] = {
    {6.0, 1.0, 8.0, 0.0, {0.55, 0.36, 0.20}},   // grain: long streaks
    {4.5, 3.0, -30.0, 0.0, {0.40, 0.30, 0.22}}, // slower colour variation
    {1.0, 0.8, 0.0, 0.0, {0.10, 0.09, 0.08}},   // fine speckle
};
const double kMean[3] = {0.56, 0.39, 0.24};

// The spot of a component on an odd window, normalized to unit energy.
std::vector<double> spot(const Component &component, int radius) {
    const int side = 2 * radius + 1;
    const double angle = component.angle_degrees * 3.14159265358979 / 180;
    std::vector<double> values(size_t(side * side));
    double energy = 0;
    for (int y = -radius; y <= radius; y++)
        for (int x = -radius; x <= radius; x++) {
            const double along = x * std::cos(angle) + y * std::sin(angle);
            const double across = -x * std::sin(angle) + y * std::cos(angle);
            double v = std::exp(-0.5 * (along * along / (component.length * component.length) +
                                        across * across / (component.width * component.width)));
            values[size_t((y + radius) * side + x + radius)] = v;
            energy += v * v;
        }
    for (double &v : values) v /= std::sqrt(energy);
    return values;
}

// The phase of a white noise's DFT, scaled to the modulus such a noise has on average (size, the square root
// of the pixel count). Multiplying a spot's spectrum by it gives a random-phase texture: a Gaussian-looking
// field whose spectrum modulus is exactly the spot's, so the exemplar's Gaussian model is known exactly.
dsn::Spectrum random_phase(int size, std::mt19937 &random) {
    std::normal_distribution<double> normal;
    dsn::Image white;
    white.width = white.height = size;
    white.channels = 1;
    white.values.resize(size_t(size * size));
    for (double &w : white.values) w = normal(random);
    dsn::Spectrum phase = dsn::forward_dft(white);
    for (std::complex<float> &value : phase.values) {
        const float modulus = std::abs(value);
        value = modulus > 0 ? value * (float(size) / modulus) : std::complex<float>(float(size), 0);
    }
    return phase;
}

// The spot (placed on the torus around the origin) filtered by the shared random phase: unit variance.
std::vector<double> random_phase_field(const std::vector<double> &kernel, int radius, int size,
                                       const dsn::Spectrum &phase) {
    dsn::Image spot_on_torus;
    spot_on_torus.width = spot_on_torus.height = size;
    spot_on_torus.channels = 1;
    spot_on_torus.values.assign(size_t(size * size), 0.0);
    const int side = 2 * radius + 1;
    for (int dy = -radius; dy <= radius; dy++)
        for (int dx = -radius; dx <= radius; dx++)
            spot_on_torus.at(((dx % size) + size) % size, ((dy % size) + size) % size, 0) +=
                kernel[size_t((dy + radius) * side + dx + radius)];
    dsn::Spectrum product = dsn::forward_dft(spot_on_torus);
    for (size_t i = 0; i < product.values.size(); i++) product.values[i] *= phase.values[i];
    return dsn::inverse_dft(product).values;
}

int run(dsn::CommandLine &command_line) {
    std::string output;
    int size = 256;
    uint32_t seed = 2024;
    while (command_line.next()) {
        if (command_line.is("--size")) {
            size = int(dsn::parse_integer(command_line, 64, 2048));
        } else if (command_line.is("--seed")) {
            seed = uint32_t(dsn::parse_integer(command_line, 0, 4294967295ll));
        } else if (command_line.is_positional() && output.empty()) {
            output = command_line.current();
        } else {
            command_line.unknown();
        }
    }
    if (output.empty()) throw dsn::UsageError("no output given");
    std::mt19937 random(seed);
    std::vector<double> image(size_t(size * size) * 3);
    for (size_t i = 0; i < image.size(); i++) image[i] = kMean[i % 3];
    // One phase for every component: the colour of each frequency is then a single vector, the rank-one
    // cross-spectrum the Gaussian model of an image (and the SOT's common phase) describes exactly.
    const dsn::Spectrum phase = random_phase(size, random);
    for (const Component &component : kComponents) {
        const int radius = int(std::ceil(3 * component.length));
        const std::vector<double> field = random_phase_field(spot(component, radius), radius, size, phase);
        for (size_t p = 0; p < field.size(); p++)
            for (int c = 0; c < 3; c++) image[p * 3 + size_t(c)] += 0.18 * component.color[c] * field[p];
    }
    std::vector<unsigned char> pixels(image.size());
    for (size_t i = 0; i < image.size(); i++)
        pixels[i] = static_cast<unsigned char>(std::lround(std::min(1.0, std::max(0.0, image[i])) * 255));
    dsn::write_file_atomically(output, dsn::encode_png(size, size, 3, pixels.data()));
    return 0;
}

} // namespace

int main(int argc, char **argv) { return dsn::run_tool("dsn-demo-exemplar", usage, argc, argv, run); }
