// The Lambertian rectangle in GLSL: the same algorithms as luminaires/lambertian/LambertianRect.cpp (float).
// Needs shared/GpuTypes.h (LambertianRectGpu) and kPi from common.glsl.

/// Closed-form irradiance at p for the unit normal n: Lambert's polygon formula on the part of
/// the rectangle above the receiver's horizon (Baum, Rushmeier, Winget 1989). RGB, W/m2.
vec3 lambertRectIrradiance(LambertianRectGpu L, vec3 p, vec3 n) {
    vec3 centre = L.corner.xyz + 0.5 * (L.edgeX.xyz + L.edgeY.xyz);
    if (!(dot(p - centre, L.normal.xyz) > 0.0)) return vec3(0.0);
    vec3 toCentre = centre - p;
    float r = length(toCentre);
    if (max(L.edgeX.w, L.edgeY.w) < 0.01 * r) {
        // A rectangle under a hundredth of its distance: L A cos cos / r^2, within ~(size / r)^2
        // ~ 1e-4 of the truth, where the corners relative to p round to more than the rectangle
        // in float (a 1e-6 m one 2 m away gave 3800x its light; the 64-bit C++ twin is exact).
        vec3 w = toCentre / r;
        return L.radiance.rgb * (L.edgeX.w * L.edgeY.w * max(dot(n, w), 0.0) * max(-dot(L.normal.xyz, w), 0.0) / (r * r));
    }
    vec3 quad[4] = vec3[4](L.corner.xyz - p, L.corner.xyz + L.edgeX.xyz - p,
                           L.corner.xyz + L.edgeX.xyz + L.edgeY.xyz - p, L.corner.xyz + L.edgeY.xyz - p);
    // Sutherland-Hodgman clip to dot(n, v) >= 0: at most 5 vertices.
    vec3 poly[5];
    int count = 0;
    for (int i = 0; i < 4; ++i) {
        vec3 a = quad[i], b = quad[(i + 1) & 3];
        float da = dot(n, a), db = dot(n, b);
        if (da >= 0.0) poly[count++] = a;
        if ((da >= 0.0) != (db >= 0.0)) poly[count++] = a + (b - a) * (da / (da - db));
    }
    if (count < 3) return vec3(0.0);
    float sum = 0.0;
    for (int i = 0; i < count; ++i) {
        vec3 a = poly[i], b = poly[(i + 1) % count];
        vec3 c = cross(a, b);
        float lc = length(c);
        if (!(lc > 0.0)) continue;
        sum += atan(lc, dot(a, b)) * dot(n, c / lc);
    }
    return L.radiance.rgb * (0.5 * abs(sum));
}

/// The rectangle as a spherical rectangle seen from p (Urena, Fajardo, King 2013).
struct SphRect {
    vec3 x, y, z;
    float x0, x1, y0, y1, z0, b0, b1, k, S;
};

SphRect lambertRectSetup(LambertianRectGpu L, vec3 p) {
    SphRect s;
    s.x = L.edgeX.xyz / L.edgeX.w;
    s.y = L.edgeY.xyz / L.edgeY.w;
    s.z = L.normal.xyz;
    vec3 d = L.corner.xyz - p;
    s.z0 = dot(d, s.z);
    s.S = 0.0;
    if (!(s.z0 < 0.0)) return s;
    s.x0 = dot(d, s.x);
    s.y0 = dot(d, s.y);
    s.x1 = s.x0 + L.edgeX.w;
    s.y1 = s.y0 + L.edgeY.w;
    vec3 v00 = vec3(s.x0, s.y0, s.z0), v01 = vec3(s.x0, s.y1, s.z0);
    vec3 v10 = vec3(s.x1, s.y0, s.z0), v11 = vec3(s.x1, s.y1, s.z0);
    vec3 n0 = normalize(cross(v00, v10));
    vec3 n1 = normalize(cross(v10, v11));
    vec3 n2 = normalize(cross(v11, v01));
    vec3 n3 = normalize(cross(v01, v00));
    // Interior angles of the spherical rectangle. atan2 of sine and cosine, not acos of the
    // cosine: acos loses half the float digits where the cosine is near -1 or 1.
    float g0 = atan(length(cross(n0, n1)), -dot(n0, n1));
    float g1 = atan(length(cross(n1, n2)), -dot(n1, n2));
    float g2 = atan(length(cross(n2, n3)), -dot(n2, n3));
    float g3 = atan(length(cross(n3, n0)), -dot(n3, n0));
    s.b0 = n0.z;
    s.b1 = n2.z;
    s.k = 2.0 * kPi - g2 - g3;
    // The area itself from two triangles (Van Oosterom and Strackee 1983) rather than the Girard
    // sum g0 + g1 + g2 + g3 - 2 pi, which cancels in float for small solid angles. Both
    // triangles' triple product is |z0| * width * height.
    vec3 a = normalize(v00), b = normalize(v10), c = normalize(v11), e = normalize(v01);
    float triple = abs(s.z0) * L.edgeX.w * L.edgeY.w / (length(v00) * length(v10) * length(v11));
    float triple2 = abs(s.z0) * L.edgeX.w * L.edgeY.w / (length(v00) * length(v11) * length(v01));
    float S = 2.0 * (atan(triple, 1.0 + dot(a, b) + dot(b, c) + dot(c, a)) +
                     atan(triple2, 1.0 + dot(a, c) + dot(c, e) + dot(e, a)));
    s.S = (S > 0.0 && !isinf(S) && !isnan(S)) ? S : 0.0;
    return s;
}

float lambertRectSolidAngle(LambertianRectGpu L, vec3 p) { return lambertRectSetup(L, p).S; }

/// Direction to a point uniform in solid angle over the rectangle; false when p sees no front.
bool lambertRectSample(LambertianRectGpu L, vec3 p, vec2 u, out vec3 wi, out float dist,
                       out float pdf) {
    SphRect s = lambertRectSetup(L, p);
    wi = vec3(0.0);
    dist = 0.0;
    pdf = 0.0;
    if (s.S <= 0.0) return false;
    float au = u.x * s.S + s.k;
    float sinAu = sin(au);
    float fu = (cos(au) * s.b0 - s.b1) / (abs(sinAu) > 1e-30 ? sinAu : 1e-30);
    float cu = clamp((fu >= 0.0 ? 1.0 : -1.0) / sqrt(fu * fu + s.b0 * s.b0), -1.0, 1.0);
    float xu = clamp(-(cu * s.z0) / max(sqrt(1.0 - cu * cu), 1e-30), s.x0, s.x1);
    float d = sqrt(xu * xu + s.z0 * s.z0);
    float h0 = s.y0 / sqrt(d * d + s.y0 * s.y0);
    float h1 = s.y1 / sqrt(d * d + s.y1 * s.y1);
    float hv = h0 + u.y * (h1 - h0);
    float hv2 = hv * hv;
    float yv = hv2 < 1.0 - 1e-6 ? hv * d / sqrt(1.0 - hv2) : s.y1;
    yv = clamp(yv, s.y0, s.y1);
    vec3 q = xu * s.x + yv * s.y + s.z0 * s.z;  // relative to p
    dist = length(q);
    if (!(dist > 0.0)) return false;
    wi = q / dist;
    pdf = 1.0 / s.S;
    return true;
}
