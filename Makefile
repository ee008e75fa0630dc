# Two entry points on a fresh machine: `make demo` and `make test` (see README).
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
OUT := out

.PHONY: demo test lint bench app clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

# The start-up kernel compiled ahead of time (numba.pycc, needs a C compiler; without one
# the build says why and numba compiles the kernel on first use instead).
KERNEL := src/chaindrive/dynamics/startup_kernel.py src/chaindrive/dynamics/kernel_codes.py

# An editable install leaves the package's own byte code to the first run, which cannot keep
# it where PYTHONDONTWRITEBYTECODE is set (as on the project machines): compile it once here
# (Python reads a current .pyc whatever that variable says; a stale one is ignored).
$(VENV)/.installed: pyproject.toml $(KERNEL) | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e .
	$(BIN)/python -m chaindrive.dynamics.kernel_build
	$(BIN)/python -m compileall -q src
	touch $@

$(VENV)/.installed-test: pyproject.toml $(KERNEL) | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e '.[test]'
	$(BIN)/python -m chaindrive.dynamics.kernel_build
	$(BIN)/python -m compileall -q src
	touch $@

demo: $(VENV)/.installed
	@mkdir -p $(OUT)
	$(BIN)/chaindrive analyze examples/seed_three_sprocket.toml
	@$(BIN)/chaindrive analyze examples/seed_three_sprocket.toml --json > $(OUT)/seed_three_sprocket.json
	@echo "JSON written to $(OUT)/seed_three_sprocket.json"
	@$(BIN)/chaindrive report examples/seed_three_sprocket.toml -o $(OUT)/seed_three_sprocket.html > /dev/null
	@echo "report written to $(abspath $(OUT))/seed_three_sprocket.html"

lint: $(VENV)/.installed-test
	$(BIN)/ruff check src tests benchmarks

test: lint
	$(BIN)/python -m pytest -q

bench: $(VENV)/.installed-test
	for b in benchmarks/bench_*.py; do echo "== $$b"; $(BIN)/python $$b || exit 1; done

app: $(VENV)/.installed
	$(BIN)/chaindrive app

clean:
	rm -rf $(VENV) $(OUT) .pytest_cache .ruff_cache
