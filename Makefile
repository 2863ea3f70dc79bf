# softimpact: every target creates .venv and installs what it needs.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
SI := $(VENV)/bin/softimpact
STAMP := $(VENV)/.installed-stamp
PYTEST_ARGS ?=

.PHONY: install test test-nojit demo lint clean

install: $(STAMP)

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test,dask]'
	touch $(STAMP)

test: $(STAMP)
	$(PY) -m pytest $(PYTEST_ARGS)

# Pure-Python run of the kernels (slow): for debugging and coverage.
test-nojit: $(STAMP)
	NUMBA_DISABLE_JIT=1 $(PY) -m pytest -x -k "not slow" $(PYTEST_ARGS)

demo: $(STAMP)
	$(SI) sweep configs/trajectory_duffing.toml -o results/demo.h5 --overwrite
	$(SI) plot trajectory results/demo.h5 -o results/demo.png
	@echo "result: results/demo.h5   figure: results/demo.png   (softimpact info results/demo.h5)"

lint: $(STAMP)
	$(VENV)/bin/ruff check .

clean:
	rm -rf $(VENV) *.egg-info .pytest_cache
	find . -name __pycache__ -type d -prune -exec rm -rf {} +
