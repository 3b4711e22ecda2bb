# snell: the two commands a new user needs are `make demo` and `make test`.
# Both install missing Debian packages first (scripts/install-deps.sh, idempotent).
JOBS ?= $(shell nproc)
BUILD_TEST := build
BUILD_REL := build-release
BUILD_SAN := build-sanitize
CMAKE_GEN := -G Ninja

.PHONY: all deps build release test test-sanitize fuzz demo bench clean

all: release

deps:
	@scripts/install-deps.sh

$(BUILD_TEST)/build.ninja: CMakeLists.txt | deps
	cmake -S . -B $(BUILD_TEST) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSNELL_BUILD_TESTS=ON

$(BUILD_REL)/build.ninja: CMakeLists.txt | deps
	cmake -S . -B $(BUILD_REL) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Release -DSNELL_BUILD_TESTS=OFF -DSNELL_BUILD_BENCH=ON

build: deps $(BUILD_TEST)/build.ninja
	cmake --build $(BUILD_TEST) -j $(JOBS)

release: deps $(BUILD_REL)/build.ninja
	cmake --build $(BUILD_REL) -j $(JOBS)

# Every test: unit, statistical (chi-square, agreement, furnace), parser, image I/O; then the
# sanitizer suite.
test: build
	cd $(BUILD_TEST) && ctest --output-on-failure -j $(JOBS) --timeout 900
	$(MAKE) test-sanitize

# The sanitizer build (clang, ASan + UBSan): unit, parser and manifold tests and a seeded run of
# the scene-loader fuzz target over its corpus (docs/testing.md, "Sanitizers and fuzzing").
# Sanitizer settings: tests/sanitize/ (suppressions name Debian's uninstrumented libraries only).
SAN_DIR := $(CURDIR)/tests/sanitize
SAN_ENV := ASAN_OPTIONS=detect_leaks=1:check_initialization_order=1:detect_stack_use_after_return=1:strict_string_checks=1 \
	LSAN_OPTIONS=suppressions=$(SAN_DIR)/lsan.supp:print_suppressions=0 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:suppressions=$(SAN_DIR)/ubsan.supp

$(BUILD_SAN)/build.ninja: CMakeLists.txt | deps
	cmake -S . -B $(BUILD_SAN) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
		-DSNELL_SANITIZE=ON -DSNELL_BUILD_FUZZ=ON -DSNELL_BUILD_TESTS=ON

test-sanitize: deps $(BUILD_SAN)/build.ninja
	$(SAN_ENV) cmake --build $(BUILD_SAN) -j $(JOBS) --target snell_test_suite
	cd $(BUILD_SAN) && $(SAN_ENV) ctest --output-on-failure -j $(JOBS) --timeout 900

# A long fuzz run: FUZZ_RUNS cases (FUZZ_ARGS adds libFuzzer flags, e.g. -max_total_time=3600
# or -jobs=2). New cases collect in $(BUILD_SAN)/fuzz/scratch, crashing inputs in
# $(BUILD_SAN)/fuzz/findings; the checked-in corpus is never written.
FUZZ_RUNS ?= 100000
FUZZ_ARGS ?=
fuzz: deps $(BUILD_SAN)/build.ninja
	$(SAN_ENV) cmake --build $(BUILD_SAN) -j $(JOBS) --target fuzz_loader
	$(SAN_ENV) tests/fuzz/run_fuzz.sh $(BUILD_SAN)/fuzz_loader $(FUZZ_RUNS) $(BUILD_SAN)/fuzz/scratch \
		$(BUILD_SAN)/fuzz/findings $(FUZZ_ARGS)

# Renders the built-in droplet scene to out/droplet.exr and out/droplet.png.
demo: release
	@mkdir -p out
	$(BUILD_REL)/snell render builtin:droplet --spp 48 -o out/droplet.exr --stats out/droplet.json

# Throughput of the renderer against Embree's raw closest-hit rate (never part of tests).
bench: release
	$(BUILD_REL)/snell_bench

clean:
	rm -rf $(BUILD_TEST) $(BUILD_REL) $(BUILD_SAN)
