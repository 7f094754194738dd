/* runtime/evaluators/continuous_batch.cpp - the API of batches of continuous points (dsn.h): checks, the
   scratch's layout (the texton's 2 x 2 texel table, built once per call, and the kernel's work arrays), the
   float variant's conversions, and the call to the batch kernel that init chose (kernels.h,
   continuous_batch.h). Empty when DSN_CONTINUOUS_BATCH is 0 (the small build). */
#include "dsn/dsn.h"

#if DSN_CONTINUOUS_BATCH
#include "core/continuous_internal.h"
#include "core/error_output.h"
#include "core/normalize_fixed.h"
#include "kernels/continuous_batch.h"
#include "kernels/continuous_point_vector.h"
#include "kernels/kernels.h"

namespace {

const size_t scratch_alignment = 64;

size_t round_up(size_t bytes) {
    return (bytes + scratch_alignment - 1u) / scratch_alignment * scratch_alignment;
}

size_t scratch_bytes(const dsn_noise_state *noise) {
    return scratch_alignment - 1u + round_up(batch_quad_count(&noise->asset) * sizeof(uint32_t)) +
           batch_work_bytes;
}

/* The aligned start of the caller's scratch. */
unsigned char *aligned_scratch(void *scratch) {
    unsigned char *bytes = static_cast<unsigned char *>(scratch);
    const uintptr_t misalignment = reinterpret_cast<uintptr_t>(bytes) % scratch_alignment;
    return bytes + (misalignment ? scratch_alignment - misalignment : 0u);
}

/* Texel `column` (bordered: texton column column - 1) of a texton row (null: the border) in channel c,
   its value's bytes in the low bits of a word (dsn_asset_texton_value's, read without a call per value);
   0 outside the window. */
inline uint32_t bordered_bits(const dsn_asset *asset, const unsigned char *row, uint32_t column, uint32_t c) {
    column -= 1u; /* the border: 0xFFFFFFFF, outside */
    if (row == 0 || column >= asset->width) return 0;
    const size_t index = static_cast<size_t>(column) * asset->channels + c;
    if (asset->bits == 8) return row[index];
    return static_cast<uint32_t>(row[2u * index]) | static_cast<uint32_t>(row[2u * index + 1u]) << 8;
}

/* Texton row `row` of the bordered texton (texton row row - 1), or null for the border. */
inline const unsigned char *bordered_row(const dsn_asset *asset, uint32_t row) {
    if (row - 1u >= asset->height) return 0;
    return asset->texton +
           static_cast<size_t>(row - 1u) * asset->width * asset->channels * (asset->bits / 8u);
}

/* Points from which a call builds the quad table for the noises that the kernel's vector evaluator takes
   (continuous_batch_group.h reads the texton itself without it): fewer do not repay its building. */
const uint32_t quad_table_least_points = 512;

/* Whether a call of `count` points builds the quad table: always where the kernel's passes across points
   run (they read only it), from quad_table_least_points points for the vector evaluator's noises. */
bool quad_table_used(const dsn_noise_state *noise, uint32_t count) {
    return dsn_kernel_entries_of(noise->tile_kernel)->continuous_point == 0 || !point_vector_takes(noise) ||
           count >= quad_table_least_points;
}

/* Fills the quad table (continuous_batch.h) at the start of the aligned scratch where the call uses it;
   returns the work arrays after the table. */
void *prepare_scratch(const dsn_noise_state *noise, unsigned char *aligned, bool table) {
    const dsn_asset *asset = &noise->asset;
    if (!table) return aligned + round_up(batch_quad_count(asset) * sizeof(uint32_t));
    uint32_t *quads = static_cast<uint32_t *>(static_cast<void *>(aligned));
    size_t index = 0;
    for (uint32_t row = 0; row <= asset->height; row++) {
        const unsigned char *top = bordered_row(asset, row), *bottom = bordered_row(asset, row + 1u);
        for (uint32_t column = 0; column <= asset->width; column++)
            for (uint32_t c = 0; c < asset->channels; c++) {
                const uint32_t top_left = bordered_bits(asset, top, column, c),
                               top_right = bordered_bits(asset, top, column + 1u, c);
                const uint32_t bottom_left = bordered_bits(asset, bottom, column, c),
                               bottom_right = bordered_bits(asset, bottom, column + 1u, c);
                if (asset->bits == 8) {
                    quads[index++] = top_left | (top_right << 8) | (bottom_left << 16) | (bottom_right << 24);
                } else {
                    quads[index++] = top_left | (top_right << 16);
                    quads[index++] = bottom_left | (bottom_right << 16);
                }
            }
    }
    return aligned + round_up(index * sizeof(uint32_t));
}

/* The checks every batch call makes, in the order documented in dsn.h. */
int check_batch(const dsn_noise_state *noise, const void *xs, const void *ys, uint32_t count, const void *out,
                const void *scratch, size_t scratch_size) {
    const int err = dsn_internal_continuous_check(noise);
    if (err != DSN_OK) return err;
    if (count == 0) return DSN_OK;
    if (xs == 0 || ys == 0 || out == 0) return DSN_ERR_NULL;
    if (scratch == 0 || scratch_size < scratch_bytes(noise)) return DSN_ERR_SCRATCH;
    return DSN_OK;
}

/* The points of a chunk: all of them at once where neither the coordinates nor the output are converted. */
uint32_t chunk_points(const int64_t *, uint32_t count, dsn_output_kind kind) {
    return kind == dsn_output_fixed ? count : batch_chunk_points;
}
uint32_t chunk_points(const double *, uint32_t, dsn_output_kind) { return batch_chunk_points; }

/* Every batch function: the checks, the scratch, then the kernel; fixed output straight into `out`, the
   other kinds (and float64 coordinates) a chunk at a time through the stack (under 2 KB). */
template <typename Coordinate>
int batch_as(const dsn_noise_state *noise, const Coordinate *xs, const Coordinate *ys, uint32_t count,
             void *out, dsn_output_kind kind, void *scratch, size_t scratch_size) {
    const int err = check_batch(noise, xs, ys, count, out, scratch, scratch_size);
    if (err != DSN_OK) return dsn_output_error(err, noise, out, kind, count);
    if (count == 0) return DSN_OK;
    unsigned char *aligned = aligned_scratch(scratch);
    const bool table = quad_table_used(noise, count);
    void *work = prepare_scratch(noise, aligned, table);
    const uint32_t *quads = table ? static_cast<const uint32_t *>(static_cast<void *>(aligned)) : 0;
    dsn_continuous_batch_entry *batch = dsn_kernel_entries_of(noise->tile_kernel)->continuous_batch;
    const uint32_t channels = noise->asset.channels;
    int64_t chunk_x[batch_chunk_points], chunk_y[batch_chunk_points];
    int32_t fixed[batch_chunk_points * DSN_MAX_CHANNELS];
    const uint32_t chunk = chunk_points(xs, count, kind);
    for (uint32_t first = 0; first < count; first += chunk) {
        const uint32_t points = count - first < chunk ? count - first : chunk;
        const int64_t *point_xs = dsn_chunk_coordinates(xs, first, points, chunk_x);
        const int64_t *point_ys = dsn_chunk_coordinates(ys, first, points, chunk_y);
        if (kind == dsn_output_fixed) {
            batch(noise, quads, point_xs, point_ys, points,
                  static_cast<int32_t *>(out) + size_t(first) * channels, 0, 0, work);
            continue;
        }
        batch(noise, quads, point_xs, point_ys, points, fixed, 0, 0, work);
        for (uint32_t k = 0; k < points; k++)
            dsn_store_pixel(out, kind, static_cast<size_t>(first + k) * channels, fixed + k * channels,
                            channels);
    }
    return DSN_OK;
}

} // namespace

extern "C" {

size_t dsn_continuous_batch_scratch_size(const dsn_noise *handle) {
    const dsn_noise_state *noise = dsn_state(handle);
    return dsn_internal_continuous_check(noise) == DSN_OK ? scratch_bytes(noise) : 0u;
}

int dsn_continuous_batch_fixed(const dsn_noise *handle, const int64_t *xs, const int64_t *ys, uint32_t count,
                               int32_t *out, void *scratch, size_t scratch_size) {
    return batch_as(dsn_state(handle), xs, ys, count, out, dsn_output_fixed, scratch, scratch_size);
}

int dsn_continuous_batch_float(const dsn_noise *handle, const double *xs, const double *ys, uint32_t count,
                               float *out, void *scratch, size_t scratch_size) {
    return batch_as(dsn_state(handle), xs, ys, count, out, dsn_output_float, scratch, scratch_size);
}

int dsn_continuous_batch_u8(const dsn_noise *handle, const int64_t *xs, const int64_t *ys, uint32_t count,
                            uint8_t *out, void *scratch, size_t scratch_size) {
    return batch_as(dsn_state(handle), xs, ys, count, out, dsn_output_u8, scratch, scratch_size);
}

} // extern "C"

#endif /* DSN_CONTINUOUS_BATCH */
