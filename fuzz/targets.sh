# The fuzz targets' inputs, sourced by fuzz/replay.sh and scripts/fuzz.sh from the repository root.
# Each function prints NUL-separated paths relative to the root.

FUZZ_TARGETS=(ies ldt tm25 lightfield scene gltf image gldf l3d tm33)

# Seeds: small files of the repository's test data (and fuzz/seeds/TARGET/ for what the test data
# lacks), so the fuzzer starts from inputs that load.
fuzz_seeds() {
  case $1 in
    ies) find tests/data/photometry tests/data/photometric tests/data/measure -iname '*.ies' -size -20k -print0 ;;
    ldt) find tests/data/photometry resources/luminaires -iname '*.ldt' -size -20k -print0 ;;
    tm25) find fuzz/seeds/tm25 -type f -print0 ;;
    lightfield) find tests/data/lightfield resources/luminaires -maxdepth 1 -name '*.lf.json' -size -20k -print0 ;;
    scene) find fuzz/seeds/scene tests/data/scenes tests/data/environment tests/data/photometric \
                tests/data/lightfield -name '*.json' ! -name '*.lf.json' -size -20k -print0 ;;
    gltf) find tests/data/gltf -name '*.gltf' -print0 ;;
    gldf) find tests/data/gldf fuzz/seeds/gldf -name '*.gldf' -size -30k -print0
          find fuzz/seeds/gldf -name '*.xml' -print0 ;;
    l3d) find fuzz/seeds/l3d -type f -print0 ;;
    tm33) find tests/data/tm33 fuzz/seeds/tm33 -name '*.xml' -print0 ;;
    image) find tests/data/environment tests/data/lightfield fuzz/seeds/image -name '*.exr' -size -20k -print0
           find fuzz/seeds/image -name '*.hdr' -print0 ;;
  esac
}

# Every crash fuzzing found (fixed since), kept as a test input.
fuzz_regressions() {
  [ -d "fuzz/regressions/$1" ] && find "fuzz/regressions/$1" -type f -print0 | sort -z
  return 0
}

# Largest input to try, bytes: a little above the largest seed (a TM-25 file's fixed part alone is
# 36 288 bytes).
fuzz_max_len() {
  case $1 in
    tm25) echo 40000 ;;
    ies|ldt|scene|lightfield|gltf) echo 20000 ;;
    image) echo 8192 ;;
    gldf) echo 30000 ;;  # the complete container is 20 838 bytes
    l3d) echo 30000 ;;   # the largest seed (example_004's structure.xml and OBJ) is 24 kB
    tm33) echo 60000 ;;  # the largest seed (example.ldt converted, 777 intensities) is 46 kB
  esac
}

# The libFuzzer dictionary of each target (keywords of the format), if any.
fuzz_dict() {
  case $1 in
    ies) echo fuzz/dict/ies.dict ;;
    ldt) echo fuzz/dict/ldt.dict ;;
    lightfield|scene|gltf|gldf|l3d|tm33) echo "fuzz/dict/$1.dict" ;;
    *) echo "" ;;
  esac
}
