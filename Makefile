# Two commands: `make demo` and `make test`. Both install missing Debian packages first.
BUILD      ?= build
BUILD_ASAN ?= build-asan
JOBS       ?= 2

.PHONY: demo test setup build build-asan clean help

help:
	@echo "make demo   install what is missing, build, run the main job on the default scene"
	@echo "make test   install what is missing, build, run every test in an optimised build and under ASan+UBSan"

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

# The sanitizer tree is built with clang: it compiles in a third less CPU time than with g++
# (measured on the whole tree), and the project is checked by a second compiler's warnings
# (docs/build.md, "The sanitizer tree with clang"). SANITIZER_CXX=g++ SANITIZER_CC=gcc for a tree built with g++.
SANITIZER_CC  ?= clang-14
SANITIZER_CXX ?= clang++-14

$(BUILD_ASAN)/CMakeCache.txt:
	CC=$(SANITIZER_CC) CXX=$(SANITIZER_CXX) cmake -S . -B $(BUILD_ASAN) -DCMAKE_BUILD_TYPE=Debug -DTHX_SANITIZE=ON \
		-DCMAKE_CXX_FLAGS_DEBUG=$(DEBUG_INFO) -DCMAKE_C_FLAGS_DEBUG=$(DEBUG_INFO)

build-asan: setup $(BUILD_ASAN)/CMakeCache.txt
	cmake --build $(BUILD_ASAN) -j$(JOBS)

demo: build
	./demo.sh $(BUILD)

# The tests need only their own executables and the programs they run (target thx_tests,
# tests/CMakeLists.txt): the benchmarks and the tools no test runs are not built here.
# The two trees' builds and tests overlap so that no core waits (docs/build.md). The real-time
# tests (label serial, which ctest runs alone) mostly wait on the clock, and the sanitizer tree's
# other tests are mostly computing: the sanitizer tree builds first; its real-time tests run while
# the optimised tree builds; then its other tests run beside all of the optimised tree's. A
# real-time test thus runs beside a compile or beside computing tests, never beside another
# real-time test. The sanitizer tree's output goes to build-asan/ctest_*.log and is printed after
# each step; make test stops after a step if anything in it failed.
SANITIZER_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
SANITIZER_CTEST = cd $(BUILD_ASAN) && $(SANITIZER_ENV) ctest --output-on-failure -j$(JOBS)
# The last lines a CI shows are the sanitizer tree's log; a failure in either tree is named again
# after it, so that those last lines say which tests failed.
FAILED_TESTS = sh -c 'echo "make test: failed in $$0:"; cat "$$0/Testing/Temporary/LastTestsFailed.log"'

test: setup $(BUILD)/CMakeCache.txt $(BUILD_ASAN)/CMakeCache.txt
	cmake --build $(BUILD_ASAN) -j$(JOBS) --target thx_tests
	@echo "make test: the sanitizer tree's real-time tests run while the optimised tree builds (their output: $(BUILD_ASAN)/ctest_serial.log)"
	@$(SANITIZER_CTEST) -L serial -LE slow > ctest_serial.log 2>&1 & tests=$$!; \
	  cmake --build $(BUILD) -j$(JOBS) --target thx_tests; built=$$?; \
	  wait $$tests; tested=$$?; \
	  echo "make test: the optimised tree is built (exit $$built); the sanitizer tree's real-time tests are done (exit $$tested):"; \
	  cat $(BUILD_ASAN)/ctest_serial.log; \
	  test $$tested -eq 0 || $(FAILED_TESTS) $(BUILD_ASAN); \
	  test $$built -eq 0 && test $$tested -eq 0
	@echo "make test: the optimised tree's tests run beside the sanitizer tree's other tests (their output: $(BUILD_ASAN)/ctest_other.log)"
	@$(SANITIZER_CTEST) -LE 'slow|serial' > ctest_other.log 2>&1 & tests=$$!; \
	  (cd $(BUILD) && ctest --output-on-failure -j$(JOBS) -LE slow); optimised=$$?; \
	  wait $$tests; sanitized=$$?; \
	  echo "make test: the optimised tree's tests are done (exit $$optimised); the sanitizer tree's other tests are done (exit $$sanitized):"; \
	  cat $(BUILD_ASAN)/ctest_other.log; \
	  test $$optimised -eq 0 || $(FAILED_TESTS) $(BUILD); \
	  test $$sanitized -eq 0 || $(FAILED_TESTS) $(BUILD_ASAN); \
	  test $$optimised -eq 0 && test $$sanitized -eq 0

clean:
	rm -rf $(BUILD) $(BUILD_ASAN)
