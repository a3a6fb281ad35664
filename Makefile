# The two commands of the README's Quick start: `make run` and `make test`.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
# What scripts/install-deps.sh installs: all (build, run, test) or build (the Dockerfile).
DEPS ?= all
SAMPLE ?= tests/data/sample.obj
# The web demo bundle that `make build` writes (clients/web); served at / by `make run`.
WEB_ROOT ?= $(BUILD)/clients/web/dist
# ccache (CMakeLists.txt) keys on paths relative to the checkout, so that every clone, and each
# of the three build trees, reuses what another compiled.
export CCACHE_BASEDIR ?= $(CURDIR)
export CCACHE_NOHASHDIR ?= true
# CI treats warnings as errors.
ifeq ($(CI),true)
CMAKE_FLAGS += -DPAPERNET_WERROR=ON
endif

# Hardening (docs/reliability.md): sanitizer builds and fuzz runs, in build dirs of their own,
# both with clang. build-asan has ASan+UBSan on every target and libFuzzer's coverage on the
# sources the fuzzers run (fuzz/CMakeLists.txt): it runs all tests and holds the fuzz targets.
# build-tsan runs the tests with threads under TSan.
# -O1 with line tables: readable reports at about half the compile time of -O2 -g.
SAN_FLAGS = -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" \
	-DPAPERNET_WEB_DEMO=OFF -DPAPERNET_CLIENT_TESTS=OFF $(CMAKE_FLAGS)
export ASAN_OPTIONS ?= detect_leaks=1:strict_string_checks=1
export UBSAN_OPTIONS ?= print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS ?= suppressions=$(CURDIR)/scripts/lsan.supp:print_suppressions=0
export TSAN_OPTIONS ?= halt_on_error=1:second_deadlock_stack=1:suppressions=$(CURDIR)/scripts/tsan.supp
# Tests with threads of their own (HTTP server, job service workers, the merge of a print's
# pieces unfolding ahead, the fit search laying out its ways two and three at a time); these run
# under TSan.
# "Stores/" prefixes the suites that run against both stores (SQLite and PostgreSQL).
TSAN_TESTS ?= ^(Stores/)?(ServeTest|JobServiceTest|JobStoreTest|StaticFiles|Streams|Merge)\.|^FitSearch\.TheChoiceIsTheSameWithAnyNumberOfThreads$$
# Left out of the sanitizer runs: tests whose verdict depends on speed. They unfold whole meshes
# within a time budget (Tabu 30 s, progressive 120 s) or wait a fixed time (60 s) for a full
# unfold, or expect a net within a 0.5 s limit, or a whole job within its 10 s limit plus a
# second (TimeLimit), or read and print a 76,840-face scan at the defaults (FitSearch.AtDetailAuto...,
# 4 s in Release), or print the Duck with the merge's whole budget (FitSearch.AMergedPiece...,
# 2.5 s in Release); sanitized code runs 3-10x slower, so there
# they would test the speed of the build (and take minutes each), not its correctness. Smaller
# unfolds of the same code run sanitized; `make check` runs these.
SANITIZE_SKIP ?= ^(Stores/ServeTest\.(ProgressiveJobServesIntermediatesThenTheResult|ShortTimeLimitGivesAnApproximateNet|GracefulStopKeepsTheRunningJobForTheNextStart|KillNineThenRestartFinishesEveryJob)/.*|Unfold\.EveryMeshInTestData|FitSearch\.(AtDetailAutoTheScanPrintsEveryLabelLegibly|AMergedPieceMayFillTheRoomKeptForTabsWhenItsTabsFitTheSheet|TendrilsCutOffSaveASheet)|Merge\.UnfoldingsCompactedToFitMergeIntoFewerPieces|Strategies/ProgressiveStrategies\..*|TimeLimit\..*)$$
# Seconds per fuzz target: `make fuzz-smoke` (CI) and `make fuzz` (the longer run).
FUZZ_SMOKE_SECONDS ?= 20
FUZZ_SECONDS ?= 300

.PHONY: all deps build test check run format format-check clean sanitize build-asan \
	sanitize-address sanitize-thread fuzz-smoke fuzz benchmarks print-benchmark

all: build

deps:
	bash scripts/install-deps.sh $(DEPS)

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)
	cmake --build $(BUILD) -j $(JOBS)

# The fast developer loop: build, format check, the tests.
check: build format-check
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# What CI runs: the above, then every test under ASan+UBSan, the threaded ones under TSan, and
# a short run of every fuzzer.
test: check sanitize fuzz-smoke

sanitize: sanitize-address sanitize-thread

build-asan: deps
	CXX=clang++ cmake -S . -B build-asan $(SAN_FLAGS) -DPAPERNET_FUZZ=ON
	cmake --build build-asan -j $(JOBS)

# Sanitizer reports go to files (log_path), so that those of the papernet processes the tests
# start (serve, unfold, info) are seen too, not only the test binary's.
sanitize-address: build-asan
	rm -rf build-asan/sanitizer-logs && mkdir -p build-asan/sanitizer-logs
	ASAN_OPTIONS=$(ASAN_OPTIONS):log_path=$(CURDIR)/build-asan/sanitizer-logs/asan \
	UBSAN_OPTIONS=$(UBSAN_OPTIONS):log_path=$(CURDIR)/build-asan/sanitizer-logs/ubsan \
	ctest --test-dir build-asan --output-on-failure -j $(JOBS) -E '$(SANITIZE_SKIP)'; \
	status=$$?; bash scripts/sanitizer-logs.sh build-asan/sanitizer-logs && exit $$status

sanitize-thread: deps
	CXX=clang++ cmake -S . -B build-tsan $(SAN_FLAGS) -DPAPERNET_SANITIZE=thread
	cmake --build build-tsan -j $(JOBS) --target papernet_server_tests papernet_print_tests \
		papernet_engine_tests
	rm -rf build-tsan/sanitizer-logs && mkdir -p build-tsan/sanitizer-logs
	TSAN_OPTIONS=$(TSAN_OPTIONS):log_path=$(CURDIR)/build-tsan/sanitizer-logs/tsan \
	ctest --test-dir build-tsan --output-on-failure -j $(JOBS) -R '$(TSAN_TESTS)' \
		-E '$(SANITIZE_SKIP)'; \
	status=$$?; bash scripts/sanitizer-logs.sh build-tsan/sanitizer-logs && exit $$status

fuzz-smoke: build-asan
	bash fuzz/run_fuzzers.sh build-asan $(FUZZ_SMOKE_SECONDS)

# The longer run (docs/reliability.md): FUZZ_SECONDS per target, one per core at a time.
fuzz: build-asan
	bash fuzz/run_fuzzers.sh build-asan $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# Starts the HTTP job service with its defaults (127.0.0.1:8080, SQLite store under ./var).
run: build
	@echo "papernet serve: open http://127.0.0.1:8080/ for the demo page, or"
	@echo "                try  curl -s -i --data-binary @$(SAMPLE) -H 'Content-Type: model/obj' 'http://127.0.0.1:8080/v1/jobs'"
	@echo "                (README.md, section 'HTTP service', has the whole session; Ctrl-C stops)"
	PAPERNET_WEB_ROOT="$${PAPERNET_WEB_ROOT:-$(WEB_ROOT)}" $(BUILD)/bin/papernet serve

# Regenerates docs/benchmarks.md, docs/benchmarks/*.svg and runs.csv from a full benchmark run
# (1,080 runs, 60 s limit each; about 8 min on 2 idle cores). Needs ../shared/data.
benchmarks: deps
	bash scripts/benchmarks.sh

# Regenerates docs/print.md's comparison with Blender's exporter (about 5 min; installs
# Blender when missing). Needs ../shared/data.
print-benchmark: deps
	bash scripts/print-benchmark.sh

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

format-check:
	clang-format --dry-run --Werror $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) build-asan build-tsan
