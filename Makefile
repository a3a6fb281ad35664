# The two commands of the README's Quick start: `make run` and `make test`.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
# What scripts/install-deps.sh installs: all (build, run, test) or build (the Dockerfile).
DEPS ?= all
SAMPLE ?= tests/data/sample.obj
# The web demo bundle that `make build` writes (clients/web); served at / by `make run`.
WEB_ROOT ?= $(BUILD)/clients/web/dist
# CI treats warnings as errors.
ifeq ($(CI),true)
CMAKE_FLAGS += -DPAPERNET_WERROR=ON
endif

.PHONY: all deps build test run format format-check clean benchmarks

all: build

deps:
	bash scripts/install-deps.sh $(DEPS)

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)
	cmake --build $(BUILD) -j $(JOBS)

test: build format-check
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# Starts the HTTP job service with its defaults (127.0.0.1:8080, SQLite store under ./var).
run: build
	@echo "papernet serve: open http://127.0.0.1:8080/ for the demo page, or"
	@echo "                try  curl -s -i --data-binary @$(SAMPLE) -H 'Content-Type: model/obj' 'http://127.0.0.1:8080/v1/jobs'"
	@echo "                (README.md, section 'HTTP service', has the whole session; Ctrl-C stops)"
	PAPERNET_WEB_ROOT="$${PAPERNET_WEB_ROOT:-$(WEB_ROOT)}" $(BUILD)/server/papernet serve

# Regenerates docs/benchmarks.md, docs/benchmarks/*.svg and runs.csv from a full benchmark run
# (1,080 runs; 30-40 min on 2 idle cores). Needs ../shared/data.
benchmarks: deps
	bash scripts/benchmarks.sh

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

format-check:
	clang-format --dry-run --Werror $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD)
