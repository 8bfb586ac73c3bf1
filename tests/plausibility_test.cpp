// Where a luminaire's own figures disagree (calculation/Plausibility.h): each rule fires on a file
// built to break it, with both numbers and the one Candela uses, stays silent inside its tolerance,
// and fires on the real files that break it (the gldf.net container's 800 lm light source beside
// its photometry's 6300 lm of lamps; a LM-63 example whose UGR reference is 42).
#include "calculation/Plausibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "formats/Gldf.h"
#include "formats/Photometry.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"

namespace candela {
namespace {

const std::string kData = CANDELA_TEST_DATA;
using gpu::kPi;

/// An isotropic point source of `flux` lm in IES form: `lamp` lumens (-1: absolute photometry)
/// and `watts` of input power. Constant intensity integrates to 4 pi I exactly.
PhotometricData isotropic(double flux, double lamp, double watts) {
    char text[400];
    double cd = flux / (4.0 * kPi);
    std::snprintf(
        text, sizeof text,
        "IESNA:LM-63-2002\n[TEST] isotropic\nTILT=NONE\n1 %.9g 1 3 1 1 2 0 0 0\n1 1 %.9g\n"
        "0 90 180\n0\n%.9g %.9g %.9g\n",
        lamp, watts, cd, cd, cd);
    return parseIes(text, "iso.ies");
}

std::string joined(const std::vector<std::string>& notes) {
    std::string out;
    for (const std::string& n : notes) out += n + "\n";
    return out;
}

bool has(const std::vector<std::string>& notes, const std::string& text) {
    return joined(notes).find(text) != std::string::npos;
}

TEST(Plausibility, ConsistentFiguresSayNothing) {
    // 1000 lm from 1000 lm of lamps at 10 W: LOR 100 %, 100 lm/W, a point (no UGR table).
    PhotometricData d = isotropic(1000.0, 1000.0, 10.0);
    ASSERT_NEAR(d.fluxFromTable(), 1000.0, 1e-6);
    EXPECT_TRUE(plausibilityNotes("iso.ies", d, nullptr).empty())
        << joined(plausibilityNotes("iso.ies", d, nullptr));
}

TEST(Plausibility, ALightOutputRatioAboveOneIsCalledOut) {
    PhotometricData d = isotropic(2000.0, 1000.0, 10.0);
    std::vector<std::string> notes = plausibilityNotes("iso.ies", d, nullptr);
    ASSERT_EQ(notes.size(), 1u) << joined(notes);
    EXPECT_TRUE(has(notes,
                    "iso.ies: the table's flux is 200.0 % of the rated lamp flux (2000 lm "
                    "of 1000 lm)"))
        << notes[0];
    EXPECT_TRUE(has(notes, "Candela uses the table's 2000 lm")) << notes[0];
    // 100.9 % is inside the table's rounding (kLorTolerance).
    EXPECT_TRUE(plausibilityNotes("iso.ies", isotropic(1009.0, 1000.0, 10.0), nullptr).empty());
}

TEST(Plausibility, AnEfficacyNoWhiteLightReachesIsCalledOut) {
    // Absolute photometry of 1000 lm at 2 W: 500 lm/W.
    std::vector<std::string> notes =
        plausibilityNotes("iso.ies", isotropic(1000.0, -1.0, 2.0), nullptr);
    ASSERT_EQ(notes.size(), 1u) << joined(notes);
    EXPECT_TRUE(has(notes, "the table's 1000 lm at the stated 2 W is 500.0 lm/W")) << notes[0];
    // 240 lm/W is below kMaxPlausibleEfficacy.
    EXPECT_TRUE(
        plausibilityNotes("iso.ies", isotropic(1000.0, -1.0, 1000.0 / 240.0), nullptr).empty());
}

TEST(Plausibility, ARatedFluxFarFromTheTableIsCalledOutBeyondFivePercent) {
    PhotometricData d = isotropic(1000.0, -1.0, 10.0);
    GldfLightEmitter fixed;
    fixed.fixed = true;
    fixed.ratedFlux = 1040.0;  // 4 %: inside kRatedFluxTolerance
    EXPECT_TRUE(plausibilityNotes("p.gldf:iso.ies", d, &fixed).empty());
    fixed.ratedFlux = 1060.0;  // 6 %
    std::vector<std::string> notes = plausibilityNotes("p.gldf:iso.ies", d, &fixed);
    ASSERT_EQ(notes.size(), 1u) << joined(notes);
    EXPECT_TRUE(has(notes,
                    "p.gldf:iso.ies: the product rates 1060 lm, but its intensity table "
                    "holds 1000 lm (+6.0 %); Candela uses the table's 1000 lm"))
        << notes[0];
    // The product: 7800 lm at 18 W against a table of 1600 lm: two lines, both numbers.
    PhotometricData small = isotropic(1600.0, -1.0, 0.0);
    fixed.ratedFlux = 7800.0;
    fixed.ratedPower = 18.0;
    notes = plausibilityNotes("p.gldf:iso.ies", small, &fixed);
    ASSERT_EQ(notes.size(), 2u) << joined(notes);
    EXPECT_TRUE(has(notes, "rates 7800 lm, but its intensity table holds 1600 lm")) << notes[0];
    EXPECT_TRUE(has(notes, "rates 7800 lm at 18 W, 433.3 lm/W")) << notes[1];
    EXPECT_TRUE(has(notes, "Candela uses the table's 1600 lm (88.9 lm/W)")) << notes[1];
}

TEST(Plausibility, AChangeableEmitterIsComparedWithTheLampsOfRelativePhotometry) {
    // 640 lm from 1000 lm of lamps (LOR 64 %): a light source rated 1000 lm agrees.
    PhotometricData d = isotropic(640.0, 1000.0, 10.0);
    GldfLightEmitter source;
    source.ratedFlux = 1000.0;
    EXPECT_TRUE(plausibilityNotes("p.gldf:iso.ies", d, &source).empty())
        << joined(plausibilityNotes("p.gldf:iso.ies", d, &source));
    source.ratedFlux = 800.0;
    std::vector<std::string> notes = plausibilityNotes("p.gldf:iso.ies", d, &source);
    ASSERT_EQ(notes.size(), 1u) << joined(notes);
    EXPECT_TRUE(has(notes,
                    "rates its light source at 800 lm, but the photometry was measured "
                    "with 1000 lm of lamps (-20.0 %)"))
        << notes[0];
}

TEST(Plausibility, TheGldfNetContainersLightSourceDisagreesWithItsPhotometry) {
    std::string path = kData + "/gldf/GldfWithFilesComplete.gldf";
    std::string bytes = readGldfBytes(path);
    GldfProduct product = parseGldf(bytes, path);
    GldfPhotometry p = gldfVariantPhotometry(bytes, product, product.variants.front());
    ASSERT_TRUE(p.emitter && !p.emitter->lights.empty());
    std::vector<std::string> notes =
        plausibilityNotes(p.data.path, p.data, &p.emitter->lights.front());
    EXPECT_TRUE(has(notes,
                    "GldfWithFilesComplete.gldf:ldc/photometry.ldt: the product rates its "
                    "light source at 800 lm, but the photometry was measured with 6300 lm "
                    "of lamps"))
        << joined(notes);
}

TEST(Plausibility, AUgrReferenceOutsideFiveToFortyIsCalledOut) {
    // The LM-63-2002 example's table gives 42.0 in the CIE 190 4H x 8H room (`candela info`;
    // the table itself is checked against CIE 190's published values in ugr_table_test.cpp).
    std::string path = kData + "/photometry/ies/lidrs/iesna2002_example_typec.ies";
    PhotometricData d = loadPhotometry(path);
    std::vector<std::string> notes = plausibilityNotes("iesna2002_example_typec.ies", d, nullptr);
    EXPECT_TRUE(has(notes,
                    "its UGR reference (CIE 190 table, room 4H x 8H, reflectances "
                    "70/50/20 %) is 42.0, outside the 5-40"))
        << joined(notes);
    EXPECT_FALSE(has(plausibilityNotes("iesna2002_example_typec.ies", d, nullptr, false), "UGR"));
}

}  // namespace
}  // namespace candela
