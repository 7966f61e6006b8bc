# Entry points; see README.md. Every target installs missing Debian packages first.
BUILD_DIR ?= build
ASAN_DIR ?= build-asan
JOBS ?= $(shell nproc)
ODOCAL := $(BUILD_DIR)/apps/odocal/odocal

.PHONY: all deps build demo test sanitize bench clean

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

# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer. The install test is left
# out: an instrumented static library cannot link into the uninstrumented consumer.
sanitize: deps
	cmake -S . -B $(ASAN_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DODOCAL_SANITIZE=ON \
	      -DODOCAL_BUILD_BENCHMARKS=OFF
	cmake --build $(ASAN_DIR) -j $(JOBS)
	ctest --test-dir $(ASAN_DIR) --output-on-failure -j $(JOBS) -LE install

bench: build
	$(BUILD_DIR)/bench/odocal_bench

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR)
