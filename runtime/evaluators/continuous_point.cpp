/* runtime/evaluators/continuous_point.cpp - the continuous mode at one point: the impulses of the cells
   around it, each adding its bilinear texton (bilinear_texton.h) to the channel sums. With DSN_SMALL_CODE
   (dsn.h) a point walks its impulses one by one; the fast build takes the kernel's entry, which sifts
   them on their packed lattice fields first (continuous_point_sift.h; the usual noises on vectors in the
   AVX2 and AVX-512 kernels, continuous_point_vector.h). Also the API's mode check and per-point
   functions. */
#include "core/bilinear_texton.h"
#include "core/cell_walk.h"
#include "core/continuous_internal.h"
#include "core/continuous_sift.h"
#include "core/impulse_position.h"
#include "core/normalize_fixed.h"
#include "core/poisson_count.h"
#include "kernels/kernels.h"

namespace {

/* ---- Walking the impulses around one point ---- */

#if DSN_SMALL_CODE
/* Both steps along one axis: the texels that bracket the impulse (see bracket), or false when it lies
   beyond the period or out of reach. With `entry_edge` (the gradient) an impulse exactly at the edge
   where it enters the reach, offset -(radius + 1), is kept: its value is 0, its slope is not. */
bool impulse_bracket(const PointAxis &point, const dsn_span &span, uint32_t cell_origin, uint32_t bits16,
                     bool entry_edge, uint32_t *lower_index, uint32_t *upper_weight) {
    int64_t offset;
    if (!impulse_offset(point, span, cell_origin, bits16, &offset)) return false;
    if (entry_edge &&
        offset == -static_cast<int64_t>(point.axis.radius + 1u) * static_cast<int64_t>(one_texel)) {
        *lower_index = 0xFFFFFFFFu;
        *upper_weight = 0;
        return true;
    }
    return bracket(offset, point.axis.radius, lower_index, upper_weight);
}

/* Sums (Q.32, per channel) of the bilinear texton over every impulse of the cell (cell_x, cell_y), and with
   Slopes its partial derivatives (add_slopes) in slopes[0 .. 2] (x) and slopes[3 .. 5] (y). */
template <bool Slopes>
void add_cell(const dsn_noise_state *noise, const PointAxis &px, const dsn_span &span_x, uint32_t cell_x,
              const PointAxis &py, const dsn_span &span_y, uint32_t cell_y, uint64_t *sums,
              uint64_t *slopes) {
    const uint32_t key = dsn_cell_key(noise, cell_x, cell_y);
    const uint32_t count = dsn_cell_impulse_count(noise, key);
    const uint32_t origin_x = cell_x << noise->cell_shift, origin_y = cell_y << noise->cell_shift;
    for (uint32_t k = 0; k < count; k++) {
        const uint32_t hash = dsn_impulse_hash(noise, key, k);
        uint32_t row, row_weight, column, column_weight;
        if (!impulse_bracket(py, span_y, origin_y, dsn_impulse_bits_y(hash), Slopes, &row, &row_weight) ||
            !impulse_bracket(px, span_x, origin_x, dsn_impulse_bits_x(hash), Slopes, &column, &column_weight))
            continue;
        add_bilinear(&noise->asset, row, row_weight, column, column_weight, sums);
        for (uint32_t c = 0; Slopes && c < noise->asset.channels; c++)
            add_slopes(texel(&noise->asset, row, column, c), texel(&noise->asset, row, column + 1u, c),
                       texel(&noise->asset, row + 1u, column, c),
                       texel(&noise->asset, row + 1u, column + 1u, c), column_weight, row_weight, &slopes[c],
                       &slopes[DSN_MAX_CHANNELS + c]);
    }
}

/* Every impulse around the point, impulse by impulse, each through dsn_impulse_hash. */
template <bool Slopes>
void sum_point(const dsn_noise_state *noise, uint64_t x, uint64_t y, uint64_t *sums, uint64_t *slopes) {
    const uint32_t shift = noise->cell_shift;
    const PointAxis px = point_axis(x, noise->radius[0], shift, noise->period[0]);
    const PointAxis py = point_axis(y, noise->radius[1], shift, noise->period[1]);
    for (uint32_t sy = 0; sy < py.axis.span_count; sy++) {
        const dsn_span span_y = dsn_axis_span(&py.axis, sy);
        for (uint32_t sx = 0; sx < px.axis.span_count; sx++) {
            const dsn_span span_x = dsn_axis_span(&px.axis, sx);
            for (uint32_t j = 0; j < span_y.cell_count; j++)
                for (uint32_t i = 0; i < span_x.cell_count; i++)
                    add_cell<Slopes>(noise, px, span_x, dsn_span_cell(&span_x, i, shift), py, span_y,
                                     dsn_span_cell(&span_y, j, shift), sums, slopes);
        }
    }
}

} // namespace

void dsn_internal_continuous_point(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out) {
    uint64_t sums[DSN_MAX_CHANNELS] = {0, 0, 0};
    sum_point<false>(noise, x, y, sums, 0);
    normalize_q32(noise, sums, out);
}

#if DSN_GRADIENTS
void dsn_internal_continuous_slopes(const dsn_noise_state *noise, uint64_t x, uint64_t y, uint64_t *value,
                                    uint64_t *slope_x, uint64_t *slope_y) {
    uint64_t slopes[2 * DSN_MAX_CHANNELS] = {0, 0, 0, 0, 0, 0};
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) value[c] = 0;
    sum_point<true>(noise, x, y, value, slopes);
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) {
        slope_x[c] = slopes[c];
        slope_y[c] = slopes[DSN_MAX_CHANNELS + c];
    }
}
#endif

namespace {

#else
} // namespace

/* The fast build: the kernel's entry (continuous_point_sift.h), the vector evaluator where the kernel has
   one that takes the noise, else the sifting walk. */
void dsn_internal_continuous_point(const dsn_noise_state *noise, uint64_t x, uint64_t y, int32_t *out) {
    uint64_t sums[DSN_MAX_CHANNELS];
    dsn_kernel_entries_of(noise->tile_kernel)->continuous_point(noise, x, y, sums, 0, 0, 0);
    normalize_q32(noise, sums, out);
}

#if DSN_GRADIENTS
void dsn_internal_continuous_slopes(const dsn_noise_state *noise, uint64_t x, uint64_t y, uint64_t *value,
                                    uint64_t *slope_x, uint64_t *slope_y) {
    dsn_kernel_entries_of(noise->tile_kernel)->continuous_point(noise, x, y, value, slope_x, slope_y, 0);
}
#endif

namespace {
#endif /* DSN_SMALL_CODE */

/* The number of values a call writes: the noise's channels, or, for a noise with none (null, never
   configured, failed), the one value that every caller's array has, zeroed. */
uint32_t values_written(const dsn_noise_state *noise) { return dsn_values_per_point(noise); }

} // namespace

int dsn_internal_continuous_check(const dsn_noise_state *noise) {
    if (!dsn_configured(noise)) return DSN_ERR_NULL;
    return dsn_continuous_reads(noise) ? DSN_OK : DSN_ERR_CONTINUOUS_MISMATCH;
}

int dsn_internal_continuous_point_as(const dsn_noise *handle, int64_t x, int64_t y, void *out,
                                     dsn_output_kind kind) {
    int32_t fixed[DSN_MAX_CHANNELS] = {0, 0, 0};
    if (out == 0) return DSN_ERR_NULL;
    const int err = dsn_continuous_point_fixed(handle, x, y, fixed);
    dsn_store_pixel(out, kind, 0, fixed, values_written(dsn_state(handle)));
    return err;
}

extern "C" {

int dsn_continuous_check(const dsn_noise *handle) { return dsn_internal_continuous_check(dsn_state(handle)); }

int dsn_continuous_point_fixed(const dsn_noise *handle, int64_t x, int64_t y, int32_t *out) {
    const dsn_noise_state *noise = dsn_state(handle);
    if (out == 0) return DSN_ERR_NULL;
    const int err = dsn_internal_continuous_check(noise);
    if (err != DSN_OK) {
        for (uint32_t c = 0; c < values_written(noise); c++) out[c] = 0;
        return err;
    }
    dsn_internal_continuous_point(noise, static_cast<uint64_t>(x), static_cast<uint64_t>(y), out);
    return DSN_OK;
}

int dsn_continuous_point_float(const dsn_noise *handle, double x, double y, float *out) {
    return dsn_internal_continuous_point_as(handle, dsn_coordinate_from_double(x),
                                            dsn_coordinate_from_double(y), out, dsn_output_float);
}

#if !DSN_SMALL_CODE
int dsn_continuous_point_u8(const dsn_noise *handle, int64_t x, int64_t y, uint8_t *out) {
    return dsn_internal_continuous_point_as(handle, x, y, out, dsn_output_u8);
}
#endif

} // extern "C"
