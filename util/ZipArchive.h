#pragma once
// A ZIP archive read from memory with libzip (GLDF containers, L3D geometry), member names decoded
// to UTF-8 (unflagged names are in the writer's DOS code page; GLDF tools on Windows write 850).
// Every failure is an InputError of one line in valid UTF-8 naming the archive and the member.

#include <cstdint>
#include <string>
#include <vector>

struct zip;

namespace candela {

/// Largest member read from an archive (uncompressed), bytes: photometry, product.xml and OBJ
/// parts are kilobytes to megabytes; 64 MB bounds what a corrupt or hostile size field can make us
/// allocate.
constexpr uint64_t kMaxZipMember = uint64_t(64) << 20;

class ZipArchive {
  public:
    /// Opens `bytes` (kept alive by the caller while the archive is used); `path` names the
    /// archive in messages, `kind` says what it should have been ("a GLDF container").
    ZipArchive(const std::string& bytes, const std::string& path, const std::string& kind);
    ~ZipArchive();
    ZipArchive(const ZipArchive&) = delete;
    ZipArchive& operator=(const ZipArchive&) = delete;

    /// Every entry's name, UTF-8, folders included (they end in '/').
    const std::vector<std::string>& names() const { return mNames; }
    /// Index of the member named `name` (UTF-8), or -1.
    int64_t find(const std::string& name) const;
    /// The member's bytes; `label` names it in messages ("ldc/a.ldt (file "f", ...)"). Refuses a
    /// member above kMaxZipMember, a damaged one and one shorter than its entry says.
    std::string read(int64_t index, const std::string& label) const;

  private:
    std::string mPath;
    struct zip* mZip = nullptr;
    std::vector<std::string> mNames;
};

}  // namespace candela
