// The report's rooms (report/Report.h): what stands in each room of the design (roomSummaries),
// each room's data and its plan seen from above, and the power density of each.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "report/ReportSections.h"
#include "scene/Procedural.h"
#include "scene/Scene.h"

namespace candela {

namespace {

/// How far outside its room a luminaire may stand and still be the room's, m: one on the ceiling
/// has its position at the ceiling's height, and rounding of written decimals moves it.
constexpr double kInsideSlack = 0.01;

/// Whether point `p` (m) lies within room `r` (its outline, from its floor to its ceiling).
bool holds(const RoomSummary& r, const glm::dvec3& p) {
    if (!insidePolygon(r.room->floor, {p.x, p.z})) return false;
    return p.y >= r.floorY - kInsideSlack && p.y <= r.floorY + r.height + kInsideSlack;
}

glm::dvec3 middleOf(const TaskArea& a) {
    return a.plane.point(0.5 * (a.lo.x + a.hi.x), 0.5 * (a.lo.y + a.hi.y));
}

}  // namespace

double RoomSummary::powerDensity() const {
    if (powerUnstated > 0 || !(area > 0.0)) return -1.0;
    return power / area;
}

double RoomSummary::powerDensityPer100Lux() const {
    const double density = powerDensity();
    if (density < 0.0 || !(em > 0.0)) return -1.0;
    return density / (em / 100.0);
}

std::vector<RoomSummary> roomSummaries(const Scene& scene, const SurfaceReport& surfaces) {
    std::vector<RoomSummary> out;
    for (size_t i = 0; i < scene.geometry.size(); ++i) {
        std::optional<RoomSpec> room = roomSpec(scene, i);
        if (!room) continue;
        RoomSummary r;
        r.name = room->name;
        r.lo = r.hi = room->floor.front();
        for (const glm::dvec2& c : room->floor) {
            r.lo = glm::min(r.lo, c);
            r.hi = glm::max(r.hi, c);
        }
        r.floorY = room->elevation;
        r.height = room->height;
        r.area = room->area();
        r.room = std::move(room);
        out.push_back(std::move(r));
    }
    const bool bounds = out.empty();
    if (bounds) {
        // No room entry: the scene's overall size stands in, and everything is in it.
        RoomSummary r;
        r.name = "The room";
        if (scene.hasSurfaces()) {
            const glm::dvec3 lo(scene.boundsMin()), hi(scene.boundsMax());
            r.lo = {lo.x, lo.z};
            r.hi = {hi.x, hi.z};
            r.floorY = lo.y;
            r.height = hi.y - lo.y;
            r.area = (hi.x - lo.x) * (hi.z - lo.z);
        }
        out.push_back(std::move(r));
    }
    for (RoomSummary& r : out) {
        for (size_t k = 0; k < scene.luminaires.size(); ++k) {
            const Luminaire& l = *scene.luminaires[k];
            if (l.atInfinity() || (!bounds && !holds(r, l.pose.position))) continue;
            r.luminaires.push_back(k);
            const double watts = luminaireInputPower(l);
            if (watts > 0.0)
                r.power += watts;
            else
                ++r.powerUnstated;
        }
        for (size_t i = 0; i < scene.geometry.size(); ++i)
            if (std::optional<FurnitureSpec> f = furnitureSpec(scene, i);
                f && (bounds || holds(r, f->position)))
                r.furniture.push_back(i);
        double largest = -1.0;
        for (size_t k = 0; k < scene.taskAreas.size(); ++k) {
            const TaskArea& a = scene.taskAreas[k];
            if (!bounds && !holds(r, middleOf(a))) continue;
            r.taskAreas.push_back(k);
            // The reference: the largest horizontal task area that was computed.
            if (a.plane.axis != 1 || a.cylindrical) continue;
            const double size = (a.hi.x - a.lo.x) * (a.hi.y - a.lo.y);
            for (const SurfaceResult& s : surfaces.surfaces)
                if (s.role == "task area" && s.name == a.name && s.summary.count > 0 &&
                    size > largest) {
                    largest = size;
                    r.reference = a.name;
                    r.em = s.summary.eAvg;
                }
        }
    }
    return out;
}

namespace report_detail {

namespace {

/// "0.50", or "(0.60, 0.50, 0.40)" for a coloured reflectance.
std::string reflectanceText(const glm::dvec3& rho) {
    if (rho.x == rho.y && rho.y == rho.z) return fmt("%.2f", rho.x);
    return "(" + fmt("%.2f", rho.x) + ", " + fmt("%.2f", rho.y) + ", " + fmt("%.2f", rho.z) + ")";
}

/// "floor 0.20, walls 0.50, ceiling 0.70; wall 2: 0.80": the walls' most common value, and each
/// wall that differs from it.
std::string reflectancesText(const RoomSpec& room) {
    std::map<std::string, int> counts;
    for (const glm::dvec3& w : room.wallReflectances) ++counts[reflectanceText(w)];
    std::string common;
    int most = 0;
    for (const auto& [text, n] : counts)
        if (n > most) {
            most = n;
            common = text;
        }
    std::string out = "floor " + reflectanceText(room.floorReflectance) + ", walls " + common +
                      ", ceiling " + reflectanceText(room.ceilingReflectance);
    for (size_t i = 0; i < room.wallReflectances.size(); ++i)
        if (reflectanceText(room.wallReflectances[i]) != common)
            out += "; wall " + std::to_string(i + 1) + ": " +
                   reflectanceText(room.wallReflectances[i]);
    return out;
}

/// The other surfaces' reflectances when the room is not a room entry: "Floor 0.20, Ceiling
/// 0.70, ..." (the mean of each mesh's colour; at most a dozen named).
std::string surfaceReflectances(const Scene& scene) {
    std::string out;
    int named = 0, more = 0;
    for (const GeometryItem& item : scene.geometry) {
        if (item.source.contains("furniture")) continue;
        for (uint32_t m : item.meshes) {
            const Mesh& mesh = scene.meshes[m];
            const glm::vec3 a = scene.materials[mesh.material].albedo;
            if (named == 12) {
                ++more;
                continue;
            }
            out +=
                (out.empty() ? "" : ", ") + mesh.name + " " + fmt("%.2f", (a.x + a.y + a.z) / 3.0);
            ++named;
        }
    }
    if (more > 0) out += " and " + std::to_string(more) + " more";
    return out.empty() ? "no surfaces" : out;
}

/// "3 windows, 1 door".
std::string openingsText(const RoomSpec& room) {
    std::map<std::string, int> counts;
    for (const RoomOpening& o : room.openings) ++counts[o.type];
    std::string out;
    for (const auto& [type, n] : counts)
        out += (out.empty() ? "" : ", ") + std::to_string(n) + " " + type + (n == 1 ? "" : "s");
    return out.empty() ? "none" : out;
}

/// The luminaires' mounting heights above the floor, m: "2.40 m" or "2.40 to 2.80 m".
std::string mountingText(const Scene& scene, const RoomSummary& r) {
    if (r.luminaires.empty()) return "";
    double lo = 1e30, hi = -1e30;
    for (size_t k : r.luminaires) {
        const double h = scene.luminaires[k]->pose.position.y - r.floorY;
        lo = std::min(lo, h);
        hi = std::max(hi, h);
    }
    return std::abs(hi - lo) < 0.005 ? fmt("%.2f m", lo)
                                     : fmt("%.2f", lo) + " to " + fmt("%.2f m", hi);
}

/// The maintenance factors of the room's luminaires: "0.8", or "0.7 to 0.8 (each luminaire's
/// own, see the schedule)".
std::string maintenanceText(const Scene& scene, const RoomSummary& r) {
    double lo = scene.maintenanceFactor, hi = lo;
    if (!r.luminaires.empty()) {
        lo = 1e30, hi = -1e30;
        for (size_t k : r.luminaires) {
            const double f = scene.maintenanceFactorOf(*scene.luminaires[k]);
            lo = std::min(lo, f);
            hi = std::max(hi, f);
        }
    }
    if (hi - lo < 1e-9) return fmt("%.3g", lo) + " (maintained values)";
    return fmt("%.3g", lo) + " to " + fmt("%.3g", hi) + " (each luminaire's own, see the schedule)";
}

/// "Desk (0.75 m above the floor, 1.60 m x 0.80 m)".
std::string taskAreaText(const TaskArea& a, double floorY) {
    std::string out = a.name;
    if (a.plane.axis == 1)
        out += " (" + fmt("%.2f m above the floor, ", a.plane.offset - floorY) +
               fmt("%.2f m x ", a.hi.x - a.lo.x) + fmt("%.2f m)", a.hi.y - a.lo.y);
    else
        out += " (vertical, " + fmt("%.2f m x ", a.hi.x - a.lo.x) + fmt("%.2f m)", a.hi.y - a.lo.y);
    return out;
}

/// The room's data table.
void roomData(Pdf& pdf, const Scene& scene, const RoomSummary& r) {
    const glm::dvec2 size = r.hi - r.lo;
    std::vector<std::vector<std::string>> rows;
    rows.push_back({"Name", r.name});
    rows.push_back({"Dimensions", fmt("%.2f m", size.x) + " x " + fmt("%.2f m", size.y) +
                                      " (x from " + fmt("%.2f", r.lo.x) + " to " +
                                      fmt("%.2f m", r.hi.x) + ", z from " + fmt("%.2f", r.lo.y) +
                                      " to " + fmt("%.2f m", r.hi.y) + ")"});
    if (r.room) {
        rows.push_back({"Floor area", fmt("%.2f m2", r.area) +
                                          (r.room->floor.size() == 4 ? "" : " (its outline)")});
        rows.push_back(
            {"Height", fmt("%.2f m", r.height) +
                           (r.floorY != 0.0 ? fmt(" (floor at %.2f m)", r.floorY) : "")});
        rows.push_back({"Walls", std::to_string(r.room->floor.size())});
        rows.push_back({"Reflectances", reflectancesText(*r.room)});
        rows.push_back({"Openings", openingsText(*r.room)});
    } else {
        rows.push_back({"Floor area", fmt("%.2f m2", r.area) +
                                          " (the overall size: the room is modelled as separate "
                                          "surfaces)"});
        rows.push_back({"Height", fmt("%.2f m", r.height)});
        rows.push_back({"Reflectances", surfaceReflectances(scene)});
    }
    std::string furniture;
    for (size_t i : r.furniture)
        if (std::optional<FurnitureSpec> f = furnitureSpec(scene, i))
            furniture += (furniture.empty() ? "" : ", ") + f->name;
    rows.push_back({"Furniture", furniture.empty() ? "none" : furniture});
    rows.push_back({"Luminaires", r.luminaires.empty()
                                      ? "none"
                                      : std::to_string(r.luminaires.size()) + ", mounting height " +
                                            mountingText(scene, r) + " above the floor"});
    std::string areas;
    for (size_t k : r.taskAreas)
        areas += (areas.empty() ? "" : "; ") + taskAreaText(scene.taskAreas[k], r.floorY);
    rows.push_back({"Task areas", areas.empty() ? "none" : areas});
    rows.push_back({"Maintenance factor", maintenanceText(scene, r)});
    pdf.table({"Room data", ""}, rows, {110, kWidth - 110}, {0, 0}, 8.5);
}

/// A dimension line from a to b (page points) with its text `label` on the side `side` (a unit
/// page vector away from the drawing): short slashes at the ends, as architects draw them.
void dimensionLine(Pdf& pdf, glm::dvec2 a, glm::dvec2 b, glm::dvec2 side,
                   const std::string& label) {
    cairo_t* cr = pdf.cr;
    cairo_set_line_width(cr, 0.5);
    cairo_move_to(cr, a.x, a.y);
    cairo_line_to(cr, b.x, b.y);
    const glm::dvec2 d = glm::normalize(b - a), slash = 2.5 * glm::normalize(d + side);
    for (glm::dvec2 e : {a, b}) {
        cairo_move_to(cr, e.x - slash.x, e.y - slash.y);
        cairo_line_to(cr, e.x + slash.x, e.y + slash.y);
    }
    cairo_stroke(cr);
    pdf.font(7);
    const glm::dvec2 m = 0.5 * (a + b) + 3.0 * side;
    cairo_save(cr);
    cairo_translate(cr, m.x, m.y);
    double angle = std::atan2(d.y, d.x);
    // Upright: along the line, read left to right, or bottom to top on a vertical line.
    if (angle >= M_PI / 2 - 1e-9) angle -= M_PI;
    if (angle < -M_PI / 2 - 1e-9) angle += M_PI;
    cairo_rotate(cr, angle);
    // Above the line when the side is "up" in the text's frame, else below it.
    const glm::dvec2 up(std::sin(angle), -std::cos(angle));
    pdf.text(0, glm::dot(up, side) > 0 ? 0.0 : 7.0, label, 0.5);
    cairo_restore(cr);
}

/// The room seen from above, x to the right and z down the page, at the cursor: the floor's
/// outline with its dimensions and each wall's length, the openings, the furniture, the task
/// areas and the luminaires, each numbered with its mounting height.
void roomPlan(Pdf& pdf, const Scene& scene, const RoomSummary& r) {
    cairo_t* cr = pdf.cr;
    const glm::dvec2 extent = glm::max(r.hi - r.lo, glm::dvec2(1e-3));
    const double marginL = 50, marginR = 30, marginT = 44, marginB = 26, maxH = 360;
    const double availW = kWidth - marginL - marginR;
    const double s = std::min(availW / extent.x, maxH / extent.y);  // points per metre
    const double w = extent.x * s, h = extent.y * s;
    pdf.need(h + marginT + marginB + 40);
    pdf.heading("Plan", 11);
    const double x0 = kLeft + marginL + (availW - w) / 2, y0 = pdf.y + marginT;
    auto at = [&](glm::dvec2 q) {
        return glm::dvec2(x0 + (q.x - r.lo.x) * s, y0 + (q.y - r.lo.y) * s);
    };
    auto path = [&](const std::vector<glm::dvec2>& polygon) {
        cairo_new_path(cr);
        for (const glm::dvec2& q : polygon) {
            glm::dvec2 p = at(q);
            cairo_line_to(cr, p.x, p.y);
        }
        cairo_close_path(cr);
    };
    std::vector<glm::dvec2> outline =
        r.room ? r.room->floor
               : std::vector<glm::dvec2>{r.lo, {r.hi.x, r.lo.y}, r.hi, {r.lo.x, r.hi.y}};
    path(outline);
    cairo_set_source_rgb(cr, 0.95, 0.95, 0.95);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_set_line_width(cr, r.room ? 1.8 : 0.8);
    if (!r.room) {
        const double dash[] = {4.0, 2.0};
        cairo_set_dash(cr, dash, 2, 0);
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);

    // Openings on the walls: a window as a thin double line, a door as its leaf and swing, a
    // skylight as a dashed rectangle.
    if (r.room) {
        const RoomSpec& room = *r.room;
        const double turn = signedArea(room.floor) > 0.0 ? 1.0 : -1.0;
        for (const RoomOpening& o : room.openings) {
            if (o.type == "skylight") {
                const glm::dvec2 lo = at(o.center - 0.5 * o.size), hi = at(o.center + 0.5 * o.size);
                const double dash[] = {2.0, 1.5};
                cairo_set_dash(cr, dash, 2, 0);
                cairo_set_source_rgb(cr, 0.2, 0.4, 0.8);
                cairo_set_line_width(cr, 0.7);
                cairo_rectangle(cr, lo.x, lo.y, hi.x - lo.x, hi.y - lo.y);
                cairo_stroke(cr);
                cairo_set_dash(cr, nullptr, 0, 0);
                continue;
            }
            const glm::dvec2 a = room.floor[o.wall],
                             b = room.floor[(o.wall + 1) % room.floor.size()];
            const glm::dvec2 d = glm::normalize(b - a), inward(-turn * d.y, turn * d.x);
            const glm::dvec2 p0 = at(a + d * o.offset), p1 = at(a + d * (o.offset + o.width));
            cairo_set_source_rgb(cr, 1, 1, 1);
            cairo_set_line_width(cr, 2.6);
            cairo_move_to(cr, p0.x, p0.y);
            cairo_line_to(cr, p1.x, p1.y);
            cairo_stroke(cr);
            cairo_set_line_width(cr, 0.6);
            if (o.type == "window") {
                cairo_set_source_rgb(cr, 0.2, 0.4, 0.8);
                for (double k : {-1.0, 1.0}) {
                    const glm::dvec2 n = 0.9 * k * inward;
                    cairo_move_to(cr, p0.x + n.x, p0.y + n.y);
                    cairo_line_to(cr, p1.x + n.x, p1.y + n.y);
                }
                cairo_stroke(cr);
            } else {  // a door: its leaf open into the room and the arc it swings through
                cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
                const double radius = o.width * s;
                const glm::dvec2 leaf = p0 + radius * inward;
                cairo_move_to(cr, p0.x, p0.y);
                cairo_line_to(cr, leaf.x, leaf.y);
                cairo_stroke(cr);
                const double from = std::atan2(d.y, d.x), to = std::atan2(inward.y, inward.x);
                const double dash[] = {1.5, 1.5};
                cairo_set_dash(cr, dash, 2, 0);
                cairo_new_sub_path(cr);
                // The short way from the wall to the leaf.
                if (std::remainder(to - from, 2 * M_PI) > 0)
                    cairo_arc(cr, p0.x, p0.y, radius, from, to);
                else
                    cairo_arc_negative(cr, p0.x, p0.y, radius, from, to);
                cairo_stroke(cr);
                cairo_set_dash(cr, nullptr, 0, 0);
            }
        }
        // Each wall's number and length outside it, where the wall is long enough on the page.
        pdf.font(6);
        cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
        for (size_t i = 0; i < room.floor.size(); ++i) {
            const glm::dvec2 a = room.floor[i], b = room.floor[(i + 1) % room.floor.size()];
            const std::string label =
                "wall " + std::to_string(i + 1) + ": " + fmt("%.2f m", room.wallLength(i));
            if (glm::length(b - a) * s < pdf.textWidth(label) + 6) continue;
            const glm::dvec2 d = glm::normalize(b - a), outward(turn * d.y, -turn * d.x);
            const glm::dvec2 m = at(0.5 * (a + b)) + 4.0 * outward;
            cairo_save(cr);
            cairo_translate(cr, m.x, m.y);
            double angle = std::atan2(d.y, d.x);
            if (angle >= M_PI / 2 - 1e-9) angle -= M_PI;
            if (angle < -M_PI / 2 - 1e-9) angle += M_PI;
            cairo_rotate(cr, angle);
            const glm::dvec2 up(std::sin(angle), -std::cos(angle));
            pdf.text(0, glm::dot(up, outward) > 0 ? -1.0 : 6.0, label, 0.5);
            cairo_restore(cr);
        }
    }

    // Furniture: its footprint, named where the name fits (the names drawn last, over the
    // luminaires above them).
    struct Label {
        std::string name;
        glm::dvec2 lo, hi;
    };
    std::vector<Label> labels;
    for (size_t i : r.furniture) {
        std::optional<FurnitureSpec> f = furnitureSpec(scene, i);
        if (!f) continue;
        const std::vector<glm::dvec2> footprint = f->footprint();
        path(footprint);
        cairo_set_source_rgb(cr, 0.87, 0.80, 0.70);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0.45, 0.35, 0.25);
        cairo_set_line_width(cr, 0.5);
        cairo_stroke(cr);
        glm::dvec2 lo = at(footprint[0]), hi = lo;
        for (const glm::dvec2& q : footprint) {
            lo = glm::min(lo, at(q));
            hi = glm::max(hi, at(q));
        }
        labels.push_back({f->name, lo, hi});
    }

    // Task areas: dashed green outlines, named inside their top-left corner.
    for (size_t k : r.taskAreas) {
        const TaskArea& a = scene.taskAreas[k];
        const glm::dvec3 c0 = a.plane.point(a.lo.x, a.lo.y), c1 = a.plane.point(a.hi.x, a.hi.y);
        const glm::dvec2 lo = at({std::min(c0.x, c1.x), std::min(c0.z, c1.z)});
        const glm::dvec2 hi = at({std::max(c0.x, c1.x), std::max(c0.z, c1.z)});
        const double dash[] = {3.0, 2.0};
        cairo_set_dash(cr, dash, 2, 0);
        cairo_set_source_rgb(cr, 0.1, 0.55, 0.2);
        cairo_set_line_width(cr, 0.9);
        // Drawn 2 points inside the outline it may share with the walls, so both show.
        const double inset = std::min(2.0, 0.25 * std::min(hi.x - lo.x, hi.y - lo.y));
        cairo_rectangle(cr, lo.x + inset, lo.y + inset, std::max(hi.x - lo.x - 2 * inset, 0.0),
                        std::max(hi.y - lo.y - 2 * inset, 0.0));
        cairo_stroke(cr);
        cairo_set_dash(cr, nullptr, 0, 0);
        pdf.font(6.5, true);
        pdf.text(lo.x + inset + 3, lo.y + inset + 8, a.name + " (task area)");
    }

    // Luminaires: the opening's outline (a circle with a cross for a point source), its number
    // and its mounting height above the floor.
    for (size_t n = 0; n < r.luminaires.size(); ++n) {
        const Luminaire& l = *scene.luminaires[r.luminaires[n]];
        const glm::dvec2 c = at({l.pose.position.x, l.pose.position.z});
        std::vector<glm::dvec2> shape;
        glm::dvec2 lo = c, hi = c;
        for (const glm::dvec3& q : l.outline()) {
            shape.push_back({q.x, q.z});
            lo = glm::min(lo, at(shape.back()));
            hi = glm::max(hi, at(shape.back()));
        }
        cairo_set_line_width(cr, 0.6);
        if (shape.size() >= 3 && std::max(hi.x - lo.x, hi.y - lo.y) >= 4.0) {
            path(shape);
            cairo_set_source_rgb(cr, 1.0, 0.85, 0.3);
            cairo_fill_preserve(cr);
            cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
            cairo_stroke(cr);
        } else {
            const double radius = 3.5;
            cairo_new_sub_path(cr);
            cairo_arc(cr, c.x, c.y, radius, 0, 2 * M_PI);
            cairo_set_source_rgb(cr, 1.0, 0.85, 0.3);
            cairo_fill_preserve(cr);
            cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
            cairo_stroke(cr);
            const double k = radius * M_SQRT1_2;
            cairo_move_to(cr, c.x - k, c.y - k);
            cairo_line_to(cr, c.x + k, c.y + k);
            cairo_move_to(cr, c.x - k, c.y + k);
            cairo_line_to(cr, c.x + k, c.y - k);
            cairo_stroke(cr);
            lo = c - radius;
            hi = c + radius;
        }
        cairo_set_source_rgb(cr, 0, 0, 0);
        pdf.font(6.5, true);
        pdf.text(hi.x + 2, lo.y - 1, std::to_string(n + 1));
        pdf.font(5.5);
        pdf.text(hi.x + 2, hi.y + 6, fmt("%.2f m", l.pose.position.y - r.floorY));
    }

    pdf.font(5.5);
    cairo_set_source_rgb(cr, 0.3, 0.22, 0.15);
    for (const Label& l : labels)
        if (pdf.textWidth(l.name) + 2 < l.hi.x - l.lo.x && l.hi.y - l.lo.y > 6)
            pdf.text(0.5 * (l.lo.x + l.hi.x), 0.5 * (l.lo.y + l.hi.y) + 2, l.name, 0.5);

    // Overall dimensions: the width above, the depth on the left.
    cairo_set_source_rgb(cr, 0, 0, 0);
    const double above = y0 - 26, left = x0 - 30;
    dimensionLine(pdf, {x0, above}, {x0 + w, above}, {0, -1}, fmt("%.2f m", extent.x));
    dimensionLine(pdf, {left, y0}, {left, y0 + h}, {-1, 0}, fmt("%.2f m", extent.y));
    cairo_set_line_width(cr, 0.3);
    cairo_set_source_rgb(cr, 0.5, 0.5, 0.5);
    for (double x : {x0, x0 + w}) {
        cairo_move_to(cr, x, above - 3);
        cairo_line_to(cr, x, y0 - 2);
    }
    for (double y : {y0, y0 + h}) {
        cairo_move_to(cr, left - 3, y);
        cairo_line_to(cr, x0 - 2, y);
    }
    cairo_stroke(cr);

    // The axes and a scale bar of 1 m below the plan.
    cairo_set_source_rgb(cr, 0, 0, 0);
    const double by = y0 + h + 16;
    cairo_set_line_width(cr, 0.6);
    cairo_move_to(cr, x0, by);
    cairo_line_to(cr, x0 + 18, by);
    cairo_move_to(cr, x0, by);
    cairo_line_to(cr, x0, by + 14);
    cairo_stroke(cr);
    pdf.font(6.5);
    pdf.text(x0 + 20, by + 2.5, "x");
    pdf.text(x0 - 1.5, by + 21, "z");
    cairo_set_line_width(cr, 2);
    cairo_move_to(cr, x0 + 40, by);
    cairo_line_to(cr, x0 + 40 + s, by);
    cairo_stroke(cr);
    pdf.text(x0 + 40 + s + 4, by + 2.5, "1 m");
    pdf.y = by + 26;
}

/// The room's luminaires by number: where each is and its mounting height.
void luminaireTable(Pdf& pdf, const Scene& scene, const RoomSummary& r,
                    const std::vector<ScheduleRow>& schedule) {
    if (r.luminaires.empty()) return;
    std::map<size_t, std::string> product;
    for (const ScheduleRow& row : schedule)
        for (size_t k : row.members) product[k] = row.product;
    std::vector<std::vector<std::string>> rows;
    for (size_t n = 0; n < r.luminaires.size(); ++n) {
        const Luminaire& l = *scene.luminaires[r.luminaires[n]];
        rows.push_back({std::to_string(n + 1), l.name, product[r.luminaires[n]],
                        fmt("%.2f", l.pose.position.x) + ", " + fmt("%.2f", l.pose.position.z),
                        fmt("%.2f", l.pose.position.y - r.floorY)});
    }
    pdf.table({"No.", "Luminaire", "Product", "Position x, z [m]", "Mounting height [m]"}, rows,
              {30, 110, 185, 90, 80}, {1, 0, 0, 1, 1}, 7.5);
}

}  // namespace

void roomSections(Pdf& pdf, const ReportInput& in) {
    const Scene& scene = *in.scene;
    const std::vector<ScheduleRow> schedule = luminaireSchedule(scene);
    for (const RoomSummary& r : roomSummaries(scene, in.surfaces)) {
        pdf.section(r.room ? "Room: " + r.name : "The room (the design's overall size)");
        roomData(pdf, scene, r);
        roomPlan(pdf, scene, r);
        pdf.paragraph(
            "Plan seen from above, x to the right and z down the page; dimensions in m. " +
                std::string(r.room ? "Walls are numbered from the first corner of the outline; "
                                     "windows are drawn as double lines, doors with their swing. "
                                   : "The dashed outline is the design's overall size. ") +
                "Furniture is drawn brown, task areas dashed green, and each luminaire numbered "
                "with its mounting height above the floor.",
            7.5);
        luminaireTable(pdf, scene, r, schedule);
    }
}

void powerDensitySection(Pdf& pdf, const ReportInput& in) {
    const Scene& scene = *in.scene;
    pdf.section("Power density");
    const bool lux = in.surfaces.units.photometric;
    pdf.paragraph(
        "The luminaires' input power per floor area, in W/m2, and that per 100 lx of the "
        "maintained illuminance Em on the room's task area, in W/m2 per 100 lx: the second says "
        "how much power the design spends on each 100 lx it delivers, so designs of different "
        "illuminance can be compared. Input power as the luminaires' data states it.",
        8);
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> sums;  // each room's arithmetic, in words
    for (const RoomSummary& r : roomSummaries(scene, in.surfaces)) {
        const int n = int(r.luminaires.size());
        std::string power =
            r.powerUnstated == 0
                ? fmt("%.4g W", r.power)
                : "not stated for " + std::to_string(r.powerUnstated) + " of " + std::to_string(n);
        const double density = r.powerDensity(), per100 = r.powerDensityPer100Lux();
        std::string reference = r.reference.empty() ? "no task area computed"
                                                    : r.reference + ": " + fmt("%.4g lx", r.em);
        rows.push_back({r.name, fmt("%.2f m2", r.area), std::to_string(n), power,
                        density >= 0.0 ? fmt("%.3g W/m2", density) : "not known",
                        lux ? reference : "not applicable (radiometric units)",
                        per100 >= 0.0 && lux ? fmt("%.3g W/m2 per 100 lx", per100) : "not known"});
        if (density >= 0.0) {
            std::string sum = r.name + ": " + fmt("%.4g W", r.power) + " / " +
                              fmt("%.2f m2", r.area) + " = " + fmt("%.3g W/m2", density);
            if (per100 >= 0.0 && lux)
                sum += "; " + fmt("%.3g W/m2", density) + " / (" + fmt("%.4g lx", r.em) +
                       " / 100 lx) = " + fmt("%.3g W/m2 per 100 lx", per100);
            sums.push_back(sum + ".");
        } else if (r.powerUnstated > 0) {
            sums.push_back(r.name + ": " + std::to_string(r.powerUnstated) + " of its " +
                           std::to_string(n) +
                           " luminaires state no input power, so its power density is not "
                           "known.");
        }
    }
    pdf.table(
        {"Room", "Floor area", "Count", "Input power", "Power density", "Em of", "Per 100 lx"},
        rows, {66, 52, 52, 60, 62, 98, 105}, {0, 1, 1, 1, 1, 0, 1}, 8);
    for (const std::string& sum : sums) pdf.paragraph(sum, 8);
}

}  // namespace report_detail

}  // namespace candela
