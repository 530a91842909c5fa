# gearfe: `make run` and `make test` work on a fresh machine (they create .venv first).
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
	$(BIN)/python -m pip install --quiet --upgrade "pip>=23.2"
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $@

run: install
	$(BIN)/gearfe tca pipelines/cases/part1_sun_planet.toml --out $(OUT)/part1_sun_planet

test: install
	$(BIN)/python -m pytest -q

bench: install
	$(BIN)/python -m pipelines.bench --out $(OUT)/bench

clean:
	rm -rf $(OUT) .pytest_cache build *.egg-info
