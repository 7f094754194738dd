// painted_stack.h - the stack depth of one call, measured by painting, for the benchmark programs that
// report what a call of the runtime needs (dsn.h documents those figures).
#ifndef DSN_BENCH_PAINTED_STACK_H
#define DSN_BENCH_PAINTED_STACK_H

#include <cstddef>

namespace bench {

// Fill the 256 KB below this frame (still inside the thread's stack), make the call, and find the deepest
// byte it changed.
template <typename Call>
__attribute__((noinline)) size_t painted_stack(Call call) {
    const size_t region_size = 1 << 18, guard = 128; // guard: this frame's own locals and spills
    volatile unsigned char *top = static_cast<unsigned char *>(__builtin_frame_address(0)) - guard;
    for (size_t i = 1; i <= region_size; i++) top[-std::ptrdiff_t(i)] = 0xA5;
    call();
    size_t deepest = region_size;
    while (deepest > 0 && top[-std::ptrdiff_t(deepest)] == 0xA5) deepest--;
    return deepest + guard; // an upper bound: includes the guard above the region
}

} // namespace bench

#endif // DSN_BENCH_PAINTED_STACK_H
