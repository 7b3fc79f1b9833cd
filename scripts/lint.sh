#!/usr/bin/env bash
# The gate every change passes: style (ruff), formatting (ruff format), types (mypy) and
# the import layers (import-linter, contract in pyproject.toml). `make lint` runs it, and
# `make test` runs it before the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=.venv/bin

# The packages mypy checks; each one listed here has zero errors.
TYPED=(core generator describer examples variation house completion)

echo "lint: ruff check"
"$bin/ruff" check --quiet .
echo "lint: ruff format --check"
"$bin/ruff" format --check --quiet .

# The top-level folders install under the one import name `scenewright` (pyproject's
# package-dir), which mypy and import-linter cannot follow through the editable install's
# import hook. They read the code through a tree of links named as it is imported.
tree=build/import-tree
rm -rf "$tree"
mkdir -p "$tree/scenewright"
for entry in scenewright/*; do
  ln -s "../../../$entry" "$tree/scenewright/$(basename "$entry")"
done
for folder in $(sed -n 's/^"scenewright\.\([a-z_]*\)" = "\([a-z_]*\)"$/\2/p' pyproject.toml); do
  ln -s "../../../$folder" "$tree/scenewright/$folder"
done

echo "lint: mypy ${TYPED[*]}"
targets=()
for package in "${TYPED[@]}"; do targets+=("$tree/scenewright/$package"); done
# Report each error at the file's own path, not the link's.
"$bin/mypy" "${targets[@]}" 2>&1 | sed "s#$tree/scenewright/\([a-z_]*\)/#\1/#" \
  | { ! grep -v '^Success' ; } || { echo "lint: mypy found errors" >&2; exit 1; }

echo "lint: import layers"
(cd "$tree" && PYTHONPATH=. "../../$bin/lint-imports" --config ../../pyproject.toml --no-cache >/tmp/lint-imports.$$ 2>&1) \
  || { cat /tmp/lint-imports.$$; rm -f /tmp/lint-imports.$$; exit 1; }
rm -f /tmp/lint-imports.$$
echo "lint: all passed"
