"""The renderer's camera model (lookAt + perspective, world Y-up) for the e2e scripts: where a
world point lands in an image whose JSON sidecar gives the camera and the render size."""
import math


def _sub(a, b): return [x - y for x, y in zip(a, b)]
def _dot(a, b): return sum(x * y for x, y in zip(a, b))
def _norm(a): return [x / math.sqrt(_dot(a, a)) for x in a]
def _cross(a, b): return [a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]]


def project(p, sidecar):
    """World point p (metres) -> image pixel (x right, y down, unrounded)."""
    cam = sidecar["camera"]
    w, h = sidecar["render_size"]
    f = _norm(_sub(cam["target"], cam["position"]))
    r = _norm(_cross(f, [0, 1, 0]))
    u = _cross(r, f)
    v = _sub(p, cam["position"])
    x, y, z = _dot(v, r), _dot(v, u), _dot(v, f)
    t = math.tan(math.radians(cam["fov_deg"]) / 2)
    return (x / (z * t * w / h) * 0.5 + 0.5) * w, (0.5 - y / (z * t) * 0.5) * h
