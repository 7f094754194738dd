// altered_state_test.cpp - what init and the evaluators do with inputs that the loader and init did not
// leave as they were: a dsn_asset whose pyramid or lattice texton fields (or the bytes they point at)
// changed after the load is refused by dsn_noise_init (DSN_ERR_ARGUMENT), and a dsn_noise that init never
// wrote (garbage bytes, or a configured one whose key fields changed) is refused by every evaluator as a
// noise not configured, its output zeroed as for a null noise (one value per point) and not beyond.
#include <doctest/doctest.h>

#include <cstring>
#include <random>
#include <vector>

#include "dsn/asset_writer.h"
#include "dsn/dsn.h"
#include "dsn/gpu.h"
#include "fixtures/test_assets.h"
#include "runtime/setup/noise_state.h"

namespace {

// A grey bilinear asset with two pyramid levels and its lattice texton (format 1.3).
dsn::AssetFields layered_fields() {
    dsn::AssetFields fields = dsn_test::synthetic_fields(1, 7, 8, DSN_SHAPE_RECTANGLE, 5);
    fields.interpolation = DSN_INTERPOLATION_BILINEAR;
    for (uint32_t side : {5u, 3u}) {
        dsn::PyramidLevel level;
        level.width = level.height = side;
        level.values.assign(size_t(side) * side, 9);
        fields.pyramid.push_back(level);
    }
    dsn::set_lattice_texton(fields);
    return fields;
}

int init_with(const dsn_asset &asset) {
    dsn_config config;
    dsn_config_defaults(&config);
    dsn_noise noise;
    return dsn_noise_init(&noise, &asset, &config);
}

} // namespace

TEST_CASE("altered asset: init re-reads the pyramid and lattice texton and refuses changed fields or bytes") {
    std::vector<unsigned char> bytes = dsn::encode_asset(layered_fields());
    dsn_asset loaded;
    REQUIRE(dsn_asset_load(&loaded, bytes.data(), bytes.size()) == DSN_OK);
    REQUIRE(loaded.pyramid_levels == 2);
    REQUIRE(loaded.lattice_texton != nullptr);
    CHECK(init_with(loaded) == DSN_OK);

    dsn_asset altered = loaded;
    altered.pyramid_levels = 3; // more records than the section holds: the walks would read past it
    CHECK(init_with(altered) == DSN_ERR_ARGUMENT);
    altered.pyramid_levels = 1; // fewer: the values would be read from a record
    CHECK(init_with(altered) == DSN_ERR_ARGUMENT);
    altered = loaded;
    altered.pyramid += DSN_PYRAMID_RECORD_SIZE; // the second record read as the first
    CHECK(init_with(altered) == DSN_ERR_ARGUMENT);
    altered = loaded;
    altered.pyramid = nullptr; // levels claimed without a pyramid
    CHECK(init_with(altered) == DSN_ERR_ARGUMENT);
    altered = loaded;
    altered.lattice_width += 2; // a wider window than the values stored
    CHECK(init_with(altered) == DSN_ERR_ARGUMENT);
    altered = loaded;
    altered.lattice_texton = nullptr; // sizes without a texton
    CHECK(init_with(altered) == DSN_ERR_ARGUMENT);
    altered = loaded;
    altered.lattice_texton += 1; // the values read one byte off
    CHECK(init_with(altered) == DSN_ERR_ARGUMENT);

    // The bytes changed after the load: level 1's record made 255 x 5 (the section's size no longer
    // matches), then the level-2 exponent out of range.
    unsigned char *record = const_cast<unsigned char *>(loaded.pyramid);
    record[0] = 255;
    CHECK(init_with(loaded) == DSN_ERR_ARGUMENT);
    record[0] = 5;
    CHECK(init_with(loaded) == DSN_OK);
    record[DSN_PYRAMID_RECORD_SIZE + 2] = 100;
    CHECK(init_with(loaded) == DSN_ERR_ARGUMENT);
}

namespace {

// Every evaluator family on `noise`, each expected to refuse it as not configured: the error code each
// documents for that, out[0] (or one value per point) zeroed, and nothing past it written.
void check_refused(const dsn_noise &noise) {
    const int32_t sentinel = 0x5A5A5A5A;
    CHECK(dsn_noise_channels(&noise) == 0);
    CHECK(dsn_continuous_check(&noise) == DSN_ERR_NULL);

    int32_t fixed[DSN_MAX_CHANNELS] = {sentinel, sentinel, sentinel};
    dsn_lattice_point_fixed(&noise, 3, 4, fixed);
    CHECK(fixed[0] == 0);
    CHECK(fixed[1] == sentinel);
    float floats[DSN_MAX_CHANNELS] = {7.0f, 7.0f, 7.0f};
    dsn_lattice_point_float(&noise, 3, 4, floats);
    CHECK(floats[0] == 0.0f);
    CHECK(floats[1] == 7.0f);
    uint8_t bytes[DSN_MAX_CHANNELS] = {7, 7, 7};
    dsn_lattice_point_u8(&noise, 3, 4, bytes);
    CHECK(bytes[0] == 0);
    CHECK(bytes[1] == 7);

    // Tiles and batches: width * height (count) values zeroed, the rest untouched.
    const uint32_t width = 4, height = 3, values = width * height;
    std::vector<int32_t> tile(values * 3, sentinel);
    CHECK(dsn_lattice_tile_scratch_size(&noise, width, height) == 0);
    CHECK(dsn_lattice_tile_fixed(&noise, 0, 0, width, height, tile.data(), nullptr, 0) == DSN_ERR_ARGUMENT);
    for (size_t i = 0; i < tile.size(); i++) CHECK(tile[i] == (i < values ? 0 : sentinel));

    const int64_t one = DSN_COORDINATE_ONE;
    fixed[0] = fixed[1] = sentinel;
    CHECK(dsn_continuous_point_fixed(&noise, one / 3, one * 5, fixed) == DSN_ERR_NULL);
    CHECK(fixed[0] == 0);
    CHECK(fixed[1] == sentinel);
    floats[0] = floats[1] = 7.0f;
    CHECK(dsn_sample(&noise, 1.5f, 2.5f, floats) == DSN_ERR_NULL);
    CHECK(floats[0] == 0.0f);
    CHECK(floats[1] == 7.0f);
    floats[0] = floats[1] = 7.0f;
    CHECK(dsn_noise_mean_float(&noise, floats) == DSN_ERR_NULL);
    CHECK(floats[0] == 0.0f);
    CHECK(floats[1] == 7.0f);

    const dsn_grid grid{0, 0, one / 2, 0, 0, one / 2};
    std::vector<unsigned char> scratch(1 << 16);
    CHECK(dsn_continuous_tile_scratch_size(&noise, &grid, width, height) == 0);
    std::fill(tile.begin(), tile.end(), sentinel);
    CHECK(dsn_continuous_tile_fixed(&noise, &grid, width, height, tile.data(), scratch.data(),
                                    scratch.size()) == DSN_ERR_NULL);
    for (size_t i = 0; i < tile.size(); i++) CHECK(tile[i] == (i < values ? 0 : sentinel));

    const std::vector<int64_t> xs(values, one), ys(values, one);
    CHECK(dsn_continuous_batch_scratch_size(&noise) == 0);
    std::fill(tile.begin(), tile.end(), sentinel);
    CHECK(dsn_continuous_batch_fixed(&noise, xs.data(), ys.data(), values, tile.data(), scratch.data(),
                                     scratch.size()) == DSN_ERR_NULL);
    for (size_t i = 0; i < tile.size(); i++) CHECK(tile[i] == (i < values ? 0 : sentinel));

    dsn_footprint footprint;
    REQUIRE(dsn_footprint_from_float(&footprint, 3.0, 0.0, 0.0, 1.0, 4) == DSN_OK);
    int32_t lod = 1;
    uint32_t taps = 1;
    CHECK(dsn_filter_level(&noise, &footprint, &lod, &taps) == DSN_ERR_NULL);
    fixed[0] = fixed[1] = sentinel;
    CHECK(dsn_filtered_point_fixed(&noise, one, one, &footprint, fixed) == DSN_ERR_NULL);
    CHECK(fixed[0] == 0);
    CHECK(fixed[1] == sentinel);
    const dsn_grid minified{0, 0, 3 * one, 0, 0, 3 * one};
    CHECK(dsn_filtered_tile_scratch_size(&noise, &minified, 4, width, height) == 0);
    std::fill(tile.begin(), tile.end(), sentinel);
    CHECK(dsn_filtered_tile_fixed(&noise, &minified, 4, width, height, tile.data(), scratch.data(),
                                  scratch.size()) == DSN_ERR_NULL);
    for (size_t i = 0; i < tile.size(); i++) CHECK(tile[i] == (i < values ? 0 : sentinel));

    std::vector<uint32_t> words(4096, 1);
    CHECK(dsn_gpu_word_count(&noise) == 0);
    CHECK(dsn_gpu_pack(&noise, words.data(), words.size()) == DSN_ERR_ARGUMENT);
}

} // namespace

TEST_CASE("garbage noise: a dsn_noise that init never wrote is refused by every evaluator") {
    dsn::AssetFields fields = dsn_test::synthetic_fields(3, 31, 8, DSN_SHAPE_DISK, 3);
    fields.interpolation = DSN_INTERPOLATION_BILINEAR;
    dsn_test::LoadedNoise loaded(fields, dsn_test::make_config(11));
    // A configured noise and its memcpy are configured.
    dsn_noise copy;
    std::memcpy(&copy, &loaded.noise, sizeof copy);
    CHECK(dsn_noise_channels(&copy) == 3);
    int32_t value[DSN_MAX_CHANNELS];
    CHECK(dsn_continuous_point_fixed(&copy, 0, 0, value) == DSN_OK);

    SUBCASE("random bytes") {
        std::mt19937_64 random(20261128);
        for (int trial = 0; trial < 8; trial++) {
            dsn_noise garbage;
            for (uint64_t &word : garbage.words) word = random();
            CAPTURE(trial);
            check_refused(garbage);
        }
    }
    SUBCASE("a configured noise's bytes with a key field changed (a stale or partly overwritten noise)") {
        // Its texton pointer and channel count stay plausible: only the check value tells it apart. A
        // texton window of 255 x 255 over the 31 x 31 stored would read far past the asset's bytes.
        dsn_noise stale = loaded.noise;
        const size_t width_offset = offsetof(dsn_noise_state, asset) + offsetof(dsn_asset, width);
        const uint32_t wide = 255;
        std::memcpy(reinterpret_cast<unsigned char *>(&stale) + width_offset, &wide, sizeof wide);
        check_refused(stale);
    }
}
