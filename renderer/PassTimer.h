#pragma once
// Times a pass for the frame statistics (FrameStats), whichever object runs it.

#include <functional>
#include <string>

#include "renderer/FrameStats.h"

namespace candela {

/// True on Mesa's software rasterizer, whose GL_TIME_ELAPSED queries end before its rasterizer
/// threads have run the pass's fragment shaders whenever those sample textures (measured: the
/// restricted-cdf pass at 960x540 reads 26 ms from its query and takes 1.6 s to glFinish).
bool softwareRasterizer();

/// Runs fn and records it as pass `name` in stats: its time from a GPU timer query, or on a
/// software rasterizer the wall time from a glFinish before it to one after it (the CPU is the
/// GPU there).
void timed(FrameStats& stats, const std::string& name, const std::function<void()>& fn);

}  // namespace candela
