#!/usr/bin/env bash
# Set up a development environment from nothing: the Debian GL libraries offscreen
# rendering needs (when missing and we may install them), a virtualenv in .venv, and
# the package with its test extras in editable mode.
set -euo pipefail
cd "$(dirname "$0")/.."

need_gl=()
ldconfig -p | grep -q 'libEGL.so.1 ' || need_gl+=(libegl1)
ldconfig -p | grep -q 'libEGL_mesa.so.0 ' || need_gl+=(libegl-mesa0)
ldconfig -p | grep -q 'libGL.so.1 ' || need_gl+=(libgl1)
if [ ${#need_gl[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    echo "setup: installing GL libraries for offscreen rendering: ${need_gl[*]}"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need_gl[@]}" >/dev/null
  else
    echo "setup: warning: missing ${need_gl[*]}; rendering will fail until they are installed" >&2
  fi
fi

# link-grammar's parser checks the describer's sentences in the tests.
if ! command -v link-parser >/dev/null; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    echo "setup: installing link-grammar for the grammar check of descriptions"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq link-grammar >/dev/null
  else
    echo "setup: warning: missing link-grammar; the description grammar test will skip (fail under CI)" >&2
  fi
fi

python3 -m venv .venv
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q -e '.[test]'
# Khronos' glTF validator (a node package) checks exported GLB files in the tests.
if command -v npm >/dev/null; then
  npm install -s --prefix .tools gltf-validator@2.0.0-dev.3.10 >/dev/null \
    || echo "setup: warning: could not install gltf-validator; GLB validation tests will skip (fail under CI)" >&2
fi
echo "setup: ready (.venv)"
