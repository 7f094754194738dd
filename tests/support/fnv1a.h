// tests/support/fnv1a.h - 64-bit FNV-1a over little-endian bytes of integer outputs (golden tests).
#ifndef DSN_TEST_FNV1A_H
#define DSN_TEST_FNV1A_H

#include <cstddef>
#include <cstdint>

namespace dsn_test {

inline uint64_t fnv1a64_bytes(const unsigned char *bytes, size_t size, uint64_t hash = 0xCBF29CE484222325u) {
    for (size_t i = 0; i < size; i++) hash = (hash ^ bytes[i]) * 0x100000001B3u;
    return hash;
}

// Hash of int32 values, each fed as its 4 little-endian bytes whatever the host.
inline uint64_t fnv1a64_int32(const int32_t *values, size_t count) {
    uint64_t hash = 0xCBF29CE484222325u;
    for (size_t i = 0; i < count; i++) {
        uint32_t v = uint32_t(values[i]);
        unsigned char bytes[4] = {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
        hash = fnv1a64_bytes(bytes, 4, hash);
    }
    return hash;
}

} // namespace dsn_test

#endif
