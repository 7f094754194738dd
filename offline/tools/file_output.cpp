// file_output.cpp - atomic file writes: a temporary file in the destination folder, fsync, rename.
#include "file_output.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace dsn {
namespace {

std::string folder_of(const std::string &path) {
    size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

[[noreturn]] void fail_write(const std::string &path, int error) {
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(error));
}

bool write_all(int fd, const unsigned char *data, size_t size) {
    while (size > 0) {
        ssize_t written = ::write(fd, data, size);
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) return false;
        data += written;
        size -= size_t(written);
    }
    return true;
}

} // namespace

namespace {

// A written and flushed temporary file beside its destination, renamed into place by commit().
class PendingFile {
  public:
    PendingFile(const std::string &path, const unsigned char *bytes, size_t size) : path_(path) {
        // Past a file size limit (ulimit -f) the default action of SIGXFSZ kills the process before
        // the temporary file can be removed; ignored, write() fails with EFBIG and the file goes.
        std::signal(SIGXFSZ, SIG_IGN);
        // Renaming over a device, pipe or folder would replace it (or fail late): only regular files.
        struct stat existing;
        if (::stat(path.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode)) {
            if (S_ISDIR(existing.st_mode)) fail_write(path, EISDIR);
            throw std::runtime_error("cannot write " + path + ": not a regular file");
        }
        std::string pattern = folder_of(path) + "/.dsn-write-XXXXXX";
        temporary_.assign(pattern.begin(), pattern.end());
        temporary_.push_back('\0');
        int fd = ::mkstemp(temporary_.data());
        if (fd < 0) fail_write(path, errno);
        bool written = write_all(fd, bytes, size) && ::fsync(fd) == 0;
        int error = errno;
        if (::close(fd) != 0 && written) {
            written = false;
            error = errno;
        }
        // mkstemp creates the file 0600; give it the permissions an ordinary new file would have.
        mode_t mask = ::umask(0);
        ::umask(mask);
        if (written && ::chmod(temporary_.data(), 0666 & ~mask) != 0) {
            written = false;
            error = errno;
        }
        if (!written) {
            ::unlink(temporary_.data());
            fail_write(path, error);
        }
    }
    PendingFile(const PendingFile &) = delete;
    PendingFile &operator=(const PendingFile &) = delete;
    ~PendingFile() {
        if (!committed_) ::unlink(temporary_.data());
        if (!backup_.empty()) ::unlink(backup_.c_str());
    }
    // Keeps the destination's current file under a second name (a hard link), so that undo() can put it
    // back after the rename. Throws when that is impossible: then nothing has been renamed yet.
    void keep_previous() {
        struct stat existing;
        if (::lstat(path_.c_str(), &existing) != 0) return; // no previous file: undo() removes the new one
        for (int attempt = 0; attempt < 100; attempt++) {
            std::string pattern = folder_of(path_) + "/.dsn-keep-XXXXXX";
            std::vector<char> name(pattern.begin(), pattern.end());
            name.push_back('\0');
            int fd = ::mkstemp(name.data());
            if (fd < 0) fail_write(path_, errno);
            ::close(fd);
            ::unlink(name.data());
            if (::link(path_.c_str(), name.data()) == 0) {
                backup_ = name.data();
                return;
            }
            if (errno != EEXIST) fail_write(path_, errno);
        }
        fail_write(path_, EEXIST);
    }
    void commit() {
        if (::rename(temporary_.data(), path_.c_str()) != 0) fail_write(path_, errno);
        committed_ = true;
    }
    // Puts back what the destination held before commit().
    void undo() {
        if (!committed_) return;
        if (backup_.empty()) {
            ::unlink(path_.c_str());
        } else if (::rename(backup_.c_str(), path_.c_str()) == 0) {
            backup_.clear();
        }
    }

  private:
    std::string path_, backup_;
    std::vector<char> temporary_;
    bool committed_ = false;
};

} // namespace

void write_files_atomically(const std::vector<FileToWrite> &files) {
    for (size_t i = 0; i < files.size(); i++)
        for (size_t j = 0; j < i; j++)
            if (same_file(files[i].path, files[j].path))
                throw std::runtime_error("cannot write " + files[i].path + " twice in one run");
    std::vector<std::unique_ptr<PendingFile>> pending;
    for (const FileToWrite &file : files)
        pending.emplace_back(new PendingFile(file.path, file.bytes.data(), file.bytes.size()));
    // All or none: when one rename fails, the files already renamed are put back as they were.
    if (pending.size() > 1)
        for (auto &file : pending) file->keep_previous();
    for (size_t i = 0; i < pending.size(); i++) {
        try {
            pending[i]->commit();
        } catch (...) {
            for (size_t j = 0; j < i; j++) pending[j]->undo();
            throw;
        }
    }
}

void write_file_atomically(const std::string &path, const std::vector<unsigned char> &bytes) {
    write_file_atomically(path, bytes.data(), bytes.size());
}

void write_file_atomically(const std::string &path, const unsigned char *bytes, size_t size) {
    PendingFile file(path, bytes, size);
    file.commit();
}

bool same_file(const std::string &a, const std::string &b) {
    struct stat status_a, status_b;
    const bool exists_a = ::stat(a.c_str(), &status_a) == 0, exists_b = ::stat(b.c_str(), &status_b) == 0;
    if (exists_a && exists_b) return status_a.st_dev == status_b.st_dev && status_a.st_ino == status_b.st_ino;
    if (exists_a || exists_b) return false;
    const auto name = [](const std::string &path) {
        const size_t slash = path.find_last_of('/');
        return slash == std::string::npos ? path : path.substr(slash + 1);
    };
    struct stat folder_a, folder_b;
    return name(a) == name(b) && ::stat(folder_of(a).c_str(), &folder_a) == 0 &&
           ::stat(folder_of(b).c_str(), &folder_b) == 0 && folder_a.st_dev == folder_b.st_dev &&
           folder_a.st_ino == folder_b.st_ino;
}

} // namespace dsn
