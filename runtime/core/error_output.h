/* runtime/core/error_output.h - what an evaluator leaves in its output when it returns an error: zeros, over
   exactly what the caller said the output holds, so that no output is ever left undefined (dsn.h, "What
   it guarantees"). Internal to libdsn; not installed. */
#ifndef DSN_ERROR_OUTPUT_H
#define DSN_ERROR_OUTPUT_H

#include <stddef.h>
#include <stdint.h>

#include "core/normalize_fixed.h"
#include "core/shared_inline.h"

/* A call's error `err`, returned after zeroing the `points` points of `kind` output at `out` (nothing for
   a null `out`): each point the noise's channels or, for a noise that has none (null, never configured,
   failed init), the one value that every caller's array holds. A tile refused for its size
   (DSN_ERR_TILE_SIZE) is left as it is: its size is not one the call may write. All-zero bytes are 0 as
   int32, float and uint8 alike: one memset (which compilers emit for such loops anyway). */
DSN_SHARED int dsn_output_error(int err, const dsn_noise_state *noise, void *out, dsn_output_kind kind,
                                size_t points) {
    const size_t channels = dsn_values_per_point(noise);
    if (err != DSN_OK && err != DSN_ERR_TILE_SIZE && out != 0)
        __builtin_memset(out, 0, points * channels * (kind == dsn_output_u8 ? 1u : 4u));
    return err;
}

#endif /* DSN_ERROR_OUTPUT_H */
