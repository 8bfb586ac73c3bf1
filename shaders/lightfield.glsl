// Light-field luminaires in GLSL: the same model, tables and sampler as luminaires/lightfield/LightField.cpp
// (Lu, Pacanowski, Granier 2015). The summed-area tables are float-float pairs (ff.glsl): in
// float, A_m of a small box far from the table's origin would lose most of its digits to
// cancellation. Every difference of table entries is taken in float-float and rounded to float
// once, when it is the energy of a block of pixels, so what is rounded is a box's own energy.
// Needs shared/GpuTypes.h (LightFieldGpu). The including shader binds the record at binding 1
// and the images' tables (luminaires/GpuTable.h, LightFieldData::gpuTables) at their texture
// units: 2D arrays, one layer per image, read with texelFetch.
#include "ff.glsl"

layout(std430, binding = 1) readonly buffer LightFieldHeader { LightFieldGpu lf; };
layout(std430, binding = 1) readonly buffer LightFieldFloats { float lfFloats[]; };
layout(binding = 8) uniform sampler2DArray uLfSat;     // kUnitLightFieldSat: float-float pairs
layout(binding = 9) uniform sampler2DArray uLfLum;     // kUnitLightFieldLum
layout(binding = 10) uniform sampler2DArray uLfColour; // kUnitLightFieldColour (RGB data only)
layout(binding = 11) uniform sampler2DArray uLfGranier; // kUnitLightFieldGranier

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
    return texelFetch(uLfLum, ivec3(int(f.x), int(f.y), m), 0).x;
}

/// Colour ratio c_m(s) (Sec. 5); white for luminance data.
vec3 lfColour(int m, vec2 s) {
    if (lf.offsets.w == 0) return vec3(1.0);
    vec2 f = clamp((s - lfImageMin()) / lfPixel(), vec2(0.0), vec2(lf.dims.zw) - 1.0);
    return texelFetch(uLfColour, ivec3(int(f.x), int(f.y), m), 0).rgb;
}

/// Entry (i, j) of image m's summed-area table: the energy of its pixels [0, i) x [0, j).
vec2 lfSatEntry(int m, int i, int j) { return texelFetch(uLfSat, ivec3(i, j, m), 0).xy; }

/// Image m's energy (the integral of C_m over the image).
float lfTotal(int m) { return ffToFloat(lfSatEntry(m, lf.dims.z, lf.dims.w)); }

/// C_m of pixel (i, j).
float lfPixelLum(int m, int i, int j) { return texelFetch(uLfLum, ivec3(i, j, m), 0).x; }

/// A coordinate on S against the pixels of one axis (0: s, 1: t): its pixel k (clamped to the
/// image), the fraction of that pixel below it and the fraction above it, each to float's
/// relative precision however far the pixel is from the image's origin. Computed from the
/// float-float position in pixels, (x - imageMin) / pixel size with both held as pairs.
struct LfCoord {
    int k;
    float below, above;
};
LfCoord lfCoord(int axis, float x) {
    vec2 o = vec2(lf.origin[2 + axis], lf.grid[axis]);
    vec2 inverse = vec2(lf.grid[2 + axis], lf.gridLow[axis]);
    vec2 u = ffMul(ffAddF(-o, x), inverse);
    int n = lf.dims[2 + axis];
    LfCoord c;
    c.k = int(floor(u.x));
    // u.x - k and k + 1 - u.x are exact in float; the low half then rounds once.
    c.below = (u.x - float(c.k)) + u.y;
    c.above = (float(c.k + 1) - u.x) - u.y;
    // Where the low half crosses an edge, the neighbouring pixel holds x.
    if (c.below < 0.0) {
        --c.k;
        c.above = -c.below;
        c.below += 1.0;
    } else if (c.above <= 0.0) {
        ++c.k;
        c.below = -c.above;
        c.above += 1.0;
    }
    if (c.k < 0) {
        c.k = 0;
        c.below = 0.0;
        c.above = 1.0;
    } else if (c.k >= n) {
        c.k = n - 1;
        c.below = 1.0;
        c.above = 0.0;
    }
    return c;
}

/// How [lo, hi] (inside the image) covers the pixels of one axis: the first and last pixel it
/// touches and the fraction of each it covers; wMiddle is 1 when whole pixels lie between them.
struct LfCover {
    int first, last;
    float wFirst, wMiddle, wLast;
};
LfCover lfCover(int axis, float lo, float hi) {
    LfCoord a = lfCoord(axis, lo), b = lfCoord(axis, hi);
    LfCover c;
    c.first = a.k;
    c.last = max(b.k, a.k);
    if (c.last == c.first) {
        // hi - lo is exact for a box inside one pixel: its width keeps every digit.
        c.wFirst = clamp((hi - lo) * lf.grid[2 + axis], 0.0, 1.0);
        c.wMiddle = c.wLast = 0.0;
    } else {
        c.wFirst = clamp(a.above, 0.0, 1.0);
        c.wMiddle = c.last > c.first + 1 ? 1.0 : 0.0;
        c.wLast = clamp(b.below, 0.0, 1.0);
    }
    return c;
}

/// The fraction of pixel k that a cover covers.
float lfCoverWeight(LfCover c, int k) {
    if (k < c.first || k > c.last) return 0.0;
    return k == c.first ? c.wFirst : (k == c.last ? c.wLast : 1.0);
}

/// Edge k of the pixels of one axis (m), to float rounding (sample positions).
float lfEdge(int axis, int k) { return lfImageMin()[axis] + float(k) * lfPixel()[axis]; }

/// The energy of pixels [i0, i1) x [j0, j1).
float lfPixelsEnergy(int m, int i0, int i1, int j0, int j1) {
    return ffSubToFloat(ffSub(lfSatEntry(m, i1, j1), lfSatEntry(m, i0, j1)),
                        ffSub(lfSatEntry(m, i1, j0), lfSatEntry(m, i0, j0)));
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
        sum += wy[k - 1] * ffSubToFloat(upTo, below);
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
            for (int c = 0; c < 3; ++c) sum += wy[k - 1] * wx[c] * ffSubToFloat(upTo[c], below[c]);
        below = upTo;
    }
    return sum;
}

/// Boxes spanning at most this many pixels per side are integrated and sampled pixel by pixel,
/// as LightField.cpp does (kDirectPixels): a receiver 1e-9 m beyond S has boxes 1e-8 of a pixel
/// wide, which only direct overlaps resolve.
const int kLfDirectPixels = 4;

/// Whether a box whose covers these are spans at most kLfDirectPixels pixels a side.
bool lfDirect(LfCover cx, LfCover cy) {
    return cx.last - cx.first < kLfDirectPixels && cy.last - cy.first < kLfDirectPixels;
}

/// A_m over the box [a, b] (Eq. 10), clipped to the image.
float lfBoxIntegral(int m, vec2 a, vec2 b) {
    a = max(a, lfImageMin());
    b = min(b, lfImageMax());
    if (!(b.x > a.x && b.y > a.y)) return 0.0;
    LfCover cx = lfCover(0, a.x, b.x), cy = lfCover(1, a.y, b.y);
    if (lfDirect(cx, cy)) {
        float sum = 0.0;
        for (int j = cy.first; j <= cy.last; ++j) {
            float row = 0.0;
            for (int i = cx.first; i <= cx.last; ++i) row += lfPixelLum(m, i, j) * lfCoverWeight(cx, i);
            sum += row * lfCoverWeight(cy, j);
        }
        return sum * lfPixel().x * lfPixel().y;
    }
    float v = lfBoxEnergy(m, cx, cy);
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
    float r0 = mix(texelFetch(uLfGranier, ivec3(i, m), 0).x, texelFetch(uLfGranier, ivec3(i.x + 1, i.y, m), 0).x, t.x);
    float r1 = mix(texelFetch(uLfGranier, ivec3(i.x, i.y + 1, m), 0).x, texelFetch(uLfGranier, ivec3(i + 1, m), 0).x, t.x);
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
bool lfSampleDirect(int m, vec2 a, vec2 b, LfCover cx, LfCover cy, vec2 xi, out vec2 s) {
    s = a;
    float column[kLfDirectPixels];
    float total = 0.0;
    for (int i = cx.first; i <= cx.last; ++i) {
        float sum = 0.0;
        for (int j = cy.first; j <= cy.last; ++j) sum += lfPixelLum(m, i, j) * lfCoverWeight(cy, j);
        column[i - cx.first] = sum * lfCoverWeight(cx, i);
        total += column[i - cx.first];
    }
    if (!(total > 0.0)) return false;
    float target = clamp(xi.x, 0.0, 1.0) * total;
    int i = cx.first;
    for (; i < cx.last && target > column[i - cx.first]; ++i) target -= column[i - cx.first];
    float c = column[i - cx.first];
    if (!(c > 0.0)) return false;
    float x0 = max(a.x, lfEdge(0, i)), x1 = min(b.x, lfEdge(0, i + 1));
    s.x = clamp(x0 + clamp(target / c, 0.0, 1.0) * (x1 - x0), x0, x1);
    float width = lfCoverWeight(cx, i);
    float targetY = clamp(xi.y, 0.0, 1.0) * c;
    int j = cy.first;
    for (; j < cy.last; ++j) {
        float e = lfPixelLum(m, i, j) * width * lfCoverWeight(cy, j);
        if (!(targetY > e)) break;
        targetY -= e;
    }
    float e = lfPixelLum(m, i, j) * width * lfCoverWeight(cy, j);
    if (!(e > 0.0)) return false;
    float y0 = max(a.y, lfEdge(1, j)), y1 = min(b.y, lfEdge(1, j + 1));
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
    // The table entries every knot subtracts: S(cx.first + 1, y) at the cover's four row edges
    // (marginal); S(column + 1, y) - S(column, y) at y = cy.first + 1 (conditional, base[0]).
    vec2 base[4];
};
float lfKnot(int m, LfKnots K, int k) {
    if (k == 0) return 0.0;
    if (k == K.n) return K.total;
    if (!K.marginal) {
        int j = K.cy.first + k;
        return K.first + ffSubToFloat(ffSub(lfSatEntry(m, K.column + 1, j), lfSatEntry(m, K.column, j)), K.base[0]);
    }
    // lfBand over columns [cx.first + 1, cx.first + k), its left edge's entries cached.
    ivec4 y = lfEdges(K.cy);
    vec3 wy = lfWeights(K.cy);
    int i = K.cx.first + k;
    float sum = 0.0;
    vec2 below = ffSub(lfSatEntry(m, i, y[0]), K.base[0]);
    for (int e = 1; e < 4; ++e) {
        vec2 upTo = ffSub(lfSatEntry(m, i, y[e]), K.base[e]);
        sum += wy[e - 1] * ffSubToFloat(upTo, below);
        below = upTo;
    }
    return K.first + sum;
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
bool lfSampleTable(int m, vec2 a, vec2 b, LfCover cx, LfCover cy, float total, vec2 xi, out vec2 s) {
    s = a;
    float floorEnergy = 1e-12 * lfTotal(m);
    LfKnots K;
    K.cx = cx;
    K.cy = cy;
    K.marginal = true;
    K.n = K.cx.last - K.cx.first + 1;
    K.total = total;
    if (!(K.total > floorEnergy)) return false;
    K.first = K.cx.wFirst * lfBand(m, K.cx.first, K.cx.first + 1, K.cy);
    ivec4 y = lfEdges(K.cy);
    for (int e = 0; e < 4; ++e) K.base[e] = lfSatEntry(m, K.cx.first + 1, y[e]);
    float target = clamp(xi.x, 0.0, 1.0) * K.total, vlo, vhi;
    int k = lfFindPiece(m, K, target, vlo, vhi);
    if (!(vhi > vlo)) return false;
    float xa = k == 0 ? a.x : lfEdge(0, K.cx.first + k);
    float xb = k + 1 == K.n ? b.x : lfEdge(0, K.cx.first + k + 1);
    s.x = clamp(xa + (target - vlo) / (vhi - vlo) * (xb - xa), xa, xb);

    K.marginal = false;
    K.column = K.cx.first + k;
    K.n = K.cy.last - K.cy.first + 1;
    K.total = lfBand(m, K.column, K.column + 1, K.cy);
    if (!(K.total > floorEnergy)) return false;
    K.first = K.cy.wFirst * lfPixelsEnergy(m, K.column, K.column + 1, K.cy.first, K.cy.first + 1);
    K.base[0] = ffSub(lfSatEntry(m, K.column + 1, K.cy.first + 1), lfSatEntry(m, K.column, K.cy.first + 1));
    target = clamp(xi.y, 0.0, 1.0) * K.total;
    k = lfFindPiece(m, K, target, vlo, vhi);
    if (!(vhi > vlo)) return false;
    float ya = k == 0 ? a.y : lfEdge(1, K.cy.first + k);
    float yb = k + 1 == K.n ? b.y : lfEdge(1, K.cy.first + k + 1);
    s.y = clamp(ya + (target - vlo) / (vhi - vlo) * (yb - ya), ya, yb);
    // Keep s inside the chosen pixel column even where x fell on its edge.
    s.x = clamp(s.x, max(lfEdge(0, K.column), a.x), min(lfEdge(0, K.column + 1), b.x));
    return true;
}

/// Draws s in [a, b] with density C_m / A_m (Eq. 8), given A_m as lfBoxIntegral returns it for
/// [a, b] (or any value <= 0: computed here). False when the box holds no energy.
bool lfSampleBoxOf(int m, vec2 a, vec2 b, float Am, vec2 xi, out vec2 s) {
    a = max(a, lfImageMin());
    b = min(b, lfImageMax());
    s = a;
    if (!(b.x > a.x && b.y > a.y)) return false;
    LfCover cx = lfCover(0, a.x, b.x), cy = lfCover(1, a.y, b.y);
    if (lfDirect(cx, cy)) return lfSampleDirect(m, a, b, cx, cy, xi, s);
    return lfSampleTable(m, a, b, cx, cy, Am > 0.0 ? Am : lfBoxEnergy(m, cx, cy), xi, s);
}
bool lfSampleBox(int m, vec2 a, vec2 b, vec2 xi, out vec2 s) { return lfSampleBoxOf(m, a, b, 0.0, xi, s); }

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
