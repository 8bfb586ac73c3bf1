// Light-field luminaires in GLSL: the same model, tables and sampler as luminaires/LightField.cpp
// (Lu, Pacanowski, Granier 2015). The summed-area tables are float-float pairs (ff.glsl): in
// float, A_m of a small box far from the table's origin would lose most of its digits to
// cancellation. Every difference of table entries is taken in float-float and rounded to float
// once, when it is the energy of a block of pixels, so what is rounded is a box's own energy.
// Needs shared/GpuTypes.h (LightFieldGpu). The including shader binds the buffer at binding 1.
#include "ff.glsl"

layout(std430, binding = 1) readonly buffer LightFieldHeader { LightFieldGpu lf; };
layout(std430, binding = 1) readonly buffer LightFieldSat { vec2 lfSat[]; };  // float-float
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

/// Entry (i, j) of image m's summed-area table: the energy of its pixels [0, i) x [0, j).
vec2 lfSatEntry(int m, int i, int j) {
    int w1 = lf.dims.z + 1;
    return lfSat[lf.offsets.x + m * w1 * (lf.dims.w + 1) + j * w1 + i];
}

/// Image m's energy (the integral of C_m over the image).
float lfTotal(int m) { return ffToFloat(lfSatEntry(m, lf.dims.z, lf.dims.w)); }

/// C_m of pixel (i, j).
float lfPixelLum(int m, int i, int j) {
    return lfFloats[lf.offsets.y + (m * lf.dims.w + j) * lf.dims.z + i];
}

/// Edge k of the pixels along one axis (0: s, 1: t), imageMin + k x pixel size, as a float-float
/// position: exact to about 1e-14 of the image, so that the box integrals below resolve a box's
/// corners against the pixel edges as finely as the corners' own floats do.
vec2 lfEdge(int axis, int k) {
    vec2 o = vec2(lf.origin[2 + axis], lf.imageLow[axis]);
    vec2 px = vec2(lf.image[2 + axis], lf.imageLow[2 + axis]);
    return ffAdd(o, ffMulF(px, float(k)));
}

/// x - edge k (m), rounded once.
float lfFromEdge(int axis, int k, float x) { return ffToFloat(ffSub(vec2(x, 0.0), lfEdge(axis, k))); }

/// The pixel of an axis that holds x, clamped to the image (the float estimate, corrected
/// against the exact edges).
int lfPixelOf(int axis, float x) {
    int n = lf.dims[2 + axis];
    int k = clamp(int(floor((x - lfImageMin()[axis]) / lfPixel()[axis])), 0, n - 1);
    if (k > 0 && lfFromEdge(axis, k, x) < 0.0) --k;
    else if (k < n - 1 && lfFromEdge(axis, k + 1, x) >= 0.0) ++k;
    return k;
}

/// How [lo, hi] (inside the image) covers the pixels of one axis: the first and last pixel it
/// touches and the fraction of each it covers; wMiddle is 1 when whole pixels lie between them.
/// A fraction is measured from a coordinate to its pixel's own exact edge, so it keeps float's
/// relative precision however far the pixel is from the image's origin.
struct LfCover {
    int first, last;
    float wFirst, wMiddle, wLast;
};
LfCover lfCover(int axis, float lo, float hi) {
    float px = lfPixel()[axis];
    LfCover c;
    c.first = lfPixelOf(axis, lo);
    c.last = max(lfPixelOf(axis, hi), c.first);
    if (c.last == c.first) {
        c.wFirst = clamp((hi - lo) / px, 0.0, 1.0);
        c.wMiddle = c.wLast = 0.0;
    } else {
        c.wFirst = clamp(-lfFromEdge(axis, c.first + 1, lo) / px, 0.0, 1.0);
        c.wMiddle = c.last > c.first + 1 ? 1.0 : 0.0;
        c.wLast = clamp(lfFromEdge(axis, c.last, hi) / px, 0.0, 1.0);
    }
    return c;
}

/// The energy of pixels [i0, i1) x [j0, j1).
float lfPixelsEnergy(int m, int i0, int i1, int j0, int j1) {
    return ffToFloat(ffSub(ffSub(lfSatEntry(m, i1, j1), lfSatEntry(m, i0, j1)),
                           ffSub(lfSatEntry(m, i1, j0), lfSatEntry(m, i0, j0))));
}

/// The table's column (row) indices bounding a cover's first pixel, middle pixels and last pixel.
ivec4 lfEdges(LfCover c) { return ivec4(c.first, c.first + 1, c.last, c.last + 1); }
vec3 lfWeights(LfCover c) { return vec3(c.wFirst, c.wMiddle, c.wLast); }

/// The energy of the rows that `cy` covers (weighted by how much of each it covers) within the
/// pixel columns [i0, i1).
float lfBand(int m, int i0, int i1, LfCover cy) {
    ivec4 y = lfEdges(cy);
    vec3 wy = lfWeights(cy);
    float sum = 0.0;
    vec2 below = ffSub(lfSatEntry(m, i1, y[0]), lfSatEntry(m, i0, y[0]));
    for (int k = 1; k < 4; ++k) {
        vec2 upTo = ffSub(lfSatEntry(m, i1, y[k]), lfSatEntry(m, i0, y[k]));
        sum += wy[k - 1] * ffToFloat(ffSub(upTo, below));
        below = upTo;
    }
    return sum;
}

/// The energy of the box that cx and cy cover: its pixels split into first, middle and last
/// columns and rows, nine blocks, each an exact-sign float-float difference of table entries
/// rounded once and weighted by its cover. Every term is >= 0, so nothing cancels in float.
float lfBoxEnergy(int m, LfCover cx, LfCover cy) {
    ivec4 x = lfEdges(cx), y = lfEdges(cy);
    vec3 wx = lfWeights(cx), wy = lfWeights(cy);
    float sum = 0.0;
    vec2 below[3];
    for (int k = 0; k < 4; ++k) {
        vec2 s0 = lfSatEntry(m, x[0], y[k]), s1 = lfSatEntry(m, x[1], y[k]);
        vec2 s2 = lfSatEntry(m, x[2], y[k]), s3 = lfSatEntry(m, x[3], y[k]);
        vec2 upTo[3] = vec2[3](ffSub(s1, s0), ffSub(s2, s1), ffSub(s3, s2));
        if (k > 0)
            for (int c = 0; c < 3; ++c) sum += wy[k - 1] * wx[c] * ffToFloat(ffSub(upTo[c], below[c]));
        below = upTo;
    }
    return sum;
}

/// Boxes spanning at most this many pixels per side are integrated and sampled pixel by pixel,
/// as LightField.cpp does (kDirectPixels): a receiver 1e-9 m beyond S has boxes 1e-8 of a pixel
/// wide, which only direct overlaps resolve.
const int kLfDirectPixels = 4;

/// Pixels [i0, i1) x [j0, j1) that the box [a, b] covers (LightField.cpp's spanOf).
ivec4 lfSpan(vec2 a, vec2 b) {
    int i0 = lfPixelOf(0, a.x), j0 = lfPixelOf(1, a.y);
    int i1 = lfPixelOf(0, b.x), j1 = lfPixelOf(1, b.y);
    i1 = clamp(lfFromEdge(0, i1, b.x) > 0.0 ? i1 + 1 : i1, i0 + 1, lf.dims.z);
    j1 = clamp(lfFromEdge(1, j1, b.y) > 0.0 ? j1 + 1 : j1, j0 + 1, lf.dims.w);
    return ivec4(i0, i1, j0, j1);
}
bool lfDirect(ivec4 span) { return span.y - span.x <= kLfDirectPixels && span.w - span.z <= kLfDirectPixels; }

/// The length of [lo, hi] inside pixel k of an axis (m).
float lfOverlap(int axis, float lo, float hi, int k) {
    return max(0.0, min(lfFromEdge(axis, k, hi), lfPixel()[axis]) - max(lfFromEdge(axis, k, lo), 0.0));
}

/// A_m over the box [a, b] (Eq. 10), clipped to the image.
float lfBoxIntegral(int m, vec2 a, vec2 b) {
    a = max(a, lfImageMin());
    b = min(b, lfImageMax());
    if (!(b.x > a.x && b.y > a.y)) return 0.0;
    ivec4 span = lfSpan(a, b);
    if (lfDirect(span)) {
        float sum = 0.0;
        for (int j = span.z; j < span.w; ++j) {
            float row = 0.0;
            for (int i = span.x; i < span.y; ++i) row += lfPixelLum(m, i, j) * lfOverlap(0, a.x, b.x, i);
            sum += row * lfOverlap(1, a.y, b.y, j);
        }
        return sum;
    }
    float v = lfBoxEnergy(m, lfCover(0, a.x, b.x), lfCover(1, a.y, b.y));
    // Below 1e-12 of the image's energy the difference is rounding (as LightField.cpp).
    return v > 1e-12 * lfTotal(m) ? v : 0.0;
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

/// Small boxes pixel by pixel (LightField.cpp's direct path): a column by its energy, x uniform
/// within it (the density is constant along a pixel row), then a row of that column by its
/// energy, y uniform in it.
bool lfSampleDirect(int m, vec2 a, vec2 b, ivec4 span, vec2 xi, out vec2 s) {
    s = a;
    float column[kLfDirectPixels];
    float total = 0.0;
    for (int i = span.x; i < span.y; ++i) {
        float sum = 0.0;
        for (int j = span.z; j < span.w; ++j) sum += lfPixelLum(m, i, j) * lfOverlap(1, a.y, b.y, j);
        column[i - span.x] = sum * lfOverlap(0, a.x, b.x, i);
        total += column[i - span.x];
    }
    if (!(total > 0.0)) return false;
    float target = clamp(xi.x, 0.0, 1.0) * total;
    int i = span.x;
    for (; i + 1 < span.y && target > column[i - span.x]; ++i) target -= column[i - span.x];
    float c = column[i - span.x];
    if (!(c > 0.0)) return false;
    float x0 = max(a.x, ffToFloat(lfEdge(0, i))), x1 = min(b.x, ffToFloat(lfEdge(0, i + 1)));
    s.x = clamp(x0 + clamp(target / c, 0.0, 1.0) * (x1 - x0), x0, x1);
    float width = lfOverlap(0, a.x, b.x, i);
    float targetY = clamp(xi.y, 0.0, 1.0) * c;
    int j = span.z;
    for (; j + 1 < span.w; ++j) {
        float e = lfPixelLum(m, i, j) * width * lfOverlap(1, a.y, b.y, j);
        if (!(targetY > e)) break;
        targetY -= e;
    }
    float e = lfPixelLum(m, i, j) * width * lfOverlap(1, a.y, b.y, j);
    if (!(e > 0.0)) return false;
    float y0 = max(a.y, ffToFloat(lfEdge(1, j))), y1 = min(b.y, ffToFloat(lfEdge(1, j + 1)));
    s.y = clamp(y0 + clamp(targetY / e, 0.0, 1.0) * (y1 - y0), y0, y1);
    return true;
}

/// The knots of a piecewise linear CDF over a box, measured from its lower end so that every knot
/// is a box's own energy in float: the restricted marginal in s (knots at the box's ends and the
/// pixel column edges between them) or the conditional in t within pixel column `column` (the
/// box's ends and the row edges between them), Eq. 8. Knot 0 is 0, knot 1 the first pixel's
/// share (`first`), knot n the total.
struct LfKnots {
    bool marginal;
    int n, column;
    float first, total;
    LfCover cx, cy;
};
float lfKnot(int m, LfKnots K, int k) {
    if (k == 0) return 0.0;
    if (k == K.n) return K.total;
    if (K.marginal) return K.first + lfBand(m, K.cx.first + 1, K.cx.first + k, K.cy);
    return K.first + lfPixelsEnergy(m, K.column, K.column + 1, K.cy.first + 1, K.cy.first + k);
}

/// The piece [k, k + 1] that holds `target` (0 <= target <= total), by a secant-guided search
/// over the knots that stops on a linear piece (Sec. 5), bisecting when a secant step fails to
/// halve the bracket; its end values in vlo and vhi.
int lfFindPiece(int m, LfKnots K, float target, out float vlo, out float vhi) {
    int lo = 0, hi = K.n;
    vlo = 0.0;
    vhi = K.total;
    bool bisect = false;
    while (hi - lo > 1) {
        int mid = bisect ? lo + (hi - lo) / 2
                         : clamp(lo + int((target - vlo) / (vhi - vlo) * float(hi - lo)), lo + 1, hi - 1);
        int before = hi - lo;
        float v = lfKnot(m, K, mid);
        if (v > target) {
            hi = mid;
            vhi = v;
        } else {
            lo = mid;
            vlo = v;
        }
        bisect = (hi - lo) * 2 > before;
    }
    return lo;
}

/// Large boxes from the summed-area table: the restricted marginal in s, then the conditional in
/// t within the chosen pixel column (Eq. 8).
bool lfSampleTable(int m, vec2 a, vec2 b, vec2 xi, out vec2 s) {
    s = a;
    float floorEnergy = 1e-12 * lfTotal(m);
    LfKnots K;
    K.cx = lfCover(0, a.x, b.x);
    K.cy = lfCover(1, a.y, b.y);
    K.marginal = true;
    K.n = K.cx.last - K.cx.first + 1;
    K.total = lfBoxEnergy(m, K.cx, K.cy);
    if (!(K.total > floorEnergy)) return false;
    K.first = K.cx.wFirst * lfBand(m, K.cx.first, K.cx.first + 1, K.cy);
    float target = clamp(xi.x, 0.0, 1.0) * K.total, vlo, vhi;
    int k = lfFindPiece(m, K, target, vlo, vhi);
    if (!(vhi > vlo)) return false;
    float xa = k == 0 ? a.x : ffToFloat(lfEdge(0, K.cx.first + k));
    float xb = k + 1 == K.n ? b.x : ffToFloat(lfEdge(0, K.cx.first + k + 1));
    s.x = clamp(xa + (target - vlo) / (vhi - vlo) * (xb - xa), xa, xb);

    K.marginal = false;
    K.column = K.cx.first + k;
    K.n = K.cy.last - K.cy.first + 1;
    K.total = lfBand(m, K.column, K.column + 1, K.cy);
    if (!(K.total > floorEnergy)) return false;
    K.first = K.cy.wFirst * lfPixelsEnergy(m, K.column, K.column + 1, K.cy.first, K.cy.first + 1);
    target = clamp(xi.y, 0.0, 1.0) * K.total;
    k = lfFindPiece(m, K, target, vlo, vhi);
    if (!(vhi > vlo)) return false;
    float ya = k == 0 ? a.y : ffToFloat(lfEdge(1, K.cy.first + k));
    float yb = k + 1 == K.n ? b.y : ffToFloat(lfEdge(1, K.cy.first + k + 1));
    s.y = clamp(ya + (target - vlo) / (vhi - vlo) * (yb - ya), ya, yb);
    // Keep s inside the chosen pixel column even where x fell on its edge.
    s.x = clamp(s.x, max(ffToFloat(lfEdge(0, K.column)), a.x), min(ffToFloat(lfEdge(0, K.column + 1)), b.x));
    return true;
}

/// Draws s in [a, b] with density C_m / A_m (Eq. 8). False when the box holds no energy.
bool lfSampleBox(int m, vec2 a, vec2 b, vec2 xi, out vec2 s) {
    a = max(a, lfImageMin());
    b = min(b, lfImageMax());
    s = a;
    if (!(b.x > a.x && b.y > a.y)) return false;
    ivec4 span = lfSpan(a, b);
    return lfDirect(span) ? lfSampleDirect(m, a, b, span, xi, s) : lfSampleTable(m, a, b, xi, s);
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
