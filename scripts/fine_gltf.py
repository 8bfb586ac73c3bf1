#!/usr/bin/env python3
"""Writes a finely tessellated glTF model for the memory checks of docs/limits.md: a sphere of
radius R metres cut into about TRIANGLES triangles (a latitude-longitude grid), with its normals,
as OUT.gltf and OUT.bin, and a scene OUT.json that puts it on the office's floor.

    python3 scripts/fine_gltf.py OUT TRIANGLES [RADIUS]
"""
import array
import json
import math
import os
import sys


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    out, triangles = sys.argv[1], int(sys.argv[2])
    radius = float(sys.argv[3]) if len(sys.argv) == 4 else 0.5
    # Rings and segments of about 2:1, two triangles per grid square.
    rings = max(2, int(math.sqrt(triangles / 4)))
    segments = max(3, triangles // (2 * rings))
    positions, normals = array.array("f"), array.array("f")
    for j in range(rings + 1):
        theta = math.pi * j / rings
        st, ct = math.sin(theta), math.cos(theta)
        for i in range(segments + 1):
            phi = 2 * math.pi * i / segments
            n = (st * math.cos(phi), ct, st * math.sin(phi))
            normals.extend(n)
            positions.extend((radius * n[0], radius * n[1], radius * n[2]))
    indices = array.array("I")
    row = segments + 1
    for j in range(rings):
        for i in range(segments):
            a = j * row + i
            b, c, d = a + 1, a + row, a + row + 1
            # Counter-clockwise seen from outside.
            indices.extend((a, b, d, a, d, c))
    base = os.path.basename(out)
    blobs = [indices.tobytes(), positions.tobytes(), normals.tobytes()]
    with open(out + ".bin", "wb") as f:
        for b in blobs:
            f.write(b)
    count = len(positions) // 3
    lo = [-radius] * 3
    hi = [radius] * 3
    gltf = {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": base + ".bin", "byteLength": sum(len(b) for b in blobs)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(blobs[0])},
            {"buffer": 0, "byteOffset": len(blobs[0]), "byteLength": len(blobs[1])},
            {"buffer": 0, "byteOffset": len(blobs[0]) + len(blobs[1]), "byteLength": len(blobs[2])},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
            {"bufferView": 1, "componentType": 5126, "count": count, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 2, "componentType": 5126, "count": count, "type": "VEC3"},
        ],
        "meshes": [{"name": "Sphere", "primitives": [{"attributes": {"POSITION": 1, "NORMAL": 2}, "indices": 0, "material": 0}]}],
        "materials": [{"name": "Plaster", "pbrMetallicRoughness": {
            "baseColorFactor": [0.6, 0.6, 0.6, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    with open(out + ".gltf", "w") as f:
        json.dump(gltf, f)
    here = os.path.dirname(os.path.abspath(__file__))
    office = os.path.join(here, "..", "resources", "scenes", "office.json")
    with open(office) as f:
        scene = json.load(f)
    # The office's luminaires name their files relative to its folder: made absolute.
    for lum in scene.get("luminaires", []):
        if "file" in lum and not os.path.isabs(lum["file"]):
            lum["file"] = os.path.normpath(os.path.join(os.path.dirname(office), lum["file"]))
    scene["geometry"].append({"gltf": base + ".gltf",
                              "transform": {"translate": [1.5, radius, 0.8]}})
    with open(out + ".json", "w") as f:
        json.dump(scene, f, indent=1)
    print("wrote %s.gltf (%d triangles, %d vertices) and %s.json" % (out, len(indices) // 3, count, out))


if __name__ == "__main__":
    main()
