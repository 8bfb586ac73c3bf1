#pragma once
// Opening what a user names as an input. Every reader goes through here before it reads a file
// or hands its path to a library (OpenImageIO, tinygltf, libzip), so that:
//  - only a regular file is read: a FIFO, a device, a socket or a folder is refused at once,
//    naming what it is (open() on a FIFO waits for a writer for ever; /dev/zero, even behind a
//    symbolic link, reads until memory runs out, and a device reports a size of 0);
//  - the file is opened before it is looked at (O_NONBLOCK, then fstat on what was opened), so it
//    cannot be swapped for a FIFO between the check and the read;
//  - a file over its kind's limit is refused before it is read, and read with a bound, so that
//    one growing while it is read is refused too.
// The limits, one per kind of input, and why each: docs/limits.md.

#include <cstdint>
#include <string>

namespace candela {

/// Scene files (JSON): a whole floor with its furniture is a few MB.
inline constexpr std::uintmax_t kMaxSceneBytes = std::uintmax_t(64) << 20;
/// Photometry (IES, EULUMDAT, TM-33) and an IES file's TILT file: the largest real files are
/// under 2 MB (a 1-degree, 361-plane table is about 1 MB).
inline constexpr std::uintmax_t kMaxPhotometryBytes = std::uintmax_t(64) << 20;
/// Small text inputs: probe points, light-field descriptions, bench CSVs.
inline constexpr std::uintmax_t kMaxTextBytes = std::uintmax_t(64) << 20;
/// Images (environment maps, light-field images): an 8192 x 4096 RGBA float map is 512 MiB
/// uncompressed.
inline constexpr std::uintmax_t kMaxImageBytes = std::uintmax_t(512) << 20;
/// glTF files and each buffer or image they name: a 5-million-triangle building is about 120 MB.
inline constexpr std::uintmax_t kMaxGltfBytes = std::uintmax_t(512) << 20;
/// No limit of its own: the reader streams the file and bounds what it keeps (TM-25 ray files).
inline constexpr std::uintmax_t kStreamed = UINTMAX_MAX;

/// Checks that `path` is a regular file (after following symbolic links) of at most `maxBytes`
/// and returns its size. Throws InputError "PATH: cannot open KIND file (REASON)",
/// "PATH: expected a KIND file, found a FIFO (named pipe)" (a folder, a character device, a block
/// device, a socket), or "PATH: expected a KIND file of at most N MiB, found M MiB".
std::uintmax_t checkInputFile(const std::string& path, const std::string& kind,
                              std::uintmax_t maxBytes);

/// The whole of a regular file of at most `maxBytes` (checkInputFile's checks and messages,
/// then a read that stops after maxBytes + 1 bytes).
std::string readInputFile(const std::string& path, const std::string& kind,
                          std::uintmax_t maxBytes);

/// "64 MiB", "1.5 GiB", "812 bytes": a size for a message.
std::string byteSize(std::uintmax_t bytes);

}  // namespace candela
