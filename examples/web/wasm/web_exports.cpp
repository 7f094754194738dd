/* web_exports.cpp - what the JavaScript module (examples/web/dsn.mjs) needs besides the C API: the size of
   a dsn_asset, and compile-time checks of the wasm32 struct layouts that the module reads and writes
   directly (dsn_asset fields, dsn_config, dsn_grid, dsn_mix, dsn_mix_control), so that a change to one of
   them fails this build instead of silently garbling the page. */
#include <stddef.h>
#include <stdint.h>

#include "dsn/dsn.h"

static_assert(sizeof(void *) == 4, "built for wasm32 only");
/* dsn.mjs: ASSET_FIELDS. */
static_assert(offsetof(dsn_asset, channels) == 8, "dsn_asset.channels moved");
static_assert(offsetof(dsn_asset, bits) == 12, "dsn_asset.bits moved");
static_assert(offsetof(dsn_asset, interpolation) == 20, "dsn_asset.interpolation moved");
static_assert(offsetof(dsn_asset, width) == 24 && offsetof(dsn_asset, height) == 28, "texton size moved");
static_assert(offsetof(dsn_asset, default_impacts_q16) == 36, "dsn_asset.default_impacts_q16 moved");
/* dsn.mjs: writeConfig (five uint32) and writeGrid (six int64). */
static_assert(sizeof(dsn_config) == 20 && offsetof(dsn_config, seed) == 0 &&
                  offsetof(dsn_config, impacts_q16) == 4 && offsetof(dsn_config, period_x) == 8 &&
                  offsetof(dsn_config, period_y) == 12 && offsetof(dsn_config, flags) == 16,
              "dsn_config layout changed");
static_assert(sizeof(dsn_grid) == 48 && offsetof(dsn_grid, origin_y) == 8 &&
                  offsetof(dsn_grid, column_step_x) == 16 && offsetof(dsn_grid, row_step_y) == 40,
              "dsn_grid layout changed");
static_assert(sizeof(dsn_noise) == DSN_NOISE_BYTES, "dsn_noise size");
/* dsn.mjs: MIX_BYTES and writeControl (a pointer and six uint32 or int32). */
static_assert(sizeof(dsn_mix) == 4640, "dsn_mix size");
static_assert(sizeof(dsn_mix_control) == 28 && offsetof(dsn_mix_control, width) == 4 &&
                  offsetof(dsn_mix_control, spacing_shift) == 12 &&
                  offsetof(dsn_mix_control, origin_x) == 16 && offsetof(dsn_mix_control, flags) == 24,
              "dsn_mix_control layout changed");

/* dsn.mjs: SURFACE_BYTES (a dsn_surface_frame after three int64 and two float[3]). */
static_assert(sizeof(dsn_surface_frame) == 36, "dsn_surface_frame size");
/* dsn.mjs: the footprint after them, 88 bytes into SURFACE_BYTES. */
static_assert(sizeof(dsn_footprint) == 40 && offsetof(dsn_footprint, max_taps) == 32, "dsn_footprint layout");

extern "C" {

uint32_t dsn_web_asset_bytes(void) { return sizeof(dsn_asset); }

} // extern "C"
