// make-assets.cpp - writes tests/cross/golden_assets.cpp: the four fixed assets the golden program hashes,
// encoded once by the asset writer from fixed integers, each with the texton pyramid the baker makes of it
// (format 1.1: every target's loader, the small build's included, reads them), and two of them again
// with a histogram mapping (format 1.2), committed as byte arrays.
//
// The committed arrays, not this program, are the source of truth: every target of the cross test reads
// exactly those bytes. Run it (make cross-assets) only to change the assets on purpose, then update
// tests/cross/golden.txt in the same commit.
#include "dsn/asset_writer.h"
#include "offline/bake_internal.h"
#include "offline/tools/file_output.h"
#include "runtime/setup/format_bytes.h"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

// A fixed 32-bit linear congruential sequence (Numerical Recipes constants): the texton values only need
// to be varied and reproducible, not random.
struct FixedSequence {
    uint32_t state;
    int32_t next(int32_t limit) {
        state = state * 1664525u + 1013904223u;
        return int32_t((state >> 8) % uint32_t(2 * limit + 1)) - limit;
    }
};

struct NamedAsset {
    const char *name;
    dsn::AssetFields fields;
};

void fill_texton(dsn::AssetFields &fields, uint32_t sequence_seed) {
    const int32_t limit = fields.bits == 8 ? 127 : 32767;
    FixedSequence sequence{sequence_seed};
    fields.texton.clear();
    for (uint32_t row = 0; row < fields.height; row++)
        for (uint32_t column = 0; column < fields.width; column++)
            for (uint32_t c = 0; c < fields.channels; c++) {
                const int32_t value = sequence.next(limit);
                fields.texton.push_back(dsn_in_support(fields.shape, fields.width, row, column) ? value : 0);
            }
    // The extreme quantized values, so that every target decodes them.
    fields.texton[0] = fields.shape == DSN_SHAPE_DISK ? 0 : limit;
    fields.texton[fields.texton.size() / 2] = -limit;
}

// Grey, 8-bit, a non-square rectangle (catches swapped axes), lattice, no default density.
NamedAsset grey8() {
    NamedAsset asset{"grey8", {}};
    dsn::AssetFields &f = asset.fields;
    f.width = 7;
    f.height = 5;
    f.scale[0] = 480000000u;
    f.mean[0] = 7 << 21; // 0.4375
    dsn::set_identity_color_transform(f);
    f.bake_seed = 1;
    fill_texton(f, 11u);
    return asset;
}

// RGB, 8-bit, a disk of radius 4 baked for bilinear interpolation, a full colour transform with negative
// entries and a fractional default density.
NamedAsset rgb8() {
    NamedAsset asset{"rgb8", {}};
    dsn::AssetFields &f = asset.fields;
    f.channels = 3;
    f.shape = DSN_SHAPE_DISK;
    f.interpolation = DSN_INTERPOLATION_BILINEAR;
    f.width = f.height = 9;
    f.default_impacts_q16 = (12u << 16) + (1u << 15); // 12.5
    f.scale[0] = 300000000u;
    f.scale[1] = 410000000u;
    f.scale[2] = 123456789u;
    f.mean[0] = 9 << 21;
    f.mean[1] = 6 << 21;
    f.mean[2] = 3 << 21;
    const int32_t transform[9] = {18000000, -2000000, 1500000,  -900000, 16000000,
                                  700000,   3000000,  -4000000, 12000000};
    for (int i = 0; i < 9; i++) f.color_transform[i] = transform[i];
    fill_texton(f, 22u);
    return asset;
}

// Grey, 16-bit, a disk of radius 2, bilinear, a minimal default density.
NamedAsset grey16() {
    NamedAsset asset{"grey16", {}};
    dsn::AssetFields &f = asset.fields;
    f.bits = 16;
    f.shape = DSN_SHAPE_DISK;
    f.interpolation = DSN_INTERPOLATION_BILINEAR;
    f.width = f.height = 5;
    f.default_impacts_q16 = DSN_IMPACTS_MIN_Q16;
    f.scale[0] = 2100000u;
    f.mean[0] = 1 << 23; // 0.5
    dsn::set_identity_color_transform(f);
    f.color_transform[0] = 5 << 22; // 1.25
    fill_texton(f, 33u);
    return asset;
}

// RGB, 16-bit, a thin rectangle, lattice, "loud": scales and transform large enough that the Q16.16
// output saturates and the 8-bit conversion clamps at both ends.
NamedAsset rgb16() {
    NamedAsset asset{"rgb16", {}};
    dsn::AssetFields &f = asset.fields;
    f.channels = 3;
    f.bits = 16;
    f.width = 3;
    f.height = 7;
    f.default_impacts_q16 = 200u << 16;
    f.scale[0] = 0xFFFFFFFFu;
    f.scale[1] = 90000000u;
    f.scale[2] = 1u;
    f.mean[0] = -(100 << 24);
    f.mean[1] = 127 << 24;
    f.mean[2] = 0;
    const int32_t transform[9] = {INT32_MAX, INT32_MIN, 0, -(3 << 24), 1 << 24, 5 << 24, 0, 0, -(1 << 24)};
    for (int i = 0; i < 9; i++) f.color_transform[i] = transform[i];
    fill_texton(f, 44u);
    return asset;
}

// A histogram mapping from fixed integers (format 1.2): per level and channel an increasing table of 33
// entries (an odd cubic, flatter at coarser levels) over the 4 texels around the asset's first mean, a
// rotation with every entry used (RGB), a centre and an expected value per channel.
void add_histogram(dsn::AssetFields &f) {
    dsn::HistogramMapping &m = f.histogram;
    m.entry_count = 33;
    m.level_count = uint32_t(1 + f.pyramid.size());
    m.step_shift = 3;
    m.input_low_q16 = (f.mean[0] >> 8) - (2 << 16);
    m.tables.clear();
    for (uint32_t l = 0; l < m.level_count; l++)
        for (uint32_t k = 0; k < f.channels; k++)
            for (int32_t i = -16; i <= 16; i++)
                m.tables.push_back(i * (1200 - 150 * int32_t(l)) + i * i * i * int32_t(3 + k) / 4 +
                                   int32_t(k) * 300);
    const int32_t rotation[9] = {14000000, -5000000, 3000000, 6000000, 15000000,
                                 -2000000, -4000000, 2500000, 17000000};
    for (int i = 0; i < 9; i++) m.rotation[i] = f.channels == 3 || i == 0 ? rotation[i] : 0;
    for (uint32_t c = 0; c < f.channels; c++) {
        m.centre[c] = f.mean[c] + int32_t(c) * 100000;
        m.expected_q16[c] = 1000 - 700 * int32_t(c);
    }
}

std::string byte_array(const char *name, const std::vector<unsigned char> &bytes) {
    std::string text = "extern const unsigned char cross_asset_" + std::string(name) + "[" +
                       std::to_string(bytes.size()) + "] = {";
    for (size_t i = 0; i < bytes.size(); i++) {
        char number[16];
        std::snprintf(number, sizeof number, "%s0x%02x,", i % 16 == 0 ? "\n    " : " ", bytes[i]);
        text += number;
    }
    return text + "\n};\n";
}

// The table of `assets` named `table`.
std::string asset_table(const char *table, const std::vector<NamedAsset> &assets) {
    std::string text = "\nextern const cross_asset " + std::string(table) + "[] = {\n";
    for (const NamedAsset &asset : assets)
        text += "    {\"" + std::string(asset.name) + "\", cross_asset_" + asset.name +
                ", sizeof cross_asset_" + asset.name + "},\n";
    return text + "};\n";
}

std::string source_file(const std::vector<NamedAsset> &assets, const std::vector<NamedAsset> &mapped) {
    std::string text = "// golden_assets.cpp - the fixed assets of the cross test, as bytes. Written by "
                       "make-assets.cpp;\n// these arrays are the source of truth (see golden.txt).\n"
                       "// clang-format off\n#include \"golden_assets.h\"\n\n";
    for (const NamedAsset &asset : assets) text += byte_array(asset.name, dsn::encode_asset(asset.fields));
    for (const NamedAsset &asset : mapped) text += byte_array(asset.name, dsn::encode_asset(asset.fields));
    return text + asset_table("cross_assets", assets) + asset_table("cross_histogram_assets", mapped);
}

} // namespace

int main(int argc, char **argv) {
    if (argc != 2 || std::string(argv[1]) == "--help") {
        std::fprintf(argc == 2 ? stdout : stderr,
                     "usage: make-assets OUTPUT.cpp\n"
                     "Writes the cross test's fixed assets as C++ byte arrays.\n");
        return argc == 2 ? 0 : 2;
    }
    try {
        std::vector<NamedAsset> assets = {grey8(), rgb8(), grey16(), rgb16()};
        for (NamedAsset &asset : assets) asset.fields.pyramid = dsn::texton_pyramid(asset.fields);
        std::vector<NamedAsset> mapped = {{"hgrey8", assets[0].fields}, {"hrgb8", assets[1].fields}};
        for (NamedAsset &asset : mapped) add_histogram(asset.fields);
        const std::string text = source_file(assets, mapped);
        dsn::write_file_atomically(argv[1], std::vector<unsigned char>(text.begin(), text.end()));
    } catch (const std::exception &error) {
        std::fprintf(stderr, "make-assets: %s\n", error.what());
        return 1;
    }
    return 0;
}
