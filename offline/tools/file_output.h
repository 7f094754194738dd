// file_output.h - writes the tools' output files atomically. Part of libdsn_tools.a.
//
// write_file_atomically() never leaves a partial file and never clobbers the destination on failure: it
// writes a temporary file in the destination's folder, flushes it to disk and renames it over the
// destination.
//
//     dsn::write_file_atomically("spot.dsnt", dsn::encode_asset(fields));
#ifndef DSN_TOOLS_FILE_OUTPUT_H
#define DSN_TOOLS_FILE_OUTPUT_H

#include <cstddef>
#include <string>
#include <vector>

namespace dsn {

// Writes `bytes` to `path` through a temporary file and a rename. Throws std::runtime_error with a
// one-line message ("cannot write out.dsnt: No space left on device"); the destination is then untouched.
void write_file_atomically(const std::string &path, const std::vector<unsigned char> &bytes);
void write_file_atomically(const std::string &path, const unsigned char *bytes, size_t size);

// Writes several files as one: every temporary file is written and flushed before the first rename, so a
// failure (full disk, missing folder, a destination that is not a regular file) leaves none of them; and
// when a rename fails, the files already renamed are put back as they were (the previous files are kept
// as hard links until all renames are done), so a run commits all its outputs or none.
struct FileToWrite {
    std::string path;
    std::vector<unsigned char> bytes;
};
void write_files_atomically(const std::vector<FileToWrite> &files);

// True when both paths name the same file: the same existing file (device and inode), or, for paths
// that do not exist yet, the same name in the same folder.
bool same_file(const std::string &a, const std::string &b);

} // namespace dsn

#endif // DSN_TOOLS_FILE_OUTPUT_H
