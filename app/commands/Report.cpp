// `candela report`: the PDF report of a scene (report/Report.h): its calculation surfaces and
// points as `candela surfaces` computes them, the UGR at its observers as `candela glare` does, a
// luminaire schedule with polar diagrams and a view rendered from its camera.
#include "report/Report.h"

#include <cstdio>
#include <ctime>
#include <filesystem>

#include "app/commands/Commands.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

int cmdReport(const Args& args) {
    std::string scenePath, out, title;
    GridSpec how;
    LightChoice light;
    int viewWidth = 960, viewHeight = 540, viewSpp = 64;
    bool view = true;
    CommandLine cli("report");
    cli.argument("scene.json", scenePath, "the scene file");
    cli.output("--out", out, "F.pdf", "the report to write (required)");
    cli.text("--title", title, "TEXT",
             "the report's title (default: the project's name, else the scene file's name)");
    cli.option("--view-size", "WxH", "the rendered view's size, pixels (960x540)",
               [&](const std::string& v) { parseSize(v, viewWidth, viewHeight, "--view-size"); });
    cli.integer("--view-spp", viewSpp, 1, 65536, "N", "samples per pixel of the view (64)");
    cli.flag("--no-view", view, "leave the rendered view out", false);
    declareEvaluation(cli, how, light);
    if (!cli.parse(args)) return 0;
    if (out.empty())
        throw CommandUsageError("missing --out F.pdf (the report to write)", cli.shortHelp());
    if (std::filesystem::path(out).extension() != ".pdf")
        throw InputError(out + ": the report is a PDF: name it NAME.pdf");
    Scene scene = loadScene(scenePath);
    applyLightChoice(scene, light, how);
    ProtectedInputs inputs(scene.inputFiles());
    checkNotAnInput(out, "--out");
    auto status = [](const std::string& s) { std::fprintf(stderr, "report: %s\n", s.c_str()); };
    if (view) {
        // A view that cannot be made at this size is refused now, not after the calculation.
        try {
            checkSceneViewSize(viewWidth, viewHeight);
        } catch (const std::exception& e) {
            throw InputError("--view-size " + std::to_string(viewWidth) + "x" +
                             std::to_string(viewHeight) + ": " + e.what() +
                             " (a smaller --view-size, or --no-view)");
        }
    }

    ReportInput in;
    computeReportContents(in, scene,
                          !title.empty() ? title
                          : !scene.project.name.empty()
                              ? scene.project.name
                              : std::filesystem::path(scenePath).stem().string(),
                          how, status);
    if (view) {
        try {
            status("rendering the view");
            in.view = renderSceneView(scene, how, viewWidth, viewHeight, viewSpp, in.viewNote);
            in.viewWidth = viewWidth;
            in.viewHeight = viewHeight;
        } catch (const std::exception& e) {
            in.view.clear();
            in.viewNote = e.what();
            std::fprintf(stderr, "report: warning: the view was not rendered: %s\n", e.what());
        }
    } else {
        in.viewNote = "left out at the designer's request";
    }
    std::string pdf = reportPdf(in);
    writeFileAtomically(out, pdf, "cannot write the report");
    int failed = 0;
    for (const SurfaceResult& s : in.surfaces.surfaces) failed += !s.passes;
    for (const PointResult& p : in.surfaces.points) failed += !p.passes;
    if (in.glare)
        for (const GlareResult& g : in.glare->observers) failed += !g.passes;
    std::printf(
        "wrote %s (%zu bytes): %zu surfaces, %zu points, %zu observers, %d requirement%s "
        "not met\n",
        out.c_str(), pdf.size(), in.surfaces.surfaces.size(), in.surfaces.points.size(),
        in.glare ? in.glare->observers.size() : size_t(0), failed, failed == 1 ? "" : "s");
    return 0;
}

}  // namespace candela
