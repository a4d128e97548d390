# The two commands a new user runs (see README.md): `make demo` and `make test`.
# Each installs missing Debian packages, configures and builds.

BUILD_DIR ?= build
BUILD_TYPE ?= Release
WERROR ?= OFF
JOBS ?= 2
CMAKE_FLAGS ?=

.PHONY: demo test build deps test-sanitize clean

deps:
	@scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) \
	  -DLANG2MANIP_WERROR=$(WERROR) $(CMAKE_FLAGS)
	cmake --build $(BUILD_DIR) -j $(JOBS)

# The paper's task offline: the scene, the symbolic plan from the offline planner, and a verified
# motion of the scene's query (grounding each action into motions is an open issue).
demo: build
	$(BUILD_DIR)/src/lang2manip/cli/lang2manip show
	$(BUILD_DIR)/src/lang2manip/cli/lang2manip plan --task "put the marker and eraser in the holder"
	$(BUILD_DIR)/src/lang2manip/cli/lang2manip solve

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# Debug build of the tests under AddressSanitizer and UndefinedBehaviorSanitizer.
# tests/lsan.supp lists the leaks of Debian's libraries that LeakSanitizer is told to ignore.
test-sanitize: export LSAN_OPTIONS = suppressions=$(CURDIR)/tests/lsan.supp
test-sanitize: export UBSAN_OPTIONS = print_stacktrace=1:halt_on_error=1
test-sanitize:
	$(MAKE) test BUILD_DIR=build-sanitize BUILD_TYPE=Debug CMAKE_FLAGS=-DLANG2MANIP_SANITIZE=ON

clean:
	rm -rf build build-sanitize
