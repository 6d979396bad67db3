# Two commands set everything up on a fresh Debian 12 machine (see README.md):
#   make run    installs missing Debian packages, builds Release into build/, runs the default scene
#   make test   the same set-up, then every test through ctest (non-zero exit on any failure)
# Not part of `make test` (docs/robustness.md):
#   make fuzz      builds the libFuzzer targets with clang into build-fuzz/ and runs each for
#                  FUZZ_SECONDS; non-zero exit on a finding (without the cuda plugin: no input
#                  reader, and nvcc refuses clang's fuzzer build as its host compiler)
#   make sanitize  builds everything with ASan + UBSan into build-sanitize/ and runs the whole ctest
BUILD_DIR ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
# the default scene: a probe palpating an organ, 1.2 s in about a second; its picture and force plot land in build/output
SCENE ?= scenes/interaction/palpation.xml
# FASCIA_WITH_VTK=OFF builds without VTK (no .vtk/.vtu reader, no VTKExporter) and does not install it
FASCIA_WITH_VTK ?= ON
# FASCIA_WITH_PYTHON=OFF builds without the Python module (docs/python.md) and does not install its packages
FASCIA_WITH_PYTHON ?= ON
PYTHON_PACKAGES := python3-dev pybind11-dev python3-numpy python3-pytest python3-distributed python3-pandas python3-meshio python3-tqdm python3-matplotlib
DEBIAN_PACKAGES := build-essential cmake pkgconf libeigen3-dev libtinyxml2-dev catch2 $(if $(filter ON,$(FASCIA_WITH_VTK)),libvtk9-dev xvfb) $(if $(filter ON,$(FASCIA_WITH_PYTHON)),$(PYTHON_PACKAGES)) $(EXTRA_PACKAGES)
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TIMEOUT ?= 30
SANITIZE_DIR ?= build-sanitize
SANITIZE_CXX ?= g++
# ccache when there is one (the fuzz build compiles everything again)
CCACHE_LAUNCHER := $(if $(shell command -v ccache 2>/dev/null),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

.PHONY: deps configure build run test bench install clean fuzz sanitize

deps:
	@missing=""; for p in $(DEBIAN_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing missing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  $$SUDO apt-get update && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y --no-install-recommends $$missing; \
	fi

configure: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DFASCIA_WITH_VTK=$(FASCIA_WITH_VTK) -DFASCIA_WITH_PYTHON=$(FASCIA_WITH_PYTHON)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

run: build
	$(BUILD_DIR)/bin/fascia-run $(SCENE) --output $(BUILD_DIR)/output $(if $(filter ON,$(FASCIA_WITH_VTK)),--snapshot $(basename $(notdir $(SCENE))).png)
	@if [ -x $(BUILD_DIR)/bin/fascia-plot ] && [ -f $(BUILD_DIR)/output/probe.csv ]; then \
	  $(BUILD_DIR)/bin/fascia-plot $(BUILD_DIR)/output/probe.csv --y probe_force_z,probe_force_x --title "the probe's push (z) and friction (x)" --output $(BUILD_DIR)/output/probe_force.png && \
	  $(BUILD_DIR)/bin/fascia-plot $(BUILD_DIR)/output/probe.csv --x probe_z --scale-x -1000:mm --offset-x 65 --xlim -2,6 \
	    --y probe_force_z --xlabel "depth of the probe's tip below the organ's top (mm)" --ylabel "push on the probe (N)" \
	    --title "the probe's push against its depth (down, sliding at 5 mm, up)" --output $(BUILD_DIR)/output/probe_depth.png; fi
	@echo "see it: $(BUILD_DIR)/bin/fascia-view $(SCENE) --play   (a window; keys and mouse: docs/viewer.md)"

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD_DIR)/bin/fascia-bench --suite heml
	$(BUILD_DIR)/bin/fascia-bench --suite scaling --repeat 7
	$(BUILD_DIR)/bin/fascia-bench --suite tled --repeat 9

fuzz:
	$(MAKE) deps EXTRA_PACKAGES=clang
	cmake -S . -B $(FUZZ_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
	      -DFASCIA_FUZZ=ON -DFASCIA_BUILD_TESTS=OFF -DFASCIA_WITH_VTK=$(FASCIA_WITH_VTK) -DFASCIA_WITH_CUDA=OFF $(CCACHE_LAUNCHER)
	cmake --build $(FUZZ_DIR) -j $(JOBS)
	FUZZ_TIMEOUT=$(FUZZ_TIMEOUT) tests/fuzz/RunFuzz.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

sanitize: deps
	tests/sanitizer/Sanitize.sh $(SANITIZE_DIR) $(SANITIZE_CXX) $(JOBS) -DFASCIA_WITH_VTK=$(FASCIA_WITH_VTK)

clean:
	rm -rf $(BUILD_DIR)
