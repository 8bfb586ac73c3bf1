#include "luminaires/environment/Environment.h"

#include <glob.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "shaders/shared/Constants.h"
#include "util/Error.h"
#include "util/ImageRead.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

using gpu::kPi;
constexpr int kMaxSide = EnvironmentMap::kMaxSide;
/// Largest accepted intensity: keeps radiance x solid angle sums far from overflow.
constexpr double kMaxIntensity = 1e12;

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

double wrap01(double x) {
    x -= std::floor(x);
    return x < 1.0 ? x : 0.0;  // floor can round x - floor(x) up to exactly 1
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The lat-long map

EnvironmentMap::EnvironmentMap(int width, int height, std::vector<glm::vec3> rgb, double intensity,
                               double rotationDeg, std::string source)
    : mWidth(width), mHeight(height), mRgb(std::move(rgb)), mSource(std::move(source)) {
    if (width <= 0 || height <= 0)
        throw InputError(mSource + ": empty image (" + std::to_string(width) + "x" +
                         std::to_string(height) + ")");
    if (width > kMaxSide || height > kMaxSide)
        throw InputError(mSource + ": image size " + std::to_string(width) + "x" +
                         std::to_string(height) + " too large (at most " +
                         std::to_string(kMaxSide) + " per side)");
    if (mRgb.size() != size_t(width) * size_t(height))
        throw InputError(mSource + ": " + std::to_string(mRgb.size()) + " texels for a " +
                         std::to_string(width) + "x" + std::to_string(height) + " image");
    if (!(intensity >= 0.0 && intensity <= kMaxIntensity))
        throw InputError(mSource + ": intensity " + std::to_string(intensity) +
                         " out of range (expected 0 .. 1e12)");
    if (!std::isfinite(rotationDeg))
        throw InputError(mSource + ": rotation_deg must be a finite number of degrees");
    for (size_t i = 0; i < mRgb.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            float x = mRgb[i][c];
            if (std::isfinite(x) && x >= 0.f) continue;
            const char* what = std::isnan(x) ? "NaN" : (std::isinf(x) ? "infinite" : "negative");
            throw InputError(mSource + ": " + what + " texel value at (" +
                             std::to_string(i % size_t(width)) + ", " +
                             std::to_string(i / size_t(width)) + ") channel " + "RGB"[c] +
                             " (radiance must be finite and >= 0)");
        }
    }
    mIntensity = intensity;
    mRotation = rotationDeg * kPi / 180.0;
}

std::shared_ptr<EnvironmentMap> EnvironmentMap::load(const std::string& path, double intensity,
                                                     double rotationDeg, int maxSide) {
    std::string ext = lowerExtension(path);
    if (ext != ".hdr" && ext != ".exr")
        throw InputError(path + ": unsupported environment map type \"" + ext +
                         "\" (expected a lat-long .hdr or .exr)");
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw InputError(path + ": cannot open environment map (No such file or directory)");
    maxSide = std::min(maxSide, kMaxSide);
    ImageFileReader in(path, path, maxSide);  // util/ImageRead.h: the .hdr or .exr reader only
    int w = in.width(), h = in.height(), channels = in.channels();
    if (w <= 0 || h <= 0 || channels <= 0)
        throw InputError(path + ": empty image (" + std::to_string(w) + "x" + std::to_string(h) +
                         ")");
    if (int64_t(w) != 2 * int64_t(h))  // 64-bit: a file may claim any int size
        throw InputError(path + ": " + std::to_string(w) + "x" + std::to_string(h) +
                         " is not a lat-long map (expected width = 2 x height" +
                         (int64_t(h) == 6 * int64_t(w)
                              ? "; this looks like a cube map, which is not read yet)"
                              : ")"));
    if (w > maxSide)
        throw InputError(path + ": image size " + std::to_string(w) + "x" + std::to_string(h) +
                         " too large (at most " + std::to_string(maxSide) + " per side)");
    // RGB (or luminance): the channels after the third are never read, so a file declaring
    // thousands of them costs nothing (all of them were allocated before).
    channels = std::min(channels, 3);
    std::unique_ptr<float[]> pixels = in.readPixels(channels);
    std::vector<glm::vec3> rgb(size_t(w) * size_t(h));
    for (size_t i = 0; i < rgb.size(); ++i) {
        const float* p = &pixels[i * size_t(channels)];
        rgb[i] = channels >= 3 ? glm::vec3(p[0], p[1], p[2]) : glm::vec3(p[0]);
    }
    return std::make_shared<EnvironmentMap>(w, h, std::move(rgb), intensity, rotationDeg, path);
}

double EnvironmentMap::rowSolidAngle(int y) const {
    double t0 = kPi * double(y) / double(mHeight), t1 = kPi * double(y + 1) / double(mHeight);
    // cos(t0) - cos(t1) = 2 sin((t0 + t1) / 2) sin((t1 - t0) / 2), exact near the poles.
    return 2.0 * kPi / double(mWidth) * 2.0 * std::sin(0.5 * (t0 + t1)) * std::sin(0.5 * (t1 - t0));
}

glm::dvec2 EnvironmentMap::uvOf(const glm::dvec3& w) const {
    double len = glm::length(w);
    if (!(len > 0.0)) return {0.0, 0.0};
    glm::dvec3 d = w / len;
    double theta = std::acos(std::clamp(d.y, -1.0, 1.0));
    double phi = std::atan2(d.z, d.x);
    return {wrap01((phi - mRotation) / (2.0 * kPi)), theta / kPi};
}

glm::ivec2 EnvironmentMap::texelOf(const glm::dvec3& w) const {
    glm::dvec2 uv = uvOf(w);
    int x = std::clamp(int(uv.x * mWidth), 0, mWidth - 1);
    int y = std::clamp(int(uv.y * mHeight), 0, mHeight - 1);
    return {x, y};
}

glm::dvec3 EnvironmentMap::direction(double u, double v) const {
    double theta = kPi * v, phi = 2.0 * kPi * u + mRotation;
    double s = std::sin(theta);
    return {s * std::cos(phi), std::cos(theta), s * std::sin(phi)};
}

glm::dvec3 EnvironmentMap::radiance(const glm::dvec3& w) const {
    glm::ivec2 t = texelOf(w);
    return texel(t.x, t.y);
}

double EnvironmentMap::totalLuminancePower() const {
    double sum = 0.0;
    for (int y = 0; y < mHeight; ++y) {
        double row = 0.0;
        for (int x = 0; x < mWidth; ++x) row += texelLuminance(x, y);
        sum += row * rowSolidAngle(y);
    }
    return sum;
}

// ---------------------------------------------------------------------------------------------
// The procedural sky

namespace {

/// Perez et al. (1993) distribution F(theta, gamma) with coefficients c = {A, B, C, D, E}.
double perez(const double c[5], double cosTheta, double gamma) {
    double cg = std::cos(gamma);
    return (1.0 + c[0] * std::exp(c[1] / std::max(cosTheta, 1e-3))) *
           (1.0 + c[2] * std::exp(c[3] * gamma) + c[4] * cg * cg);
}

/// Zenith chromaticity: Preetham et al. (1999), Appendix A.2, T^2, T, 1 rows times
/// (theta_s^3, theta_s^2, theta_s, 1).
double zenithChromaticity(const double m[3][4], double t, double thetaS) {
    double th[4] = {thetaS * thetaS * thetaS, thetaS * thetaS, thetaS, 1.0};
    double row[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) row[i] += m[i][j] * th[j];
    return t * t * row[0] + t * row[1] + row[2];
}

/// CIE xyY to linear sRGB (Rec. 709 primaries, D65), negative components clamped.
glm::dvec3 xyYToRgb(double x, double y, double Y) {
    if (!(y > 0.0)) return glm::dvec3(0.0);
    double X = x * Y / y, Z = (1.0 - x - y) * Y / y;
    glm::dvec3 c(3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z,
                 -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
                 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z);
    return glm::max(c, glm::dvec3(0.0));
}

/// Direct normal illuminance of the sun (lux) at elevation h (radians) for Linke turbidity t:
/// Rigollier et al. (2000) Eq. (2) with the solar illuminance constant 128 klx, the Kasten and
/// Young (1989) relative air mass and Kasten's (1996) Rayleigh optical thickness.
double sunNormalIlluminance(double h, double t) {
    double hDeg = h * 180.0 / kPi;
    double m = 1.0 / (std::sin(h) + 0.50572 * std::pow(hDeg + 6.07995, -1.6364));
    double rayleigh =
        m <= 20.0 ? 1.0 / (6.6296 + m * (1.7513 + m * (-0.1202 + m * (0.0065 - m * 0.00013))))
                  : 1.0 / (10.4 + 0.718 * m);
    return 128000.0 * std::exp(-0.8662 * t * m * rayleigh);
}

}  // namespace

std::shared_ptr<EnvironmentMap> EnvironmentMap::adjusted(double intensity,
                                                         double rotationDeg) const {
    return std::make_shared<EnvironmentMap>(mWidth, mHeight, mRgb, intensity, rotationDeg, mSource);
}

SunPosition sunPosition(double latitudeDeg, int dayOfYear, double solarHours) {
    const double rad = kPi / 180.0;
    double declination = 23.45 * rad * std::sin(2.0 * kPi * (284.0 + dayOfYear) / 365.0);
    double hourAngle = 15.0 * rad * (solarHours - 12.0);
    double lat = latitudeDeg * rad;
    // East-north-up components of the unit vector to the sun.
    double up = std::sin(lat) * std::sin(declination) +
                std::cos(lat) * std::cos(declination) * std::cos(hourAngle);
    double east = -std::cos(declination) * std::sin(hourAngle);
    double north = std::cos(lat) * std::sin(declination) -
                   std::sin(lat) * std::cos(declination) * std::cos(hourAngle);
    SunPosition out;
    out.elevationDeg = std::asin(std::clamp(up, -1.0, 1.0)) / rad;
    // Scene: x = east, z = -north; phi = atan2(z, x).
    out.azimuthDeg = std::atan2(-north, east) / rad;
    return out;
}

namespace {

/// Throws InputError for sky parameters outside the model's range or the map's limits.
void checkSkyParams(const SkyParams& sky) {
    if (!(sky.sunElevationDeg >= 0.0 && sky.sunElevationDeg <= 90.0))
        throw InputError("sky: sun_elevation_deg must be in [0, 90] (the model has no night)");
    if (!(sky.turbidity >= 1.7 && sky.turbidity <= 10.0))
        throw InputError("sky: turbidity must be in [1.7, 10] (the range Preetham et al. fitted)");
    if (!std::isfinite(sky.sunAzimuthDeg))
        throw InputError("sky: sun_azimuth_deg must be a finite number of degrees");
    if (!(sky.groundAlbedo >= 0.0 && sky.groundAlbedo <= 1.0))
        throw InputError("sky: ground albedo must be in [0, 1]");
    if (sky.width < 8 || sky.width > kMaxSide || sky.width % 2 != 0)
        throw InputError("sky: resolution must be an even width in [8, 16384] texels");
}

/// Solid angle (sr) of one texel in row y of an unrotated w x h map.
double texelSolidAngle(int y, int w, int h) {
    double t0 = kPi * y / h, t1 = kPi * (y + 1) / h;
    return 2.0 * kPi / w * 2.0 * std::sin(0.5 * (t0 + t1)) * std::sin(0.5 * (t1 - t0));
}

/// Radiance of Preetham et al.'s (1999) clear sky for turbidity t and the sun at `sun` (zenith
/// angle thetaS), in the upper half of an unrotated w x h map; the lower half is left 0.
std::vector<glm::dvec3> preethamSky(double t, double thetaS, const glm::dvec3& sun, int w, int h) {
    // Preetham et al. (1999), Appendix A.2: Perez coefficients for Y, x and y, linear in T.
    const double cY[5] = {0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251,
                          0.1206 * t - 2.5771, -0.0670 * t + 0.3703};
    const double cx[5] = {-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125,
                          -0.0641 * t - 0.8989, -0.0033 * t + 0.0452};
    const double cy[5] = {-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102,
                          -0.0441 * t - 1.6537, -0.0109 * t + 0.0529};
    // Zenith luminance (kcd/m2), Preetham Eq. in A.2: chi = (4/9 - T/120)(pi - 2 theta_s).
    double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2.0 * thetaS);
    double yZenith = ((4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192) * 1000.0;
    static const double kMx[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                     {-0.02903, 0.06377, -0.03202, 0.00394},
                                     {0.11693, -0.21196, 0.06052, 0.25886}};
    static const double kMy[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                     {-0.04214, 0.08970, -0.04153, 0.00516},
                                     {0.15346, -0.26756, 0.06670, 0.26688}};
    double xZenith = zenithChromaticity(kMx, t, thetaS);
    double yzChroma = zenithChromaticity(kMy, t, thetaS);

    // The map is built unrotated (rotation applies at lookup), so the sun sits at phi_s here.
    std::vector<glm::dvec3> acc(size_t(w) * size_t(h), glm::dvec3(0.0));
    auto dirOf = [&](double u, double v) {
        double th = kPi * v, ph = 2.0 * kPi * u;
        return glm::dvec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
    };
    for (int y = 0; y < h / 2; ++y) {
        for (int x = 0; x < w; ++x) {
            glm::dvec3 d = dirOf((x + 0.5) / w, (y + 0.5) / h);
            double gamma = std::acos(std::clamp(glm::dot(d, sun), -1.0, 1.0));
            double lum = yZenith * perez(cY, d.y, gamma) / perez(cY, 1.0, thetaS);
            double cxv = xZenith * perez(cx, d.y, gamma) / perez(cx, 1.0, thetaS);
            double cyv = yzChroma * perez(cy, d.y, gamma) / perez(cy, 1.0, thetaS);
            acc[size_t(y) * size_t(w) + size_t(x)] = xyYToRgb(cxv, cyv, std::max(lum, 0.0));
        }
    }
    return acc;
}

/// Adds the sun disc (turbidity t, zenith angle thetaS) to the unrotated w x h map `acc`.
void addSunDisc(std::vector<glm::dvec3>& acc, int w, int h, const glm::dvec3& sun, double thetaS,
                double t) {
    // The sun disc: 32 x 64 points equally spaced in solid angle (rings of equal area), each
    // carrying 1/2048 of E_dn; a point adds its share / texel solid angle to its texel.
    double eSun = sunNormalIlluminance(kPi / 2.0 - thetaS, t);
    double radius = kSunAngularRadiusDeg * kPi / 180.0;
    glm::dvec3 t1 = std::abs(sun.y) < 0.9 ? glm::normalize(glm::cross(sun, glm::dvec3(0, 1, 0)))
                                          : glm::dvec3(1, 0, 0);
    glm::dvec3 t2 = glm::cross(sun, t1);
    const int kRings = 32, kSpokes = 64;
    double share = eSun / double(kRings * kSpokes);
    for (int i = 0; i < kRings; ++i) {
        double alpha = radius * std::sqrt((i + 0.5) / kRings);
        for (int j = 0; j < kSpokes; ++j) {
            double beta = 2.0 * kPi * (j + 0.5) / kSpokes;
            glm::dvec3 d = std::cos(alpha) * sun +
                           std::sin(alpha) * (std::cos(beta) * t1 + std::sin(beta) * t2);
            if (d.y <= 0.0) continue;  // below the horizon: hidden by the ground
            double theta = std::acos(std::clamp(d.y, -1.0, 1.0));
            double u = wrap01(std::atan2(d.z, d.x) / (2.0 * kPi));
            int x = std::clamp(int(u * w), 0, w - 1),
                y = std::clamp(int(theta / kPi * h), 0, h - 1);
            acc[size_t(y) * size_t(w) + size_t(x)] += glm::dvec3(share / texelSolidAngle(y, w, h));
        }
    }
}

/// Radiance of the ground: a Lambertian plane of this albedo lit by the sky and the sun above
/// it (the upper half of `acc`).
glm::dvec3 groundRadiance(const std::vector<glm::dvec3>& acc, int w, int h, double albedo) {
    glm::dvec3 eHorizontal(0.0);
    for (int y = 0; y < h / 2; ++y) {
        double cosTheta = std::cos(kPi * (y + 0.5) / h);
        for (int x = 0; x < w; ++x)
            eHorizontal +=
                acc[size_t(y) * size_t(w) + size_t(x)] * cosTheta * texelSolidAngle(y, w, h);
    }
    return albedo * eHorizontal / kPi;
}

}  // namespace

std::shared_ptr<EnvironmentMap> makeSkyMap(const SkyParams& sky, double intensity,
                                           double rotationDeg) {
    checkSkyParams(sky);
    const int w = sky.width, h = sky.width / 2;
    const double t = sky.turbidity;
    const double thetaS = kPi / 2.0 - sky.sunElevationDeg * kPi / 180.0;
    const double phiS = sky.sunAzimuthDeg * kPi / 180.0;
    const glm::dvec3 sun(std::sin(thetaS) * std::cos(phiS), std::cos(thetaS),
                         std::sin(thetaS) * std::sin(phiS));
    std::vector<glm::dvec3> acc = preethamSky(t, thetaS, sun, w, h);
    addSunDisc(acc, w, h, sun, thetaS, t);
    glm::dvec3 ground = groundRadiance(acc, w, h, sky.groundAlbedo);
    std::vector<glm::vec3> rgb(acc.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            size_t i = size_t(y) * size_t(w) + size_t(x);
            rgb[i] = glm::vec3(y < h / 2 ? acc[i] : ground);
        }
    char name[160];
    std::snprintf(name, sizeof name, "sky (sun elevation %g deg, azimuth %g deg, turbidity %g)",
                  sky.sunElevationDeg, sky.sunAzimuthDeg, sky.turbidity);
    return std::make_shared<EnvironmentMap>(w, h, std::move(rgb), intensity, rotationDeg, name);
}

// ---------------------------------------------------------------------------------------------
// Sequences

EnvironmentSequence::EnvironmentSequence(std::string pattern, std::vector<std::string> files,
                                         double fps, double intensity, double rotationDeg)
    : mPattern(std::move(pattern)),
      mFiles(std::move(files)),
      mFps(fps),
      mIntensity(intensity),
      mRotationDeg(rotationDeg) {
    if (mFiles.empty()) throw InputError(mPattern + ": no file matches the sequence pattern");
    if (!(fps > 0.0 && std::isfinite(fps)))
        throw InputError(mPattern + ": fps must be a positive number of frames per second");
    mCached = EnvironmentMap::load(mFiles[0], mIntensity, mRotationDeg);
    mCachedIndex = 0;
}

std::shared_ptr<EnvironmentSequence> EnvironmentSequence::open(const std::string& pattern,
                                                               double fps, double intensity,
                                                               double rotationDeg) {
    glob_t g{};
    int rc = ::glob(pattern.c_str(), 0, nullptr, &g);
    std::vector<std::string> files;
    if (rc == 0)
        for (size_t i = 0; i < g.gl_pathc; ++i) files.emplace_back(g.gl_pathv[i]);
    globfree(&g);
    std::sort(files.begin(), files.end());
    return std::make_shared<EnvironmentSequence>(pattern, std::move(files), fps, intensity,
                                                 rotationDeg);
}

size_t EnvironmentSequence::frameIndex(double seconds) const {
    if (!(seconds > 0.0) || !std::isfinite(seconds)) return 0;
    double f = std::floor(seconds * mFps);
    return size_t(std::fmod(f, double(mFiles.size())));
}

std::shared_ptr<const EnvironmentMap> EnvironmentSequence::frame(size_t index) {
    index %= mFiles.size();
    if (!mCached || index != mCachedIndex) {
        mCached = EnvironmentMap::load(mFiles[index], mIntensity, mRotationDeg);
        mCachedIndex = index;
    }
    return mCached;
}

// ---------------------------------------------------------------------------------------------
// The scene-file field

namespace {

std::string resolve(const std::string& file, const std::string& baseDir) {
    fs::path p(file);
    if (p.is_relative() && !baseDir.empty()) p = fs::path(baseDir) / p;
    return p.string();
}

double readIntensity(const nlohmann::json& v, const json::Where& where) {
    double x = json::number(v, where);
    if (!(x >= 0.0 && x <= kMaxIntensity))
        json::fail(where, "a scale factor in [0, 1e12], got " + v.dump());
    return x;
}

/// Reruns `load` turning its errors into "scene.json: environment.file: <its message>".
template <class Fn>
auto withWhere(const json::Where& where, Fn load) {
    try {
        return load();
    } catch (const InputError& e) {
        throw InputError(where.str() + ": " + e.what());
    }
}

SkyParams readSky(const nlohmann::json& v, const json::Where& at) {
    json::checkKeys(
        v, {"sun_elevation_deg", "sun_azimuth_deg", "turbidity", "ground_albedo", "resolution"},
        at);
    SkyParams sky;
    sky.sunElevationDeg =
        json::optional(v, "sun_elevation_deg", at, sky.sunElevationDeg, json::number);
    if (!(sky.sunElevationDeg >= 0.0 && sky.sunElevationDeg <= 90.0))
        json::fail(at / "sun_elevation_deg",
                   "an elevation in [0, 90] degrees, got " + v["sun_elevation_deg"].dump());
    sky.sunAzimuthDeg = json::optional(v, "sun_azimuth_deg", at, sky.sunAzimuthDeg, json::number);
    sky.turbidity = json::optional(v, "turbidity", at, sky.turbidity, json::number);
    if (!(sky.turbidity >= 1.7 && sky.turbidity <= 10.0))
        json::fail(at / "turbidity", "a turbidity in [1.7, 10], got " + v["turbidity"].dump());
    sky.groundAlbedo = json::optional(v, "ground_albedo", at, sky.groundAlbedo, json::number);
    if (!(sky.groundAlbedo >= 0.0 && sky.groundAlbedo <= 1.0))
        json::fail(at / "ground_albedo",
                   "a reflectance in [0, 1], got " + v["ground_albedo"].dump());
    double width = json::optional(v, "resolution", at, double(sky.width), json::number);
    if (!(width >= 8 && width <= kMaxSide && std::floor(width) == width && int(width) % 2 == 0))
        json::fail(at / "resolution",
                   "an even lat-long width in [8, 16384] texels, got " + v["resolution"].dump());
    sky.width = int(width);
    return sky;
}

}  // namespace

namespace {

/// The optional "unit" of a map or sequence: "W/(m2 sr)" (the default) or "cd/m2".
Quantities readUnit(const nlohmann::json& v, const json::Where& where) {
    if (!v.contains("unit")) return Quantities::Radiometric;
    std::string unit = json::string(v["unit"], where / "unit");
    if (unit == "cd/m2") return Quantities::Photometric;
    if (unit != "W/(m2 sr)")
        json::fail(where / "unit", "\"W/(m2 sr)\" or \"cd/m2\", got \"" + unit + "\"");
    return Quantities::Radiometric;
}

}  // namespace

Quantities environmentQuantities(const nlohmann::json& environment) {
    if (!environment.is_object()) return Quantities::Radiometric;
    if (environment.contains("sky")) return Quantities::Photometric;
    auto unit = environment.find("unit");
    return unit != environment.end() && unit->is_string() && unit->get<std::string>() == "cd/m2"
               ? Quantities::Photometric
               : Quantities::Radiometric;
}

EnvironmentSource parseEnvironment(const nlohmann::json& v, const json::Where& where,
                                   const std::string& baseDir) {
    if (!v.is_object())
        json::fail(where, "null or an object with \"file\", \"sky\" or \"sequence\", got " +
                              std::string(v.type_name()));
    int kinds = int(v.contains("file")) + int(v.contains("sky")) + int(v.contains("sequence"));
    if (kinds != 1) json::fail(where, "exactly one of \"file\", \"sky\" or \"sequence\"");
    double intensity = json::optional(v, "intensity", where, 1.0, readIntensity);
    double rotation =
        json::optional(v, "rotation_deg", where, 0.0,
                       json::range(-json::kMaxAngleDeg, json::kMaxAngleDeg, "an angle in degrees"));
    EnvironmentSource out;
    if (v.contains("file")) {
        json::checkKeys(v, {"file", "intensity", "rotation_deg", "unit"}, where);
        readUnit(v, where);
        std::string file = resolve(json::string(v["file"], where / "file"), baseDir);
        out.map = withWhere(where / "file",
                            [&] { return EnvironmentMap::load(file, intensity, rotation); });
    } else if (v.contains("sky")) {
        json::checkKeys(v, {"sky", "intensity", "rotation_deg"}, where);
        SkyParams sky = readSky(v["sky"], where / "sky");
        out.map = withWhere(where / "sky", [&] { return makeSkyMap(sky, intensity, rotation); });
    } else {
        json::checkKeys(v, {"sequence", "fps", "intensity", "rotation_deg", "unit"}, where);
        readUnit(v, where);
        std::string pattern = resolve(json::string(v["sequence"], where / "sequence"), baseDir);
        double fps = json::optional(v, "fps", where, 10.0, json::positive);
        out.sequence = withWhere(where / "sequence", [&] {
            return EnvironmentSequence::open(pattern, fps, intensity, rotation);
        });
        out.map = out.sequence->frame(0);
    }
    return out;
}

}  // namespace candela
