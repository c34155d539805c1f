# The two commands of the README, plus a few conveniences. Each target installs what is
# missing (scripts/install-deps), configures and builds before it runs anything.
PRESET ?= release
BUILD_DIR := build/$(PRESET)
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
SCREENSHOT ?= $(BUILD_DIR)/sandbox.png

.PHONY: all deps configure build run test charts clean fuzz asan-fast soak format-check tidy

all: build

deps:
	@scripts/install-deps

configure: deps
	cmake --preset $(PRESET)

build: configure
	cmake --build --preset $(PRESET) -j $(JOBS)

# With a display: the sandbox in a window. Without one: render under Xvfb to a PNG and say where.
run: build
	@if [ -n "$$DISPLAY$$WAYLAND_DISPLAY" ]; then \
	  $(BUILD_DIR)/app/sandbox/sandbox $(SCENE); \
	else \
	  echo "no display: rendering $(if $(SCENE),$(SCENE),the default scene) under Xvfb instead"; \
	  xvfb-run -a -s "-screen 0 1600x1200x24" $(BUILD_DIR)/app/sandbox/sandbox $(SCENE) \
	    --screenshot $(SCREENSHOT) --frames 120 && \
	  echo "screenshot: $(abspath $(SCREENSHOT))"; \
	fi

test: build
	ctest --preset $(PRESET)

# Regenerates docs/results.md and its charts (docs/lab.md, "lab report"): sweeps of the seed's
# scenes, the stability suite and the peers, measured on this machine in one run.
charts: build
	$(BUILD_DIR)/app/lab/lab report

# The reliability checks CI runs besides `make test PRESET=ci` (docs/architecture.md, "CI").
# make fuzz SECONDS=N: each fuzz target (fuzz preset, clang; FUZZ_TARGETS, by default scene files,
# recording files and clip files of every format) for N seconds on its corpus in
# build/fuzz/corpus/TARGET, seeded by scripts/run-fuzzer; FUZZ_FLAGS adds libFuzzer options
# (FUZZ_FLAGS=-fork=2 runs two at once).
# Every target runs even when one fails; findings go to build/fuzz/artifacts/TARGET/.
fuzz: SECONDS ?= 60
fuzz: FUZZ_TARGETS ?= scene recording clip
fuzz: deps
	cmake --preset fuzz
	cmake --build --preset fuzz -j $(JOBS)
	status=0; for target in $(FUZZ_TARGETS); do \
	  scripts/run-fuzzer $$target $(SECONDS) $(FUZZ_FLAGS) || status=1; \
	done; exit $$status

# The fast physics and scene tests under AddressSanitizer and UndefinedBehaviorSanitizer (the
# asan preset, building physics_tests, scene_tests and testsupport_tests only;
# scripts/ctest-asan-fast says which run). The whole suite is make test PRESET=asan.
asan-fast: deps
	cmake --preset asan
	cmake --build --preset asan-fast -j $(JOBS)
	scripts/ctest-asan-fast

# make soak SECONDS=N: the soak test (tests/soak/) for N seconds.
soak: SECONDS ?= 300
soak: configure
	cmake --build --preset $(PRESET) -j $(JOBS) --target soak
	$(BUILD_DIR)/tests/soak/soak --seconds $(SECONDS)

format-check:
	scripts/check-format

tidy: deps
	scripts/run-tidy

clean:
	rm -rf build
