// The report's parts that are data, not drawing (report/Report.h): the luminaire schedule groups
// identical luminaires and takes each one's figures from its file; the false-colour legend strip
// holds the scale's colours; a scene with nothing to report still makes a PDF. The pages
// themselves are read back by poppler in tests/cli/report.sh.

#include "report/Report.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "TestUtil.h"
#include "renderer/passes/TonemapPass.h"
#include "scene/Scene.h"
#include "scene/SceneIo.h"
#include "shaders/shared/FalseColour.h"
#include "tests/TempDir.h"

using namespace candela;
using candela::test::TempDir;

// The office's six downlights are one row: the IES file's manufacturer and luminaire name, its
// flux from the table (796.54 lm, `candela info`), its 75 W.
TEST(Report, ScheduleGroupsIdenticalLuminairesWithTheirFilesFigures) {
    Scene office = loadScene(test::sourceDir() + "/resources/scenes/office.json");
    std::vector<ScheduleRow> rows = luminaireSchedule(office);
    ASSERT_EQ(rows.size(), 1u);
    const ScheduleRow& r = rows[0];
    EXPECT_EQ(r.count, 6);
    EXPECT_EQ(r.names, "Downlight 1 .. Downlight 6");
    EXPECT_NE(r.manufacturer.find("Halo"), std::string::npos) << r.manufacturer;
    EXPECT_NEAR(r.flux, 796.54, 0.01);
    EXPECT_EQ(r.power, 75.0);
    EXPECT_EQ(r.maintenanceFactor, 1.0);

    // Dimming one makes it a row of its own; a maintenance factor of its own too.
    TempDir tmp;
    nlohmann::json doc = sceneToJson(office);
    doc["luminaires"][0]["scale"] = 0.5;
    doc["luminaires"][1]["maintenance_factor"] = 0.8;
    std::string base = test::sourceDir() + "/resources/scenes/";
    for (auto& l : doc["luminaires"]) l["file"] = base + l["file"].get<std::string>();
    std::ofstream(tmp.file("office.json")) << doc.dump();
    rows = luminaireSchedule(loadScene(tmp.file("office.json")));
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].count, 1);
    EXPECT_NEAR(rows[0].flux, 0.5 * 796.54, 0.01);
    EXPECT_EQ(rows[1].maintenanceFactor, 0.8);
    EXPECT_EQ(rows[2].count, 4);
}

// A GLDF pendant's two placements: the product's manufacturer and name, each emitter its row.
TEST(Report, ScheduleNamesTheGldfProduct) {
    TempDir tmp;
    std::ofstream(tmp.file("scene.json"))
        << R"({"luminaires": [{"type": "gldf", "file": ")" + test::dataDir() +
               R"(/gldf/PendantTwoEmitters.gldf", "position": [0, 3, 0]}]})";
    std::vector<ScheduleRow> rows = luminaireSchedule(loadScene(tmp.file("scene.json")));
    ASSERT_EQ(rows.size(), 2u);
    for (const ScheduleRow& r : rows) {
        EXPECT_EQ(r.kind, "GLDF");
        EXPECT_EQ(r.count, 1);
        EXPECT_FALSE(r.manufacturer.empty());
        EXPECT_FALSE(r.product.empty());
        EXPECT_GT(r.flux, 0.0);
    }
}

// The strip beside a false-colour picture: the picture unchanged on the left, the scale's colour
// in the bar's middle (t = 0.5 there: stop 4 of shaders/shared/FalseColour.h, within 10 of 255
// for the anti-aliased bar's pixel grid).
TEST(Report, FalseColourLegendStripHoldsTheScale) {
    const int w = 40, h = 240;
    std::vector<unsigned char> picture(size_t(w) * h * 3, 77);
    FalseColourLegend legend;
    legend.min = 0.f;
    legend.max = 500.f;
    int width = w;
    std::vector<unsigned char> out = withFalseColourLegend(picture, width, h, legend, "lx");
    ASSERT_GT(width, w);
    ASSERT_EQ(out.size(), size_t(width) * h * 3);
    for (int r = 0; r < h; r += 17)
        for (int c = 0; c < w; c += 7)
            ASSERT_EQ(out[(size_t(r) * width + c) * 3], 77) << r << " " << c;
    // The bar spans 8 %..92 % of the height, starting one font size (10 px here) right of the
    // picture and 12 px wide.
    double fontSize = 10.0, top = h * 0.08, bottom = h * 0.92;
    int column = w + int(fontSize) + 6, row = int((top + bottom) / 2);
    float t = float((bottom - (row + 0.5)) / (bottom - top));
    glm::vec3 want = gpu::falseColour(t) * 255.f;
    const unsigned char* p = &out[(size_t(row) * width + column) * 3];
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], want[k], 10.0) << k;
}

// Nothing to report still makes a PDF: no luminaire, surface, observer or view.
TEST(Report, AnEmptySceneStillMakesAPdf) {
    TempDir tmp;
    std::ofstream(tmp.file("empty.json")) << R"({"luminaires": []})";
    Scene scene = loadScene(tmp.file("empty.json"));
    ReportInput in;
    in.scene = &scene;
    in.title = "empty";
    in.date = "2026-11-26";
    in.evaluation = "none";
    in.surfaces.units = scene.units();
    in.glareNote = "no observers";
    in.viewNote = "--no-view";
    std::string pdf = reportPdf(in);
    EXPECT_EQ(pdf.rfind("%PDF-", 0), 0u);
    EXPECT_NE(pdf.find("%%EOF"), std::string::npos);
    EXPECT_GT(pdf.size(), 2000u);
}
