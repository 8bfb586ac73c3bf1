#pragma once
// Who owns an autosave (an editor process) and an autosave found beside a scene (ui/Project.h
// says where they go and who may touch them).

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

namespace candela::ui {

/// One editor process: who owns an autosave.
struct EditorSession {
    std::string host;              ///< gethostname().
    long pid = 0;                  ///< Process id.
    unsigned long long start = 0;  ///< Process start, clock ticks after boot (/proc/PID/stat).

    /// This process.
    static EditorSession current();
    /// The process `pid` of this host as it is now (start 0 when there is none).
    static EditorSession of(long pid);
    /// "HOST-PID-START", the part of its autosaves' names after "autosave-".
    std::string tag() const;
    /// Whether the process still runs: this host, that id, and that start time.
    bool running() const;
    /// When the process started (system clock); the epoch when it cannot be told.
    std::chrono::system_clock::time_point startTime() const;
    bool operator==(const EditorSession&) const = default;
};

/// An autosave found beside a scene, as offered when the scene is opened.
struct AutosaveFile {
    std::filesystem::path path;
    std::filesystem::file_time_type written;  ///< Its last write.
    /// Written after the scene file's last change (false: the scene was saved since).
    bool newerThanScene = true;
    /// The editor that wrote it; none for an autosave of an older Candela (no owner in its name).
    std::optional<EditorSession> owner;
    /// "14:02:31, newer than the saved file": the dialog's line for it.
    std::string describe() const;
};

}  // namespace candela::ui
