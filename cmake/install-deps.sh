#!/usr/bin/env bash
# Installs the Debian 12 packages Plenopath Studio needs; a no-op when all are present.
# Used by `make run`, `make test` and .ci/run. Add new dependencies here and nowhere else.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config clang clang-format libclang-rt-14-dev
  qtbase5-dev libqt5opengl5-dev libqt5svg5-dev
  libvtk9-qt-dev libvtk9-dev mpi-default-dev
  libopencv-dev opencv-data libavformat-dev libavcodec-dev libswscale-dev libavutil-dev
  libeigen3-dev libcgal-dev libceres-dev libgeographiclib-dev libdxflib-dev libexpat1-dev libexiv2-dev
  libarchive-dev unzip
  nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth x11-utils imagemagick gpsbabel ffmpeg libimage-exiftool-perl
  python3 python3-jsonschema python3-ezdxf povray povray-examples blender chromium fonts-dejavu-core fonts-wqy-microhei
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
