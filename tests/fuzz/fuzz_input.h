// fuzz_input.h - reads fuzzer bytes as a stream of integers (zeros once the bytes run out), and stops a
// fuzz run with a trap when an invariant breaks.
#ifndef DSN_FUZZ_INPUT_H
#define DSN_FUZZ_INPUT_H

#include <cstddef>
#include <cstdint>

struct FuzzInput {
    const uint8_t *data;
    size_t size;
    size_t position = 0;

    FuzzInput(const uint8_t *bytes, size_t count) : data(bytes), size(count) {}
    uint32_t byte() { return position < size ? data[position++] : 0u; }
    uint32_t u32() {
        uint32_t value = 0;
        for (int i = 0; i < 4; i++) value |= byte() << (8 * i);
        return value;
    }
    int32_t i32() { return int32_t(u32()); }
};

// A broken invariant is a finding: stop here so libFuzzer saves the input.
inline void fuzz_require(bool condition) {
    if (!condition) __builtin_trap();
}

#endif // DSN_FUZZ_INPUT_H
