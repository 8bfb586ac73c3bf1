// photometric `reference`: Monte Carlo, progressive: opening points (Prost Eq. 6.3), cosine
// directions and directions in proportion to the table's intensity, combined by the balance
// heuristic (PhotometricEstimators.cpp, photometricReference).
#include "photometric_shading.glsl"

/// One sample of the reference (PhotometricEstimators.cpp): the BRDF times f / (c.x pdf_area +
/// c.y pdf_cosine + c.z pdf_table) for the direction d toward opening point q at distance r,
/// multiplied through by cos_L so that it stays finite in the opening's plane; 0 outside the
/// opening or in shadow.
vec3 phMisTerm(Surface s, vec3 n, vec3 q, vec3 d, float r, float rect, vec3 c) {
    if (!phInside(q.xy)) return vec3(0.0);
    float cosP = dot(n, d), cosL = abs(d.z);
    if (!(cosP > 0.0) || !(ph.position.w > 0.0)) return vec3(0.0);
    float pdfTable = c.z > 0.0 ? phTablePdf(-d) : 0.0;
    float w = phIntensity(-d) * cosP / ph.position.w /
              (c.x * r * r / rect + c.y * cosL * cosP / kPi + c.z * cosL * pdfTable);
    if (!(w > 0.0) || isinf(w)) return vec3(0.0);
    return brdf(s, normalize(phFromLocal(d))) * w * visibleTo(s, q);
}

vec3 shadeTechnique(Surface s, vec3 p, vec3 n, int spp, inout uint rng) {
    float degenerateE;
    if (phDegenerate(p, n, degenerateE)) return s.albedo / kPi * degenerateE;
    vec3 result = vec3(0.0);
    // One of three strategies per sample, balance heuristic (PhotometricEstimators.cpp): a
    // point uniform on the bounding rectangle; a direction cosine-distributed about the normal
    // (probability the form factor, clamped to [0.05, 0.5], of three quarters); a direction in
    // proportion to the table's intensity (a quarter, where the table has any).
    vec2 lo, hi;
    phBounds(lo, hi);
    float rect = (hi.x - lo.x) * (hi.y - lo.y);
    PhPolygon seen = phClip(phOpening(p), n);
    float cTable = ph.samples.z != 0 ? 0.25 : 0.0;
    float cCosine = (1.0 - cTable) * clamp(seen.count >= 3 ? phProjectedSolidAngle(seen, n) / kPi : 0.0, 0.05, 0.5);
    vec3 c = vec3(1.0 - cTable - cCosine, cCosine, cTable);
    float sgn = n.z >= 0.0 ? 1.0 : -1.0, fa = -1.0 / (sgn + n.z), fb = n.x * n.y * fa;
    vec3 t = vec3(1.0 + sgn * n.x * n.x * fa, sgn * fb, -sgn * n.x), bt = vec3(fb, sgn + n.y * n.y * fa, -n.y);
    for (int k = 0; k < spp; ++k) {
        // Stratified over the pass's samples, as the C++ twin.
        float pick = min((float(k) + rand01(rng)) / float(spp), 0.99999994), u1 = rand01(rng), u2 = rand01(rng);
        if (pick < c.x) {
            vec3 q = vec3(lo + vec2(u1, u2) * (hi - lo), 0.0);
            vec3 v = q - p;
            float r = length(v);
            if (r > 0.0) result += phMisTerm(s, n, q, v / r, r, rect, c);
        } else {
            vec3 d;
            if (pick < c.x + c.y) {
                float rad = sqrt(u1), phi = 2.0 * kPi * u2;
                d = rad * cos(phi) * t + rad * sin(phi) * bt + sqrt(max(0.0, 1.0 - u1)) * n;
            } else {
                // The table's direction leaves the opening toward the receiver: look back.
                d = -phTableSample(min((pick - c.x - c.y) / c.z, 0.99999994), vec2(u1, u2));
            }
            if (abs(d.z) > 0.0) {
                float along = -p.z / d.z;
                vec3 hit = p + along * d;
                if (along > 0.0 && all(greaterThanEqual(hit.xy, lo)) && all(lessThanEqual(hit.xy, hi)))
                    result += phMisTerm(s, n, vec3(hit.xy, 0.0), d, along, rect, c);
            }
        }
    }
    return result / float(spp);
}

#include "photometric_main.glsl"
