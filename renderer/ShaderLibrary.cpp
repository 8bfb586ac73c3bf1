#include "renderer/ShaderLibrary.h"

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include "util/Error.h"

namespace candela {

bool ProgramKey::operator<(const ProgramKey& o) const {
    return std::tie(vertex, fragment, compute, defines) <
           std::tie(o.vertex, o.fragment, o.compute, o.defines);
}

std::string ProgramKey::label() const {
    std::string s = compute.empty() ? fragment : compute;
    if (!defines.empty()) {
        s += "[";
        for (size_t i = 0; i < defines.size(); ++i) s += (i ? "," : "") + defines[i];
        s += "]";
    }
    return s;
}

std::filesystem::path ShaderLibrary::defaultShaderDir() {
    if (const char* env = std::getenv("CANDELA_SHADER_DIR"); env && *env) return env;
    return std::filesystem::path(CANDELA_SOURCE_DIR) / "shaders";
}

ShaderLibrary::ShaderLibrary(std::filesystem::path shaderDir)
    : mDir(shaderDir.empty() ? defaultShaderDir() : std::move(shaderDir)) {}

std::string ShaderLibrary::preprocess(const std::string& file, std::vector<std::string>& fileTable,
                                      Entry& entry, int depth) const {
    if (depth > 16) throw RuntimeError(file + ": #include nested too deeply (a cycle?)");
    std::filesystem::path path = mDir / file;
    std::ifstream in(path);
    if (!in) throw RuntimeError(path.string() + ": cannot open shader file");
    std::error_code ec;
    entry.files[path] = std::filesystem::last_write_time(path, ec);
    int fileId = int(fileTable.size());
    fileTable.push_back(file);

    static const std::regex includeRe(R"(^\s*#\s*include\s+\"([^\"]+)\"\s*$)");
    std::ostringstream out;
    out << "#line 1 " << fileId << "\n";
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        std::smatch m;
        if (std::regex_match(line, m, includeRe)) {
            std::string inc = m[1];
            // Each file is included once per program (all our headers are include-once).
            bool seen = false;
            for (const auto& f : fileTable) seen = seen || f == inc;
            if (!seen) out << preprocess(inc, fileTable, entry, depth + 1);
            out << "#line " << lineNo + 1 << " " << fileId << "\n";
        } else if (line.find("#pragma once") != std::string::npos) {
            out << "\n";
        } else {
            out << line << "\n";
        }
    }
    return out.str();
}

std::string ShaderLibrary::stageText(const ProgramKey& key, const std::string& file,
                                     std::vector<std::string>& fileTable, Entry& entry) const {
    std::string source = "#version 450 core\n";
    for (const std::string& d : key.defines) {
        std::string def = d;
        if (auto eq = def.find('='); eq != std::string::npos) def[eq] = ' ';
        source += "#define " + def + "\n";
    }
    return source + preprocess(file, fileTable, entry, 0);
}

std::string ShaderLibrary::source(const ProgramKey& key, const std::string& file,
                                  std::vector<std::string>* files) const {
    std::vector<std::string> fileTable;
    Entry entry;
    std::string text = stageText(key, file, fileTable, entry);
    if (files) *files = std::move(fileTable);
    return text;
}

GLuint ShaderLibrary::compileStage(GLenum stage, const std::string& file, const ProgramKey& key,
                                   Entry& entry, bool& ok) {
    std::vector<std::string> fileTable;
    std::string source = stageText(key, file, fileTable, entry);
    GLuint shader = glCreateShader(stage);
    const char* src = source.c_str();
    glShaderSource(shader, 1, &src, nullptr);
    glCompileShader(shader);
    GLint status = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &status);
    if (!status) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(size_t(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        // Mesa writes "N:LINE(COL): error"; replace the source-string number by the file name.
        static const std::regex locRe(R"((^|\n)(\d+):(\d+)\()");
        std::string named;
        std::sregex_iterator it(log.begin(), log.end(), locRe), end;
        size_t last = 0;
        for (; it != end; ++it) {
            size_t id = std::stoul((*it)[2]);
            named += log.substr(last, size_t(it->position()) - last);
            named += std::string((*it)[1]) + (id < fileTable.size() ? fileTable[id] : "?") + ":" +
                     std::string((*it)[3]) + "(";
            last = size_t(it->position() + it->length());
        }
        named += log.substr(last);
        mErrorLog += key.label() + ":\n" + named;
        ok = false;
    }
    return shader;
}

bool ShaderLibrary::build(const ProgramKey& key, Entry& entry) {
    Entry fresh;
    bool ok = true;
    mErrorLog.clear();
    std::vector<GLuint> shaders;
    if (!key.compute.empty()) {
        shaders.push_back(compileStage(GL_COMPUTE_SHADER, key.compute, key, fresh, ok));
    } else {
        shaders.push_back(compileStage(GL_VERTEX_SHADER, key.vertex, key, fresh, ok));
        shaders.push_back(compileStage(GL_FRAGMENT_SHADER, key.fragment, key, fresh, ok));
    }
    GLuint program = glCreateProgram();
    for (GLuint s : shaders) glAttachShader(program, s);
    if (ok) {
        glLinkProgram(program);
        GLint status = 0;
        glGetProgramiv(program, GL_LINK_STATUS, &status);
        if (!status) {
            GLint length = 0;
            glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
            std::string log(size_t(std::max(length, 1)), '\0');
            glGetProgramInfoLog(program, length, nullptr, log.data());
            mErrorLog += key.label() + ": link failed:\n" + log;
            ok = false;
        }
    }
    for (GLuint s : shaders) glDeleteShader(s);
    if (!ok) {
        glDeleteProgram(program);
        // Still watch the files so that fixing them triggers a reload.
        for (auto& f : fresh.files) entry.files[f.first] = f.second;
        return false;
    }
    entry.program = gl::Program(program);
    entry.files = std::move(fresh.files);
    return true;
}

GLuint ShaderLibrary::program(const ProgramKey& key) {
    auto it = mPrograms.find(key);
    if (it != mPrograms.end() && it->second.program) return it->second.program.id();
    Entry entry;
    if (!build(key, entry)) throw RuntimeError("shader compile failed: " + mErrorLog);
    return mPrograms.insert_or_assign(key, std::move(entry)).first->second.program.id();
}

bool ShaderLibrary::reloadChanged() {
    bool changed = false;
    for (auto& [key, entry] : mPrograms) {
        bool stale = false;
        for (const auto& [path, time] : entry.files) {
            std::error_code ec;
            auto now = std::filesystem::last_write_time(path, ec);
            stale = stale || ec || now != time;
        }
        if (!stale) continue;
        Entry fresh;
        if (build(key, fresh)) {
            entry = std::move(fresh);
            changed = true;
        } else {
            entry.files = fresh.files;  // keep the last good program, wait for the next edit
        }
    }
    return changed;
}

std::vector<std::string> ShaderLibrary::compiledVariants() const {
    std::vector<std::string> out;
    for (const auto& [key, entry] : mPrograms) out.push_back(key.label());
    return out;
}

}  // namespace candela
