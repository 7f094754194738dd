// dft.cpp - full-size 2-D DFTs of images, built on kiss_fftnd (complex): the reference transforms.
#include "bake_internal.h"
#include "kiss_plan.h"

namespace dsn {

Spectrum forward_dft(const Image &image) {
    Spectrum spectrum;
    spectrum.width = image.width;
    spectrum.height = image.height;
    spectrum.channels = image.channels;
    const size_t plane = spectrum.plane_size();
    spectrum.values.resize(plane * size_t(image.channels));
    FftPlan2d plan = make_fft_plan_2d(image.width, image.height, false);
    std::vector<std::complex<float>> input(plane);
    for (int c = 0; c < image.channels; c++) {
        for (size_t i = 0; i < plane; i++) input[i] = float(image.values[size_t(c) * plane + i]);
        kiss_fftnd(plan.get(), as_kiss(input.data()), as_kiss(&spectrum.values[size_t(c) * plane]));
    }
    return spectrum;
}

Image inverse_dft(const Spectrum &spectrum) {
    Image image;
    image.width = spectrum.width;
    image.height = spectrum.height;
    image.channels = spectrum.channels;
    const size_t plane = spectrum.plane_size();
    image.values.resize(plane * size_t(spectrum.channels));
    FftPlan2d plan = make_fft_plan_2d(spectrum.width, spectrum.height, true);
    std::vector<std::complex<float>> output(plane);
    const double normalization = 1.0 / double(plane);
    for (int c = 0; c < spectrum.channels; c++) {
        kiss_fftnd(plan.get(), as_kiss(&spectrum.values[size_t(c) * plane]), as_kiss(output.data()));
        for (size_t i = 0; i < plane; i++)
            image.values[size_t(c) * plane + i] = output[i].real() * normalization;
    }
    return image;
}

} // namespace dsn
