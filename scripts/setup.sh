#!/usr/bin/env bash
# Set up a development environment from nothing: the Debian GL libraries offscreen
# rendering needs (when missing and we may install them), a virtualenv in .venv, and
# the package with its test extras in editable mode.
set -euo pipefail
cd "$(dirname "$0")/.."

# shellcheck source=scripts/apt.sh
. scripts/apt.sh

need_gl=()
ldconfig -p | grep -q 'libEGL.so.1 ' || need_gl+=(libegl1)
ldconfig -p | grep -q 'libEGL_mesa.so.0 ' || need_gl+=(libegl-mesa0)
ldconfig -p | grep -q 'libGL.so.1 ' || need_gl+=(libgl1)
if [ ${#need_gl[@]} -gt 0 ]; then
  apt_install_or_warn "for offscreen rendering" "rendering will fail until they are installed" "${need_gl[@]}"
fi

# link-grammar's parser checks the describer's sentences in the tests.
if ! command -v link-parser >/dev/null; then
  apt_install_or_warn "for the grammar check of descriptions" \
    "the description grammar test will skip (fail under CI)" link-grammar
fi

python3 -m venv .venv
.venv/bin/python -m pip install -q --upgrade pip
# setuptools tells at every editable install, as a warning, that a folder named like the
# package may shadow it on imports: here the folder scenewright/ is that package, by
# design (pyproject's package-dir), so the notice is not shown.
PYTHONWARNINGS="ignore:Editable installation" .venv/bin/python -m pip install -q -e '.[test]'
# Khronos' glTF validator (a node package) checks exported GLB files in the tests.
if command -v npm >/dev/null; then
  npm install -s --prefix .tools gltf-validator@2.0.0-dev.3.10 >/dev/null \
    || echo "setup: warning: could not install gltf-validator; GLB validation tests will skip (fail under CI)" >&2
fi
# three.js (a node package) renders exported GLB files in headless Chromium in the tests
# (scripts/threejs_render.py); those tests skip without it or without chromium.
if command -v npm >/dev/null; then
  npm install -s --prefix .tools-three three@0.187.0 >/dev/null \
    || echo "setup: warning: could not install three; three.js render tests will skip" >&2
fi
echo "setup: ready (.venv)"
