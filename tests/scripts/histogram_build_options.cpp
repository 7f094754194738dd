// histogram_build_options.cpp - the loader and init under the build options of the histogram mapping
// (dsn.h, DSN_HISTOGRAM; format.h, steps 8 and 16), on the cross test's assets: a build with the mapping
// loads the two 1.2 assets (with their pyramids, DSN_FILTERING or not) and maps their values, one
// without it refuses them with DSN_ERR_UNSUPPORTED, skips step 16 for a file without the flag, and its
// init refuses a hand-filled mapping. Built and run by tests/scripts/histogram-build-options. Prints
// one line per failed check; exits 1 when any failed.
#include <stdio.h>
#include <string.h>

#include "../../runtime/format_bytes.h"
#include "../cross/golden_assets.h"
#include "dsn/dsn.h"

namespace {

int failures = 0;

void check(bool condition, const char *what, const char *asset) {
    if (condition) return;
    printf("histogram-build-options (DSN_HISTOGRAM %d, DSN_FILTERING %d): %s: %s\n", DSN_HISTOGRAM,
           DSN_FILTERING, asset, what);
    failures++;
}

unsigned char copy[4096];

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
    return failures == 0 ? 0 : 1;
}
