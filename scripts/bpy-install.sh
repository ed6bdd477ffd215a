#!/usr/bin/env bash
# Installs the official Blender builds as Python modules (`bpy` from PyPI; issue 34), pinned and
# cached, for the bpy lane (scripts/bpy-lane.sh):
#   - bpy 4.5.15 (the 4.5 LTS line's latest patch; CPython 3.11) in a venv on the host (Python 3.11.7);
#   - bpy 5.2.4 (the 5.2 line's latest; CPython 3.13 only) in a venv of Debian 13's Python 3.13.5,
#     inside the Debian 13 folder of scripts/debian13-lane.sh (/opt/bpy-5.2 there).
# Each gets a launcher, $root/<version>/python: 4.5's is the venv's interpreter; 5.2's starts
# Debian 13's interpreter on the host through Debian 13's own dynamic loader and libraries
# (`ld.so --library-path`), so the tests, the add-on's `stex` and the files stay the host's
# (Debian 13's glibc is newer than the host's: its python3.13 cannot run on the host's). Its
# children (`stex`) get the host's loader and libraries again: --library-path is not inherited.
#
# Wheels are downloaded once into $root/wheels (≈ 370 MB for 4.5, ≈ 400 MB for 5.2, with their
# pinned dependencies); a venv whose marker names the same pins is reused. Without the wheels
# and without PyPI the script fails (exit 1) naming what it could not get. Root: $STOCHTEX_BPY_ROOT,
# default /var/cache/stochtex/bpy; the Debian 13 folder: $STOCHTEX_DEBIAN13_ROOT, default
# /var/cache/stochtex/debian13 (made by debootstrap when missing; scripts/debian13-bootstrap.sh).
#
# Usage (root): scripts/bpy-install.sh
set -euo pipefail

root=${STOCHTEX_BPY_ROOT:-/var/cache/stochtex/bpy}
debian13=${STOCHTEX_DEBIAN13_ROOT:-/var/cache/stochtex/debian13}
here=$(cd "$(dirname "$0")" && pwd)
wheels=$root/wheels
platforms=(--platform manylinux_2_28_x86_64 --platform manylinux_2_17_x86_64 --platform manylinux2014_x86_64)
# The pins: the module and its dependencies (from each wheel's METADATA).
pins_45=(bpy==4.5.15 numpy==1.26.4 cython==3.3.1 requests==2.34.2 zstandard==0.25.0
         certifi==2026.10.19.post1 charset_normalizer==3.5.3 idna==3.21 urllib3==2.8.0)
pins_52=(bpy==5.2.4 numpy==2.3.5 cython==3.3.1 requests==2.34.2 zstandard==0.25.0 cattrs==26.2.1
         attrs==26.1.0 typing_extensions==4.16.0
         certifi==2026.10.19.post1 charset_normalizer==3.5.3 idna==3.21 urllib3==2.8.0)

if [ "$(id -u)" -ne 0 ]; then
  echo "bpy-install: needs root (the Debian 13 folder: debootstrap, chroot); STOCHTEX_SKIP_BPY=1 skips the bpy lane" >&2
  exit 1
fi
mkdir -p "$wheels"
exec 8>"$root/.lock"
flock 8  # one installer at a time per cache

# fetch PYTHON-VERSION PIN…: the pinned wheels into $wheels, from PyPI unless already there.
fetch() {
  local version=$1; shift
  if pip download -q --no-deps --only-binary=:all: --no-index --find-links "$wheels" \
       --python-version "$version" "${platforms[@]}" -d "$wheels" "$@" >/dev/null 2>&1; then
    return 0  # all cached
  fi
  local start=$SECONDS
  echo "bpy-install: downloading $* (CPython $version) from PyPI into $wheels"
  if ! pip download -q --no-deps --only-binary=:all: --python-version "$version" "${platforms[@]}" \
       -d "$wheels" "$@" >"$root/download.log" 2>&1; then
    tail -5 "$root/download.log" >&2
    echo "bpy-install: FAILED: could not download $1 (CPython $version) from PyPI (see $root/download.log);" \
         "the bpy lane needs PyPI once, then its cache $wheels. STOCHTEX_SKIP_BPY=1 skips the lane." >&2
    exit 1
  fi
  echo "bpy-install: downloaded in $((SECONDS - start)) s"
}

# ---- 4.5 LTS: a venv of the host's Python 3.11 ----
ready45=$root/4.5/.ready
if [ "$(cat "$ready45" 2>/dev/null)" != "${pins_45[*]}" ]; then
  fetch 3.11 "${pins_45[@]}"
  rm -rf "$root/4.5"
  python3.11 -m venv "$root/4.5/venv"
  "$root/4.5/venv/bin/pip" install -q --no-index --find-links "$wheels" "${pins_45[@]}"
  printf '#!/bin/sh\nexec %s "$@"\n' "$root/4.5/venv/bin/python" >"$root/4.5/python"  # a link would hide the venv
  chmod +x "$root/4.5/python"
  echo "${pins_45[*]}" >"$ready45"
  echo "bpy-install: bpy 4.5 installed in $root/4.5/venv"
else
  echo "bpy-install: reusing bpy 4.5 in $root/4.5/venv"
fi

# ---- 5.2: a venv of Debian 13's Python 3.13 in the Debian 13 folder ----
ready52=$root/5.2/.ready
venv52=/opt/bpy-5.2  # inside the folder
if [ "$(cat "$ready52" 2>/dev/null)" != "${pins_52[*]}" ] || [ ! -x "$debian13$venv52/bin/pip" ]; then
  fetch 3.13 "${pins_52[@]}"
  bash "$here/debian13-bootstrap.sh" "$debian13"
  mounts=()
  unmount_all() { local i; for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do umount "${mounts[i]}" || umount -l "${mounts[i]}"; done; mounts=(); }
  trap unmount_all EXIT
  mkdir -p "$debian13/proc" "$debian13/stochtex/wheels"
  mount -t proc proc "$debian13/proc" && mounts+=("$debian13/proc")
  mount --bind "$wheels" "$debian13/stochtex/wheels" && mounts+=("$debian13/stochtex/wheels")
  in_folder() { chroot "$debian13" env -u PIP_FIND_LINKS DEBIAN_FRONTEND=noninteractive HOME=/root LANG=C.UTF-8 "$@"; }
  if ! in_folder sh -c 'command -v python3.13 >/dev/null && python3.13 -c "import ensurepip"' 2>/dev/null; then
    echo "bpy-install: installing python3.13 and python3.13-venv in $debian13"
    cp /etc/resolv.conf "$debian13/etc/resolv.conf"
    in_folder apt-get update -qq
    in_folder apt-get install -y -qq --no-install-recommends python3.13 python3.13-venv >/dev/null
    in_folder apt-get clean
  fi
  rm -rf "${debian13:?}$venv52"
  in_folder python3.13 -m venv "$venv52"
  in_folder "$venv52/bin/pip" install -q --no-index --find-links /stochtex/wheels "${pins_52[@]}"
  unmount_all
  mkdir -p "$root/5.2"
  echo "${pins_52[*]}" >"$ready52"
  echo "bpy-install: bpy 5.2 installed in $debian13$venv52"
else
  echo "bpy-install: reusing bpy 5.2 in $debian13$venv52"
fi
# The host's view of that venv (written every time: cheap, and a fixed launcher reaches caches
# made before the fix): $root/5.2 is a venv of its own (pyvenv.cfg: Debian 13's interpreter as
# home, the folder's site-packages) whose bin/python starts Debian 13's interpreter through Debian
# 13's loader under its own name, so sys.executable (which Blender runs for its extension
# commands) is this launcher again. bpy's own lib/ comes first on the loader's path: the path
# outranks the module's RUNPATH ($ORIGIN/lib), and the Debian 13 lane installs Debian's Blender
# 4.3 in the same folder, whose libembree4.so.4 and libtbb.so.12 (same names, older versions)
# would otherwise stand in for the ones bpy 5.2 was built with ("undefined symbol:
# rtcTraversableIntersect1").
bpy_lib=$debian13$venv52/lib/python3.13/site-packages/bpy/lib
mkdir -p "$root/5.2/bin"
ln -sfn "$debian13$venv52/lib" "$root/5.2/lib"
printf 'home = %s\ninclude-system-site-packages = false\nversion = 3.13\n' "$debian13/usr/bin" >"$root/5.2/pyvenv.cfg"
cat >"$root/5.2/bin/python" <<EOF
#!/bin/sh
# Debian 13's Python 3.13 with bpy 5.2 (scripts/bpy-install.sh), run on this host by Debian 13's loader.
exec $debian13/lib64/ld-linux-x86-64.so.2 --library-path $bpy_lib:$debian13/lib/x86_64-linux-gnu:$debian13/usr/lib/x86_64-linux-gnu \\
  --argv0 $root/5.2/bin/python $debian13/usr/bin/python3.13 "\$@"
EOF
chmod +x "$root/5.2/bin/python"
ln -sfn bin/python "$root/5.2/python"

# Both must import and say what they are (a broken cache fails here, not in a test).
for version in 4.5 5.2; do
  "$root/$version/python" -c 'import bpy, sys; o = bpy.app.build_options
print("bpy-install: bpy %s, Python %s, cycles_osl %s" % (bpy.app.version_string, sys.version.split()[0], o.cycles_osl))' 2>/dev/null |
    grep '^bpy-install' || { echo "bpy-install: FAILED: bpy $version does not import ($root/$version/python)" >&2; exit 1; }
done
