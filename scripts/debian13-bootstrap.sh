#!/usr/bin/env bash
# Makes a Debian 13 (trixie) folder by debootstrap, once: the base system, no packages beyond it
# (each lane installs its own inside: scripts/debian13-lane.sh, scripts/bpy-install.sh). A folder
# already bootstrapped is left as it is; an interrupted one is started afresh.
# Usage (root): scripts/debian13-bootstrap.sh FOLDER
set -euo pipefail
root=${1:?usage: debian13-bootstrap.sh FOLDER}
[ -f "$root/.stochtex-bootstrapped" ] && exit 0
start=$SECONDS
if grep -q " $root/" /proc/mounts; then echo "debian13-bootstrap: something is still mounted under $root; not removing it" >&2; exit 1; fi
rm -rf --one-file-system "$root"
mkdir -p "$(dirname "$root")"
dpkg-query -W -f='${Status}' debootstrap 2>/dev/null | grep -q "install ok installed" ||
  { DEBIAN_FRONTEND=noninteractive apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap; }
echo "debian13-bootstrap: debootstrap trixie into $root"
debootstrap --variant=minbase trixie "$root" >"$root.debootstrap.log" 2>&1 ||
  { tail -20 "$root.debootstrap.log" >&2; exit 1; }
ln -sf ../proc/self/mounts "$root/etc/mtab"  # Blender lists the mounted file systems
touch "$root/.stochtex-bootstrapped"
echo "debian13-bootstrap: done after $((SECONDS - start)) s"
