// environment `balanced-mis`: Eq. (6): N_s/2 balanced light samples and N_s/2 BRDF samples
// (cosine lobe, and the Phong lobe on glossy materials), balance heuristic.
#include "environment_shading.glsl"

/// Probability of choosing the diffuse lobe among the BRDF's lobes.
float diffuseShare(Surface s) {
#ifdef GLOSSY
    if ((s.flags & kMaterialGlossy) != 0) {
        float d = luminance(s.albedo), g = luminance(s.specular);
        return d + g > 0.0 ? d / (d + g) : 1.0;
    }
#endif
    return 1.0;
}

/// pdf_B: the cosine lobe (cos / pi) and the Phong lobe about the mirror direction
/// ((e + 1) / (2 pi) cos^e), mixed by diffuseShare.
float brdfPdf(Surface s, vec3 w, float share) {
    float pd = share * max(dot(s.n, w), 0.0) / kPi;
    if (share < 1.0) {
        vec3 r = reflect(-s.wo, s.n);
        pd += (1.0 - share) * (s.exponent + 1.0) / (2.0 * kPi) * pow(max(dot(r, w), 0.0), s.exponent);
    }
    return pd;
}

/// A direction about axis z with cos(theta) = u1^(1/(e+1)): pdf (e + 1) / (2 pi) cos^e(theta)
/// (e = 1 is the cosine lobe, pdf cos / pi).
vec3 lobeSample(vec3 z, float e, float u1, float u2) {
    float cosT = pow(u1, 1.0 / (e + 1.0));
    float sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
    float phi = 2.0 * kPi * u2;
    vec3 t = normalize(abs(z.x) > 0.5 ? cross(z, vec3(0.0, 1.0, 0.0)) : cross(z, vec3(1.0, 0.0, 0.0)));
    vec3 b = cross(z, t);
    return normalize(sinT * cos(phi) * t + sinT * sin(phi) * b + cosT * z);
}

vec3 shadeTechnique(Surface s, int ns, inout uint rng) {
    vec3 result = vec3(0.0);
    float mu[6];
    envBalance(s.n, mu);
    float share = diffuseShare(s);
    for (int f = 0; f < 6; ++f) {
        float nf = 0.5 * mu[f] * float(ns);
        if (!(nf > 0.0)) continue;
        int count = int(ceil(nf));
        int start = int(rand01(rng) * float(env.dims.w));
        for (int i = 0; i < count; ++i) {
            float beta = float(i + 1) <= nf ? 1.0 : nf - floor(nf);
            EnvironmentSampleGpu smp = poolSample(f, start, i);
            float pdf = smp.direction.w;
            if (!(pdf > 0.0)) continue;
            vec3 w = smp.direction.xyz;
            float denom = 0.5 * mu[f] * pdf + 0.5 * brdfPdf(s, w, share);
            result += beta * integrand(s, w, smp.radiance.rgb) / denom;
        }
    }
    float nb = 0.5 * float(ns);
    int countB = int(ceil(nb));
    vec3 mirror = reflect(-s.wo, s.n);
    for (int i = 0; i < countB; ++i) {
        float beta = float(i + 1) <= nb ? 1.0 : nb - floor(nb);
        float u0 = rand01(rng), u1 = rand01(rng), u2 = rand01(rng);
        vec3 w = u0 < share ? lobeSample(s.n, 1.0, u1, u2) : lobeSample(mirror, s.exponent, u1, u2);
        float denom = 0.5 * envPdf(mu, w) + 0.5 * brdfPdf(s, w, share);
        if (!(denom > 0.0)) continue;
        result += beta * integrand(s, w, envRadiance(w)) / denom;
    }
    result /= float(ns);
    return result;
}

#include "environment_main.glsl"
