#!/usr/bin/env python3
"""Packs Candela's binaries with the shared libraries they load into one archive for the lent GPU
machine (tools `device`), which has NVIDIA's driver but none of Debian's libraries and cannot fetch
any. OpenImageIO's full closure is over 500 MB (OpenCV, OpenVDB, FFmpeg, GDAL, LLVM through
OSMesa), far over what a call can carry, and none of that is reached by renders and benches, which
read EXR and write PNG: those libraries are replaced by stubs that define the symbols the packed
libraries import from them and abort, naming the symbol, if one is ever called.

Usage: scripts/device/make_bundle.py OUT.tar.xz NAME=BINARY...
  e.g. make_bundle.py .gpu/bundle.tar.xz candela=build/candela gltests=build/tests/candela_gltests
The archive holds bin/NAME (stripped) and lib/ (the libraries and stubs); glibc, libstdc++ and
the GL/EGL loaders are left to the machine.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

SYSTEM = re.compile(r"^(libc|libm|libdl|libpthread|librt|ld-linux-x86-64|libGL|libEGL|libGLX|"
                    r"libGLdispatch|libOpenGL|libstdc\+\+|libgcc_s)\.so")
STUB = re.compile(r"^(libOSMesa|libopencv_|libdcm|liboflog|libofstd|libavcodec|libavformat|"
                  r"libavutil|libswscale|libheif|libopenvdb|libraw_r)")


def run(*args):
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode:
        sys.exit(" ".join(args[:3]) + ": " + r.stderr[-2000:])
    return r.stdout


def needed(path):
    return re.findall(r"\(NEEDED\).*\[(.*)\]", run("readelf", "-d", path))


def library_paths():
    paths = {}
    for line in run("ldconfig", "-p").splitlines()[1:]:
        m = re.match(r"\s*(\S+) \((.*)\) => (\S+)", line)
        if m and "x86-64" in m.group(2):
            paths.setdefault(m.group(1), m.group(3))
    return paths


def undefined_symbols(path):
    """Names (without version) a file imports."""
    out = run("nm", "-D", "--undefined-only", path)
    return {line.split()[-1].split("@")[0] for line in out.splitlines() if line.strip()}


def write_stub(soname, real, wanted, folder):
    """A library named soname defining the symbols of `real` that `wanted` holds."""
    out = run("nm", "-D", "-S", "--defined-only", "--with-symbol-versions", real)
    functions, objects, versions = [], [], {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 4:
            _, size, kind, name = parts
        elif len(parts) == 3:
            size, (kind, name) = "1", parts[1:]
        else:
            continue
        base, _, version = name.partition("@")
        version = version.lstrip("@")
        if base not in wanted or kind in "U":
            continue
        if version:
            versions.setdefault(version, set()).add(base)
        if kind in "TtWiI":
            functions.append(base)
        else:
            objects.append((base, max(int(size, 16), 8)))
    src = ['#include <stdio.h>', '#include <stdlib.h>',
           'static void die(const char* s) { fprintf(stderr, "gpu bundle: stub %s called\\n", s);'
           ' abort(); }']
    for i, name in enumerate(sorted(set(functions))):
        # Constructors and destructors run from static initialisers (OpenImageIO registers
        # DCMTK's codecs at load): those do nothing; any other call aborts.
        # Version queries (OpenImageIO lists its libraries' versions at load) answer "0".
        if re.search(r"C[12]E|D[012]Ev", name):
            src.append(f'void f{i}(void) __asm__("{name}"); void f{i}(void) {{}}')
        elif "version" in name.lower():
            src.append(f'const char* f{i}(void) __asm__("{name}"); '
                       f'const char* f{i}(void) {{ return "0"; }}')
        else:
            src.append(f'void f{i}(void) __asm__("{name}"); '
                       f'void f{i}(void) {{ die("{soname}: {name}"); }}')
    for i, (name, size) in enumerate(sorted(set(objects))):
        src.append(f'char o{i}[{size}] __asm__("{name}") __attribute__((aligned(16)));')
    c = os.path.join(folder, soname + ".c")
    with open(c, "w") as f:
        f.write("\n".join(src) + "\n")
    args = ["cc", "-shared", "-fPIC", "-O0", "-o", os.path.join(folder, "lib", soname), c,
            "-Wl,-soname," + soname]
    if versions:
        script = os.path.join(folder, soname + ".map")
        with open(script, "w") as f:
            for version, names in versions.items():
                f.write(version + " { global: " + "; ".join(sorted(names)) + "; };\n")
        args.append("-Wl,--version-script=" + script)
    run(*args)
    return len(set(functions)) + len(set(objects))


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    archive, binaries = sys.argv[1], dict(a.split("=", 1) for a in sys.argv[2:])
    paths = library_paths()
    keep, stubs, seen = {}, set(), set()
    todo = list(binaries.values())
    while todo:
        for name in needed(todo.pop()):
            if name in seen or SYSTEM.match(name):
                continue
            seen.add(name)
            if STUB.match(name):
                stubs.add(name)
            else:
                keep[name] = paths[name]
                todo.append(paths[name])
    with tempfile.TemporaryDirectory() as folder:
        os.makedirs(os.path.join(folder, "lib"))
        os.makedirs(os.path.join(folder, "bin"))
        importers = list(binaries.values()) + list(keep.values())
        wanted = set().union(*(undefined_symbols(p) for p in importers))
        for name, path in keep.items():
            shutil.copy(path, os.path.join(folder, "lib", name))
            run("strip", "--strip-unneeded", os.path.join(folder, "lib", name))
        for name in sorted(stubs):
            n = write_stub(name, paths[name], wanted, folder)
            print(f"stub {name}: {n} symbols")
        for name, path in binaries.items():
            shutil.copy(path, os.path.join(folder, "bin", name))
            run("strip", os.path.join(folder, "bin", name))
        tmp = archive + ".tmp"
        run("tar", "-C", folder, "-cJf", tmp, "bin", "lib")
        os.replace(tmp, archive)
    print(f"{archive}: {len(keep)} libraries, {len(stubs)} stubs, "
          f"{os.path.getsize(archive) / 1e6:.1f} MB")


if __name__ == "__main__":
    main()
