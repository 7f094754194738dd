/* runtime/tile.cpp - the tile API: argument checks, the caller's scratch, and the choice of the tile
   code (tile_render.h) this CPU runs: on x86-64 the AVX-512 copy (tile_avx512.cpp) or the AVX2 copy
   (tile_avx2.cpp) when init found them, else the copy built here. All give the same bits as the
   per-point path. */
#include "tile_dispatch.h"
#include "tile_render.h"

namespace {

/* Checks the arguments every tile call shares and counts the tile's values. Largest tile: sides up to
   DSN_TILE_MAX_SIDE and width * height * channels 32-bit values addressable. */
int tile_values(const dsn_noise_state *noise, const void *out, uint32_t width, uint32_t height,
                size_t *values) {
    if (noise == 0 || out == 0) return DSN_ERR_NULL;
    if (noise->asset.texton == 0) return DSN_ERR_ARGUMENT;
    if (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE)
        return DSN_ERR_TILE_SIZE;
    uint64_t count = uint64_t(width) * height * noise->asset.channels; /* < 2^34 */
    if (count > (~size_t(0) - 8) / sizeof(uint32_t)) return DSN_ERR_TILE_SIZE;
    *values = size_t(count);
    return DSN_OK;
}

/* The tile, by the copy of the tile code that init chose for this CPU. */
void render_dispatched(const dsn_noise_state *noise, uint32_t x0, uint32_t y0, uint32_t width,
                       uint32_t height, void *out, dsn_output_kind kind, uint32_t *accumulator) {
#if DSN_TILE_AVX2_DISPATCH
    if (noise->tile_kernel == DSN_TILE_KERNEL_AVX512) {
        dsn_internal_render_tile_avx512(noise, x0, y0, width, height, out, kind, accumulator);
        return;
    }
    if (noise->tile_kernel == DSN_TILE_KERNEL_AVX2) {
        dsn_internal_render_tile_avx2(noise, x0, y0, width, height, out, kind, accumulator);
        return;
    }
#endif
    render_tile(noise, x0, y0, width, height, out, kind, accumulator);
}

/* The scratch accumulator: the caller's bytes, aligned up to 4. */
uint32_t *scratch_accumulator(void *scratch, size_t scratch_size, size_t values) {
    if (scratch == 0) return 0;
    size_t misalignment = reinterpret_cast<uintptr_t>(scratch) % sizeof(uint32_t);
    size_t skip = misalignment ? sizeof(uint32_t) - misalignment : 0;
    if (scratch_size < skip || (scratch_size - skip) / sizeof(uint32_t) < values) return 0;
    return static_cast<uint32_t *>(static_cast<void *>(static_cast<unsigned char *>(scratch) + skip));
}

/* A tile of `kind` values. The 32-bit sums of the fallback go to the scratch, or to the output itself for
   fixed output (uint32 may alias int32), which needs no scratch. */
int render_checked(const dsn_noise_state *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                   void *out, dsn_output_kind kind, void *scratch, size_t scratch_size) {
    size_t values = 0;
    const int err = tile_values(noise, out, width, height, &values);
    if (err != DSN_OK) return err;
    uint32_t *accumulator = kind == dsn_output_fixed ? static_cast<uint32_t *>(out)
                                                     : scratch_accumulator(scratch, scratch_size, values);
    if (accumulator == 0) return DSN_ERR_SCRATCH;
    render_dispatched(noise, uint32_t(x0), uint32_t(y0), width, height, out, kind, accumulator);
    return DSN_OK;
}

} // namespace

extern "C" size_t dsn_lattice_tile_scratch_size(const dsn_noise *handle, uint32_t width, uint32_t height) {
    const dsn_noise_state *noise = dsn_state(handle);
    size_t values = 0;
    if (tile_values(noise, noise, width, height, &values) != DSN_OK) return 0;
    return values * sizeof(uint32_t) + sizeof(uint32_t) - 1;
}

extern "C" int dsn_lattice_tile_fixed(const dsn_noise *handle, int32_t x0, int32_t y0, uint32_t width,
                                      uint32_t height, int32_t *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return render_checked(noise, x0, y0, width, height, out, dsn_output_fixed, scratch, scratch_size);
}

extern "C" int dsn_lattice_tile_float(const dsn_noise *handle, int32_t x0, int32_t y0, uint32_t width,
                                      uint32_t height, float *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return render_checked(noise, x0, y0, width, height, out, dsn_output_float, scratch, scratch_size);
}

extern "C" int dsn_lattice_tile_u8(const dsn_noise *handle, int32_t x0, int32_t y0, uint32_t width,
                                   uint32_t height, uint8_t *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return render_checked(noise, x0, y0, width, height, out, dsn_output_u8, scratch, scratch_size);
}

#if DSN_TILE_AVX2_DISPATCH
#include <cpuid.h>

/* AVX2 needs the CPU's feature bit (CPUID leaf 7, EBX bit 5) and an OS that saves the YMM registers
   (CPUID leaf 1: AVX and OSXSAVE; XCR0 bits 1 and 2). AVX-512 F and BW need EBX bits 16 and 30 and the
   opmask and ZMM registers saved too (XCR0 bits 5 to 7). This file is built without -mavx2, so the check
   itself uses no AVX instruction. */
uint32_t dsn_internal_tile_kernel(void) {
    unsigned int eax = 0, ebx = 0, ecx = 0, edx = 0;
    const unsigned int osxsave_and_avx = (1u << 27) | (1u << 28);
    if (__get_cpuid_max(0, 0) < 7 || !__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return DSN_TILE_KERNEL_DEFAULT;
    if ((ecx & osxsave_and_avx) != osxsave_and_avx) return DSN_TILE_KERNEL_DEFAULT;
    uint32_t xcr0 = 0, xcr0_high = 0;
    __asm__("xgetbv" : "=a"(xcr0), "=d"(xcr0_high) : "c"(0));
    if ((xcr0 & 6u) != 6u) return DSN_TILE_KERNEL_DEFAULT;
    __cpuid_count(7, 0, eax, ebx, ecx, edx);
    if ((ebx & (1u << 5)) == 0) return DSN_TILE_KERNEL_DEFAULT;
    const unsigned int avx512_f_and_bw = (1u << 16) | (1u << 30);
    return (ebx & avx512_f_and_bw) == avx512_f_and_bw && (xcr0 & 0xE6u) == 0xE6u ? DSN_TILE_KERNEL_AVX512
                                                                                 : DSN_TILE_KERNEL_AVX2;
}
#endif
