# volspline: `make demo` and `make test` are all the set-up a user needs on Debian 12.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
# Unity builds (CMake's UNITY_BUILD, 8 sources per batch) parse the heavy headers (Eigen, CGAL,
# CLI11, GoogleTest) once per batch instead of once per file: a clean build, as CI does, takes about
# half as long. Every name at namespace scope of a .cpp file, in an anonymous namespace too, must
# therefore be unique within its target (docs/design.md). UNITY=OFF builds file by file.
UNITY ?= ON
UNITY_FLAGS = -DCMAKE_UNITY_BUILD=$(UNITY)

.PHONY: all deps build demo test bench asan fuzz clean

all: build

deps:
	@scripts/install-deps

build: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release $(UNITY_FLAGS) $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	$(BUILD_DIR)/bin/volspline demo --out out/demo

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD_DIR)/bin/evaluation_bench

# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (used by CI), without the
# tests labelled "slow" (minutes each under the sanitizers; `make test` runs them). -g1 keeps line
# numbers in the sanitizers' stack traces at a fraction of the cost of full debug information.
# ASAN_LABELS= runs everything. Built with clang, the same build also holds the libFuzzer targets
# (`make fuzz`): the library is compiled once for both (docs/testing.md).
ASAN_LABELS ?= -LE slow
SANITIZER_CONFIGURE = CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O0 -g1" -DVOLSPLINE_SANITIZE=ON -DVOLSPLINE_BUILD_FUZZ=ON -DVOLSPLINE_BUILD_BENCH=OFF $(UNITY_FLAGS) $(CMAKE_FLAGS) >/dev/null
asan: deps
	@$(SANITIZER_CONFIGURE)
	@cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS) $(ASAN_LABELS)

# libFuzzer targets, in the sanitizer build (clang, AddressSanitizer + UndefinedBehaviorSanitizer,
# coverage instrumentation in the whole library); FUZZ_SECONDS per target (EXCHANGE_FUZZ_SECONDS
# for the scene, G+Smo, IRIT, VTU, skeleton and volume-data readers).
FUZZ_SECONDS ?= 10
EXCHANGE_FUZZ_SECONDS ?= 5
FUZZ = build-asan/bin
FUZZ_WORK = build-asan/fuzz-work
fuzz: deps
	@$(SANITIZER_CONFIGURE)
	@cmake --build build-asan -j $(JOBS) --target model_reader_fuzz mesh_reader_fuzz scene_reader_fuzz gismo_xml_fuzz irit_itd_fuzz vtu_reader_fuzz skeleton_reader_fuzz volume_data_fuzz
	mkdir -p $(FUZZ_WORK)/corpus $(FUZZ_WORK)/corpus-mesh $(FUZZ_WORK)/corpus-scene $(FUZZ_WORK)/corpus-gismo $(FUZZ_WORK)/corpus-irit $(FUZZ_WORK)/corpus-vtu $(FUZZ_WORK)/corpus-skeleton $(FUZZ_WORK)/corpus-volume
	cp examples/*.json $(FUZZ_WORK)/corpus/ 2>/dev/null || true
	cp examples/skeletons/*.json $(FUZZ_WORK)/corpus-skeleton/
	$(FUZZ)/model_reader_fuzz -max_total_time=$(FUZZ_SECONDS) -max_len=65536 $(FUZZ_WORK)/corpus fuzz/corpus
	$(FUZZ)/mesh_reader_fuzz -max_total_time=$(FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 $(FUZZ_WORK)/corpus-mesh fuzz/corpus-mesh
	$(FUZZ)/scene_reader_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 $(FUZZ_WORK)/corpus-scene fuzz/corpus-scene
	$(FUZZ)/gismo_xml_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 $(FUZZ_WORK)/corpus-gismo fuzz/corpus-gismo
	$(FUZZ)/irit_itd_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 $(FUZZ_WORK)/corpus-irit fuzz/corpus-irit
	$(FUZZ)/vtu_reader_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 $(FUZZ_WORK)/corpus-vtu fuzz/corpus-vtu
	$(FUZZ)/skeleton_reader_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 $(FUZZ_WORK)/corpus-skeleton fuzz/corpus-skeleton
	$(FUZZ)/volume_data_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 $(FUZZ_WORK)/corpus-volume fuzz/corpus-volume

clean:
	rm -rf $(BUILD_DIR) build-asan build-fuzz out
