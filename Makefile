# The two set-up commands of the README, plus the build they share.
BUILD_DIR ?= build
ASAN_DIR  ?= build-asan
JOBS      ?= $(shell nproc)
OUT       ?= out/paper
FUZZ_SECONDS ?= 60
# Sanitizer reports with function names, files and lines (llvm-14, installed by setup).
export ASAN_SYMBOLIZER_PATH ?= /usr/lib/llvm-14/bin/llvm-symbolizer

.PHONY: setup build run test asan-build test-asan fuzz bench report-check clean

setup:
	@bash scripts/setup.sh

# Unity builds (sources compiled eight to an object): about half the compile time.
$(BUILD_DIR)/build.ninja: | setup
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON

build: setup $(BUILD_DIR)/build.ninja
	cmake --build $(BUILD_DIR) -j $(JOBS)

run: build
	$(BUILD_DIR)/radrecon paper --out $(OUT)
	@echo "Results are in $(OUT)/: report.html (open it in a browser), errors.json, table1.md, table2.md, solutions/, figures/"

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The sanitized tree, run by CI: clang-14 with AddressSanitizer, UndefinedBehaviorSanitizer and
# libFuzzer's coverage, at -O1 with line tables (-g1: reports name files and lines), unity-built.
# Built for x86-64-v3 where the CPU has AVX2, so that the tests run the AVX2 forms of the SIMD
# kernels (core/simd.h) there and the main build's widest (AVX-512 where the CPU has it).
ASAN_ARCH ?= $(shell grep -qw avx2 /proc/cpuinfo 2>/dev/null && echo x86-64-v3 || echo default)
asan-build: setup
	cmake -S . -B $(ASAN_DIR) -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_UNITY_BUILD=ON \
	  -DRADRECON_FUZZ=ON -DRADRECON_BENCHMARKS=OFF -DRADRECON_ARCH=$(ASAN_ARCH)
	cmake --build $(ASAN_DIR) -j $(JOBS)

# The tests under the sanitizers (the slow ones excepted), and every fuzz seed replayed.
test-asan: asan-build
	cd $(ASAN_DIR) && ctest --output-on-failure -j $(JOBS) -LE slow

# Every reader's fuzzer for FUZZ_SECONDS each, a core each (docs/hostile.md, "Fuzzing").
fuzz: asan-build
	bash fuzz/run.sh $(ASAN_DIR) $(FUZZ_SECONDS)

# The paper report in headless Chromium, with screenshots in out/report-check/ (docs/report.md).
report-check: build
	bash tests/paper/report_check.sh $(BUILD_DIR)/radrecon out/report-check

bench: build
	bash bench/run_benchmarks.sh

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR)
