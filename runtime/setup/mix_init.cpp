/* runtime/setup/mix_init.cpp - dsn_mix_init: copies the materials onto the impulse process of material 0,
   which the whole mix shares, normalized for its density; finds the walks' reach and bounds their cost;
   and the small helpers of the mixing API. */
#include "core/cell_hash.h"
#include "core/normalize_fixed.h"
#include "setup/init_internal.h"
#include "setup/mix_state.h"

#if DSN_MIXING

namespace {

void clear_mix(dsn_mix_state *mix) {
    unsigned char *bytes = static_cast<unsigned char *>(static_cast<void *>(mix));
    for (size_t i = 0; i < sizeof *mix; i++) bytes[i] = 0;
}

uint32_t larger(uint32_t a, uint32_t b) { return a > b ? a : b; }

/* The material as the mix reads it: its noise on the impulse process of `lead` (its seed, cells, Poisson
   table and periods), normalized for that process's density lambda (impacts_q16 / (2^16 support_size),
   which the normalization reads from these two fields, restored after). Its own evaluators then give
   the mix where its weights are this material's alone. */
dsn_noise_state material_on_process(const dsn_noise_state *noise, const dsn_noise_state *lead) {
    dsn_noise_state material = *noise;
    material.impacts_q16 = lead->impacts_q16;
    material.asset.support_size = lead->asset.support_size;
    dsn_internal_compute_normalization(&material);
    material.impacts_q16 = noise->impacts_q16;
    material.asset.support_size = noise->asset.support_size;
    material.seed = lead->seed;
    material.seed_column = lead->seed_column;
    material.seed_row = lead->seed_row;
    material.cell_shift = lead->cell_shift;
    material.period[0] = lead->period[0];
    material.period[1] = lead->period[1];
    material.poisson_parts = lead->poisson_parts;
    material.poisson_size = lead->poisson_size;
    for (uint32_t i = 0; i < sizeof material.poisson_cdf / sizeof material.poisson_cdf[0]; i++)
        material.poisson_cdf[i] = lead->poisson_cdf[i];
    for (uint32_t i = 0; i < sizeof material.poisson_guide; i++)
        material.poisson_guide[i] = lead->poisson_guide[i];
#if DSN_NOISE_CHECK
    material.check = dsn_internal_state_check(&material);
#endif
    return material;
}

/* Whether two windows have one size and radius. */
bool same_window(const dsn_texton_window &a, const dsn_texton_window &b) {
    return a.width == b.width && a.height == b.height && a.radius[0] == b.radius[0] &&
           a.radius[1] == b.radius[1];
}

/* The mix's dsn_mix_alike_* bits (mix_state.h). */
uint32_t alike_textons(const dsn_mix_state *mix) {
    const dsn_noise_state *lead = &mix->material[0];
    uint32_t alike = dsn_mix_alike_textons | dsn_mix_alike_lattice_textons;
    for (uint32_t m = 1; m < mix->count; m++) {
        const dsn_noise_state *material = &mix->material[m];
        if (material->asset.channels != lead->asset.channels || material->asset.bits != lead->asset.bits)
            return 0;
        if (!same_window(dsn_continuous_texton_window(material), dsn_continuous_texton_window(lead)))
            alike &= ~static_cast<uint32_t>(dsn_mix_alike_textons);
        if (!same_window(dsn_lattice_texton_window(material), dsn_lattice_texton_window(lead)))
            alike &= ~static_cast<uint32_t>(dsn_mix_alike_lattice_textons);
    }
    return alike;
}

} // namespace

/* As dsn_internal_state_check: each word times its own odd constant, summed (independent products, a few
   cycles on every call), then mixed so that every input bit moves the result. */
uint32_t dsn_internal_mix_check(const dsn_mix_state *mix) {
    uint32_t sum = 0x4D495821u;
    sum += (mix->count | mix->channels << 8 | mix->alike << 16) * 0x165667B1u;
    sum += (mix->radius[0] | mix->radius[1] << 16) * 0xD3A2646Du;
    sum += (mix->lattice_radius[0] | mix->lattice_radius[1] << 16) * 0xFD7046C5u;
    for (uint32_t m = 0; m < mix->count && m < DSN_MIX_MAX_MATERIALS; m++)
        sum += mix->material[m].check * (0x9E3779B1u + 0x3C6EF372u * m); /* odd factors */
    return dsn_mix32(sum);
}

extern "C" {

int dsn_mix_init(dsn_mix *handle, const dsn_noise *const *materials, uint32_t count) {
    dsn_mix_state *mix = dsn_mix_state_of(handle);
    if (mix == 0) return DSN_ERR_NULL;
    clear_mix(mix);
    if (materials == 0) return DSN_ERR_NULL;
    if (count == 0 || count > DSN_MIX_MAX_MATERIALS) return DSN_ERR_ARGUMENT;
    for (uint32_t m = 0; m < count; m++)
        if (!dsn_configured(dsn_state(materials[m]))) return DSN_ERR_NULL;
    for (uint32_t m = 0; m < count; m++)
        if (dsn_has_mapping(dsn_state(materials[m]))) return DSN_ERR_UNSUPPORTED;

    const dsn_noise_state *lead = dsn_state(materials[0]);
    mix->count = count;
    mix->channels = 1;
    for (uint32_t m = 0; m < count; m++) {
        const dsn_noise_state material = material_on_process(dsn_state(materials[m]), lead);
        const dsn_texton_window lattice = dsn_lattice_texton_window(&material);
        mix->channels = larger(mix->channels, material.asset.channels);
        for (uint32_t axis = 0; axis < 2; axis++) {
            mix->radius[axis] = larger(mix->radius[axis], material.radius[axis]);
            mix->lattice_radius[axis] = larger(mix->lattice_radius[axis], lattice.radius[axis]);
        }
        mix->material[m] = material;
    }
    mix->alike = alike_textons(mix);
    /* The continuous walk covers X - 1 .. X + 1 with its radius, the lattice walk the point with its own. */
    const uint64_t continuous =
        dsn_internal_walk_cost(lead, 2u * mix->radius[0] + 3u, 2u * mix->radius[1] + 3u);
    const uint64_t lattice =
        dsn_internal_walk_cost(lead, 2u * mix->lattice_radius[0] + 1u, 2u * mix->lattice_radius[1] + 1u);
    if (continuous > DSN_MAX_POINT_IMPULSES || lattice > DSN_MAX_POINT_IMPULSES) {
        clear_mix(mix);
        return DSN_ERR_COST;
    }
    mix->check = dsn_internal_mix_check(mix);
    return DSN_OK;
}

uint32_t dsn_mix_channels(const dsn_mix *handle) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    return dsn_mix_configured(mix) ? mix->channels : 0u;
}

/* From the float's bits, as the coordinate conversions are, with no float arithmetic: 255 w rounded half
   up, for w in [0, 1]. */
uint8_t dsn_mix_weight_from_float(float weight) {
    uint32_t bits;
    __builtin_memcpy(&bits, &weight, sizeof bits);
    if ((bits & 0x80000000u) != 0 || bits > 0x7F800000u) return 0; /* negative (or -0), NaN */
    if (bits >= 0x3F800000u) return 255;                           /* 1 and above, +infinity */
    /* 0 <= w < 1: floor(w 2^32) is below 2^32 and exact to 2^-32; then 255 w + 1/2, floored. */
    const uint64_t fixed = static_cast<uint64_t>(dsn_coordinate_from_float(weight));
    return static_cast<uint8_t>((fixed * 255u + (static_cast<uint64_t>(1) << 31)) >> 32);
}

} // extern "C"

#endif /* DSN_MIXING */
