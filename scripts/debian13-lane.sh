#!/usr/bin/env bash
# The Debian 13 lane of the test command (scripts/run-tests.sh; issue 15): g++ 14, OIIO 2.5.18,
# Blender 4.3.2 in a trixie folder. What it builds and runs: scripts/debian-folder-lane.sh.
# STOCHTEX_SKIP_DEBIAN13=1 skips it; STOCHTEX_DEBIAN13_ROOT, STOCHTEX_DEBIAN13_TESTS as there.
exec bash "$(dirname "$0")/debian-folder-lane.sh" trixie "$@"
