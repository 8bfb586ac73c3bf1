#pragma once
// The hard-case grid (issue 18, part 1): geometries at the extremes (receivers at contact, in the
// emitter's plane, at grazing normals, 1e5 m away; openings from 1e-6 m to 100 m, segments,
// points; intensity tables with a narrow spike, all zeros, one non-zero value; a large up-and-down
// opening with batwing tables; light fields with one bright pixel), each with an expected value the
// test owns: a closed form or a quadrature written here, in double precision, that shares no code
// with the estimators.
//
// Every technique the registry lists for a case's kind runs on it (a technique added later runs
// without editing this table); TechniqueLimits (hardcases_test.cpp) says what each technique
// promises there: agreement within a tolerance, or a documented bound.

#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "luminaires/Luminaire.h"

namespace candela::hard {

/// Every emitter's plane (photometric opening, rectangle, S) is y = kH, metres, facing down; the
/// photometric openings and the rectangles are centred on (0, kH, 0).
constexpr double kH = 2.0;

/// What kind of trouble a case is (a technique's limits are stated per class).
enum class Class {
    Ordinary,     ///< Nothing extreme: a reference point for every technique.
    Contact,      ///< 1e-9 to 1e-3 m in front of an opening or S.
    OnPlane,      ///< Exactly in the emitter's plane (or on S).
    Grazing,      ///< The receiver's normal (nearly) in the emitter's plane.
    Behind,       ///< Behind the emitter (or between U and S): exactly no light.
    Far,          ///< 1e5 m away.
    Tiny,         ///< An opening of 1e-6 m.
    Huge,         ///< An opening of 100 m.
    Segment,      ///< A zero-width opening.
    Point,        ///< A point opening.
    Spike,        ///< A 1e9 cd spike 0.5 degrees wide.
    Zero,         ///< A table of zeros.
    SingleValue,  ///< A table with one non-zero entry.
    BrightPixel,  ///< A light field with one bright pixel.
    Table,        ///< A smooth measured-like table, up and down, near a large opening.
};
const char* className(Class c);

struct Case {
    std::string name;
    LuminaireKind kind = LuminaireKind::Photometric;  ///< Luminaire kind.
    Class cls = Class::Ordinary;
    std::shared_ptr<const Luminaire> light;  ///< A placed luminaire of that kind.
    glm::dvec3 p{0.0}, n{0.0, 1.0, 0.0};     ///< Receiver, world, unit normal.
    double expected = 0.0;                   ///< Irradiance (luminance-weighted), the light's unit.
    std::string how;                         ///< How the expected value was found.
    /// The receiver is within float rounding of the emitter (the GPU sees it on the plane).
    bool belowFloat = false;
    /// Photometric cases: the table's intensity (cd) at the angle gamma from the aim (every
    /// table here is rotationally symmetric), for the point law at the opening's centre.
    std::function<double(double gamma)> intensity;
    /// Photometric cases: pi F L_max, what the opening would give at its brightest radiance
    /// everywhere: no estimate may exceed it.
    double upperBound = 0.0;
};

/// The point law at the photometric case's opening centre (2 m up, aiming down): what the
/// `point` technique computes, I(gamma) cos / r^2.
double pointLaw(const Case& c);

/// The area form of a photometric opening [-a, a] x [-b, b] in the plane y = 2 (aiming down)
/// with a rotationally symmetric table `intensity(gamma)`: (1/A) int I(gamma) cos_p / r^2 dA, by
/// Gauss-Legendre on a grid graded around the receiver's foot point (and the extra breakpoints).
double areaForm(const glm::dvec3& p, const glm::dvec3& n, double a, double b,
                const std::function<double(double)>& intensity, std::vector<double> extraX = {},
                std::vector<double> extraZ = {});

/// Every case of the grid (built once; light fields are made in memory).
const std::vector<Case>& cases();

/// Lambert's polygon form factor from p (unit normal n) to the convex polygon `corners` (world),
/// with the polygon clipped at p's horizon: the test's own closed form.
double polygonFormFactor(const glm::dvec3& p, const glm::dvec3& n,
                         const std::vector<glm::dvec3>& corners);

}  // namespace candela::hard
