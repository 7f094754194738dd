// quantize.cpp - per-channel quantization of a texton to 8 or 16 bits, and back.
#include "bake_internal.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dsn {
namespace {

const double kScaleOne = 1099511627776.0; // 2^40: scale_raw / 2^40 is the quantization step

} // namespace

QuantizedTexton quantize(const Texton &texton, int bits) {
    if (bits != 8 && bits != 16) throw std::invalid_argument("bits must be 8 or 16");
    QuantizedTexton quantized;
    quantized.bits = bits;
    const double limit = bits == 8 ? 127 : 32767;
    const size_t plane = texton.support.mask.size();
    const size_t channels = size_t(texton.channels);
    quantized.values.assign(plane * channels, 0);
    for (size_t c = 0; c < channels; c++) {
        double largest = 0;
        for (size_t i = 0; i < plane; i++)
            largest = std::max(largest, std::fabs(texton.values[c * plane + i]));
        // The stored raw scale, not the ideal one, is what the runtime multiplies by: round with it.
        const double raw = std::clamp(std::round(largest / limit * kScaleOne), 1.0, 4294967295.0);
        quantized.scale_raw[c] = uint32_t(raw);
        const double step = raw / kScaleOne;
        for (size_t i = 0; i < plane; i++)
            quantized.values[i * channels + c] =
                int32_t(std::clamp(std::round(texton.values[c * plane + i] / step), -limit, limit));
    }
    return quantized;
}

Texton dequantize(const QuantizedTexton &quantized, const Support &support, int channels) {
    Texton texton;
    texton.support = support;
    texton.channels = channels;
    const size_t plane = support.mask.size();
    texton.values.resize(plane * size_t(channels));
    for (size_t c = 0; c < size_t(channels); c++)
        for (size_t i = 0; i < plane; i++)
            texton.values[c * plane + i] = double(quantized.values[i * size_t(channels) + c]) *
                                           double(quantized.scale_raw[c]) / kScaleOne;
    return texton;
}

} // namespace dsn
