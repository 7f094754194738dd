/* runtime/setup/noise_init.cpp - dsn_config_defaults and dsn_noise_init: checks the configuration, chooses
   the cell size, then builds the Poisson table and the normalization (their own files). */
#include "core/cell_hash.h"
#include "core/histogram_map.h"
#include "kernels/kernels.h"
#include "setup/init_internal.h"
#include "setup/wide_arithmetic.h"

namespace {

/* Expected cost of one per-point evaluation with cells of side c = 2^shift, a linear model in fixed units
   (Q16). A point visits (w - 1 + c)(h - 1 + c) / c^2 cells and examines lambda (w - 1 + c)(h - 1 + c)
   impulses, lambda w h of which reach it.
   - 16 x 16 cells with one Poisson draw take point.cpp's vector walk: 90 units per cell, 13 per impulse
     examined (hit or not).
   - Other sizes take the impulse-by-impulse walk: 72 units per cell and 30 per further draw, 27 per
     impulse examined and 27 more per impulse that reaches the point.
   The constants were fitted to per-point timings on x86-64 (make bench times the evaluators) and are now
   fixed: the cell size is part of the output, so every platform, with or without SSE2, must make the same
   choice from the same model. The usual 31 x 31 texton at 30 impacts per pixel gets c = 16 (8.3 cells,
   66 impulses), as do 31 x 31 at 5 impacts and 63 x 63 at 30; 15 x 15 at 30 would need three draws for
   c = 16 and gets c = 8. The tile path is insensitive to the choice. */
uint64_t point_cost_q16(const dsn_asset *asset, uint32_t impacts_q16, uint32_t shift, uint64_t parts,
                        uint64_t hits_q16) {
    const uint32_t side = 1u << shift; /* <= 256: the area is below 2^19 and 2 shift <= 16 */
    const uint32_t area = (asset->width - 1 + side) * (asset->height - 1 + side);
    const uint64_t cells_q16 = uint64_t(area) << (16 - 2 * shift);
    const uint64_t impulses_q16 = dsn_divide(uint64_t(area) * impacts_q16, asset->support_size);
    if (shift == 4 && parts == 1) return cells_q16 * 90 + impulses_q16 * 13;
    return cells_q16 * (72 + 30 * (parts - 1)) + (impulses_q16 + hits_q16) * 27;
}

/* Mean impulse count of a cell, lambda c^2, in Q32. */
uint64_t cell_mean_q32(const dsn_asset *asset, uint32_t impacts_q16, uint32_t shift) {
    uint64_t numerator = (uint64_t(impacts_q16) << (2 * shift)) << 16; /* < 2^58 */
    return dsn_divide(numerator + asset->support_size / 2, asset->support_size);
}

uint64_t poisson_parts(uint64_t mean_q32) {
    const uint64_t part_max_q32 = uint64_t(DSN_POISSON_MEAN_MAX) << 32;
    return (mean_q32 + part_max_q32 - 1) / part_max_q32;
}

/* The cell size, and the mean impulse count of its cells (Q32). */
uint32_t choose_cell_shift(const dsn_asset *asset, uint32_t impacts_q16, uint64_t *best_mean_q32) {
    /* At most 2^8: the continuous mode needs >= 8 fractional position bits of the 16 per axis. */
    const uint64_t hits_q16 =
        dsn_divide(uint64_t(asset->width) * asset->height * impacts_q16, asset->support_size);
    uint32_t best_shift = 0;
    uint64_t best_cost = UINT64_MAX;
    for (uint32_t shift = 0; shift <= 8; shift++) {
        const uint64_t mean_q32 = cell_mean_q32(asset, impacts_q16, shift);
        const uint64_t cost = point_cost_q16(asset, impacts_q16, shift, poisson_parts(mean_q32), hits_q16);
        if (cost <= best_cost) {
            best_cost = cost;
            best_shift = shift;
            *best_mean_q32 = mean_q32;
        }
    }
    return best_shift;
}

/* A dsn_asset that dsn_asset_load did not fill (or that was altered) must not reach the evaluators. */
int asset_is_usable(const dsn_asset *asset) {
    uint32_t support_size;
#if DSN_HISTOGRAM
    if (!dsn_internal_histogram_usable(asset)) return 0;
#else
    if (asset->histogram_table != 0) return 0; /* an asset this build cannot show as it should */
#endif
    if (asset->texton == 0 || dsn_internal_check_geometry(asset, &support_size) != DSN_OK ||
        asset->support_size != support_size)
        return 0;
#if DSN_READS_SECTIONS
    /* The pyramid and lattice texton as loaded: the filtered walks and the lattice view index with their
       sizes. */
    if (dsn_internal_check_sections(asset) != DSN_OK) return 0;
#endif
    return 1;
}

void clear_noise(dsn_noise_state *noise) {
    unsigned char *bytes = static_cast<unsigned char *>(static_cast<void *>(noise));
    for (size_t i = 0; i < sizeof *noise; i++) bytes[i] = 0;
}

} // namespace

#if DSN_READS_SECTIONS
const dsn_noise_state *dsn_internal_lattice_view(const dsn_noise_state *noise, dsn_noise_state *view) {
    if (noise->asset.lattice_texton == 0) return noise;
    *view = *noise;
    view->asset.texton = noise->asset.lattice_texton;
    view->asset.width = noise->asset.lattice_width;
    view->asset.height = noise->asset.lattice_height;
    view->asset.shape = DSN_SHAPE_RECTANGLE;
    view->radius[0] = (view->asset.width - 1) / 2;
    view->radius[1] = (view->asset.height - 1) / 2;
    return view;
}
#endif

#if DSN_NOISE_CHECK
namespace {

uint32_t pointer_word(const void *pointer) {
    const uint64_t bits = static_cast<uint64_t>(reinterpret_cast<uintptr_t>(pointer));
    return static_cast<uint32_t>(bits ^ (bits >> 32));
}

} // namespace

/* Not tile_kernel: every id gives the same bits and dsn_kernel_entries_of takes an id out of range as the
   default kernel, so the tests choose a copy's kernel without sealing it again.
   Fourteen words (small fields packed, as they are stored), each times its own odd constant and summed:
   independent products, not a chain of dependent ones, so a few cycles per call; then mixed (murmur3's
   finalizer) so that every input bit moves the result. */
uint32_t dsn_internal_state_check(const dsn_noise_state *noise) {
    const dsn_asset &asset = noise->asset;
    uint32_t sum = 0x6A09E667u;
    sum += pointer_word(asset.texton) * 0x9E3779B1u;
    sum += pointer_word(asset.pyramid) * 0x85EBCA77u;
    sum += pointer_word(asset.lattice_texton) * 0xC2B2AE3Du;
    sum += pointer_word(asset.histogram_table) * 0x27D4EB2Fu;
    sum += (asset.channels | asset.bits << 8 | asset.shape << 16 | asset.interpolation << 24) * 0x165667B1u;
    sum += (asset.width | asset.height << 16) * 0xD3A2646Du;
    sum += asset.support_size * 0xFD7046C5u;
    sum += (asset.pyramid_levels | asset.histogram_levels << 8 | asset.histogram_step_shift << 16 |
            noise->cell_shift << 24) *
           0xB55A4F09u;
    sum += (asset.histogram_entries | noise->gain_shift << 16) * 0x7FEB352Du;
    sum += (asset.lattice_width | asset.lattice_height << 16) * 0x846CA68Bu;
    sum += (noise->radius[0] | noise->radius[1] << 16) * 0x2C1B3C6Du;
    sum += (noise->poisson_parts | noise->poisson_size << 16 | noise->flags << 24) * 0x297A2D39u;
    sum += noise->period[0] * 0x68E31DA5u + noise->period[1] * 0xB5297A4Fu + noise->impacts_q16 * 0x1B873593u;
    sum ^= sum >> 16;
    sum *= 0x85EBCA6Bu;
    sum ^= sum >> 13;
    sum *= 0xC2B2AE35u;
    return sum ^ (sum >> 16);
}
#endif

extern "C" const char *dsn_version(void) { return DSN_VERSION_STRING; }

extern "C" uint32_t dsn_noise_channels(const dsn_noise *handle) {
    return dsn_configured(dsn_state(handle)) ? dsn_state(handle)->asset.channels : 0u;
}

extern "C" void dsn_config_defaults(dsn_config *config) {
    if (config == 0) return;
    config->seed = 0;
    config->impacts_q16 = 0;
    config->period_x = 0;
    config->period_y = 0;
    config->flags = 0;
}

extern "C" int dsn_noise_init(dsn_noise *handle, const dsn_asset *asset, const dsn_config *config) {
    dsn_noise_state *noise = dsn_state(handle);
    if (noise == 0 || asset == 0 || config == 0) return DSN_ERR_NULL;
    clear_noise(noise);
    if (!asset_is_usable(asset) || (config->flags & ~DSN_FLAGS_ALL) != 0) return DSN_ERR_ARGUMENT;
    uint32_t impacts = config->impacts_q16 != 0          ? config->impacts_q16
                       : asset->default_impacts_q16 != 0 ? asset->default_impacts_q16
                                                         : DSN_IMPACTS_DEFAULT_Q16;
    if (impacts < DSN_IMPACTS_MIN_Q16 || impacts > DSN_IMPACTS_MAX_Q16) return DSN_ERR_IMPACTS;
    /* Every period 1 .. 2^32 - 1 is valid (0 = none): nothing to check. */

    noise->asset = *asset;
#if DSN_HISTOGRAM
    if (config->flags & DSN_FLAG_NO_HISTOGRAM) noise->asset.histogram_table = 0; /* Gaussian-space values */
#endif
    noise->seed = config->seed;
    noise->seed_column = dsn_mix32(config->seed ^ 0x68E31DA4u);
    noise->seed_row = dsn_mix32(config->seed + 0xB5297A4Du);
    noise->flags = config->flags;
    noise->tile_kernel = dsn_internal_choose_kernel();
    noise->impacts_q16 = impacts;
    noise->period[0] = config->period_x;
    noise->period[1] = config->period_y;
    noise->radius[0] = (asset->width - 1) / 2;
    noise->radius[1] = (asset->height - 1) / 2;
    uint64_t mean_q32 = 0;
    noise->cell_shift = choose_cell_shift(asset, impacts, &mean_q32);
    dsn_internal_build_poisson_table(noise, mean_q32);
    dsn_internal_compute_normalization(noise);
#if DSN_FILTERING
    dsn_internal_compute_level_margins(noise);
#endif
#if DSN_CHECKS_COST
    if (dsn_internal_point_cost(noise) > DSN_MAX_POINT_IMPULSES) {
        clear_noise(noise);
        return DSN_ERR_COST;
    }
#endif
#if DSN_NOISE_CHECK
    noise->check = dsn_internal_state_check(noise);
#endif
    return DSN_OK;
}
