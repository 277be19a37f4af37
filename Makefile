# Plenopath Studio — the two commands that matter: `make run` and `make test`.
BUILD_DIR ?= build
BUILD_TYPE ?= RelWithDebInfo
JOBS ?= $(shell nproc)
SANITIZE ?= $(PLENOPATH_SANITIZE)
ifneq ($(SANITIZE),)
  BUILD_DIR := build-sanitize
  BUILD_TYPE := Debug
endif
CMAKE_FLAGS ?=
# ccache hits across clones: hash paths relative to the source tree, not the absolute folder.
export CCACHE_BASEDIR := $(CURDIR)
export CCACHE_NOHASHDIR := 1
# GUI and VTK tests need a display: use the real one if there is one, otherwise a virtual X server.
ifeq ($(DISPLAY),)
  WITH_DISPLAY := xvfb-run -a -s "-screen 0 1600x1000x24"
else
  WITH_DISPLAY :=
endif

.PHONY: all deps configure build run test bench format format-check fuzz clean screenshot

all: build

deps:
	@bash cmake/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) \
	  -DPLENOPATH_SANITIZE=$(SANITIZE) $(CMAKE_FLAGS) > $(BUILD_DIR).configure.log 2>&1 \
	  || (cat $(BUILD_DIR).configure.log; exit 1)

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

run: build
	@bash app/run-sample.sh $(BUILD_DIR)

test: build
	@cd $(BUILD_DIR) && $(WITH_DISPLAY) ctest --output-on-failure -j $(JOBS) --timeout 900

bench: build
	@bash tests/bench/run-all.sh $(BUILD_DIR)

fuzz: CMAKE_FLAGS += -DPLENOPATH_BUILD_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DPLENOPATH_BUILD_STUDIO=OFF
fuzz: BUILD_DIR := build-fuzz
FUZZ_TARGETS := fuzz_dxf_import fuzz_gps_track fuzz_image_header fuzz_project fuzz_path fuzz_path_points fuzz_anchors fuzz_rig fuzz_tour_json fuzz_spherical_video
FUZZ_SECONDS ?= 600
fuzz: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target $(FUZZ_TARGETS)
	@bash tests/fuzz/run-long.sh $(BUILD_DIR) $(FUZZ_SECONDS)

screenshot: build
	@bash app/take-screenshot.sh $(BUILD_DIR) resources/screenshots/studio.png

format:
	@git ls-files -z -- 'app/*.cpp' 'app/*.h' 'widgets/*.cpp' 'widgets/*.h' 'model/*.cpp' 'model/*.h' \
	  'processing/*.cpp' 'processing/*.h' 'rig/*.cpp' 'rig/*.h' 'tests/*.cpp' 'tests/*.h' | xargs -0 clang-format -i

format-check:
	@bash cmake/check-format.sh

clean:
	rm -rf build build-sanitize build-fuzz build*.configure.log
