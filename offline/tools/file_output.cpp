// file_output.cpp - atomic file writes: a temporary file in the destination folder, fsync, rename; the
// temporary files removed on a fatal signal; several files committed under a lock on their folders; the
// output paths checked before a run.
#include "file_output.h"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <stdexcept>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>

#include "command_line.h"

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

// The temporary files that exist now (written, not yet renamed), for the signal handler below, which may
// neither allocate nor lock: a fixed table of names, each copied in before its slot is marked used. A run
// writes a few files at once; past the table's size a file is written unlisted.
struct TemporarySlot {
    volatile sig_atomic_t used;
    char path[4096];
};
TemporarySlot temporary_slots[16];

// The signals whose default action ends the process: on each, the temporary files are removed first.
// SIGXFSZ is ignored instead (PendingFile), so that the write fails with EFBIG and says so.
const int kCleanupSignals[] = {SIGHUP,  SIGINT,    SIGQUIT, SIGTERM, SIGPIPE, SIGALRM, SIGUSR1, SIGUSR2,
                               SIGXCPU, SIGVTALRM, SIGPROF, SIGABRT, SIGSEGV, SIGBUS,  SIGFPE,  SIGILL};

sigset_t cleanup_signal_set() {
    sigset_t set;
    sigemptyset(&set);
    for (int signal : kCleanupSignals) sigaddset(&set, signal);
    return set;
}

// Async-signal-safe: unlink(), then the signal again with its default action, so the process ends as that
// signal would have ended it (the exit status a shell or a supervisor expects).
extern "C" void remove_temporaries_and_end(int signal) {
    for (TemporarySlot &slot : temporary_slots)
        if (slot.used) ::unlink(slot.path);
    struct sigaction default_action;
    std::memset(&default_action, 0, sizeof default_action);
    default_action.sa_handler = SIG_DFL;
    ::sigaction(signal, &default_action, nullptr);
    ::raise(signal); // delivered when the handler returns (the signal is blocked while it runs)
}

// Installs the handler once, on the signals still at their default action: one the caller ignores (nohup's
// SIGHUP) stays ignored, and one a sanitizer or a debugger handles stays theirs.
void install_cleanup_handler() {
    static bool installed = false;
    if (installed) return;
    installed = true;
    for (int signal : kCleanupSignals) {
        struct sigaction current;
        if (::sigaction(signal, nullptr, &current) != 0 || current.sa_handler != SIG_DFL ||
            (current.sa_flags & SA_SIGINFO))
            continue;
        struct sigaction action;
        std::memset(&action, 0, sizeof action);
        action.sa_handler = remove_temporaries_and_end;
        action.sa_mask = cleanup_signal_set(); // one cleanup at a time
        ::sigaction(signal, &action, nullptr);
    }
}

// Blocks the cleanup signals in this thread for its lifetime: a name is listed in the same breath as it is
// created, and several renames happen with no signal in between (all or none).
class SignalsHeld {
  public:
    SignalsHeld() {
        const sigset_t set = cleanup_signal_set();
        ::pthread_sigmask(SIG_BLOCK, &set, &previous_);
    }
    ~SignalsHeld() { ::pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
    SignalsHeld(const SignalsHeld &) = delete;
    SignalsHeld &operator=(const SignalsHeld &) = delete;

  private:
    sigset_t previous_;
};

// The slot listing `path`, or -1 when the table is full or the name too long. Called with signals held.
int list_temporary(const char *path) {
    const size_t length = std::strlen(path);
    for (int i = 0; i < int(sizeof temporary_slots / sizeof *temporary_slots); i++) {
        TemporarySlot &slot = temporary_slots[i];
        if (slot.used || length >= sizeof slot.path) continue;
        std::memcpy(slot.path, path, length + 1);
        slot.used = 1;
        return i;
    }
    return -1;
}

void unlist_temporary(int slot) {
    if (slot >= 0) temporary_slots[slot].used = 0;
}

// mkstemp on `pattern`, the new name listed for the signal handler before any signal can arrive.
int make_listed_temporary(std::vector<char> &pattern, int *slot) {
    install_cleanup_handler();
    SignalsHeld held;
    const int fd = ::mkstemp(pattern.data());
    *slot = fd < 0 ? -1 : list_temporary(pattern.data());
    return fd;
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
        int fd = make_listed_temporary(temporary_, &temporary_slot_);
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
            unlist_temporary(temporary_slot_);
            fail_write(path, error);
        }
    }
    PendingFile(const PendingFile &) = delete;
    PendingFile &operator=(const PendingFile &) = delete;
    ~PendingFile() {
        if (!committed_) ::unlink(temporary_.data());
        if (!backup_.empty()) ::unlink(backup_.c_str());
        unlist_temporary(temporary_slot_);
        unlist_temporary(backup_slot_);
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
            int fd = make_listed_temporary(name, &backup_slot_);
            if (fd < 0) fail_write(path_, errno);
            ::close(fd);
            ::unlink(name.data());
            if (::link(path_.c_str(), name.data()) == 0) {
                backup_ = name.data();
                return;
            }
            const int error = errno;
            unlist_temporary(backup_slot_);
            backup_slot_ = -1;
            if (error != EEXIST) fail_write(path_, error);
        }
        fail_write(path_, EEXIST);
    }
    void commit() {
        if (::rename(temporary_.data(), path_.c_str()) != 0) fail_write(path_, errno);
        committed_ = true;
        unlist_temporary(temporary_slot_); // its name is the destination's now
        temporary_slot_ = -1;
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
    int temporary_slot_ = -1, backup_slot_ = -1; // in temporary_slots, for the signal handler
    bool committed_ = false;
};

} // namespace

// Exclusive flock()s on the folders of `paths`, taken in one order (device, inode) so that two runs
// locking the same folders cannot wait on each other, and released when it goes. A folder that cannot be
// locked (a file system without flock) is written unlocked, as before.
class FolderLocks {
  public:
    explicit FolderLocks(const std::vector<std::string> &paths) {
        std::vector<std::pair<std::pair<dev_t, ino_t>, int>> folders;
        for (const std::string &path : paths) {
            const int fd = ::open(folder_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
            struct stat status;
            if (fd < 0) continue;
            if (::fstat(fd, &status) != 0) {
                ::close(fd);
                continue;
            }
            folders.push_back({{status.st_dev, status.st_ino}, fd});
        }
        std::sort(folders.begin(), folders.end());
        for (size_t i = 0; i < folders.size(); i++) {
            if (i > 0 && folders[i].first == folders[i - 1].first) { // the same folder twice: one lock
                ::close(folders[i].second);
                continue;
            }
            while (::flock(folders[i].second, LOCK_EX) != 0 && errno == EINTR) {
            }
            fds_.push_back(folders[i].second);
        }
    }
    ~FolderLocks() {
        for (int fd : fds_) ::close(fd); // closing the folder releases its lock
    }
    FolderLocks(const FolderLocks &) = delete;
    FolderLocks &operator=(const FolderLocks &) = delete;

  private:
    std::vector<int> fds_;
};

void write_files_atomically(const std::vector<FileToWrite> &files) {
    for (size_t i = 0; i < files.size(); i++)
        for (size_t j = 0; j < i; j++)
            if (same_file(files[i].path, files[j].path))
                throw std::runtime_error("cannot write " + files[i].path + " twice in one run");
    std::vector<std::unique_ptr<PendingFile>> pending;
    for (const FileToWrite &file : files)
        pending.emplace_back(new PendingFile(file.path, file.bytes.data(), file.bytes.size()));
    // Two runs writing the same files (two bakes to one asset and report) commit one after the other, so
    // the files left are one run's set, never a mix; no signal ends a run between its renames.
    std::vector<std::string> paths;
    for (const FileToWrite &file : files) paths.push_back(file.path);
    const FolderLocks locks(paths);
    const SignalsHeld held;
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

void check_outputs(const std::vector<NamedPath> &inputs, const std::vector<NamedPath> &outputs) {
    for (size_t i = 0; i < outputs.size(); i++) {
        const NamedPath &output = outputs[i];
        if (output.path.empty()) throw UsageError(output.name + " needs a file name, not an empty one");
        for (const NamedPath &input : inputs)
            if (same_file(input.path, output.path))
                throw UsageError("output " + output.path + " is " + input.name);
        for (size_t j = 0; j < i; j++)
            if (same_file(outputs[j].path, output.path))
                throw UsageError(output.name + " " + output.path + " is the same file as " + outputs[j].name);
        const std::string folder = folder_of(output.path);
        struct stat status;
        const bool found = ::stat(folder.c_str(), &status) == 0;
        if (!found || !S_ISDIR(status.st_mode))
            throw UsageError(output.name + " " + output.path + ": its folder " + folder +
                             (found             ? " is not a folder"
                              : errno == ENOENT ? " does not exist"
                                                : std::string(": ") + std::strerror(errno)));
        if (::access(folder.c_str(), W_OK | X_OK) != 0)
            throw UsageError(output.name + " " + output.path + ": cannot write in its folder " + folder +
                             ": " + std::strerror(errno));
        if (::stat(output.path.c_str(), &status) == 0 && !S_ISREG(status.st_mode)) {
            if (S_ISDIR(status.st_mode)) fail_write(output.path, EISDIR);
            throw std::runtime_error("cannot write " + output.path + ": not a regular file");
        }
    }
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
