#pragma once
// The standard UGR table of a luminaire's photometric file: CIE 190:2010's tabular method, the
// table of 19 room sizes x 5 reflectance sets x 2 viewing directions that catalogues print and
// designers look up (EN 12464-1's UGR_L is checked against it).
//
// The standard room (CIE 190, as catalogue programs set it up): an observer at the middle of
// one wall, eye H below the plane of the luminaires, looking horizontally across the room; X
// is the room's size across the line of sight, Y along it, both in units of H. A regular grid of
// identical luminaires fills the ceiling, `spacing` x H apart, half a spacing in from the walls.
// Crosswise, the luminaire's C0 half-plane faces the observer (C = atan(T / R), CIE 117 eq. 4.5;
// for a linear EULUMDAT luminaire its length runs across the line of sight); endwise, C90 does
// (C = 90 deg - atan(T / R), eq. 4.6). T is a luminaire's offset across the line of sight, R
// along it, gamma = atan(sqrt(R^2 + T^2) / H).
//
// Each cell is CIE 117's UGR = 8 log10(0.25 / Lb x sum of L^2 omega / p^2) over the luminaires
// in the field of view (T / R <= 3, gamma <= 85 deg, Guth's index tabulated there), with
//   L = I(C, gamma) / Ap(C, gamma), the luminous area projected towards the eye (cd/m2),
//   omega = Ap / r^2 (sr), so L^2 omega = I^2 / (Ap r^2),
//   p from CIE 117 Table 4.1 (Guth), bilinear in T / R and H / R (not Levin's fit, which
//     calculation/Glare.h uses at observers: catalogue tables, and the programs that print them,
//     use the table, and the table here is compared with theirs),
//   Lb = E_WID / pi, the indirect vertical illuminance at the eye (CIE 190 eqs 7-12):
//     E_WID = B F_UWID, B = Phi N / A_w (A_w = 2 H (X + Y), the walls between the eye and the
//     luminaires; N every luminaire of the room), F_UWID = F_DF F_T,FW + F_DW F_T,WW-1 +
//     F_DC F_T,CW with the transfer factors of CIE 190 Table 5 and the distribution fractions
//     F_DF (direct to the floor), F_DW (to the walls), F_DC (to the ceiling) from the zonal
//     fluxes and CIE 190 Table 4's F_GL (see computeUgrTable).
// The table does not depend on H: sum L^2 omega / p^2 and Lb both scale as 1 / H^2. Small
// luminous areas keep L^2 omega: CIE 147's small-source form, which calculation/Glare.h applies at
// observers, is not part of the tabular method the table is checked against.
//
// The flux Phi: the intensities are taken at the flux the file gives them for, and Phi is that
// flux, as DIALux and Relux print catalogue tables: the first lamp set's for EULUMDAT (its
// cd/klm per 1000 lm of that set), the lamps' for a relative IES or TM-33 file, the luminaire's
// for absolute photometry. L^2 scales as Phi^2 and Lb as Phi, so UGR(Phi') = UGR(Phi) +
// 8 log10(Phi' / Phi) (CIE 190 eq. 2, with Phi = 1000 lm for its normalised tables).
//
// No GL here.

#include <array>
#include <string>
#include <vector>

#include "formats/Photometry.h"

namespace candela {

/// The 19 room sizes (X, Y in units of H), in the order catalogues print them.
struct UgrRoomSize {
    int x = 0, y = 0;
};
constexpr int kUgrRoomCount = 19, kUgrReflectanceCount = 5;
extern const std::array<UgrRoomSize, kUgrRoomCount> kUgrRoomSizes;

/// Ceiling, walls and floor (the reference plane) reflectances, %.
struct UgrReflectances {
    int ceiling = 0, walls = 0, floor = 0;
};
extern const std::array<UgrReflectances, kUgrReflectanceCount> kUgrReflectances;

struct UgrTableOptions {
    /// Luminaire spacing over H (the spacing-to-height ratio). 0.25, DIALux and Relux's
    /// catalogue convention, is the default; CIE 190's own standard-condition table uses 1.
    /// 1 / spacing must be a whole number, so that every standard room holds whole rows.
    double spacing = 0.25;
    double height = 2.0;  ///< H, luminaires above the eye, m (the table does not depend on it).
};

/// The luminous area as the table projects it, in the photometric frame (metres).
struct UgrLuminousArea {
    enum class Shape {
        Box,               ///< Rectangle alongC0 x alongC90 with four vertical faces.
        Round,             ///< Ellipse (circle) alongC0 x alongC90 with a vertical side.
        Ellipsoid,         ///< Axes alongC0, alongC90 and heights[0] (a sphere when equal).
        CylinderAlongC0,   ///< Lying cylinder: length alongC0, diameter alongC90.
        CylinderAlongC90,  ///< Lying cylinder: length alongC90, diameter alongC0.
    };
    Shape shape = Shape::Box;
    double alongC0 = 0.0;   ///< Extent along the C0-C180 axis, m.
    double alongC90 = 0.0;  ///< Extent along the C90-C270 axis, m.
    /// Heights of the faces seen from C0, C90, C180 and C270, m (all 0: flat).
    std::array<double, 4> heights{};
    std::string note;  ///< Where the sizes come from, for the printed header.

    /// Seen from below: the area the table uses at gamma 0, m2.
    double bottom() const;
    /// Projected towards the direction (C, gamma) in degrees, m2.
    double projected(double cDeg, double gammaDeg) const;
};

/// Guth's position index from CIE 117 Table 4.1, bilinear in T / R (rows 0..3 by 0.1) and
/// H / R (columns 0..1.9 by 0.1); 0 where the table gives none (outside it, or next to a
/// missing entry).
double guthTablePositionIndex(double tOverR, double hOverR);

/// One room size of the table with what its cells are made of.
struct UgrRoomResult {
    UgrRoomSize size;
    double roomIndex = 0.0;        ///< k = X Y / (H (X + Y)).
    int luminaires = 0;            ///< N, every luminaire of the room.
    std::array<int, 2> counted{};  ///< In the field of view: crosswise, endwise.
    std::array<double, 2> sum{};   ///< Sum of L^2 omega / p^2, (cd/m2)^2 sr: crosswise, endwise.
    std::array<double, 4> fGL{};   ///< CIE 190 Table 4's F_GL1..4 at k.
    double fDF = 0.0, fDW = 0.0, fDC = 0.0;  ///< Direct fractions to floor, walls, ceiling.
    double wallFlux = 0.0;                   ///< B = Phi N / A_w, lm/m2.
    /// Per reflectance set: CIE 190 Table 5's F_T,FW, F_T,WW-1, F_T,CW.
    std::array<std::array<double, 3>, kUgrReflectanceCount> fT{};
    std::array<double, kUgrReflectanceCount> fUWID{};       ///< F_UWID.
    std::array<double, kUgrReflectanceCount> background{};  ///< Lb, cd/m2.
    /// UGR per reflectance set, crosswise and endwise; NaN when no luminaire in the field of
    /// view emits towards the eye (an uplight: no direct glare to rate).
    std::array<double, kUgrReflectanceCount> crosswise{}, endwise{};
};

struct UgrTable {
    std::string path;  ///< The photometric file.
    UgrTableOptions options;
    double flux = 0.0;  ///< Phi, lm (see above).
    std::string
        fluxNote;  ///< Whose flux it is ("lamp set 1 of 2", "lamps", "absolute photometry").
    double lightOutputRatio = 0.0;  ///< Luminaire over lamp flux (1 for absolute photometry).
    double rDLO = 0.0, rULO = 0.0;  ///< Downward and upward light output ratios.
    /// Fractions of Phi emitted below 41.4, 60, 75.5 and 90 degrees (the zones CIE 190's F_GL
    /// weigh).
    std::array<double, 4> cumulative{};
    UgrLuminousArea area;
    std::vector<UgrRoomResult> rooms;  ///< kUgrRoomSizes' order.
};

/// What the table uses of a file: its luminous area (the EULUMDAT fields 16-21 read as DIALux
/// and Relux read them, else the file's opening). Throws InputError naming the file when it has
/// none (a point source has no luminance).
UgrLuminousArea ugrLuminousArea(const PhotometricData& data);

/// The table of `data`. Throws InputError naming the file when it has no luminous area, no
/// flux, or an option is outside its range.
UgrTable computeUgrTable(const PhotometricData& data, const UgrTableOptions& options = {});

}  // namespace candela
