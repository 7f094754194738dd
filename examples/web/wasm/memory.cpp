/* memory.cpp - memcpy, memmove, memset and memcmp for the freestanding wasm32 build, which links no C
   library. The compiler calls memcpy and memset for struct copies and zeroing even in freestanding code,
   and the cross test's golden program calls memcpy itself. Built with -ffreestanding, so these loops stay
   loops (clang would otherwise turn them back into calls to the very functions they define). */
#include <stddef.h>

#include "string.h"

extern "C" {

void *memcpy(void *destination, const void *source, size_t size) {
    unsigned char *to = static_cast<unsigned char *>(destination);
    const unsigned char *from = static_cast<const unsigned char *>(source);
    for (size_t i = 0; i < size; i++) to[i] = from[i];
    return destination;
}

void *memmove(void *destination, const void *source, size_t size) {
    unsigned char *to = static_cast<unsigned char *>(destination);
    const unsigned char *from = static_cast<const unsigned char *>(source);
    if (to < from)
        for (size_t i = 0; i < size; i++) to[i] = from[i];
    else
        for (size_t i = size; i > 0; i--) to[i - 1] = from[i - 1];
    return destination;
}

void *memset(void *destination, int value, size_t size) {
    unsigned char *to = static_cast<unsigned char *>(destination);
    const unsigned char byte = static_cast<unsigned char>(value);
    for (size_t i = 0; i < size; i++) to[i] = byte;
    return destination;
}

int memcmp(const void *left, const void *right, size_t size) {
    const unsigned char *a = static_cast<const unsigned char *>(left);
    const unsigned char *b = static_cast<const unsigned char *>(right);
    for (size_t i = 0; i < size; i++)
        if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
    return 0;
}

} // extern "C"
