// kiss_plan.h - owning handles for kissfft plans (internal to the offline library).
#ifndef DSN_OFFLINE_KISS_PLAN_H
#define DSN_OFFLINE_KISS_PLAN_H

#include <complex>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include <kiss_fft.h>
#include <kiss_fftnd.h>

namespace dsn {

struct KissFree {
    void operator()(void *plan) const { std::free(plan); }
};
using FftPlan = std::unique_ptr<kiss_fft_state, KissFree>;
using FftPlan2d = std::unique_ptr<kiss_fftnd_state, KissFree>;

// A 1-D complex plan of `size` points (any size: mixed radix).
inline FftPlan make_fft_plan(int size, bool inverse) {
    FftPlan plan(kiss_fft_alloc(size, inverse ? 1 : 0, nullptr, nullptr));
    if (!plan) throw std::runtime_error("out of memory for an FFT plan");
    return plan;
}

// A 2-D complex plan over a row-major height x width array.
inline FftPlan2d make_fft_plan_2d(int width, int height, bool inverse) {
    const int dims[2] = {height, width};
    FftPlan2d plan(kiss_fftnd_alloc(dims, 2, inverse ? 1 : 0, nullptr, nullptr));
    if (!plan) throw std::runtime_error("out of memory for an FFT plan");
    return plan;
}

// std::complex<float> is layout-compatible with kiss_fft_cpx {float r, i} (kiss_fft_scalar is float).
static_assert(sizeof(kiss_fft_cpx) == sizeof(std::complex<float>), "kissfft must be built for float");
inline kiss_fft_cpx *as_kiss(std::complex<float> *values) { return reinterpret_cast<kiss_fft_cpx *>(values); }
inline const kiss_fft_cpx *as_kiss(const std::complex<float> *values) {
    return reinterpret_cast<const kiss_fft_cpx *>(values);
}

} // namespace dsn

#endif // DSN_OFFLINE_KISS_PLAN_H
