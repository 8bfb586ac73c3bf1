#include "ui/Project.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "scene/SceneIo.h"
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

fs::path autosavePath(const std::string& scenePath) {
    if (scenePath.empty()) return stateDir() / "untitled.autosave.json";
    fs::path p = fs::absolute(scenePath);
    std::string stem = p.filename().string();
    if (stem.size() > 5 && stem.compare(stem.size() - 5, 5, ".json") == 0)
        stem.resize(stem.size() - 5);
    return p.parent_path() / ("." + stem + ".autosave.json");
}

bool writeAutosave(EditorState& state) {
    fs::path target = autosavePath(state.scene.path);
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

bool restoreAutosave(EditorState& state, const std::string& scenePath) {
    fs::path autosave = autosavePath(scenePath);
    std::error_code ec;
    if (!fs::exists(autosave, ec)) return false;
    if (!scenePath.empty() && fs::exists(scenePath, ec) &&
        fs::last_write_time(autosave, ec) < fs::last_write_time(scenePath, ec))
        return false;  // saved since: the autosave is older than the file
    try {
        Scene restored = loadScene(autosave.string());
        restored.path = scenePath;
        state.scene = std::move(restored);
        state.pendingChanges = kChangeAll;
        state.dirty = true;
        state.history = {};
        ++state.geometryVersion;
        setStatus(state, "Restored unsaved edits from the autosave " + autosave.string() +
                             " (File > Revert to Saved discards them)");
        return true;
    } catch (const std::exception& e) {
        setStatus(state,
                  std::string("The autosave could not be read (kept, not restored): ") + e.what(),
                  true);
        return false;
    }
}

void removeAutosave(const std::string& scenePath) {
    std::error_code ec;
    fs::remove(autosavePath(scenePath), ec);
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
