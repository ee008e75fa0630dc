# Two entry points on a fresh machine: `make demo` and `make test` (see README).
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
OUT := out

.PHONY: demo test lint typecheck bench app clean bytecode flaky fuzz

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(VENV)/.installed: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e .
	touch $@

$(VENV)/.installed-test: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $@

# The start-up kernel compiled ahead of time (numba.pycc, needs a C compiler; without one
# the build says why and numba compiles the kernel on first use instead). After an install.
KERNEL := src/chaindrive/dynamics/transient/kernel.py src/chaindrive/dynamics/transient/kernel_codes.py src/chaindrive/dynamics/transient/kernel_build.py

$(VENV)/.kernel: $(KERNEL) | $(BIN)/python
	$(BIN)/python -m chaindrive.dynamics.transient.kernel_build
	touch $@

# An editable install leaves the package's own byte code to the first run, which cannot keep
# it where PYTHONDONTWRITEBYTECODE is set (as on the project machines): compile it here
# (only what changed; Python reads a current .pyc whatever that variable says and ignores a
# stale one).
bytecode:
	@$(BIN)/python -m compileall -q src

demo: $(VENV)/.installed $(VENV)/.kernel bytecode
	@mkdir -p $(OUT)
	@echo "== examples/seed_three_sprocket.toml: the source paper's own three-sprocket design, analysed"
	@echo "   as published. It fails two checks by design (its idler S3 has 0.24 teeth in mesh, and the"
	@echo "   first tooth harmonic sits 2.7 % from the first natural frequency), and six more cannot be"
	@echo "   verified (its PA6-GF30 teeth: no allowables for that polymer): the tool says so."
	$(BIN)/chaindrive analyze examples/seed_three_sprocket.toml
	@echo "== examples/conveyor_five_sprocket.toml: a conveyor with its motor, reducer and machines. It"
	@echo "   fails two checks by design: its start-up peak lies inside the band of the chain's estimated"
	@echo "   fatigue strength (15-20 % of the breaking load), and a span's parametric resonance lies"
	@echo "   inside the uncertainty band of the assumed sag and stiffness: the tool says so."
	$(BIN)/chaindrive analyze examples/conveyor_five_sprocket.toml
	@echo "== examples/reduction_drive_bhandari.toml: a textbook two-sprocket drive (10B-1, 19/76 teeth)"
	@echo "   with its 5.5 kW motor and driven machine, every input the dynamics needs given. It passes"
	@echo "   every check; its fatigue limit is an estimate and says so next to the number."
	$(BIN)/chaindrive analyze examples/reduction_drive_bhandari.toml
	@$(BIN)/chaindrive analyze examples/seed_three_sprocket.toml --json > $(OUT)/seed_three_sprocket.json
	@echo "JSON written to $(OUT)/seed_three_sprocket.json"
	@$(BIN)/chaindrive report examples/seed_three_sprocket.toml -o $(OUT)/seed_three_sprocket.html > /dev/null
	@echo "report written to $(abspath $(OUT))/seed_three_sprocket.html"

lint: $(VENV)/.installed-test $(VENV)/.kernel bytecode
	$(BIN)/ruff check src tests benchmarks

# mypy on src/ (settings and the per-module overrides in pyproject.toml [tool.mypy])
typecheck: $(VENV)/.installed-test
	$(BIN)/python -m mypy

# The suite on WORKERS processes (pytest-xdist; the project machine and CI have 2 cores; a
# test file stays on one worker, so its module fixtures start once). WORKERS=0: one process.
WORKERS ?= 2
test: lint typecheck
	$(BIN)/python -m pytest -q -n $(WORKERS) --dist loadfile

# The tests of time, threads, processes, Dask, the web server and the browser (marker
# `concurrency`), each repeated N times in a row, with LOAD busy processes meanwhile
# (LOAD=2 keeps both cores busy); prints each test's failure count.
N ?= 30
LOAD ?= 0
flaky: $(VENV)/.installed-test $(VENV)/.kernel bytecode
	$(BIN)/python -m tests.flaky --count $(N) --load $(LOAD) --workers $(WORKERS)

# The long fuzzing run of docs/reliability.md: FUZZ new random mutated designs (make test
# runs a short derandomised profile of the same test).
FUZZ ?= 2000
fuzz: $(VENV)/.installed-test $(VENV)/.kernel bytecode
	CHAINDRIVE_FUZZ_EXAMPLES=$(FUZZ) $(BIN)/python -m pytest -q -p no:cacheprovider \
		tests/property/test_fuzz.py --hypothesis-show-statistics

bench: $(VENV)/.installed-test $(VENV)/.kernel bytecode
	for b in benchmarks/bench_*.py; do echo "== $$b"; $(BIN)/python $$b || exit 1; done

app: $(VENV)/.installed $(VENV)/.kernel bytecode
	$(BIN)/chaindrive app

clean:
	rm -rf $(VENV) $(OUT) .pytest_cache .ruff_cache .mypy_cache src/chaindrive/dynamics/transient/_startup_aot.*
	find src tests benchmarks -name __pycache__ -type d -prune -exec rm -rf {} +
