#include "scene/LayoutGrid.h"

#include <algorithm>
#include <cmath>

#include "scene/Procedural.h"

namespace candela {

LayoutFrame layoutFrame(const Scene& scene, const TaskArea& area) {
    LayoutFrame f;
    const glm::dvec3 a0 = area.plane.point(area.lo.x, area.lo.y);
    const glm::dvec3 a1 = area.plane.point(area.hi.x, area.hi.y);
    const glm::dvec2 middle(0.5 * (a0.x + a1.x), 0.5 * (a0.z + a1.z));
    for (const GeometryItem& item : scene.geometry) {
        auto room = item.source.find("room");
        if (room == item.source.end()) continue;
        std::vector<glm::dvec2> corners;
        for (const nlohmann::json& c : (*room)["floor"])
            corners.push_back({c[0].get<double>(), c[1].get<double>()});
        if (!insidePolygon(corners, middle)) continue;
        f.lo = f.hi = corners.front();
        for (const glm::dvec2& c : corners) {
            f.lo = glm::min(f.lo, c);
            f.hi = glm::max(f.hi, c);
        }
        f.outline = std::move(corners);
        f.floorY = room->value("elevation", 0.0);
        return f;
    }
    if (scene.hasSurfaces()) {
        const glm::dvec3 lo(scene.boundsMin()), hi(scene.boundsMax());
        f.lo = {lo.x, lo.z};
        f.hi = {hi.x, hi.z};
        f.floorY = lo.y;
        return f;
    }
    f.lo = {std::min(a0.x, a1.x), std::min(a0.z, a1.z)};
    f.hi = {std::max(a0.x, a1.x), std::max(a0.z, a1.z)};
    return f;
}

std::vector<glm::dvec3> layoutPositions(const LayoutFrame& frame, int columns, int rows,
                                        double mountingHeight) {
    std::vector<glm::dvec3> positions;
    const glm::dvec2 spacing = (frame.hi - frame.lo) / glm::dvec2(columns, rows);
    auto millimetre = [](double x) { return std::round(x * 1000.0) / 1000.0 + 0.0; };
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            glm::dvec2 p = frame.lo + glm::dvec2((i + 0.5) * spacing.x, (j + 0.5) * spacing.y);
            if (!frame.outline.empty() && !insidePolygon(frame.outline, p)) continue;
            positions.push_back(
                {millimetre(p.x), millimetre(frame.floorY + mountingHeight), millimetre(p.y)});
        }
    return positions;
}

std::vector<nlohmann::json> parseLayout(const nlohmann::json& item, const json::Where& where,
                                        const Scene& scene, size_t maxLuminaires) {
    json::checkKeys(item, {"name", "area", "grid", "height", "luminaire"}, where);
    const std::string name =
        json::optional(item, "name", where, std::string("Layout"), json::string);
    const TaskArea* area = nullptr;
    const std::string areaName = json::optional(item, "area", where, std::string(), json::string);
    for (const TaskArea& a : scene.taskAreas)
        if (areaName.empty() ? scene.taskAreas.size() == 1 : a.name == areaName) area = &a;
    if (!area)
        json::fail(where / "area", areaName.empty()
                                       ? "the task area the layout lights (the scene has " +
                                             std::to_string(scene.taskAreas.size()) + ")"
                                       : "one of the scene's task areas, got \"" + areaName + "\"");
    if (!item.contains("grid"))
        json::fail(where / "grid", "[columns along x, rows along z] (missing)");
    const glm::dvec2 grid = json::vec2(item["grid"], where / "grid");
    for (int k = 0; k < 2; ++k)
        if (grid[k] != std::floor(grid[k]) || grid[k] < 1 || grid[k] > double(maxLuminaires))
            json::fail((where / "grid")[k],
                       "a whole number of luminaires from 1 to " + std::to_string(maxLuminaires));
    if (grid.x * grid.y > double(maxLuminaires))
        json::fail(where / "grid", "at most " + std::to_string(maxLuminaires) +
                                       " luminaires in all, got " +
                                       std::to_string(grid.x * grid.y));
    if (!item.contains("height"))
        json::fail(where / "height", "the mounting height above the floor in metres (missing)");
    const double height = json::length(item["height"], where / "height");
    if (!item.contains("luminaire") || !item["luminaire"].is_object())
        json::fail(where / "luminaire", "a luminaire entry (type, file, ...) without a position");
    for (const char* key : {"position", "name"})
        if (item["luminaire"].contains(key))
            json::fail(where / "luminaire" / key,
                       std::string("no ") + key + ": the layout places and names its luminaires");
    const LayoutFrame frame = layoutFrame(scene, *area);
    std::vector<nlohmann::json> entries;
    for (const glm::dvec3& p : layoutPositions(frame, int(grid.x), int(grid.y), height)) {
        nlohmann::json entry = item["luminaire"];
        entry["position"] = {p.x, p.y, p.z};
        entry["name"] = name + " " + std::to_string(entries.size() + 1);
        entries.push_back(std::move(entry));
    }
    return entries;
}

}  // namespace candela
