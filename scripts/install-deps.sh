#!/usr/bin/env bash
# Install the Debian 12 packages saarcor needs, skipping those already present.
# Used by `make run` and `make test` (target `deps`); safe to run repeatedly.
# Exit codes: 0 all present/installed, 1 install failed, 2 missing packages but no root/sudo.
set -euo pipefail

PACKAGES=(
  build-essential pkg-config python3  # toolchain, report scripts
  libmpfr-dev                        # correctly rounded reference for fp24 verification
  libcmocka-dev                      # unit-test framework
  libopenimageio-dev openimageio-tools  # image I/O, compare, idiff
  libpng-dev                         # PNG writing without OpenImageIO (host/image/img_png.c)
  libopenexr-dev                     # EXR writing without OpenImageIO (host/image/img_exr.c)
  libtinygltf-dev                    # glTF 2.0 scene loading (host/)
  libembree-dev                      # reference ray tracer (accuracy baseline)
  verilator iverilog yosys nextpnr-ice40 fpga-icestorm  # RTL simulation and synthesis
  valgrind gnuplot-nox               # instruction-count benchmarks, plots
  libopenmpi-dev openmpi-bin         # distributed render and sweeps (make mpi, render --mpi)
  clang libclang-rt-14-dev           # libFuzzer harnesses (make fuzz, tests/test_fuzz.sh)
)

missing=()
for p in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "deps: installing ${#missing[@]} missing package(s): ${missing[*]}"
SUDO=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then SUDO=(sudo); else
    echo "deps: error: not root and no sudo; install as root: apt-get install ${missing[*]}" >&2
    exit 2
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -qq || { echo "deps: error: apt-get update failed" >&2; exit 1; }
"${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/tmp/saarcor-apt.log 2>&1 \
  || { echo "deps: error: apt-get install failed (log: /tmp/saarcor-apt.log)" >&2; tail -5 /tmp/saarcor-apt.log >&2; exit 1; }
echo "deps: done"
