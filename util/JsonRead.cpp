#include "util/JsonRead.h"

#include <cmath>
#include <cstdio>

#include "util/Error.h"

namespace candela::json {

Where Where::operator/(const std::string& child) const {
    return {file, field.empty() ? child : field + "." + child};
}

Where Where::operator[](size_t index) const {
    return {file, field + "[" + std::to_string(index) + "]"};
}

std::string Where::str() const {
    return field.empty() ? file : file + ": " + field;
}

void fail(const Where& where, const std::string& expected) {
    throw InputError(where.str() + ": expected " + expected);
}

double number(const nlohmann::json& v, const Where& where) {
    if (v.is_string()) {
        const std::string& s = v.get_ref<const std::string&>();
        fail(where, "a finite number, got the string \"" + s + "\"");
    }
    if (!v.is_number()) fail(where, "a number, got " + std::string(v.type_name()));
    double x = v.get<double>();
    if (!std::isfinite(x)) fail(where, "a finite number, got " + std::to_string(x));
    return x;
}

bool boolean(const nlohmann::json& v, const Where& where) {
    if (!v.is_boolean()) fail(where, "true or false, got " + v.dump());
    return v.get<bool>();
}

double positive(const nlohmann::json& v, const Where& where) {
    double x = number(v, where);
    if (!(x > 0.0)) fail(where, "a positive number, got " + v.dump());
    return x;
}

double inRange(const nlohmann::json& v, const Where& where, double lo, double hi,
               const std::string& what) {
    double x = number(v, where);
    if (!(x >= lo && x <= hi)) {
        char bounds[96];
        std::snprintf(bounds, sizeof bounds, " from %g to %g, got ", lo, hi);
        fail(where, what + bounds + v.dump());
    }
    return x;
}

std::string maxMetresText() {
    char text[32];
    std::snprintf(text, sizeof text, "%g", kMaxMetres);
    return text;
}

glm::dvec3 point(const nlohmann::json& v, const Where& where) {
    glm::dvec3 p = vec3(v, where);
    for (int i = 0; i < 3; ++i)
        if (!(std::abs(p[i]) <= kMaxMetres))
            fail(where[size_t(i)], "a coordinate in metres from -" + maxMetresText() + " to " +
                                       maxMetresText() + ", got " + v.dump());
    return p;
}

double length(const nlohmann::json& v, const Where& where) {
    double x = number(v, where);
    if (!(x > 0.0 && x <= kMaxMetres))
        fail(where,
             "a positive length in metres of at most " + maxMetresText() + ", got " + v.dump());
    return x;
}

template <int N>
static glm::vec<N, double> readVec(const nlohmann::json& v, const Where& where) {
    if (!v.is_array() || v.size() != N)
        fail(where, "an array of " + std::to_string(N) + " numbers, got " + v.dump());
    glm::vec<N, double> out;
    for (int i = 0; i < N; ++i) out[i] = number(v[i], where[i]);
    return out;
}

glm::dvec3 vec3(const nlohmann::json& v, const Where& where) {
    return readVec<3>(v, where);
}
glm::dvec2 vec2(const nlohmann::json& v, const Where& where) {
    return readVec<2>(v, where);
}

glm::dvec3 direction(const nlohmann::json& v, const Where& where) {
    glm::dvec3 d = vec3(v, where);
    if (glm::length(d) < 1e-12) fail(where, "a non-zero direction, got " + v.dump());
    return d;
}

std::string string(const nlohmann::json& v, const Where& where) {
    if (!v.is_string()) fail(where, "a string, got " + std::string(v.type_name()));
    return v.get<std::string>();
}

void checkKeys(const nlohmann::json& object, std::initializer_list<const char*> allowed,
               const Where& where) {
    if (!object.is_object()) fail(where, "an object, got " + std::string(object.type_name()));
    for (auto it = object.begin(); it != object.end(); ++it) {
        bool known = false;
        for (const char* key : allowed) known = known || it.key() == key;
        if (!known) {
            std::string list;
            for (const char* key : allowed) list += std::string(list.empty() ? "" : ", ") + key;
            throw InputError(where.str() + ": unknown field \"" + it.key() +
                             "\" (expected one of " + list + ")");
        }
    }
}

}  // namespace candela::json
