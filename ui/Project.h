#pragma once
// Projects around the scene file: the autosaves (every minute, to separate files, offered when the
// scene is opened after a crash), the scene file as last read or written (so that a save over
// another editor's or program's changes asks first), and the recent-files list. Scene files
// themselves are written atomically by saveScene (scene/SceneIo.h).
//
// Every editor process autosaves to its own file: the autosave of a scene at DIR/NAME.json by
// the editor OWNER is DIR/.NAME.autosave-OWNER.json, beside it, so the paths the scene holds
// relative to its folder stay valid; an untitled scene's goes to the state folder as
// untitled.autosave-OWNER.json. OWNER is HOST-PID-START (the process start time in clock ticks
// after boot, so that a reused process id is not taken for a running editor). No editor removes
// or overwrites another's autosave; one whose editor is no longer running (a crash, or a quit
// with unsaved edits) is offered, with every other such autosave of the scene, when the scene is
// next opened. The state folder is $CANDELA_STATE_DIR, else $XDG_STATE_HOME/candela, else
// ~/.local/state/candela; it holds the untitled autosaves and recent.json.

#include <filesystem>
#include <string>
#include <vector>

#include "ui/EditorState.h"

namespace candela::ui {

std::filesystem::path stateDir();

/// Where `owner`'s autosave of a scene file goes (scenePath empty: the untitled scene's).
std::filesystem::path autosavePath(const std::string& scenePath, const EditorSession& owner);

/// The autosaves of a scene that no running editor owns, and `self`'s own (left by an earlier
/// opening of the scene in this session), newest first.
std::vector<AutosaveFile> findAutosaves(const std::string& scenePath, const EditorSession& self);

/// Writes the scene to this session's autosave file (atomically); on failure sets an error status
/// and returns false. Does not touch the scene's own file, its saved state or other autosaves.
bool writeAutosave(EditorState& state);
/// Loads an autosave in place of the scene's contents, keeps the scene's path, marks it unsaved
/// and says so in the status bar. The autosave becomes this session's (so that saving removes
/// it), unless this session has an autosave of the scene already (both are then kept). When the
/// scene file may have changed after the autosave's editor read it, the next save asks first.
/// Returns false (status: why; the file kept) when it cannot be read.
bool restoreAutosave(EditorState& state, const AutosaveFile& file);
/// Deletes an autosave the user chose to discard.
void discardAutosave(const AutosaveFile& file);
/// Removes `owner`'s autosave of a scene (after it was saved, or reverted); never another's.
void removeAutosave(const std::string& scenePath, const EditorSession& owner);

/// The scene file's contents as a fingerprint (size and hash); empty when it cannot be read.
std::string fileFingerprint(const std::string& path);

/// A list of strings kept in the state folder as {"KEY": [...]} in FILE (recent.json,
/// library.json). Reading a missing or damaged file gives an empty list (it starts again);
/// writing is atomic and throws InputError naming the file.
std::vector<std::string> readStateList(const std::string& file, const char* key);
void writeStateList(const std::string& file, const char* key, const std::vector<std::string>& list);

/// Recently opened or saved scene files, newest first (at most 10; missing files dropped).
std::vector<std::string> recentFiles();
void addRecentFile(const std::string& path);

}  // namespace candela::ui
