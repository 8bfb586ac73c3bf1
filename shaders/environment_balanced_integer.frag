// environment `balanced-integer`: balanced with N_f rounded to whole samples: the baseline the
// fractional counts replace (biased, pops; the temporal-stability bench's baseline).
#include "environment_shading.glsl"

void envFaceShares(Surface s, int ns, out float mu[6]) {
    envBalance(s.n, mu);
    for (int f = 0; f < 6; ++f) mu[f] = round(mu[f] * float(ns)) / float(ns);
}

#include "environment_faces.glsl"
#include "environment_main.glsl"
