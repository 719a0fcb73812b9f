# Quick start: `make run` (set up + main job) and `make test` (set up + tests).
PY ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: setup run test test-fast bench faults browser validation docs docs-serve clean

# Debian's Chromium opens the HTML report in the tests (installed once, with sudo if not root).
SUDO := $(if $(filter 0,$(shell id -u)),,sudo)

$(BIN)/python:
	$(PY) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(STAMP): pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e ".[test]"
	touch $(STAMP)

setup: $(STAMP)

# The reproduction report of the seeds, then a design study of a machine not from the papers
# (examples/toploader.toml: which balls and profile meet G40 at 95 % over 25-75 g*m).
run: setup
	$(BIN)/autobalance reproduce all --quick --out-dir out/
	mkdir -p out/design
	$(BIN)/autobalance design examples/toploader.toml --quick --grade 40 \
	  --plot out/design/toploader-design.png --out out/design/toploader-design.nc \
	  | tee out/design/toploader-design.txt
	$(BIN)/autobalance study fill-map examples/toploader-ring.toml --quick --dynamic --linear \
	  --plot out/design/toploader-ring-fill.png --out out/design/toploader-ring-fill.nc \
	  | tee out/design/toploader-ring-fill.txt

test: setup browser
	$(BIN)/python -m pytest -q

# The fast tier (under a minute): everything but the markers declared in pyproject.toml
# (slow simulations and subprocesses, the quick report, Chromium, a real Dask cluster).
FAST := not slow and not report and not chromium and not dask
test-fast: setup
	$(BIN)/python -m pytest -q -m "$(FAST)"

# A dpkg run that an earlier install left interrupted is finished first (`dpkg --configure -a`
# does nothing on a clean system); apt waits up to 10 min for another apt's lock.
APT := DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get -o DPkg::Lock::Timeout=600
browser:
	@command -v chromium >/dev/null 2>&1 || { \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) dpkg --configure -a && \
	  $(APT) update -qq && $(APT) install -y -qq chromium >/dev/null; }

# docs/VALIDATION.md is generated from the quick report's rows (tests/test_report.py checks it).
validation: run
	cp out/VALIDATION.md docs/VALIDATION.md

# The documentation site (MkDocs; warnings are errors) into site/, or served on 127.0.0.1:8000.
docs: setup
	$(BIN)/python -m mkdocs build --strict --site-dir site

docs-serve: setup
	$(BIN)/python -m mkdocs serve -a 127.0.0.1:8000

bench: setup
	$(BIN)/python benchmarks/run.py
	$(BIN)/python benchmarks/sweep_bench.py
	$(BIN)/python benchmarks/plateau_bench.py
	$(BIN)/python benchmarks/slip_etd_bench.py
	$(BIN)/python benchmarks/liquid_bench.py

# Fault-injection trials of the sweep store (kill -9, Ctrl-C, SIGTERM, concurrent resumes).
faults: setup
	$(BIN)/python benchmarks/faults.py

clean:
	rm -rf $(VENV) out site .pytest_cache
	find src -name '*.nbi' -delete -o -name '*.nbc' -delete
