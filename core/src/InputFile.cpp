#include "fascia/base/InputFile.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace fascia::core {

namespace {

const char* typeName(mode_t mode) {
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

std::string bytes(std::uintmax_t n) { return std::to_string(n) + " bytes"; }

void checkStat(const struct stat& st, const std::string& path, const std::string& what, std::uintmax_t maxBytes,
               const SourceLoc& loc) {
    if (S_ISDIR(st.st_mode)) throwInputError(loc, "'" + path + "' is a folder, not a " + what);
    if (!S_ISREG(st.st_mode))
        throwInputError(loc, "'" + path + "' is " + typeName(st.st_mode) + ", not a " + what,
                        {"a " + what + " must be a regular file (it is read whole, so a pipe or a device is refused)"});
    if (std::uintmax_t(st.st_size) > maxBytes)
        throwInputError(loc, "'" + path + "' is " + bytes(std::uintmax_t(st.st_size)) + ", more than the " +
                                 bytes(maxBytes) + " a " + what + " may have");
}

} // namespace

std::uintmax_t requireRegularFile(const std::string& path, const std::string& what, std::uintmax_t maxBytes,
                                  const SourceLoc& loc) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        const int err = errno;
        if (err == ENOENT || err == ENOTDIR) throwInputError(loc, "cannot open '" + path + "': no such file");
        throwInputError(loc, "cannot open '" + path + "': " + std::strerror(err));
    }
    checkStat(st, path, what, maxBytes, loc);
    return std::uintmax_t(st.st_size);
}

std::string readRegularFile(const std::string& path, const std::string& what, std::uintmax_t maxBytes,
                            const SourceLoc& loc) {
    requireRegularFile(path, what, maxBytes, loc);
    // O_NONBLOCK: should the path have become a FIFO since the stat, open() returns at once
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        const int err = errno;
        throwInputError(loc, "cannot read '" + path + "' (" + std::strerror(err) + ")");
    }
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0) throwInputError(loc, "cannot read '" + path + "' (" + std::strerror(errno) + ")");
    checkStat(st, path, what, maxBytes, loc);
    std::string text(size_t(st.st_size) + 1, '\0');  // one byte more: filled only when the file grew
    size_t got = 0;
    for (;;) {
        if (got == text.size()) {
            if (got > maxBytes) break;
            text.resize(size_t(std::min<std::uintmax_t>(maxBytes + 1, std::max<std::uintmax_t>(2 * got, 4096))));
        }
        const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throwInputError(loc, "cannot read '" + path + "' (" + std::strerror(errno) + ")");
        if (n == 0) break;
        got += size_t(n);
    }
    if (got > maxBytes)
        throwInputError(loc, "'" + path + "' grew past the " + bytes(maxBytes) + " a " + what + " may have while it was read");
    text.resize(got);
    return text;
}

} // namespace fascia::core
