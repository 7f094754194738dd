/* examples/c_api/main.c - the runtime from plain C99, with the asset compiled into the program.

   The build turns a small .dsnt file into example_asset.h (an array of bytes), so this program needs no
   file system: the way a microcontroller or a single-binary tool would ship a texture. It first takes
   the float path (load with a seed, sample at float texel coordinates, the mean colour), then the full
   API: loads and configures the asset step by step, evaluates a few lattice and continuous points, and
   checks that the float path gives the full API's bits and that a tile gives the same values as the
   per-point calls. Exit status 0 when every check passes. */
#include <stdio.h>
#include <string.h>

#include "dsn/dsn.h"
#include "example_asset.h" /* example_asset[], example_asset_size */

#define TILE_SIDE 8

static int check(int err, const char *what) {
    if (err != DSN_OK) fprintf(stderr, "c_api: %s: %s\n", what, dsn_error_message(err));
    return err == DSN_OK;
}

/* Tile evaluation without a heap: the scratch lives in a static buffer checked against the need. */
static unsigned char tile_scratch[1 << 16];

static int tile_matches_points(const dsn_noise *noise, int32_t x0, int32_t y0) {
    int32_t tile[TILE_SIDE * TILE_SIDE * DSN_MAX_CHANNELS], point[DSN_MAX_CHANNELS];
    uint32_t channels = dsn_noise_channels(noise), i, j, c;
    size_t need = dsn_lattice_tile_scratch_size(noise, TILE_SIDE, TILE_SIDE);
    if (need > sizeof tile_scratch) {
        fprintf(stderr, "c_api: the tile needs %lu bytes of scratch\n", (unsigned long)need);
        return 0;
    }
    if (!check(dsn_lattice_tile_fixed(noise, x0, y0, TILE_SIDE, TILE_SIDE, tile, tile_scratch,
                                      sizeof tile_scratch),
               "tile"))
        return 0;
    for (j = 0; j < TILE_SIDE; j++)
        for (i = 0; i < TILE_SIDE; i++) {
            dsn_lattice_point_fixed(noise, (int32_t)((uint32_t)x0 + i), (int32_t)((uint32_t)y0 + j), point);
            for (c = 0; c < channels; c++)
                if (point[c] != tile[(j * TILE_SIDE + i) * channels + c]) {
                    fprintf(stderr, "c_api: tile and point differ at (%lu, %lu)\n", (unsigned long)i,
                            (unsigned long)j);
                    return 0;
                }
        }
    return 1;
}

/* The float path: one call to load (the bytes must outlive the noise), one call per sample. */
static int float_path(dsn_noise *noise) {
    float rgb[DSN_MAX_CHANNELS], mean[DSN_MAX_CHANNELS];
    if (!check(dsn_noise_load(noise, example_asset, example_asset_size, 2024), "dsn_noise_load")) return 0;
    if (!check(dsn_sample(noise, 10.25f, -3.5f, rgb), "dsn_sample")) return 0;
    printf("sample (10.25, -3.5): %.6f %.6f %.6f\n", rgb[0], rgb[1], rgb[2]);
    /* What a renderer fades to where the texture is too fine to show. */
    if (!check(dsn_noise_mean_float(noise, mean), "dsn_noise_mean_float")) return 0;
    printf("mean: %.6f %.6f %.6f\n", mean[0], mean[1], mean[2]);
    return 1;
}

int main(void) {
    static const int32_t points[][2] = {{0, 0}, {1, 0}, {-1000, 77}, {2147483647, -2147483647 - 1}};
    dsn_noise quick;
    dsn_asset asset;
    dsn_config config;
    dsn_noise noise;
    float value[DSN_MAX_CHANNELS], sample[DSN_MAX_CHANNELS];
    uint8_t rgb[DSN_MAX_CHANNELS];
    unsigned p;

    if (!float_path(&quick)) return 1;

    /* The full API: the same noise, step by step, with every option at hand. */
    if (!check(dsn_asset_load(&asset, example_asset, example_asset_size), "load")) return 1;
    dsn_config_defaults(&config);
    config.seed = 2024;
    if (!check(dsn_noise_init(&noise, &asset, &config), "init")) return 1;
    printf("asset: %lu bytes, %lu channel(s), texton %lux%lu\n", (unsigned long)example_asset_size,
           (unsigned long)asset.channels, (unsigned long)asset.width, (unsigned long)asset.height);

    for (p = 0; p < sizeof points / sizeof points[0]; p++) {
        dsn_lattice_point_float(&noise, points[p][0], points[p][1], value);
        dsn_lattice_point_u8(&noise, points[p][0], points[p][1], rgb);
        printf("lattice (%ld, %ld): %.6f (u8 %u)\n", (long)points[p][0], (long)points[p][1], value[0],
               (unsigned)rgb[0]);
    }
    /* Continuous points in texels, e.g. texture coordinates times a texture size. */
    if (!check(dsn_continuous_point_float(&noise, 10.25, -3.5, value), "continuous")) return 1;
    printf("continuous (10.25, -3.5): %.6f\n", value[0]);
    /* The asset is bilinear-baked, so the float path configured it exactly as above. */
    if (!check(dsn_sample(&quick, 10.25f, -3.5f, sample), "sample") ||
        memcmp(sample, value, dsn_noise_channels(&noise) * sizeof value[0]) != 0) {
        fprintf(stderr, "c_api: the float path and the full API differ\n");
        return 1;
    }
    printf("float path == full API: ok\n");

    if (!tile_matches_points(&noise, -4, -4) || !tile_matches_points(&noise, 2147483644, 2147483644))
        return 1;
    printf("tile == per-point: ok\n");
    return 0;
}
