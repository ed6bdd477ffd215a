#!/usr/bin/env bash
# The Debian sid lane of the test command (scripts/run-tests.sh; issue 31): g++ 16, OIIO 3.1.18
# (plugin ABI 27), Blender 5.2.2 in a sid folder (debootstrap from http://deb.debian.org/debian).
# What it builds and runs: scripts/debian-folder-lane.sh. STOCHTEX_SKIP_SID=1 skips it;
# STOCHTEX_SID_ROOT (default /var/cache/stochtex/sid), STOCHTEX_SID_TESTS as there.
exec bash "$(dirname "$0")/debian-folder-lane.sh" sid "$@"
