/* golden_assets.h - the fixed assets of the cross test (bytes in golden_assets.cpp, made by make-assets):
   four assets, and two of them again with a histogram mapping (format 1.2). */
#ifndef DSN_CROSS_GOLDEN_ASSETS_H
#define DSN_CROSS_GOLDEN_ASSETS_H

#include <stddef.h>

#define CROSS_ASSET_COUNT 4
#define CROSS_HISTOGRAM_ASSET_COUNT 2

typedef struct cross_asset {
    const char *name;
    const unsigned char *bytes;
    size_t size;
} cross_asset;

extern const cross_asset cross_assets[CROSS_ASSET_COUNT];
extern const cross_asset cross_histogram_assets[CROSS_HISTOGRAM_ASSET_COUNT];

#endif /* DSN_CROSS_GOLDEN_ASSETS_H */
