// photometric `uniform-area`: points uniform on the opening's bounding rectangle, the textbook
// Monte Carlo of the area form (Prost Eq. 6.3 on its own; luminaires/photometric/PhotometricUniformArea.cpp).
#include "photometric_shading.glsl"

vec3 shadeTechnique(Surface s, vec3 p, vec3 n, int spp, inout uint rng) {
    float degenerateE;
    if (phDegenerate(p, n, degenerateE)) return s.albedo / kPi * degenerateE;  // a segment or a point
    vec2 lo, hi;
    phBounds(lo, hi);
    float rect = (hi.x - lo.x) * (hi.y - lo.y);
    vec3 result = vec3(0.0);
    for (int k = 0; k < spp; ++k) {
        vec3 q = vec3(lo + vec2(rand01(rng), rand01(rng)) * (hi - lo), 0.0);
        if (!phInside(q.xy)) continue;
        vec3 v = q - p;
        float r = length(v);
        if (!(r > 0.0)) continue;
        vec3 d = v / r;
        float cosP = dot(n, d);
        if (!(cosP > 0.0)) continue;
        // The radiance I / (A cos_L) times the geometry cos_L cos_p / r^2, over pdf 1 / S_rect.
        float w = phIntensity(-d) * cosP * rect / (ph.position.w * r * r);
        result += brdf(s, normalize(phFromLocal(d))) * w * visibleTo(s, q);
    }
    return result / float(spp);
}

#include "photometric_main.glsl"
