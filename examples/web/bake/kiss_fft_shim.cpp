// kiss_fft_shim.cpp - the four functions of kissfft's C library that the baker calls (kiss_fft_alloc,
// kiss_fft, kiss_fftnd_alloc, kiss_fftnd), for the wasm32-wasi build of the baker: Debian packages the C
// library for the host only, but also kissfft.hh, the same mixed-radix algorithm as a header-only C++
// template, which this file wraps. A plan is one malloc'd block (the baker frees plans with free()):
// its kissfft objects are built in place and, being never destroyed, leak their twiddle tables, which
// is harmless in a module instantiated for one bake.
#include <complex>
#include <cstdlib>
#include <new>
#include <vector>

#include <kiss_fft.h>
#include <kiss_fftnd.h>
#include <kissfft.hh>

using Fft = kissfft<float>;
using Complex = std::complex<float>;

struct kiss_fft_state {
    Fft fft;
};

struct kiss_fftnd_state {
    int rows, columns;
    Fft row_fft, column_fft; // along a row (columns points), along a column (rows points)
};

extern "C" {

kiss_fft_cfg kiss_fft_alloc(int nfft, int inverse_fft, void *, size_t *) {
    void *block = std::malloc(sizeof(kiss_fft_state));
    if (block == nullptr || nfft <= 0) return static_cast<kiss_fft_cfg>(block);
    return new (block) kiss_fft_state{Fft(static_cast<size_t>(nfft), inverse_fft != 0)};
}

void kiss_fft(kiss_fft_cfg plan, const kiss_fft_cpx *in, kiss_fft_cpx *out) {
    plan->fft.transform(reinterpret_cast<const Complex *>(in), reinterpret_cast<Complex *>(out));
}

kiss_fftnd_cfg kiss_fftnd_alloc(const int *dims, int ndims, int inverse_fft, void *, size_t *) {
    if (ndims != 2 || dims[0] <= 0 || dims[1] <= 0) return nullptr; // the baker's transforms are 2-D
    void *block = std::malloc(sizeof(kiss_fftnd_state));
    if (block == nullptr) return nullptr;
    return new (block) kiss_fftnd_state{dims[0], dims[1], Fft(static_cast<size_t>(dims[1]), inverse_fft != 0),
                                        Fft(static_cast<size_t>(dims[0]), inverse_fft != 0)};
}

// Row-major rows x columns: every row, then every column (through a contiguous copy).
void kiss_fftnd(kiss_fftnd_cfg plan, const kiss_fft_cpx *in, kiss_fft_cpx *out) {
    const size_t rows = static_cast<size_t>(plan->rows), columns = static_cast<size_t>(plan->columns);
    const Complex *source = reinterpret_cast<const Complex *>(in);
    Complex *target = reinterpret_cast<Complex *>(out);
    std::vector<Complex> line(columns > rows ? columns : rows), transformed(line.size());
    for (size_t r = 0; r < rows; r++) {
        plan->row_fft.transform(source + r * columns, transformed.data());
        for (size_t c = 0; c < columns; c++) target[r * columns + c] = transformed[c];
    }
    for (size_t c = 0; c < columns; c++) {
        for (size_t r = 0; r < rows; r++) line[r] = target[r * columns + c];
        plan->column_fft.transform(line.data(), transformed.data());
        for (size_t r = 0; r < rows; r++) target[r * columns + c] = transformed[r];
    }
}

} // extern "C"
