# The two commands of the README, plus a few conveniences. Each target installs what is
# missing (scripts/install-deps), configures and builds before it runs anything.
PRESET ?= release
BUILD_DIR := build/$(PRESET)
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
SCREENSHOT ?= $(BUILD_DIR)/sandbox.png

.PHONY: all deps configure build run test charts clean

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

clean:
	rm -rf build
