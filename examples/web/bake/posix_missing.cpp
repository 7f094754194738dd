// posix_missing.cpp - posix_missing.h's functions for the wasm32-wasi baker: the page bakes in memory
// and writes no file, so each fails as an unsupported call would (errno ENOSYS).
#include <cerrno>

#include "posix_missing.h"

extern "C" {

int mkstemp(char *) {
    errno = ENOSYS;
    return -1;
}

mode_t umask(mode_t) { return 022; }

int chmod(const char *, mode_t) {
    errno = ENOSYS;
    return -1;
}

} // extern "C"
