#!/usr/bin/env bash
# The Debian 13 lane of the test command (scripts/run-tests.sh; issue 15): today's hosts next
# to Debian 12's. In a Debian 13 (trixie) folder made by debootstrap it builds stochtex with
# g++ 14 against OIIO 2.5 and runs the tests that depend on those hosts:
#   - the OIIO plugin's tests (plugin_test, plugin_stress_test) against OIIO 2.5.18, its
#     oiiotool and Python bindings;
#   - the Blender scene tests (blender_scene_test) with Blender 4.3.2, which installs the add-on
#     as an extension (`blender --command extension validate`, package_install_files) and drives
#     it end to end (analyse, bake, material, Cycles render, compared with the core);
#   - the add-on's CLI layer (AddonCliLayer) under Python 3.13;
#   - POV-Ray's scene tests (pov_scene_test, Debian 13's POV-Ray) and the model conformance
#     suite (model_conformance_test: every model's contracts — filtering, periodic and solid
#     forms, batches equal to point evaluation, byte-identical round trips — with the core as
#     g++ 14 compiles it).
# The rest of the suite is the per-model maths in detail, already run by the Debian 12 lane;
# building and running all of it again here would cost the test command about as much as the
# first lane for what the conformance suite already checks of the new compiler.
#
# The folder is made once and reused when complete: $STOCHTEX_DEBIAN13_ROOT, default
# /var/cache/stochtex/debian13 (≈ 1.6 GB; delete it to start over). The source tree and
# ../shared are bind-mounted read-only inside; the build lives in the folder
# (/stochtex/build), so a second run only rebuilds what changed. /proc (and a tmpfs on /dev/shm)
# are mounted only while the folder is in use and unmounted on exit, failure included.
#
# Usage (root): scripts/debian13-lane.sh.  STOCHTEX_SKIP_DEBIAN13=1 skips the lane;
# STOCHTEX_DEBIAN13_TESTS=REGEX runs only the lane's tests whose names match (ctest -R).
set -euo pipefail

if [ "${STOCHTEX_SKIP_DEBIAN13:-0}" = "1" ]; then
  echo "debian13-lane: skipped (STOCHTEX_SKIP_DEBIAN13=1)"
  exit 0
fi

# The packages of the lane inside Debian 13: the build (no Google Benchmark: the lane builds no
# bench/), OIIO's tools and Python bindings for the plugin tests, Blender and xvfb for the scene
# tests, POV-Ray for its scene tests.
packages=(
  build-essential cmake pkg-config
  libopenimageio-dev openimageio-tools python3-openimageio
  libopenexr-dev libimath-dev libopencolorio-dev libpng-dev
  libeigen3-dev libfftw3-dev libhwy-dev libtbb-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev
  blender xvfb xauth povray python3-numpy
)
# The build targets and tests of the lane (see the header for why these).
targets=(stex stex_imageio stochtex_addon plugin_test plugin_stress_test blender_scene_test pov_scene_test
         model_conformance_test)
tests='(^|/)(PluginImageInput|PluginTools|PluginTextureSystem|PluginStress|BlenderScene|PovScene|PovCli|ModelConformance|ModelRegistry)\.|^AddonCliLayer$'

if [ "${1:-}" = "--inside" ]; then
  # ---- inside the Debian 13 folder (chroot): build and test ----
  export HOME=/root LANG=C.UTF-8
  jobs=$(nproc)
  echo "debian13-lane: $(. /etc/os-release; echo "$PRETTY_NAME"), $(g++ --version | head -1)," \
       "OIIO $(dpkg-query -W -f='${Version}' libopenimageio-dev), $(blender --version 2>/dev/null | head -1)"
  nice cmake -S /stochtex/src -B /stochtex/build -DCMAKE_BUILD_TYPE=Release \
    -DSTOCHTEX_BUILD_BENCH=OFF -DSTOCHTEX_TSAN_TESTS=OFF -DSTOCHTEX_SHARED_DIR=/stochtex/shared >/dev/null
  nice cmake --build /stochtex/build -j"$jobs" --target "${targets[@]}"
  echo "debian13-lane: built in $SECONDS s"
  selected=${STOCHTEX_DEBIAN13_TESTS:-$tests}
  # The interactive test measures whether Blender's UI keeps ticking during a bake: it runs
  # alone afterwards, not beside another test's Cycles render on the same cores.
  alone='^BlenderScene\.InteractiveOperator'
  status=0
  ctest --test-dir /stochtex/build --output-on-failure -j"$jobs" -R "$selected" -E "$alone" || status=$?
  if [[ $(ctest --test-dir /stochtex/build -N -R "$selected") == *BlenderScene.InteractiveOperator* ]]; then
    ctest --test-dir /stochtex/build --output-on-failure -R "$alone" || status=$?
  fi
  exit $status
fi

# ---- on the host (Debian 12, root): make or reuse the folder, then run the part above in it ----
src=$(cd "$(dirname "$0")/.." && pwd)
shared=$(cd "$src/.." && pwd)/shared
root=${STOCHTEX_DEBIAN13_ROOT:-/var/cache/stochtex/debian13}
if [ "$(id -u)" -ne 0 ]; then
  echo "debian13-lane: needs root (debootstrap, chroot, mounts); STOCHTEX_SKIP_DEBIAN13=1 skips the lane" >&2
  exit 1
fi
start=$SECONDS
mkdir -p "$(dirname "$root")"
exec 9>"$root.lock"
flock 9  # one lane at a time per folder

mounts=()
unmount_all() {
  local i
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do
    umount "${mounts[i]}" 2>/dev/null || umount -l "${mounts[i]}" || true
  done
  mounts=()
}
trap unmount_all EXIT
trap 'exit 130' INT; trap 'exit 143' TERM  # a signal becomes an exit, so the mounts still go
mount_in() {  # mount_in TARGET MOUNT-ARGUMENTS…
  local target=$1; shift
  mkdir -p "$target"
  mount "$@" "$target"
  mounts+=("$target")
}

ready="$root/.stochtex-lane-ready"
if [ ! -f "$ready" ] || [ "$(cat "$ready")" != "${packages[*]}" ]; then
  bash "$(dirname "$0")/debian13-bootstrap.sh" "$root"  # nothing, or an interrupted debootstrap
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  # No services start inside the folder (packages such as dbus would try).
  printf '#!/bin/sh\nexit 101\n' >"$root/usr/sbin/policy-rc.d" && chmod +x "$root/usr/sbin/policy-rc.d"
  mount_in "$root/proc" -t proc proc
  echo "debian13-lane: installing ${#packages[@]} packages in Debian 13"
  chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
  chroot "$root" apt-get clean
  unmount_all
  echo "${packages[*]}" >"$ready"
  echo "debian13-lane: folder ready after $((SECONDS - start)) s"
else
  echo "debian13-lane: reusing $root"
fi

mount_in "$root/proc" -t proc proc
mount_in "$root/dev/shm" -t tmpfs tmpfs
mount_in "$root/stochtex/src" --bind "$src"
mount -o remount,bind,ro "$root/stochtex/src"
if [ -d "$shared" ]; then
  mount_in "$root/stochtex/shared" --bind "$shared"
  mount -o remount,bind,ro "$root/stochtex/shared"
fi
status=0
chroot "$root" /bin/bash /stochtex/src/scripts/debian13-lane.sh --inside || status=$?
unmount_all
echo "debian13-lane: $([ $status -eq 0 ] && echo passed || echo FAILED) in $((SECONDS - start)) s"
exit $status
