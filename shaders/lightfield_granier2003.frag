// lightfield `granier2003`: Granier et al. 2003, Eq. 14: one textured spot light per basis
// function at its node, C_m averaged over the support's footprint (deterministic), as
// luminaires/lightfield/LightFieldEstimators.cpp.
#include "lightfield_shading.glsl"

/// On S (onS) the footprints shrink to the receiver's point, and each mean to the pixel there:
/// the limit from beyond S, as the C++ twin.
vec3 shadeTechnique(Surface s, vec3 q, vec3 nl, bool onS, int K, vec2 shift, float offset) {
    vec3 sum = vec3(0.0);
    float phiIntegral = lf.geometry.y * lf.geometry.z;
    if (onS) q.z = lfDelta();
    for (int m = 0; m < lfImageCount(); ++m) {
        vec2 a, b;
        float scale = (q.z - lfDelta()) / q.z, mean;
        if (onS) {
            a = b = q.xy;
            mean = lfLum(m, q.xy);
        } else {
            if (!lfRestrictedBox(m, q, a, b)) continue;
            // Mean over the support's whole footprint on S (C_m is 0 where it leaves the image).
            float footprint = 9.0 * lf.geometry.y * lf.geometry.z * scale * scale;
            mean = lfBoxIntegral(m, a, b) / footprint;
        }
        if (!(mean > 0.0)) continue;
        vec2 node = lfNode(m);
        vec3 d = vec3(node - q.xy, -q.z);
        float dist = length(d);
        vec3 wl = d / dist;
        float cosR = dot(nl, wl), cosL = q.z / dist;
        if (cosR <= 0.0) continue;
        vec2 centre = 0.5 * (a + b);
        float model = lfPsi(m, node, centre) / 0.5625;  // Phi_m at its node is 0.75^2
        vec3 wi = normalize(wl.x * lf.axisX.xyz + wl.y * lf.axisY.xyz + wl.z * lf.axisZ.xyz);
        // The far-field correction W_m / U_m, blended in with the footprint's area (the C++ twin,
        // LightFieldEstimators.cpp, says why).
        vec2 farCentre = node + (q.xy - node) * (lfDelta() / q.z), half_ = 1.5 * lf.geometry.yz;
        float uniform_ = lfBoxIntegral(m, farCentre - half_, farCentre + half_) / 9.0;
        float weighted = lfGranierWeighted(m, farCentre), blend = scale * scale;
        float conserve = uniform_ > 0.0 && weighted >= 0.0 ? (1.0 - blend) + blend * weighted / uniform_ : 1.0;
        sum += conserve * phiIntegral * mean * model * cosR * cosL / (dist * dist) * lfColour(m, centre) * brdf(s, wi) *
               visibility(s, toWorld(vec3(node, 0.0))) * imageVisibility(s, m);
    }
    return sum;
}

#include "lightfield_main.glsl"
