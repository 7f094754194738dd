// asset_file.h - reads a .dsnt file for a tool and says in one line why one cannot be used (part of
// libdsn_tools.a): every tool that reads assets (dsn-inspect, dsn-render, dsn-gpu-render, dsn-contact-sheet)
// reads them here, so they refuse the same files with the same words (dsn-tiny-renderer, which links the
// runtime alone, has a reader of its own with the same limit).
//
//     dsn_asset asset;
//     const std::vector<unsigned char> bytes = dsn::load_asset_file("wood.dsnt", asset);
//     // asset points into bytes; throws std::runtime_error with the line to print
#ifndef DSN_TOOLS_ASSET_FILE_H
#define DSN_TOOLS_ASSET_FILE_H

#include <cstddef>
#include <string>
#include <vector>

#include "dsn/dsn.h"

namespace dsn {

// The largest .dsnt file of the format this library reads (include/dsn/format.h): the header, the
// texton, every section of a known kind at its largest, the CRC. A larger file is not an asset.
size_t largest_asset_bytes();

// The file's bytes, at most largest_asset_bytes(), read by read_input_file (offline/file_input.h): throws
// std::runtime_error: "cannot read PATH: No such file or directory" (the system's reason), "cannot read
// PATH: not a regular file" (a FIFO, a device, a folder), or "PATH is too large: larger than the limit of
// N bytes for a dsn asset".
std::vector<unsigned char> read_asset_file(const std::string &path);

// The line that says why `bytes` (read from `path`) failed dsn_asset_load with `error`: for an image
// (PNG, JPEG, GIF, BMP, PSD, HDR or PNM by its first bytes) "PATH is an image, not a dsn asset: bake it
// first: dsn-bake PATH -o NAME.dsnt", else "PATH is not a dsn asset: " and dsn_error_message(error).
std::string asset_problem(const std::string &path, const std::vector<unsigned char> &bytes, int error);

// read_asset_file, then dsn_asset_load into `asset` (which then points into the returned bytes); throws
// std::runtime_error with read_asset_file's or asset_problem's line.
std::vector<unsigned char> load_asset_file(const std::string &path, dsn_asset &asset);

} // namespace dsn

#endif // DSN_TOOLS_ASSET_FILE_H
