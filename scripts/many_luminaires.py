#!/usr/bin/env python3
"""Writes a scene of N recessed downlights (the shipped halo-recessed-downlight.ies) on a 1 m
square pitch at 2.79 m, centred on the origin, for the many-luminaire checks of docs/limits.md.
With --floor, a floor plane under them (reflectance 0.2); without, no geometry at all.

    python3 scripts/many_luminaires.py N OUT.json [--floor]
"""
import json
import math
import os
import sys


def main():
    args = [a for a in sys.argv[1:] if a != "--floor"]
    if len(args) != 2:
        sys.exit(__doc__)
    count, out = int(args[0]), args[1]
    ies = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "resources", "luminaires",
                                       "photometric", "halo-recessed-downlight.ies"))
    side = math.ceil(math.sqrt(count))
    luminaires = [{"type": "photometric", "name": "Downlight %d" % (i + 1), "file": ies,
                   "position": [i % side - side / 2, 2.79, i // side - side / 2],
                   "aim": [0, -1, 0], "c0": [1, 0, 0]} for i in range(count)]
    geometry = []
    if "--floor" in sys.argv[1:]:
        geometry.append({"name": "Floor", "albedo": [0.2, 0.2, 0.2],
                         "plane": {"center": [0, 0, 0], "normal": [0, 1, 0],
                                   "size": [side + 2, side + 2]}})
    with open(out, "w") as f:
        json.dump({"geometry": geometry, "luminaires": luminaires}, f)


if __name__ == "__main__":
    main()
