// The Library panel: the luminaire files (.ies, .ldt, TM-33 .xml/.iesxml, .gldf, .lf.json) under
// resources/luminaires and in folders the user adds, each with a thumbnail of the light it casts on
// a floor 1 m below (luminaires/lightfield/FarField.h: footprintImage; a light field through its
// far field; a GLDF container through its first variant, listed with its manufacturer, product and
// variants). Add puts one in the scene and arms placement; Swap replaces the selected luminaire's
// file keeping its pose. Thumbnails are made one per frame, only while the panel shows them.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "formats/Gldf.h"
#include "luminaires/lightfield/FarField.h"
#include "luminaires/lightfield/LightField.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/SceneIo.h"
#include "ui/ImGuiUtil.h"
#include "ui/Panels.h"
#include "ui/Project.h"

namespace candela::ui {

namespace fs = std::filesystem;

namespace {

constexpr int kThumbnailPixels = 48;  ///< Thumbnail side, pixels (shown at this size).

constexpr const char* kLibraryFile = "library.json";  ///< In the state folder (ui/Project.h).

void saveFolders(EditorState& state) {
    try {
        writeStateList(kLibraryFile, "folders", state.library.folders);
    } catch (const std::exception& e) {
        setStatus(state, std::string("Library folders not kept: ") + e.what(), true);
    }
}

/// Whether an .xml file's first kilobytes name a TM-33 root element.
bool looksLikeTm33(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return false;  // a FIFO would block the scan
    std::ifstream in(path, std::ios::binary);
    std::string head(4096, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    head.resize(size_t(in.gcount()));
    return head.find("<IESTM33") != std::string::npos;
}

void scan(LibraryUi& lib) {
    lib.entries.clear();
    std::vector<std::string> roots = {std::string(CANDELA_SOURCE_DIR) + "/resources/luminaires"};
    roots.insert(roots.end(), lib.folders.begin(), lib.folders.end());
    for (const std::string& root : roots) {
        std::error_code ec;
        for (auto it = fs::recursive_directory_iterator(
                 root, fs::directory_options::skip_permission_denied, ec);
             !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
            if (!it->is_regular_file(ec)) continue;
            FileKind kind = fileKind(it->path().string());
            // Every .xml is not TM-33 (an unpacked L3D's structure.xml): list those that say so.
            if (!luminaireKindOf(kind)) continue;
            if (it->path().extension() == ".xml" && !looksLikeTm33(it->path())) continue;
            if (luminaireKindOf(kind))
                lib.entries.push_back({fs::absolute(it->path()).lexically_normal().string(),
                                       it->path().filename().string(), kind});
        }
    }
    std::sort(lib.entries.begin(), lib.entries.end(),
              [](const LibraryEntry& a, const LibraryEntry& b) { return a.label < b.label; });
    lib.scanned = true;
}

/// The key of a file's thumbnail in EditorState::images.
std::string thumbnailImage(const LibraryEntry& entry) {
    return "library:" + entry.path;
}

/// The thumbnail (uploaded to `images`) and one line of facts of a file (its flux), made once.
void makeThumbnail(LibraryUi& lib, ImageTextures& images, const LibraryEntry& entry) {
    LibraryUi::Thumbnail& t = lib.thumbnails[entry.path];
    try {
        std::shared_ptr<const PhotometricData> table;
        char info[160];
        if (entry.kind == FileKind::Gldf) {
            // The product line first, so a container whose first variant cannot be placed still
            // says what it is.
            GldfProduct product = loadGldf(entry.path);
            t.info = product.manufacturer + " " + product.productName + ", " +
                     std::to_string(product.variants.size()) + " variant(s):";
            for (const GldfVariant& v : product.variants)
                t.info += " " + (v.name.empty() ? v.id : v.name) + ";";
            PhotometricLuminaire light;
            light.loadGldf(entry.path, "");
            table = light.data;
            std::snprintf(info, sizeof info, " first: %s, %.0f lm", table->format.c_str(),
                          table->fluxFromTable());
            t.info += info;
            std::vector<unsigned char> rgb = footprintImage(*table, kThumbnailPixels);
            images.upload(thumbnailImage(entry), kThumbnailPixels, kThumbnailPixels, rgb);
            t.hasImage = true;
            return;
        }
        if (entry.kind == FileKind::LightField) {
            auto model = std::make_shared<LightFieldLuminaire>();
            model->data = LightFieldData::load(entry.path);
            table = photometricModel(*farFieldTwin(Luminaire(model)))->data;
            std::snprintf(info, sizeof info, "light field, %d x %d images, %.0f lm",
                          model->data->count.x, model->data->count.y, model->data->cachedPower().y);
        } else {
            table = PhotometricLuminaire::load(entry.path);
            std::snprintf(info, sizeof info, "%s, %.0f lm%s", table->format.c_str(),
                          table->fluxFromTable(),
                          table->warnings.empty() ? "" : ", with warnings (see the inspector)");
        }
        std::vector<unsigned char> rgb = footprintImage(*table, kThumbnailPixels);
        images.upload(thumbnailImage(entry), kThumbnailPixels, kThumbnailPixels, rgb);
        t.hasImage = true;
        t.info = info;
    } catch (const std::exception& e) {
        t.failed = true;
        t.info += (t.info.empty() ? "" : " ") + std::string(e.what());
    }
}

/// One file of the library: its thumbnail (made here when none is yet and `madeOne` is false:
/// at most one a frame), its label and what was read, Add and Swap. True when the scene changed.
bool libraryRow(EditorState& state, const LibraryEntry& entry, bool& madeOne) {
    LibraryUi& lib = state.library;
    bool changed = false;
    int selected = state.selectedLuminaire;
    ImGui::PushID(entry.path.c_str());
    auto found = lib.thumbnails.find(entry.path);
    float rowTop = ImGui::GetCursorPosY();
    if (found == lib.thumbnails.end() && !madeOne && state.images &&
        ImGui::IsRectVisible(ImVec2(1.f, float(kThumbnailPixels)))) {
        makeThumbnail(lib, *state.images, entry);
        madeOne = true;
        found = lib.thumbnails.find(entry.path);
    }
    ImageTextures::Shown thumbnail =
        found != lib.thumbnails.end() && found->second.hasImage && state.images
            ? state.images->find(thumbnailImage(entry))
            : ImageTextures::Shown{};
    if (thumbnail.id) {
        ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(thumbnail.id)),
                     ImVec2(float(kThumbnailPixels), float(kThumbnailPixels)));
        itemTooltip(
            "Illuminance on a floor 1 m below it, aimed down, over 5 x 5 m (log scale, 3 decades)");
    } else {
        ImGui::Dummy(ImVec2(float(kThumbnailPixels), float(kThumbnailPixels)));
    }
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::TextUnformatted(entry.label.c_str());
    if (found != lib.thumbnails.end()) {
        if (found->second.failed)
            ImGui::TextColored(errorColour(), "cannot read: %s", found->second.info.c_str());
        else
            ImGui::TextDisabled("%s", found->second.info.c_str());
    }
    if (ImGui::SmallButton("Add")) {
        int index = addLuminaireFromFile(state, entry.path);
        if (index >= 0) {
            state.placement.armed = true;
            setStatus(state, "Added " + state.scene.luminaires[size_t(index)]->name +
                                 ": click a surface to place it (Escape keeps it where it is)");
        }
        changed = true;
    }
    recordRect(state, "library.add:" + entry.label);
    itemTooltip(entry.path);
    ImGui::SameLine();
    ImGui::BeginDisabled(selected < 0);
    if (ImGui::SmallButton("Swap"))
        changed = swapLuminaireFile(state, selected, entry.path) || changed;
    recordRect(state, "library.swap:" + entry.label);
    ImGui::EndDisabled();
    itemTooltip("Replace the selected luminaire's file with this one, keeping its pose and name");
    ImGui::EndGroup();
    ImGui::SetCursorPosY(std::max(ImGui::GetCursorPosY(), rowTop + float(kThumbnailPixels) + 4.f));
    ImGui::PopID();
    return changed;
}

/// The folders added to the library: a field and Add folder, and each with Remove.
void libraryFolders(EditorState& state) {
    LibraryUi& lib = state.library;
    ImGui::SetNextItemWidth(-70.f);
    ImGui::InputTextWithHint("##folder", "folder with .ies / .ldt / .xml / .gldf / .lf.json",
                             &lib.folderText);
    ImGui::SameLine();
    if (ImGui::Button("Add folder")) {
        std::error_code ec;
        fs::path folder = fs::absolute(lib.folderText).lexically_normal();
        if (lib.folderText.empty() || !fs::is_directory(folder, ec)) {
            reportError(state, "Library: \"" + lib.folderText + "\" is not a folder");
        } else if (std::find(lib.folders.begin(), lib.folders.end(), folder.string()) ==
                   lib.folders.end()) {
            lib.folders.push_back(folder.string());
            saveFolders(state);
            scan(lib);
            lib.folderText.clear();
        }
    }
    for (size_t i = 0; i < lib.folders.size(); ++i) {
        ImGui::PushID(int(i));
        ImGui::TextDisabled("%s", lib.folders[i].c_str());
        ImGui::SameLine();
        if (ImGui::SmallButton("Remove")) {
            lib.folders.erase(lib.folders.begin() + long(i));
            saveFolders(state);
            scan(lib);
            ImGui::PopID();
            break;
        }
        ImGui::PopID();
    }
}

}  // namespace

bool libraryPanel(EditorState& state, const PanelRect& rect) {
    LibraryUi& lib = state.library;
    if (!lib.scanned) {
        lib.folders = readStateList(kLibraryFile, "folders");
        scan(lib);
    }
    placeNextWindow(rect);
    ImGui::Begin("Library", nullptr, kPanelFlags);
    recordPanelRect(state, "library");
    bool changed = false;
    bool madeOne = false;  // at most one new thumbnail per frame
    // The files the open scene uses first (where they are, beside the bundled ones or not).
    std::vector<LibraryEntry> used = sceneLuminaireFiles(state.scene);
    std::string usedHeader = "In this scene (" + std::to_string(used.size()) + ")###library_scene";
    if (!used.empty() &&
        ImGui::CollapsingHeader(usedHeader.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::PushID("scene");  // a file may be listed below too
        for (const LibraryEntry& entry : used)
            changed = libraryRow(state, entry, madeOne) || changed;
        ImGui::PopID();
    }
    recordRect(state, "library.in_scene");
    std::string allHeader = "Library (" + std::to_string(lib.entries.size()) + ")###library_all";
    if (ImGui::CollapsingHeader(allHeader.c_str(), ImGuiTreeNodeFlags_DefaultOpen))
        for (const LibraryEntry& entry : lib.entries)
            changed = libraryRow(state, entry, madeOne) || changed;
    ImGui::Separator();
    libraryFolders(state);
    ImGui::End();
    return changed;
}

}  // namespace candela::ui
