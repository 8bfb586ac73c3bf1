#!/usr/bin/env bash
# Installs Candela's build and test dependencies from Debian 12's packages (needs root or sudo).
set -euo pipefail
packages=(
  build-essential cmake pkg-config git python3
  libglfw3-dev libimgui-dev libglm-dev libtinygltf-dev libopenimageio-dev
  libosmesa6-dev libgl-dev libegl-dev libgtest-dev libbenchmark-dev nlohmann-json3-dev libembree-dev
  libzip-dev libpugixml-dev  # GLDF containers (formats/Gldf.h)
  libtinyobjloader-dev  # L3D geometry's OBJ parts (formats/L3d.h)
  libcairo2-dev  # the PDF report (report/Report.h)
  libcli11-dev  # the command line's parser (app/commands/Cli.h)
  poppler-utils  # pdftotext and pdftoppm: the report's test reads its pages
  xvfb xdotool imagemagick x11-utils mesa-utils clang-format gnuplot-nox
  fonts-dejavu-core openimageio-tools
  glslang-tools  # glslangValidator: every shader variant checked against GLSL 4.50 core
  clang libclang-rt-14-dev  # libFuzzer and the sanitizers of scripts/fuzz.sh
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
