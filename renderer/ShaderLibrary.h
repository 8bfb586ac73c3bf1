#pragma once
// Loads GLSL from shaders/, resolves #include "file", injects #defines for variants and #line
// markers (so compiler logs name the real file), compiles programs on first use, and hot-reloads
// changed files, keeping the last program that compiled when an edit breaks it.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "renderer/gl/GlObjects.h"

namespace candela {

/// A program variant: its stage files (relative to the shader folder) and its defines.
struct ProgramKey {
    std::string vertex;
    std::string fragment;
    std::string compute;
    std::vector<std::string> defines;  ///< "NAME" or "NAME VALUE".

    bool operator<(const ProgramKey& o) const;
    std::string label() const;  ///< "lambertian_rect_analytic.frag[SHADOWS]"
};

class ShaderLibrary {
  public:
    /// shaderDir: folder with the .glsl/.vert/.frag/.comp files. Empty: defaultShaderDir().
    explicit ShaderLibrary(std::filesystem::path shaderDir = {});

    /// The program for key, compiled on first use. Throws RuntimeError with the log when it
    /// fails to compile the first time; afterwards a failed reload keeps the previous program.
    GLuint program(const ProgramKey& key);
    /// Recompiles programs whose files changed on disk. Returns true if any program changed.
    bool reloadChanged();
    /// Log of the last failed compile (empty when the last reload succeeded).
    const std::string& errorLog() const { return mErrorLog; }
    /// The preprocessed text of one stage file of key, as the driver is given it (version,
    /// defines, includes resolved, #line markers); needs no GL context.
    /// `files`, when given, receives the file of each #line source-string number.
    std::string source(const ProgramKey& key, const std::string& file,
                       std::vector<std::string>* files = nullptr) const;
    /// Labels of every variant compiled so far (frame statistics prove what was built).
    std::vector<std::string> compiledVariants() const;
    const std::filesystem::path& directory() const { return mDir; }

    /// CANDELA_SHADER_DIR if set, else the source tree's shaders/ folder.
    static std::filesystem::path defaultShaderDir();

  private:
    struct Entry {
        gl::Program program;
        std::map<std::filesystem::path, std::filesystem::file_time_type> files;
    };
    /// Compiles key; on success fills entry, on failure returns false and sets mErrorLog.
    bool build(const ProgramKey& key, Entry& entry);
    GLuint compileStage(GLenum stage, const std::string& file, const ProgramKey& key, Entry& entry,
                        bool& ok);
    std::string preprocess(const std::string& file, std::vector<std::string>& fileTable,
                           Entry& entry, int depth) const;
    std::string stageText(const ProgramKey& key, const std::string& file,
                          std::vector<std::string>& fileTable, Entry& entry) const;

    std::filesystem::path mDir;
    std::map<ProgramKey, Entry> mPrograms;
    std::string mErrorLog;
};

}  // namespace candela
