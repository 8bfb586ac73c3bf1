#include "util/FileInput.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "util/Activity.h"
#include "util/Error.h"
#include "util/TextEncoding.h"

namespace candela {

namespace {

/// What a file that is not regular is, in words.
const char* fileTypeName(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

/// "a" or "an" before `kind` as it is read aloud ("an image", "an L3D", "a GLDF").
std::string withArticle(const std::string& kind) {
    bool vowel = !kind.empty() && (std::string("aeiouAEIOU").find(kind[0]) != std::string::npos ||
                                   kind.starts_with("L3D"));
    return (vowel ? "an " : "a ") + kind;
}

/// An open descriptor, closed on every way out.
struct Descriptor {
    int fd = -1;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

/// Opens `path` without waiting (a FIFO with no writer would block a plain open) and checks what
/// was opened. Leaves the descriptor blocking again for reading.
std::uintmax_t openChecked(const std::string& path, const std::string& kind,
                           std::uintmax_t maxBytes, Descriptor& d) {
    const std::string shown = toValidUtf8(path);
    errno = 0;
    d.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (d.fd < 0) {
        int err = errno;
        throw InputError(shown + ": cannot open " + kind + " file (" +
                         (err ? std::strerror(err) : "unknown error") + ")");
    }
    struct stat st {};
    if (::fstat(d.fd, &st) != 0) {
        int err = errno;
        throw InputError(shown + ": cannot read " + kind + " file (" + std::strerror(err) + ")");
    }
    if (!S_ISREG(st.st_mode))
        throw InputError(shown + ": expected " + withArticle(kind) + " file, found " +
                         fileTypeName(st.st_mode));
    if (std::uintmax_t(st.st_size) > maxBytes)
        throw InputError(shown + ": expected " + withArticle(kind) + " file of at most " +
                         byteSize(maxBytes) + ", found " + byteSize(std::uintmax_t(st.st_size)));
    int flags = ::fcntl(d.fd, F_GETFL);
    if (flags >= 0) ::fcntl(d.fd, F_SETFL, flags & ~O_NONBLOCK);
    return std::uintmax_t(st.st_size);
}

}  // namespace

std::string byteSize(std::uintmax_t bytes) {
    char text[48];
    if (bytes >= (std::uintmax_t(1) << 30) && bytes % (std::uintmax_t(1) << 30) == 0)
        std::snprintf(text, sizeof text, "%ju GiB", bytes >> 30);
    else if (bytes >= (std::uintmax_t(1) << 30))
        std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1 << 30));
    else if (bytes >= (std::uintmax_t(1) << 20) && bytes % (std::uintmax_t(1) << 20) == 0)
        std::snprintf(text, sizeof text, "%ju MiB", bytes >> 20);
    else if (bytes >= (std::uintmax_t(1) << 20))
        std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
    else
        std::snprintf(text, sizeof text, "%ju bytes", bytes);
    return text;
}

std::uintmax_t checkInputFile(const std::string& path, const std::string& kind,
                              std::uintmax_t maxBytes) {
    Descriptor d;
    return openChecked(path, kind, maxBytes, d);
}

std::string readInputFile(const std::string& path, const std::string& kind,
                          std::uintmax_t maxBytes) {
    ScopedActivity activity("reading " + toValidUtf8(path) + " (" + kind + " file)");
    Descriptor d;
    std::uintmax_t size = openChecked(path, kind, maxBytes, d);
    std::string bytes;
    bytes.reserve(size_t(size));
    char buffer[1 << 16];
    for (;;) {
        ssize_t n = ::read(d.fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            int err = errno;
            throw InputError(toValidUtf8(path) + ": cannot read " + kind + " file (" +
                             std::strerror(err) + ")");
        }
        if (n == 0) break;
        bytes.append(buffer, size_t(n));
        if (bytes.size() > maxBytes)  // it grew while it was read
            throw InputError(toValidUtf8(path) + ": expected " + withArticle(kind) +
                             " file of at most " + byteSize(maxBytes) +
                             ", found more while reading it");
    }
    return bytes;
}

}  // namespace candela
