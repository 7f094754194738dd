/* runtime/simd/simd.h - the one place that picks the vector operations of a translation unit: the ops header
   (simd_sse2.h, simd_avx2.h or simd_avx512.h, each defining the same names) of the widest instruction
   set the file is compiled for; the operations of a width that several share are in simd_128.h (all of
   them) and simd_256.h (AVX2 and AVX-512). DSN_SIMD is 1 when there is one, 0 on targets without SSE2 (which
   then take the 32-bit tile path). */
#ifndef DSN_SIMD_H
#define DSN_SIMD_H

#if defined(__AVX512F__) && defined(__AVX512BW__)
#include "simd/simd_avx512.h"
#define DSN_SIMD 1
#elif defined(__AVX2__)
#include "simd/simd_avx2.h"
#define DSN_SIMD 1
#elif defined(__SSE2__)
#include "simd/simd_sse2.h"
#define DSN_SIMD 1
#else
#define DSN_SIMD 0
#endif
/* 1 where the ops header streams whole rows in cache lines (stream_line), else strips stream their own
   16-byte stores. */
#ifndef DSN_SIMD_STREAM_LINES
#define DSN_SIMD_STREAM_LINES 0
#endif
/* 1 where the ops header sums two rows of a channel from one load of a paired plane (add_pair, then
   finish_pair): then every plane of the strips' texton is paired. */
#ifndef DSN_SIMD_PAIRED_ROWS
#define DSN_SIMD_PAIRED_ROWS 0
#endif

#endif /* DSN_SIMD_H */
