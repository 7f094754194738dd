// file_output.h - writes the tools' output files atomically. Part of libdsn_tools.a.
//
// write_file_atomically() never leaves a partial file and never clobbers the destination on failure: it
// writes a temporary file in the destination's folder, flushes it to disk and renames it over the
// destination. A signal that ends the process (SIGTERM, SIGINT, SIGHUP... any left at its default action)
// removes the temporary files first, then ends it as that signal would have.
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
// as hard links until all renames are done), so a run commits all its outputs or none. The renames
// happen under an exclusive flock() of each destination folder, so two runs writing the same files
// leave one run's whole set (never one run's asset with the other's report).
struct FileToWrite {
    std::string path;
    std::vector<unsigned char> bytes;
};
void write_files_atomically(const std::vector<FileToWrite> &files);

// A file a run reads or writes, named for the error messages by its flag ("-o", "--report") or its role
// ("the input image").
struct NamedPath {
    std::string name;
    std::string path;
};

// Checks a run's outputs before any work is done, so that a mistake is not found only when they are
// written, minutes later: UsageError (exit 2) for an empty name, an output that is one of the inputs ("output
// PATH is the input image") or another output ("--report PATH is the same file as -o"), and an output whose
// folder is missing, is no folder, or cannot be written in; std::runtime_error ("cannot write PATH: not a
// regular file") for an existing destination that is a folder, a device or a FIFO.
void check_outputs(const std::vector<NamedPath> &inputs, const std::vector<NamedPath> &outputs);

// True when both paths name the same file: the same existing file (device and inode), or, for paths
// that do not exist yet, the same name in the same folder.
bool same_file(const std::string &a, const std::string &b);

} // namespace dsn

#endif // DSN_TOOLS_FILE_OUTPUT_H
