/* runtime/point.cpp - per-point evaluation on the lattice: sums the texton values of every impulse
   whose window holds the point, then normalizes; plus the float and 8-bit conversions. */
#include "noise_internal.h"

namespace {

/* Adds texton entry `index` (channels interleaved) of every channel to sums, modulo 2^32. Values are
   decoded without implementation-defined conversions: (b ^ 0x80) - 128 is the two's-complement byte. */
template <uint32_t Channels, uint32_t Bits>
inline void add_texton_entry(const unsigned char *texton, uint32_t index, uint32_t *sums) {
    for (uint32_t c = 0; c < Channels; c++) {
        uint32_t value;
        if (Bits == 8) {
            value = uint32_t(texton[index * Channels + c] ^ 0x80u) - 0x80u;
        } else {
            const unsigned char *bytes = texton + 2 * (index * Channels + c);
            value = (uint32_t(bytes[0] | (bytes[1] << 8)) ^ 0x8000u) - 0x8000u;
        }
        sums[c] += value;
    }
}

/* Impulses of one cell that reach the point (about half of those examined, for the usual texton).
   A branch-free variant (masked adds of entry 0 for misses) measured no faster here. */
template <uint32_t Channels, uint32_t Bits>
inline void add_cell(const dsn_noise *noise, uint32_t key, const dsn_span *span_x, uint32_t origin_x,
                     const dsn_span *span_y, uint32_t origin_y, uint32_t *sums) {
    /* Locals, not loads through the pointers: stores to sums could alias them otherwise. */
    const uint32_t shift = noise->cell_shift, width = noise->asset.width, height = noise->asset.height;
    const uint32_t base_x = span_x->base, base_y = span_y->base;
    const uint32_t last_x = span_x->last_position, last_y = span_y->last_position;
    const unsigned char *texton = noise->asset.texton;
    const uint32_t count = dsn_cell_impulse_count(noise, key);
    uint32_t cell_sums[Channels];
    for (uint32_t c = 0; c < Channels; c++) cell_sums[c] = 0;
    for (uint32_t k = 0; k < count; k++) {
        uint32_t hash = dsn_impulse_hash(noise, key, k);
        uint32_t position_x = origin_x + dsn_impulse_offset(dsn_impulse_bits_x(hash), shift);
        uint32_t position_y = origin_y + dsn_impulse_offset(dsn_impulse_bits_y(hash), shift);
        uint32_t column = base_x - position_x, row = base_y - position_y;
        uint32_t hit = uint32_t(column < width) & uint32_t(row < height) & uint32_t(position_x <= last_x) &
                       uint32_t(position_y <= last_y);
        if (hit) add_texton_entry<Channels, Bits>(texton, row * width + column, cell_sums);
    }
    for (uint32_t c = 0; c < Channels; c++) sums[c] += cell_sums[c];
}

template <uint32_t Channels, uint32_t Bits>
void accumulate_point(const dsn_noise *noise, uint32_t x, uint32_t y, uint32_t *sums) {
    const uint32_t shift = noise->cell_shift;
    dsn_axis axis_x, axis_y;
    dsn_axis_init(&axis_x, x, 1, noise->radius[0], shift, noise->period[0]);
    dsn_axis_init(&axis_y, y, 1, noise->radius[1], shift, noise->period[1]);
    for (uint32_t span_index_y = 0; span_index_y < axis_y.span_count; span_index_y++) {
        dsn_span span_y = dsn_axis_span(&axis_y, span_index_y);
        for (uint32_t i = 0; i < span_y.cell_count; i++) {
            uint32_t cell_y = dsn_span_cell(&span_y, i, shift), row_key = dsn_row_key(noise, cell_y);
            for (uint32_t span_index_x = 0; span_index_x < axis_x.span_count; span_index_x++) {
                dsn_span span_x = dsn_axis_span(&axis_x, span_index_x);
                for (uint32_t j = 0; j < span_x.cell_count; j++) {
                    uint32_t cell_x = dsn_span_cell(&span_x, j, shift);
                    add_cell<Channels, Bits>(noise, dsn_cell_key_in_row(noise, cell_x, row_key), &span_x,
                                             cell_x << shift, &span_y, cell_y << shift, sums);
                }
            }
        }
    }
}

void accumulate(const dsn_noise *noise, uint32_t x, uint32_t y, uint32_t *sums) {
    sums[0] = sums[1] = sums[2] = 0;
    if (noise->asset.channels == 3)
        noise->asset.bits == 8 ? accumulate_point<3, 8>(noise, x, y, sums)
                               : accumulate_point<3, 16>(noise, x, y, sums);
    else
        noise->asset.bits == 8 ? accumulate_point<1, 8>(noise, x, y, sums)
                               : accumulate_point<1, 16>(noise, x, y, sums);
}

/* A noise that dsn_noise_init did not fill (zeroed on failure) has no texton and evaluates nothing. */
int usable(const dsn_noise *noise, const void *out) {
    return noise != 0 && out != 0 && noise->asset.texton != 0;
}

} // namespace

extern "C" void dsn_eval_fixed(const dsn_noise *noise, int32_t x, int32_t y, int32_t *out) {
    if (!usable(noise, out)) return;
    uint32_t sums[3];
    accumulate(noise, uint32_t(x), uint32_t(y), sums);
    dsn_normalize(noise, sums, out);
}

extern "C" float dsn_fixed_to_float(int32_t value) {
    /* One rounding (int32 -> float), then an exact power-of-two scaling: the same on every FPU. */
    return float(value) * (1.0f / 65536.0f);
}

extern "C" uint8_t dsn_fixed_to_u8(int32_t value) {
    if (value <= 0) return 0;
    if (value >= DSN_ONE) return 255;
    return uint8_t((uint32_t(value) * 255u + 32768u) >> 16);
}

extern "C" void dsn_eval_float(const dsn_noise *noise, int32_t x, int32_t y, float *out) {
    int32_t fixed[3];
    if (!usable(noise, out)) return;
    dsn_eval_fixed(noise, x, y, fixed);
    for (uint32_t c = 0; c < noise->asset.channels; c++) out[c] = dsn_fixed_to_float(fixed[c]);
}

extern "C" void dsn_eval_u8(const dsn_noise *noise, int32_t x, int32_t y, uint8_t *out) {
    int32_t fixed[3];
    if (!usable(noise, out)) return;
    dsn_eval_fixed(noise, x, y, fixed);
    for (uint32_t c = 0; c < noise->asset.channels; c++) out[c] = dsn_fixed_to_u8(fixed[c]);
}
