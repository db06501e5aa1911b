# gearcli — two commands on a fresh machine: `make demo` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
CASE   ?= cases/seed.yaml
OUT    ?= out/seed
JOBS   ?= auto

.PHONY: install warm demo test test-fast bench bench-report bench-ab lint clean browser

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
	@# exit 4: the seed's findings (failed checks, each with its remedy), said by gearcli above
	@$(BIN)/gearcli run $(CASE) -o $(OUT) --force; rc=$$?; \
	if [ $$rc -ne 0 ] && [ $$rc -ne 4 ]; then exit $$rc; fi

# The suite's duration, measured with `bash .ci/run` on a clean clone (2057 tests, empty solver
# cache, chromium present, 2-core VM with nothing else running): pytest 4.0 min, about 5 min
# wall with the install; on the same VM at load average 7-11 from other jobs the suite took
# 12-13 min. Update it when the suite changes much.
TEST_DURATION := ~4 min on 2 quiet cores (measured: 2057 tests in 239 s; 12-13 min on a busy 2-core VM)
test: lint browser
	@echo "running the test suite (pytest -n $(JOBS)): $(TEST_DURATION); make test-fast skips the slow tests"
	$(BIN)/python -m pytest -n $(JOBS) -q

# Debian's chromium and chromium-driver for the report's browser test, installed where they are
# missing and apt may be used (root); elsewhere that one test is skipped and says why. apt waits
# up to APT_LOCK_WAIT s for a busy package manager; its output goes to a log, and when it fails
# its error lines are shown (the whole log with `make browser APT_VERBOSE=1`).
APT_LOCK_WAIT ?= 120
APT_VERBOSE ?=
BROWSER_PACKAGES := chromium chromium-driver
browser:
	@if ! command -v chromium >/dev/null || ! command -v chromedriver >/dev/null; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "installing $(BROWSER_PACKAGES) (apt) for the browser test"; \
	    log=$$(mktemp); apt="apt-get -y -q -o DPkg::Lock::Timeout=$(APT_LOCK_WAIT)"; \
	    if ! $$apt install $(BROWSER_PACKAGES) >$$log 2>&1 && \
	       ! { $$apt update >$$log 2>&1 && $$apt install $(BROWSER_PACKAGES) >$$log 2>&1; }; then \
	      echo "could not install chromium: the browser test will be skipped. apt-get said:"; \
	      if [ -n "$(APT_VERBOSE)" ] || ! grep -E '^(E|W|Err):' $$log; then tail -n 20 $$log; fi \
	        | sed 's/^/  | /'; \
	    fi; rm -f $$log; \
	  else echo "no chromium: the browser test will be skipped"; fi; \
	fi

test-fast: $(STAMP)
	$(BIN)/python -m pytest -n $(JOBS) -q -m "not slow"

bench: $(STAMP)
	$(BIN)/python bench/run.py

# gearcli report of the seed run over `python -c "import matplotlib.pyplot"` (issue 29) alone
bench-report: $(STAMP)
	$(BIN)/python bench/run.py --report-only

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
