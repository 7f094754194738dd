/* runtime/evaluators/tile.cpp - the lattice tile API: argument checks and the caller's scratch; the tile
   itself is computed by the kernel init chose for this CPU (kernels.h), which gives the bits of the per-point
   path whichever it is. */
#include "core/error_output.h"
#include "kernels/kernels.h"

namespace {

/* Checks the arguments every tile call shares and counts the tile's values. Largest tile: sides up to
   DSN_TILE_MAX_SIDE and width * height * channels 32-bit values addressable. */
int tile_values(const dsn_noise_state *noise, const void *out, uint32_t width, uint32_t height,
                size_t *values) {
    if (noise == 0 || out == 0) return DSN_ERR_NULL;
    if (!dsn_configured(noise)) return DSN_ERR_ARGUMENT;
    if (width == 0 || height == 0 || width > DSN_TILE_MAX_SIDE || height > DSN_TILE_MAX_SIDE)
        return DSN_ERR_TILE_SIZE;
    uint64_t count = uint64_t(width) * height * noise->asset.channels; /* < 2^34 */
    if (count > (~size_t(0) - 8) / sizeof(uint32_t)) return DSN_ERR_TILE_SIZE;
    *values = size_t(count);
    return DSN_OK;
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
#if DSN_READS_SECTIONS
    dsn_noise_state view;
    const dsn_noise_state *lattice = dsn_internal_lattice_view(noise, &view);
#else
    if (dsn_lattice_texton_unread(noise)) return DSN_ERR_UNSUPPORTED;
    const dsn_noise_state *lattice = noise;
#endif
    dsn_kernel_entries_of(noise->tile_kernel)
        ->lattice_tile(lattice, uint32_t(x0), uint32_t(y0), width, height, out, 0, 0, kind, accumulator, 0);
    return DSN_OK;
}

/* render_checked, with the output zeroed on an error (dsn.h): one copy for the three output types. */
int render_or_zero(const dsn_noise_state *noise, int32_t x0, int32_t y0, uint32_t width, uint32_t height,
                   void *out, dsn_output_kind kind, void *scratch, size_t scratch_size) {
    const int err = render_checked(noise, x0, y0, width, height, out, kind, scratch, scratch_size);
    return dsn_output_error(err, noise, out, kind, size_t(width) * height);
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
    return render_or_zero(noise, x0, y0, width, height, out, dsn_output_fixed, scratch, scratch_size);
}

extern "C" int dsn_lattice_tile_float(const dsn_noise *handle, int32_t x0, int32_t y0, uint32_t width,
                                      uint32_t height, float *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return render_or_zero(noise, x0, y0, width, height, out, dsn_output_float, scratch, scratch_size);
}

extern "C" int dsn_lattice_tile_u8(const dsn_noise *handle, int32_t x0, int32_t y0, uint32_t width,
                                   uint32_t height, uint8_t *out, void *scratch, size_t scratch_size) {
    const dsn_noise_state *noise = dsn_state(handle);
    return render_or_zero(noise, x0, y0, width, height, out, dsn_output_u8, scratch, scratch_size);
}
