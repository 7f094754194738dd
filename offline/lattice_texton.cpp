// lattice_texton.cpp - the lattice texton of a bilinear asset (format.h, version 1.3): what the lattice
// evaluators read so that a texton baked for bilinear reads gives the same statistics on the lattice.
//
// The continuous noise sampled on the lattice has the texton's spectrum times B = b(xi1) b(xi2),
// b(xi) = 2/3 + cos(2 pi xi)/3 (the tent's autocorrelation sampled at the integers). The two-tap filter
// k = [a, b] (offsets 0 and +1), a = (1 + 1/sqrt 3)/2, b = (1 - 1/sqrt 3)/2, has a + b = 1 and
// |k^(xi)|^2 = a^2 + b^2 + 2ab cos(2 pi xi) = b(xi), so the lattice noise of t * (k (x) k) has exactly
// the continuous noise's covariance at integer lags, with the same sum (the same mean).
#include "dsn/asset_writer.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dsn {
namespace {

const double kTapNear = (1 + 1 / std::sqrt(3.0)) / 2; // the filter's weight at offset 0
const double kTapFar = (1 - 1 / std::sqrt(3.0)) / 2;  // at offset +1

// Rounds `exact` to integers whose sum is `sum` (largest remainders take the difference), within
// [-limit, limit].
std::vector<int32_t> round_to_sum(const std::vector<double> &exact, int64_t sum, int32_t limit) {
    std::vector<int32_t> rounded(exact.size());
    int64_t rounded_sum = 0;
    for (size_t i = 0; i < exact.size(); i++) {
        rounded[i] = int32_t(std::lround(exact[i]));
        rounded_sum += rounded[i];
    }
    const int step = sum > rounded_sum ? 1 : -1;
    // The entries whose rounding went furthest against the needed direction come first.
    std::vector<size_t> order(exact.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) {
        return step * (exact[i] - rounded[i]) > step * (exact[j] - rounded[j]);
    });
    for (size_t k = 0; k < order.size() && rounded_sum != sum; k++) {
        int32_t &value = rounded[order[k]];
        if (value + step < -limit || value + step > limit) continue;
        value += step;
        rounded_sum += step;
    }
    return rounded;
}

} // namespace

void set_lattice_texton(AssetFields &fields) {
    const uint32_t width = fields.width + 2, height = fields.height + 2, channels = fields.channels;
    const int32_t limit = fields.bits == 8 ? 127 : 32767;
    // The texton's value at (column, row) of the lattice texton's window, shifted by one texel.
    auto texton_at = [&](uint32_t column, uint32_t row, uint32_t c) -> double {
        if (column == 0 || row == 0 || column > fields.width || row > fields.height) return 0;
        return fields.texton[((row - 1) * fields.width + column - 1) * channels + c];
    };
    const double taps[2] = {kTapNear, kTapFar};
    fields.lattice_width = width;
    fields.lattice_height = height;
    fields.lattice_texton.assign(size_t(width) * height * channels, 0);
    for (uint32_t c = 0; c < channels; c++) {
        std::vector<double> exact(size_t(width) * height, 0.0);
        int64_t sum = 0;
        for (size_t i = c; i < fields.texton.size(); i += channels) sum += fields.texton[i];
        for (uint32_t row = 0; row < height; row++)
            for (uint32_t column = 0; column < width; column++)
                for (uint32_t i = 0; i < 2; i++)
                    for (uint32_t j = 0; j < 2; j++)
                        if (column >= i && row >= j)
                            exact[row * width + column] +=
                                taps[i] * taps[j] * texton_at(column - i, row - j, c);
        const std::vector<int32_t> rounded = round_to_sum(exact, sum, limit);
        for (size_t i = 0; i < rounded.size(); i++) fields.lattice_texton[i * channels + c] = rounded[i];
    }
}

} // namespace dsn
