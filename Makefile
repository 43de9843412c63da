# Two commands do all set-up on a fresh Debian 12 machine:
#   make run   installs missing packages, builds, renders the default scene to out/default/
#   make test  installs missing packages, builds, runs every test through CTest
# and the further checks CI runs (docs/robustness.md, docs/embedding.md):
#   make test-arm64             every asset scene's state hash on arm64 (cross-built, run under
#                               qemu-aarch64) against the native build's
#   make test-compilers         the same with a Clang build against the GCC build
#   make test-sanitize          the same tests under AddressSanitizer + UndefinedBehaviorSanitizer
#   make test-install           the engine installed to a temporary prefix, examples/embed built on it
#   make fuzz [FUZZ_SECONDS=600] the three libFuzzer targets for FUZZ_SECONDS each (default 60), with clang
BUILD ?= build
JOBS ?= $(shell nproc)
PACKAGES := build-essential cmake pkg-config nlohmann-json3-dev catch2 \
            libosmesa6-dev libstb-dev zlib1g-dev libglfw3-dev xvfb xauth xdotool \
            libavcodec-dev libavformat-dev libswscale-dev libavutil-dev \
            clang libclang-rt-14-dev
SUDO := $(shell [ "$$(id -u)" -eq 0 ] || echo sudo)

SANITIZE_BUILD ?= build-sanitize
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
# gcc's -Wmaybe-uninitialized misfires on std::regex and std::function under the sanitizers.
SANITIZE_FLAGS := -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all \
                  -fno-omit-frame-pointer -Wno-maybe-uninitialized
# Leaks are reported at exit, except inside OSMesa (it keeps its context until exit): .ci/lsan.supp
# names that library only, never our code. The window tests (Xvfb, GLX) run with leak checks off:
# LSan reports 112 bytes from a driver it cannot unwind (no frame pointers), valgrind finds no leak
# in the same run, and a suppression cannot name a library the report does not show.
SANITIZE_ENV := ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 \
                LSAN_OPTIONS=suppressions=$(CURDIR)/.ci/lsan.supp:print_suppressions=0 \
                UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

.PHONY: deps build run test test-install test-sanitize fuzz clean build-sim test-arm64 test-compilers

deps:
	@missing=""; for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

run: build
	./$(BUILD)/ballbox render

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Only the engine is built (in the same tree as `make build`); the script installs its component
# to a temporary prefix and builds examples/embed there with find_package and with pkg-config.
test-install: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS) --target engine
	examples/embed/test_install.sh $(BUILD)

# A second build tree with the sanitizers in every object (benchmarks left out: not tests).
# -O1 with line tables alone: built in half the time of -O2 -g (5 min 11 s against 10 min 26 s on
# two cores), the suite as fast under the sanitizers (298 s against 302), reports still give lines.
# Without -DNDEBUG: the engine's asserts (its preconditions) are checked here, the one CI build that does.
SANITIZE_OPTIMIZE := -O1 -g1
test-sanitize: deps
	cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBALLBOX_BUILD_BENCH=OFF \
	  -DCMAKE_C_FLAGS="$(SANITIZE_FLAGS)" -DCMAKE_CXX_FLAGS="$(SANITIZE_FLAGS)" \
	  -DCMAKE_C_FLAGS_RELWITHDEBINFO="$(SANITIZE_OPTIMIZE)" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$(SANITIZE_OPTIMIZE)" \
	  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined"
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	cd $(SANITIZE_BUILD) && $(SANITIZE_ENV) ASAN_OPTIONS=detect_leaks=0 \
	  ctest --output-on-failure -j $(JOBS) -R '^play window'
	cd $(SANITIZE_BUILD) && $(SANITIZE_ENV) ctest --output-on-failure -j $(JOBS) -E '^play window'

# clang only: libFuzzer and the sanitizers instrument every library (fuzz/instrument.cmake).
fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DBALLBOX_FUZZ=ON -DBUILD_TESTING=OFF -DBALLBOX_BUILD_BENCH=OFF -DBALLBOX_WITH_GLFW=OFF
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_scene fuzz_script fuzz_snapshot ballbox
	fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

# The state hash is the same on x86-64 and arm64 and with GCC and Clang (docs/robustness.md).
# These build the engine and `ballbox sim` alone (BALLBOX_WITH_RENDER=OFF) and compare every asset
# scene's hash after HASH_STEPS steps with the native GCC build's (.ci/compare_hashes.sh).
SIM_BUILD ?= build-sim
ARM64_BUILD ?= build-arm64
CLANG_BUILD ?= build-clang
HASH_STEPS ?= 3600
SIM_PACKAGES := build-essential cmake nlohmann-json3-dev
SIM_CONFIG := -DCMAKE_BUILD_TYPE=Release -DBALLBOX_WITH_RENDER=OFF -DBUILD_TESTING=OFF \
              -DBALLBOX_BUILD_BENCH=OFF

build-sim:
	@$(MAKE) --no-print-directory deps PACKAGES="$(SIM_PACKAGES)"
	cmake -S . -B $(SIM_BUILD) $(SIM_CONFIG)
	cmake --build $(SIM_BUILD) -j $(JOBS) --target ballbox

# Linked statically, so qemu-aarch64 needs no arm64 libraries to run it.
test-arm64: build-sim
	@$(MAKE) --no-print-directory deps PACKAGES="$(SIM_PACKAGES) g++-aarch64-linux-gnu qemu-user"
	cmake -S . -B $(ARM64_BUILD) $(SIM_CONFIG) -DCMAKE_EXE_LINKER_FLAGS=-static \
	  -DCMAKE_TOOLCHAIN_FILE=$(CURDIR)/cmake/aarch64-linux-gnu.cmake
	cmake --build $(ARM64_BUILD) -j $(JOBS) --target ballbox
	.ci/compare_hashes.sh $(HASH_STEPS) x86-64 $(SIM_BUILD)/ballbox arm64 qemu-aarch64 $(ARM64_BUILD)/ballbox

test-compilers: build-sim
	@$(MAKE) --no-print-directory deps PACKAGES="$(SIM_PACKAGES) clang"
	CC=clang CXX=clang++ cmake -S . -B $(CLANG_BUILD) $(SIM_CONFIG)
	cmake --build $(CLANG_BUILD) -j $(JOBS) --target ballbox
	.ci/compare_hashes.sh $(HASH_STEPS) gcc $(SIM_BUILD)/ballbox clang $(CLANG_BUILD)/ballbox

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) $(FUZZ_BUILD) $(SIM_BUILD) $(ARM64_BUILD) $(CLANG_BUILD)

# make bench: every benchmark program into bench-out/, then docs/benchmarks.md and its plots in
# docs/img/ (bench/plots/make_page.sh), with Box2D 2.4 and Chipmunk 7 from Debian beside ballbox.
# About 20 minutes; never part of make test or CI.
BENCH_BUILD ?= build-benchmarks
.PHONY: bench
bench:
	@$(MAKE) --no-print-directory deps PACKAGES="$(PACKAGES) libbox2d-dev libchipmunk-dev gnuplot-nox"
	cmake -S . -B $(BENCH_BUILD) -DCMAKE_BUILD_TYPE=Release -DBALLBOX_BENCH_PEERS=ON -DBUILD_TESTING=OFF
	cmake --build $(BENCH_BUILD) -j $(JOBS)
	bench/plots/make_page.sh $(BENCH_BUILD) bench-out
