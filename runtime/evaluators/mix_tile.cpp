/* runtime/evaluators/mix_tile.cpp - the mix's tiles (dsn.h, "Mixing"), and the scratch they ask for: where
   one material's weights hold alone over a tile's reach, that material's own tile; where the weights agree
   over it, each material's own tile code over the impulses that draw it (the kernels' two-material strips,
   a lattice pass per material, a continuous splat per material), the materials' values then added;
   elsewhere mix_point.cpp's walks, a lattice tile by bands of rows (by runs of a row where bands cannot go)
   and a continuous tile by groups of a row's points. */
#include "core/grid_points.h"
#include "evaluators/grid_splat.h"
#include "evaluators/mix_evaluation.h"
#include "kernels/kernels.h"
#include "kernels/splat_cells.h"

#if DSN_MIXING

namespace {

/* The rows of a band that dsn_mix_lattice_tile_scratch_size asks for. Walking the impulses that reach a
   band costs (rows + 2 reach) / rows of walking them once (about 2 for 32 rows of a 31 x 31 texton, which
   bench measures no slower than 64). A band of material passes asks for up to 128, the strip path's
   tallest rectangle (tile_strips.h); a walked band is at most 32 rows of it. */
const uint32_t band_most_rows = 128, walk_most_rows = 32;

/* The bytes of one row of a band's values: every material's channels at each point, material after
   material (a walked band's sums, or each material pass's values). */
size_t band_row_bytes(const dsn_mix_state *mix, uint32_t width) {
    size_t values = 0;
    for (uint32_t m = 0; m < mix->count; m++) values += mix->material[m].asset.channels;
    return values * width * sizeof(uint32_t);
}
/* Material m as a band's kernels render it: its lattice noise on the mix's process, normalized from its
   offset weighted by `weight`. The strip path sizes its rectangles for the density of the impulses it
   sums (tile_strips.h's choose_rectangle): here the material's share of the process's, rounded up (an
   estimate only: the path counts a rectangle's impulses and takes the 32-bit sums where too many). */
void pass_noise(const dsn_mix_state *mix, uint32_t m, uint32_t weight, dsn_noise_state *pass) {
    const dsn_noise_state *material = &mix->material[m], *lead = &mix->material[0];
#if DSN_READS_SECTIONS
    dsn_noise_state view;
    *pass = *dsn_internal_lattice_view(material, &view);
#else
    *pass = *material;
#endif
    material_weighted_offset(material, weight, pass->offset);
    const uint64_t share =
        (static_cast<uint64_t>(lead->impacts_q16) * weight + (1u << mix_weight_bits) - 1u) >> mix_weight_bits;
    pass->impacts_q16 = share != 0 ? static_cast<uint32_t>(share) : 1u;
    pass->asset.support_size = lead->asset.support_size;
}

/* Material m's values over a band into `values` (its channels per point): the kernel's lattice tile of
   pass_noise from the impulses of the mix's process that draw it (`filter`). */
void material_pass(const dsn_mix_state *mix, uint32_t m, uint32_t weight, const dsn_impulse_filter *filter,
                   uint32_t x0, uint32_t width, uint32_t y, uint32_t rows, int32_t *values) {
    dsn_noise_state pass;
    pass_noise(mix, m, weight, &pass);
    dsn_kernel_entries_of(pass.tile_kernel)
        ->lattice_tile(&pass, x0, y, width, rows, values, 0, 0, dsn_output_fixed,
                       static_cast<uint32_t *>(static_cast<void *>(values)), filter);
}

/* The materials that impulses draw where a region's weights are uniform (a material no hash draws has no
   impulse and a zero weight: its values are zero), the impulses each keeps, and the point weights. */
struct DrawnMaterials {
    uint32_t count, materials[DSN_MIX_MAX_MATERIALS], weights[DSN_MIX_MAX_MATERIALS];
    dsn_impulse_filter filters[DSN_MIX_MAX_MATERIALS];
};

void drawn_materials(const dsn_mix_state *mix, const MixRegion &region, DrawnMaterials *drawn) {
    for (uint32_t m = 0; m < DSN_MIX_MAX_MATERIALS; m++) drawn->weights[m] = region.draws.weights[m];
    drawn->count = 0;
    for (uint32_t m = 0; m < mix->count; m++) {
        const dsn_impulse_filter filter = material_filter(region.draws.thresholds, m);
        if (filter.low >= filter.high) continue;
        drawn->materials[drawn->count] = m;
        drawn->filters[drawn->count++] = filter;
    }
}

/* Rows of two drawn materials with the mix's channels by the kernel's mixed tile (kernels.h's
   lattice_mix_tile), where it takes them: each material's normalized values added before they are
   stored, in one walk of the strips, with no scratch. False where it does not (having perhaps written
   part of the rows). */
bool mixed_band(const dsn_mix_state *mix, const DrawnMaterials &drawn, uint32_t x0, uint32_t width,
                uint32_t y, uint32_t rows, const dsn_mix_band_target &target) {
    dsn_lattice_mix_tile_entry *tile = dsn_kernel_entries_of(mix->material[0].tile_kernel)->lattice_mix_tile;
    if (tile == 0) return false;
    dsn_noise_state passes[2];
    for (uint32_t k = 0; k < 2; k++) {
        const uint32_t m = drawn.materials[k];
        if (mix->material[m].asset.channels != mix->channels) return false;
        pass_noise(mix, m, drawn.weights[m], &passes[k]);
    }
    const dsn_noise_state *const noises[2] = {&passes[0], &passes[1]};
    const size_t value_bytes = target.kind == dsn_output_u8 ? 1u : 4u;
    void *const out = static_cast<unsigned char *>(target.out) + target.first * mix->channels * value_bytes;
    return tile(noises, drawn.filters, 2u, x0, y, width, rows, out, target.kind) != 0;
}

inline int32_t saturated(int64_t total) {
    const int64_t low = total < INT32_MIN ? INT32_MIN : total;
    return static_cast<int32_t>(low > INT32_MAX ? INT32_MAX : low);
}

/* sum_planes of two planes with the mix's channels: blocks of 16 values summed into a local array (a loop
   of constant length into memory nothing else points at, which compilers vectorize), then stored. */
template <typename Store>
void sum_two_planes(const int32_t *first, const int32_t *second, size_t values, const Store &store) {
    const size_t block = 16;
    size_t v = 0;
    for (; v + block <= values; v += block) {
        int32_t sums[block];
        for (size_t k = 0; k < block; k++) sums[k] = saturating_add(first[v + k], second[v + k]);
        for (size_t k = 0; k < block; k++) store(v + k, sums[k]);
    }
    for (; v < values; v++) store(v, saturating_add(first[v], second[v]));
}

/* sum_planes where every plane has the mix's channels: value by value, the planes' count a constant. */
template <uint32_t Count, typename Store>
void sum_full_planes(const int32_t *const *planes, size_t values, const Store &store) {
    for (size_t v = 0; v < values; v++) {
        int64_t total = planes[0][v];
        for (uint32_t k = 1; k < Count; k++) total += planes[k][v];
        store(v, saturated(total));
    }
}

/* The sum of the materials' values (their planes, a grey material's value in each channel) at each
   value of a band, saturated to int32, stored by store(index, value). Where a grey material mixes with
   RGB ones, chunk by chunk, plane after plane. */
template <typename Store>
void sum_planes(const dsn_mix_state *mix, const int32_t *const *planes, const uint32_t *channels,
                uint32_t count, size_t points, const Store &store) {
    const uint32_t mix_channels = mix->channels;
    bool full = true;
    for (uint32_t k = 0; k < count; k++) full = full && channels[k] == mix_channels;
    if (full) {
        const size_t values = points * mix_channels;
        if (count == 1) sum_full_planes<1>(planes, values, store);
        if (count == 2) sum_two_planes(planes[0], planes[1], values, store);
        if (count == 3) sum_full_planes<3>(planes, values, store);
        if (count == 4) sum_full_planes<4>(planes, values, store);
        return;
    }
    const size_t chunk_points = 64;
    for (size_t first = 0; first < points; first += chunk_points) {
        const size_t chunk = points - first < chunk_points ? points - first : chunk_points;
        const size_t values = chunk * mix_channels;
        int64_t totals[chunk_points * DSN_MAX_CHANNELS];
        for (size_t v = 0; v < values; v++) totals[v] = 0;
        for (uint32_t k = 0; k < count; k++) {
            const int32_t *plane = planes[k] + first * channels[k];
            if (channels[k] == mix_channels) {
                for (size_t v = 0; v < values; v++) totals[v] += plane[v];
            } else {
                for (size_t p = 0; p < chunk; p++)
                    for (uint32_t c = 0; c < mix_channels; c++) totals[p * mix_channels + c] += plane[p];
            }
        }
        for (size_t v = 0; v < values; v++) store(first * mix_channels + v, saturated(totals[v]));
    }
}

/* A band whose weights are uniform over its reach: the kernel's two-material strips where they take it
   (mixed_band), else one material pass for each material that impulses draw, into its plane (a walked
   band's layout), then each value the sum of the materials', as mix_point.cpp's mix_output_from sums them. */
void pass_band(const dsn_mix_state *mix, const MixRegion &region, uint32_t x0, uint32_t width, uint32_t y,
               uint32_t rows, int32_t *scratch, const dsn_mix_band_target &target) {
    const size_t points = static_cast<size_t>(rows) * width;
    DrawnMaterials drawn;
    drawn_materials(mix, region, &drawn);
    if (drawn.count == 2 && mixed_band(mix, drawn, x0, width, y, rows, target)) return;
    const int32_t *planes[DSN_MIX_MAX_MATERIALS];
    uint32_t channels[DSN_MIX_MAX_MATERIALS], count = 0;
    int32_t *next = scratch;
    /* Fixed output: the first material with the mix's channels goes straight into the band's output, which
       the sum then reads and overwrites in place (each value read before it is written), one plane less
       to write and read. */
    int32_t *const in_place = target.kind == dsn_output_fixed
                                  ? static_cast<int32_t *>(target.out) + target.first * mix->channels
                                  : 0;
    for (uint32_t d = 0; d < drawn.count; d++) {
        const uint32_t m = drawn.materials[d];
        const dsn_impulse_filter &filter = drawn.filters[d];
        const bool every = filter.low == 0 && filter.high == static_cast<uint64_t>(1) << 32;
        channels[count] = mix->material[m].asset.channels;
        const bool direct = count == 0 && in_place != 0 && channels[count] == mix->channels;
        int32_t *const values = direct ? in_place : next;
        material_pass(mix, m, drawn.weights[m], every ? 0 : &filter, x0, width, y, rows, values);
        planes[count] = values;
        if (!direct) next += points * channels[count];
        count++;
    }
    if (count == 1 && planes[0] == in_place) return;
    void *const out = target.out;
    const size_t first = target.first * mix->channels;
    if (target.kind == dsn_output_fixed)
        sum_planes(mix, planes, channels, count, points,
                   [&](size_t index, int32_t value) { static_cast<int32_t *>(out)[first + index] = value; });
    else if (target.kind == dsn_output_float)
        sum_planes(mix, planes, channels, count, points, [&](size_t index, int32_t value) {
            static_cast<float *>(out)[first + index] = dsn_fixed_to_float(value);
        });
    else
        sum_planes(mix, planes, channels, count, points, [&](size_t index, int32_t value) {
            static_cast<uint8_t *>(out)[first + index] = dsn_fixed_to_u8(value);
        });
}

/* A lattice tile of a mix whose weights mix over its reach, in bands of as many rows as the scratch holds:
   a band whose weights are uniform over its reach by material passes (pass_band), the others walked in
   bands of up to walk_most_rows (dsn_internal_mix_walk_band). False, writing nothing, where the scratch holds
   no row, or where an axis with a period crosses the int32 sign change within the tile (the reduction modulo
   the period breaks the coordinates' contiguity there): the runs then go. */
bool lattice_tile_by_bands(const dsn_mix_state *mix, const dsn_mix_control *control, uint32_t x0, uint32_t y0,
                           uint32_t width, uint32_t height, void *out, dsn_output_kind kind, void *scratch,
                           size_t scratch_size) {
    const uint32_t until_x = 0x80000000u - x0, until_y = 0x80000000u - y0;
    if ((mix->material[0].period[0] != 0 && until_x != 0 && until_x < width) ||
        (mix->material[0].period[1] != 0 && until_y != 0 && until_y < height) || scratch == 0)
        return false;
    /* the values 4-byte aligned (the caller's scratch need not be) */
    const size_t misalignment = reinterpret_cast<uintptr_t>(scratch) % sizeof(uint32_t);
    const size_t skip = misalignment ? sizeof(uint32_t) - misalignment : 0u;
    const size_t fitting = scratch_size > skip ? (scratch_size - skip) / band_row_bytes(mix, width) : 0u;
    if (fitting == 0) return false;
    const uint32_t band_rows = static_cast<uint32_t>(fitting < band_most_rows ? fitting : band_most_rows);
    const uint32_t walk_rows = band_rows < walk_most_rows ? band_rows : walk_most_rows;
    void *const first = static_cast<unsigned char *>(scratch) + skip;
    for (uint32_t j0 = 0; j0 < height; j0 += band_rows) {
        const uint32_t rows = height - j0 < band_rows ? height - j0 : band_rows, y = y0 + j0;
        const MixRegion region = window_region(mix, control, x0, width, y, rows);
        if (region.uniform) {
            const dsn_mix_band_target target = {out, kind, static_cast<size_t>(j0) * width};
            pass_band(mix, region, x0, width, y, rows, static_cast<int32_t *>(first), target);
            continue;
        }
        for (uint32_t k = 0; k < rows; k += walk_rows) {
            const uint32_t walked = rows - k < walk_rows ? rows - k : walk_rows;
            const dsn_mix_band_target target = {out, kind, static_cast<size_t>(j0 + k) * width};
            dsn_internal_mix_walk_band(mix, control, x0, width, y + k, walked, static_cast<uint32_t *>(first),
                                       target);
        }
    }
    return true;
}

/* A lattice tile of a mix whose weights mix over its reach: row by row, in runs of up to run_points. */
void lattice_tile_by_runs(const dsn_mix_state *mix, const dsn_mix_control *control, uint32_t x0, uint32_t y0,
                          uint32_t width, uint32_t height, void *out, dsn_output_kind kind) {
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width;) {
            const uint32_t x = x0 + i, until_sign_change = 0x80000000u - x;
            uint32_t length = width - i < run_points ? width - i : run_points;
            if (mix->material[0].period[0] != 0 && until_sign_change != 0 && until_sign_change < length)
                length = until_sign_change;
            const dsn_mix_band_target target = {out, kind, static_cast<size_t>(j) * width + i};
            dsn_internal_mix_walk_run(mix, control, x, length, y0 + j, target);
            i += length;
        }
}

/* ---- Continuous tiles where the weights are uniform ---- */

#if !DSN_SMALL_CODE
/* The scratch of a continuous tile by materials: every material's block sums (grid_splat.h), 8-aligned. */
size_t materials_sums_size(const dsn_mix_state *mix, uint32_t width, uint32_t height) {
    size_t bytes = sizeof(uint64_t) - 1u;
    for (uint32_t m = 0; m < mix->count; m++)
        bytes += dsn_internal_splat_block_pixels(width, height) * mix->material[m].asset.channels *
                 sizeof(uint64_t);
    return bytes;
}

/* A material's normalized row (`own` channels a pixel) added to the mix's totals (`channels` a pixel): a
   grey material's value to each channel. */
void add_row_values(const int32_t *values, uint32_t own, uint32_t channels, uint32_t columns,
                    int64_t *totals) {
    if (own == channels) {
        for (uint32_t v = 0; v < columns * channels; v++) totals[v] += values[v];
        return;
    }
    for (uint32_t i = 0; i < columns; i++)
        for (uint32_t c = 0; c < channels; c++) totals[i * channels + c] += values[i];
}

/* A continuous tile whose weights are uniform over its reach, block by block (grid_splat.h): each drawn
   material's impulses (its hash filter) splatted with its texton into its own block sums, each row of them
   normalized by the kernel from the material's weighted offset, and each value the materials' values
   summed (64-bit, saturated; a grey material's in every channel). 8-bit textons are read from cell records
   for the first two materials (64 KB of stack each, as one material's tile). False, writing nothing, where
   a material's grid is not splatted or the scratch does not hold every material's block sums. */
bool continuous_tile_by_materials(const dsn_mix_state *mix, const DrawnMaterials &drawn, const dsn_grid *grid,
                                  uint32_t width, uint32_t height, void *out, dsn_output_kind kind,
                                  void *scratch, size_t scratch_size) {
    if (scratch == 0 || scratch_size < materials_sums_size(mix, width, height)) return false;
    dsn_noise_state passes[DSN_MIX_MAX_MATERIALS];
    dsn_grid_splat splats[DSN_MIX_MAX_MATERIALS];
    uint64_t *sums[DSN_MIX_MAX_MATERIALS];
    uint64_t *next = dsn_internal_aligned_sums(scratch);
    const size_t block_pixels = dsn_internal_splat_block_pixels(width, height);
#if DSN_SPLAT_CELLS
    const uint32_t celled = 2;
    alignas(64) uint64_t cells[celled][splat_cell_capacity]; /* RGB cells on 32-byte boundaries */
#endif
    for (uint32_t d = 0; d < drawn.count; d++) {
        const uint32_t m = drawn.materials[d];
        const dsn_noise_state *material = &mix->material[m];
        passes[d] = *material;
        material_weighted_offset(material, drawn.weights[m], passes[d].offset);
        const dsn_splat_texture texture = {material->asset.texton,
                                           material->asset.width,
                                           material->asset.height,
                                           material->asset.width,
                                           material->asset.channels,
                                           material->asset.bits,
                                           0};
        if (!dsn_internal_grid_splat_init(&passes[d], grid, width, height, &texture, &splats[d]))
            return false;
        const bool every = drawn.filters[d].low == 0 && drawn.filters[d].high == static_cast<uint64_t>(1)
                                                                                     << 32;
        splats[d].filter = every ? 0 : &drawn.filters[d];
#if DSN_SPLAT_CELLS
        if (d < celled && make_splat_cells(splats[d].setup.texture, cells[d], splat_cell_capacity,
                                           &splats[d].setup.cell_row, 0) != 0)
            splats[d].setup.cells = cells[d];
#endif
        sums[d] = next;
        next += block_pixels * material->asset.channels;
    }
    const uint32_t channels = mix->channels;
    const dsn_kernel_entries *kernel = dsn_kernel_entries_of(mix->material[0].tile_kernel);
    for (uint32_t top = 0; top < height; top += dsn_splat_block_rows)
        for (uint32_t left = 0; left < width; left += dsn_splat_block_columns) {
            const dsn_splat_block block = dsn_internal_splat_block(left, top, width, height);
            for (uint32_t d = 0; d < drawn.count; d++)
                dsn_internal_grid_splat_block(&passes[d], &splats[d], &block, sums[d]);
            for (uint32_t j = 0; j < block.rows; j++) {
                const uint32_t count = block.columns * channels;
                int64_t totals[dsn_splat_block_columns * DSN_MAX_CHANNELS];
                for (uint32_t v = 0; v < count; v++) totals[v] = 0;
                for (uint32_t d = 0; d < drawn.count; d++) {
                    int32_t values[dsn_splat_block_columns * DSN_MAX_CHANNELS];
                    kernel->continuous_splat_normalize(&passes[d],
                                                       sums[d] + static_cast<size_t>(j) * block.stride,
                                                       block.plane, block.columns, values);
                    add_row_values(values, passes[d].asset.channels, channels, block.columns, totals);
                }
                int32_t row[dsn_splat_block_columns * DSN_MAX_CHANNELS];
                for (uint32_t v = 0; v < count; v++) row[v] = saturated_total(totals[v]);
                const size_t first = (static_cast<size_t>(top + j) * width + left) * channels;
                if (kind == dsn_output_fixed)
                    __builtin_memcpy(static_cast<int32_t *>(out) + first, row, count * sizeof row[0]);
                else
                    for (uint32_t i = 0; i < block.columns; i++)
                        dsn_store_pixel(out, kind, first + i * channels, row + i * channels, channels);
            }
        }
    return true;
}
#endif /* !DSN_SMALL_CODE */

/* ---- The API ---- */

int lattice_tile_as(const dsn_mix *handle, const dsn_mix_control *control, int32_t x0, int32_t y0,
                    uint32_t width, uint32_t height, void *out, dsn_output_kind kind, void *scratch,
                    size_t scratch_size) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    const size_t points = static_cast<size_t>(width) * height;
    if (tile_size_check(width, height) != DSN_OK) return DSN_ERR_TILE_SIZE;
    if (out == 0) return DSN_ERR_NULL;
    const int err = check_call(mix, control, false);
    if (err != DSN_OK) return output_error(err, mix, out, kind, points);
    const uint32_t reach_x = mix->lattice_radius[0], reach_y = mix->lattice_radius[1];
    const uint32_t only =
        tile_material(mix, control, static_cast<uint64_t>(static_cast<uint32_t>(x0) - reach_x) << 32,
                      static_cast<uint64_t>(static_cast<uint32_t>(y0) - reach_y) << 32,
                      static_cast<uint64_t>(static_cast<uint32_t>(x0) + width - 1u + reach_x) << 32,
                      static_cast<uint64_t>(static_cast<uint32_t>(y0) + height - 1u + reach_y) << 32);
    if (only < mix->count && mix->material[only].asset.channels == mix->channels) {
        const dsn_noise *material = dsn_mix_material_noise(mix, only);
        if (kind == dsn_output_fixed)
            return dsn_lattice_tile_fixed(material, x0, y0, width, height, static_cast<int32_t *>(out), 0, 0);
        if (scratch_size >= dsn_lattice_tile_scratch_size(material, width, height))
            return kind == dsn_output_float
                       ? dsn_lattice_tile_float(material, x0, y0, width, height, static_cast<float *>(out),
                                                scratch, scratch_size)
                       : dsn_lattice_tile_u8(material, x0, y0, width, height, static_cast<uint8_t *>(out),
                                             scratch, scratch_size);
    }
    /* weights uniform over the whole tile, two materials drawn: the kernel's mixed strips, where they take
       them, with or without scratch */
    const MixRegion region =
        window_region(mix, control, static_cast<uint32_t>(x0), width, static_cast<uint32_t>(y0), height);
    if (region.uniform) {
        DrawnMaterials drawn;
        drawn_materials(mix, region, &drawn);
        const dsn_mix_band_target target = {out, kind, 0};
        if (drawn.count == 2 && mixed_band(mix, drawn, static_cast<uint32_t>(x0), width,
                                           static_cast<uint32_t>(y0), height, target))
            return DSN_OK;
    }
    if (!lattice_tile_by_bands(mix, control, static_cast<uint32_t>(x0), static_cast<uint32_t>(y0), width,
                               height, out, kind, scratch, scratch_size))
        lattice_tile_by_runs(mix, control, static_cast<uint32_t>(x0), static_cast<uint32_t>(y0), width,
                             height, out, kind);
    return DSN_OK;
}

int continuous_tile_as(const dsn_mix *handle, const dsn_mix_control *control, const dsn_grid *grid,
                       uint32_t width, uint32_t height, void *out, dsn_output_kind kind, void *scratch,
                       size_t scratch_size) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    const int err = grid_tile_check(mix, control, grid, width, height, out, kind);
    if (err != DSN_OK) return err;
    int64_t low_x, low_y, high_x, high_y;
    if (grid_box(grid, width, height, &low_x, &low_y, &high_x, &high_y)) {
        /* the impulses' floors lie within radius + 1 texels of the box, itself within a texel of the points
         */
        const int64_t reach_x = static_cast<int64_t>(mix->radius[0] + 2u) << 32;
        const int64_t reach_y = static_cast<int64_t>(mix->radius[1] + 2u) << 32;
        const uint64_t origin_x = static_cast<uint64_t>(grid->origin_x),
                       origin_y = static_cast<uint64_t>(grid->origin_y);
        const MixRegion region =
            mix_region(control, mix->count, origin_x + static_cast<uint64_t>(low_x - reach_x),
                       origin_y + static_cast<uint64_t>(low_y - reach_y),
                       origin_x + static_cast<uint64_t>(high_x + reach_x),
                       origin_y + static_cast<uint64_t>(high_y + reach_y), 1024u);
        const uint32_t only = region.single ? region.only : mix->count;
        if (only < mix->count && mix->material[only].asset.channels == mix->channels) {
            const dsn_noise *material = dsn_mix_material_noise(mix, only);
            if (scratch_size >= dsn_continuous_tile_scratch_size(material, grid, width, height)) {
                if (kind == dsn_output_fixed)
                    return dsn_continuous_tile_fixed(material, grid, width, height,
                                                     static_cast<int32_t *>(out), scratch, scratch_size);
                if (kind == dsn_output_float)
                    return dsn_continuous_tile_float(material, grid, width, height, static_cast<float *>(out),
                                                     scratch, scratch_size);
                return dsn_continuous_tile_u8(material, grid, width, height, static_cast<uint8_t *>(out),
                                              scratch, scratch_size);
            }
        }
#if !DSN_SMALL_CODE
        if (region.uniform) {
            DrawnMaterials drawn;
            drawn_materials(mix, region, &drawn);
            if (continuous_tile_by_materials(mix, drawn, grid, width, height, out, kind, scratch,
                                             scratch_size))
                return DSN_OK;
        }
#endif
    }
    /* a row's points in groups */
    uint64_t xs[group_points], ys[group_points];
    uint32_t grouped = 0;
    dsn_grid_points(grid, width, height, mix->channels, [&](size_t index, uint64_t x, uint64_t y) {
        xs[grouped] = x;
        ys[grouped] = y;
        grouped++;
        const size_t column = (index / mix->channels) % width;
        if (grouped < group_points && column + 1u < width) return;
        int32_t values[group_points][DSN_MAX_CHANNELS];
        dsn_internal_mix_continuous_points(mix, control, xs, ys, grouped, values);
        for (uint32_t p = 0; p < grouped; p++)
            dsn_store_pixel(out, kind, index - (grouped - 1u - p) * mix->channels, values[p], mix->channels);
        grouped = 0;
    });
    return DSN_OK;
}

} // namespace

extern "C" {

int dsn_mix_lattice_tile_u8(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                            uint32_t width, uint32_t height, uint8_t *out, void *scratch,
                            size_t scratch_size) {
    return lattice_tile_as(mix, control, x0, y0, width, height, out, dsn_output_u8, scratch, scratch_size);
}

int dsn_mix_continuous_tile_u8(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                               uint32_t width, uint32_t height, uint8_t *out, void *scratch,
                               size_t scratch_size) {
    return continuous_tile_as(mix, control, grid, width, height, out, dsn_output_u8, scratch, scratch_size);
}

size_t dsn_mix_lattice_tile_scratch_size(const dsn_mix *handle, uint32_t width, uint32_t height) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    if (!dsn_mix_configured(mix) || tile_size_check(width, height) != DSN_OK) return 0;
    /* the values of a whole band (and 3 bytes to align them) */
    size_t most = band_row_bytes(mix, width) * (height < band_most_rows ? height : band_most_rows) +
                  sizeof(uint32_t) - 1u;
    for (uint32_t m = 0; m < mix->count; m++) {
        const size_t size = dsn_lattice_tile_scratch_size(dsn_mix_material_noise(mix, m), width, height);
        most = size > most ? size : most;
    }
    return most;
}

size_t dsn_mix_continuous_tile_scratch_size(const dsn_mix *handle, const dsn_grid *grid, uint32_t width,
                                            uint32_t height) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    size_t most = 0;
    if (!dsn_mix_configured(mix)) return 0;
    for (uint32_t m = 0; m < mix->count; m++) {
        const size_t size =
            dsn_continuous_tile_scratch_size(dsn_mix_material_noise(mix, m), grid, width, height);
        most = size > most ? size : most;
    }
#if !DSN_SMALL_CODE
    /* every material's block sums, where the grid is splatted (the scratch of one material's tile) */
    if (most != 0 && tile_size_check(width, height) == DSN_OK) {
        const size_t materials = materials_sums_size(mix, width, height);
        most = materials > most ? materials : most;
    }
#endif
    return most;
}

int dsn_mix_lattice_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                               uint32_t width, uint32_t height, int32_t *out, void *scratch,
                               size_t scratch_size) {
    return lattice_tile_as(mix, control, x0, y0, width, height, out, dsn_output_fixed, scratch, scratch_size);
}

int dsn_mix_lattice_tile_float(const dsn_mix *mix, const dsn_mix_control *control, int32_t x0, int32_t y0,
                               uint32_t width, uint32_t height, float *out, void *scratch,
                               size_t scratch_size) {
    return lattice_tile_as(mix, control, x0, y0, width, height, out, dsn_output_float, scratch, scratch_size);
}

int dsn_mix_continuous_tile_fixed(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                                  uint32_t width, uint32_t height, int32_t *out, void *scratch,
                                  size_t scratch_size) {
    return continuous_tile_as(mix, control, grid, width, height, out, dsn_output_fixed, scratch,
                              scratch_size);
}

int dsn_mix_continuous_tile_float(const dsn_mix *mix, const dsn_mix_control *control, const dsn_grid *grid,
                                  uint32_t width, uint32_t height, float *out, void *scratch,
                                  size_t scratch_size) {
    return continuous_tile_as(mix, control, grid, width, height, out, dsn_output_float, scratch,
                              scratch_size);
}

} // extern "C"

#endif /* DSN_MIXING */
