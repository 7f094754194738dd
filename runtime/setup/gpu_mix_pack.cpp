/* runtime/setup/gpu_mix_pack.cpp - dsn_gpu_mix_pack: a configured mix and its control as the 32-bit words
   that dsn/dsn.glsl's mixing functions read (the layout is documented in dsn/gpu.h). */
#include "core/mix_weights.h"
#include "dsn/gpu.h"
#include "setup/mix_state.h"

#if DSN_MIXING

namespace {

/* The control's bytes of weights: width * height samples of one byte per material. */
size_t control_bytes(const dsn_mix_state *mix, const dsn_mix_control *control) {
    return static_cast<size_t>(control->width) * control->height * mix->count;
}

} // namespace

extern "C" size_t dsn_gpu_mix_word_count(const dsn_mix *handle, const dsn_mix_control *control) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    if (handle == 0 || !dsn_mix_configured(mix) || mix_control_check(control) != DSN_OK) return 0;
    size_t count =
        DSN_GPU_MIX_HEADER_WORDS + DSN_GPU_MIX_CONTROL_WORDS + (control_bytes(mix, control) + 3u) / 4u;
    for (uint32_t m = 0; m < mix->count; m++) count += dsn_gpu_word_count(dsn_mix_material_noise(mix, m));
    return count;
}

extern "C" int dsn_gpu_mix_pack(const dsn_mix *handle, const dsn_mix_control *control, uint32_t *words,
                                size_t capacity) {
    const dsn_mix_state *mix = dsn_mix_state_of(handle);
    if (handle == 0 || words == 0 || !dsn_mix_configured(mix)) return DSN_ERR_NULL;
    const int err = mix_control_check(control);
    if (err != DSN_OK) return err;
    const size_t count = dsn_gpu_mix_word_count(handle, control);
    if (capacity < count) return DSN_ERR_ARGUMENT;
    words[0] = DSN_GPU_MIX_MAGIC;
    words[1] = DSN_GPU_LAYOUT_VERSION;
    words[2] = static_cast<uint32_t>(count);
    words[3] = mix->count;
    words[4] = mix->channels;
    words[5] = mix->radius[0];
    words[6] = mix->radius[1];
    words[7] = mix->lattice_radius[0];
    words[8] = mix->lattice_radius[1];
    size_t next = DSN_GPU_MIX_HEADER_WORDS;
    for (uint32_t m = 0; m < DSN_MIX_MAX_MATERIALS; m++) {
        words[9 + m] = m < mix->count ? static_cast<uint32_t>(next) : 0u;
        if (m >= mix->count) continue;
        const dsn_noise *material = dsn_mix_material_noise(mix, m);
        /* A mix refuses materials with a histogram mapping, so every material packs. */
        const int packed = dsn_gpu_pack(material, words + next, capacity - next);
        if (packed != DSN_OK) return packed;
        next += dsn_gpu_word_count(material);
    }
    words[13] = static_cast<uint32_t>(next);
    words[14] = 0;
    words[15] = 0;
    uint32_t *at = words + next;
    at[0] = control->width;
    at[1] = control->height;
    at[2] = control->spacing_shift;
    at[3] = static_cast<uint32_t>(control->origin_x);
    at[4] = static_cast<uint32_t>(control->origin_y);
    at[5] = control->flags;
    at += DSN_GPU_MIX_CONTROL_WORDS;
    const size_t bytes = control_bytes(mix, control);
    for (size_t i = 0; i < (bytes + 3u) / 4u; i++) at[i] = 0;
    for (size_t i = 0; i < bytes; i++)
        at[i / 4u] |= static_cast<uint32_t>(control->weights[i]) << (8u * (i % 4u));
    return DSN_OK;
}

#endif /* DSN_MIXING */
