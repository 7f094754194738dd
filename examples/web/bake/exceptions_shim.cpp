// exceptions_shim.cpp - what a throw does in the wasm32-wasi baker. Debian's wasm32 libc++abi is built
// without exception support (no __cxa_allocate_exception, no __cxa_throw), and every error of the baker
// is a thrown std::exception (std::runtime_error or std::invalid_argument) that ends the bake. So a throw
// hands what() to the page (the import env.bake_error) and stops the module (unreachable): the page
// shows the message and drops the instance.
#include <cstdlib>
#include <cstring>
#include <exception>
#include <typeinfo>

extern "C" {

__attribute__((import_module("env"), import_name("bake_error"))) void bake_error(const char *text,
                                                                                 size_t size);

void *__cxa_allocate_exception(size_t size) noexcept { return std::malloc(size); }

[[noreturn]] void __cxa_throw(void *thrown, std::type_info *, void (*)(void *)) {
    // Every throw in the baker's code throws an object derived from std::exception, first base.
    const char *message = thrown ? static_cast<std::exception *>(thrown)->what() : "out of memory";
    bake_error(message, std::strlen(message));
    __builtin_trap();
}

} // extern "C"
