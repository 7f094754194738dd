// dft.cpp - full-size 2-D DFTs of real images and their inverse, as real transforms built from 1-D
// complex kiss_fft: two real rows share one complex row transform (packed as a + i b), and only the
// half spectrum (xi1 = 0..M/2) goes through the column transforms; the other half is its mirror
// (the spectrum of a real image is Hermitian). kiss_fftndr (the package's 2-D real transform) is not
// used: it crashes on 2-D sizes from 64 x 64. Row pairs and columns are split among the cores
// (parallel.h); each is transformed alone, so the result does not depend on the number of threads.
#include "bake_internal.h"
#include "kiss_plan.h"
#include "parallel.h"

#include <algorithm>

namespace dsn {
namespace {

using Complex = std::complex<float>;

// Forward DFT of one real plane (row-major, width x height) into the full spectrum plane `output`.
// Row pairs that are zero (a texton on a torus is zero on most rows) are not transformed.
void forward_plane(const double *input, int width, int height, const FftPlan &row_plan,
                   const FftPlan &column_plan, std::vector<Complex> &columns, Complex *output) {
    const size_t half = size_t(width) / 2 + 1, w = size_t(width), h = size_t(height);
    const size_t pairs = (h + 1) / 2;
    // Rows, written column-major: columns[k * height + y] is frequency k of row y.
    parallel_ranges(pairs, items_per_thread(w), [&](size_t first, size_t last) {
        std::vector<Complex> row_in(w), row_out(w);
        for (size_t pair = first; pair < last; pair++) {
            const size_t a = 2 * pair, b = a + 1;
            const double *row_a = input + a * w, *row_b = b < h ? input + b * w : nullptr;
            bool zero = true;
            for (size_t x = 0; x < w; x++) {
                row_in[x] = Complex(float(row_a[x]), row_b ? float(row_b[x]) : 0.0f);
                zero = zero && row_a[x] == 0 && (!row_b || row_b[x] == 0);
            }
            if (zero) {
                for (size_t k = 0; k < half; k++) {
                    columns[k * h + a] = 0;
                    if (row_b) columns[k * h + b] = 0;
                }
                continue;
            }
            kiss_fft(row_plan.get(), as_kiss(row_in.data()), as_kiss(row_out.data()));
            for (size_t k = 0; k < half; k++) {
                const Complex z = row_out[k], mirror = std::conj(row_out[(w - k) % w]);
                columns[k * h + a] = (z + mirror) * 0.5f;
                if (row_b) {
                    const Complex difference = z - mirror; // = 2i B
                    columns[k * h + b] = Complex(difference.imag() * 0.5f, -difference.real() * 0.5f);
                }
            }
        }
    });
    parallel_ranges(half, items_per_thread(h), [&](size_t first, size_t last) {
        std::vector<Complex> column_out(h);
        for (size_t k = first; k < last; k++) {
            kiss_fft(column_plan.get(), as_kiss(&columns[k * h]), as_kiss(column_out.data()));
            std::copy(column_out.begin(), column_out.end(), columns.begin() + std::ptrdiff_t(k * h));
        }
    });
    // The full plane: the half read back, the other half its mirror X(-xi) = conj X(xi).
    parallel_ranges(h, items_per_thread(w), [&](size_t first, size_t last) {
        for (size_t xi2 = first; xi2 < last; xi2++) {
            Complex *row = output + xi2 * w;
            const size_t mirror_row = (h - xi2) % h;
            for (size_t k = 0; k < half; k++) row[k] = columns[k * h + xi2];
            for (size_t k = half; k < w; k++) row[k] = std::conj(columns[(w - k) * h + mirror_row]);
        }
    });
}

// Real part of the inverse DFT (unnormalized) of one spectrum plane: the inverse of its Hermitian part
// (X(xi) + conj X(-xi)) / 2, which is real. Writes width x height values times `scale` to `output`.
void inverse_plane(const Complex *input, int width, int height, const FftPlan &row_plan,
                   const FftPlan &column_plan, std::vector<Complex> &columns, double scale, double *output) {
    const size_t half = size_t(width) / 2 + 1, w = size_t(width), h = size_t(height);
    parallel_ranges(half, items_per_thread(h), [&](size_t first, size_t last) {
        std::vector<Complex> column_in(h);
        for (size_t k = first; k < last; k++) {
            const size_t mirror_column = (w - k) % w;
            for (size_t xi2 = 0; xi2 < h; xi2++)
                column_in[xi2] =
                    (input[xi2 * w + k] + std::conj(input[((h - xi2) % h) * w + mirror_column])) * 0.5f;
            kiss_fft(column_plan.get(), as_kiss(column_in.data()), as_kiss(&columns[k * h]));
        }
    });
    const size_t pairs = (h + 1) / 2;
    parallel_ranges(pairs, items_per_thread(w), [&](size_t first, size_t last) {
        std::vector<Complex> row_in(w), row_out(w);
        for (size_t pair = first; pair < last; pair++) {
            const size_t a = 2 * pair, b = a + 1;
            const bool second = b < h;
            // row_in = A + i B over the full row, A and B the Hermitian spectra of rows a and b.
            for (size_t k = 0; k < w; k++) {
                const bool upper = k >= half;
                const size_t source = upper ? w - k : k;
                Complex first_value = columns[source * h + a],
                        second_value = second ? columns[source * h + b] : Complex(0);
                if (upper) {
                    first_value = std::conj(first_value);
                    second_value = std::conj(second_value);
                } else if (k == 0 || (w % 2 == 0 && k == half - 1)) {
                    first_value = first_value.real(); // self-conjugate frequencies are real
                    second_value = second_value.real();
                }
                row_in[k] = Complex(first_value.real() - second_value.imag(),
                                    first_value.imag() + second_value.real());
            }
            kiss_fft(row_plan.get(), as_kiss(row_in.data()), as_kiss(row_out.data()));
            for (size_t x = 0; x < w; x++) {
                output[a * w + x] = double(row_out[x].real()) * scale;
                if (second) output[b * w + x] = double(row_out[x].imag()) * scale;
            }
        }
    });
}

} // namespace

Spectrum forward_dft(const Image &image) {
    Spectrum spectrum;
    spectrum.width = image.width;
    spectrum.height = image.height;
    spectrum.channels = image.channels;
    const size_t plane = spectrum.plane_size();
    spectrum.values.resize(plane * size_t(image.channels));
    const FftPlan row_plan = make_fft_plan(image.width, false),
                  column_plan = make_fft_plan(image.height, false);
    std::vector<Complex> columns((size_t(image.width) / 2 + 1) * size_t(image.height));
    for (int c = 0; c < image.channels; c++)
        forward_plane(&image.values[size_t(c) * plane], image.width, image.height, row_plan, column_plan,
                      columns, &spectrum.values[size_t(c) * plane]);
    return spectrum;
}

Image inverse_dft(const Spectrum &spectrum) {
    Image image;
    image.width = spectrum.width;
    image.height = spectrum.height;
    image.channels = spectrum.channels;
    const size_t plane = spectrum.plane_size();
    image.values.resize(plane * size_t(spectrum.channels));
    const FftPlan row_plan = make_fft_plan(spectrum.width, true),
                  column_plan = make_fft_plan(spectrum.height, true);
    std::vector<Complex> columns((size_t(spectrum.width) / 2 + 1) * size_t(spectrum.height));
    for (int c = 0; c < spectrum.channels; c++)
        inverse_plane(&spectrum.values[size_t(c) * plane], spectrum.width, spectrum.height, row_plan,
                      column_plan, columns, 1.0 / double(plane), &image.values[size_t(c) * plane]);
    return image;
}

} // namespace dsn
