/* golden_output.h - where the golden program's text goes: stdout on a host, semihosting on the MCU. */
#ifndef DSN_CROSS_GOLDEN_OUTPUT_H
#define DSN_CROSS_GOLDEN_OUTPUT_H

#ifdef __cplusplus
extern "C" {
#endif

/* Writes a NUL-terminated string as it is. */
void golden_write(const char *text);

#ifdef __cplusplus
}
#endif

#endif /* DSN_CROSS_GOLDEN_OUTPUT_H */
