# The two set-up commands of the README, plus the build they share.
BUILD_DIR ?= build
ASAN_DIR  ?= build-asan
JOBS      ?= $(shell nproc)
OUT       ?= out/paper

.PHONY: setup build run test test-asan bench report-check clean

setup:
	@bash scripts/setup.sh

$(BUILD_DIR)/build.ninja: | setup
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: setup $(BUILD_DIR)/build.ninja
	cmake --build $(BUILD_DIR) -j $(JOBS)

run: build
	$(BUILD_DIR)/radrecon paper --out $(OUT)
	@echo "Results are in $(OUT)/: report.html (open it in a browser), errors.json, table1.md, table2.md, solutions/, figures/"

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The same tests under AddressSanitizer and UndefinedBehaviorSanitizer (run by CI). Line tables
# only (-g1): the reports still name files and lines, and the objects are smaller.
test-asan: setup
	cmake -S . -B $(ASAN_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
	  -DRADRECON_SANITIZE=ON -DRADRECON_BENCHMARKS=OFF
	cmake --build $(ASAN_DIR) -j $(JOBS)
	cd $(ASAN_DIR) && ctest --output-on-failure -j $(JOBS) -LE slow

# The paper report in headless Chromium, with screenshots in out/report-check/ (docs/report.md).
report-check: build
	bash tests/paper/report_check.sh $(BUILD_DIR)/radrecon out/report-check

bench: build
	bash bench/run_benchmarks.sh

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR)
