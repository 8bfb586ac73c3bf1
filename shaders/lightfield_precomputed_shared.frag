// lightfield `precomputed-shared`: the paper's own Fig. 11 baseline. One set of light samples,
// drawn from the global CDFs (lightfield_global_cdf.glsl) once per pass, shared by every pixel:
// all pixels seed their random numbers alike, so each pass is one set of K samples (images by
// the same systematic offset, points by the same rotation of the Halton sequence) and N samples
// over passes are one shared set of N. Each pixel's estimate is distributed as
// precomputed-global's; the difference is that its error is the same set's everywhere (structured
// rather than noise).
#include "lightfield_shading.glsl"
#include "lightfield_global_cdf.glsl"
#include "lightfield_balanced.glsl"
#include "lightfield_pass.glsl"

void main() { lfShadePass(uvec2(0u)); }
