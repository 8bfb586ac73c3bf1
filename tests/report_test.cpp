// The report's parts that are data, not drawing (report/Report.h): the luminaire schedule groups
// identical luminaires and takes each one's figures from its file; the false-colour legend strip
// holds the scale's colours; a scene with nothing to report still makes a PDF. The pages
// themselves are read back by poppler in tests/cli/report.sh.

#include "report/Report.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "TestUtil.h"
#include "formats/Photometry.h"
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

// The power density of an L-shaped room worked by hand: its floor is a 4 x 2 m rectangle and a
// 2 x 1 m one beside it, 10 m2; two downlights of 75 W stand in it (the third hangs in the notch
// of the L, outside it), 150 W in all: 15 W/m2, and at the task area's Em of 400 lx,
// 15 / (400 / 100) = 3.75 W/m2 per 100 lx. A source that states no input power leaves both
// unknown; a scene without a room entry is measured on its overall size.
TEST(Report, PowerDensityIsInputPowerOverFloorArea) {
    TempDir tmp;
    const std::string ies =
        test::sourceDir() + "/resources/luminaires/photometric/halo-recessed-downlight.ies";
    auto downlight = [&](double x, double z) {
        return R"({"type": "photometric", "file": ")" + ies + R"(", "position": [)" +
               std::to_string(x) + ", 2.5, " + std::to_string(z) + "]}";
    };
    const std::string room =
        R"({"room": {"name": "Office L", "floor": [[0, 0], [4, 0], [4, 2], [2, 2], [2, 3], [0, 3]],
                     "height": 3}})";
    const std::string task =
        R"("task_areas": [{"name": "Work", "plane": "y=0.75", "extent": [0, 0, 4, 2]}])";
    std::ofstream(tmp.file("l.json")) << R"({"geometry": [)" + room + R"(], "luminaires": [)" +
                                             downlight(1, 1) + ", " + downlight(3, 1) + ", " +
                                             downlight(3, 2.5) + "], " + task + "}";
    Scene scene = loadScene(tmp.file("l.json"));
    SurfaceReport surfaces;
    SurfaceResult work;
    work.name = "Work";
    work.role = "task area";
    work.summary.count = 50;
    work.summary.eAvg = 400.0;
    surfaces.surfaces.push_back(work);
    std::vector<RoomSummary> rooms = roomSummaries(scene, surfaces);
    ASSERT_EQ(rooms.size(), 1u);
    const RoomSummary& r = rooms[0];
    EXPECT_EQ(r.name, "Office L");
    ASSERT_TRUE(r.room.has_value());
    EXPECT_NEAR(r.area, 10.0, 1e-12);
    EXPECT_EQ(r.luminaires, (std::vector<size_t>{0, 1}));
    EXPECT_EQ(r.taskAreas, (std::vector<size_t>{0}));
    EXPECT_EQ(r.powerUnstated, 0);
    EXPECT_NEAR(r.power, 150.0, 1e-12);
    EXPECT_NEAR(r.powerDensity(), 15.0, 1e-12);
    EXPECT_EQ(r.reference, "Work");
    EXPECT_NEAR(r.powerDensityPer100Lux(), 3.75, 1e-12);

    // A panel that states no input power (a Lambertian source has no file to state one).
    std::ofstream(tmp.file("l.json"))
        << R"({"geometry": [)" + room + R"(], "luminaires": [)" + downlight(1, 1) +
               R"(, {"type": "lambertian-rect", "size": [0.5, 0.5], "luminance": [1000, 1000, 1000],
                     "position": [3, 2.9, 1]}], )" +
               task + "}";
    scene = loadScene(tmp.file("l.json"));
    const RoomSummary unstated = roomSummaries(scene, surfaces).at(0);
    EXPECT_EQ(unstated.luminaires.size(), 2u);
    EXPECT_EQ(unstated.powerUnstated, 1);
    EXPECT_LT(unstated.powerDensity(), 0.0);
    EXPECT_LT(unstated.powerDensityPer100Lux(), 0.0);

    // The office has no room entry: its overall size, 6 x 4 m, and its six 75 W downlights.
    Scene office = loadScene(test::sourceDir() + "/resources/scenes/office.json");
    rooms = roomSummaries(office, SurfaceReport{});
    ASSERT_EQ(rooms.size(), 1u);
    EXPECT_FALSE(rooms[0].room.has_value());
    EXPECT_NEAR(rooms[0].area, 24.0, 1e-4);  // float bounds of the planes
    EXPECT_EQ(rooms[0].luminaires.size(), 6u);
    EXPECT_NEAR(rooms[0].powerDensity(), 450.0 / 24.0, 1e-3);
    EXPECT_LT(rooms[0].powerDensityPer100Lux(), 0.0);  // no Em given
}

// The classroom's room as its entry writes it: 10 x 8 m, 80 m2, 3 m high, its reflectances, three
// windows and a door, its three pieces of furniture and the layout's 15 luminaires 2.4 m above
// the floor.
TEST(Report, ClassroomRoomSummary) {
    Scene scene = loadScene(test::sourceDir() + "/resources/scenes/classroom-project.json");
    std::vector<RoomSummary> rooms = roomSummaries(scene, SurfaceReport{});
    ASSERT_EQ(rooms.size(), 1u);
    const RoomSummary& r = rooms[0];
    ASSERT_TRUE(r.room.has_value());
    EXPECT_EQ(r.lo, glm::dvec2(-5, -4));
    EXPECT_EQ(r.hi, glm::dvec2(5, 4));
    EXPECT_NEAR(r.area, 80.0, 1e-12);
    EXPECT_EQ(r.height, 3.0);
    EXPECT_EQ(r.room->floorReflectance, glm::dvec3(0.2));
    EXPECT_EQ(r.room->wallReflectances, std::vector<glm::dvec3>(4, glm::dvec3(0.5)));
    EXPECT_EQ(r.room->ceilingReflectance, glm::dvec3(0.7));
    ASSERT_EQ(r.room->openings.size(), 4u);
    EXPECT_EQ(r.room->openings[3].type, "door");
    EXPECT_EQ(r.room->openings[3].wall, 1u);  // the file's wall 2
    EXPECT_EQ(r.furniture.size(), 3u);
    ASSERT_EQ(r.luminaires.size(), 15u);
    for (size_t k : r.luminaires)
        EXPECT_NEAR(scene.luminaires[k]->pose.position.y - r.floorY, 2.4, 1e-9);
    // The desk's footprint, 1.6 x 0.8 m about (0, -3).
    std::optional<FurnitureSpec> desk = furnitureSpec(scene, 1);
    ASSERT_TRUE(desk.has_value());
    EXPECT_EQ(desk->name, "Teacher's desk");
    std::vector<glm::dvec2> footprint = desk->footprint();
    ASSERT_EQ(footprint.size(), 4u);
    EXPECT_NEAR(footprint[0].x, -0.8, 1e-12);
    EXPECT_NEAR(footprint[0].y, -3.4, 1e-12);
    EXPECT_NEAR(footprint[2].x, 0.8, 1e-12);
    EXPECT_NEAR(footprint[2].y, -2.6, 1e-12);
}

// A datasheet's light output ratio against the files' own numbers: the EULUMDAT file's lamp flux
// (field 26c) and its stated LORL (field 23), read here from its lines; the IES file's 900 lm
// lamp; none for absolute photometry (an IES file with -1 lumens per lamp).
TEST(Report, DatasheetLightOutputRatioFromTheFilesNumbers) {
    const std::string ldt =
        test::sourceDir() + "/resources/luminaires/photometric/prolicht-e30.ldt";
    std::ifstream in(ldt);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(line);
    }
    ASSERT_GT(lines.size(), 29u);
    const double lorl = std::stod(lines[22]) / 100.0, lampFlux = std::stod(lines[28]);
    DatasheetFigures f = datasheetFigures(loadPhotometry(ldt));
    EXPECT_EQ(f.lampFlux, lampFlux);
    EXPECT_EQ(f.statedLightOutputRatio, lorl);
    EXPECT_GT(f.flux, 0.0);
    EXPECT_NEAR(f.lightOutputRatio, f.flux / lampFlux, 1e-12);

    const std::string ies =
        test::sourceDir() + "/resources/luminaires/photometric/halo-recessed-downlight.ies";
    f = datasheetFigures(loadPhotometry(ies));
    EXPECT_EQ(f.lampFlux, 900.0);       // 1 lamp of 900 lm, the TILT line's next line
    EXPECT_NEAR(f.flux, 796.54, 0.01);  // `candela info`'s flux of the table
    EXPECT_NEAR(f.lightOutputRatio, 796.54 / 900.0, 1e-4);
    EXPECT_LT(f.statedLightOutputRatio, 0.0);  // IES has no field for it

    f = datasheetFigures(loadPhotometry(test::dataDir() + "/photometric/spot.ies"));
    EXPECT_LT(f.lightOutputRatio, 0.0);
    EXPECT_EQ(f.lampFlux, 0.0);
}
