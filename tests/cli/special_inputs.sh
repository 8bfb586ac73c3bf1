#!/usr/bin/env bash
# Every kind of input refuses what is not a regular file, and a file over its limit, at once:
# a FIFO (open() would wait for a writer for ever), /dev/zero behind a symbolic link (read until
# memory ran out), a folder, and a 1 GiB sparse file, given as a scene, photometry (IES, LDT,
# TM-33) and an IES file's TILT file, GLDF, L3D, glTF and a buffer it names, a light field and
# an image it names, an environment map and a frame of an environment sequence, probe points and
# a TM-25 ray file. Each must exit 1 with a message naming the file and what it is, and peak
# memory at most 100 MB above `candela info` on a small valid file (no read of the whole thing).
# A run that waits is stopped after 60 s and fails (the refusals take well under a second).
set -uo pipefail
binary=$1
tests=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0

# The baseline: a small valid input's peak resident memory, in KB.
/usr/bin/time -o "$out/base.txt" -f "%M" "$binary" info "$tests/../resources/validation/isotropic.ies" >/dev/null 2>&1
base=$(tail -n 1 "$out/base.txt")
limit=$((base + 100 * 1024))

# special TYPE PATH: makes PATH a FIFO, a link to /dev/zero, a folder or a 1 GiB sparse file.
special() {
  mkdir -p "$(dirname "$2")"
  case $1 in
    fifo) mkfifo "$2" ;;
    zero) ln -s /dev/zero "$2" ;;
    folder) mkdir "$2" ;;
    sparse) truncate -s 1G "$2" ;;
  esac
}

# refuse TYPE NAME WORD -- ARGS: candela ARGS exits 1 within the time limit, naming NAME and WORD
# (what the file is), within the memory limit.
refuse() {
  local type=$1 name=$2 word=$3
  shift 4
  local err rc rss
  err=$(timeout 60 /usr/bin/time -o "$out/rss.txt" -f "%M" "$binary" "$@" 2>&1 >/dev/null)
  rc=$?
  rss=$(tail -n 1 "$out/rss.txt" 2>/dev/null || echo 0)
  if [ $rc -eq 1 ] && grep -qF -- "$name" <<<"$err" && grep -qF -- "$word" <<<"$err" &&
     [ "$rss" -le "$limit" ]; then
    passed=$((passed + 1))
  else
    failures=$((failures + 1))
    echo "FAIL: $type as $name: candela $* (exit $rc, peak $rss KB, limit $limit KB): $(tail -n 3 <<<"$err")"
  fi
}

for type in fifo zero folder sparse; do
  d="$out/$type"
  mkdir -p "$d"
  case $type in
    fifo) word="FIFO" ;;
    zero) word="character device" ;;
    folder) word="folder" ;;
    sparse) word="at most" ;;
  esac
  for name in s.json s.ies s.ldt s.xml s.gldf s.l3d s.gltf s.lf.json s.csv s.tm25ray s.tilt \
              s.bin s_img.exr s.exr seq/a.exr; do
    special "$type" "$d/$name"
  done
  # Files that name a special file.
  printf 'IESNA:LM-63-2002\nTILT=s.tilt\n1 1000 1 1 1 1 2 0 0 0\n1 1 0\n0\n0\n1000\n' >"$d/tilt.ies"
  sed 's/"tri.bin"/"s.bin"/' "$tests/data/gltf/triangle.gltf" >"$d/buf.gltf"
  python3 - "$tests/data/lightfield/tiny.lf.json" "$d/lf.lf.json" <<'PY'
import json, sys
lf = json.load(open(sys.argv[1]))
lf["images"] = ["s_img.exr"] * len(lf["images"])
json.dump(lf, open(sys.argv[2], "w"))
PY
  echo '{"environment": {"file": "s.exr"}}' >"$d/env.json"
  echo '{"environment": {"sequence": "seq/*.exr"}}' >"$d/seq.json"

  refuse $type s.json "$word" -- info "$d/s.json"
  refuse $type s.ies "$word" -- info "$d/s.ies"
  refuse $type s.ldt "$word" -- info "$d/s.ldt"
  refuse $type s.xml "$word" -- info "$d/s.xml"
  refuse $type s.tilt "$word" -- info "$d/tilt.ies"
  refuse $type s.gldf "$word" -- info "$d/s.gldf"
  refuse $type s.l3d "$word" -- info "$d/s.l3d"
  refuse $type s.gltf "$word" -- info "$d/s.gltf"
  refuse $type s.bin "$word" -- info "$d/buf.gltf"
  refuse $type s.lf.json "$word" -- info "$d/s.lf.json"
  refuse $type s_img.exr "$word" -- info "$d/lf.lf.json"
  refuse $type s.exr "$word" -- info "$d/env.json"
  refuse $type a.exr "$word" -- info "$d/seq.json"
  refuse $type s.csv "$word" -- probe "$tests/data/cli/ok.json" --points "$d/s.csv"
  # A TM-25 file is streamed (no size limit of its own): the sparse one fails on its first bytes.
  [ $type = sparse ] && tm25word="TM25" || tm25word=$word
  refuse $type s.tm25ray "$tm25word" -- convert "$d/s.tm25ray" --out "$out/o.lf.json"
done

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
