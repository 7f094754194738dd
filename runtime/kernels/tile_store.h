/* runtime/kernels/tile_store.h - the strip path's output stores: a normalized strip row into the caller's
   fixed, float or 8-bit values, whole strips in the widest stores the instruction set has, partial strips 8
   pixels (one 128-bit lane) at a time, past the caches when the output is far larger than them: in
   16-byte streaming stores, or where the instruction set streams whole lines (DSN_SIMD_STREAM_LINES),
   rows staged then copied past them.
   Internal to tile_render.h.

   A normalized strip row arrives as 2 Channels vectors whose 128-bit lane j holds 4 pixels' interleaved
   values of pixels 8 j .. 8 j + 7 (the low four pixels' vectors first, then the high four's: 3 vectors
   each with 3 channels, 1 with 1); output_order (simd.h) puts a whole strip in output order. */
#ifndef DSN_TILE_STORE_H
#define DSN_TILE_STORE_H

#include "core/normalize_fixed.h"
#include "kernels/tile_strips.h"

namespace {

/* One output value, of the pixel-by-pixel path. */
inline void store_value(int32_t *out, int32_t value) { *out = value; }
inline void store_value(float *out, int32_t value) { *out = dsn_fixed_to_float(value); }
inline void store_value(uint8_t *out, int32_t value) { *out = dsn_fixed_to_u8(value); }

/* Stores `vectors` interleaved output vectors (4 values each) of which the first `values` are wanted;
   `stream`: put_4. */
inline void store_vectors(int32_t *out, const vector_128 *v, uint32_t vectors, uint32_t values, int stream) {
    if (values == 4 * vectors) {
#pragma GCC unroll 6
        for (uint32_t i = 0; i < vectors; i++) put_4(out + 4 * i, v[i], stream);
        return;
    }
    int32_t buffer[24];
    for (uint32_t i = 0; i < vectors; i++) store_4x32(buffer + 4 * i, v[i]);
    for (uint32_t i = 0; i < values; i++) out[i] = buffer[i];
}

inline void store_vectors(float *out, const vector_128 *v, uint32_t vectors, uint32_t values, int stream) {
    float buffer[24];
    float *dst = values == 4 * vectors ? out : buffer;
#pragma GCC unroll 6
    for (uint32_t i = 0; i < vectors; i++) put_4(dst + 4 * i, to_float_4(v[i]), stream);
    if (dst == buffer)
        for (uint32_t i = 0; i < values; i++) out[i] = buffer[i];
}

inline void store_vectors(uint8_t *out, const vector_128 *v, uint32_t vectors, uint32_t values, int) {
    /* Zeroed because gcc -Os cannot see that vectors is 2 or 6 (the stores below are free at -O2). */
    vector_128 words[3] = {zero_128(), zero_128(), zero_128()};
#pragma GCC unroll 3
    for (uint32_t i = 0; i < vectors; i += 2)
        words[i / 2] = pack_saturated_32x16(to_u8_range(v[i]), to_u8_range(v[i + 1]));
    vector_128 first = pack_saturated_unsigned_16x8(words[0], vectors > 2 ? words[1] : words[0]);
    vector_128 second =
        pack_saturated_unsigned_16x8(vectors > 2 ? words[2] : words[0], vectors > 2 ? words[2] : words[0]);
    if (values == 4 * vectors) { /* 24 bytes (3 channels) or 8 (1 channel) */
        if (vectors > 2) {
            store_16x8(out, first);
            store_low_8x8(out + 16, second);
        } else {
            store_low_8x8(out, first);
        }
        return;
    }
    uint8_t buffer[32];
    store_16x8(buffer, first);
    store_16x8(buffer + 16, second);
    for (uint32_t i = 0; i < values; i++) out[i] = buffer[i];
}

inline simd_vector output_vector(simd_vector fixed, int32_t *) { return fixed; }
inline simd_floats output_vector(simd_vector fixed, float *) { return to_output_floats(fixed); }

/* A vector of normalized values as the bits of the output's 32-bit values. */
inline simd_vector output_bits(simd_vector fixed, int32_t *) { return fixed; }
inline simd_vector output_bits(simd_vector fixed, float *) { return as_integers(to_output_floats(fixed)); }
inline void stream_4(int32_t *out, vector_128 bits) { put_4(out, bits, 1); }
inline void stream_4(float *out, vector_128 bits) { put_4(out, as_floats(bits), 1); }

/* A whole strip of fixed or float output in full-width stores, in output order. The streaming decision
   (16-byte alignment) is taken once per strip: every store of the strip has the same alignment. Streamed,
   the strip goes out in 16-byte stores, which need no output order: lane j of the vectors in turn. */
template <uint32_t Channels, typename Value>
inline int store_whole_strip(const simd_vector *values, Value *out, int stream) {
    const uint32_t values_per_vector = sizeof(simd_vector) / sizeof(int32_t);
    if (stream && (reinterpret_cast<uintptr_t>(out) & 15u) == 0) {
#pragma GCC unroll 4
        for (uint32_t part = 0; part < lane / 8; part++)
#pragma GCC unroll 6
            for (uint32_t i = 0; i < 2 * Channels; i++)
                stream_4(out + 8 * Channels * part + 4 * i, lane_128(output_bits(values[i], out), part));
        return 1;
    }
    simd_vector ordered[6];
    output_order<Channels>(values, ordered);
#pragma GCC unroll 6
    for (uint32_t m = 0; m < 2 * Channels; m++)
        put_vector(out + values_per_vector * m, output_vector(ordered[m], out));
    return 1;
}
/* 8-bit output of a whole strip, where the instruction set packs it in one go (else returns 0). */
template <uint32_t Channels>
inline int store_whole_strip(const simd_vector *values, uint8_t *out, int) {
    return store_whole_strip_u8<Channels>(values, out);
}

/* The first `pixels` pixels of a normalized strip row: whole strips as store_whole_strip can, else 8
   pixels (a 128-bit lane of each vector) at a time. */
template <uint32_t Channels, typename Value>
DSN_SIMD_INLINE void store_strip(const simd_vector *values, uint32_t pixels, Value *out, int stream) {
    const uint32_t vectors = 2 * Channels;
    if (pixels == lane && store_whole_strip<Channels>(values, out, stream)) return;
    for (uint32_t part = 0; part * 8 < pixels; part++) {
        vector_128 group[6];
        for (uint32_t i = 0; i < vectors; i++) group[i] = lane_128(values[i], part);
        const uint32_t rest = pixels - 8 * part;
        store_vectors(out + 8 * Channels * part, group, vectors, (rest < 8 ? rest : 8) * Channels, stream);
    }
}

#if DSN_SIMD_STREAM_LINES
/* `count` 32-bit output values of a row, normalized into `staged` (which agrees with out modulo 64 bytes),
   into `out`: the whole cache lines past the caches, 64 bytes at a time; the partial lines at either end,
   which the neighbouring rectangles share, in ordinary stores. */
template <typename Value>
inline void stream_row(const Value *staged, uint32_t count, Value *out) {
    const uint32_t line_values = 64 / sizeof(Value);
    const uint32_t to_line = uint32_t(-reinterpret_cast<uintptr_t>(out) & 63u) / sizeof(Value);
    const uint32_t head = to_line < count ? to_line : count;
    uint32_t i = 0;
    for (; i < head; i++) out[i] = staged[i];
    for (; i + line_values <= count; i += line_values) stream_line(out + i, staged + i);
    for (; i < count; i++) out[i] = staged[i];
}
#endif

} // namespace

#endif /* DSN_TILE_STORE_H */
