// The table of commands (app/commands/CommandTable.h).
#include "app/commands/CommandTable.h"

#include <cstdio>

namespace candela {

namespace {

const CommandInfo kCommands[] = {
    {"edit", "open the editor on a scene (without a display: its screenshots, offscreen)",
     "edit [scene.json] [options]\n"
     "  Opens the interactive editor. Without a display it renders the scene's view offscreen\n"
     "  (OSMesa, 960x540, up to 64 samples per pixel) and writes the screenshots (PNG, EXR,\n"
     "  JSON) into the screenshot folder.\n",
     "candela edit resources/scenes/editor-room.json", &cmdEdit},
    {"info", "describe a scene, light field, glTF file, photometry file or GLDF container",
     "info FILE [--strict]\n"
     "  What the file holds: a scene's meshes, luminaires and units; a light field's basis,\n"
     "  images, flux and precomputation time; photometry's flux from the table, lamps x LOR and\n"
     "  warnings for what was assumed to read it; a GLDF container's product, variants, rated\n"
     "  flux and power; L3D geometry's parts and luminous openings.\n",
     "candela info resources/luminaires/photometric/halo-recessed-downlight.ies", &cmdInfo},
    {"render", "render a scene's view, in false colour, or a comparison sheet of techniques",
     "render scene.json --out F.png|F.exr [options]\n"
     "  The scene's view from its camera, with its interreflected light: PNG tone-mapped, EXR\n"
     "  linear (W/(m2 sr) or cd/m2; with --false-colour, lx).\n"
     "render scene.json --sheet DIR --pane TECHNIQUES[:SPP] [--pane ...] [options]\n"
     "  A comparison sheet: 1-4 panes (technique lists such as\n"
     "  photometric=scattered,lightfield=precomputed-global) against a progressive reference;\n"
     "  sheet-NNN.png/.exr/.json in DIR.\n",
     "candela render resources/scenes/office.json --out office.png --size 960x540", &cmdRender},
    {"probe", "the irradiance at points (CSV), by any technique, on the CPU or the GPU",
     "probe scene.json --points pts.csv [options]\n"
     "probe scene.json --pixel X,Y [--size WxH] [options]\n"
     "  pts.csv: x,y,z,nx,ny,nz per line (metres, a unit normal); --pixel: the surface the\n"
     "  scene's camera sees through that pixel. Prints CSV x,y,z,nx,ny,nz,E,... with E the\n"
     "  irradiance (lx, or W/m2 for a radiometric scene; stderr names the unit). Direct light\n"
     "  without shadows unless --visibility and --indirect add them.\n",
     "candela probe resources/scenes/office.json --points tests/data/photometric/far_points.csv",
     &cmdProbe},
    {"grid", "illuminance on a calculation grid: Emin, Eavg, Emax, U0",
     "grid scene.json --plane y=0.8 [options]\n"
     "  Illuminance (lx) at the points of a grid on the plane, and Emin, Eavg, Emax and U0 of\n"
     "  the direct, interreflected and total light. By default shadows and interreflected light\n"
     "  wherever the scene calls for them; --light direct and --no-shadows leave them out, and\n"
     "  the output says so.\n",
     "candela grid resources/scenes/office.json --plane y=0.8 --spacing 0.5", &cmdGrid},
    {"surfaces", "EN 12464-1 task areas, surroundings and backgrounds against requirements",
     "surfaces scene.json [options]\n"
     "  Em, U0, Emin, Emax (lx) of the scene's task areas, their immediate surroundings and\n"
     "  backgrounds against their requirements, and planar and cylindrical illuminance at its\n"
     "  calculation points.\n",
     "candela surfaces resources/scenes/classroom.json", &cmdSurfaces},
    {"layout", "the count and arrangement of a luminaire that meets a task area's target",
     "layout scene.json --luminaire FILE --height M [--em LX] [--u0 U] [--out F.json]\n"
     "  The lumen method's first guess, then each regular arrangement computed as `surfaces`\n"
     "  computes it (direct light with shadows and interreflected light) until the fewest\n"
     "  luminaires that meet the target maintained Em (lx) and U0 are found; --out writes the\n"
     "  scene with them.\n",
     "candela layout resources/scenes/classroom-project.json --luminaire "
     "resources/luminaires/photometric/prolicht-e30.ldt --height 2.4 --out classroom-laid-out.json",
     &cmdLayout},
    {"glare", "the Unified Glare Rating at observers, or a luminaire's UGR table",
     "glare scene.json [--observer X,Y,Z --view X,Y,Z] [options]\n"
     "  UGR (CIE 117) at the scene's \"glare_observers\" or the one given (metres), the\n"
     "  background luminance (cd/m2) from the interreflected light.\n"
     "glare --table FILE.ldt|FILE.ies|FILE.xml|FILE.gldf [--spacing-ratio R] [--out F.csv]\n"
     "  The standard UGR table of a luminaire (CIE 190 tabular method: 19 rooms x 5\n"
     "  reflectances, crosswise and endwise), the luminaires R x the mounting height apart.\n",
     "candela glare resources/scenes/office.json", &cmdGlare},
    {"report", "a PDF report of a scene for a client",
     "report scene.json --out report.pdf [options]\n"
     "  Luminaire schedule, polar diagrams, surfaces with false colour and values, UGR and a\n"
     "  view rendered from the scene's camera.\n",
     "candela report resources/scenes/office.json --out office.pdf", &cmdReport},
    {"polar", "a photometric file's polar candela diagram and its table",
     "polar FILE.ies|FILE.ldt|FILE.xml [--out polar.png] [options]\n"
     "  The C0-C180 and C90-C270 planes' luminous intensity (cd): their table on stdout, and\n"
     "  their polar diagram as a PNG.\n",
     "candela polar resources/luminaires/photometric/halo-recessed-downlight.ies --out polar.png",
     &cmdPolar},
    {"convert", "a light field from a TM-25 ray file or a headlight, or photometry as TM-33",
     "convert RAYS.TM25RAY --out NAME.lf.json [ray-file options]\n"
     "  A light-field luminaire from an IES TM-25 ray file.\n"
     "convert --procedural bike-headlight|car-headlight --out NAME.lf.json [--rays N]\n"
     "  A simulated headlight as a light field.\n"
     "convert FILE.ies|FILE.ldt --out NAME.xml\n"
     "  The photometry as IES TM-33-18 XML.\n",
     "candela convert resources/luminaires/photometric/halo-recessed-downlight.ies --out halo.xml",
     &cmdConvert},
    {"bench", "what accuracy costs in time: error against time for a family of techniques",
     "bench --lightfield F.lf.json [--out DIR] [options]\n"
     "  The light-field techniques' error against GPU time (CSV, images, plot, ratios).\n"
     "bench --environment sky|MAP.hdr|MAP.exr [--out DIR] [options]\n"
     "  Environment techniques: error against samples and time, table rebuilds, stability.\n"
     "bench --prost FILE|DIR... [--out DIR] [options]\n"
     "  Prost's evaluation of the photometric techniques (NMSE, bounds, bumps, GPU time).\n"
     "bench --shadows [SCENE.json] [--out DIR] [options]\n"
     "  Per-cell shadow maps against ray-traced shadows.\n"
     "bench --indirect [SCENE.json] [--out DIR] [options]\n"
     "  What interreflected light costs in time, and how it scales with the patches.\n"
     "bench --drag [SCENE.json] [--out DIR] [options]\n"
     "  How live the editor stays while a luminaire is dragged.\n"
     "bench --design [--out DIR] [options]\n"
     "  A designer's calculations (grid, surfaces, reports) on the shipped office and\n"
     "  classroom: time and accuracy.\n"
     "  Every bench writes into DIR whole or not at all; docs/performance.md holds results.\n",
     "candela bench --design --out bench-design", &cmdBench},
    {"validate", "the validation suite against closed forms (CIE 171:2006)",
     "validate [--case NAME]... [--list]\n"
     "validate --closed ROOM.json\n"
     "  The integrating cube and sphere, direct light and an obstruction against closed forms;\n"
     "  --closed checks a closed room's energy balance.\n",
     "candela validate --list", &cmdValidate},
};

}  // namespace

std::span<const CommandInfo> commands() {
    return kCommands;
}

const CommandInfo* findCommand(const std::string& name) {
    for (const CommandInfo& c : kCommands)
        if (name == c.name) return &c;
    return nullptr;
}

std::string commandList() {
    std::string out =
        "usage: candela COMMAND [options]    (candela help COMMAND: its options and an "
        "example)\n\n";
    char line[256];
    for (const CommandInfo& c : kCommands) {
        std::snprintf(line, sizeof line, "  %-9s %s\n", c.name, c.summary);
        out += line;
    }
    return out + "\n  --version  the version and the commit it was built from\n";
}

std::string commandHeading(const CommandInfo& c) {
    std::string out = std::string("candela ") + c.name + ": " + c.summary + "\n\nusage:\n";
    // Each form of the usage as "candela FORM".
    std::string usage = c.usage;
    size_t at = 0;
    while (at < usage.size()) {
        size_t end = usage.find('\n', at);
        std::string line = usage.substr(at, end - at);
        // A form, a form's continuation (aligned under it) or a description.
        bool form = line.rfind(c.name, 0) == 0;
        size_t first = line.find_first_not_of(' ');
        bool continued = first != std::string::npos && line[first] == '[';
        out += form ? "  candela " : continued ? "          " : "  ";
        out += line + "\n";
        at = end == std::string::npos ? usage.size() : end + 1;
    }
    return out;
}

}  // namespace candela
