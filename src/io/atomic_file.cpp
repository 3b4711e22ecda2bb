#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace snell {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw std::runtime_error("cannot write '" + path + "': " + what);
}

/// Writes all of `bytes` to fd and flushes it to the device; false (errno set) on any failure.
bool write_all(int fd, const std::string& bytes) {
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        done += size_t(n);
    }
    return ::fsync(fd) == 0 || errno == EINVAL || errno == EROFS;  // devices may not sync
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& bytes) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) {
        // A device or pipe: written in place, each write checked (/dev/full reports ENOSPC).
        const int fd = ::open(path.c_str(), O_WRONLY);
        if (fd < 0) fail(path, std::strerror(errno));
        const bool ok = write_all(fd, bytes);
        const int err = errno;
        if (::close(fd) != 0 || !ok) fail(path, std::strerror(ok ? errno : err));
        return;
    }
    const fs::path target(path);
    std::string name = ".";  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on a + chain
    name += target.filename().string();
    name += ".tmp";
    name += std::to_string(::getpid());
    const fs::path tmp = target.parent_path() / name;
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) fail(path, std::string("cannot create a temporary file beside it: ") + std::strerror(errno));
    const bool ok = write_all(fd, bytes);
    const int err = errno;
    if (::close(fd) != 0 || !ok) {
        const std::string why = std::strerror(ok ? errno : err);
        fs::remove(tmp, ec);
        fail(path, why);
    }
    fs::rename(tmp, target, ec);
    if (ec) {
        fs::remove(tmp, ec);
        fail(path, "cannot move the finished file into place: " + ec.message());
    }
}

}  // namespace snell
