/* wasm_output.cpp - golden_write() for the freestanding wasm32 target: hands each string to the host
   (tests/cross/run-wasm.mjs under Node), which writes it to stdout. */
#include <stddef.h>

#include "golden_output.h"

extern "C" {
__attribute__((import_module("golden"), import_name("write"))) void golden_host_write(const char *text,
                                                                                      size_t size);
}

void golden_write(const char *text) {
    size_t size = 0;
    while (text[size] != '\0') size++;
    golden_host_write(text, size);
}
