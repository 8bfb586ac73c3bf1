#!/usr/bin/env python3
"""Checks that the source folders form layers: every #include "..." of Candela's own code points
at a file in its own folder or in a lower layer, never upward and never into a sibling of the
same layer. docs/architecture.md explains each layer. Also checks that only a luminaire kind's
own files know its class: no dynamic_cast, no cast to a kind's model class and no comparison of a
kind with its scene-file name anywhere else (code asks the registry, the adapters and the
LuminaireKind enum). Exits 1 listing every include or line that breaks a rule, 0 (and one line)
when there is none.

Usage: scripts/check-layout.py [--graph]   (--graph prints the folder graph as Graphviz dot)
"""
import re
import subprocess
import sys
from collections import defaultdict
from pathlib import Path

# Lowest first. A unit is a folder (every file below it that no longer prefix claims) or, where
# a file stands above its own folder's other files, that file's path without its extension.
LAYERS = [
    ["util", "shaders/shared"],                     # files, JSON, threads; CPU/GLSL constants
    ["formats"],                                    # photometric and geometry file formats
    ["luminaires"],                                 # the luminaire interface, shared maths
    ["luminaires/photometric", "luminaires/environment", "luminaires/lambertian"],
    ["luminaires/lightfield"],                      # its far field is a photometric table
    ["luminaires/Registry"],                        # every kind, by name, from scene entries
    ["scene"],                                      # the scene model, its file, ray queries
    ["calculation"],                                # grids, surfaces, glare, interreflection
    ["renderer"],                                   # OpenGL passes and techniques
    ["report"],                                     # PDF report, diagrams, comparison sheets
    ["ui"],                                         # the editor
    ["app"],                                        # the command line
]
# Headless commands stay out of the editor's folder: only the editor's own command includes it.
UI_USERS = {"app/main.cpp", "app/commands/Edit.cpp"}
CHECKED = ("util", "shaders", "formats", "luminaires", "scene", "calculation", "renderer",
           "report", "ui", "app")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
# A kind's own files: its folder, and the editor's panel that shows its details.
KIND_FILES = ("luminaires/photometric/", "luminaires/lightfield/", "luminaires/environment/",
              "luminaires/lambertian/", "ui/PhotometricPanel.cpp", "ui/LightFieldPanel.cpp")
MODELS = r"(PhotometricLuminaire|LightFieldLuminaire|LambertianRect|EnvironmentLight)"
KIND_NAMES = r'"(lambertian-rect|lightfield|photometric|environment)"'
KIND_KNOWLEDGE = [
    (re.compile(r"\bdynamic_cast\s*<"), "a dynamic_cast"),
    (re.compile(r"\bstatic_cast\s*<\s*(const\s+)?" + MODELS + r"\b"), "a cast to a kind's model"),
    (re.compile(r"\bkind\w*(\(\))?\s*[!=]=\s*" + KIND_NAMES), "a kind compared by name"),
    (re.compile(KIND_NAMES + r"\s*[!=]=\s*\w*kind"), "a kind compared by name"),
]


def unit_of(path):
    """The layer unit a repository path belongs to: the longest matching prefix."""
    stem = path.rsplit(".", 1)[0]
    best = None
    for layer in LAYERS:
        for u in layer:
            if (stem == u or path.startswith(u + "/")) and (best is None or len(u) > len(best)):
                best = u
    return best


def rank(u):
    return next(i for i, layer in enumerate(LAYERS) if u in layer)


def main():
    root = Path(__file__).resolve().parent.parent
    files = subprocess.check_output(["git", "ls-files", "*.h", "*.cpp"], cwd=root, text=True)
    problems, edges = [], defaultdict(int)
    for path in files.split():
        if not path.startswith(CHECKED):
            continue
        src = unit_of(path)
        if src is None:
            problems.append(f"{path}: in no layer (scripts/check-layout.py lists the folders)")
            continue
        for inc in INCLUDE.findall((root / path).read_text(errors="replace")):
            if not (root / inc).exists():
                continue  # a system or generated header
            dst = unit_of(inc)
            if dst is None:
                problems.append(f"{path}: includes {inc}, which is in no layer")
                continue
            if dst == src:
                continue
            edges[(src, dst)] += 1
            if rank(dst) > rank(src):
                problems.append(f"{path}: includes {inc}, a higher layer ({dst} above {src})")
            elif rank(dst) == rank(src):
                problems.append(f"{path}: includes {inc}, a sibling of the same layer ({dst})")
            if dst == "ui" and src == "app" and path not in UI_USERS:
                problems.append(f"{path}: a headless command includes the editor's {inc}")
        if not path.startswith(KIND_FILES):
            for number, line in enumerate((root / path).read_text(errors="replace").splitlines()):
                for pattern, what in KIND_KNOWLEDGE:
                    if pattern.search(line.split("//")[0]):
                        problems.append(f"{path}:{number + 1}: {what} outside the kind's files")
    if "--graph" in sys.argv:
        print("digraph layers {\n  rankdir=BT;")
        for (a, b), n in sorted(edges.items()):
            print(f'  "{a}" -> "{b}" [label={n}];')
        print("}")
        return 0
    for p in problems:
        print(p)
    if problems:
        print(f"check-layout: {len(problems)} include(s) out of layer order or kind knowledge "
              "outside a kind's files")
        return 1
    print(f"check-layout: {len(edges)} folder dependencies, all downward")
    return 0


if __name__ == "__main__":
    sys.exit(main())
