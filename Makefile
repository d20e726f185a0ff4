# Thin wrapper over CMake/CTest. The two commands a new user types:
#   make demo    bootstrap, build, run the default flexible-arm scenario end to end
#   make check   bootstrap, build, run every test and gate (incl. ASan/UBSan)
# Others: make build, make bench, make install PREFIX=..., make clean.
BUILD   ?= build
ASAN    ?= build-asan
BENCHB  ?= build-bench
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
PREFIX  ?= /usr/local
PY      ?= /usr/bin/python3

.PHONY: all bootstrap bootstrap-check build check check-main check-asan bench demo install clean

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

check-asan:
	cmake -S . -B $(ASAN) -DCMAKE_BUILD_TYPE=Debug -DFRAC_SANITIZE=ON -DFRAC_C_ONLY=ON -DFRAC_GATES=OFF
	cmake --build $(ASAN) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(ASAN) --output-on-failure -j $(JOBS) -L c -LE gate

bench: bootstrap-check
	cmake -S . -B $(BENCHB) -DCMAKE_BUILD_TYPE=Release -DFRAC_GATES=OFF -DPython3_EXECUTABLE=$(PY)
	cmake --build $(BENCHB) -j $(JOBS)
	tests/bench/run.sh $(BENCHB)

demo: build
	scripts/demo.sh $(BUILD)

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(ASAN) $(BENCHB)
