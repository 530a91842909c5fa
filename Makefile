# gearfe: `make run` and `make test` work on a fresh machine (they create .venv first).
# Set-up: the packages are installed by uv (itself installed into the venv by pip), which downloads and unpacks
# wheels in parallel: 52 s -> 26 s for a fresh clone (measured, cold caches). Should uv fail (no wheel for the
# platform, an old pip), the same packages are installed by pip (upgraded only when older than 23.2, no .pyc
# files compiled at install time).
PYTHON ?= python3
VENV   ?= .venv
BIN     = $(VENV)/bin
OUT    ?= out

export VTK_DEFAULT_OPENGL_WINDOW = vtkEGLRenderWindow
export MPLBACKEND = Agg

.PHONY: install run test bench clean

install: $(VENV)/.installed

$(VENV)/.installed: pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	( $(BIN)/python -m pip install --quiet --disable-pip-version-check uv \
	  && $(BIN)/uv pip install --python $(BIN)/python --quiet -e '.[test]' ) \
	|| ( $(BIN)/python -m pip install --quiet --disable-pip-version-check "pip>=23.2" \
	  && $(BIN)/python -m pip install --quiet --disable-pip-version-check --no-compile -e '.[test]' )
	touch $@

# Part 1, Numerical Example 1.3: new vs conventional design (Fig. 1.9), then the TCA of the sun-planet pair
# (--force: a second `make run` replaces the results of the first)
run: install
	$(BIN)/gearfe compare pipelines/cases/stress_part1_new.toml pipelines/cases/stress_part1_conventional.toml \
		--out $(OUT)/part1_compare --force
	$(BIN)/gearfe tca pipelines/cases/part1_sun_planet.toml --out $(OUT)/part1_sun_planet --force
	@echo "report: $(OUT)/part1_compare/report.html (both designs side by side, every picture embedded)"
	@echo "images: $(OUT)/part1_compare/compare_zones.png, compare_pressure.png, compare_overview.png;"
	@echo "        each design: $(OUT)/part1_compare/{new,conventional}/ (report.html, teeth_*.png, flank_*.png, ...)"
	@echo "        TCA plots: $(OUT)/part1_sun_planet/te.png, contact_paths.png"

# two workers, one test file each (module fixtures are built once), heaviest files first (tests/conftest.py), one
# BLAS/MKL thread per worker (two workers on two cores: extra threads only spin); convergence studies (marker
# "bench") run with make bench
test: install
	OMP_NUM_THREADS=1 MKL_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 \
		$(BIN)/python -m pytest -q -n 2 --dist loadfile --no-loadscope-reorder -m "not bench"

bench: install
	$(BIN)/python -m pytest -q -m bench
	$(BIN)/python -m benchmarks --out $(OUT)/bench

clean:
	rm -rf $(OUT) .pytest_cache build *.egg-info
