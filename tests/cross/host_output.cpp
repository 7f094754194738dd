/* host_output.cpp - golden_write() for hosted targets (Linux, native or under qemu-user): stdout. */
#include <stdio.h>

#include "golden_output.h"

void golden_write(const char *text) { fputs(text, stdout); }
