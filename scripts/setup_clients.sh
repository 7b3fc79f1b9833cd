#!/usr/bin/env bash
# The tools users open our files in, for the tests that open them there (make test runs
# this after scripts/setup.sh): Debian's Blender (with python3-numpy, which its glTF
# importer needs), Chromium (three.js renders a GLB in it) and Godot 3 with Xvfb (a game
# engine imports and renders a GLB; it needs a display). Each is installed when missing
# and we may; without them their tests skip. About 200 MB of packages on a machine that
# has none; make demo does not need them.
set -euo pipefail
cd "$(dirname "$0")/.."

missing=()
command -v blender >/dev/null || missing+=(blender)
dpkg -s python3-numpy >/dev/null 2>&1 || missing+=(python3-numpy)
command -v chromium >/dev/null || missing+=(chromium)
command -v godot3 >/dev/null || missing+=(godot3)
command -v xvfb-run >/dev/null || missing+=(xvfb)
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
# shellcheck source=scripts/apt.sh
. scripts/apt.sh
apt_install_or_warn "for the tests that open exported files in them" \
  "the tests that open exported files in them will skip" "${missing[@]}"
