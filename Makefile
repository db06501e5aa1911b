# gearcli — two commands on a fresh machine: `make demo` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
CASE   ?= cases/seed.yaml
OUT    ?= out/seed
JOBS   ?= auto

.PHONY: install warm demo test test-fast bench bench-ab lint clean browser

install: $(STAMP)

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test]"
	@# bytecode for the package now: an editable install compiles nothing, and where
	@# PYTHONDONTWRITEBYTECODE is set every call would compile ~60 modules again (~0.1 s)
	$(BIN)/python -m compileall -q gearcli >/dev/null
	@$(MAKE) --no-print-directory warm
	@touch $(STAMP)

# Compile the solver into the user cache now (a 0.05 s run; a no-op when it is cached), so
# that the first real run, `make demo`, never waits for it.
warm:
	@d=$$(mktemp -d) && $(BIN)/gearcli simulate $(CASE) -o $$d/run --quiet \
		--set run.end_time=0.05 && rm -rf $$d

demo: $(STAMP)
	@mkdir -p $(dir $(OUT))
	$(BIN)/gearcli geometry $(CASE) --plot $(OUT)-geometry.svg --force
	@$(BIN)/gearcli run $(CASE) -o $(OUT) --force; rc=$$?; \
	if [ $$rc -eq 4 ]; then echo "(exit 4: a check failed or the run is outside the model's \
	validity; the verdicts are in $(OUT)/report.html)"; elif [ $$rc -ne 0 ]; then exit $$rc; fi

test: lint browser
	$(BIN)/python -m pytest -n $(JOBS) -q

# Debian's chromium and chromium-driver for the report's browser test, installed where they are
# missing and apt may be used (root); elsewhere that one test is skipped and says why.
browser:
	@if ! command -v chromium >/dev/null || ! command -v chromedriver >/dev/null; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "installing chromium and chromium-driver (apt) for the browser test"; \
	    apt-get install -y -q chromium chromium-driver >/dev/null 2>&1 || \
	    { apt-get update -q >/dev/null 2>&1 && \
	      apt-get install -y -q chromium chromium-driver >/dev/null 2>&1; } || \
	    echo "could not install chromium: the browser test will be skipped"; \
	  else echo "no chromium: the browser test will be skipped"; fi; \
	fi

test-fast: $(STAMP)
	$(BIN)/python -m pytest -n $(JOBS) -q -m "not slow"

bench: $(STAMP)
	$(BIN)/python bench/run.py

# Kernel A/B against another revision, alternating rounds (bench/ab.py): make bench-ab BASE=HEAD~3
BASE ?= HEAD
bench-ab: $(STAMP)
	$(BIN)/python bench/ab.py --base $(BASE)

lint: $(STAMP)
	$(BIN)/ruff check gearcli tests bench examples

clean:
	rm -rf $(VENV) out build *.egg-info .pytest_cache .ruff_cache

# --- parametric studies (gearcli sweep); one target per study so `make -j studies` works ---
STUDY_OUT ?= out/studies
.PHONY: studies study-table5 study-speed study-speed-curve
studies: study-table5 study-speed study-speed-curve

study-table5: $(STAMP)
	$(BIN)/gearcli sweep cases/studies/table5.yaml -o $(STUDY_OUT)/table5

study-speed: $(STAMP)
	$(BIN)/gearcli sweep cases/studies/speed.yaml -o $(STUDY_OUT)/speed

study-speed-curve: $(STAMP)
	$(BIN)/gearcli sweep cases/studies/speed_curve.yaml -o $(STUDY_OUT)/speed_curve --force
