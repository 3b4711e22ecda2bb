# snell: the two commands a new user needs are `make demo` and `make test`.
# Both install missing Debian packages first (scripts/install-deps.sh, idempotent).
JOBS ?= $(shell nproc)
BUILD_TEST := build
BUILD_REL := build-release
CMAKE_GEN := -G Ninja

.PHONY: all deps build release test demo bench clean

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

# Every test: unit, statistical (chi-square, agreement, furnace), parser, image I/O.
test: build
	cd $(BUILD_TEST) && ctest --output-on-failure -j $(JOBS) --timeout 900

# Renders the built-in droplet scene to out/droplet.exr and out/droplet.png.
demo: release
	@mkdir -p out
	$(BUILD_REL)/snell render builtin:droplet --spp 48 -o out/droplet.exr --stats out/droplet.json

# Throughput of the renderer against Embree's raw closest-hit rate (never part of tests).
bench: release
	$(BUILD_REL)/snell_bench

clean:
	rm -rf $(BUILD_TEST) $(BUILD_REL)
