#pragma once
// Shared by the libFuzzer targets (one translation unit each): a scratch folder for parsers that
// read files, and the checks of what a parser returns. A parser may return or throw InputError;
// any other exception escapes LLVMFuzzerTestOneInput, and libFuzzer reports it as a crash, as it
// does a violated check (abort) and every ASan or UBSan report.

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "util/TextEncoding.h"

namespace candela::fuzz {

namespace fs = std::filesystem;

/// Stops the run: libFuzzer saves the input as a crash.
[[noreturn]] inline void violated(const std::string& what) {
    std::fprintf(stderr, "fuzz check failed: %s\n", what.c_str());
    std::abort();
}

/// A folder of this process's own under $TMPDIR (or /tmp), removed at exit.
inline const fs::path& scratchDir() {
    static const fs::path dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/candela-fuzz-XXXXXX";
        std::vector<char> name(pattern.begin(), pattern.end());
        name.push_back('\0');
        if (!mkdtemp(name.data())) violated("cannot make a scratch folder under " + pattern);
        fs::path made(name.data());
        static const fs::path removeAtExit = made;
        std::atexit([] {
            std::error_code ec;
            fs::remove_all(removeAtExit, ec);
        });
        return made;
    }();
    return dir;
}

/// Copies repository files (paths relative to the source folder) into the scratch folder, under
/// their own names.
inline void copyIntoScratch(const std::vector<std::string>& files) {
    for (const std::string& f : files) {
        fs::path from = fs::path(CANDELA_SOURCE_DIR) / f;
        std::error_code ec;
        fs::copy_file(from, scratchDir() / from.filename(), fs::copy_options::overwrite_existing,
                      ec);
        if (ec) violated("cannot copy " + from.string() + ": " + ec.message());
    }
}

/// Writes the input to scratchDir()/name and returns the path.
inline std::string writeScratch(const std::string& name, const uint8_t* data, size_t size) {
    fs::path path = scratchDir() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) violated("cannot write " + path.string());
    return path.string();
}

/// A message shown to users: one line of valid UTF-8 that starts with `path` and a colon.
inline void checkMessage(std::string_view message, const std::string& path) {
    if (!isValidUtf8(message)) violated("message is not valid UTF-8: " + toValidUtf8(message));
    if (message.find_first_of("\r\n") != std::string_view::npos)
        violated("message of more than one line: " + std::string(message));
    if (message.substr(0, path.size() + 1) != path + ":")
        violated("message does not start with the file: " + std::string(message));
}

/// Every value finite (and within [lo, hi]).
template <class Range>
void checkFinite(const Range& values, const char* what, double lo = -HUGE_VAL,
                 double hi = HUGE_VAL) {
    for (auto v : values)
        if (!(std::isfinite(double(v)) && double(v) >= lo && double(v) <= hi))
            violated(std::string(what) + " holds " + std::to_string(double(v)));
}

}  // namespace candela::fuzz
