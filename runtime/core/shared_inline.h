/* runtime/core/shared_inline.h - how the helpers shared by the evaluators are compiled (DSN_SHARED,
   DSN_INLINE): inlined where speed matters, one out-of-line copy each in the small build. Internal to libdsn;
   not installed. */
#ifndef DSN_SHARED_INLINE_H
#define DSN_SHARED_INLINE_H

#include "dsn/dsn.h" /* DSN_SMALL_CODE */

/* The larger helpers are inlined for speed; the small build (DSN_SMALL_CODE, dsn.h) keeps one
   out-of-line copy of each instead (C++ inline functions: every link keeps a single copy). */
#if DSN_SMALL_CODE && defined(__clang__)
#define DSN_SHARED inline __attribute__((noinline))
#elif DSN_SMALL_CODE && defined(__GNUC__)
#define DSN_SHARED inline __attribute__((noinline, noclone))
#else
#define DSN_SHARED static inline
#endif

/* A small helper called several times in a row (the three normalizations of a lattice point's gradient),
   where GCC would keep the calls: inlined at each, but in the small build. */
#if !DSN_SMALL_CODE && defined(__GNUC__)
#define DSN_INLINE static inline __attribute__((always_inline))
#else
#define DSN_INLINE static inline
#endif

#endif /* DSN_SHARED_INLINE_H */
