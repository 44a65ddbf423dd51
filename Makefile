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
# The sanitizer tree builds first; its tests then run while the optimised tree builds. A third of
# their time is the real-time tests that ctest runs alone (RUN_SERIAL: alone among the tests, not
# on the machine), which leave the cores mostly idle, and the compiles fill them (docs/build.md).
# Their output goes to build-asan/ctest.log and is printed once both are done.
SANITIZER_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

test: setup $(BUILD)/CMakeCache.txt $(BUILD_ASAN)/CMakeCache.txt
	cmake --build $(BUILD_ASAN) -j$(JOBS) --target thx_tests
	@echo "make test: the sanitizer tree's tests run while the optimised tree builds (their output: $(BUILD_ASAN)/ctest.log)"
	@cd $(BUILD_ASAN) && $(SANITIZER_ENV) ctest --output-on-failure -j$(JOBS) -LE slow > ctest.log 2>&1 & tests=$$!; \
	  cmake --build $(BUILD) -j$(JOBS) --target thx_tests; built=$$?; \
	  echo "make test: the optimised tree is built (exit $$built); waiting for the sanitizer tree's tests"; \
	  wait $$tests; tested=$$?; \
	  echo "make test: the sanitizer tree's tests are done (exit $$tested); their output:"; \
	  cat $(BUILD_ASAN)/ctest.log; \
	  test $$built -eq 0 && test $$tested -eq 0
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS) -LE slow

clean:
	rm -rf $(BUILD) $(BUILD_ASAN)
