// Light-field luminaires in GLSL: the same model, tables and sampler as luminaires/LightField.cpp
// (Lu, Pacanowski, Granier 2015). The summed-area tables are read in double precision: in float,
// A_m of a small box far from the table's origin would lose most of its digits to cancellation.
// Needs shared/GpuTypes.h (LightFieldGpu). The including shader binds the buffer at binding 1.

layout(std430, binding = 1) readonly buffer LightFieldHeader { LightFieldGpu lf; };
layout(std430, binding = 1) readonly buffer LightFieldDoubles { double lfDoubles[]; };
layout(std430, binding = 1) readonly buffer LightFieldFloats { float lfFloats[]; };
layout(std430, binding = 1) readonly buffer LightFieldUints { uint lfUints[]; };

float lfDelta() { return lf.geometry.x; }
int lfImageCount() { return lf.dims.x * lf.dims.y; }
vec2 lfImageMin() { return lf.origin.zw; }
vec2 lfImageMax() { return lf.image.xy; }
vec2 lfPixel() { return lf.image.zw; }

/// Quadratic B-spline, support [-1.5, 1.5].
float lfBspline2(float x) {
    x = abs(x);
    if (x < 0.5) return 0.75 - x * x;
    if (x < 1.5) return 0.5 * (1.5 - x) * (1.5 - x);
    return 0.0;
}

vec2 lfNode(int m) {
    return lf.origin.xy + vec2(float(m % lf.dims.x), float(m / lf.dims.x)) * lf.geometry.yz;
}

/// Psi_m(u -> s) (Eq. 1): Phi_m(u), times delta^2 cos^4(theta) for the goesele model.
float lfPsi(int m, vec2 u, vec2 s) {
    vec2 d = (u - lfNode(m)) / lf.geometry.yz;
    float phi = lfBspline2(d.x) * lfBspline2(d.y);
    if (lf.geometry.w > 0.5 && phi > 0.0) {
        float d2 = lfDelta() * lfDelta();
        vec2 r = s - u;
        float c2 = d2 / (d2 + dot(r, r));
        phi *= d2 * c2 * c2;
    }
    return phi;
}

/// C_m(s), 0 outside the image.
float lfLum(int m, vec2 s) {
    vec2 f = (s - lfImageMin()) / lfPixel();
    if (!(f.x >= 0.0 && f.y >= 0.0 && f.x < float(lf.dims.z) && f.y < float(lf.dims.w))) return 0.0;
    int idx = m * lf.dims.z * lf.dims.w + int(f.y) * lf.dims.z + int(f.x);
    return lfFloats[lf.offsets.y + idx];
}

/// Colour ratio c_m(s) (Sec. 5); white for luminance data.
vec3 lfColour(int m, vec2 s) {
    if (lf.offsets.w == 0) return vec3(1.0);
    vec2 f = clamp((s - lfImageMin()) / lfPixel(), vec2(0.0), vec2(lf.dims.zw) - 1.0);
    int idx = m * lf.dims.z * lf.dims.w + int(f.y) * lf.dims.z + int(f.x);
    vec2 rg = unpackHalf2x16(lfUints[lf.offsets.z + 2 * idx]);
    vec2 b = unpackHalf2x16(lfUints[lf.offsets.z + 2 * idx + 1]);
    return vec3(rg, b.x);
}

double lfSatEntry(int m, int i, int j) {
    int w1 = lf.dims.z + 1;
    return lfDoubles[lf.offsets.x + m * w1 * (lf.dims.w + 1) + j * w1 + i];
}

/// Integral of C_m over [imageMin, s] (bilinear in a pixel: exact for a piecewise constant image).
double lfSatAt(int m, vec2 s) {
    dvec2 f = clamp((dvec2(s) - dvec2(lfImageMin())) / dvec2(lfPixel()), dvec2(0.0), dvec2(lf.dims.zw));
    int i = min(int(f.x), lf.dims.z - 1), j = min(int(f.y), lf.dims.w - 1);
    double fx = f.x - double(i), fy = f.y - double(j);
    double s00 = lfSatEntry(m, i, j), s10 = lfSatEntry(m, i + 1, j);
    double s01 = lfSatEntry(m, i, j + 1), s11 = lfSatEntry(m, i + 1, j + 1);
    return s00 + fx * (s10 - s00) + fy * (s01 - s00) + fx * fy * (s11 - s10 - s01 + s00);
}

/// A_m over the box [a, b] (Eq. 10).
double lfBoxIntegral(int m, vec2 a, vec2 b) {
    if (!(b.x > a.x && b.y > a.y)) return 0.0;
    double v = lfSatAt(m, b) - lfSatAt(m, vec2(a.x, b.y)) - lfSatAt(m, vec2(b.x, a.y)) + lfSatAt(m, a);
    // Below 1e-12 of the image's energy the difference is rounding (as LightField.cpp).
    return v > 1e-12 * lfSatEntry(m, lf.dims.z, lf.dims.w) ? v : 0.0;
}

/// granier2003's far-field table: W_m, image m weighted by its B-spline, for a support centred
/// on `centre` (bilinear; LightFieldData::granierTable); -1 without a table.
float lfGranierWeighted(int m, vec2 centre) {
    int o = lf.options.y, n = lf.options.z;
    if (n < 2) return -1.0;
    vec2 lo = vec2(lfFloats[o], lfFloats[o + 1]), hi = vec2(lfFloats[o + 2], lfFloats[o + 3]);
    vec2 f = (centre - lo) / (hi - lo) * float(n - 1);
    if (!(f.x >= 0.0 && f.y >= 0.0 && f.x <= float(n - 1) && f.y <= float(n - 1))) return 0.0;
    f = min(f, vec2(float(n - 1) - 1e-3));
    ivec2 i = ivec2(f);
    vec2 t = f - vec2(i);
    int base = o + 4 + (m * n + i.y) * n + i.x;
    float r0 = mix(lfFloats[base], lfFloats[base + 1], t.x), r1 = mix(lfFloats[base + n], lfFloats[base + n + 1], t.x);
    return mix(r0, r1, t.y);
}

/// Restricted box of image m seen from local q (q.z > delta): Eq. (7) with the U-plane term,
/// s = u + (q - u) delta / q.z, clipped to the image. False when empty.
bool lfRestrictedBox(int m, vec3 q, out vec2 a, out vec2 b) {
    vec2 c = lfNode(m), h = 1.5 * lf.geometry.yz;
    float f = lfDelta() / q.z;
    a = max(c - h + (q.xy - (c - h)) * f, lfImageMin());
    b = min(c + h + (q.xy - (c + h)) * f, lfImageMax());
    return b.x > a.x && b.y > a.y;
}

// The knots of the restricted marginal in s and of the conditional in t (see LightField.cpp).
double lfMarginal(int m, int c0, int k, vec2 a, vec2 b) {
    float x = clamp(lfImageMin().x + float(c0 + k) * lfPixel().x, a.x, b.x);
    return lfSatAt(m, vec2(x, b.y)) - lfSatAt(m, vec2(x, a.y));
}
double lfColumn(int m, int r0, int k, vec2 a, vec2 b, float colL, float colR) {
    float y = clamp(lfImageMin().y + float(r0 + k) * lfPixel().y, a.y, b.y);
    return lfSatAt(m, vec2(colR, y)) - lfSatAt(m, vec2(colL, y));
}

/// Draws s in [a, b] with density C_m / A_m (Eq. 8), inverting both piecewise linear CDFs with a
/// secant-guided search over their knots that stops on a linear piece (Sec. 5); bisection when a
/// secant step fails to halve the bracket. False when the box holds no energy.
bool lfSampleBox(int m, vec2 a, vec2 b, vec2 xi, out vec2 s) {
    s = a;
    vec2 px = lfPixel(), o = lfImageMin();
    int c0 = clamp(int(floor((a.x - o.x) / px.x)), 0, lf.dims.z - 1);
    int c1 = clamp(int(ceil((b.x - o.x) / px.x)), c0 + 1, lf.dims.z);
    int lo = 0, hi = c1 - c0;
    double vlo = lfMarginal(m, c0, lo, a, b), vhi = lfMarginal(m, c0, hi, a, b);
    double floorEnergy = 1e-12 * lfSatEntry(m, lf.dims.z, lf.dims.w);
    if (!(vhi - vlo > floorEnergy)) return false;
    double target = vlo + double(clamp(xi.x, 0.0, 1.0)) * (vhi - vlo);
    bool bisect = false;
    while (hi - lo > 1) {
        int mid = bisect ? lo + (hi - lo) / 2
                         : clamp(lo + int((target - vlo) / (vhi - vlo) * double(hi - lo)), lo + 1, hi - 1);
        int before = hi - lo;
        double v = lfMarginal(m, c0, mid, a, b);
        if (v > target) { hi = mid; vhi = v; } else { lo = mid; vlo = v; }
        bisect = (hi - lo) * 2 > before;
    }
    if (!(vhi > vlo)) return false;
    float xa = clamp(o.x + float(c0 + lo) * px.x, a.x, b.x), xb = clamp(o.x + float(c0 + hi) * px.x, a.x, b.x);
    s.x = clamp(xa + float((target - vlo) / (vhi - vlo)) * (xb - xa), xa, xb);
    int column = c0 + lo;
    float colL = o.x + float(column) * px.x, colR = colL + px.x;

    int r0 = clamp(int(floor((a.y - o.y) / px.y)), 0, lf.dims.w - 1);
    int r1 = clamp(int(ceil((b.y - o.y) / px.y)), r0 + 1, lf.dims.w);
    lo = 0;
    hi = r1 - r0;
    vlo = lfColumn(m, r0, lo, a, b, colL, colR);
    vhi = lfColumn(m, r0, hi, a, b, colL, colR);
    if (!(vhi - vlo > floorEnergy)) return false;
    target = vlo + double(clamp(xi.y, 0.0, 1.0)) * (vhi - vlo);
    bisect = false;
    while (hi - lo > 1) {
        int mid = bisect ? lo + (hi - lo) / 2
                         : clamp(lo + int((target - vlo) / (vhi - vlo) * double(hi - lo)), lo + 1, hi - 1);
        int before = hi - lo;
        double v = lfColumn(m, r0, mid, a, b, colL, colR);
        if (v > target) { hi = mid; vhi = v; } else { lo = mid; vlo = v; }
        bisect = (hi - lo) * 2 > before;
    }
    if (!(vhi > vlo)) return false;
    float ya = clamp(o.y + float(r0 + lo) * px.y, a.y, b.y), yb = clamp(o.y + float(r0 + hi) * px.y, a.y, b.y);
    s.y = clamp(ya + float((target - vlo) / (vhi - vlo)) * (yb - ya), ya, yb);
    s.x = clamp(s.x, max(colL, a.x), min(colR, b.x));
    return true;
}

/// Halton radical inverse in base 2 (bit reversal) and base 3.
float lfHalton2(uint i) { return float(bitfieldReverse(i) >> 8) * (1.0 / 16777216.0); }
float lfHalton3(uint i) {
    float f = 1.0 / 3.0, r = 0.0;
    while (i > 0u) {
        r += f * float(i % 3u);
        i /= 3u;
        f /= 3.0;
    }
    return r;
}
