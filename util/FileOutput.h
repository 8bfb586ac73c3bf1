#pragma once
// Every file Candela writes goes through here, so that no command destroys an input and no
// failure leaves half a file:
//  - the bytes go to a new temporary file in the target's folder (.NAME.tmp-XXXXXX.EXT), are
//    flushed to disk and renamed over the target; on any failure the old file is intact, the
//    temporary file is removed and an InputError names the target;
//  - while a ProtectedInputs scope lives (a command opens one once its inputs are loaded), a
//    write onto one of those inputs is refused, whatever path spells it (relative, "..",
//    symbolic or hard links).
// Images are encoded in memory by OpenImageIO and then written like any other bytes: its PNG
// writer reports success after a short write, so it never writes a file itself.

#include <string>
#include <string_view>
#include <vector>

namespace candela {

/// Writes `bytes` to `path` through a temporary file in the same folder (mkstemps, keeping the
/// extension), fsync and rename(); a replaced file keeps its permissions, a new one gets
/// rw-r--r--. Throws InputError "PATH: FAILURE (step: reason)" and leaves any existing file and
/// the folder as they were; refuses (InputError) a path that is a protected input.
void writeFileAtomically(const std::string& path, std::string_view bytes,
                         std::string_view failure = "cannot write this file");

/// Several files replaced together (a light field's manifest and images): add() writes each to
/// its temporary file at once (checked as writeFileAtomically does); commit() renames them all.
/// A failure in add() or a set destroyed before commit() removes every temporary file and
/// replaces nothing.
class AtomicFileSet {
  public:
    AtomicFileSet() = default;
    ~AtomicFileSet();
    AtomicFileSet(const AtomicFileSet&) = delete;
    AtomicFileSet& operator=(const AtomicFileSet&) = delete;

    void add(const std::string& path, std::string_view bytes,
             std::string_view failure = "cannot write this file");
    void commit();

  private:
    struct Pending {
        std::string path, temporary;
        std::string prefix;  ///< "PATH: failure", the start of its error messages.
    };
    std::vector<Pending> mPending;
};

/// Encodes pixels as writeImageAtomically does and returns the file's bytes.
std::string encodeImage(const std::string& path, int width, int height, int channels,
                        const float* pixels, const std::string& compression = {});

/// Encodes RGB or grey pixels (rows top to bottom, `channels` values per pixel) in the format
/// the extension of `path` names (.png, .exr, ...; OpenImageIO) and writes them with
/// writeFileAtomically. `compression` is OpenImageIO's "compression" attribute (empty: the
/// format's default). Throws InputError naming the file.
void writeImageAtomically(const std::string& path, int width, int height, int channels,
                          const unsigned char* pixels);
void writeImageAtomically(const std::string& path, int width, int height, int channels,
                          const float* pixels, const std::string& compression = {});

/// Whether two paths name the same file: std::filesystem::equivalent when both exist (so
/// symbolic and hard links count), else their absolute weakly_canonical forms are equal.
bool sameFile(const std::string& a, const std::string& b);

/// The files the running command reads (the scene, its luminaire, image and glTF files, a points
/// CSV, ...). While an object lives, every writer above refuses to write onto one of them.
/// Scopes may nest and each forgets its files when destroyed, so nothing outlives the command
/// (or the test) that opened it. Thread-safe.
class ProtectedInputs {
  public:
    explicit ProtectedInputs(const std::vector<std::string>& files = {});
    ~ProtectedInputs();
    ProtectedInputs(const ProtectedInputs&) = delete;
    ProtectedInputs& operator=(const ProtectedInputs&) = delete;

    void add(const std::string& file);
    void add(const std::vector<std::string>& files);

  private:
    friend std::string protectedInputFor(const std::string& output);
    struct Entry {
        std::string given;     ///< As the command named it (for messages).
        std::string absolute;  ///< Made absolute when added (the working folder may change).
    };
    std::vector<Entry> mFiles;
};

/// The one input a command exists to replace: the scene the editor has open, which File > Save
/// writes. While an object lives, writes from its own thread onto that file pass the check; every
/// other protected file stays refused, and other threads (a report being exported) are unaffected.
class InputReplacement {
  public:
    explicit InputReplacement(const std::string& file);
    ~InputReplacement();
    InputReplacement(const InputReplacement&) = delete;
    InputReplacement& operator=(const InputReplacement&) = delete;

  private:
    std::string mAbsolute;
    const InputReplacement* mOuter;  ///< The thread's replacement before this one.
    friend std::string protectedInputFor(const std::string& output);
};

/// The protected input (as its command named it) that `output` resolves to; empty when none (or
/// when this thread's InputReplacement names it).
std::string protectedInputFor(const std::string& output);

/// Throws InputError "INPUT: WHAT OUTPUT would overwrite this input of OWNER; choose another
/// output file" when `output` resolves to a protected input. `what` names the output (a flag such
/// as "--csv"; empty: "writing"), `owner` what reads the input.
void checkNotAnInput(const std::string& output, std::string_view what = {},
                     std::string_view owner = "the command");

}  // namespace candela
