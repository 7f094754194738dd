// fuzz_asset_roundtrip.cpp - fuzzed fields and a tiny fuzzed texton -> writer -> loader -> the loader sees
// exactly the fields that were written; fields the writer refuses must be ones the loader would refuse.
#include <cstdint>
#include <stdexcept>

#include "dsn/asset_writer.h"
#include "dsn/dsn.h"
#include "fuzz_input.h"
#include "runtime/setup/format_bytes.h"

namespace {

dsn::AssetFields fuzzed_fields(FuzzInput &input) {
    dsn::AssetFields fields;
    const uint32_t choice = input.byte();
    fields.channels = (choice & 1u) ? 3u : 1u;
    fields.bits = (choice & 2u) ? 16u : 8u;
    fields.shape = (choice >> 2) & 1u;
    fields.interpolation = (choice >> 3) & 1u;
    fields.width = 1u + 2u * (input.byte() % 8u);
    fields.height = fields.shape == DSN_SHAPE_DISK ? fields.width : 1u + 2u * (input.byte() % 8u);
    fields.default_impacts_q16 = input.u32();
    for (uint32_t c = 0; c < fields.channels; c++) {
        fields.scale[c] = input.u32();
        fields.mean[c] = input.i32();
    }
    for (uint32_t i = 0; i < 9; i++) fields.color_transform[i] = input.i32();
    if (fields.channels == 1)
        for (uint32_t i = 1; i < 9; i++) fields.color_transform[i] = 0;
    fields.bake_iterations = input.u32();
    fields.bake_seed = input.u32();
    fields.bake_rme_q24 = input.u32();
    fields.exemplar_width = input.u32() & 0xFFFFu;
    fields.exemplar_height = input.u32() & 0xFFFFu;
    const int32_t limit = fields.bits == 8 ? 127 : 32767;
    for (uint32_t row = 0; row < fields.height; row++)
        for (uint32_t column = 0; column < fields.width; column++)
            for (uint32_t c = 0; c < fields.channels; c++) {
                int32_t value = int32_t(input.u32() % uint32_t(2 * limit + 1)) - limit;
                fields.texton.push_back(dsn_in_support(fields.shape, fields.width, row, column) ? value : 0);
            }
    return fields;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FuzzInput input(data, size);
    const dsn::AssetFields fields = fuzzed_fields(input);
    std::vector<unsigned char> bytes;
    try {
        bytes = dsn::encode_asset(fields);
    } catch (const std::invalid_argument &) {
        // Only the free-form fields can be refused: a zero scale or an out-of-range density.
        bool zero_scale = false;
        for (uint32_t c = 0; c < fields.channels; c++) zero_scale = zero_scale || fields.scale[c] == 0;
        const uint32_t impacts = fields.default_impacts_q16;
        fuzz_require(zero_scale ||
                     (impacts != 0 && (impacts < DSN_IMPACTS_MIN_Q16 || impacts > DSN_IMPACTS_MAX_Q16)));
        return 0;
    }
    dsn_asset asset;
    fuzz_require(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
    fuzz_require(asset.channels == fields.channels && asset.bits == fields.bits);
    fuzz_require(asset.shape == fields.shape && asset.interpolation == fields.interpolation);
    fuzz_require(asset.width == fields.width && asset.height == fields.height);
    fuzz_require(asset.default_impacts_q16 == fields.default_impacts_q16);
    for (uint32_t c = 0; c < 3; c++)
        fuzz_require(asset.scale[c] == fields.scale[c] && asset.mean[c] == fields.mean[c]);
    for (uint32_t i = 0; i < 9; i++) fuzz_require(asset.color_transform[i] == fields.color_transform[i]);
    fuzz_require(asset.bake_iterations == fields.bake_iterations && asset.bake_seed == fields.bake_seed);
    fuzz_require(asset.bake_rme_q24 == fields.bake_rme_q24);
    fuzz_require(asset.exemplar_width == fields.exemplar_width);
    fuzz_require(asset.exemplar_height == fields.exemplar_height);
    size_t index = 0;
    for (uint32_t row = 0; row < fields.height; row++)
        for (uint32_t column = 0; column < fields.width; column++)
            for (uint32_t c = 0; c < fields.channels; c++)
                fuzz_require(dsn_asset_texton_value(&asset, row, column, c) == fields.texton[index++]);
    return 0;
}
