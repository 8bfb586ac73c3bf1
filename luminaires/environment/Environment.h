#pragma once
// Distant lighting from an environment map: the model (a latitude-longitude radiance map that is
// exactly piecewise constant per texel), its three sources (an HDR file, a procedural sun and
// sky, a sequence of frames) and the scene-file field that chooses one.
//
// Convention (the scene-file contract): the texel-centre coordinates (u, v) in [0, 1)^2 of a
// W x H lat-long image, v = 0 the top row, map to theta = pi v and phi = 2 pi u + rotation, the
// direction (sin(theta) cos(phi), cos(theta), sin(theta) sin(phi)) in the Y-up world: the top
// row is the zenith (+Y), u = 0 looks along +X, u = 1/4 along +Z. Texel (i, j) covers
// u in [i/W, (i+1)/W), v in [j/H, (j+1)/H), and the map's radiance is that texel's value on all of
// it (no filtering), so every sampler and the exact reference integrate the same function.
//
// Lat-long files must be exactly 2:1 (width = 2 height): anything else is far more likely a cube
// strip, a mirror ball or a cropped panorama than a lat-long map, and reading it as one would
// silently light the scene from the wrong directions. Maps built in code (the sky, tests) may
// have any size.

#include <glm/glm.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "luminaires/Units.h"
#include "util/JsonRead.h"

namespace candela {

/// Luminance of linear Rec. 709 RGB (the weights used everywhere in Candela).
inline double luminanceOf(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

class EnvironmentMap {
  public:
    /// Validates the texels (finite, non-negative) and the size; errors name `source`.
    /// `rgb` holds width * height texels, row 0 at the top (v = 0).
    EnvironmentMap(int width, int height, std::vector<glm::vec3> rgb, double intensity,
                   double rotationDeg, std::string source);

    /// Largest accepted image side, texels (a 16k lat-long map is 2 GB of float RGB already).
    static constexpr int kMaxSide = 16384;

    /// A lat-long .hdr or .exr (anything else is refused) read through OpenImageIO as RGB float
    /// (1 channel is grey, a 4th channel is ignored), at most `maxSide` texels wide. Throws
    /// InputError naming the file.
    static std::shared_ptr<EnvironmentMap> load(const std::string& path, double intensity = 1.0,
                                                double rotationDeg = 0.0, int maxSide = kMaxSide);

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    /// Multiplies every texel (dimensionless).
    double intensity() const { return mIntensity; }
    /// Turn about +Y added to phi, radians.
    double rotation() const { return mRotation; }
    /// File name or a description of where the map came from (for messages).
    const std::string& source() const { return mSource; }

    /// Radiance of texel (x, y) including the intensity, W/(m2 sr) (cd/m2 for the sky), RGB.
    glm::dvec3 texel(int x, int y) const {
        return mIntensity * glm::dvec3(mRgb[size_t(y) * size_t(mWidth) + size_t(x)]);
    }
    double texelLuminance(int x, int y) const { return luminanceOf(texel(x, y)); }
    /// Solid angle of any texel of row y (sr): (2 pi / W) (cos theta0 - cos theta1).
    double rowSolidAngle(int y) const;

    /// Radiance arriving from direction w (any length > 0), exactly the texel's value.
    glm::dvec3 radiance(const glm::dvec3& w) const;
    /// (u, v) in [0, 1]^2 of a direction (inverse of direction()).
    glm::dvec2 uvOf(const glm::dvec3& w) const;
    /// Texel containing a direction, clamped to the image.
    glm::ivec2 texelOf(const glm::dvec3& w) const;
    /// Unit direction of the map coordinates (u, v) under the convention above.
    glm::dvec3 direction(double u, double v) const;

    /// Integral of the luminance over the sphere (sum of luminance x solid angle), W/m2 sr * sr.
    double totalLuminancePower() const;

    /// The same texels with another intensity and rotation (the editor's edits of a loaded file).
    std::shared_ptr<EnvironmentMap> adjusted(double intensity, double rotationDeg) const;

  private:
    int mWidth = 0, mHeight = 0;
    std::vector<glm::vec3> mRgb;
    double mIntensity = 1.0;
    double mRotation = 0.0;
    std::string mSource;
};

/// Parameters of the procedural sun and sky (see makeSkyMap).
struct SkyParams {
    double sunElevationDeg = 30.0;  ///< Sun above the horizon, degrees in [0, 90].
    double sunAzimuthDeg = 120.0;   ///< phi of the sun (from +X towards +Z), degrees.
    double turbidity = 3.0;         ///< Atmospheric turbidity T in [1.7, 10] (Preetham's range).
    double groundAlbedo = 0.2;      ///< Reflectance of the uniform ground below the horizon.
    int width = 512;                ///< Lat-long width in texels; the height is width / 2.
};

/// Angular radius of the sun disc, degrees.
constexpr double kSunAngularRadiusDeg = 0.265;

/// Renders a clear sky into a lat-long map, in cd/m2 (irradiance from it is illuminance, lux):
/// - sky luminance: the Perez et al. (1993) all-weather distribution F(theta, gamma) =
///   (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma) with the turbidity-dependent
///   coefficients and zenith luminance of Preetham, Shirley, Smits (1999), "A Practical Analytic
///   Model for Daylight", Eq. (3)-(4) and Appendix A.2; Y = Y_z F(theta, gamma) / F(0, theta_s);
///   colour from the same appendix's x, y chromaticity distributions (CIE xyY to linear sRGB);
/// - the sun: a disc of angular radius kSunAngularRadiusDeg, white, with a direct normal
///   illuminance E_dn = 128 klx exp(-0.8662 T m delta_R(m)) (Linke-turbidity beam model of
///   Rigollier, Bauer, Wald 2000, Eq. (2); Kasten-Young 1989 air mass m; Kasten 1996 Rayleigh
///   optical thickness delta_R), spread over the texels the disc covers in proportion to the
///   overlap (so its illuminance is kept at any resolution);
/// - below the horizon a uniform Lambertian ground: albedo x horizontal illuminance / pi.
/// Throws InputError for parameters outside their ranges.
std::shared_ptr<EnvironmentMap> makeSkyMap(const SkyParams& sky, double intensity = 1.0,
                                           double rotationDeg = 0.0);

/// Where the sun is at a place and time, for the editor's time-of-day control: declination
/// (Cooper 1969) and the hour angle of apparent solar time, no refraction or equation of time.
/// The compass maps to the scene as north = -Z, east = +X, so the returned azimuth is the
/// scene's sun_azimuth_deg (phi from +X towards +Z): compass azimuth - 90 degrees. Elevation is
/// negative at night.
struct SunPosition {
    double elevationDeg = 0.0;
    double azimuthDeg = 0.0;
};
SunPosition sunPosition(double latitudeDeg, int dayOfYear, double solarHours);

/// Frames of a dynamic environment: files matching a glob pattern (sorted by name), shown at
/// `fps` frames per second and looping. Frames load on demand; the last one is cached.
class EnvironmentSequence {
  public:
    /// Throws InputError when nothing matches, fps is not positive, or the first frame is bad.
    EnvironmentSequence(std::string pattern, std::vector<std::string> files, double fps,
                        double intensity, double rotationDeg);
    static std::shared_ptr<EnvironmentSequence> open(const std::string& pattern, double fps,
                                                     double intensity, double rotationDeg);

    size_t frameCount() const { return mFiles.size(); }
    double fps() const { return mFps; }
    const std::vector<std::string>& files() const { return mFiles; }
    /// Index of the frame shown at time t (seconds): floor(t fps) modulo the count.
    size_t frameIndex(double seconds) const;
    std::shared_ptr<const EnvironmentMap> frame(size_t index);
    std::shared_ptr<const EnvironmentMap> frameAt(double seconds) {
        return frame(frameIndex(seconds));
    }

  private:
    std::string mPattern;
    std::vector<std::string> mFiles;
    double mFps = 10.0;
    double mIntensity = 1.0, mRotationDeg = 0.0;
    size_t mCachedIndex = 0;
    std::shared_ptr<const EnvironmentMap> mCached;
};

/// The parsed "environment" field of a scene.
struct EnvironmentSource {
    std::shared_ptr<const EnvironmentMap> map;      ///< The map now (frame 0 of a sequence).
    std::shared_ptr<EnvironmentSequence> sequence;  ///< Only for {"sequence": ...}.
};

/// Parses {"file": F, "intensity": k, "rotation_deg": a, "unit": U}, {"sky": {...}, "intensity",
/// ...} or {"sequence": "frames/*.exr", "fps": f, ...}; relative paths resolve against `baseDir`.
/// A file or sequence is in "W/(m2 sr)" (the default) or "cd/m2" ("unit"); the sky is in cd/m2.
/// Errors name the scene file and the field (and the image file for image errors).
EnvironmentSource parseEnvironment(const nlohmann::json& v, const json::Where& where,
                                   const std::string& baseDir);

/// The unit system of a scene's (already validated) "environment" field: the sky is
/// photometric, a file or a sequence whatever its "unit" says (radiometric by default).
Quantities environmentQuantities(const nlohmann::json& environment);

}  // namespace candela
