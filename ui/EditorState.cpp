#include "ui/EditorState.h"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>

#include "luminaires/Adapter.h"
#include "luminaires/Registry.h"
#include "luminaires/environment/Environment.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/SceneIo.h"
#include "ui/Project.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela::ui {

namespace {

SceneSnapshot snapshot(const EditorState& state, bool geometry) {
    const Scene& scene = state.scene;
    SceneSnapshot out;
    for (const auto& lum : scene.luminaires) out.luminaires.push_back(lum->clone());
    out.layouts = scene.layouts;
    out.project = scene.project;
    out.camera = scene.camera;
    out.maintenanceFactor = scene.maintenanceFactor;
    out.taskAreas = scene.taskAreas;
    out.calcPoints = scene.calcPoints;
    out.glareObservers = scene.glareObservers;
    out.environment = scene.environment;
    out.environmentMap = scene.environmentMap;
    out.environmentSequence = scene.environmentSequence;
    out.hasGeometry = geometry;
    if (geometry) {
        out.geometry = scene.geometry;
        out.meshes = scene.meshes;
        out.materials = scene.materials;
    }
    out.selectedLuminaire = state.selectedLuminaire;
    return out;
}

void restore(EditorState& state, SceneSnapshot& from) {
    Scene& scene = state.scene;
    scene.luminaires = std::move(from.luminaires);
    scene.layouts = std::move(from.layouts);
    scene.project = std::move(from.project);
    scene.camera = from.camera;
    scene.maintenanceFactor = from.maintenanceFactor;
    scene.taskAreas = std::move(from.taskAreas);
    scene.calcPoints = std::move(from.calcPoints);
    scene.glareObservers = std::move(from.glareObservers);
    state.measure.surfaces.reset();  // computed for the surfaces being replaced
    scene.environment = std::move(from.environment);
    scene.environmentMap = std::move(from.environmentMap);
    scene.environmentSequence = std::move(from.environmentSequence);
    if (from.hasGeometry) {
        scene.geometry = std::move(from.geometry);
        scene.meshes = std::move(from.meshes);
        scene.materials = std::move(from.materials);
    }
    int n = int(scene.luminaires.size());
    state.selectedLuminaire = from.selectedLuminaire < n ? from.selectedLuminaire : -1;
    if (state.selectedGeometry >= int(scene.geometry.size())) state.selectedGeometry = -1;
    state.drag = {};
    state.inspectorError.clear();
    state.alsoSelected.clear();
}

/// Moves the top step of `from` to `to`, restoring its scene and keeping the current one.
bool step(EditorState& state, std::vector<UndoStep>& from, std::vector<UndoStep>& to,
          const char* verb) {
    if (from.empty()) return false;
    UndoStep s = std::move(from.back());
    from.pop_back();
    UndoStep back{s.label, s.changes, -1, snapshot(state, s.before.hasGeometry)};
    restore(state, s.before);
    if (state.scene.updateBodies()) s.changes |= kChangeGeometry;
    to.push_back(std::move(back));
    to.back().changes |= s.changes;
    state.pendingChanges |= s.changes;
    state.dirty = true;
    ++state.edits;
    if (s.changes & kChangeGeometry) ++state.geometryVersion;
    setStatus(state, std::string(verb) + " " + s.label);
    return true;
}

}  // namespace

namespace {

/// The placements of one GLDF variant (one luminaire per emitter, sharing the insertion point)
/// move as one: a pose edit to one of them, whatever made it, is given to those that shared its
/// pose and were not edited themselves.
void keepGldfPlacementsTogether(Scene& scene, const std::vector<Pose>& before) {
    auto& lums = scene.luminaires;
    if (lums.size() != before.size()) return;  // added or removed: nothing was only moved
    for (size_t i = 0; i < lums.size(); ++i) {
        if (lums[i]->pose == before[i]) continue;
        for (size_t j = 0; j < lums.size(); ++j) {
            if (j == i || !sameGldfVariant(*lums[i], *lums[j]) || before[j] != before[i] ||
                lums[j]->pose != before[j])
                continue;
            lums[j]->pose = lums[i]->pose;
        }
    }
}

}  // namespace

void applyEdit(EditorState& state, std::string_view label, unsigned changes,
               const std::function<void(Scene&)>& edit) {
    UndoHistory& h = state.history;
    bool recorded = (changes & ~unsigned(kChangeCamera)) != 0;
    bool merge =
        !h.undo.empty() && h.undo.back().label == label && h.undo.back().gesture == h.gesture;
    if (recorded && !merge) {
        h.undo.push_back({std::string(label), changes, h.gesture,
                          snapshot(state, (changes & kChangeGeometry) != 0)});
        if (h.undo.size() > UndoHistory::kMaxSteps) h.undo.erase(h.undo.begin());
    }
    if (recorded) {
        h.undo.back().changes |= changes;
        h.redo.clear();
    }
    std::vector<Pose> before;
    if (changes & kChangeLuminaires)
        for (const auto& l : state.scene.luminaires) before.push_back(l->pose);
    edit(state.scene);
    if (changes & kChangeLuminaires) keepGldfPlacementsTogether(state.scene, before);
    // Luminaire bodies follow their luminaires: the geometry changes with them.
    if ((changes & (kChangeLuminaires | kChangeGeometry)) && state.scene.updateBodies()) {
        changes |= kChangeGeometry;
        if (recorded) h.undo.back().changes |= kChangeGeometry;
    }
    state.pendingChanges |= changes;
    state.dirty = true;
    ++state.edits;
    if (changes & kChangeGeometry) ++state.geometryVersion;
}

std::vector<LibraryEntry> sceneLuminaireFiles(const Scene& scene) {
    std::map<std::string, std::pair<FileKind, int>> files;  // by absolute path: kind, users
    for (const auto& l : scene.luminaires) {
        std::vector<std::string> used;
        for (const std::string& file : sourceFiles(*l)) {
            FileKind kind = fileKind(file);
            // A light field's images and an L3D's parts are not luminaire files of their own.
            if (!luminaireKindOf(kind)) continue;
            std::string path = std::filesystem::absolute(file).lexically_normal().string();
            if (std::find(used.begin(), used.end(), path) != used.end()) continue;
            used.push_back(path);
            auto& entry = files[path];
            entry.first = kind;
            ++entry.second;
        }
    }
    std::vector<LibraryEntry> out;
    for (const auto& [path, what] : files)
        out.push_back({path,
                       std::filesystem::path(path).filename().string() + " (" +
                           std::to_string(what.second) +
                           (what.second == 1 ? " luminaire)" : " luminaires)"),
                       what.first});
    std::sort(out.begin(), out.end(),
              [](const LibraryEntry& a, const LibraryEntry& b) { return a.label < b.label; });
    return out;
}

double snapStep(const PlacementUi& placement) {
    bool ctrl = ImGui::GetCurrentContext() && ImGui::GetIO().KeyCtrl;
    return placement.snapping != ctrl ? placement.snap : 0.0;
}

const Bvh& surfaceBvh(EditorState& state) {
    PlacementUi& p = state.placement;
    if (!p.surfaces || p.surfacesVersion != state.geometryVersion) {
        p.surfaces = std::make_shared<const Bvh>(Bvh::build(state.scene));
        p.surfacesVersion = state.geometryVersion;
    }
    return *p.surfaces;
}

Pose poseOnSurface(const Pose& pose, const glm::dvec3& point, const glm::dvec3& normal,
                   bool aimAlongNormal, double clearance, double snap) {
    Pose out = pose;
    glm::dvec3 n = glm::normalize(normal);
    glm::dvec3 p = point;
    if (snap > 0.0) {
        // Round the two coordinates along the surface (those other than the normal's largest).
        glm::dvec3 a = glm::abs(n);
        int axis = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
        for (int i = 0; i < 3; ++i)
            if (i != axis) p[i] = std::round(p[i] / snap) * snap;
    }
    out.position = p + clearance * n;
    out.aim = aimAlongNormal ? n : glm::dvec3(0.0, -1.0, 0.0);
    return out;
}

bool undo(EditorState& state) {
    return step(state, state.history.undo, state.history.redo, "Undid");
}

bool redo(EditorState& state) {
    return step(state, state.history.redo, state.history.undo, "Redid");
}

void setStatus(EditorState& state, std::string message, bool error) {
    state.status = std::move(message);
    state.statusIsError = error;
}

bool addTaskAreaFromGrid(EditorState& state) {
    const GridSpec& g = state.measure.grid;
    if (!state.measure.extentSet || !(g.hi.x > g.lo.x) || !(g.hi.y > g.lo.y)) {
        setStatus(state, "Task area: give the grid an extent first (Scene bounds, Selected plane)",
                  true);
        return false;
    }
    TaskArea area;
    area.name = state.measure.taskName.empty() ? "Task area" : state.measure.taskName;
    area.plane = g.plane;
    area.lo = g.lo;
    area.hi = g.hi;
    area.required = state.measure.taskRequired;
    // The surfaces change no image: kChangeSettings records the step (and restarts the frame).
    applyEdit(state, "Add task area " + area.name, kChangeSettings,
              [&area](Scene& scene) { scene.taskAreas.push_back(area); });
    state.measure.surfaces.reset();
    return true;
}

bool addTaskAreaFromDrag(EditorState& state, const glm::dvec3& a, const glm::dvec3& b) {
    GridSpec& g = state.measure.grid;
    // In-plane coordinates rounded to 1 cm, as a designer types them.
    glm::dvec2 pa = g.plane.inPlane(a), pb = g.plane.inPlane(b);
    glm::dvec2 lo = glm::round(glm::min(pa, pb) * 100.0) / 100.0;
    glm::dvec2 hi = glm::round(glm::max(pa, pb) * 100.0) / 100.0;
    if (!(hi.x - lo.x >= kMinDrawnSide) || !(hi.y - lo.y >= kMinDrawnSide)) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "Task area: %.2f x %.2f m is too small (drag at least %.2f m on each side)",
                      hi.x - lo.x, hi.y - lo.y, kMinDrawnSide);
        setStatus(state, text, true);
        return false;
    }
    TaskArea area;
    area.name = state.measure.taskName.empty() ? "Task area" : state.measure.taskName;
    area.plane = g.plane;
    area.lo = lo;
    area.hi = hi;
    area.required = state.measure.taskRequired;
    applyEdit(state, "Draw task area " + area.name, kChangeSettings,
              [&area](Scene& scene) { scene.taskAreas.push_back(area); });
    g.lo = lo;
    g.hi = hi;
    state.measure.extentSet = true;
    state.measure.surfaces.reset();
    char text[200];
    std::snprintf(text, sizeof text, "Drew task area %s on %s: %s %.2f..%.2f m, %s %.2f..%.2f m",
                  area.name.c_str(), planeText(area.plane).c_str(), g.plane.uName().c_str(), lo.x,
                  hi.x, g.plane.vName().c_str(), lo.y, hi.y);
    setStatus(state, text);
    return true;
}

void removeTaskArea(EditorState& state, size_t index) {
    if (index >= state.scene.taskAreas.size()) return;
    applyEdit(
        state, "Remove task area " + state.scene.taskAreas[index].name, kChangeSettings,
        [index](Scene& scene) { scene.taskAreas.erase(scene.taskAreas.begin() + long(index)); });
    state.measure.surfaces.reset();
}

namespace {

/// The task areas' names, planes and extents as text: what followTaskAreas compares.
std::vector<std::string> areaKeys(const std::vector<TaskArea>& areas) {
    std::vector<std::string> keys;
    char text[200];
    for (const TaskArea& a : areas) {
        std::snprintf(text, sizeof text, "%s %.17g %.17g %.17g %.17g;", planeText(a.plane).c_str(),
                      a.lo.x, a.lo.y, a.hi.x, a.hi.y);
        keys.push_back(a.name + " " + text);
    }
    return keys;
}

}  // namespace

bool followTaskAreas(EditorState& state) {
    MeasureState& measure = state.measure;
    std::vector<std::string> keys = areaKeys(state.scene.taskAreas);
    std::string all;
    for (const std::string& k : keys) all += k;
    if (all == measure.followedAreas) return false;
    // One area more than before, the others as they were: the grid shows the new one.
    bool added = !measure.followedAreas.empty() && keys.size() >= 2 &&
                 all.size() > keys.back().size() &&
                 all.compare(0, all.size() - keys.back().size(), measure.followedAreas) == 0;
    measure.followedAreas = all;
    if (state.scene.taskAreas.empty()) return false;
    const TaskArea& a = added ? state.scene.taskAreas.back() : state.scene.taskAreas.front();
    measure.grid.plane = a.plane;
    measure.grid.lo = a.lo;
    measure.grid.hi = a.hi;
    measure.extentSet = true;
    return true;
}

bool addGlareObserverAtCamera(EditorState& state) {
    const Camera& c = state.scene.camera;
    glm::dvec3 view = c.target - c.position;
    GlareObserver o;
    o.name = state.measure.observerName.empty() ? "Observer" : state.measure.observerName;
    o.position = c.position;
    o.limit = state.measure.observerLimit;
    try {
        // Through the scene file's parser: the same checks, the view made horizontal.
        nlohmann::json entry = {{"name", o.name},
                                {"position", {o.position.x, o.position.y, o.position.z}},
                                {"view", {view.x, view.y, view.z}}};
        if (o.limit > 0.0) entry["limit"] = o.limit;
        o = parseGlareObserver(entry, json::Where{"the camera", ""});
    } catch (const std::exception& e) {
        setStatus(state, std::string("Glare observer: ") + e.what(), true);
        return false;
    }
    applyEdit(state, "Add glare observer " + o.name, kChangeSettings,
              [&o](Scene& scene) { scene.glareObservers.push_back(o); });
    state.measure.glare.reset();
    return true;
}

void removeGlareObserver(EditorState& state, size_t index) {
    if (index >= state.scene.glareObservers.size()) return;
    applyEdit(state, "Remove glare observer " + state.scene.glareObservers[index].name,
              kChangeSettings, [index](Scene& scene) {
                  scene.glareObservers.erase(scene.glareObservers.begin() + long(index));
              });
    state.measure.glare.reset();
}

void setFalseColour(EditorState& state, bool on) {
    ToneMapOperator& op = state.settings.toneMap;
    if (on == (op == ToneMapOperator::FalseColour)) return;  // already so: keep what it replaced
    if (on) {
        state.measure.previousOperator = op;
        op = ToneMapOperator::FalseColour;
    } else {
        op = state.measure.previousOperator;
    }
}

bool setProjectInfo(EditorState& state, const ProjectInfo& project) {
    const ProjectInfo& now = state.scene.project;
    if (now.name == project.name && now.client == project.client &&
        now.designer == project.designer && now.date == project.date &&
        now.description == project.description)
        return false;
    // Nothing the renderer draws changes; the settings flag records the step.
    applyEdit(state, "Project data", kChangeSettings, [&](Scene& s) { s.project = project; });
    return true;
}

void reportError(EditorState& state, const std::string& message) {
    setStatus(state, message, true);
    state.modalError = message;
}

void takeScene(EditorState& state, Scene scene) {
    // Unsaved edits of the scene being left stay in this session's autosave, offered when
    // that scene is opened again (or after this editor ends).
    if (state.dirty) writeAutosave(state);
    state.scene = std::move(scene);
    // The Measure panel's grid and results were the last scene's: the grid starts on this
    // scene's first task area (followTaskAreas) or, without one, on its floor's bounds.
    MeasureState& measure = state.measure;
    measure.grid.plane = CalcPlane{};
    measure.grid.lo = measure.grid.hi = glm::dvec2(0.0);
    measure.extentSet = false;
    measure.followedAreas.clear();
    measure.result.reset();
    measure.surfaces.reset();
    measure.glare.reset();
    measure.error.clear();
    measure.surfacesError.clear();
    measure.glareError.clear();
    followTaskAreas(state);
    if (state.scene.camera.exposure > 0.0)
        state.settings.exposure = float(state.scene.camera.exposure);
    state.selectedLuminaire = -1;
    state.alsoSelected.clear();
    state.selectedGeometry = -1;
    state.drag = {};
    state.inspectorError.clear();
    state.pendingChanges = kChangeAll;
    state.dirty = false;
    state.history = {};
    ++state.geometryVersion;
}

bool openSceneFile(EditorState& state, const std::string& path) {
    try {
        Scene loaded = loadScene(path);
        std::string onDisk = fileFingerprint(path);
        takeScene(state, std::move(loaded));
        if (state.scene.path.empty()) state.scene.path = path;
        state.project.onDisk = onDisk;
        state.project.conflict = false;
        setStatus(state, "Opened " + path);
        addRecentFile(path);
        // Unsaved edits of editors that crashed or quit: offered, never applied unasked.
        state.project.offers = findAutosaves(state.scene.path, state.project.session);
        if (!state.project.offers.empty())
            setStatus(state, "Opened " + path + "; unsaved edits of it were found (" +
                                 std::to_string(state.project.offers.size()) + " autosave" +
                                 (state.project.offers.size() > 1 ? "s" : "") + ")");
        return true;
    } catch (const std::exception& e) {
        reportError(state, std::string("Could not open scene: ") + e.what());
        return false;
    }
}

bool saveSceneFile(EditorState& state, const std::string& path, bool overwriteChanges) {
    std::string target = path.empty() ? state.scene.path : path;
    if (target.empty()) {
        reportError(state, "Save: the scene has no file yet; use File > Save As");
        return false;
    }
    try {
        // Every file the scene reads but its own may not be replaced by it (Save As onto the
        // luminaire's .ies, the environment map, a glTF buffer, ...); its own is what Save is for.
        bool own = !state.scene.path.empty() && sameFile(target, state.scene.path);
        std::vector<std::string> inputs = state.scene.inputFiles();
        std::erase_if(inputs, [&](const std::string& file) {
            return !state.scene.path.empty() && sameFile(file, state.scene.path);
        });
        ProtectedInputs protectedInputs(inputs);
        std::optional<InputReplacement> replacing;
        if (own) replacing.emplace(state.scene.path);  // the editor's own scene (Editor.cpp)
        checkNotAnInput(target, "Save As", "the scene");
        // Another editor or program changed the file since this editor read or wrote it: ask.
        std::error_code ec;
        if (own && !overwriteChanges && std::filesystem::exists(target, ec) &&
            fileFingerprint(target) != state.project.onDisk) {
            state.project.conflict = true;
            setStatus(state, target + " changed on disk since it was opened; not saved yet", true);
            return false;
        }
        saveScene(state.scene, target);
        replacing.reset();
        // This session's autosaves only (the untitled one too, when saving it as a file).
        removeAutosave(state.scene.path, state.project.session);
        removeAutosave(target, state.project.session);
        state.scene.path = target;
        state.dirty = false;
        state.project.onDisk = fileFingerprint(target);
        state.project.conflict = false;
        setStatus(state, "Saved " + target);
        addRecentFile(target);
        return true;
    } catch (const std::exception& e) {
        reportError(state, std::string("Could not save scene: ") + e.what());
        return false;
    }
}

std::string uniqueLuminaireName(const Scene& scene, const std::string& base,
                                const std::vector<std::string>& alsoTaken) {
    auto used = [&](const std::string& name) {
        for (const auto& lum : scene.luminaires)
            if (lum->name == name) return true;
        return std::find(alsoTaken.begin(), alsoTaken.end(), name) != alsoTaken.end();
    };
    if (!used(base)) return base;
    for (int n = 2;; ++n) {
        std::string name = base + " " + std::to_string(n);
        if (!used(name)) return name;
    }
}

namespace {

/// Places a new luminaire 0.5 m below the top of the scene, aimed down, and selects it (one undo
/// step).
int insertLuminaire(EditorState& state, const LuminaireKindInfo& kind,
                    std::unique_ptr<Luminaire> lum) {
    if (!lum) {
        reportError(state, "Add: kind " + std::string(kind.name) + " has no default luminaire");
        return -1;
    }
    const Scene& scene = state.scene;
    glm::dvec3 position(0.0, 2.5, 0.0);
    if (!scene.meshes.empty()) {
        glm::dvec3 lo(scene.boundsMin()), hi(scene.boundsMax());
        position = glm::dvec3(0.5 * (lo.x + hi.x), hi.y - 0.5, 0.5 * (lo.z + hi.z));
    }
    lum->pose.position = position;
    lum->pose.aim = glm::dvec3(0.0, -1.0, 0.0);
    lum->pose.c0 = glm::dvec3(1.0, 0.0, 0.0);
    lum->name = uniqueLuminaireName(scene, lum->name.empty() ? std::string(kind.name) : lum->name);
    if (lum->technique.empty()) lum->technique = std::string(kind.defaultTechnique);
    std::string label = "Add " + lum->name;
    // A GLDF variant placing several emitters comes with the others: added in the same step and
    // selected with it, so they move together.
    std::vector<std::unique_ptr<Luminaire>> more = companions(*lum);
    for (size_t k = 0; k < more.size(); ++k) {
        more[k]->name = lum->name + " #" + std::to_string(k + 1);
        more[k]->pose = lum->pose;
        more[k]->technique = lum->technique;
    }
    if (!more.empty()) lum->name += " #0";
    int first = int(scene.luminaires.size());
    applyEdit(state, label, kChangeLuminaires, [&](Scene& s) {
        s.luminaires.push_back(std::move(lum));
        for (auto& m : more) s.luminaires.push_back(std::move(m));
    });
    state.selectedLuminaire = first;
    state.alsoSelected.clear();
    for (int i = first + 1; i < int(state.scene.luminaires.size()); ++i)
        state.alsoSelected.push_back(i);
    state.selectedGeometry = -1;
    state.inspectorError.clear();
    return state.selectedLuminaire;
}

}  // namespace

int addLuminaire(EditorState& state, const LuminaireKindInfo& kind) {
    try {
        auto create = kind.adapter().create;
        return insertLuminaire(state, kind, create ? create() : nullptr);
    } catch (const std::exception& e) {
        reportError(state, "Add " + std::string(kind.name) + ": " + e.what());
        return -1;
    }
}

FileKind fileKind(const std::string& path) {
    std::string lower = path;
    for (char& c : lower) c = char(std::tolower((unsigned char)c));
    auto endsWith = [&](std::string_view suffix) {
        return lower.size() >= suffix.size() &&
               lower.compare(lower.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    if (endsWith(".ies") || endsWith(".ldt") || endsWith(".xml") || endsWith(".iesxml"))
        return FileKind::Photometric;  // .xml and .iesxml: IES TM-33
    if (endsWith(".gldf")) return FileKind::Gldf;
    if (endsWith(".lf.json")) return FileKind::LightField;
    if (endsWith(".hdr") || endsWith(".exr")) return FileKind::Environment;
    if (endsWith(".gltf") || endsWith(".glb")) return FileKind::Geometry;
    return FileKind::Unknown;
}

const char* luminaireKindOf(FileKind kind) {
    return kind == FileKind::Photometric  ? "photometric"
           : kind == FileKind::LightField ? "lightfield"
           : kind == FileKind::Gldf       ? "gldf"
                                          : nullptr;
}

std::unique_ptr<Luminaire> luminaireFromFile(const std::string& path) {
    const char* type = luminaireKindOf(fileKind(path));
    if (!type)
        throw InputError(path +
                         ": cannot make a luminaire from this file (expected .ies, .ldt, .xml or "
                         ".iesxml (TM-33), .gldf or .lf.json)");
    // Through the scene-file parser, so the file gets the same checks as a loaded scene's (a
    // .gldf: its first variant).
    nlohmann::json entry = {{"type", type}, {"file", path}};
    const LuminaireFormatInfo* format = findFormat(type);
    LuminaireParser parse = format ? format->parse : findKind(type)->adapter().parse;
    std::unique_ptr<Luminaire> lum = parse(entry, json::Where{path, "file"});
    std::string stem = std::filesystem::path(path).filename().string();
    lum->name = stem.substr(0, stem.find('.'));
    lum->technique = std::string(findKind(lum->kind()).defaultTechnique);
    return lum;
}

int addLuminaireFromFile(EditorState& state, const std::string& path) {
    try {
        std::unique_ptr<Luminaire> lum = luminaireFromFile(path);
        const LuminaireKindInfo& info = findKind(lum->kind());
        int index = insertLuminaire(state, info, std::move(lum));
        if (index >= 0)
            setStatus(state,
                      "Added " + state.scene.luminaires[size_t(index)]->name + " from " + path);
        return index;
    } catch (const std::exception& e) {
        reportError(state, e.what());
        return -1;
    }
}

bool dropFile(EditorState& state, const std::string& path) {
    FileKind kind = fileKind(path);
    std::string absolute = std::filesystem::absolute(path).lexically_normal().string();
    try {
        if (kind == FileKind::Environment) {
            nlohmann::json entry = {{"file", absolute}};
            EnvironmentSource env =
                parseEnvironment(entry, json::Where{path, "dropped environment"},
                                 std::filesystem::path(absolute).parent_path().string());
            applyEdit(state, "Environment " + std::filesystem::path(path).filename().string(),
                      kChangeEnvironment, [&](Scene& s) {
                          s.environment = entry;
                          s.environmentMap = env.map;
                          s.environmentSequence = env.sequence;
                      });
            setStatus(state, "Environment map: " + absolute);
            return true;
        }
        if (kind == FileKind::Geometry) {
            // Parsed as a one-entry scene, then appended: meshes, their materials, the entry.
            nlohmann::json doc = {{"geometry", nlohmann::json::array({{{"gltf", absolute}}})}};
            Scene part = parseScene(doc, absolute);
            applyEdit(state, "Add " + std::filesystem::path(path).filename().string(),
                      kChangeGeometry, [&](Scene& s) {
                          uint32_t materialBase = uint32_t(s.materials.size());
                          uint32_t meshBase = uint32_t(s.meshes.size());
                          for (Material& m : part.materials) s.materials.push_back(std::move(m));
                          for (Mesh& m : part.meshes) {
                              m.material += materialBase;
                              s.meshes.push_back(std::move(m));
                          }
                          for (GeometryItem& g : part.geometry) {
                              for (uint32_t& m : g.meshes) m += meshBase;
                              s.geometry.push_back(std::move(g));
                          }
                      });
            setStatus(state, "Added geometry from " + absolute);
            return true;
        }
        if (luminaireKindOf(kind)) {
            int index = addLuminaireFromFile(state, absolute);
            if (index >= 0) state.placement.armed = true;
            return index >= 0;
        }
        reportError(state, path +
                               ": cannot open a dropped file of this type (expected .ies, .ldt, "
                               ".xml, .gldf, .lf.json, "
                               ".hdr, .exr, .gltf or .glb)");
        return false;
    } catch (const std::exception& e) {
        reportError(state, e.what());
        return false;
    }
}

bool swapLuminaireFile(EditorState& state, int index, const std::string& path) {
    if (index < 0 || index >= int(state.scene.luminaires.size())) return false;
    try {
        std::unique_ptr<Luminaire> lum = luminaireFromFile(path);
        const Luminaire& old = *state.scene.luminaires[size_t(index)];
        lum->pose = old.pose;
        lum->name = old.name;
        if (findTechnique(lum->kind(), old.technique)) lum->technique = old.technique;
        std::string label = "Swap " + old.name;
        applyEdit(state, label, kChangeLuminaires,
                  [&](Scene& s) { s.luminaires[size_t(index)] = std::move(lum); });
        setStatus(state, "Swapped " + state.scene.luminaires[size_t(index)]->name + " for " + path +
                             " (pose kept)");
        return true;
    } catch (const std::exception& e) {
        reportError(state, "Swap: " + std::string(e.what()));
        return false;
    }
}

std::vector<int> selectedLuminaires(const EditorState& state) {
    std::vector<int> out;
    int n = int(state.scene.luminaires.size());
    if (state.selectedLuminaire >= 0 && state.selectedLuminaire < n)
        out.push_back(state.selectedLuminaire);
    for (int i : state.alsoSelected)
        if (i >= 0 && i < n && std::find(out.begin(), out.end(), i) == out.end()) out.push_back(i);
    std::sort(out.begin(), out.end());
    return out;
}

void toggleSelected(EditorState& state, int index) {
    if (index < 0 || index >= int(state.scene.luminaires.size())) return;
    std::vector<int> group = selectedLuminaires(state);
    auto it = std::find(group.begin(), group.end(), index);
    bool adding = it == group.end();
    if (adding)
        group.push_back(index);
    else
        group.erase(it);
    state.selectedLuminaire = group.empty() ? -1 : adding ? index : group.front();
    state.alsoSelected.clear();
    for (int i : group)
        if (i != state.selectedLuminaire) state.alsoSelected.push_back(i);
    state.selectedGeometry = -1;
    state.inspectorError.clear();
}

void deleteSelected(EditorState& state) {
    std::vector<int> group = selectedLuminaires(state);
    if (group.empty()) return;
    if (group.size() == 1) {
        deleteLuminaire(state, group.front());
        return;
    }
    std::string label = "Delete " + std::to_string(group.size()) + " luminaires";
    applyEdit(state, label, kChangeLuminaires, [&](Scene& s) {
        for (auto it = group.rbegin(); it != group.rend(); ++it)
            s.luminaires.erase(s.luminaires.begin() + *it);
    });
    state.selectedLuminaire = -1;
    state.alsoSelected.clear();
    state.drag = {};
    state.inspectorError.clear();
}

int arrayLuminaire(EditorState& state, int index, int nx, int nz, double dx, double dz) {
    if (index < 0 || index >= int(state.scene.luminaires.size())) return 0;
    nx = std::clamp(nx, 1, 50);
    nz = std::clamp(nz, 1, 50);
    const Luminaire& source = *state.scene.luminaires[size_t(index)];
    std::vector<std::unique_ptr<Luminaire>> copies;
    std::vector<std::string> names;  // the copies' names so far
    for (int k = 0; k < nz; ++k)
        for (int i = 0; i < nx; ++i) {
            if (i == 0 && k == 0) continue;  // the source itself
            std::unique_ptr<Luminaire> copy = source.clone();
            copy->pose.position += glm::dvec3(i * dx, 0.0, k * dz);
            copy->name = uniqueLuminaireName(state.scene, source.name, names);
            names.push_back(copy->name);
            copies.push_back(std::move(copy));
        }
    if (copies.empty()) return 0;
    int added = int(copies.size());
    char label[160];
    std::snprintf(label, sizeof label, "Array %d x %d of %s", nx, nz, source.name.c_str());
    applyEdit(state, label, kChangeLuminaires, [&](Scene& s) {
        for (auto& copy : copies) s.luminaires.push_back(std::move(copy));
    });
    setStatus(state, std::string(label) + ": added " + std::to_string(added));
    return added;
}

int duplicateLuminaire(EditorState& state, int index) {
    if (index < 0 || index >= int(state.scene.luminaires.size())) return -1;
    std::unique_ptr<Luminaire> copy = state.scene.luminaires[size_t(index)]->clone();
    copy->name = uniqueLuminaireName(state.scene, copy->name);
    copy->pose.position.x += 0.25;
    std::string label = "Duplicate " + copy->name;
    applyEdit(state, label, kChangeLuminaires,
              [&](Scene& s) { s.luminaires.push_back(std::move(copy)); });
    state.selectedLuminaire = int(state.scene.luminaires.size()) - 1;
    state.alsoSelected.clear();
    state.inspectorError.clear();
    return state.selectedLuminaire;
}

void deleteLuminaire(EditorState& state, int index) {
    if (index < 0 || index >= int(state.scene.luminaires.size())) return;
    std::string label = "Delete " + state.scene.luminaires[size_t(index)]->name;
    applyEdit(state, label, kChangeLuminaires,
              [&](Scene& s) { s.luminaires.erase(s.luminaires.begin() + index); });
    if (state.selectedLuminaire == index)
        state.selectedLuminaire = -1;
    else if (state.selectedLuminaire > index)
        --state.selectedLuminaire;
    if (state.drag.mode == DragMode::Luminaire) state.drag = {};
    state.inspectorError.clear();
    state.alsoSelected.clear();
}

void replaceLuminaire(EditorState& state, int index, std::unique_ptr<Luminaire> replacement) {
    if (index < 0 || index >= int(state.scene.luminaires.size()) || !replacement) return;
    const Luminaire& old = *state.scene.luminaires[size_t(index)];
    replacement->pose = old.pose;
    replacement->name = old.name;
    replacement->technique = old.technique;
    applyEdit(state, "Edit " + old.name, kChangeLuminaires,
              [&](Scene& s) { s.luminaires[size_t(index)] = std::move(replacement); });
}

}  // namespace candela::ui
