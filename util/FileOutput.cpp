#include "util/FileOutput.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "util/Error.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

/// Longest part of the target's name copied into the temporary name, so that the temporary
/// name stays within the 255 bytes a file name may have on Linux file systems.
constexpr size_t kMaxNameInTemporary = 120;

/// New files get rw-r--r-- (what an ofstream gives under the usual umask 022).
constexpr mode_t kNewFileMode = 0644;

std::mutex& registryMutex() {
    static std::mutex mutex;
    return mutex;
}

/// Every live ProtectedInputs scope (registryMutex guards it and their entries).
std::vector<const ProtectedInputs*>& registry() {
    static std::vector<const ProtectedInputs*> scopes;
    return scopes;
}

/// The innermost InputReplacement of this thread (null: none).
thread_local const InputReplacement* tReplacement = nullptr;

std::string absolutePath(const std::string& path) {
    std::error_code ec;
    fs::path absolute = fs::absolute(path, ec);
    return (ec ? fs::path(path) : absolute).lexically_normal().string();
}

/// A new temporary file beside `target` whose name keeps the target's extension.
int createTemporary(const fs::path& dir, const fs::path& target, std::string& name) {
    std::string leaf = target.filename().string();
    std::string extension = target.extension().string();
    if (extension.size() > 16) extension.clear();  // no format would be named by it anyway
    std::string stem =
        leaf.substr(0, std::min(leaf.size() - extension.size(), kMaxNameInTemporary));
    name = (dir / ("." + stem + ".tmp-XXXXXX" + extension)).string();
    std::vector<char> pattern(name.begin(), name.end());
    pattern.push_back('\0');
    int fd = ::mkstemps(pattern.data(), int(extension.size()));
    name = pattern.data();
    return fd;
}

/// Writes `bytes` to a new temporary file beside `path` (flushed to disk, with the permissions
/// the target has or will have) and returns its name. On failure removes it and throws.
std::string writeTemporary(const std::string& path, std::string_view bytes,
                           const std::string& prefix) {
    fs::path target(path);
    if (!target.has_filename() || target.filename() == "." || target.filename() == "..")
        throw InputError(prefix + " (not a file name)");
    fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::string temporary;
    int fd = createTemporary(dir, target, temporary);
    if (fd < 0) {
        throw InputError(prefix + " (cannot create a temporary file in " + dir.string() + ": " +
                         std::strerror(errno) + ")");
    }
    auto fail = [&](const char* step) {
        int err = errno;
        if (fd >= 0) ::close(fd);
        ::unlink(temporary.c_str());
        throw InputError(prefix + " (" + step + ": " + std::strerror(err) + ")");
    };
    // Keep the permissions of the file being replaced.
    struct stat existing;
    mode_t mode = ::stat(path.c_str(), &existing) == 0 ? (existing.st_mode & 07777) : kNewFileMode;
    if (::fchmod(fd, mode) != 0) fail("chmod");

    size_t written = 0;
    while (written < bytes.size()) {
        ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
        if (n < 0 && errno == EINTR) continue;
        if (n == 0) errno = EIO;  // a write that makes no progress would loop for ever
        if (n <= 0) fail("write");
        written += size_t(n);
    }
    if (::fsync(fd) != 0) fail("fsync");
    int closed = ::close(fd);
    fd = -1;
    if (closed != 0) fail("close");
    return temporary;
}

/// Renames the temporary file over `path` (removing it on failure), then makes the rename
/// durable (best effort: failing there cannot lose data).
void replaceWith(const std::string& temporary, const std::string& path, const std::string& prefix) {
    if (::rename(temporary.c_str(), path.c_str()) != 0) {
        int err = errno;
        ::unlink(temporary.c_str());
        throw InputError(prefix + " (rename: " + std::strerror(err) + ")");
    }
    fs::path dir =
        fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
    int dirFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (dirFd >= 0) {
        ::fsync(dirFd);
        ::close(dirFd);
    }
}

}  // namespace

void writeFileAtomically(const std::string& path, std::string_view bytes,
                         std::string_view failure) {
    checkNotAnInput(path);
    std::string prefix = path + ": " + std::string(failure);
    replaceWith(writeTemporary(path, bytes, prefix), path, prefix);
}

AtomicFileSet::~AtomicFileSet() {
    for (const Pending& p : mPending) ::unlink(p.temporary.c_str());
}

void AtomicFileSet::add(const std::string& path, std::string_view bytes, std::string_view failure) {
    checkNotAnInput(path);
    std::string prefix = path + ": " + std::string(failure);
    std::string temporary = writeTemporary(path, bytes, prefix);
    mPending.push_back({path, temporary, prefix});
}

void AtomicFileSet::commit() {
    // Each rename either happens or leaves its target as it was; a failure part-way (which takes
    // a target that turned into a folder, say) still removes the temporary files left.
    std::vector<Pending> pending = std::move(mPending);
    mPending.clear();
    for (size_t i = 0; i < pending.size(); ++i) {
        try {
            replaceWith(pending[i].temporary, pending[i].path, pending[i].prefix);
        } catch (...) {
            for (size_t k = i + 1; k < pending.size(); ++k) ::unlink(pending[k].temporary.c_str());
            throw;
        }
    }
}

namespace {

/// Encodes through OpenImageIO into memory (its I/O proxy): the bytes of the file `path` names.
std::string encode(const std::string& path, int width, int height, int channels,
                   OIIO::TypeDesc type, const void* pixels, const std::string& compression) {
    checkNotAnInput(path);  // before the encoding's work
    auto out = OIIO::ImageOutput::create(path);
    if (!out)
        throw InputError(
            path + ": cannot write images of this type (use .png or .exr): " + OIIO::geterror());
    if (!out->supports("ioproxy"))
        throw InputError(path + ": cannot write images of this type (use .png or .exr)");
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    OIIO::Filesystem::IOProxy* proxy = &memory;
    OIIO::ImageSpec spec(width, height, channels, type);
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    if (!compression.empty()) spec.attribute("compression", compression);
    // has_error(): some writers (PNG) report a failed write only there, not through their result.
    if (!out->open(path, spec) || !out->write_image(type, pixels) || !out->close() ||
        out->has_error())
        throw InputError(path + ": cannot encode the image: " + out->geterror());
    return std::string(encoded.begin(), encoded.end());
}

}  // namespace

std::string encodeImage(const std::string& path, int width, int height, int channels,
                        const float* pixels, const std::string& compression) {
    return encode(path, width, height, channels, OIIO::TypeDesc::FLOAT, pixels, compression);
}

void writeImageAtomically(const std::string& path, int width, int height, int channels,
                          const unsigned char* pixels) {
    writeFileAtomically(path,
                        encode(path, width, height, channels, OIIO::TypeDesc::UINT8, pixels, {}),
                        "cannot write the image");
}

void writeImageAtomically(const std::string& path, int width, int height, int channels,
                          const float* pixels, const std::string& compression) {
    writeFileAtomically(
        path, encode(path, width, height, channels, OIIO::TypeDesc::FLOAT, pixels, compression),
        "cannot write the image");
}

bool sameFile(const std::string& a, const std::string& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) {
        bool same = fs::equivalent(a, b, ec);
        if (!ec) return same;
    }
    fs::path ca = fs::weakly_canonical(absolutePath(a), ec);
    if (ec) ca = absolutePath(a);
    fs::path cb = fs::weakly_canonical(absolutePath(b), ec);
    if (ec) cb = absolutePath(b);
    return ca == cb;
}

ProtectedInputs::ProtectedInputs(const std::vector<std::string>& files) {
    add(files);
    std::lock_guard lock(registryMutex());
    registry().push_back(this);
}

ProtectedInputs::~ProtectedInputs() {
    std::lock_guard lock(registryMutex());
    std::erase(registry(), this);
}

void ProtectedInputs::add(const std::string& file) {
    if (file.empty()) return;
    std::lock_guard lock(registryMutex());
    mFiles.push_back({file, absolutePath(file)});
}

void ProtectedInputs::add(const std::vector<std::string>& files) {
    for (const std::string& file : files) add(file);
}

InputReplacement::InputReplacement(const std::string& file)
    : mAbsolute(absolutePath(file)), mOuter(tReplacement) {
    tReplacement = this;
}

InputReplacement::~InputReplacement() {
    tReplacement = mOuter;
}

std::string protectedInputFor(const std::string& output) {
    if (output.empty()) return {};
    std::string absolute = absolutePath(output);
    for (const InputReplacement* r = tReplacement; r; r = r->mOuter)
        if (sameFile(absolute, r->mAbsolute)) return {};
    std::lock_guard lock(registryMutex());
    for (const ProtectedInputs* scope : registry())
        for (const ProtectedInputs::Entry& input : scope->mFiles)
            if (sameFile(absolute, input.absolute)) return input.given;
    return {};
}

void checkNotAnInput(const std::string& output, std::string_view what, std::string_view owner) {
    std::string input = protectedInputFor(output);
    if (input.empty()) return;
    throw InputError(input + ": " + (what.empty() ? std::string("writing") : std::string(what)) +
                     " " + output + " would overwrite this input of " + std::string(owner) +
                     "; choose another output file");
}

}  // namespace candela
