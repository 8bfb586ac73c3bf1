#pragma once
// Checked reads of scene-file fields: every failure names the file, the field and what was
// expected, and no NaN, infinity or wrong type gets past.

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>

namespace candela::json {

/// Where a value came from, for error messages: "scene.json: luminaires[0].size".
struct Where {
    std::string file;
    std::string field;
    Where operator/(const std::string& child) const;
    Where operator[](size_t index) const;
    std::string str() const;
};

[[noreturn]] void fail(const Where& where, const std::string& expected);

double number(const nlohmann::json& v, const Where& where);
double positive(const nlohmann::json& v, const Where& where);
glm::dvec3 vec3(const nlohmann::json& v, const Where& where);
glm::dvec2 vec2(const nlohmann::json& v, const Where& where);
/// A non-zero vector (directions such as aim): rejects zero length.
glm::dvec3 direction(const nlohmann::json& v, const Where& where);
std::string string(const nlohmann::json& v, const Where& where);
bool boolean(const nlohmann::json& v, const Where& where);
/// Requires an object and rejects keys not in `allowed` (catches typos such as "positon").
void checkKeys(const nlohmann::json& object, std::initializer_list<const char*> allowed,
               const Where& where);

/// A number in [lo, hi] (both finite): a field whose physical sense has bounds, so that a value
/// such as 1e308 is refused at load instead of becoming an infinity or a silent 0 later.
/// `what` says what it is ("an angle in degrees"); the message adds the bounds.
double inRange(const nlohmann::json& v, const Where& where, double lo, double hi,
               const std::string& what);
/// inRange as a reader for optional().
inline auto range(double lo, double hi, std::string what) {
    return [=](const nlohmann::json& v, const Where& where) {
        return inRange(v, where, lo, hi, what);
    };
}

/// The largest turn an angle field may ask for, degrees (ten turns): beyond it a float's
/// rounding makes the angle meaningless (1e308 degrees turned everything to 0).
inline constexpr double kMaxAngleDeg = 3600.0;

/// The largest coordinate or length a scene may give, metres (1000 km): no building is larger,
/// the renderer's floats keep millimetres only to about 10 km, and 1e308 made areas infinite.
inline constexpr double kMaxMetres = 1e6;
/// kMaxMetres as the messages write it ("1e+06").
std::string maxMetresText();
/// A point [x, y, z] in metres, each coordinate within +-kMaxMetres.
glm::dvec3 point(const nlohmann::json& v, const Where& where);
/// A length in metres in (0, kMaxMetres].
double length(const nlohmann::json& v, const Where& where);

/// Optional field: returns fallback when absent; validates like the functions above if present.
template <class Fn, class T>
T optional(const nlohmann::json& object, const char* key, const Where& where, T fallback, Fn read) {
    auto it = object.find(key);
    if (it == object.end()) return fallback;
    return read(*it, where / key);
}

}  // namespace candela::json
