#!/usr/bin/env bash
# Installs what vsil needs on Debian bookworm (as root, or with sudo), then configures and
# builds into build/. Safe to run again: apt-get skips what is installed, cmake rebuilds little.
# Environment: VSIL_BUILD_DIR (default build), VSIL_CMAKE_ARGS (extra cmake arguments),
# VSIL_EXTRA_PACKAGES (more Debian packages, e.g. clang for scripts/fuzz.sh), VSIL_SHARED_DIR
# (the folder holding datasets/, default ../shared beside the checkout), VSIL_BUILD_TYPE,
# VSIL_CONFIGURE_ONLY=1 (install and configure, build nothing), VSIL_UNITY_BUILD (default ON:
# a first build in about half the time; OFF for many small rebuilds, where ccache pays more).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ make pkg-config      # the build
  libegl-dev libegl-mesa0 libgl1-mesa-dri  # headless EGL: headers, Mesa's EGL driver, llvmpipe
  libosmesa6-dev                 # OSMesa (Mesa llvmpipe; Mesa 25.1 dropped it: optional below)
  libfftw3-dev                   # FFT Gaussian broadening
  libpng-dev                     # PNG files in and out
  libopencv-core-dev libopencv-imgproc-dev  # images in memory, distance transforms
  libopencv-imgcodecs-dev        # the tests: OpenCV's image files, checked against (not in vsil)
  libopencv-videoio-dev          # vsil animate --video (OpenCV's video writer, FFmpeg)
  libglm-dev                     # vector and matrix math
  nlohmann-json3-dev             # JSON (metadata, benchmark tables)
  libcli11-dev                   # command-line parsing
  libtinyxml2-dev zlib1g-dev     # VTK XML (.vti) files, zlib/gzip payloads
  libdeflate-dev                 # VTI zlib blocks, inflated faster than by zlib
  liblz4-dev liblzma-dev         # VTI files compressed with LZ4 or LZMA
  libnifti2-dev                  # NIfTI-1/-2 files (nifticlib)
  libgdcm-dev                    # DICOM series (GDCM)
  libgtest-dev libbenchmark-dev  # tests and micro-benchmarks
  python3-dev pybind11-dev       # the Python module (src/python)
  python3-numpy python3-pytest python3-pil  # its tests (tests/python; Pillow reads the CLI's PNGs)
  python3-venv python3-setuptools python3-wheel  # pip install . without a package index (pyproject.toml)
  python3-nibabel python3-pydicom  # reference writers for the NIfTI and DICOM round trips
  libcpp-httplib-dev             # vsil serve's HTTP server
  chromium chromium-driver python3-selenium  # vsil serve's browser test drives the page headless
  libopenmpi-dev openmpi-bin     # MPI: slab-parallel render under mpirun, vsil sweep (optional)
  ${VSIL_EXTRA_PACKAGES:-}
)
# vsil needs one GL back end (EGL or OSMesa) and builds each one that is there; where Debian no
# longer has OSMesa, the build goes on with EGL alone.
optional=(libosmesa6-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=(); [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  installable=()
  for p in "${missing[@]}"; do
    if [[ " ${optional[*]} " == *" $p "* ]] && ! apt-cache show "$p" >/dev/null 2>&1; then
      echo "bootstrap: $p is not in this Debian release: building without it" >&2
      continue
    fi
    installable+=("$p")
  done
  if ((${#installable[@]})); then
    echo "bootstrap: installing ${installable[*]}" >&2
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${installable[@]}" >&2
  fi
fi

build_dir=${VSIL_BUILD_DIR:-build}
shared_args=()
[[ -n ${VSIL_SHARED_DIR:-} ]] && shared_args=(-DVSIL_SHARED_DIR="$VSIL_SHARED_DIR")
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE="${VSIL_BUILD_TYPE:-RelWithDebInfo}" \
  -DCMAKE_UNITY_BUILD="${VSIL_UNITY_BUILD:-ON}" "${shared_args[@]}" ${VSIL_CMAKE_ARGS:-} >&2
[[ ${VSIL_CONFIGURE_ONLY:-0} == 1 ]] || cmake --build "$build_dir" -j"$(nproc)" >&2
