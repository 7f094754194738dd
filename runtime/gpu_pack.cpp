/* runtime/gpu_pack.cpp - dsn_gpu_pack: a configured noise as the 32-bit words that dsn/dsn.glsl reads
   (the layout is documented in dsn/gpu.h). */
#include "dsn/gpu.h"
#include "noise_state.h"

namespace {

const uint32_t cdf_words = 96, guide_words = 64;
const uint32_t cdf_first = 48, guide_first = cdf_first + cdf_words;

static_assert(sizeof(dsn_noise_state::poisson_cdf) == cdf_words * sizeof(uint32_t),
              "the layout holds the whole Poisson table");
static_assert(sizeof(dsn_noise_state::poisson_guide) == guide_words,
              "the layout holds the whole Poisson guide");
static_assert(guide_first + guide_words == DSN_GPU_HEADER_WORDS, "the texton follows the guide");

/* The low and high words of an int64, two's complement, without implementation-defined conversions. */
void put_int64(uint32_t *words, uint32_t index, int64_t value) {
    const uint64_t bits = static_cast<uint64_t>(value);
    words[index] = static_cast<uint32_t>(bits);
    words[index + 1] = static_cast<uint32_t>(bits >> 32);
}

/* A configured noise has a texton; dsn_noise_init zeroes the noise when it fails. */
const dsn_noise_state *configured(const dsn_noise *handle) {
    const dsn_noise_state *noise = dsn_state(handle);
    return noise != 0 && noise->asset.texton != 0 ? noise : 0;
}

} // namespace

extern "C" size_t dsn_gpu_word_count(const dsn_noise *handle) {
    const dsn_noise_state *noise = configured(handle);
    if (noise == 0) return 0;
    return DSN_GPU_HEADER_WORDS + size_t(noise->asset.width) * noise->asset.height * noise->asset.channels;
}

extern "C" int dsn_gpu_pack(const dsn_noise *handle, uint32_t *words, size_t capacity) {
    if (handle == 0 || words == 0) return DSN_ERR_NULL;
    const dsn_noise_state *noise = configured(handle);
    const size_t count = dsn_gpu_word_count(handle);
    if (noise == 0 || capacity < count) return DSN_ERR_ARGUMENT;
    const dsn_asset *asset = &noise->asset;

    for (uint32_t i = 0; i < DSN_GPU_HEADER_WORDS; i++) words[i] = 0;
    words[0] = DSN_GPU_MAGIC;
    words[1] = DSN_GPU_LAYOUT_VERSION;
    words[2] = static_cast<uint32_t>(count);
    words[3] = asset->channels;
    words[4] = asset->bits;
    words[5] = asset->width;
    words[6] = asset->height;
    words[7] = noise->radius[0];
    words[8] = noise->radius[1];
    words[9] = noise->cell_shift;
    words[10] = noise->period[0];
    words[11] = noise->period[1];
    words[12] = noise->seed_column;
    words[13] = noise->seed_row;
    words[14] = noise->gain_shift;
    words[15] = noise->poisson_parts;
    words[16] = noise->poisson_size;
    words[17] = dsn_continuous_check(handle) == DSN_OK ? 1u : 0u;
    for (uint32_t i = 0; i < 9; i++) put_int64(words, 18 + 2 * i, noise->gain[i]);
    for (uint32_t i = 0; i < 3; i++) put_int64(words, 36 + 2 * i, noise->offset[i]);
    for (uint32_t i = 0; i < cdf_words; i++) words[cdf_first + i] = noise->poisson_cdf[i];
    for (uint32_t i = 0; i < guide_words; i++) words[guide_first + i] = noise->poisson_guide[i];

    /* The texton through the loader's reader: whole values, whatever the asset's byte layout. */
    uint32_t *texton = words + DSN_GPU_HEADER_WORDS;
    for (uint32_t row = 0; row < asset->height; row++)
        for (uint32_t column = 0; column < asset->width; column++)
            for (uint32_t c = 0; c < asset->channels; c++)
                *texton++ = static_cast<uint32_t>(dsn_asset_texton_value(asset, row, column, c));
    return DSN_OK;
}
