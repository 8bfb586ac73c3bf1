// Strict GLSL (issue 20, part 3): every shader variant the registry and the passes can produce,
// preprocessed as the driver is given it, is validated by glslangValidator (Khronos' reference
// front end, Debian's glslang-tools) against GLSL 4.50 core, so what Mesa tolerates and another
// driver refuses fails here. No GL context: the sources come from renderer/ProgramVariants.h.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include "renderer/ProgramVariants.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

struct Validation {
    bool ran = false;  ///< false: glslangValidator could not be started
    int status = -1;
    std::string log;
};

/// Runs glslangValidator on one stage's text written to `dir`; its exit status and output.
Validation validate(const fs::path& dir, const std::string& name, const std::string& stage,
                    const std::string& text) {
    fs::path file = dir / (name + "." + stage);
    std::ofstream(file) << text;
    Validation v;
    std::string command = "glslangValidator " + file.string() + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return v;
    char buffer[4096];
    for (size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) v.log.append(buffer, n);
    int status = pclose(pipe);
    v.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    v.ran = v.status != 127;  // the shell's "command not found"
    return v;
}

/// glslang's "ERROR: 3:41: ..." with the source-string number replaced by its file name.
std::string namedLog(const std::string& log, const std::vector<std::string>& files) {
    static const std::regex location(R"((ERROR|WARNING): (\d+):(\d+):)");
    std::string out;
    size_t last = 0;
    for (std::sregex_iterator it(log.begin(), log.end(), location), end; it != end; ++it) {
        size_t id = std::stoul((*it)[2]);
        out += log.substr(last, size_t(it->position()) - last);
        out += std::string((*it)[1]) + ": " + (id < files.size() ? files[id] : "?") + ":" +
               std::string((*it)[3]) + ":";
        last = size_t(it->position() + it->length());
    }
    return out + log.substr(last);
}

fs::path freshDir(const std::string& name) {
    fs::path dir =
        fs::temp_directory_path() / ("candela_glsl_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(ShaderVariants, EveryVariantPassesGlslang) {
    ShaderLibrary shaders;
    std::vector<ShaderStageSource> stages = allShaderStages(shaders);
    ASSERT_FALSE(stages.empty());
    fs::path dir = freshDir("variants");
    int index = 0;
    for (const ShaderStageSource& s : stages) {
        Validation v = validate(dir, std::to_string(index++), s.stage, s.text);
        ASSERT_TRUE(v.ran)
            << "glslangValidator not found: install glslang-tools (scripts/setup.sh)";
        EXPECT_EQ(v.status, 0) << s.label << ":\n" << namedLog(v.log, s.files);
    }
    std::printf("%zu stages of %zu program variants validated\n", stages.size(),
                allProgramVariants().size());
    fs::remove_all(dir);
}

// What drivers disagree on, kept out of every variant: fp64 (issue 20, part 1: consumer GPUs run
// it at 1/32 to 1/64 of fp32, some drivers not at all) and asin/acos (NVIDIA's are cubic fits
// off by up to 7e-5 rad; an H200 read 0.4 lx where an edge-on opening gives exactly 0). Comments
// are stripped first, so a comment may name them.
TEST(ShaderVariants, NoVariantUsesDoublesOrInverseSineAndCosine) {
    ShaderLibrary shaders;
    static const std::regex comment(R"(//[^\n]*|/\*[\s\S]*?\*/)");
    static const std::regex banned(R"(\b(double|dvec[234]|dmat[234](x[234])?|acos|asin)\b)");
    std::vector<ShaderStageSource> stages = allShaderStages(shaders);
    ASSERT_FALSE(stages.empty());
    for (const ShaderStageSource& s : stages) {
        std::string code = std::regex_replace(s.text, comment, " ");
        std::smatch m;
        EXPECT_FALSE(std::regex_search(code, m, banned)) << s.label << " uses " << m.str();
    }
    // The check can fail.
    std::string sample = "// acos in a comment\nfloat a = acos(x); dvec2 b;";
    std::string code = std::regex_replace(sample, comment, " ");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(code, m, banned));
    EXPECT_EQ(m.str(), "acos");
}

// The check can fail: an implicit float-to-int conversion, which GLSL 4.50 forbids, and a
// vertex shader that writes a fragment output.
TEST(ShaderVariants, TheValidatorRefusesInvalidGlsl) {
    fs::path dir = freshDir("invalid");
    Validation conversion =
        validate(dir, "conversion", "frag", "#version 450 core\nvoid main() { int i = 1.5; }\n");
    ASSERT_TRUE(conversion.ran);
    EXPECT_NE(conversion.status, 0) << conversion.log;
    Validation stage =
        validate(dir, "stage", "vert", "#version 450 core\nvoid main() { gl_FragDepth = 0.0; }\n");
    EXPECT_NE(stage.status, 0) << stage.log;
    Validation fine = validate(dir, "fine", "frag",
                               "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
    EXPECT_EQ(fine.status, 0) << fine.log;
    fs::remove_all(dir);
}

// Every stage file in shaders/ is part of some listed variant: a pass that built a program the
// list does not know, or a technique shader the registry does not name, would escape the
// validation above.
TEST(ShaderVariants, TheListCoversEveryStageFile) {
    ShaderLibrary shaders;
    std::set<std::string> listed;
    for (const ProgramKey& key : allProgramVariants()) {
        for (const std::string& f : {key.vertex, key.fragment, key.compute})
            if (!f.empty()) listed.insert(f);
    }
    for (const auto& entry : fs::directory_iterator(shaders.directory())) {
        std::string ext = entry.path().extension().string();
        if (ext != ".vert" && ext != ".frag" && ext != ".comp") continue;
        EXPECT_TRUE(listed.count(entry.path().filename().string()))
            << entry.path().filename() << " is in no listed program variant";
    }
}

}  // namespace
}  // namespace candela
