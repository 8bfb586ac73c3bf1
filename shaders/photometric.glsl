// Photometric area lights in GLSL: the same algorithms as luminaires/photometric/PhotometricEstimators.cpp
// and luminaires/SphericalPolygon.cpp, in float. Needs shared/GpuTypes.h (PhotometricGpu) and
// kPi from common.glsl. Everything works in the luminaire's local frame (opening in z = 0, aim
// +z) with vectors relative to the receiver, as on the CPU.
#include "shared/Photometric.h"

layout(std430, binding = 1) readonly buffer PhotometricHeader { PhotometricGpu ph; };
layout(std430, binding = 1) readonly buffer PhotometricFloats { float phFloats[]; };
// kUnitPhotometricIntensity: the candela table, unscaled (x = vertical index, y = horizontal).
layout(binding = 8) uniform sampler2DArray uPhCandela;
// kUnitPhotometricCellCdf: the cells' CDF, entry k at (k mod (nv - 1), k div (nv - 1)).
layout(binding = 9) uniform sampler2DArray uPhCellCdf;

float phCandela(int iv, int ih) { return texelFetch(uPhCandela, ivec3(iv, ih, 0), 0).x; }
float phCellCdf(int k) {
    int w = max(ph.dims.x - 1, 1);
    return texelFetch(uPhCellCdf, ivec3(k % w, k / w, 0), 0).x;
}

// --- The intensity table ------------------------------------------------------------------------

/// Cell of x in the ascending array of n angles at float offset o: i with a[i] <= x <= a[i+1] and
/// the fraction t; false outside [a[0], a[n-1]]. A single angle is a cell of its own (t = 0).
bool phCell(int o, int n, float x, out int i, out float t) {
    i = 0;
    t = 0.0;
    if (n < 1 || !(x >= phFloats[o] && x <= phFloats[o + n - 1])) return false;
    if (n == 1) return true;
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (phFloats[o + mid] <= x) lo = mid;
        else hi = mid;
    }
    float a = phFloats[o + lo], b = phFloats[o + hi];
    i = lo;
    t = b > a ? clamp((x - a) / (b - a), 0.0, 1.0) : 0.0;
    return true;
}

/// The table's (vertical, horizontal) angles of the unit local direction d. Angles are atan of
/// sine and cosine, never asin or acos: NVIDIA's acos is a cubic fit off by up to 7e-5 rad, which
/// on an H200 lit an opening's edge-on plane with 0.4 lx and read a receiver 1e-6 m in front of
/// it 15x too bright (the table's 90-degree cell read 7e-5 rad inside).
void phAngles(vec3 d, out float vertical, out float horizontal) {
    if (ph.dims.w == 1) {  // type B: polar axis +y
        vertical = atan(d.y, length(d.xz));
        horizontal = atan(d.x, d.z);
    } else {  // type C: gamma from +z, C counter-clockwise from +x
        vertical = atan(length(d.xy), d.z);
        horizontal = atan(d.y, d.x);
        if (horizontal < 0.0) horizontal += 2.0 * kPi;
    }
}

/// Candela towards the unit local direction d, bilinear in (vertical, horizontal) angle like
/// PhotometricData::intensity (scale is already in the table).
float phIntensity(vec3 d) {
    float vertical, horizontal;
    phAngles(d, vertical, horizontal);
    int nv = ph.dims.x, nh = ph.dims.y;
    int iv, ih;
    float tv, th;
    if (!phCell(ph.offsets.x, nv, vertical, iv, tv)) return 0.0;
    if (!phCell(ph.offsets.y, nh, horizontal, ih, th)) {
        // A full turn that stops short of 2 pi by rounding: wrap into the first cell.
        if (nh > 1 || !phCell(ph.offsets.y, nh, horizontal - 2.0 * kPi, ih, th)) return 0.0;
    }
    int iv1 = min(iv + 1, nv - 1), ih1 = min(ih + 1, nh - 1);
    float a = mix(phCandela(iv, ih), phCandela(iv1, ih), tv);
    float b = mix(phCandela(iv, ih1), phCandela(iv1, ih1), tv);
    return max(mix(a, b, th), 0.0) * ph.colour.w;
}

/// The coordinate along which solid angle is uniform within a cell: -cos(gamma) (type C) or
/// sin(V) (type B), rising with the vertical angle.
float phAreaCoordinate(float vertical) { return ph.dims.w == 1 ? sin(vertical) : -cos(vertical); }

/// Probability per steradian of phTableSample at the unit local direction d: the cell's share
/// of the CDF over its solid angle (luminaires/photometric/IntensitySampler.cpp, from the same floats).
float phTablePdf(vec3 d) {
    if (ph.samples.z == 0) return 0.0;
    float vertical, horizontal;
    phAngles(d, vertical, horizontal);
    int nv = ph.dims.x, nh = ph.dims.y, iv, ih;
    float tv, th;
    if (nv < 2 || nh < 2 || !phCell(ph.offsets.x, nv, vertical, iv, tv) || !phCell(ph.offsets.y, nh, horizontal, ih, th))
        return 0.0;
    iv = min(iv, nv - 2);
    ih = min(ih, nh - 2);
    int cell = ih * (nv - 1) + iv;
    float share = phCellCdf(cell + 1) - phCellCdf(cell);
    float omega = (phAreaCoordinate(phFloats[ph.offsets.x + iv + 1]) - phAreaCoordinate(phFloats[ph.offsets.x + iv])) *
                  (phFloats[ph.offsets.y + ih + 1] - phFloats[ph.offsets.y + ih]);
    return omega > 0.0 ? share / omega : 0.0;
}

/// A unit local direction drawn in proportion to the table's intensity (IntensitySampler):
/// the cell by its CDF, then uniform in solid angle within it.
vec3 phTableSample(float pick, vec2 u) {
    int nv = ph.dims.x, nh = ph.dims.y;
    int lo = 0, hi = (nv - 1) * (nh - 1) - 1;
    while (lo < hi) {  // the first cell whose upper CDF exceeds pick
        int mid = (lo + hi) / 2;
        if (phCellCdf(mid + 1) > pick) hi = mid;
        else lo = mid + 1;
    }
    int ih = lo / (nv - 1), iv = lo - ih * (nv - 1);
    float a0 = phAreaCoordinate(phFloats[ph.offsets.x + iv]), a1 = phAreaCoordinate(phFloats[ph.offsets.x + iv + 1]);
    float a = mix(a0, a1, u.x);
    float az = mix(phFloats[ph.offsets.y + ih], phFloats[ph.offsets.y + ih + 1], u.y);
    if (ph.dims.w == 1) {
        float sinV = clamp(a, -1.0, 1.0), cosV = sqrt(max(0.0, 1.0 - sinV * sinV));
        return vec3(cosV * sin(az), sinV, cosV * cos(az));
    }
    float cosG = clamp(-a, -1.0, 1.0), sinG = sqrt(max(0.0, 1.0 - cosG * cosG));
    return vec3(sinG * cos(az), sinG * sin(az), cosG);
}

// --- Receiver setup -----------------------------------------------------------------------------

vec3 phToLocal(vec3 v) { return vec3(dot(v, ph.axisX.xyz), dot(v, ph.axisY.xyz), dot(v, ph.axisZ.xyz)); }
vec3 phFromLocal(vec3 v) { return v.x * ph.axisX.xyz + v.y * ph.axisY.xyz + v.z * ph.axisZ.xyz; }
vec2 phCorner(int i) { return vec2(phFloats[ph.offsets.w + 2 * i], phFloats[ph.offsets.w + 2 * i + 1]); }

/// Point-source irradiance at local p (unit normal n) from local opening point q.
float phPointIrradiance(vec3 p, vec3 n, vec3 q) {
    vec3 v = q - p;
    float r2 = dot(v, v);
    if (!(r2 > 0.0)) return 0.0;
    float r = sqrt(r2);
    float c = dot(n, v) / r;
    if (!(c > 0.0)) return 0.0;
    return phIntensity(-v / r) * c / r2;
}

/// L(w) cos(theta_p) along the unit direction d from the receiver, L = I / (A |cos theta_L|).
float phIntegrand(vec3 n, vec3 d) {
    float c = dot(n, d), cosL = abs(d.z);
    if (!(c > 0.0) || !(cosL > 1e-7) || !(ph.position.w > 0.0)) return 0.0;
    return phIntensity(-d) * c / (ph.position.w * cosL);
}

/// Zero-area openings: a point (the point law) or a segment: the point law averaged along it,
/// integrated over the angle seen from the receiver (x = d tan(theta) from the foot of the
/// perpendicular: smooth however close; PhotometricEstimators.cpp), 16-point Gauss-Legendre on
/// each side of the foot.
bool phDegenerate(vec3 p, vec3 n, out float e) {
    e = 0.0;
    int corners = ph.dims.z;
    if (corners >= 3) return false;
    if (corners == 0) {
        e = phPointIrradiance(p, n, vec3(0.0));
        return true;
    }
    vec3 a = vec3(phCorner(0), 0.0), b = vec3(phCorner(1), 0.0);
    float len = length(b - a);
    if (!(len > 0.0)) return true;
    vec3 axis = (b - a) / len;
    float foot = dot(p - a, axis);
    float d = length(a + foot * axis - p);
    if (!(d > 0.0)) return true;
    float t0 = atan(-foot, d), t1 = atan(len - foot, d), split = clamp(0.0, t0, t1);
    for (int half_ = 0; half_ < 2; ++half_) {
        float lo = half_ == 0 ? t0 : split, hi = half_ == 0 ? split : t1;
        if (!(hi > lo)) continue;
        for (int i = 0; i < 16; ++i) {
            float sgn = i < 8 ? -1.0 : 1.0;
            float x = sgn * kGaussLegendre16Node[i % 8], w = kGaussLegendre16Weight[i % 8];
            float theta = 0.5 * (lo + hi) + 0.5 * x * (hi - lo), c = cos(theta);
            vec3 q = a + (foot + d * tan(theta)) * axis;
            e += 0.5 * w * (hi - lo) * phPointIrradiance(p, n, q) * d / (c * c) / len;
        }
    }
    return true;
}

bool phInside(vec2 q) {
    int corners = ph.dims.z;
    for (int i = 0; i < corners; ++i) {
        vec2 a = phCorner(i), e = phCorner((i + 1) % corners) - a;
        if (e.x * (q.y - a.y) - e.y * (q.x - a.x) < 0.0) return false;
    }
    return true;
}

void phBounds(out vec2 lo, out vec2 hi) {
    lo = vec2(1e30);
    hi = vec2(-1e30);
    for (int i = 0; i < ph.dims.z; ++i) {
        lo = min(lo, phCorner(i));
        hi = max(hi, phCorner(i));
    }
}

/// Area form with the fixed Poisson set at float offset o (count points): the mean over the
/// points inside the opening of I cos / r^2.
float phPoisson(vec3 p, vec3 n, int o, int count) {
    vec2 lo, hi;
    phBounds(lo, hi);
    float sum = 0.0;
    int inside = 0;
    for (int i = 0; i < count; ++i) {
        vec2 q = lo + vec2(phFloats[o + 2 * i], phFloats[o + 2 * i + 1]) * (hi - lo);
        if (!phInside(q)) continue;
        sum += phPointIrradiance(p, n, vec3(q, 0.0));
        ++inside;
    }
    return inside > 0 ? sum / float(inside) : 0.0;
}

// --- Spherical polygons (luminaires/SphericalPolygon.cpp) ----------------------------------------

struct PhPolygon {
    vec3 v[kMaxPolygon];
    int count;
};

PhPolygon phOpening(vec3 p) {
    PhPolygon q;
    q.count = min(ph.dims.z, kMaxPolygon);
    for (int i = 0; i < q.count; ++i) q.v[i] = vec3(phCorner(i), 0.0) - p;
    return q;
}

PhPolygon phClip(PhPolygon a, vec3 normal) {
    PhPolygon out_;
    out_.count = 0;
    for (int i = 0; i < a.count; ++i) {
        vec3 u = a.v[i], w = a.v[(i + 1) % a.count];
        float du = dot(normal, u), dw = dot(normal, w);
        if (du >= 0.0 && out_.count < kMaxPolygon) out_.v[out_.count++] = u;
        if ((du >= 0.0) != (dw >= 0.0) && out_.count < kMaxPolygon) out_.v[out_.count++] = u + (w - u) * (du / (du - dw));
    }
    if (out_.count < 3) out_.count = 0;
    return out_;
}

float phTriangleSolidAngle(vec3 a, vec3 b, vec3 c) {
    float la = length(a), lb = length(b), lc = length(c);
    if (!(la > 0.0 && lb > 0.0 && lc > 0.0)) return 0.0;
    a /= la;
    b /= lb;
    c /= lc;
    float num = abs(dot(a, cross(b, c)));
    float den = 1.0 + dot(a, b) + dot(b, c) + dot(c, a);
    return 2.0 * atan(num, den);
}

float phSolidAngle(PhPolygon q) {
    float sum = 0.0;
    for (int i = 1; i + 1 < q.count; ++i) sum += phTriangleSolidAngle(q.v[0], q.v[i], q.v[i + 1]);
    return sum;
}

float phProjectedSolidAngle(PhPolygon q, vec3 m) {
    float sum = 0.0;
    for (int i = 0; i < q.count; ++i) {
        vec3 a = q.v[i], b = q.v[(i + 1) % q.count];
        vec3 c = cross(a, b - a);  // = a x b, with the digits of a short edge (as the C++ twin)
        float lc = length(c);
        if (!(lc > 0.0)) continue;
        sum += atan(lc, dot(a, b)) * dot(m, c) / lc;
    }
    // At most the whole hemisphere, pi: at contact (the opening filling the hemisphere) float
    // rounding of the clipped polygon's angles otherwise gave up to 1 % more.
    return min(0.5 * abs(sum), kPi);
}

const int PH_INSIDE = 0;
const int PH_EDGE = 1;
const int PH_CORNER = 2;

/// Closest point of q to `target` (a point in q's plane, receiver-relative); place and index as
/// spherical::closestPoint.
vec3 phClosest(PhPolygon q, vec3 target, float tolerance, out int place, out int index) {
    place = PH_INSIDE;
    index = 0;
    vec3 normal = vec3(0.0);
    for (int i = 0; i < q.count; ++i) normal += cross(q.v[i] - target, q.v[(i + 1) % q.count] - target);
    float ln = length(normal);
    if (ln > 0.0 && q.count >= 3) {
        normal /= ln;
        vec3 foot = target + dot(q.v[0] - target, normal) * normal;
        float clearance = 1e30;
        for (int i = 0; i < q.count; ++i) {
            vec3 a = q.v[i], e = q.v[(i + 1) % q.count] - a;
            float le = length(e);
            if (!(le > 0.0)) continue;
            clearance = min(clearance, dot(cross(e, foot - a), normal) / le);
        }
        if (clearance > tolerance) return foot;
    }
    float best = 1e30;
    vec3 point = q.count > 0 ? q.v[0] : vec3(0.0);
    for (int i = 0; i < q.count; ++i) {
        vec3 a = q.v[i], e = q.v[(i + 1) % q.count] - a;
        float le2 = dot(e, e);
        float t = le2 > 0.0 ? clamp(dot(target - a, e) / le2, 0.0, 1.0) : 0.0;
        vec3 c = a + t * e;
        float d = length(c - target);
        if (!(d < best)) continue;
        best = d;
        float le = sqrt(le2);
        point = c;
        index = i;
        place = PH_EDGE;
        if (t * le <= tolerance) {
            place = PH_CORNER;
            point = a;
        } else if ((1.0 - t) * le <= tolerance) {
            place = PH_CORNER;
            index = (i + 1) % q.count;
            point = q.v[index];
        }
    }
    return point;
}

bool phInCircumcircle(vec3 a, vec3 b, vec3 c, vec3 d) {
    vec3 nrm = cross(b - a, c - a);
    float ln = length(nrm);
    if (!(ln > 0.0)) return false;
    float centre = -dot(nrm, a);
    float point = dot(nrm, d - a);
    return (centre > 0.0 ? -point : point) > 1e-6 * ln;
}

float phSide(vec3 a, vec3 b, vec3 c) { return dot(cross(a, b), c); }

/// The initial triangulation of scattered sampling (Prost Fig. 5.8) over the polygon q seen from
/// the receiver, with vertex 0 the closest point (place, index as phClosest) and 1..k the
/// corners, made Delaunay by Lawson's flips (Alg. 5.1, bounded like the CPU version) when asked.
/// Returns the number of triangles.
int phTriangulate(int k, int place, int index, vec3 dirs[kMaxPolygon + 1], bool delaunay,
                  out ivec3 tri[2 * kMaxPolygon], inout int flips) {
    int count = 0;
    if (place == PH_CORNER) {
        for (int j = 1; j + 1 < k; ++j)
            tri[count++] = ivec3(1 + index, 1 + (index + j) % k, 1 + (index + j + 1) % k);
    } else {
        for (int i = 0; i < k; ++i)
            if (!(place == PH_EDGE && i == index)) tri[count++] = ivec3(0, 1 + i, 1 + (i + 1) % k);
    }
    bool changed = delaunay;
    while (changed && flips < 4 * kMaxPolygon) {
        changed = false;
        for (int i = 0; i < count && !changed; ++i) {
            for (int e = 0; e < 3 && !changed; ++e) {
                int a = tri[i][e], b = tri[i][(e + 1) % 3], cc = tri[i][(e + 2) % 3];
                for (int j = 0; j < count; ++j) {
                    if (j == i) continue;
                    ivec3 o = tri[j];
                    bool hasA = o.x == a || o.y == a || o.z == a;
                    bool hasB = o.x == b || o.y == b || o.z == b;
                    if (!hasA || !hasB) continue;
                    int d = (o.x != a && o.x != b) ? o.x : ((o.y != a && o.y != b) ? o.y : o.z);
                    if (!phInCircumcircle(dirs[a], dirs[b], dirs[cc], dirs[d])) break;
                    bool convex = phSide(dirs[a], dirs[b], dirs[cc]) * phSide(dirs[a], dirs[b], dirs[d]) < 0.0 &&
                                  phSide(dirs[cc], dirs[d], dirs[a]) * phSide(dirs[cc], dirs[d], dirs[b]) < 0.0;
                    if (!convex) break;
                    tri[i] = ivec3(a, d, cc);
                    tri[j] = ivec3(d, b, cc);
                    ++flips;
                    changed = true;
                    break;
                }
            }
        }
    }
    return count;
}

/// Scattered sampling (Prost Ch. 5): corners of the opening clipped at the tilted horizon plus
/// the closest point, Delaunay triangulation by flips, cubature (5.6) of the cosine-weighted
/// mean of L, times the closed-form projected solid angle (5.11).
float phScattered(vec3 p, vec3 n, out int flips) {
    flips = 0;
    PhPolygon full = phOpening(p);
    PhPolygon visible = phClip(full, n);
    if (visible.count < 3) return 0.0;
    float projected = phProjectedSolidAngle(visible, n);
    if (!(projected > 0.0)) return 0.0;
    float eps = ph.axisY.w;
    vec3 tilted = abs(p.z) * n + (p.z >= 0.0 ? 1.0 : -1.0) * eps * vec3(0.0, 0.0, 1.0);
    PhPolygon q = phClip(full, tilted);
    if (q.count < 3) q = visible;
    int place, index;
    vec3 cp = phClosest(q, vec3(0.0), 1e-6 * ph.axisX.w, place, index);

    const int V = kMaxPolygon + 1;
    vec3 dirs[V];
    float f[V], c[V];
    int k = q.count;
    for (int i = 0; i <= k; ++i) {
        vec3 v = i == 0 ? cp : q.v[i - 1];
        float lv = length(v);
        dirs[i] = lv > 0.0 ? v / lv : vec3(0.0, 0.0, 1.0);
        f[i] = phIntegrand(n, dirs[i]);
        c[i] = max(dot(n, dirs[i]), 0.0);
    }
    ivec3 tri[2 * kMaxPolygon];
    int count = phTriangulate(k, place, index, dirs, true, tri, flips);
    float qf = 0.0, qc = 0.0;
    for (int i = 0; i < count; ++i) {
        ivec3 t = tri[i];
        float area = phTriangleSolidAngle(dirs[t.x], dirs[t.y], dirs[t.z]);
        qf += area * (f[t.x] + f[t.y] + f[t.z]) / 3.0;
        qc += area * (c[t.x] + c[t.y] + c[t.z]) / 3.0;
    }
    return qc > 0.0 ? projected * qf / qc : 0.0;
}

// --- The adaptive technique (PhotometricEstimators.cpp, adaptiveValue) ---------------------------

/// A point of the cubature on the plane of its initial triangle's unit corners: p, its direction
/// d, f = L cos_p and c = cos_p there.
struct PhVertex {
    vec3 p, d;
    float f, c;
};

PhVertex phVertex(vec3 n, vec3 p) {
    float l = length(p);
    vec3 d = l > 0.0 ? p / l : vec3(0.0, 0.0, 1.0);
    return PhVertex(p, d, phIntegrand(n, d), max(dot(n, d), 0.0));
}

/// The vertex rule on the spherical triangle xyz: solid angle times the means of f and c.
vec2 phVertexRule(PhVertex x, PhVertex y, PhVertex z) {
    float area = phTriangleSolidAngle(x.d, y.d, z.d);
    return area * vec2(x.f + y.f + z.f, x.c + y.c + z.c) / 3.0;
}

// The cubature's triangles: their three corners (points, as PhVertex::p), and (x, y, z) = their
// children's vertex rule of f and c and its error estimate. Private to each invocation, at most
// kAdaptiveGpuTriangles of them; a split evaluates its triangle's corners and midpoints again
// rather than keep them (the shader compiler's time grows with this memory).
vec3 phTriCorner[3 * kAdaptiveGpuTriangles];
vec3 phTriFine[kAdaptiveGpuTriangles];

/// Scattered sampling on the opening clipped at the true horizon, its worst spherical triangle
/// split at its flat edges' midpoints until the estimated errors sum to kAdaptiveTolerance of
/// the value or kAdaptiveGpuSplits splits are spent; times the closed-form projected solid angle.
/// One loop stores every triangle, the initial ones and each split's four children, and one
/// evaluates every point: the shader compiler inlines every call, and one intensity lookup site
/// keeps llvmpipe's compile in seconds.
float phAdaptive(vec3 p, vec3 n) {
    PhPolygon visible = phClip(phOpening(p), n);
    if (visible.count < 3) return 0.0;
    float projected = phProjectedSolidAngle(visible, n);
    if (!(projected > 0.0)) return 0.0;
    int place, index;
    vec3 cp = phClosest(visible, vec3(0.0), 1e-6 * ph.axisX.w, place, index);
    const int V = kMaxPolygon + 1;
    vec3 dirs[V];
    int k = visible.count;
    for (int i = 0; i <= k; ++i) {
        vec3 v = i == 0 ? cp : visible.v[i - 1];
        float lv = length(v);
        dirs[i] = lv > 0.0 ? v / lv : vec3(0.0, 0.0, 1.0);
    }
    ivec3 tri[2 * kMaxPolygon];
    int flips = 0;
    int initial = phTriangulate(k, place, index, dirs, false, tri, flips);  // the fan: see the CPU
    // A triangle's six points: corners a, b, c, then midpoints ab, bc, ca; its children as
    // indices into them (CubatureTriangle::children).
    const ivec3 kChild[4] = ivec3[4](ivec3(0, 3, 5), ivec3(3, 1, 4), ivec3(5, 4, 2), ivec3(3, 4, 5));
    PhVertex parent[6];
    int stored = 0, next = 0, child = 4, worst = 0, splits = 0;
    float sumF = 0.0, sumError = 0.0;
    for (;;) {
        // The triangle to store: its corners' points, and which of them need evaluating.
        vec3 corner[3];
        int slot;
        bool evaluate = true;
        if (next < initial) {  // the initial triangulation's next triangle
            corner[0] = dirs[tri[next].x];
            corner[1] = dirs[tri[next].y];
            corner[2] = dirs[tri[next].z];
            slot = stored++;
            ++next;
        } else if (child < 4) {  // the next child of the triangle being split
            slot = child == 0 ? worst : stored++;
            evaluate = false;
        } else {  // every triangle stored: split the worst, or stop
            if (splits >= kAdaptiveGpuSplits || !(sumError > kAdaptiveTolerance * sumF) ||
                stored + 3 > kAdaptiveGpuTriangles)
                break;
            worst = 0;
            for (int i = 1; i < stored; ++i)
                if (phTriFine[i].z > phTriFine[worst].z) worst = i;
            for (int j = 0; j < 6; ++j) {
                vec3 q = j < 3 ? phTriCorner[3 * worst + j]
                               : 0.5 * (phTriCorner[3 * worst + j - 3] + phTriCorner[3 * worst + (j - 2) % 3]);
                parent[j] = phVertex(n, q);
            }
            sumF -= phTriFine[worst].x;
            sumError -= phTriFine[worst].z;
            child = 0;
            ++splits;
            continue;
        }
        PhVertex t[6];
        if (!evaluate) {
            ivec3 c = kChild[child];
            t[0] = parent[c.x];
            t[1] = parent[c.y];
            t[2] = parent[c.z];
            ++child;
        }
        // The corners (an initial triangle's), then the edges' midpoints.
        for (int e = evaluate ? 0 : 3; e < 6; ++e)
            t[e] = phVertex(n, e < 3 ? corner[e] : 0.5 * (t[e - 3].p + t[(e - 2) % 3].p));
        vec2 coarse = phVertexRule(t[0], t[1], t[2]);
        vec2 fine = vec2(0.0);
        for (int j = 0; j < 4; ++j) fine += phVertexRule(t[kChild[j].x], t[kChild[j].y], t[kChild[j].z]);
        for (int j = 0; j < 3; ++j) phTriCorner[3 * slot + j] = t[j].p;
        phTriFine[slot] = vec3(fine, abs(fine.x - coarse.x));
        sumF += fine.x;
        sumError += phTriFine[slot].z;
    }
    float qf = 0.0, qc = 0.0;
    for (int i = 0; i < stored; ++i) {
        qf += phTriFine[i].x;
        qc += phTriFine[i].y;
    }
    return qc > 0.0 ? projected * qf / qc : 0.0;
}

/// The opening's radiance along the unit direction d from the receiver, I / (A |cos theta_L|).
float phRadiance(vec3 d) {
    float cosL = abs(d.z);
    if (!(cosL > 1e-7) || !(ph.position.w > 0.0)) return 0.0;
    return phIntensity(-d) / (ph.position.w * cosL);
}

/// Corners and barycentre: their cosine-weighted mean of L times the closed-form projected solid
/// angle (PhotometricEstimators.cpp, structuredValue).
float phStructured(vec3 p, vec3 n) {
    PhPolygon visible = phClip(phOpening(p), n);
    if (visible.count < 3) return 0.0;
    vec3 centre = vec3(0.0);
    float sumF = 0.0, sumC = 0.0;
    for (int i = 0; i < visible.count; ++i) {
        centre += visible.v[i];
        vec3 d = normalize(visible.v[i]);
        sumF += phIntegrand(n, d);
        sumC += max(0.0, dot(n, d));
    }
    vec3 dc = normalize(centre / float(visible.count));
    sumF += phIntegrand(n, dc);
    sumC += max(0.0, dot(n, dc));
    return sumC > 0.0 ? phProjectedSolidAngle(visible, n) * sumF / sumC : 0.0;
}

float phMrp(vec3 p, vec3 n) {
    PhPolygon visible = phClip(phOpening(p), n);
    if (visible.count < 3) return 0.0;
    float tol = 1e-6 * ph.axisX.w;
    int place, index;
    vec3 pc = phClosest(visible, vec3(0.0), tol, place, index);
    float h = -p.z;
    vec3 pn = pc;
    if (abs(n.z) > 1e-7 && h / n.z > 0.0) pn = phClosest(visible, (h / n.z) * n, tol, place, index);
    vec3 half_ = normalize(pc) + normalize(pn);
    vec3 pm = pc;
    if (abs(half_.z) > 1e-7 && h / half_.z > 0.0) pm = phClosest(visible, (h / half_.z) * half_, tol, place, index);
    float lm = length(pm);
    if (!(lm > 0.0)) return 0.0;
    // The radiance there times the closed-form projected solid angle (PhotometricEstimators.cpp).
    return phProjectedSolidAngle(visible, n) * phRadiance(pm / lm);
}
