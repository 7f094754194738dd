// file_input.h - read_input_file: the whole of an input file, read only when it is a regular file of at
// most a given size. Every tool reads its inputs here (the baker's images through load_exemplar, the
// assets through offline/tools/asset_file), so a FIFO, a device or a folder is refused at once with the
// same words instead of blocking the tool or filling its memory. Header-only, so that libdsn_bake.a and
// libdsn_tools.a share it without either library needing the other.
//
//     const std::vector<unsigned char> bytes = dsn::read_input_file(path, 1 << 20, "a notes file");
//     // throws std::runtime_error with the one line to print
#ifndef DSN_OFFLINE_FILE_INPUT_H
#define DSN_OFFLINE_FILE_INPUT_H

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace dsn {

// "256 MiB" or "3957062 bytes": a limit in the unit it was chosen in.
inline std::string input_limit_text(size_t limit) {
    const size_t mebibyte = size_t(1) << 20;
    return limit % mebibyte == 0 ? std::to_string(limit / mebibyte) + " MiB"
                                 : std::to_string(limit) + " bytes";
}

// The bytes of the file at `path`, at most `limit` of them. Throws std::runtime_error with one line:
//   "cannot read PATH: No such file or directory" (the system's reason),
//   "cannot read PATH: not a regular file" (a FIFO, a folder, a device, a socket),
//   "PATH is too large: larger than the limit of LIMIT for WHAT" (`what`: "a dsn asset").
// The file is opened without blocking (a FIFO with no writer would hang an ordinary open) and checked
// on the open descriptor, so what is read is what was checked; the read stops one byte past the limit,
// however large the file grows meanwhile.
inline std::vector<unsigned char> read_input_file(const std::string &path, size_t limit,
                                                  const std::string &what) {
    const auto cannot_read = [&path](const std::string &reason) {
        return std::runtime_error("cannot read " + path + ": " + reason);
    };
    const auto too_large = [&] {
        return std::runtime_error(path + " is too large: larger than the limit of " +
                                  input_limit_text(limit) + " for " + what);
    };
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) throw cannot_read(std::strerror(errno));
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat status;
    if (::fstat(fd, &status) != 0) throw cannot_read(std::strerror(errno));
    if (!S_ISREG(status.st_mode)) throw cannot_read("not a regular file");
    if (status.st_size < 0 || uint64_t(status.st_size) > limit) throw too_large();
    // A regular file may still grow after fstat: read at most one byte more than the limit.
    std::vector<unsigned char> bytes(size_t(status.st_size) + 1);
    size_t size = 0;
    for (;;) {
        if (size == bytes.size()) {
            if (size > limit) throw too_large();
            bytes.resize(std::min(limit + 1, 2 * size));
        }
        const ssize_t count = ::read(fd, bytes.data() + size, bytes.size() - size);
        if (count < 0 && errno == EINTR) continue;
        if (count < 0) throw cannot_read(std::strerror(errno));
        if (count == 0) break;
        size += size_t(count);
    }
    bytes.resize(size);
    return bytes;
}

} // namespace dsn

#endif // DSN_OFFLINE_FILE_INPUT_H
