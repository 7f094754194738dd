// gpu_pack_test.cpp - dsn_gpu_pack: the documented layout of dsn/gpu.h word by word against the configured
// noise (grey and RGB, 8 and 16 bits, periods, flags), and its argument errors (nothing written on an error).
// Whether dsn.glsl reads the words right is `make gpu-test`'s job.
#include <doctest/doctest.h>

#include <vector>

#include "dsn/gpu.h"
#include "fixtures/test_assets.h"
#include "runtime/setup/noise_state.h"

namespace {

using dsn_test::LoadedNoise;

uint64_t pair_at(const std::vector<uint32_t> &words, size_t index) {
    return uint64_t(words[index]) | uint64_t(words[index + 1]) << 32;
}

void check_layout(const dsn_noise &noise) {
    const dsn_noise_state *state = dsn_state(&noise);
    const dsn_asset &asset = state->asset;
    const size_t count = dsn_gpu_word_count(&noise);
    const size_t texton_words = size_t(asset.width) * asset.height * asset.channels;
    const bool separate = asset.lattice_texton != nullptr;
    const uint32_t lattice_width = separate ? asset.lattice_width : asset.width;
    const uint32_t lattice_height = separate ? asset.lattice_height : asset.height;
    REQUIRE(count == DSN_GPU_HEADER_WORDS + texton_words +
                         (separate ? size_t(lattice_width) * lattice_height * asset.channels : 0u));
    std::vector<uint32_t> words(count + 1, 0xDEADBEEFu);
    REQUIRE(dsn_gpu_pack(&noise, words.data(), count) == DSN_OK);
    CHECK(words[count] == 0xDEADBEEFu); // nothing past the count
    CHECK(words[0] == DSN_GPU_MAGIC);
    CHECK(words[1] == DSN_GPU_LAYOUT_VERSION);
    CHECK(words[2] == count);
    CHECK(words[3] == asset.channels);
    CHECK(words[4] == asset.bits);
    CHECK(words[5] == asset.width);
    CHECK(words[6] == asset.height);
    CHECK(words[7] == state->radius[0]);
    CHECK(words[8] == state->radius[1]);
    CHECK(words[9] == state->cell_shift);
    CHECK(words[10] == state->period[0]);
    CHECK(words[11] == state->period[1]);
    CHECK(words[12] == state->seed_column);
    CHECK(words[13] == state->seed_row);
    CHECK(words[14] == state->gain_shift);
    CHECK(words[15] == state->poisson_parts);
    CHECK(words[16] == state->poisson_size);
    CHECK(words[17] == (dsn_continuous_check(&noise) == DSN_OK ? 1u : 0u));
    for (size_t i = 0; i < 9; i++) CHECK(pair_at(words, 18 + 2 * i) == uint64_t(state->gain[i]));
    for (size_t i = 0; i < 3; i++) CHECK(pair_at(words, 36 + 2 * i) == uint64_t(state->offset[i]));
    CHECK(words[42] == lattice_width);
    CHECK(words[43] == lattice_height);
    CHECK(words[44] == (lattice_width - 1) / 2);
    CHECK(words[45] == (lattice_height - 1) / 2);
    CHECK(words[46] == DSN_GPU_HEADER_WORDS + (separate ? texton_words : 0u));
    CHECK(words[47] == 0u);
    for (size_t i = 0; i < 96; i++) CHECK(words[48 + i] == state->poisson_cdf[i]);
    for (size_t i = 0; i < 64; i++) CHECK(words[144 + i] == state->poisson_guide[i]);
    size_t index = DSN_GPU_HEADER_WORDS, differences = 0;
    for (uint32_t row = 0; row < asset.height; row++)
        for (uint32_t column = 0; column < asset.width; column++)
            for (uint32_t c = 0; c < asset.channels; c++)
                differences += int32_t(words[index++]) != dsn_asset_texton_value(&asset, row, column, c);
    if (separate) { // the lattice texton follows, read as a texton of its own size
        dsn_asset lattice = asset;
        lattice.texton = asset.lattice_texton;
        lattice.width = lattice_width;
        lattice.height = lattice_height;
        for (uint32_t row = 0; row < lattice.height; row++)
            for (uint32_t column = 0; column < lattice.width; column++)
                for (uint32_t c = 0; c < asset.channels; c++)
                    differences +=
                        int32_t(words[index++]) != dsn_asset_texton_value(&lattice, row, column, c);
    }
    CHECK(index == count);
    CHECK(differences == 0);
}

} // namespace

TEST_CASE("dsn_gpu_pack writes the documented layout") {
    const struct {
        uint32_t channels, side, bits, shape;
        dsn_config config;
    } cases[] = {
        {1, 9, 8, DSN_SHAPE_RECTANGLE, dsn_test::make_config(1)},
        {3, 7, 16, DSN_SHAPE_DISK,
         dsn_test::make_config(0xFFFFFFFFu, 100, 13, 0, DSN_FLAG_NO_COLOR_TRANSFORM)},
        {3, 31, 8, DSN_SHAPE_DISK, dsn_test::make_config(77, 0.25, 0, 7, DSN_FLAG_ALLOW_LATTICE_CONTINUOUS)},
        {1, 3, 16, DSN_SHAPE_RECTANGLE, dsn_test::make_config(5, 1000)},
    };
    for (const auto &each : cases) {
        CAPTURE(each.channels);
        CAPTURE(each.side);
        LoadedNoise loaded(dsn_test::synthetic_fields(each.channels, each.side, each.bits, each.shape, 3),
                           each.config);
        check_layout(loaded.noise);
        dsn::AssetFields bilinear =
            dsn_test::synthetic_fields(each.channels, each.side, each.bits, each.shape, 3);
        bilinear.interpolation = DSN_INTERPOLATION_BILINEAR; // with its lattice texton (format 1.3)
        dsn::set_lattice_texton(bilinear);
        LoadedNoise with_lattice(bilinear, each.config);
        check_layout(with_lattice.noise);
    }
}

TEST_CASE("dsn_gpu_pack: argument errors write nothing") {
    LoadedNoise loaded(dsn_test::synthetic_fields(3, 5, 8, DSN_SHAPE_RECTANGLE, 1), dsn_test::make_config(2));
    const size_t count = dsn_gpu_word_count(&loaded.noise);
    REQUIRE(count == DSN_GPU_HEADER_WORDS + 5 * 5 * 3);
    std::vector<uint32_t> words(count, 0xDEADBEEFu);
    CHECK(dsn_gpu_pack(nullptr, words.data(), count) == DSN_ERR_NULL);
    CHECK(dsn_gpu_pack(&loaded.noise, nullptr, count) == DSN_ERR_NULL);
    CHECK(dsn_gpu_pack(&loaded.noise, words.data(), count - 1) == DSN_ERR_ARGUMENT);
    CHECK(dsn_gpu_word_count(nullptr) == 0);

    // A noise whose init failed is zeroed: no words, and an argument error.
    dsn_noise failed;
    dsn_config bad = dsn_test::make_config(2);
    bad.flags = 0x80u;
    CHECK(dsn_noise_init(&failed, &loaded.asset, &bad) == DSN_ERR_ARGUMENT);
    CHECK(dsn_gpu_word_count(&failed) == 0);
    CHECK(dsn_gpu_pack(&failed, words.data(), count) == DSN_ERR_ARGUMENT);
    for (uint32_t word : words) REQUIRE(word == 0xDEADBEEFu);
}
