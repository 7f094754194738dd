// gpu_pack_test.cpp - dsn_gpu_pack: the documented layout of dsn/gpu.h word by word against the configured
// noise (grey and RGB, 8 and 16 bits, periods, flags), and its argument errors (nothing written on an error);
// dsn_gpu_mix_pack likewise against the configured mix and its control.
// Whether dsn.glsl reads the words right is `make gpu-test`'s job.
#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include "dsn/gpu.h"
#include "fixtures/test_assets.h"
#include "runtime/setup/mix_state.h"
#include "runtime/setup/noise_state.h"

namespace {

using dsn_test::LoadedNoise;

uint64_t pair_at(const std::vector<uint32_t> &words, size_t index) {
    return uint64_t(words[index]) | uint64_t(words[index + 1]) << 32;
}

/* Words 208 .. 215: the surface offset, the offset less 3/32 of (mean - offset) (dsn.h, "Surface noise"),
   and the walk's cube bound, the support times 2^36 over c^2 impacts (Q16), at most 2^20. */
void check_surface_words(const dsn_noise_state &state, const std::vector<uint32_t> &words) {
    for (uint32_t c = 0; c < 3; c++) {
        int64_t expected = 0;
        if (c < state.asset.channels) {
            const int64_t mean = int64_t(state.asset.mean[c]) * (int64_t(1) << (state.gain_shift - 8));
            const int64_t excess = 3 * (mean - state.offset[c]); // no clamp needed: the fixtures are small
            expected = state.offset[c] - (excess >= 0 ? excess / 32 : -((-excess + 31) / 32));
        }
        CHECK(int64_t(pair_at(words, 208 + 2 * c)) == expected);
    }
    const uint64_t side = uint64_t(1) << state.cell_shift;
    const uint64_t cubes = (uint64_t(state.asset.support_size) << 36) / (side * side * state.impacts_q16);
    CHECK(words[214] == std::min<uint64_t>(cubes, DSN_MAX_POINT_IMPULSES));
    CHECK(words[215] == 0u);
}

void check_layout(const dsn_noise &noise) {
    const dsn_noise_state *state = dsn_state(&noise);
    const dsn_asset &asset = state->asset;
    const size_t count = dsn_gpu_word_count(&noise);
    const size_t texton_words = size_t(asset.width) * asset.height * asset.channels;
    const bool separate = asset.lattice_texton != nullptr;
    const uint32_t lattice_width = separate ? asset.lattice_width : asset.width;
    const uint32_t lattice_height = separate ? asset.lattice_height : asset.height;
    const size_t quad_words = 2 * size_t(asset.width + 1) * (asset.height + 1) * asset.channels;
    REQUIRE(count == DSN_GPU_HEADER_WORDS + texton_words +
                         (separate ? size_t(lattice_width) * lattice_height * asset.channels : 0u) +
                         quad_words);
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
    CHECK(words[47] == count - quad_words);
    for (size_t i = 0; i < 96; i++) CHECK(words[48 + i] == state->poisson_cdf[i]);
    for (size_t i = 0; i < 64; i++) CHECK(words[144 + i] == state->poisson_guide[i]);
    check_surface_words(*state, words);
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
    // The quads: quad (r, q) holds the texels (r - 1, q - 1), (r - 1, q) in its first word, (r, q - 1),
    // (r, q) in its second, 16 bits each, 0 outside the texton.
    for (uint32_t r = 0; r <= asset.height; r++)
        for (uint32_t q = 0; q <= asset.width; q++)
            for (uint32_t c = 0; c < asset.channels; c++)
                for (uint32_t corner = 0; corner < 4; corner++) {
                    const uint32_t word = words[index + corner / 2];
                    const int64_t row = int64_t(r) - 1 + corner / 2, column = int64_t(q) - 1 + corner % 2;
                    const bool inside = row >= 0 && row < asset.height && column >= 0 && column < asset.width;
                    const int32_t expected =
                        inside ? dsn_asset_texton_value(&asset, uint32_t(row), uint32_t(column), c) : 0;
                    differences += int32_t(int16_t(uint16_t(word >> (16 * (corner % 2))))) != expected;
                    if (corner == 3) index += 2;
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
    REQUIRE(count == DSN_GPU_HEADER_WORDS + 5 * 5 * 3 + 2 * 6 * 6 * 3); // the texton, its quads
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

#if DSN_MIXING
TEST_CASE("dsn_gpu_mix_pack writes the documented layout: the materials' packs, then the control") {
    LoadedNoise grey(dsn_test::synthetic_fields(1, 9, 8, DSN_SHAPE_RECTANGLE, 3), dsn_test::make_config(1));
    LoadedNoise rgb(dsn_test::synthetic_fields(3, 7, 16, DSN_SHAPE_DISK, 3),
                    dsn_test::make_config(9, 100, 13));
    const dsn_noise *materials[2] = {&grey.noise, &rgb.noise};
    dsn_mix mix;
    REQUIRE(dsn_mix_init(&mix, materials, 2) == DSN_OK);
    const dsn_mix_state *state = dsn_mix_state_of(&mix);
    // 3 x 2 samples of 2 bytes: 12 bytes, 3 words
    const uint8_t weights[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 255};
    const dsn_mix_control control = {weights, 3, 2, 5, -7, 11, DSN_MIX_PERIODIC_Y};
    const size_t count = dsn_gpu_mix_word_count(&mix, &control);
    const size_t first = dsn_gpu_word_count(dsn_mix_material_noise(state, 0));
    const size_t second = dsn_gpu_word_count(dsn_mix_material_noise(state, 1));
    REQUIRE(count == DSN_GPU_MIX_HEADER_WORDS + first + second + DSN_GPU_MIX_CONTROL_WORDS + 3);
    std::vector<uint32_t> words(count + 1, 0xDEADBEEFu);
    REQUIRE(dsn_gpu_mix_pack(&mix, &control, words.data(), count) == DSN_OK);
    CHECK(words[count] == 0xDEADBEEFu);
    CHECK(words[0] == DSN_GPU_MIX_MAGIC);
    CHECK(words[1] == DSN_GPU_LAYOUT_VERSION);
    CHECK(words[2] == count);
    CHECK(words[3] == 2u);
    CHECK(words[4] == 3u);
    CHECK(words[5] == state->radius[0]);
    CHECK(words[6] == state->radius[1]);
    CHECK(words[7] == state->lattice_radius[0]);
    CHECK(words[8] == state->lattice_radius[1]);
    CHECK(words[9] == DSN_GPU_MIX_HEADER_WORDS);
    CHECK(words[10] == DSN_GPU_MIX_HEADER_WORDS + first);
    CHECK(words[11] == 0u);
    CHECK(words[12] == 0u);
    const size_t control_start = DSN_GPU_MIX_HEADER_WORDS + first + second;
    CHECK(words[13] == control_start);
    CHECK(words[14] == 0u);
    CHECK(words[15] == 0u);
    // Each material is its own pack: material 1 on material 0's impulse process.
    for (uint32_t m = 0; m < 2; m++) {
        const dsn_noise *material = dsn_mix_material_noise(state, m);
        std::vector<uint32_t> own(dsn_gpu_word_count(material));
        REQUIRE(dsn_gpu_pack(material, own.data(), own.size()) == DSN_OK);
        CHECK(std::equal(own.begin(), own.end(), words.begin() + words[9 + m]));
    }
    CHECK(words[DSN_GPU_MIX_HEADER_WORDS + first + 12] == words[DSN_GPU_MIX_HEADER_WORDS + 12]); // seed
    const uint32_t *packed = words.data() + control_start;
    CHECK(packed[0] == 3u);
    CHECK(packed[1] == 2u);
    CHECK(packed[2] == 5u);
    CHECK(packed[3] == uint32_t(-7));
    CHECK(packed[4] == 11u);
    CHECK(packed[5] == DSN_MIX_PERIODIC_Y);
    CHECK(packed[6] == 0x04030201u);
    CHECK(packed[7] == 0x08070605u);
    CHECK(packed[8] == 0xFF0B0A09u);

    // A weight count that is not a multiple of 4: the last word's unused bytes are 0.
    const dsn_mix_control odd = {weights, 1, 3, 0, 0, 0, 0};
    const size_t odd_count = dsn_gpu_mix_word_count(&mix, &odd);
    REQUIRE(odd_count == control_start + DSN_GPU_MIX_CONTROL_WORDS + 2);
    std::vector<uint32_t> odd_words(odd_count, 0xDEADBEEFu);
    REQUIRE(dsn_gpu_mix_pack(&mix, &odd, odd_words.data(), odd_count) == DSN_OK);
    CHECK(odd_words[odd_count - 1] == 0x00000605u);
}

TEST_CASE("dsn_gpu_mix_pack: argument errors write nothing") {
    LoadedNoise loaded(dsn_test::synthetic_fields(3, 5, 8, DSN_SHAPE_RECTANGLE, 1), dsn_test::make_config(2));
    const dsn_noise *materials[1] = {&loaded.noise};
    dsn_mix mix;
    REQUIRE(dsn_mix_init(&mix, materials, 1) == DSN_OK);
    const uint8_t weights[4] = {255, 255, 255, 255};
    const dsn_mix_control control = {weights, 2, 2, 0, 0, 0, 0};
    const size_t count = dsn_gpu_mix_word_count(&mix, &control);
    REQUIRE(count ==
            DSN_GPU_MIX_HEADER_WORDS + dsn_gpu_word_count(&loaded.noise) + DSN_GPU_MIX_CONTROL_WORDS + 1);
    std::vector<uint32_t> words(count, 0xDEADBEEFu);
    CHECK(dsn_gpu_mix_pack(nullptr, &control, words.data(), count) == DSN_ERR_NULL);
    CHECK(dsn_gpu_mix_pack(&mix, nullptr, words.data(), count) == DSN_ERR_NULL);
    CHECK(dsn_gpu_mix_pack(&mix, &control, nullptr, count) == DSN_ERR_NULL);
    CHECK(dsn_gpu_mix_pack(&mix, &control, words.data(), count - 1) == DSN_ERR_ARGUMENT);
    dsn_mix_control no_weights = control, empty = control, wide = control, flagged = control;
    no_weights.weights = nullptr;
    empty.width = 0;
    wide.spacing_shift = 17;
    flagged.flags = 4;
    CHECK(dsn_gpu_mix_pack(&mix, &no_weights, words.data(), count) == DSN_ERR_NULL);
    for (const dsn_mix_control *bad : {&empty, &wide, &flagged}) {
        CHECK(dsn_gpu_mix_word_count(&mix, bad) == 0);
        CHECK(dsn_gpu_mix_pack(&mix, bad, words.data(), count) == DSN_ERR_ARGUMENT);
    }
    CHECK(dsn_gpu_mix_word_count(nullptr, &control) == 0);
    CHECK(dsn_gpu_mix_word_count(&mix, nullptr) == 0);
    // A mix whose init failed is zeroed: no words, and a null error (as the mix functions say).
    dsn_mix failed;
    CHECK(dsn_mix_init(&failed, materials, 0) == DSN_ERR_ARGUMENT);
    CHECK(dsn_gpu_mix_word_count(&failed, &control) == 0);
    CHECK(dsn_gpu_mix_pack(&failed, &control, words.data(), count) == DSN_ERR_NULL);
    for (uint32_t word : words) REQUIRE(word == 0xDEADBEEFu);
}
#endif
