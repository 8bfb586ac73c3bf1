#pragma once
// What a scene asks to be measured, as its file states it: calculation planes, EN 12464-1 task
// areas with their requirements, calculation points, and the observers where glare is rated.
// Read and written with the scene (scene/SceneIo.h); evaluated by the calculations
// (calculation/CalculationSurfaces.h, calculation/Glare.h).

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "util/JsonRead.h"

namespace candela {

/// An axis-aligned calculation plane: points with coordinate `offset` (m) along `axis`
/// (0 x, 1 y, 2 z), receiving light on the side of the normal `sign` * axis. Its in-plane axes
/// (u, v) are the two others in x, y, z order: y plane (x, z), x plane (y, z), z plane (x, y).
/// `candela grid` and scene files write one as text (parsePlane).
struct CalcPlane {
    int axis = 1;
    double offset = 0.0;  ///< Metres.
    double sign = 1.0;    ///< +1 or -1: which way the receiving side faces.
    glm::dvec3 normal() const;
    glm::dvec3 point(double u, double v) const;  ///< World point (m) at in-plane coordinates (m).
    glm::dvec2 inPlane(const glm::dvec3& p) const;  ///< A point's (u, v), m: point()'s inverse.
    std::string axisName() const;                   ///< "x", "y" or "z": the normal's axis.
    std::string uName() const;                      ///< "x", "y" or "z".
    std::string vName() const;
};

/// "[+|-]x|y|z=VALUE" (metres): "y=0.8" faces up, "-x=2.5" faces -x. Errors name `what`.
CalcPlane parsePlane(const std::string& text, const std::string& what = "plane");
/// The text parsePlane reads ("y=0.8", "-x=2.5").
std::string planeText(const CalcPlane& plane);

struct Requirement {
    double em = 0.0;  ///< Maintained illuminance, lx: Em must reach it; 0: none.
    double u0 = 0.0;  ///< Uniformity Emin / Em must reach it; 0: none.
    bool any() const { return em > 0.0 || u0 > 0.0; }
    bool operator==(const Requirement&) const = default;
};

/// A task area: a rectangle on an axis-aligned plane, usually the horizontal work plane.
struct TaskArea {
    std::string name;
    CalcPlane plane;
    glm::dvec2 lo{0.0}, hi{0.0};  ///< In-plane extent (CalcPlane's u, v), m.
    Requirement required;
    double spacing = 0.0;      ///< Grid spacing, m; 0: the standard's rule.
    bool surroundings = true;  ///< Also evaluate its immediate surrounding and background.
    /// Cylindrical illuminance Ez at each point (a horizontal plane only, no surroundings: Table
    /// 1 is for the task's own illuminance) instead of the illuminance on the plane.
    bool cylindrical = false;
};

/// Illuminance at a point on a surface element with a normal, or cylindrical illuminance (the
/// mean vertical illuminance over all horizontal directions, world y up).
struct CalcPoint {
    std::string name;
    glm::dvec3 position{0.0};
    glm::dvec3 normal{0.0, 1.0, 0.0};  ///< Unit; unused when cylindrical.
    bool cylindrical = false;
    double requiredLux = 0.0;  ///< 0: none.
};

/// Scene-file entries ("task_areas", "calculation_points"), checked like every field.
TaskArea parseTaskArea(const nlohmann::json& entry, const json::Where& where);
CalcPoint parseCalcPoint(const nlohmann::json& entry, const json::Where& where);
nlohmann::json toJson(const TaskArea& area);
nlohmann::json toJson(const CalcPoint& point);

/// Where an observer sits and looks: a scene file's "glare_observers" entry
/// {"name", "position": eye [x, y, z] m, "view": [x, y, z] (made horizontal), "limit": UGR_L,
///  "background_cd_m2": Lb}.
struct GlareObserver {
    std::string name = "observer";
    glm::dvec3 position{0.0, 1.2, 0.0};  ///< The eye, m (EN 12464-1's seated eye height 1.2 m).
    glm::dvec3 view{0.0, 0.0, -1.0};     ///< Unit and horizontal: the line of sight.
    double limit = 0.0;                  ///< UGR_L the observer's task allows; 0: none.
    double background = 0.0;  ///< Lb, cd/m2; 0: from the interreflected light at the eye.
    bool operator==(const GlareObserver&) const = default;
};

GlareObserver parseGlareObserver(const nlohmann::json& entry, const json::Where& where);
nlohmann::json toJson(const GlareObserver& observer);

}  // namespace candela
