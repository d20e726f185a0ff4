# Thin wrapper over CMake/CTest. The two commands a new user types:
#   make demo    bootstrap, build, run the default flexible-arm scenario end to end
#   make check   bootstrap, build, run every test and gate (incl. ASan/UBSan)
# Others: make build, make bench, make fuzz, make install PREFIX=..., make clean.
BUILD   ?= build
ASAN    ?= build-asan
BENCHB  ?= build-bench
FUZZB   ?= build-fuzz
# Seconds per fuzz target: inside make check, and for make fuzz.
FUZZ_CHECK_SECONDS ?= 20
FUZZ_SECONDS ?= 600
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
PREFIX  ?= /usr/local
PY      ?= /usr/bin/python3

.PHONY: all bootstrap bootstrap-check build check check-main check-asan check-fuzz fuzz fuzz-build bench demo install clean

all: build

bootstrap:
	@scripts/bootstrap.sh

bootstrap-check:
	@scripts/bootstrap.sh check

build: bootstrap
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPython3_EXECUTABLE=$(PY)
	cmake --build $(BUILD) -j $(JOBS)

check: bootstrap-check build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)
	$(MAKE) --no-print-directory check-asan
	$(MAKE) --no-print-directory check-fuzz

check-asan:
	cmake -S . -B $(ASAN) -DCMAKE_BUILD_TYPE=Debug -DFRAC_SANITIZE=ON -DFRAC_C_ONLY=ON -DFRAC_GATES=OFF
	cmake --build $(ASAN) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(ASAN) --output-on-failure -j $(JOBS) -L c -LE gate

# libFuzzer targets (tests/fuzz, docs/fuzzing.md) with clang, ASan and UBSan.
fuzz-build: bootstrap-check
	cmake -S . -B $(FUZZB) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFRAC_FUZZ=ON \
	  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++
	cmake --build $(FUZZB) -j $(JOBS)

check-fuzz: fuzz-build
	tests/fuzz/run.sh $(FUZZB) $(FUZZ_CHECK_SECONDS)

fuzz: fuzz-build
	tests/fuzz/run.sh $(FUZZB) $(FUZZ_SECONDS)

bench: bootstrap-check
	cmake -S . -B $(BENCHB) -DCMAKE_BUILD_TYPE=Release -DFRAC_GATES=OFF -DPython3_EXECUTABLE=$(PY)
	cmake --build $(BENCHB) -j $(JOBS)
	tests/bench/run.sh $(BENCHB)

demo: build
	scripts/demo.sh $(BUILD)

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(ASAN) $(BENCHB) $(FUZZB)
