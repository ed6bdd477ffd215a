#!/usr/bin/env bash
# A lane of the test command that builds and tests stochtex inside a Debian folder made by
# debootstrap: today's hosts next to Debian 12's. Its front-ends say which Debian:
#   scripts/debian13-lane.sh  Debian 13 (trixie): g++ 14, OIIO 2.5.18, Blender 4.3.2;
#   scripts/sid-lane.sh       Debian sid: g++ 16, OIIO 3.1.18, Blender 5.2.2.
# In the folder it builds stochtex against that Debian's packages and runs the tests that
# depend on those hosts:
#   - the OIIO plugin's tests (plugin_test, plugin_stress_test) against that OIIO, its
#     oiiotool and Python bindings;
#   - the Blender scene tests (blender_scene_test) with that Blender, which installs the add-on
#     as an extension (`blender --command extension validate`, package_install_files) and drives
#     it end to end (analyse, bake, material, Cycles render, compared with the core);
#   - the add-on's CLI layer (AddonCliLayer) under that Python;
#   - POV-Ray's scene tests (pov_scene_test) and the model conformance suite
#     (model_conformance_test: every model's contracts — filtering, periodic and solid forms,
#     batches equal to point evaluation, byte-identical round trips — with the core as that
#     compiler compiles it).
# The rest of the suite is the per-model maths in detail, already run by the Debian 12 lane;
# building and running all of it again here would cost the test command about as much as the
# first lane for what the conformance suite already checks of the new compiler.
#
# The folder is made once and reused when complete: $STOCHTEX_<LANE>_ROOT, default
# /var/cache/stochtex/<lane> (1.6–2.2 GB; delete it to start over). The source tree and
# ../shared are bind-mounted read-only inside; the build lives in the folder
# (/stochtex/build), so a second run only rebuilds what changed. /proc (and a tmpfs on /dev/shm)
# are mounted only while the folder is in use and unmounted on exit, failure included.
#
# Usage (root): scripts/debian-folder-lane.sh trixie|sid [--prepare] (the front-ends call it).
# --prepare only makes (or checks) the folder and exits: the test command runs it in the
# background, network-bound, while the main build compiles, and the lane later finds it ready.
# STOCHTEX_SKIP_<LANE>=1 skips the lane; STOCHTEX_<LANE>_TESTS=REGEX runs only the lane's tests
# whose names match (ctest -R). <LANE> is DEBIAN13 for trixie, SID for sid.
set -euo pipefail

suite=${1:-}
shift || true
case "$suite" in
  trixie)
    lane=debian13 LANE=DEBIAN13 debian="Debian 13"
    mirror=""  # debootstrap's default
    apt_options=()
    extra_packages=()
    ;;
  sid)
    lane=sid LANE=SID debian="Debian sid"
    mirror=http://deb.debian.org/debian
    # The sid index these machines reach is a fixed snapshot past its Valid-Until date.
    apt_options=(-o Acquire::Check-Valid-Until=false)
    # Blender 5.2's extension system imports cattrs and requests when it registers (without them
    # every headless run prints a traceback); Debian's blender depends on neither.
    extra_packages=(python3-cattr python3-requests)
    ;;
  *)
    echo "debian-folder-lane: usage: $0 trixie|sid [--prepare]" >&2
    exit 2
    ;;
esac
skip_var=STOCHTEX_SKIP_$LANE root_var=STOCHTEX_${LANE}_ROOT tests_var=STOCHTEX_${LANE}_TESTS

if [ "${!skip_var:-0}" = "1" ]; then
  echo "$lane-lane: skipped ($skip_var=1)"
  exit 0
fi

# The packages of the lane inside the folder (the same names in trixie and sid): the build (no Google Benchmark: the lane builds no
# bench/), OIIO's tools and Python bindings for the plugin tests, Blender and xvfb for the scene
# tests, POV-Ray for its scene tests.
packages=(
  build-essential cmake pkg-config
  libopenimageio-dev openimageio-tools python3-openimageio
  libopenexr-dev libimath-dev libopencolorio-dev libpng-dev
  libeigen3-dev libfftw3-dev libhwy-dev libtbb-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev
  blender xvfb xauth povray python3-numpy
  "${extra_packages[@]}"
)
# The build targets and tests of the lane (see the header for why these; ColourSpaceNames: the
# names a photo's colour space has in that OIIO).
targets=(stex stex_imageio stochtex_addon plugin_test plugin_stress_test blender_scene_test pov_scene_test
         model_conformance_test colour_space_names_test)
tests='(^|/)(PluginImageInput|PluginTileCache|PluginTools|PluginTextureSystem|PluginStress|BlenderScene|PovScene|PovCli|ModelConformance|ModelRegistry|ColourSpaceNames)\.|^AddonCliLayer$'

if [ "${1:-}" = "--inside" ]; then
  # ---- inside the folder (chroot): build and test ----
  export HOME=/root LANG=C.UTF-8
  jobs=$(nproc)
  echo "$lane-lane: $(. /etc/os-release; echo "$PRETTY_NAME"), $(g++ --version | head -1)," \
       "OIIO $(dpkg-query -W -f='${Version}' libopenimageio-dev), $(blender --version 2>/dev/null | head -1)"
  nice cmake -S /stochtex/src -B /stochtex/build -DCMAKE_BUILD_TYPE=Release \
    -DSTOCHTEX_BUILD_BENCH=OFF -DSTOCHTEX_TSAN_TESTS=OFF -DSTOCHTEX_SHARED_DIR=/stochtex/shared >/dev/null
  nice cmake --build /stochtex/build -j"$jobs" --target "${targets[@]}"
  echo "$lane-lane: built in $SECONDS s"
  selected=${!tests_var:-$tests}
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
root=${!root_var:-/var/cache/stochtex/$lane}
if [ "$(id -u)" -ne 0 ]; then
  echo "$lane-lane: needs root (debootstrap, chroot, mounts); $skip_var=1 skips the lane" >&2
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
mounted_below() { grep -q " $root/" /proc/mounts; }

ready="$root/.stochtex-lane-ready"
if [ ! -f "$ready" ] || [ "$(cat "$ready")" != "${packages[*]}" ]; then
  if [ ! -f "$root/.stochtex-bootstrapped" ]; then
    # Nothing, or an interrupted debootstrap: start the folder afresh.
    if mounted_below; then echo "$lane-lane: something is still mounted under $root; not removing it" >&2; exit 1; fi
    rm -rf --one-file-system "$root"
    dpkg-query -W -f='${Status}' debootstrap 2>/dev/null | grep -q "install ok installed" ||
      { DEBIAN_FRONTEND=noninteractive apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap; }
    echo "$lane-lane: debootstrap $suite into $root"
    debootstrap --variant=minbase "$suite" "$root" $mirror >"$root.debootstrap.log" 2>&1 ||
      { tail -20 "$root.debootstrap.log" >&2; echo "$lane-lane: FAILED: debootstrap $suite ${mirror:-(default mirror)} failed (log above, $root.debootstrap.log)" >&2; exit 1; }
    ln -sf ../proc/self/mounts "$root/etc/mtab"  # Blender lists the mounted file systems
    touch "$root/.stochtex-bootstrapped"
    echo "$lane-lane: debootstrap done after $((SECONDS - start)) s"
  fi
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  # No services start inside the folder (packages such as dbus would try).
  printf '#!/bin/sh\nexit 101\n' >"$root/usr/sbin/policy-rc.d" && chmod +x "$root/usr/sbin/policy-rc.d"
  mount_in "$root/proc" -t proc proc
  echo "$lane-lane: installing ${#packages[@]} packages in $debian"
  chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get "${apt_options[@]}" update -qq ||
    { echo "$lane-lane: FAILED: apt-get update in $debian failed (its package index is unreachable?)" >&2; exit 1; }
  chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get "${apt_options[@]}" install -y -qq --no-install-recommends \
    "${packages[@]}" >"$root.install.log" 2>&1 ||
    { tail -20 "$root.install.log" >&2; echo "$lane-lane: FAILED: cannot install the lane's packages in $debian (log above, $root.install.log)" >&2; exit 1; }
  chroot "$root" apt-get clean
  unmount_all
  echo "${packages[*]}" >"$ready"
  echo "$lane-lane: folder ready after $((SECONDS - start)) s"
else
  echo "$lane-lane: reusing $root"
fi
if [ "${1:-}" = "--prepare" ]; then exit 0; fi

mount_in "$root/proc" -t proc proc
mount_in "$root/dev/shm" -t tmpfs tmpfs
mount_in "$root/stochtex/src" --bind "$src"
mount -o remount,bind,ro "$root/stochtex/src"
if [ -d "$shared" ]; then
  mount_in "$root/stochtex/shared" --bind "$shared"
  mount -o remount,bind,ro "$root/stochtex/shared"
fi
status=0
chroot "$root" /bin/bash /stochtex/src/scripts/debian-folder-lane.sh "$suite" --inside || status=$?
unmount_all
echo "$lane-lane: $([ $status -eq 0 ] && echo passed || echo FAILED) in $((SECONDS - start)) s"
exit $status
