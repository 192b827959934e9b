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
# ASAN_LABELS= runs everything.
ASAN_LABELS ?= -LE slow
asan: deps
	@cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O0 -g1" -DVOLSPLINE_SANITIZE=ON -DVOLSPLINE_BUILD_BENCH=OFF $(UNITY_FLAGS) $(CMAKE_FLAGS) >/dev/null
	@cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS) $(ASAN_LABELS)

# libFuzzer targets built with clang (-O1 with line tables: what the sanitizers need for their
# reports, cheaper to build than RelWithDebInfo); FUZZ_SECONDS per target (EXCHANGE_FUZZ_SECONDS
# for the scene, G+Smo, IRIT and VTU readers).
FUZZ_SECONDS ?= 10
EXCHANGE_FUZZ_SECONDS ?= 5
fuzz: deps
	@CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" -DVOLSPLINE_BUILD_FUZZ=ON -DVOLSPLINE_BUILD_TESTS=OFF -DVOLSPLINE_BUILD_BENCH=OFF $(UNITY_FLAGS) >/dev/null
	@cmake --build build-fuzz -j $(JOBS) --target model_reader_fuzz mesh_reader_fuzz scene_reader_fuzz gismo_xml_fuzz irit_itd_fuzz vtu_reader_fuzz skeleton_reader_fuzz volume_data_fuzz
	mkdir -p build-fuzz/corpus build-fuzz/corpus-mesh && cp examples/*.json build-fuzz/corpus/ 2>/dev/null || true
	build-fuzz/bin/model_reader_fuzz -max_total_time=$(FUZZ_SECONDS) -max_len=65536 build-fuzz/corpus fuzz/corpus
	build-fuzz/bin/mesh_reader_fuzz -max_total_time=$(FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 build-fuzz/corpus-mesh fuzz/corpus-mesh
	mkdir -p build-fuzz/corpus-scene build-fuzz/corpus-gismo build-fuzz/corpus-irit build-fuzz/corpus-vtu
	build-fuzz/bin/scene_reader_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 build-fuzz/corpus-scene fuzz/corpus-scene
	build-fuzz/bin/gismo_xml_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 build-fuzz/corpus-gismo fuzz/corpus-gismo
	build-fuzz/bin/irit_itd_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 build-fuzz/corpus-irit fuzz/corpus-irit
	build-fuzz/bin/vtu_reader_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 build-fuzz/corpus-vtu fuzz/corpus-vtu
	mkdir -p build-fuzz/corpus-skeleton && cp examples/skeletons/*.json build-fuzz/corpus-skeleton/
	build-fuzz/bin/skeleton_reader_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 build-fuzz/corpus-skeleton fuzz/corpus-skeleton
	mkdir -p build-fuzz/corpus-volume
	build-fuzz/bin/volume_data_fuzz -max_total_time=$(EXCHANGE_FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=2048 build-fuzz/corpus-volume fuzz/corpus-volume

clean:
	rm -rf $(BUILD_DIR) build-asan build-fuzz out
