// texton.cpp - the support mask, textons on the torus (crop, spectrum) and the luminance-texton baseline.
#include "bake_internal.h"
#include "runtime/setup/format_bytes.h"

#include <cmath>
#include <stdexcept>

namespace dsn {
namespace {

// Index of signed coordinate `offset` on a torus of `size` points.
size_t wrap(int offset, int size) { return size_t(((offset % size) + size) % size); }

} // namespace

int Support::size() const {
    int count = 0;
    for (unsigned char inside : mask) count += inside;
    return count;
}

Support support_mask(int radius, uint32_t shape) {
    if (radius < 1 || radius > kMaxRadius)
        throw std::invalid_argument("radius " + std::to_string(radius) + " out of range 1.." +
                                    std::to_string(kMaxRadius));
    if (shape != DSN_SHAPE_RECTANGLE && shape != DSN_SHAPE_DISK) throw std::invalid_argument("unknown shape");
    Support support;
    support.radius = radius;
    support.shape = shape;
    const int side = support.side();
    support.mask.resize(size_t(side) * size_t(side));
    for (int row = 0; row < side; row++)
        for (int column = 0; column < side; column++)
            support.mask[size_t(row) * size_t(side) + size_t(column)] =
                dsn_in_support(shape, uint32_t(side), uint32_t(row), uint32_t(column)) ? 1 : 0;
    return support;
}

Texton crop_to_support(const Image &torus_image, const Support &support) {
    Texton texton;
    texton.support = support;
    texton.channels = torus_image.channels;
    const int side = support.side(), r = support.radius;
    texton.values.assign(size_t(side) * size_t(side) * size_t(torus_image.channels), 0.0);
    for (int c = 0; c < torus_image.channels; c++)
        for (int row = 0; row < side; row++)
            for (int column = 0; column < side; column++) {
                const size_t index = size_t(row) * size_t(side) + size_t(column);
                if (!support.mask[index]) continue;
                texton.values[size_t(c) * support.mask.size() + index] = torus_image.at(
                    int(wrap(column - r, torus_image.width)), int(wrap(row - r, torus_image.height)), c);
            }
    return texton;
}

Spectrum texton_spectrum(const Texton &texton, int width, int height) {
    Image torus;
    torus.width = width;
    torus.height = height;
    torus.channels = texton.channels;
    torus.values.assign(size_t(width) * size_t(height) * size_t(texton.channels), 0.0);
    const int r = texton.support.radius;
    for (int c = 0; c < texton.channels; c++)
        for (int dy = -r; dy <= r; dy++)
            for (int dx = -r; dx <= r; dx++)
                torus.at(int(wrap(dx, width)), int(wrap(dy, height)), c) += texton.at(dx, dy, c);
    return forward_dft(torus);
}

Texton luminance_texton(const Spectrum &model, const Support &support) {
    Spectrum rotated = model;
    const size_t plane = model.plane_size();
    for (size_t i = 0; i < plane; i++) {
        std::complex<double> luminance = model.values[i];
        if (model.channels == 3)
            luminance = std::complex<double>(model.values[i]) / 3.0 +
                        std::complex<double>(model.values[plane + i]) / 2.0 +
                        std::complex<double>(model.values[2 * plane + i]) / 6.0;
        const double modulus = std::abs(luminance);
        const std::complex<double> phase = modulus > 0 ? std::conj(luminance) / modulus : 0.0;
        for (int c = 0; c < model.channels; c++) {
            std::complex<float> &value = rotated.values[size_t(c) * plane + i];
            value = std::complex<float>(std::complex<double>(value) * phase);
        }
    }
    return crop_to_support(inverse_dft(rotated), support);
}

} // namespace dsn
