/* posix_missing.h - declarations that wasi-libc (Debian's 2022 snapshot) leaves out but the baker's file
   writer names (offline/asset_writer.cpp, which the page never calls): forced into the wasm32-wasi
   build of the baker with -include. posix_missing.cpp defines them as failing calls. */
#ifndef DSN_WEB_POSIX_MISSING_H
#define DSN_WEB_POSIX_MISSING_H

#include <sys/types.h>

#ifdef __cplusplus
extern "C" {
#endif

int mkstemp(char *pattern);
mode_t umask(mode_t mask);
int chmod(const char *path, mode_t mode);

#ifdef __cplusplus
}
#endif

#endif /* DSN_WEB_POSIX_MISSING_H */
