// histogram_build_options.cpp - the loader and init under the build options of the histogram mapping
// (dsn.h, DSN_HISTOGRAM; format.h, steps 8 and 16), on the cross test's assets: a build with the mapping
// loads the two 1.2 assets (with their pyramids, DSN_FILTERING or not) and maps their values, one
// without it refuses them with DSN_ERR_UNSUPPORTED, skips step 16 for a file without the flag, and its
// init refuses a hand-filled mapping; and a 1.3 bilinear asset's lattice texton, read or refused on the
// lattice by the builds that read sections or none. Built and run by tests/scripts/histogram-build-options.
// Prints one line per failed check; exits 1 when any failed.
#include <stdio.h>
#include <string.h>

#include "cross/golden_assets.h"
#include "dsn/dsn.h"
#include "runtime/setup/format_bytes.h"

namespace {

int failures = 0;

void check(bool condition, const char *what, const char *asset) {
    if (condition) return;
    printf("histogram-build-options (DSN_HISTOGRAM %d, DSN_FILTERING %d): %s: %s\n", DSN_HISTOGRAM,
           DSN_FILTERING, asset, what);
    failures++;
}

unsigned char copy[4096];

/* A 1.3 bilinear asset (the loader's fuzz seed with a lattice texton): a build that reads sections reads
   its lattice texton and evaluates it on the lattice; the small build, which reads none, refuses it on the
   lattice with DSN_ERR_UNSUPPORTED and zeroes the output, and reads it in continuous mode. */
void check_lattice_texton() {
    const char *name = "asset-27-lattice-texton.dsnt";
    FILE *file = fopen("tests/fuzz/corpus/asset_loader/asset-27-lattice-texton.dsnt", "rb");
    const size_t size = file != 0 ? fread(copy, 1, sizeof copy, file) : 0;
    if (file != 0) fclose(file);
    dsn_asset asset;
    dsn_noise noise;
    dsn_config config;
    dsn_config_defaults(&config);
    check(dsn_asset_load(&asset, copy, size) == DSN_OK, "a 1.3 asset loads", name);
    check(dsn_noise_init(&noise, &asset, &config) == DSN_OK, "init", name);
    int32_t tile[4 * 3] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1}, point[3] = {1, 1, 1}, continuous[3];
    const int tile_code = dsn_lattice_tile_fixed(&noise, 3, 4, 2, 2, tile, 0, 0);
    dsn_lattice_point_fixed(&noise, 3, 4, point);
    check(dsn_continuous_point_fixed(&noise, int64_t(3) << 32, int64_t(4) << 32, continuous) == DSN_OK,
          "the continuous mode reads it", name);
#if DSN_FILTERING || DSN_HISTOGRAM
    check(asset.lattice_texton != 0 && asset.lattice_width == asset.width + 2, "its lattice texton is read",
          name);
    check(tile_code == DSN_OK && tile[0] == point[0] && tile[1] == point[1] && tile[2] == point[2],
          "the lattice tile equals the lattice point", name);
#else
    check(asset.lattice_texton == 0, "no section is read", name);
    check(tile_code == DSN_ERR_UNSUPPORTED, "the lattice tile is refused", name);
    uint32_t nonzero = 0;
    for (int32_t value : tile) nonzero += value != 0;
    for (int32_t value : point) nonzero += value != 0;
    check(nonzero == 0, "the refused outputs are zeroed", name);
#endif
}

} // namespace

int main() {
    dsn_asset asset;
    for (uint32_t a = 0; a < CROSS_ASSET_COUNT; a++)
        check(dsn_asset_load(&asset, cross_assets[a].bytes, cross_assets[a].size) == DSN_OK,
              "a 1.1 asset loads", cross_assets[a].name);
    for (uint32_t a = 0; a < CROSS_HISTOGRAM_ASSET_COUNT; a++) {
        const cross_asset &bytes = cross_histogram_assets[a];
        const int code = dsn_asset_load(&asset, bytes.bytes, bytes.size);
        // The same file without the flag: step 16 refuses it, a build without the mapping skips it.
        if (bytes.size > sizeof copy) {
            check(false, "the copy holds the asset", bytes.name);
            continue;
        }
        memcpy(copy, bytes.bytes, bytes.size);
        dsn_write_u32le(copy + DSN_OFFSET_FLAGS, 0);
        dsn_write_u32le(copy + bytes.size - 4, dsn_crc32(0, copy, bytes.size - 4));
        dsn_asset unflagged;
        const int unflagged_code = dsn_asset_load(&unflagged, copy, bytes.size);
#if DSN_HISTOGRAM
        check(code == DSN_OK, "a 1.2 asset loads", bytes.name);
        check(asset.histogram_table != 0 && asset.pyramid_levels > 0 &&
                  asset.histogram_levels == asset.pyramid_levels + 1,
              "the mapping and the pyramid are read", bytes.name);
        check(unflagged_code == DSN_ERR_HISTOGRAM, "a kind-2 section without the flag is refused",
              bytes.name);
        dsn_config config;
        dsn_config_defaults(&config);
        dsn_noise mapped, gaussian;
        check(dsn_noise_init(&mapped, &asset, &config) == DSN_OK, "init", bytes.name);
        config.flags = DSN_FLAG_NO_HISTOGRAM;
        check(dsn_noise_init(&gaussian, &asset, &config) == DSN_OK, "init without the mapping", bytes.name);
        uint32_t differ = 0;
        for (int32_t x = 0; x < 16; x++) {
            int32_t a_value[3], b_value[3];
            dsn_lattice_point_fixed(&mapped, x, 3, a_value);
            dsn_lattice_point_fixed(&gaussian, x, 3, b_value);
            differ += a_value[0] != b_value[0];
        }
        check(differ > 0, "the mapping changes the values", bytes.name);
#else
        check(code == DSN_ERR_UNSUPPORTED, "a 1.2 asset with the flag is unsupported", bytes.name);
        check(unflagged_code == DSN_OK, "step 16 is skipped", bytes.name);
        // A mapping filled in by hand is refused rather than ignored.
        dsn_config config;
        dsn_config_defaults(&config);
        dsn_noise noise;
        check(dsn_noise_init(&noise, &unflagged, &config) == DSN_OK, "init", bytes.name);
        unflagged.histogram_table = copy;
        check(dsn_noise_init(&noise, &unflagged, &config) == DSN_ERR_ARGUMENT, "init refuses a mapping",
              bytes.name);
#endif
    }
    check_lattice_texton();
    return failures == 0 ? 0 : 1;
}
