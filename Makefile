# The two commands a new user runs (see README.md): `make demo` and `make test`.
# Each installs missing Debian packages, configures and builds.

BUILD_DIR ?= build
BUILD_TYPE ?= Release
WERROR ?= OFF
JOBS ?= 2
CMAKE_FLAGS ?=
FUZZ_SECONDS ?= 30
FUZZ_BUILD_DIR ?= build-fuzz
FUZZ_JOBS ?= 1

.PHONY: demo test build deps deps-browser test-sanitize fuzz clean

deps:
	@scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) \
	  -DLANG2MANIP_WERROR=$(WERROR) $(CMAKE_FLAGS)
	cmake --build $(BUILD_DIR) -j $(JOBS)

# The paper's task offline: "put the marker and eraser in the holder" on the Panda desk scene,
# planned, grounded into grasps, IK and motions, executed and verified; files in lang2manip-out/run/.
demo: build
	$(BUILD_DIR)/src/lang2manip/cli/lang2manip run --out lang2manip-out/run

# The browser tests of the viewer need Debian's chromium (installed here, not for `make demo`);
# LANG2MANIP_REQUIRE_BROWSER=1 makes a missing one a failure instead of a skipped test.
test: export LANG2MANIP_REQUIRE_BROWSER = 1
test: deps-browser build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

deps-browser:
	@scripts/install-deps.sh --browser

# Debug build of the tests under AddressSanitizer and UndefinedBehaviorSanitizer.
# tests/lsan.supp lists the leaks of Debian's libraries that LeakSanitizer is told to ignore.
test-sanitize: export LSAN_OPTIONS = suppressions=$(CURDIR)/tests/lsan.supp
test-sanitize: export UBSAN_OPTIONS = print_stacktrace=1:halt_on_error=1
# The micro-benchmarks are left out: the optimized build compiles them and they time nothing here.
test-sanitize:
	$(MAKE) test BUILD_DIR=build-sanitize BUILD_TYPE=Debug \
	  CMAKE_FLAGS="-DLANG2MANIP_SANITIZE=ON -DLANG2MANIP_BUILD_BENCHMARKS=OFF"

# The libFuzzer harnesses of fuzz/ (clang, ASan + UBSan), each run for FUZZ_SECONDS; fails on any
# crash, leak, UB, timeout or OOM (inputs in $(FUZZ_BUILD_DIR)/fuzz-findings/). See README.md.
fuzz:
	@scripts/install-deps.sh --fuzz
	cmake -S . -B $(FUZZ_BUILD_DIR) -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
	  -DLANG2MANIP_FUZZ=ON -DLANG2MANIP_BUILD_TESTS=OFF -DLANG2MANIP_BUILD_BENCHMARKS=OFF -DLANG2MANIP_BUILD_VIEWER=OFF
	cmake --build $(FUZZ_BUILD_DIR) -j $(JOBS) --target lang2manip_fuzz_harnesses
	FUZZ_JOBS=$(FUZZ_JOBS) fuzz/run-fuzz.sh $(FUZZ_BUILD_DIR) $(FUZZ_SECONDS)

clean:
	rm -rf build build-sanitize $(FUZZ_BUILD_DIR)
