// environment `balanced`: cube-map CDFs, samples per face balanced per normal (Eq. 3-5).
#include "environment_shading.glsl"

void envFaceShares(Surface s, int ns, out float mu[6]) { envBalance(s.n, mu); }

#include "environment_faces.glsl"
#include "environment_main.glsl"
