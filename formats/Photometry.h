#pragma once
// Far-field photometry of a luminaire: luminous intensity per direction from an IES LM-63 or
// EULUMDAT file, plus the size of its luminous opening (Prost 2019, seed 004, Ch. 2).
//
// Local frame (PhotometricLuminaire::photometricFrame): +z is the aim (gamma = 0, nadir for a
// downlight), +x is C = 0 (the pose's c0), +y is C = 90 = c0 x aim, so C grows counter-clockwise
// seen from above a downlight (Pose::frame's y, aim x c0, is the opposite direction). For type B
// files the polar axis is local +y: horizontal angle H turns about +y from +z towards +x, vertical
// angle V lifts towards +y, so (H, V) = (0, 0) is the aim.
//
// The table is stored expanded to the full range its goniometer covers (symmetries unfolded), in
// absolute candela (candela multiplier, ballast factor, ballast-lamp factor and EULUMDAT's cd/klm
// scaling applied). TILT=INCLUDE (or a TILT file next to the .ies) is applied at the tilt of the
// luminaire's standard orientation (angle 0 of the tilt table) and kept in `tilt` so a renderer
// can apply the factor for another mounting. No GL here.
//
// Leniency: files that DIALux and Relux read load here too, and what was assumed to read them
// is kept in PhotometricData::warnings, one line each ("PATH:LINE: what; what was assumed"):
// UTF-16 and Windows-1252 (Latin-1) text (transcoded to UTF-8), mixed line endings, trailing
// blank lines, values after the table (ignored); in IES files "//" comments; in EULUMDAT files
// empty lamp-set fields (type, colour temperature, colour rendering, wattage), empty direct
// ratios, a repeated last C plane (a C360 copy of C0, or the last angle twice), decimal commas,
// a conversion factor of 0 (read as 1) and a light output ratio of 0 (the declared flux
// unknown). With PhotometryOptions::strict each of them is an InputError instead, naming the
// file, the line and the leniency. Defective values (non-numbers, inf, NaN, negative
// intensities, intensities above kMaxCandela, openings above kMaxOpening) are always errors.

#include <glm/glm.hpp>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace candela {

enum class Goniometer { C, B };

/// Symmetry as declared in the file (kept for `candela info`; the table is already unfolded).
enum class PhotometricSymmetry {
    None,          ///< Full 0-360 (IES) / Isym 0.
    Axial,         ///< One C plane: rotationally symmetric (IES single angle / Isym 1).
    Quadrant,      ///< 0-90 mirrored to all four quadrants (IES 0-90 / Isym 4).
    PlaneC0C180,   ///< Mirror about the C0-C180 plane (IES 0-180 / Isym 2).
    PlaneC90C270,  ///< Mirror about the C90-C270 plane (IES 90-270 / Isym 3).
};

/// The luminous opening in the local frame, centred on the origin, in metres. An IES file gives
/// its length along C0-C180 (local x) and its width along C90-C270 (local y); a EULUMDAT file its
/// length along C90-C270 (the luminaire's long axis) and its width along C0-C180.
struct LuminousOpening {
    enum class Shape { Point, Rectangle, Ellipse, Sphere, Cylinder };
    /// Axis of a Cylinder (added for the LM-63-2002 horizontal cylinders): Z for the usual
    /// vertical cylinder (an ellipse of length x width seen from below), X or Y for a cylinder
    /// lying along local x or y, whose emitting face seen from below is its length x width
    /// rectangle. Ignored for the other shapes.
    enum class Axis { Z, X, Y };
    Shape shape = Shape::Point;
    Axis axis = Axis::Z;
    /// Along local x (C0-C180), metres: an IES file's length, a EULUMDAT file's width.
    double length = 0.0;
    /// Along local y (C90-C270), metres: an IES file's width, a EULUMDAT file's length.
    double width = 0.0;
    double height = 0.0;  ///< Along local z, metres (0 for flat openings).
    /// Polygon of the emitting face, counter-clockwise seen from below (from +z looking back at
    /// the luminaire, i.e. the emitting side), in the local z = 0 plane; ellipses as 16-gons.
    /// Empty for a point source.
    std::vector<glm::dvec2> polygon() const;
    double area() const;  ///< Area of polygon(), m2 (0 for a point).
};

/// How a photometry file is read.
struct PhotometryOptions {
    /// Refuse every leniency (an InputError "PATH:LINE: LENIENCY (refused by --strict)") instead
    /// of loading the file with a warning.
    bool strict = false;
};

/// Largest absolute intensity a file may give, cd. The brightest searchlights reach about 1e9 cd;
/// this leaves six orders of magnitude and keeps squares of intensities (variances) within float
/// range on the GPU (1e30 < 3.4e38), so a file holding 1e308 is refused rather than giving an
/// infinite flux.
constexpr double kMaxCandela = 1e15;
/// Largest declared flux (lamp flux, or lamp flux x light output ratio), lm: what a table within
/// kMaxCandela can hold, 4 pi x 1e15 lm, rounded up.
constexpr double kMaxLumens = 1e16;
/// Largest luminous opening (length, width, height), metres: no luminaire's opening is a
/// kilometre across, and its area stays far from overflowing.
constexpr double kMaxOpening = 1e3;

struct PhotometricData {
    std::string path;    ///< File it came from (for messages).
    std::string format;  ///< "IES LM-63-1986", "IES LM-63-1991", "-1995", "-2002", "-2019",
                         ///< "EULUMDAT", "IES TM-33-18", "IES TM-33-23".
    std::vector<std::pair<std::string, std::string>> keywords;  ///< IES [KEY] value / LDT fields.
    std::string name;  ///< Luminaire name (IES [LUMINAIRE] or LDT luminaire name), may be empty.

    Goniometer goniometer = Goniometer::C;
    PhotometricSymmetry symmetry = PhotometricSymmetry::Axial;
    /// Polar angles, degrees, strictly ascending: gamma in [0, 180] for type C, V in [-90, 90]
    /// for type B.
    std::vector<double> vertical;
    /// Azimuths, degrees, strictly ascending, unfolded to the full turn: type C from 0 to 360
    /// inclusive (first and last rows equal), type B from -180 to 180 inclusive (or -90..90 when
    /// the file covers only the front).
    std::vector<double> horizontal;
    /// Absolute candela, candela[h * vertical.size() + v], all >= 0 and finite.
    std::vector<double> candela;

    LuminousOpening opening;

    double lampFlux =
        -1.0;  ///< Rated lamp lumens in total (all lamps); -1 for absolute photometry.
    /// EULUMDAT: each lamp set's total luminous flux (field 26c), lm, in the file's order (their
    /// sum is lampFlux); empty for the other formats. Catalogue UGR tables use the first set's.
    std::vector<double> lampSetFlux;
    double lightOutputRatio = 1.0;          ///< EULUMDAT LORL / 100; 1 when the file does not say.
    bool declaresLightOutputRatio = false;  ///< The file states one (EULUMDAT; IES has no field).
    double inputWatts = 0.0;
    /// The luminaire's luminous flux as the file states it beside its table (TM-33's
    /// LuminousFlux), lm; 0 when it states none. Only compared with fluxFromTable(), never used
    /// in place of it.
    double statedFlux = 0.0;

    /// What was assumed to read the file (see "Leniency" above), one line each, valid UTF-8:
    /// "PATH:LINE: what; what was assumed". Empty for a file that follows its format.
    std::vector<std::string> warnings;

    /// IES TILT table (lamp-to-luminaire geometry 1-3, angles in degrees, multiplying factors);
    /// empty for TILT=NONE.
    int tiltGeometry = 0;
    std::vector<double> tiltAngles, tiltFactors;
    std::string tiltPath;  ///< The TILT=<file> file read (empty for NONE or INCLUDE).

    /// Luminous intensity in candela towards the unit local direction d (local frame above);
    /// bilinear in (vertical, horizontal) so it is never negative; 0 outside the table's range.
    double intensity(const glm::dvec3& d) const;
    /// Total luminous flux, lm: the exact integral over the sphere of the bilinear interpolant
    /// that intensity() evaluates (per cell, linear in angle times sin/cos integrated in closed
    /// form).
    double fluxFromTable() const;
    /// The first non-empty value among `keys` (IES [KEY]s, EULUMDAT fields, TM-33 elements), in
    /// the order given; "" when none is there.
    std::string keyword(std::initializer_list<const char*> keys) const;
    /// The largest intensity in the table, cd.
    double maxIntensity() const;
    /// The flux the file declares for the luminaire, lamp flux x light output ratio, lm; 0 when
    /// it declares none (absolute photometry, or a light output ratio of 0).
    double declaredFlux() const;
};

/// Whether loadPhotometry() reads files with this extension (lower case, with its dot): .ies,
/// .ldt, and .xml or .iesxml for TM-33.
bool isPhotometryExtension(const std::string& lowerExtension);

/// The options loadPhotometry() and the parsers use when given none: every luminaire a scene or
/// the editor loads. The command line's --strict sets them once, before anything is loaded
/// (PhotometricLuminaire::load caches files by path, not by options).
const PhotometryOptions& defaultPhotometryOptions();
void setDefaultPhotometryOptions(const PhotometryOptions& options);

/// Reads an IES LM-63 (.ies), EULUMDAT (.ldt) or IES TM-33 (.xml, .iesxml) file, chosen by
/// extension (case-insensitive).
/// Throws InputError "PATH:LINE: what was expected, what was found" on any defect (one line,
/// valid UTF-8); `text` is the file's bytes in any encoding the leniency above allows.
PhotometricData loadPhotometry(const std::string& path,
                               const PhotometryOptions& options = defaultPhotometryOptions());
PhotometricData parseIes(const std::string& text, const std::string& pathForMessages,
                         const PhotometryOptions& options = defaultPhotometryOptions());
PhotometricData parseEulumdat(const std::string& text, const std::string& pathForMessages,
                              const PhotometryOptions& options = defaultPhotometryOptions());
/// IES TM-33-18 (root <IESTM33>) and TM-33-23 (root <IESTM33-22>) XML: see Tm33File.cpp.
PhotometricData parseTm33(const std::string& text, const std::string& pathForMessages,
                          const PhotometryOptions& options = defaultPhotometryOptions());

/// A table written as an IES TM-33-18 document (root <IESTM33>, version 1.0): the horizontal
/// angles its symmetry needs, the opening as emission areas, the header from the source's
/// keywords. `date` (YYYY-MM-DD) stands for the report date when the source states none (a
/// comment says so). What the format cannot hold (a spherical or lying cylindrical opening,
/// written as its bounding box) is appended to `notes`, one line each.
std::string writeTm33(const PhotometricData& data, const std::string& date,
                      std::vector<std::string>& notes);

/// Helpers shared by the two parsers (Photometry.cpp); not part of the public interface.
namespace photometry_detail {
/// Largest angle or candela count a file may declare (guards allocations on corrupt files).
constexpr int kMaxCount = 100000;
/// Throws InputError "PATH:LINE: expected EXPECTED, found FOUND" (made valid UTF-8).
[[noreturn]] void fail(const std::string& path, int line, const std::string& expected,
                       const std::string& found);
/// A leniency at `lines` ("12" or "12-21"): appends "PATH:LINES: WHAT; ASSUMED" to
/// data.warnings, or in strict mode throws InputError "PATH:LINES: WHAT (refused by --strict)".
void allow(PhotometricData& data, const PhotometryOptions& options, const std::string& lines,
           const std::string& what, const std::string& assumed);
inline void allow(PhotometricData& data, const PhotometryOptions& options, int line,
                  const std::string& what, const std::string& assumed) {
    allow(data, options, std::to_string(line), what, assumed);
}
/// The file's bytes as lines of UTF-8 text: decodes them (util/TextEncoding.h) and allows (see
/// allow()) a non-UTF-8 encoding, mixed line endings and trailing blank lines, which are dropped.
std::vector<std::string> readLines(const std::string& bytes, PhotometricData& data,
                                   const PhotometryOptions& options);
/// Refuses (fail()) intensities above kMaxCandela; `line` is where the value is.
void checkCandela(const std::string& path, int line, double candela, const std::string& what);
/// Parses a whole token as a finite double (C locale, no trailing characters).
bool parseNumber(const std::string& token, double& value);
/// Splits text into lines on LF, CRLF or a lone CR (a final line without a newline included).
std::vector<std::string> splitLines(const std::string& text);
/// A number's text to 9 significant digits, for messages.
std::string formatNumber(double v);
/// The symmetry that the range of a file's horizontal angles implies (LM-63's rule, which
/// TM-33-18 keeps): one angle axial; type C 0..90 quadrants, 0..180 and 90..270 mirrors, 0..(more
/// than 180) none; type B 0..H mirrored about H = 0, from below 0 none. `given` is ascending and
/// within the goniometer's range; fails naming `line` for any other range.
PhotometricSymmetry symmetryOfRange(Goniometer goniometer, const std::vector<double>& given,
                                    const std::string& path, int line);
/// The tilt table's factor at angle 0 (the standard orientation), linear between entries and
/// held at the end values outside the table; 1 without a table.
double tiltFactorAtZero(const PhotometricData& d);
/// Unfolds rows of candela given at the file's horizontal angles `given` (row h holds
/// data.vertical.size() values) into data.horizontal / data.candela over the full range, using
/// data.goniometer and data.symmetry. Type C: 0..360 inclusive; type B: -180..180 or the mirrored
/// front range. The given angles must already be validated for the symmetry.
void unfold(PhotometricData& data, const std::vector<double>& given,
            const std::vector<double>& givenCandela);
}  // namespace photometry_detail

}  // namespace candela
