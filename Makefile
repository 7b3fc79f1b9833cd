# Two entry points, both of which set everything up first on a fresh machine:
#   make demo   - venv, packages, GL libraries; then generate the village scene into out/
#   make test   - the same set-up; then the whole test suite
# `.ci/run` calls `make test`.

VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed

.PHONY: setup demo test lint bench clean

setup: $(STAMP)

$(STAMP): pyproject.toml scripts/setup.sh
	bash scripts/setup.sh
	touch $(STAMP)

demo: setup
	$(VENV)/bin/scenewright generate village --seed 7 -o out/

lint: setup
	bash scripts/lint.sh

test: setup
	$(PY) -m pytest

bench: setup
	for script in benchmarks/bench_*.py; do $(PY) $$script || exit 1; done

clean:
	rm -rf $(VENV) out build *.egg-info
