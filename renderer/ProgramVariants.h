#pragma once
// Every GPU program the renderer asks the shader library for, defined once: the passes and the
// frame plan take their program keys from here, and allProgramVariants() lists every variant they
// can produce (each registry technique's shader with and without shadows and gloss, and the fixed
// passes), so a check can validate all of them without rendering a scene that needs each one
// (tests/shader_variants_test.cpp runs glslangValidator over them).

#include <filesystem>
#include <vector>

#include "renderer/ShaderLibrary.h"

namespace candela {

struct TechniqueInfo;

namespace programs {

ProgramKey gbuffer();
ProgramKey indirect();
ProgramKey resolve();
ProgramKey accumulate();  ///< adds one scaled image into another (ResolvePass)
ProgramKey tonemap();
ProgramKey shadowDepth();

/// The environment's table-building compute passes (environment_cdf.comp), in the order they run.
enum class EnvironmentTables { Cube, Energy, Rows, Columns, Samples };
ProgramKey environmentTables(EnvironmentTables pass);

/// A technique's shading program: SHADOW_MAPS or SHADOWS (shadow rays) where an occluder can
/// block its source, GLOSSY where a glossy material is in view.
ProgramKey shading(const TechniqueInfo& technique, bool shadowMaps, bool shadowRays, bool glossy);

}  // namespace programs

/// Every program variant: each registry technique's shading programs in each shadow and gloss
/// combination its technique can be planned with, then the fixed passes' programs.
std::vector<ProgramKey> allProgramVariants();

/// One preprocessed stage of a program, as the driver is given it (ShaderLibrary::source).
struct ShaderStageSource {
    std::string label;  ///< the program's label and the stage, "photometric_mrp.frag[GLOSSY]"
    std::string stage;  ///< "vert", "frag" or "comp"
    std::string text;
    std::vector<std::string> files;  ///< the file of each #line source-string number
};

/// The preprocessed stages of every variant of allProgramVariants() (no GL context needed).
std::vector<ShaderStageSource> allShaderStages(const ShaderLibrary& shaders);

}  // namespace candela
