// dsn/asset_writer.h - serializes the fields of a .dsnt asset (format.h) into the bytes of the file.
//
// Offline C++ API (part of libdsn_bake.a, usable without the rest of the baker: it needs no FFT). The
// writer refuses any field the runtime loader would reject, so every asset it produces loads:
// encode_asset() throws std::invalid_argument naming the first bad field.
//
//     dsn::AssetFields fields;               // defaults: grey, 8-bit, 1x1 rectangle, identity transform
//     fields.width = fields.height = 3;
//     fields.scale[0] = 1u << 30;            // texton value = q * 2^-10
//     fields.texton.assign(9, 0);
//     fields.texton[4] = 100;
//     std::vector<unsigned char> bytes = dsn::encode_asset(fields); // write them to spot.dsnt
#ifndef DSN_ASSET_WRITER_H
#define DSN_ASSET_WRITER_H

#include <cstdint>
#include <vector>

#include "dsn/format.h"

namespace dsn {

// One level of the texton pyramid (format 1.1, format.h): width x height (odd, 1..255) quantized values
// per channel, row-major, channels interleaved, standing for q * scale[c] * 2^exponent / 2^40.
struct PyramidLevel {
    uint32_t width = 1;
    uint32_t height = 1;
    int32_t exponent = 0; // DSN_PYRAMID_EXPONENT_MIN .. DSN_PYRAMID_EXPONENT_MAX
    std::vector<int32_t> values;
};

// The histogram mapping (format 1.2, format.h, section kind 2): per decorrelated channel k and level l,
// a table of entry_count Q3.12 values T[l][k][i] standing for the Gaussian-space input
// input_low_q16 / 2^16 + i 2^-step_shift, then the rotation back to colours. Empty `tables` (the default)
// writes no mapping.
struct HistogramMapping {
    uint32_t entry_count = 65; // N: 2 .. DSN_HISTOGRAM_MAX_ENTRIES
    uint32_t level_count = 1;  // M: 1 .. 1 + pyramid levels
    uint32_t step_shift = 3;   // s: 0 .. DSN_HISTOGRAM_MAX_STEP_SHIFT
    int32_t input_low_q16 = -(4 << 16);
    int32_t rotation[9] = {DSN_Q24_ONE, 0, 0, 0, DSN_Q24_ONE, 0, 0, 0, DSN_Q24_ONE}; // Q8.24
    int32_t centre[3] = {0, 0, 0};                                                   // Q8.24
    int32_t expected_q16[3] = {0, 0, 0}; // Q16.16, within +-DSN_HISTOGRAM_EXPECTED_LIMIT
    std::vector<int32_t> tables;         // M * channels * N values, index (l * channels + k) * N + i
};

// Every header field of format 1.0, in its stored fixed-point form, plus the quantized texton values
// (width * height * channels, row-major from the top row, channels interleaved), and the optional
// pyramid and histogram mapping: with neither the file is a 1.0 file, with levels only a 1.1 file with
// one pyramid section, with a mapping a 1.2 file, with a lattice texton a 1.3 file.
struct AssetFields {
    uint32_t channels = 1;
    uint32_t bits = 8;
    uint32_t shape = DSN_SHAPE_RECTANGLE;
    uint32_t interpolation = DSN_INTERPOLATION_LATTICE;
    uint32_t width = 1;
    uint32_t height = 1;
    uint32_t default_impacts_q16 = 0;
    uint32_t scale[3] = {0, 0, 0};
    int32_t mean[3] = {0, 0, 0};
    int32_t color_transform[9] = {DSN_Q24_ONE, 0, 0, 0, DSN_Q24_ONE, 0, 0, 0, DSN_Q24_ONE};
    uint32_t bake_iterations = 0;
    uint32_t bake_seed = 0;
    uint32_t bake_rme_q24 = 0;
    uint32_t exemplar_width = 0;
    uint32_t exemplar_height = 0;
    std::vector<int32_t> texton;
    std::vector<PyramidLevel> pyramid; // levels 1, 2, ...: at most DSN_PYRAMID_MAX_LEVELS
    HistogramMapping histogram;        // with tables: a 1.2 file with the flag and a kind-2 section
    // The lattice texton of a bilinear asset (format 1.3, section kind 3): lattice_width x lattice_height
    // values per channel at the texton's scale, summing per channel to the texton's sum. Empty (the
    // default) writes none; set_lattice_texton() fills it from the texton.
    uint32_t lattice_width = 0;
    uint32_t lattice_height = 0;
    std::vector<int32_t> lattice_texton;
};

// The identity colour transform for `channels` (grey: K[0] = 1, the other entries 0).
void set_identity_color_transform(AssetFields &fields);

// Fills the lattice texton of a bilinear asset from its quantized texton (format.h, version 1.3): the
// texton convolved with the two-tap filter whose power spectrum is the bilinear read's, one texel larger
// on each side, rounded with the per-channel sums kept exactly.
void set_lattice_texton(AssetFields &fields);
// The complete file: header (with the pyramid section when there are levels), texton, CRC. Throws
// std::invalid_argument on a field the loader rejects.
std::vector<unsigned char> encode_asset(const AssetFields &fields);

} // namespace dsn

#endif // DSN_ASSET_WRITER_H
