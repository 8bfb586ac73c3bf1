// environment `uniform-faces`: cube-map CDFs, 1/6 of the samples per face (Fig. 2's baseline).
#include "environment_shading.glsl"

void envFaceShares(Surface s, int ns, out float mu[6]) {
    for (int f = 0; f < 6; ++f) mu[f] = 1.0 / 6.0;
}

#include "environment_faces.glsl"
#include "environment_main.glsl"
