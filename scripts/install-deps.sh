#!/usr/bin/env bash
# Installs every Debian 12 package stochtex needs to build, test and run its demo.
# Idempotent; run as root on a fresh Debian 12 machine.  Usage: scripts/install-deps.sh [--with-blender]
set -euo pipefail
packages=(
  build-essential cmake pkg-config git
  libopenimageio-dev openimageio-tools python3-openimageio
  libopenexr-dev libimath-dev libopencolorio-dev libpng-dev
  libeigen3-dev libfftw3-dev
  libhwy-dev libtbb-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev libnoise-dev
  povray python3-numpy
  clang-14 libclang-rt-14-dev  # the sanitizer lane: ASan + UBSan, libFuzzer (scripts/sanitizer-lane.sh)
  slurm-wlm munge  # the batch tests' one-node Slurm cluster (scripts/slurm-fixture.sh, tests/batch/)
  chromium  # the batch gallery's browser test (tests/batch/gallery_browser_test.sh)
  debootstrap  # the Debian 13 and sid lanes' folders (scripts/debian-folder-lane.sh), made side by side
)
# Blender scene tests: blender, and xvfb for the tests of the add-on's interactive UI path.
if [ "${1:-}" = "--with-blender" ]; then packages+=(blender xvfb); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages (${missing[*]}); run this script as root" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: installed ${missing[*]}"
