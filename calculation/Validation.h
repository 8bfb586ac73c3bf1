#pragma once
// The validation suite (issue 17, part 4): analytic cases of the kind lighting-design software is
// validated with (CIE 171:2006, Section 5), each computed by Candela's own CPU path and compared
// with a closed form that shares none of its code:
//
// - an integrating cube (a closed 2 m room of uniform reflectance rho): the area-weighted mean
//   illuminance over all its inner surfaces is Phi / (S (1 - rho)), exactly, for any luminaire
//   (energy balance), here a photometric point source, a photometric area source and a measured
//   light field, rho = 0, 0.2, 0.5, 0.8;
// - a closed, finely tessellated sphere of uniform rho with a point source off its centre: the
//   interreflected part is rho Phi / (A (1 - rho)) at every point, however uneven the direct light;
// - direct light: an isotropic point source over a plane (I cos^3 / h^2), a Lambertian rectangle
//   over a parallel and a perpendicular plane (Howell's configuration factors);
// - an obstruction: a table between a luminaire and the work plane;
// - CIE 171:2006's own analytical cases (cie171-5.2 point source, 5.3 area source, 5.4 flux
//   conservation, 5.6 diffuse reflection, 5.7 internal obstruction, 5.8 interreflection in the
//   4 m cube up to rho 0.95), each computed as a design calculation is (computeReceivers with
//   everything the scene calls for).
//
// `candela validate` prints them as a table; tests/validation_test.cpp runs each as a ctest.

#include <string>
#include <vector>

namespace candela {

struct Scene;

struct ValidationResult {
    std::string name;         ///< Case id, e.g. "cube-point-rho0.5".
    std::string description;  ///< One line: what is compared.
    std::string unit;         ///< Of expected and measured ("lx").
    double expected = 0.0;
    double measured = 0.0;   ///< For cases over many points: the one that deviates most.
    double deviation = 0.0;  ///< (measured - expected) / expected.
    double tolerance = 0.0;  ///< Largest |deviation| that passes.
    bool pass = false;
    double seconds = 0.0;  ///< Wall time of the case.
    std::string detail;    ///< What else was measured (patches, iterations, points).
};

/// Every case, in the order `candela validate` prints them.
std::vector<std::string> validationCases();
/// Runs one case; throws InputError for an unknown name (naming the known ones).
ValidationResult runValidationCase(const std::string& name);

/// The energy balance of a closed room the user built (`candela validate --closed SCENE`): all the
/// light its luminaires emit lands on its surfaces and is absorbed there, so the light each
/// surface absorbs, sum A (1 - rho) (E_direct + E_interreflected), adds up to the luminaires'
/// flux, whatever the reflectances (the integrating cube's law for any closed room). Throws
/// InputError naming the file when the scene has no surfaces, no luminaires, an environment
/// (light from outside), or is not closed: rays from a luminaire escape, or reach the back of a
/// surface (one that does not face into the room).
ValidationResult validateClosedRoom(const Scene& scene, int patches = 2500);

/// Howell's configuration factor from a planar element to a parallel rectangle [x0, x1] x
/// [y0, y1] at height h (corner superposition of catalogue C-11; signed corners).
double parallelRectangleFactor(double x0, double x1, double y0, double y1, double h);
/// Howell's configuration factor from a planar element to a rectangle in a plane perpendicular to
/// it: the element at the origin with normal +x, the rectangle in the plane x = 0... see the .cpp.
double perpendicularRectangleFactor(double y0, double y1, double z0, double z1, double c);

}  // namespace candela
