# The two commands of README.md: `make run` and `make test`. Both set up what they need.
VENV ?= .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.sward-installed

# Python keeps the modules it compiled (__pycache__) even where the environment says not to:
# without them every process compiles its modules from source again, seconds of each start,
# and the designer and the tests start many (render processes, command-line runs).
unexport PYTHONDONTWRITEBYTECODE

.PHONY: run test lint bench setup system-deps test-deps clean

$(STAMP): pyproject.toml
	@bash scripts/python-env.sh $(VENV)
	@touch $(STAMP)

# the numba kernels compiled once into their cache (scripts/compile_kernels.py)
KERNELS := $(VENV)/.sward-kernels
$(KERNELS): $(STAMP)
	@echo "sward setup: compiling the numba kernels (once)"
	@$(PY) scripts/compile_kernels.py
	@touch $(KERNELS)

setup: $(KERNELS)

# the optional extras (sward[cluster]: Ray, sward[usd]: usd-core) stay out of `make run`;
# their tests need them
EXTRAS := $(VENV)/.sward-extras
$(EXTRAS): $(STAMP)
	@bash scripts/python-env.sh $(VENV) test,cluster,usd
	@touch $(EXTRAS)

system-deps:
	@bash scripts/system-deps.sh

test-deps:  # the designer's, and Node.js for the glTF validator
	@bash scripts/system-deps.sh test

run: system-deps $(KERNELS)
	$(VENV)/bin/sward

lint: $(STAMP)
	$(VENV)/bin/ruff check .
	$(VENV)/bin/ruff format --check .
	$(VENV)/bin/lint-imports
	$(VENV)/bin/mypy
	$(VENV)/bin/vulture

# the Khronos glTF validator (npm), which tests/test_export.py runs on every export
VALIDATOR := $(VENV)/node/node_modules/gltf-validator/package.json
$(VALIDATOR):
	npm install --silent --no-audit --no-fund --prefix $(VENV)/node gltf-validator@2.0.0-dev.3.10

test: test-deps $(EXTRAS) $(VALIDATOR)
	# the linters and the kernels' compile, one core each, side by side
	@$(MAKE) --no-print-directory -j2 --output-sync=target lint $(KERNELS)
	$(VENV)/bin/sward info
	# core/ and the designer's controllers with Qt and GL unimportable (tests/blocked.py)
	$(PY) -m pytest -n 2 -p tests.blocked -p no:pytest-qt -p no:xvfb tests/core tests/app
	# The window tests (marker gui, under Xvfb) run in a process of their own; the window
	# draws no GL (its frames come from render processes), the other tests use standalone EGL.
	# Two workers (pytest-xdist): much of a GL test is Python, process starts and llvmpipe's
	# single-threaded shader compiles, and a window test waits on its render processes.
	# The tune tests measure what settings cost and run one at a time (their xdist group).
	$(PY) -m pytest -n 2 --dist loadgroup -m "not gui" --ignore=tests/core --ignore=tests/app
	QT_QPA_PLATFORM=xcb $(PY) -m pytest -n 2 -m gui

bench: $(STAMP)
	$(VENV)/bin/sward bench --out benchmarks/results.json

clean:
	rm -rf $(VENV) .pytest_cache .ruff_cache
