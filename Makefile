# Entry points; see README.md. Every target installs missing Debian packages first.
BUILD_DIR ?= build
ASAN_DIR ?= build-asan
JOBS ?= $(shell nproc)
ODOCAL := $(BUILD_DIR)/apps/odocal/odocal

.PHONY: all deps build demo test sanitize fuzz fuzz-build bench paper format format-check clean

all: build

deps:
	scripts/install-deps

build: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j $(JOBS)

# The main job on a built-in default: simulate the paper's 3-lap circuit with worn rear tyres,
# calibrate it with the paper's iterative method, compare with the truth.
demo: build
	$(ODOCAL) demo --out $(BUILD_DIR)/demo-log

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer, built by clang. The install
# test is left out (an instrumented static library cannot link into the uninstrumented consumer),
# and so are the end-to-end runs labelled slow (not even built), which `make test` runs in
# Release. odocal's code is built at -O1 (cmake/odocalSanitizers.cmake, docs/reliability.md
# "Sanitizers"); the library also carries libFuzzer's coverage instrumentation, so that `make fuzz`
# links its harnesses in the same directory instead of compiling the library a third time.
SANITIZE_CONFIGURE = cmake -S . -B $(ASAN_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Debug \
	-DCMAKE_CXX_COMPILER=clang++ -DODOCAL_SANITIZE=ON -DODOCAL_FUZZ=ON -DODOCAL_FUNCTION_CLONES=OFF \
	-DODOCAL_BUILD_BENCHMARKS=OFF -DODOCAL_BUILD_SLOW_TESTS=OFF
sanitize: deps
	$(SANITIZE_CONFIGURE)
	cmake --build $(ASAN_DIR) -j $(JOBS)
	ctest --test-dir $(ASAN_DIR) --output-on-failure -j $(JOBS) -LE 'install|slow'

# libFuzzer harnesses (fuzz/, docs/reliability.md) in the sanitizer build's directory (ASan +
# UBSan, the library instrumented too): each runs over its corpus and regression reproducers,
# then FUZZ_SECONDS of fuzzing (0: regression only).
FUZZ_SECONDS ?= 60
FUZZERS := csv_streams yaml_configs import_map log_pipeline ros1_bag mcap sqlite3_bag message_decoder
fuzz-build: deps
	$(SANITIZE_CONFIGURE)
	cmake --build $(ASAN_DIR) -j $(JOBS) --target $(FUZZERS:%=%_fuzzer)

fuzz: fuzz-build
	tools/run_fuzzers $(ASAN_DIR) $(FUZZ_SECONDS) $(FUZZERS)

bench: build
	$(BUILD_DIR)/bench/odocal_bench
	$(BUILD_DIR)/bench/odocal_bag_bench

# The paper's tables and figures (docs/results.md): the experiments (finished pieces in
# $(PAPER_DIR) are reused; `make paper FRESH=1` recomputes everything), the speed benchmarks,
# then the plots and the markdown. Uses 3 laps of Hockenheim when ../shared has the track.
PAPER_DIR ?= $(BUILD_DIR)/paper
HOCKENHEIM := ../shared/data/tracks/hockenheim/track.csv
PAPER_BENCH := $(BUILD_DIR)/bench/odocal_bench \
  --benchmark_filter='BM_ReferenceFilter/0|BM_OdometryEkfPass|BM_LeastSquaresSolve|BM_Calibrate|BM_ParseCsv'
paper: build
	$(ODOCAL) experiment paper --out $(PAPER_DIR) \
	  $(if $(wildcard $(HOCKENHEIM)),--track $(HOCKENHEIM)) $(if $(FRESH),--fresh)
	@if [ -n "$(FRESH)" ] || [ ! -f $(PAPER_DIR)/bench.json ] || \
	    [ $(BUILD_DIR)/bench/odocal_bench -nt $(PAPER_DIR)/bench.json ]; then \
	  echo "benchmarks: $(PAPER_BENCH)"; \
	  $(PAPER_BENCH) --benchmark_out=$(PAPER_DIR)/bench.json --benchmark_out_format=json; \
	else echo "benchmarks: reusing $(PAPER_DIR)/bench.json"; fi
	/usr/bin/python3 tools/paper_report.py $(PAPER_DIR) --markdown docs/results.md \
	  --figures docs/figures/results --bench-command "$(PAPER_BENCH)"

# C++ sources as .clang-format says (CI runs format-check; `make format` rewrites them).
FORMAT_FILES = $(shell git ls-files --cached --others --exclude-standard '*.cpp' '*.hpp')
format-check: deps
	@clang-format --dry-run --Werror $(FORMAT_FILES) && echo "format-check: $(words $(FORMAT_FILES)) files formatted"

format: deps
	clang-format -i $(FORMAT_FILES)

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR)
