/* runtime/evaluators/point.cpp - per-point evaluation on the lattice: sums the texton values of every impulse
   whose window holds the point (the kernel's vector walk where it takes the noise, else cell by cell),
   then normalizes; plus the float and 8-bit conversions. */
#include "core/cell_walk.h"
#include "core/lattice_impulses.h"
#include "core/lattice_internal.h"
#include "core/normalize_fixed.h"
#include "core/poisson_count.h"
#include "kernels/kernels.h"

namespace {

#if !DSN_SMALL_CODE

/* Kept out of line so that its frame is not on the stack of the vector walk's calls. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
void accumulate_any(const dsn_noise_state *noise, const dsn_texton_window *texton, uint32_t x, uint32_t y,
                    uint32_t *sums) {
    const uint32_t shift = noise->cell_shift;
    dsn_axis axis_x, axis_y;
    dsn_axis_init(&axis_x, x, 1, texton->radius[0], shift, noise->period[0]);
    dsn_axis_init(&axis_y, y, 1, texton->radius[1], shift, noise->period[1]);
    for (uint32_t span_index_y = 0; span_index_y < axis_y.span_count; span_index_y++) {
        const dsn_span span_y = dsn_axis_span(&axis_y, span_index_y);
        for (uint32_t i = 0; i < span_y.cell_count; i++) {
            const uint32_t cell_y = dsn_span_cell(&span_y, i, shift), row_key = dsn_row_key(noise, cell_y);
            const axis_cell in_y = cell_on_axis(&span_y, cell_y, shift);
            for (uint32_t span_index_x = 0; span_index_x < axis_x.span_count; span_index_x++) {
                const dsn_span span_x = dsn_axis_span(&axis_x, span_index_x);
                for (uint32_t j = 0; j < span_x.cell_count; j++) {
                    const uint32_t cell_x = dsn_span_cell(&span_x, j, shift);
                    const axis_cell in_x = cell_on_axis(&span_x, cell_x, shift);
                    const uint32_t key = dsn_cell_key_in_row(noise, cell_x, row_key);
                    add_impulses(noise, texton, key, 0, dsn_cell_impulse_count(noise, key), &in_x, &in_y,
                                 sums);
                }
            }
        }
    }
}

/* The sums of the point (x, y), and where Points is 3 of its right and lower neighbours (sums + 3,
   sums + 6), from the kernel's vector walk where it takes the noise (kernels.h), else cell by cell. */
template <uint32_t Points>
void accumulate(const dsn_noise_state *noise, const dsn_texton_window *texton, uint32_t x, uint32_t y,
                uint32_t *sums) {
    dsn_lattice_point_entry *walk = dsn_kernel_entries_of(noise->tile_kernel)->lattice_point;
    if (walk != 0 && walk(noise, texton, x, y, Points, sums, 0)) return;
    for (uint32_t i = 0; i < 3 * Points; i++) sums[i] = 0;
    for (uint32_t p = 0; p < Points; p++)
        accumulate_any(noise, texton, x + (p == 1), y + (p == 2), sums + 3 * p);
}

#endif /* !DSN_SMALL_CODE */

/* Whether `noise` evaluates into `out`. A noise that dsn_noise_init did not fill (zeroed on failure) has
   no texton: then out[0], all that the caller of an unconfigured noise is known to hold, is zeroed (the
   per-point functions return no error code, and dsn.h promises no output left undefined). */
template <typename Value>
bool usable(const dsn_noise_state *noise, Value *out) {
    if (out != 0 && dsn_configured(noise)) return true;
    if (out != 0) out[0] = 0;
    return false;
}

} // namespace

#if DSN_SMALL_CODE
/* The small build evaluates a point as a 1 x 1 tile: one walk over the cells for both (same bits), and
   the tile's zeroing of out[0] for a noise not configured. */
extern "C" void dsn_lattice_point_fixed(const dsn_noise *handle, int32_t x, int32_t y, int32_t *out) {
    (void)dsn_lattice_tile_fixed(handle, x, y, 1, 1, out, 0, 0);
}
extern "C" void dsn_lattice_point_float(const dsn_noise *handle, int32_t x, int32_t y, float *out) {
    uint32_t scratch[DSN_MAX_CHANNELS + 1]; /* dsn_lattice_tile_scratch_size of one point, at most */
    (void)dsn_lattice_tile_float(handle, x, y, 1, 1, out, scratch, sizeof scratch);
}
extern "C" void dsn_lattice_point_u8(const dsn_noise *handle, int32_t x, int32_t y, uint8_t *out) {
    uint32_t scratch[DSN_MAX_CHANNELS + 1];
    (void)dsn_lattice_tile_u8(handle, x, y, 1, 1, out, scratch, sizeof scratch);
}
#else
#if DSN_GRADIENTS
void dsn_internal_lattice_neighbour_sums(const dsn_noise_state *noise, uint32_t x, uint32_t y,
                                         uint32_t *sums) {
    const dsn_texton_window texton = dsn_lattice_texton_window(noise);
    accumulate<3>(noise, &texton, x, y, sums);
}
#endif

extern "C" void dsn_lattice_point_fixed(const dsn_noise *handle, int32_t x, int32_t y, int32_t *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (!usable(noise, out)) return;
    uint32_t sums[3];
#if !DSN_READS_SECTIONS
    if (dsn_lattice_texton_unread(noise)) {
        for (uint32_t c = 0; c < noise->asset.channels; c++) out[c] = 0;
        return;
    }
#endif
    const dsn_texton_window texton = dsn_lattice_texton_window(noise);
    accumulate<1>(noise, &texton, uint32_t(x), uint32_t(y), sums);
    dsn_normalize(noise, sums, out);
}
#endif

#if !DSN_SMALL_CODE
extern "C" void dsn_lattice_point_float(const dsn_noise *handle, int32_t x, int32_t y, float *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    int32_t fixed[3];
    if (!usable(noise, out)) return;
    dsn_lattice_point_fixed(handle, x, y, fixed);
    for (uint32_t c = 0; c < noise->asset.channels; c++) out[c] = dsn_fixed_to_float(fixed[c]);
}

extern "C" void dsn_lattice_point_u8(const dsn_noise *handle, int32_t x, int32_t y, uint8_t *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    int32_t fixed[3];
    if (!usable(noise, out)) return;
    dsn_lattice_point_fixed(handle, x, y, fixed);
    for (uint32_t c = 0; c < noise->asset.channels; c++) out[c] = dsn_fixed_to_u8(fixed[c]);
}
#endif
