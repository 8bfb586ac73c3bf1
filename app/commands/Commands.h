#pragma once
// The `candela` subcommands. Each returns the process exit code; errors go to stderr with the
// file and the problem, never a crash.

#include <string>
#include <vector>

#include "app/commands/Cli.h"

namespace candela {

struct CalcPlane;
struct Scene;
struct GridResult;
struct GridSpec;
struct LightChoice;

int cmdRender(const Args& args);
int cmdProbe(const Args& args);
int cmdInfo(const Args& args);
int cmdEdit(const Args& args);
int cmdConvert(const Args& args);
int cmdBench(const Args& args);
int cmdGrid(const Args& args);
int cmdSurfaces(const Args& args);
int cmdLayout(const Args& args);
int cmdGlare(const Args& args);
/// `glare --table FILE`: the standard UGR table of a photometric file (calculation/UgrTable.h).
int cmdGlareTable(const Args& args);
/// The help of `glare --table`'s --spacing-ratio, which `glare --help` lists too.
extern const char* const kSpacingRatioHelp;
int cmdReport(const Args& args);
int cmdPolar(const Args& args);
int cmdValidate(const Args& args);

/// The options `grid`, `surfaces` and `report` share (how illuminance is evaluated): --light
/// total|direct, --no-shadows (into `light`, which applyLightChoice turns into `how` once the
/// scene is loaded), --spp N, --technique T, --env-technique T, --patches N, --indirect-method M;
/// --indirect and --visibility ask for what is already the default.
void declareEvaluation(CommandLine& cli, GridSpec& how, LightChoice& light);

/// The scene from its camera, offscreen (OSMesa): `spp` samples per pixel, lit as `how`
/// computes the numbers beside it (its interreflected light, when it has it, from as many
/// patches), tone-mapped as `render` draws it; 8-bit RGB rows top to bottom. `note` says how,
/// in a client's words.
std::vector<unsigned char> renderSceneView(const Scene& scene, const GridSpec& how, int width,
                                           int height, int spp, std::string& note);

/// Throws, as renderSceneView would, when a view of width x height pixels cannot be made
/// (allocates its images offscreen and frees them): a command checks its view's size before
/// its calculation.
void checkSceneViewSize(int width, int height);

/// `grid --csv`: x,y,z,E_lx,E_stderr_lx (_W_m2 for a radiometric scene) through a temporary file
/// and a rename (util/FileOutput.h); throws InputError naming the file.
void writeGridCsv(const std::string& path, const GridResult& result);

}  // namespace candela
