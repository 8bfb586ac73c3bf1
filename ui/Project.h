#pragma once
// Projects around the scene file: the autosave (every minute, to a separate file, restored when
// the scene is opened after a crash) and the recent-files list. Scene files themselves are
// written atomically by saveScene (scene/SceneIo.h).
//
// The autosave of a scene at DIR/NAME.json is DIR/.NAME.autosave.json, beside it, so the paths
// the scene holds relative to its folder stay valid; an untitled scene's goes to the state
// folder. The state folder is $CANDELA_STATE_DIR, else $XDG_STATE_HOME/candela, else
// ~/.local/state/candela; it holds untitled.autosave.json and recent.json.

#include <filesystem>
#include <string>
#include <vector>

#include "ui/EditorState.h"

namespace candela::ui {

std::filesystem::path stateDir();
/// Where the autosave of a scene file goes (scenePath empty: the untitled scene's).
std::filesystem::path autosavePath(const std::string& scenePath);

/// Writes the scene to its autosave file (atomically); on failure sets an error status and
/// returns false. Does not touch the scene's own file or its saved state.
bool writeAutosave(EditorState& state);
/// Called after a scene is opened (or at start with none): if an autosave newer than the file
/// exists, loads it in place of the file's contents, keeps the scene's path, marks it unsaved and
/// says so in the status bar. Returns whether it restored.
bool restoreAutosave(EditorState& state, const std::string& scenePath);
/// Removes the autosave of a scene (after it was saved, or on request).
void removeAutosave(const std::string& scenePath);

/// A list of strings kept in the state folder as {"KEY": [...]} in FILE (recent.json,
/// library.json). Reading a missing or damaged file gives an empty list (it starts again);
/// writing is atomic and throws InputError naming the file.
std::vector<std::string> readStateList(const std::string& file, const char* key);
void writeStateList(const std::string& file, const char* key, const std::vector<std::string>& list);

/// Recently opened or saved scene files, newest first (at most 10; missing files dropped).
std::vector<std::string> recentFiles();
void addRecentFile(const std::string& path);

}  // namespace candela::ui
