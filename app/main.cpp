// candela: the interactive lighting editor and its headless tools.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>

#include "app/commands/Commands.h"
#include "luminaires/Photometry.h"
#include "util/Activity.h"
#include "util/TextEncoding.h"

namespace {

const char* kUsage =
    "usage: candela <command> [options]\n"
    "  edit [scene.json]                 open the editor (no display: render the scene's\n"
    "                                    screenshots offscreen into ./candela-screenshots/)\n"
    "  render scene.json --out F.png|F.exr [--technique T] [--spp N] [--size WxH] [--stats]\n"
    "                                    [--indirect on|off] [--light "
    "total|direct|interreflected]\n"
    "                                    [--tonemap exponential|reinhard] [--exposure K]\n"
    "                                    [--false-colour [--legend MIN,MAX] [--log] [--isolux "
    "L,..|none]]\n"
    "  render scene.json --sheet DIR --pane TECHNIQUES[:SPP] [--pane ...] [--reference-spp N] "
    "[--error-maps]\n"
    "                                    comparison sheet: 1-4 panes (technique lists, e.g.\n"
    "                                    photometric=scattered,lightfield=precomputed-global) "
    "against a\n"
    "                                    progressive reference; sheet-NNN.png/.exr/.json in DIR\n"
    "  probe scene.json --points pts.csv [--technique T] [--spp N] [--visibility [embree|bvh]]\n"
    "                                    [--indirect] [--device cpu|gpu] [--seed S]\n"
    "                                    CSV x,y,z,nx,ny,nz,E,... with E the irradiance (lx, or\n"
    "                                    W/m2 for a radiometric scene; stderr names it)\n"
    "  info FILE                         describe a scene (.json), a glTF file, a light field\n"
    "                                    (.lf.json: basis, images, flux, precomputation time)\n"
    "                                    or photometry (.ies/.ldt/.xml TM-33: flux from the table, "
    "lamps x "
    "LOR,\n"
    "                                    warnings for what was assumed to read the file)\n"
    "                                    or a GLDF container (.gldf: product, variants, rated\n"
    "                                    flux and power, each variant's photometry)\n"
    "  --strict (info, render, probe, grid, surfaces, polar): refuse photometry files that need a "
    "leniency\n"
    "                                    (empty EULUMDAT fields, Latin-1 or UTF-16 text, mixed "
    "line\n"
    "                                    endings, ...) instead of loading them with a warning\n"
    "  convert RAYS.TM25RAY --out NAME.lf.json [--grid WxH] [--res N] [--delta D]\n"
    "                                    [--axis z|main] [--coverage C] [--raw-flux]\n"
    "  convert --procedural bike-headlight|car-headlight --out NAME.lf.json [--rays N]\n"
    "                                    light-field luminaire from an IES TM-25 ray file\n"
    "                                    (delta in metres) or a simulated headlight\n"
    "  convert FILE.ies|FILE.ldt --out NAME.xml\n"
    "                                    the photometry as IES TM-33-18 XML\n"
    "  bench --lightfield F.lf.json [--out DIR] [--spp 4,8,..] [--reference-spp N] [--size WxH]\n"
    "                                    [--fig11 SPP,SAMPLES]\n"
    "                                    error against GPU time of the light-field techniques\n"
    "                                    (CSV, images, plot, ratios; --fig11 63,63000: the "
    "paper's\n"
    "                                    Fig. 11, restricted-cdf against one shared sample set)\n"
    "  bench --environment sky|MAP.hdr [--out DIR] [--spp 4,8,..] [--reference-spp N] [--size WxH] "
    "[--repeats K]\n"
    "                                    environment techniques: error against samples and time,\n"
    "                                    table rebuild against shading, temporal stability\n"
    "  bench --design [--out DIR] [--reference-spp N]\n"
    "                                    a designer's calculations (grid, surfaces, reports on\n"
    "                                    the shipped office and classroom): time and accuracy\n"
    "  bench --prost FILE|DIR... [--out DIR] [--size N] [--reference-spp N]\n"
    "                                    Prost's evaluation of the photometric techniques (NMSE,\n"
    "                                    error bounds, bumps, GPU time; CSV, image sheets, plot)\n"
    "  grid scene.json --plane y=0.8 [--extent u0,v0,u1,v1] [--spacing 0.25] [--spp N] [--csv F]\n"
    "                                    [--light total|direct] [--no-shadows]\n"
    "                                    illuminance on a calculation grid; Emin, Eavg, Emax, U0\n"
    "                                    of the direct, interreflected and total light (by\n"
    "                                    default shadows and interreflected light wherever the\n"
    "                                    scene calls for them; --light direct, --no-shadows\n"
    "                                    leave them out, and the output says so)\n"
    "  surfaces scene.json [--spp N] [--light total|direct] [--no-shadows] [--csv F]\n"
    "                                    EN 12464-1 task areas, their immediate surroundings and\n"
    "                                    backgrounds (Em, U0, Emin, Emax against requirements) "
    "and\n"
    "                                    planar and cylindrical illuminance at points\n"
    "  glare scene.json [--observer X,Y,Z --view X,Y,Z [--limit UGR_L] [--background CD_M2]]\n"
    "                                    [--spp N] [--patches N] [--csv F]\n"
    "                                    Unified Glare Rating (CIE 117) at the scene's\n"
    "                                    \"glare_observers\" or the one given, background from\n"
    "                                    the interreflected light\n"
    "  glare --table FILE.ldt|FILE.ies|FILE.xml|FILE.gldf [--spacing 0.25] [--csv F]\n"
    "                                    the standard UGR table of a luminaire (CIE 190 tabular\n"
    "                                    method: 19 rooms x 5 reflectances, crosswise and\n"
    "                                    endwise; luminaires every 0.25 H as DIALux and Relux\n"
    "                                    print it, --spacing 1 for CIE 190's 1:1)\n"
    "  report scene.json --out report.pdf [--title T] [--spp N] [--light total|direct] "
    "[--no-shadows]\n"
    "                                    [--view-size WxH] [--view-spp N] [--no-view]\n"
    "                                    a PDF report: luminaire schedule, polar diagrams,\n"
    "                                    surfaces with false colour and values, UGR, a view\n"
    "  polar FILE.ies|FILE.ldt|FILE.xml [--out polar.png] [--step DEG]\n"
    "                                    polar candela diagram (C0-C180, C90-C270) and its table\n"
    "  validate [--case NAME]... [--list]\n"
    "                                    the validation suite: integrating cube and sphere,\n"
    "                                    direct light and an obstruction against closed forms\n";

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    std::string command = argv[1];
    candela::Args args(argv + 2, argv + argc);
    // --strict: every photometry file these commands load is read strictly (Photometry.h).
    for (const char* c : {"info", "render", "probe", "grid", "surfaces", "polar"}) {
        if (command != c) continue;
        auto strict = std::find(args.begin(), args.end(), "--strict");
        if (strict == args.end()) break;
        args.erase(strict);
        candela::setDefaultPhotometryOptions({.strict = true});
    }
    try {
        if (command == "render") return candela::cmdRender(args);
        if (command == "probe") return candela::cmdProbe(args);
        if (command == "info") return candela::cmdInfo(args);
        if (command == "edit") return candela::cmdEdit(args);
        if (command == "convert") return candela::cmdConvert(args);
        if (command == "bench") return candela::cmdBench(args);
        if (command == "grid") return candela::cmdGrid(args);
        if (command == "surfaces") return candela::cmdSurfaces(args);
        if (command == "glare") return candela::cmdGlare(args);
        if (command == "report") return candela::cmdReport(args);
        if (command == "polar") return candela::cmdPolar(args);
        if (command == "validate") return candela::cmdValidate(args);
        std::fprintf(stderr, "candela: unknown command \"%s\"\n%s", command.c_str(), kUsage);
        return 2;
    } catch (const std::bad_alloc&) {
        // Says what it was doing (util/Activity.h) instead of "std::bad_alloc".
        std::string what = candela::toValidUtf8(candela::takeFailedActivity());
        std::fprintf(stderr,
                     "candela %s: error: out of memory%s%s (docs/limits.md lists what Candela "
                     "bounds)\n",
                     command.c_str(), what.empty() ? "" : " while ", what.c_str());
        return 1;
    } catch (const std::exception& e) {
        // One line of valid UTF-8 whatever the message quotes (file names, fields in Latin-1).
        std::string message = candela::toValidUtf8(e.what());
        std::replace(message.begin(), message.end(), '\n', ' ');
        std::replace(message.begin(), message.end(), '\r', ' ');
        std::fprintf(stderr, "candela %s: error: %s\n", command.c_str(), message.c_str());
        return 1;
    }
}
