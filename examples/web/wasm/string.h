/* string.h - the four memory functions of the freestanding wasm32 build (examples/web/wasm/memory.cpp), for
   code built against the runtime there that includes <string.h> (the cross test's golden program). */
#ifndef DSN_WASM_STRING_H
#define DSN_WASM_STRING_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

void *memcpy(void *destination, const void *source, size_t size);
void *memmove(void *destination, const void *source, size_t size);
void *memset(void *destination, int value, size_t size);
int memcmp(const void *left, const void *right, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* DSN_WASM_STRING_H */
