// dsn/asset_writer.h - serializes the fields of a .dsnt asset (format.h) and writes files atomically.
//
// Offline C++ API (part of libdsn_bake.a). The writer refuses any field the runtime loader would reject,
// so every asset it produces loads: encode_asset() throws std::invalid_argument naming the first bad
// field. write_file_atomically() never leaves a partial file and never clobbers the destination on
// failure: it writes a temporary file in the destination's folder, flushes it to disk and renames it
// over the destination.
//
//     dsn::AssetFields fields;               // defaults: grey, 8-bit, 1x1 rectangle, identity transform
//     fields.width = fields.height = 3;
//     fields.scale[0] = 1u << 30;            // texton value = q * 2^-10
//     fields.texton.assign(9, 0);
//     fields.texton[4] = 100;
//     dsn::write_file_atomically("spot.dsnt", dsn::encode_asset(fields));
#ifndef DSN_ASSET_WRITER_H
#define DSN_ASSET_WRITER_H

#include <cstdint>
#include <string>
#include <vector>

#include "dsn/format.h"

namespace dsn {

// Every header field of format 1.0, in its stored fixed-point form, plus the quantized texton values
// (width * height * channels, row-major from the top row, channels interleaved).
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
};

// The identity colour transform for `channels` (grey: K[0] = 1, the other entries 0).
void set_identity_color_transform(AssetFields &fields);

// The complete file: header, texton, CRC. Throws std::invalid_argument on a field the loader rejects.
std::vector<unsigned char> encode_asset(const AssetFields &fields);

// Writes `bytes` to `path` through a temporary file and a rename. Throws std::runtime_error with a
// one-line message ("cannot write out.dsnt: No space left on device"); the destination is then untouched.
void write_file_atomically(const std::string &path, const std::vector<unsigned char> &bytes);

// Writes several files as one: every temporary file is written and flushed before the first rename, so a
// failure (full disk, missing folder, a destination that is not a regular file) leaves none of them.
struct FileToWrite {
    std::string path;
    std::vector<unsigned char> bytes;
};
void write_files_atomically(const std::vector<FileToWrite> &files);

// True when both paths name the same file: the same existing file (device and inode), or, for paths
// that do not exist yet, the same name in the same folder.
bool same_file(const std::string &a, const std::string &b);

} // namespace dsn

#endif // DSN_ASSET_WRITER_H
