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
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (parseEvaluationFlag(args, i, how, light))
            continue;
        else if (a == "--out")
            out = outputValue(args, i);
        else if (a == "--title")
            title = flagValue(args, i);
        else if (a == "--view-size")
            parseSize(flagValue(args, i), viewWidth, viewHeight);
        else if (a == "--view-spp")
            viewSpp = parseInt(a, flagValue(args, i), 1, 65536);
        else if (a == "--no-view")
            view = false;
        else if (!a.empty() && a[0] == '-')
            throw UsageError("report: unknown option " + a);
        else if (scenePath.empty())
            scenePath = a;
        else
            throw UsageError("report: unexpected argument " + a);
    }
    if (scenePath.empty() || out.empty())
        throw UsageError(std::string("usage: candela report scene.json --out report.pdf "
                                     "[--title T] ") +
                         kEvaluationUsage + " [--view-size WxH] [--view-spp N] [--no-view]");
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
                          title.empty() ? std::filesystem::path(scenePath).stem().string() : title,
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
        in.viewNote = "--no-view";
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
