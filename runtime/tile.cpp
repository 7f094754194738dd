/* runtime/tile.cpp - tile evaluation on the lattice: splats every impulse that reaches the tile into an
   integer accumulator (one contiguous add of width x channels values per texton row), then normalizes
   each pixel. The sums are the per-point sums (integer addition modulo 2^32 is order-free), so the bits
   equal the per-point path's. */
#include "noise_internal.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace {

/* A run of tile indices [offset, offset + length) along one axis whose coordinates are contiguous
   integers. Without a period the whole axis is one run on the torus. With a period the coordinate is
   read as int32 and reduced modulo P, so the run is cut where x0 + i passes from INT32_MAX to
   INT32_MIN (after that cut the reduced coordinates are contiguous again). */
typedef struct tile_run {
    uint32_t start, offset, length;
} tile_run;

uint32_t split_runs(uint32_t start, uint32_t length, uint32_t period, tile_run *runs) {
    uint32_t until_sign_flip = 0x80000000u - start;
    runs[0].start = start;
    runs[0].offset = 0;
    runs[0].length = length;
    if (period == 0 || until_sign_flip == 0 || until_sign_flip >= length) return 1;
    runs[0].length = until_sign_flip;
    runs[1].start = 0x80000000u;
    runs[1].offset = until_sign_flip;
    runs[1].length = length - until_sign_flip;
    return 2;
}

/* dst[i] += texton value i, for `count` interleaved values, modulo 2^32. This is the inner loop of the
   tile path; with SSE2 it runs 16 (8-bit) or 8 (16-bit) values per step (sign extension by unpacking a
   value with itself and shifting arithmetically, which is exact two's-complement in the hardware). */
template <uint32_t Bits>
inline void add_row(uint32_t *dst, const unsigned char *src, uint32_t count) {
    uint32_t i = 0;
#if defined(__SSE2__)
    if (Bits == 8) {
        for (; i + 16 <= count; i += 16) {
            __m128i bytes = _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(src + i)));
            __m128i low16 = _mm_srai_epi16(_mm_unpacklo_epi8(bytes, bytes), 8);
            __m128i high16 = _mm_srai_epi16(_mm_unpackhi_epi8(bytes, bytes), 8);
            __m128i *out = static_cast<__m128i *>(static_cast<void *>(dst + i));
            __m128i values[4] = {_mm_srai_epi32(_mm_unpacklo_epi16(low16, low16), 16),
                                 _mm_srai_epi32(_mm_unpackhi_epi16(low16, low16), 16),
                                 _mm_srai_epi32(_mm_unpacklo_epi16(high16, high16), 16),
                                 _mm_srai_epi32(_mm_unpackhi_epi16(high16, high16), 16)};
            for (int part = 0; part < 4; part++)
                _mm_storeu_si128(out + part, _mm_add_epi32(_mm_loadu_si128(out + part), values[part]));
        }
    } else {
        for (; i + 8 <= count; i += 8) {
            __m128i words =
                _mm_loadu_si128(static_cast<const __m128i *>(static_cast<const void *>(src + 2 * i)));
            __m128i *out = static_cast<__m128i *>(static_cast<void *>(dst + i));
            __m128i low = _mm_srai_epi32(_mm_unpacklo_epi16(words, words), 16);
            __m128i high = _mm_srai_epi32(_mm_unpackhi_epi16(words, words), 16);
            _mm_storeu_si128(out, _mm_add_epi32(_mm_loadu_si128(out), low));
            _mm_storeu_si128(out + 1, _mm_add_epi32(_mm_loadu_si128(out + 1), high));
        }
    }
#endif
    if (Bits == 8) {
        for (; i < count; i++) dst[i] += uint32_t(src[i] ^ 0x80u) - 0x80u;
    } else {
        for (; i < count; i++) dst[i] += (uint32_t(src[2 * i] | (src[2 * i + 1] << 8)) ^ 0x8000u) - 0x8000u;
    }
}

typedef struct splat_target {
    uint32_t *accumulator;
    uint32_t row_stride; /* tile width * channels */
} splat_target;

/* One rectangle of the tile where both axes are single runs. */
template <uint32_t Bits>
void splat_region(const dsn_noise *noise, const tile_run *run_x, const tile_run *run_y,
                  const splat_target *target) {
    const dsn_asset *asset = &noise->asset;
    const uint32_t shift = noise->cell_shift, channels = asset->channels;
    const uint32_t texton_stride = asset->width * channels * (Bits / 8);
    dsn_axis axis_x, axis_y;
    dsn_axis_init(&axis_x, run_x->start, run_x->length, noise->radius[0], shift, noise->period[0]);
    dsn_axis_init(&axis_y, run_y->start, run_y->length, noise->radius[1], shift, noise->period[1]);
    for (uint32_t span_index_y = 0; span_index_y < axis_y.span_count; span_index_y++) {
        dsn_span span_y = dsn_axis_span(&axis_y, span_index_y);
        for (uint32_t i = 0; i < span_y.cell_count; i++) {
            uint32_t cell_y = dsn_span_cell(&span_y, i, shift), row_key = dsn_row_key(noise, cell_y);
            for (uint32_t span_index_x = 0; span_index_x < axis_x.span_count; span_index_x++) {
                dsn_span span_x = dsn_axis_span(&axis_x, span_index_x);
                for (uint32_t j = 0; j < span_x.cell_count; j++) {
                    uint32_t cell_x = dsn_span_cell(&span_x, j, shift);
                    uint32_t key = dsn_cell_key_in_row(noise, cell_x, row_key);
                    uint32_t count = dsn_cell_impulse_count(noise, key);
                    for (uint32_t k = 0; k < count; k++) {
                        uint32_t hash = dsn_impulse_hash(noise, key, k);
                        uint32_t x = (cell_x << shift) + dsn_impulse_offset(dsn_impulse_bits_x(hash), shift);
                        uint32_t y = (cell_y << shift) + dsn_impulse_offset(dsn_impulse_bits_y(hash), shift);
                        dsn_reach reach_x, reach_y;
                        if (x > span_x.last_position || y > span_y.last_position ||
                            !dsn_reach_window(span_x.base - x, run_x->length, asset->width, &reach_x) ||
                            !dsn_reach_window(span_y.base - y, run_y->length, asset->height, &reach_y))
                            continue;
                        uint32_t *dst = target->accumulator +
                                        (run_y->offset + reach_y.first_index) * target->row_stride +
                                        (run_x->offset + reach_x.first_index) * channels;
                        const unsigned char *src = asset->texton + reach_y.first_texton * texton_stride +
                                                   reach_x.first_texton * channels * (Bits / 8);
                        for (uint32_t row = 0; row < reach_y.count; row++)
                            add_row<Bits>(dst + row * target->row_stride, src + row * texton_stride,
                                          reach_x.count * channels);
                    }
                }
            }
        }
    }
}

/* Largest tile: sides up to DSN_TILE_MAX_SIDE and width * height * channels 32-bit values addressable. */
int tile_values(const dsn_noise *noise, uint32_t width, uint32_t height, size_t *values) {
    if (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE)
        return DSN_ERR_TILE_SIZE;
    uint64_t count = uint64_t(width) * height * noise->asset.channels; /* < 2^34 */
    if (count > (~size_t(0) - 8) / sizeof(uint32_t)) return DSN_ERR_TILE_SIZE;
    *values = size_t(count);
    return DSN_OK;
}

void accumulate_tile(const dsn_noise *noise, uint32_t x0, uint32_t y0, uint32_t width, uint32_t height,
                     uint32_t *accumulator, size_t values) {
    for (size_t i = 0; i < values; i++) accumulator[i] = 0;
    tile_run runs_x[2], runs_y[2];
    uint32_t run_count_x = split_runs(x0, width, noise->period[0], runs_x);
    uint32_t run_count_y = split_runs(y0, height, noise->period[1], runs_y);
    splat_target target = {accumulator, width * noise->asset.channels};
    for (uint32_t ry = 0; ry < run_count_y; ry++)
        for (uint32_t rx = 0; rx < run_count_x; rx++)
            noise->asset.bits == 8 ? splat_region<8>(noise, &runs_x[rx], &runs_y[ry], &target)
                                   : splat_region<16>(noise, &runs_x[rx], &runs_y[ry], &target);
}

/* The scratch accumulator: the caller's bytes, aligned up to 4. */
uint32_t *scratch_accumulator(void *scratch, size_t scratch_size, size_t values) {
    if (scratch == 0) return 0;
    size_t misalignment = reinterpret_cast<uintptr_t>(scratch) % sizeof(uint32_t);
    size_t skip = misalignment ? sizeof(uint32_t) - misalignment : 0;
    if (scratch_size < skip || (scratch_size - skip) / sizeof(uint32_t) < values) return 0;
    return static_cast<uint32_t *>(static_cast<void *>(static_cast<unsigned char *>(scratch) + skip));
}

int check_noise(const dsn_noise *noise, const void *out) {
    if (noise == 0 || out == 0) return DSN_ERR_NULL;
    return noise->asset.texton != 0 ? DSN_OK : DSN_ERR_ARGUMENT;
}

/* Tile into a scratch accumulator, then convert each pixel with `store`. */
template <typename Value, typename Store>
int tile_converted(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                   Value *out, void *scratch, size_t scratch_size, Store store) {
    size_t values = 0;
    int err = check_noise(noise, out);
    if (err == DSN_OK) err = tile_values(noise, width, height, &values);
    if (err != DSN_OK) return err;
    uint32_t *accumulator = scratch_accumulator(scratch, scratch_size, values);
    if (accumulator == 0) return DSN_ERR_SCRATCH;
    accumulate_tile(noise, uint32_t(x0), uint32_t(y0), width, height, accumulator, values);
    const uint32_t channels = noise->asset.channels;
    for (size_t i = 0; i < values; i += channels) {
        int32_t fixed[3];
        dsn_normalize(noise, accumulator + i, fixed);
        for (uint32_t c = 0; c < channels; c++) out[i + c] = store(fixed[c]);
    }
    return DSN_OK;
}

} // namespace

extern "C" size_t dsn_tile_scratch_size(const dsn_noise *noise, uint32_t width, uint32_t height) {
    size_t values = 0;
    if (check_noise(noise, noise) != DSN_OK || tile_values(noise, width, height, &values) != DSN_OK) return 0;
    return values * sizeof(uint32_t) + sizeof(uint32_t) - 1;
}

extern "C" int dsn_tile_fixed(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                              int32_t *out, void *scratch, size_t scratch_size) {
    (void)scratch;
    (void)scratch_size;
    size_t values = 0;
    int err = check_noise(noise, out);
    if (err == DSN_OK) err = tile_values(noise, width, height, &values);
    if (err != DSN_OK) return err;
    /* The output itself is the accumulator (uint32 may alias int32); each pixel's sums are copied out
       before its values are written over them. */
    uint32_t *accumulator = static_cast<uint32_t *>(static_cast<void *>(out));
    accumulate_tile(noise, uint32_t(x0), uint32_t(y0), width, height, accumulator, values);
    const uint32_t channels = noise->asset.channels;
    for (size_t i = 0; i < values; i += channels) {
        uint32_t sums[3] = {accumulator[i], channels == 3 ? accumulator[i + 1] : 0u,
                            channels == 3 ? accumulator[i + 2] : 0u};
        dsn_normalize(noise, sums, out + i);
    }
    return DSN_OK;
}

extern "C" int dsn_tile_float(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                              float *out, void *scratch, size_t scratch_size) {
    return tile_converted(noise, x0, y0, width, height, out, scratch, scratch_size, dsn_fixed_to_float);
}

extern "C" int dsn_tile_u8(const dsn_noise *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                           uint8_t *out, void *scratch, size_t scratch_size) {
    return tile_converted(noise, x0, y0, width, height, out, scratch, scratch_size, dsn_fixed_to_u8);
}
