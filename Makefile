# The two quick-start commands: `make run` (the app on http://localhost:8501) and `make test`.
# Each creates ./.venv on first use from the pinned requirements.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PORT   ?= 8501

.PHONY: run test screenshots bench clean

$(BIN)/.runtime: requirements.txt
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -r requirements.txt
	touch $@

$(BIN)/.dev: $(BIN)/.runtime requirements-dev.txt
	$(BIN)/python -m pip install -q -r requirements-dev.txt
	touch $@

run: $(BIN)/.runtime
	$(BIN)/python serve.py --server.port $(PORT)

# Every test, in two parts: those without a live server or browser on up to four processes at once
# (AppTest and the physics, CPU-bound), then those with one, one at a time (they measure time on
# screen; two modules at a time, a fresh clone's run failed two of them: docs/benchmarks-log.md). ``served``
# is set by tests/conftest.py.
test: $(BIN)/.dev
	$(BIN)/python -m pytest -m "not served" --numprocesses=auto --maxprocesses=4
	$(BIN)/python -m pytest -m served

# The quick benchmarks (BENCHMARKS.md §1 and §4, about ten minutes), beside the last recorded ratios
# (bench/recorded.json; `bench/quick.py --record` updates them). Not part of `make test`.
bench: $(BIN)/.dev
	$(BIN)/python bench/quick.py

screenshots: $(BIN)/.dev
	$(BIN)/python scripts/screenshots.py --themes light dark --sizes laptop projector phone

clean:
	rm -rf $(VENV) .pytest_cache .hypothesis
