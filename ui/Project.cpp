#include "ui/Project.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>

#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileInput.h"
#include "util/FileOutput.h"

namespace candela::ui {

namespace fs = std::filesystem;

namespace {

constexpr size_t kMaxRecent = 10;

}  // namespace

fs::path stateDir() {
    if (const char* dir = std::getenv("CANDELA_STATE_DIR"); dir && *dir) return dir;
    if (const char* dir = std::getenv("XDG_STATE_HOME"); dir && *dir)
        return fs::path(dir) / "candela";
    if (const char* home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".local/state/candela";
    return fs::temp_directory_path() / "candela-state";
}

namespace {

constexpr const char* kAutosaveInfix = ".autosave";  ///< NAME.autosave-OWNER.json

/// The name an autosave of `scenePath` starts with: DIR/.NAME.autosave (untitled: the state
/// folder's untitled.autosave).
fs::path autosaveStem(const std::string& scenePath) {
    if (scenePath.empty()) return stateDir() / (std::string("untitled") + kAutosaveInfix);
    fs::path p = fs::absolute(scenePath);
    std::string stem = p.filename().string();
    if (stem.size() > 5 && stem.compare(stem.size() - 5, 5, ".json") == 0)
        stem.resize(stem.size() - 5);
    return p.parent_path() / ("." + stem + kAutosaveInfix);
}

/// Reads /proc/PID/stat's start time (field 22, clock ticks after boot); 0 when it cannot.
unsigned long long processStart(long pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // The command name (field 2) is in parentheses and may hold spaces: count after its ')'.
    size_t close = text.rfind(')');
    if (close == std::string::npos) return 0;
    std::istringstream fields(text.substr(close + 1));
    std::string field;
    for (int i = 3; i <= 22 && fields >> field; ++i)
        if (i == 22) return std::strtoull(field.c_str(), nullptr, 10);
    return 0;
}

/// The owner in an autosave's name after "autosave-": HOST-PID-START (the host may hold '-').
std::optional<EditorSession> parseOwner(const std::string& tag) {
    size_t second = tag.rfind('-');
    if (second == std::string::npos || second == 0) return std::nullopt;
    size_t first = tag.rfind('-', second - 1);
    if (first == std::string::npos || first == 0) return std::nullopt;
    EditorSession owner;
    owner.host = tag.substr(0, first);
    char* end = nullptr;
    std::string pid = tag.substr(first + 1, second - first - 1);
    owner.pid = std::strtol(pid.c_str(), &end, 10);
    if (pid.empty() || *end != '\0' || owner.pid <= 0) return std::nullopt;
    std::string start = tag.substr(second + 1);
    owner.start = std::strtoull(start.c_str(), &end, 10);
    if (start.empty() || *end != '\0') return std::nullopt;
    return owner;
}

std::string clockText(fs::file_time_type time) {
    auto system = std::chrono::time_point_cast<std::chrono::system_clock::duration>(
        time - fs::file_time_type::clock::now() + std::chrono::system_clock::now());
    std::time_t t = std::chrono::system_clock::to_time_t(system);
    std::tm tm{};
    localtime_r(&t, &tm);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &tm);
    return text;
}

}  // namespace

EditorSession EditorSession::of(long pid) {
    EditorSession s;
    char host[256] = {};
    if (::gethostname(host, sizeof host - 1) == 0) s.host = host;
    // A name part of the autosave's file name: no path separators.
    std::replace(s.host.begin(), s.host.end(), '/', '_');
    if (s.host.empty()) s.host = "localhost";
    s.pid = pid;
    s.start = processStart(pid);
    return s;
}

EditorSession EditorSession::current() {
    static const EditorSession self = of(long(::getpid()));
    return self;
}

std::string EditorSession::tag() const {
    return host + "-" + std::to_string(pid) + "-" + std::to_string(start);
}

bool EditorSession::running() const {
    if (*this == current()) return true;
    // Another machine's editor (a shared folder) cannot be looked up: taken as running, so its
    // autosave is never offered here while it may still be writing it.
    if (host != current().host) return true;
    return pid > 0 && processStart(pid) == start && start != 0;
}

std::chrono::system_clock::time_point EditorSession::startTime() const {
    // Now, less the time since the start: the seconds since boot (/proc/uptime, to 10 ms) less
    // the start in clock ticks after boot.
    std::ifstream in("/proc/uptime");
    double uptime = -1.0;
    in >> uptime;
    long ticks = ::sysconf(_SC_CLK_TCK);
    if (!(uptime >= 0.0) || ticks <= 0 || start == 0) return {};
    auto since = std::chrono::duration<double>(uptime - double(start) / double(ticks));
    return std::chrono::system_clock::now() -
           std::chrono::duration_cast<std::chrono::system_clock::duration>(since);
}

std::string AutosaveFile::describe() const {
    std::string who = !owner             ? "an earlier Candela"
                      : owner->running() ? "this editor"
                      : owner->host != EditorSession::current().host
                          ? "an editor on " + owner->host
                          : "an editor that is no longer running";
    return "Autosaved " + clockText(written) + " by " + who + ", " +
           (newerThanScene ? "newer than the saved file"
                           : "older than the saved file (saved since)");
}

fs::path autosavePath(const std::string& scenePath, const EditorSession& owner) {
    fs::path stem = autosaveStem(scenePath);
    return stem.parent_path() / (stem.filename().string() + "-" + owner.tag() + ".json");
}

std::vector<AutosaveFile> findAutosaves(const std::string& scenePath, const EditorSession& self) {
    std::vector<AutosaveFile> found;
    fs::path stem = autosaveStem(scenePath);
    std::string prefix = stem.filename().string();
    std::error_code ec;
    fs::file_time_type sceneTime{};
    bool sceneExists = !scenePath.empty() && fs::exists(scenePath, ec);
    if (sceneExists) sceneTime = fs::last_write_time(scenePath, ec);
    for (fs::directory_iterator it(stem.parent_path(), ec), end; !ec && it != end;
         it.increment(ec)) {
        std::string name = it->path().filename().string();
        if (name.size() < prefix.size() + 5 || name.compare(0, prefix.size(), prefix) != 0 ||
            name.compare(name.size() - 5, 5, ".json") != 0 || !it->is_regular_file(ec))
            continue;
        std::string rest = name.substr(prefix.size(), name.size() - prefix.size() - 5);
        AutosaveFile file;
        file.path = it->path();
        if (!rest.empty()) {  // "" is an older Candela's shared .NAME.autosave.json
            if (rest[0] != '-') continue;
            file.owner = parseOwner(rest.substr(1));
            if (!file.owner) continue;
            if (*file.owner != self && file.owner->running()) continue;  // another live editor's
        }
        file.written = fs::last_write_time(file.path, ec);
        file.newerThanScene = !sceneExists || file.written >= sceneTime;
        found.push_back(std::move(file));
    }
    std::sort(found.begin(), found.end(),
              [](const AutosaveFile& a, const AutosaveFile& b) { return a.written > b.written; });
    return found;
}

bool writeAutosave(EditorState& state) {
    fs::path target = autosavePath(state.scene.path, state.project.session);
    try {
        fs::create_directories(target.parent_path());
        // A plain scene file (the loader accepts no other keys): it opens like any scene.
        writeFileAtomically(target.string(), sceneToJson(state.scene).dump(1) + "\n");
        return true;
    } catch (const std::exception& e) {
        setStatus(state, std::string("Autosave failed: ") + e.what(), true);
        return false;
    }
}

bool restoreAutosave(EditorState& state, const AutosaveFile& file) {
    try {
        Scene restored = loadScene(file.path.string());
        restored.path = state.scene.path;
        state.scene = std::move(restored);
        state.pendingChanges = kChangeAll;
        state.dirty = true;
        ++state.edits;
        state.history = {};
        ++state.geometryVersion;
        // Its editor read the scene file after it started: a change on disk after that start
        // may be newer than what the edits began from, so the next save asks. (An older
        // Candela's autosave names no editor: always ask.)
        std::error_code ec;
        if (!state.scene.path.empty() && fs::exists(state.scene.path, ec)) {
            auto changed = fs::last_write_time(state.scene.path, ec);
            auto changedSystem = std::chrono::time_point_cast<std::chrono::system_clock::duration>(
                changed - fs::file_time_type::clock::now() + std::chrono::system_clock::now());
            if (!file.owner || changedSystem >= file.owner->startTime())
                state.project.onDisk.clear();
        }
        // Adopted: this session's own autosave from now on, removed when the scene is saved.
        fs::path own = autosavePath(state.scene.path, state.project.session);
        if (file.path != own && !fs::exists(own, ec)) fs::rename(file.path, own, ec);
        setStatus(state, "Restored unsaved edits from " + file.path.filename().string() +
                             " (File > Revert to Saved discards them)");
        return true;
    } catch (const std::exception& e) {
        setStatus(state,
                  std::string("The autosave could not be read (kept, not restored): ") + e.what(),
                  true);
        return false;
    }
}

void discardAutosave(const AutosaveFile& file) {
    std::error_code ec;
    fs::remove(file.path, ec);
}

void removeAutosave(const std::string& scenePath, const EditorSession& owner) {
    std::error_code ec;
    fs::remove(autosavePath(scenePath, owner), ec);
}

std::string fileFingerprint(const std::string& path) {
    std::string bytes;
    try {
        bytes = readInputFile(path, "scene", kMaxSceneBytes);
    } catch (const InputError&) {
        return {};
    }
    return std::to_string(bytes.size()) + ":" + std::to_string(std::hash<std::string>{}(bytes));
}

std::vector<std::string> readStateList(const std::string& file, const char* key) {
    std::vector<std::string> out;
    std::ifstream in(stateDir() / file);
    if (!in) return out;
    try {
        nlohmann::json doc = nlohmann::json::parse(in);  // kept: the loop reads into it
        for (const auto& entry : doc.at(key))
            if (entry.is_string()) out.push_back(entry.get<std::string>());
    } catch (const std::exception&) {
        out.clear();  // a damaged list is not worth an error: it starts again
    }
    return out;
}

void writeStateList(const std::string& file, const char* key,
                    const std::vector<std::string>& list) {
    fs::create_directories(stateDir());
    writeFileAtomically((stateDir() / file).string(), nlohmann::json{{key, list}}.dump(1) + "\n");
}

std::vector<std::string> recentFiles() {
    std::vector<std::string> out = readStateList("recent.json", "recent");
    std::error_code ec;
    std::erase_if(out, [&](const std::string& path) { return !fs::exists(path, ec); });
    return out;
}

void addRecentFile(const std::string& path) {
    std::string absolute = fs::absolute(path).lexically_normal().string();
    std::vector<std::string> list = recentFiles();
    std::erase(list, absolute);
    list.insert(list.begin(), absolute);
    if (list.size() > kMaxRecent) list.resize(kMaxRecent);
    try {
        writeStateList("recent.json", "recent", list);
    } catch (const std::exception&) {
        // The list is a convenience: a read-only state folder only loses it.
    }
}

}  // namespace candela::ui
