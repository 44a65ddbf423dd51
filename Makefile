# Two commands: `make demo` and `make test`. Both install missing Debian packages first.
BUILD      ?= build
BUILD_ASAN ?= build-asan
JOBS       ?= 2

.PHONY: demo test setup build build-asan clean help

help:
	@echo "make demo   install what is missing, build, run the main job on the default scene"
	@echo "make test   install what is missing, build, run every test, then again under ASan+UBSan"

setup:
	@./setup.sh

# Line tables only (-g1): backtraces and sanitizer reports keep their file:line, and both trees
# build about a fifth faster than with full debug info. Configure a tree of your own with plain
# CMake for variables in a debugger.
DEBUG_INFO = -g1

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
		"-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 $(DEBUG_INFO) -DNDEBUG" \
		"-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 $(DEBUG_INFO) -DNDEBUG"

build: setup $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j$(JOBS)

$(BUILD_ASAN)/CMakeCache.txt:
	cmake -S . -B $(BUILD_ASAN) -DCMAKE_BUILD_TYPE=Debug -DTHX_SANITIZE=ON \
		-DCMAKE_CXX_FLAGS_DEBUG=$(DEBUG_INFO) -DCMAKE_C_FLAGS_DEBUG=$(DEBUG_INFO)

build-asan: setup $(BUILD_ASAN)/CMakeCache.txt
	cmake --build $(BUILD_ASAN) -j$(JOBS)

demo: build
	./demo.sh $(BUILD)

# The tests need only their own executables and the programs they run (target thx_tests,
# tests/CMakeLists.txt): the benchmarks and the tools no test runs are not built here.
test: setup $(BUILD)/CMakeCache.txt $(BUILD_ASAN)/CMakeCache.txt
	cmake --build $(BUILD) -j$(JOBS) --target thx_tests
	cmake --build $(BUILD_ASAN) -j$(JOBS) --target thx_tests
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS) -LE slow
	cd $(BUILD_ASAN) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
		ctest --output-on-failure -j$(JOBS) -LE slow

clean:
	rm -rf $(BUILD) $(BUILD_ASAN)
