# Two entry points, both of which set everything up first on a fresh machine:
#   make demo   - venv, packages, GL libraries; then generate the village scene into out/
#   make test   - the same set-up; then the whole test suite, on every core
# For contributors: make lint (the gate alone), make test-fast (the suite without the
# tests marked slow: kill and resume runs, every shipped rule set end to end).
# `.ci/run` calls `make test`.

VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed
CLIENTS := $(VENV)/.clients

.PHONY: setup compile demo test test-fast lint bench parser-tables clean

setup: $(STAMP)

# The project's own modules, compiled ahead: where PYTHONDONTWRITEBYTECODE is set (as on
# many CI images) Python never writes them itself, and every command, and every command
# a test runs, would compile each module it loads again. compileall skips what is
# already up to date.
PACKAGES := scenewright core generator describer render learning completion examples \
	variation composer house
compile: setup
	$(PY) -m compileall -q $(PACKAGES)

$(STAMP): pyproject.toml scripts/setup.sh scripts/apt.sh
	bash scripts/setup.sh
	touch $(STAMP)

# Blender and Chromium, which the tests open exported files in (not needed by demo).
$(CLIENTS): scripts/setup_clients.sh | $(STAMP)
	bash scripts/setup_clients.sh
	touch $(CLIENTS)

demo: compile
	$(VENV)/bin/scenewright generate village --seed 7 -o out/

lint: setup
	bash scripts/lint.sh

# The gate first, then the tests on every core (pytest-xdist); each test draws from its
# own fixed seeds, so the outcome is the same as a serial run's.
test: compile $(CLIENTS)
	bash scripts/lint.sh
	$(PY) -m pytest -n auto --dist worksteal

test-fast: compile
	$(PY) -m pytest -n auto --dist worksteal -m "not slow"

bench: compile
	for script in benchmarks/bench_*.py; do $(PY) $$script || exit 1; done

# The rules parser's stored tables, after an edit of generator/rules.lark or a new lark
# (a test fails until they are written again).
parser-tables: setup
	$(PY) scripts/parser_tables.py

clean:
	rm -rf $(VENV) out build *.egg-info
