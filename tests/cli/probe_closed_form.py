#!/usr/bin/env python3
"""Independent references for `candela probe` on a Lambertian rectangle (no code shared with
Candela): Howell's configuration factor for a receiver parallel to the rectangle, by corner
superposition, and, for tilted receivers, Gauss-Legendre quadrature of L cos cos / r^2 over the
part of the rectangle above the receiver's horizon (clipped, triangulated, subdivided).

Usage: probe_closed_form.py candela-binary workdir
Checks `analytic` to 1e-5 relative and `reference` to 0.5 % (and 4 standard errors)."""
import math
import subprocess
import sys

L = 10.0                          # radiance, W/(m2 sr), all channels
CENTRE = (0.0, 2.5, 0.0)          # the light: 1 x 0.5 m, width along x, height along z
HALF = (0.5, 0.25)
AIM = (0.0, -1.0, 0.0)

def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def add(a, b): return tuple(x + y for x, y in zip(a, b))
def mul(a, s): return tuple(x * s for x in a)
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def norm(a): return mul(a, 1.0 / math.sqrt(dot(a, a)))

def corner_factor(a, b, h):
    """Howell C-11: differential area parallel to a rectangle a x b, below one corner at h."""
    X, Y = a / h, b / h
    return (X / math.sqrt(1 + X * X) * math.atan(Y / math.sqrt(1 + X * X)) +
            Y / math.sqrt(1 + Y * Y) * math.atan(X / math.sqrt(1 + Y * Y))) / (2 * math.pi)

def parallel_irradiance(p):
    """Receiver facing up (towards the light), below the light's plane."""
    h = CENTRE[1] - p[1]
    def G(x, z):
        if x == 0 or z == 0:
            return 0.0
        return math.copysign(1, x) * math.copysign(1, z) * corner_factor(abs(x), abs(z), h)
    x0, x1 = CENTRE[0] - HALF[0] - p[0], CENTRE[0] + HALF[0] - p[0]
    z0, z1 = CENTRE[2] - HALF[1] - p[2], CENTRE[2] + HALF[1] - p[2]
    F = G(x1, z1) - G(x0, z1) - G(x1, z0) + G(x0, z0)
    return math.pi * L * F

def gauss_legendre(n):
    nodes, weights = [], []
    for i in range(1, n + 1):
        x = math.cos(math.pi * (i - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-15:
                break
        nodes.append(x)
        weights.append(2 / ((1 - x * x) * dp * dp))
    return nodes, weights

GL_N, GL_W = gauss_legendre(8)

def quad_triangle(f, a, b, c, depth):
    if depth > 0:
        ab, bc, ca = mul(add(a, b), 0.5), mul(add(b, c), 0.5), mul(add(c, a), 0.5)
        return (quad_triangle(f, a, ab, ca, depth - 1) + quad_triangle(f, ab, b, bc, depth - 1) +
                quad_triangle(f, ca, bc, c, depth - 1) + quad_triangle(f, ab, bc, ca, depth - 1))
    e1, e2 = sub(b, a), sub(c, a)
    cr = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
    area2 = math.sqrt(dot(cr, cr))
    total = 0.0
    for u, wu in zip(GL_N, GL_W):          # collapsed square -> triangle (Duffy)
        s = 0.5 * (u + 1)
        for v, wv in zip(GL_N, GL_W):
            t = 0.5 * (v + 1)
            q = add(a, add(mul(e1, s * (1 - t)), mul(e2, s * t)))
            total += wu * wv * 0.25 * s * f(q)
    return total * area2

def quadrature_irradiance(p, n):
    corners = [add(CENTRE, (sx * HALF[0], 0.0, sz * HALF[1]))
               for sx, sz in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    # Clip to the receiver's upper half-space (Sutherland-Hodgman, written for this test).
    d = [dot(n, sub(c, p)) for c in corners]
    poly = []
    for i in range(4):
        j = (i + 1) % 4
        if d[i] >= 0:
            poly.append(corners[i])
        if (d[i] >= 0) != (d[j] >= 0):
            t = d[i] / (d[i] - d[j])
            poly.append(add(corners[i], mul(sub(corners[j], corners[i]), t)))
    def f(q):
        w = sub(q, p)
        r2 = dot(w, w)
        cr = max(0.0, dot(n, w))
        ce = max(0.0, -dot(AIM, w))
        return L * cr * ce / (r2 * r2)
    total = 0.0
    for k in range(1, len(poly) - 1):
        total += quad_triangle(f, poly[0], poly[k], poly[k + 1], 4)
    return total

# 16 receivers: (point, normal, reference kind)
UP = (0.0, 1.0, 0.0)
cases = [
    ((0.0, 0.0, 0.0), UP, "parallel"),                 # below the centre, 2.5 m
    ((0.8, 0.0, 0.6), UP, "parallel"),
    ((5.0, 0.0, 3.0), UP, "parallel"),                 # far: grazing incidence (~24 deg elevation)
    ((40.0, 0.0, 0.0), UP, "parallel"),                # very far: 3.6 deg elevation
    ((0.1, 2.5 - 1e-3, 0.1), UP, "parallel"),          # 1 mm below the emitter
    ((1.0, 2.5 - 1e-3, 0.1), UP, "parallel"),          # near the light's plane, beside it
    ((0.7, 2.5 - 1e-6, 0.0), UP, "parallel"),          # 1 um from the plane, beside it
    ((0.0, 2.5 - 1e-6, 2.0), UP, "parallel"),
    ((0.0, 0.0, 0.0), norm((1.0, 1.0, 0.0)), "quad"),
    ((0.3, 1.0, -0.2), norm((0.2, 1.0, -0.7)), "quad"),
    ((3.0, 2.4, 0.0), (-1.0, 0.0, 0.0), "quad"),        # wall: light 0.1 m above, grazing
    ((0.0, 1.5, 0.0), norm((1.0, 0.05, 0.0)), "quad"),  # horizon cuts the light in half
    ((0.2, 2.0, 0.1), (0.0, 0.0, 1.0), "quad"),         # vertical receiver under the light
    ((2.0, 0.5, -1.0), norm((-1.0, 0.3, 0.5)), "quad"),
    ((0.0, 3.0, 0.0), UP, "zero"),                      # behind the emitter: exactly 0
    ((0.0, 0.0, 0.0), (0.0, -1.0, 0.0), "zero"),        # facing away: exactly 0
]

def run(binary, workdir, technique, spp):
    pts = workdir + "/points.csv"
    with open(pts, "w") as f:
        f.write("x,y,z,nx,ny,nz\n")
        for p, n, _ in cases:
            f.write(",".join(repr(v) for v in p + n) + "\n")
    out = subprocess.run([binary, "probe", workdir + "/scene.json", "--points", pts,
                          "--technique", technique, "--spp", str(spp)],
                         capture_output=True, text=True, check=True).stdout.splitlines()
    header = out[0].split(",")
    assert header[:7] == ["x", "y", "z", "nx", "ny", "nz", "E"], header
    rows = [dict(zip(header, map(float, line.split(",")))) for line in out[1:]]
    assert len(rows) == len(cases)
    return rows

def main():
    binary, workdir = sys.argv[1], sys.argv[2]
    with open(workdir + "/scene.json", "w") as f:
        f.write('{"geometry": [], "luminaires": [{"type": "lambertian-rect", "size": [1.0, 0.5],'
                ' "radiance": [10, 10, 10], "position": [0, 2.5, 0], "aim": [0, -1, 0],'
                ' "c0": [1, 0, 0]}], "camera": {"position": [0, 1, 5], "target": [0, 1, 0]}}')
    exact = []
    for p, n, kind in cases:
        exact.append(parallel_irradiance(p) if kind == "parallel" else
                     quadrature_irradiance(p, n) if kind == "quad" else 0.0)
    failures = 0
    analytic = run(binary, workdir, "analytic", 1)
    # 2^18 solid-angle samples: relative standard error well under 0.1 % for these receivers.
    reference = run(binary, workdir, "reference", 1 << 18)
    for (p, n, kind), e, a, r in zip(cases, exact, analytic, reference):
        # analytic: 1e-5 relative (the bound); 1e-12 W/m2 absolute where E = 0.
        ok_a = abs(a["E"] - e) <= 1e-5 * abs(e) + 1e-12
        # reference: 0.5 % relative and 4 standard errors (plus 1e-12 absolute for E = 0).
        ok_r = abs(r["E"] - e) <= 0.005 * abs(e) + 1e-12 and \
            abs(r["E"] - e) <= 4 * r["E_stderr"] + 1e-9 * abs(e) + 1e-12
        status = "ok" if ok_a and ok_r else "FAIL"
        failures += status == "FAIL"
        print(f"{status} p={p} n={tuple(round(v, 4) for v in n)} {kind}: exact {e:.9g} "
              f"analytic {a['E']:.9g} ({(a['E'] - e) / (e or 1):+.2e}) reference {r['E']:.9g} "
              f"({(r['E'] - e) / (e or 1):+.2e}, se {r['E_stderr']:.2g})")
    print(f"{len(cases) - failures} passed, {failures} failed")
    sys.exit(1 if failures else 0)

main()
