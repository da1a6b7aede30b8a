# The two commands a newcomer needs (see README.md):
#   make demo   install what the demo needs, build the vdg tool, run the main job on the shipped
#               examples -> out/demo/
#   make test   install every dependency, build (warnings as errors) and run every test, then the
#               same tests again under AddressSanitizer + UndefinedBehaviorSanitizer, then a
#               bounded run of every fuzz target (make fuzz); ends with a table of its stages'
#               times (also in build/test-stages.txt; CONTRIBUTING.md, "The time budget")
# Other targets: build, bench, fuzz (FUZZ_SECONDS per target, FUZZ_JOBS at a time), format, clean.
JOBS ?= 2
BUILD := build/release
ASAN_BUILD := build/asan
FUZZ_BUILD := build/fuzz
FUZZ_SECONDS ?= 20
FUZZ_JOBS ?= $(JOBS)
# make test's tests must not skip: it installs the glTF validator, Slurm + munge, Xvfb, ffmpeg,
# Node with web/node_modules + Chromium, and Blender.
REQUIRE := VDG_REQUIRE_GLTF_VALIDATOR=1 VDG_REQUIRE_SLURM=1 VDG_REQUIRE_XVFB=1 VDG_REQUIRE_FFMPEG=1 \
           VDG_REQUIRE_WEB=1 VDG_REQUIRE_BLENDER=1 VDG_REQUIRE_PYTHON=1

.PHONY: deps demo-deps build demo test test-release test-asan fuzz bench format clean \
        ci-build ci-ctest asan-build asan-ctest fuzz-build fuzz-run

deps:
	@scripts/install-deps

demo-deps:
	@scripts/install-deps --demo

$(BUILD)/CMakeCache.txt:
	cmake --preset release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# The demo needs the tool, the Python module (import vdg, docs/python.md) and the Blender add-on's
# zip (docs/blender.md): no tests, benchmarks or example generators are compiled for it. The module
# is for Debian's python3 (Blender's Python).
demo: demo-deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS) --target vdg vdg_python vdg_blender_addon
	scripts/demo $(BUILD)/bin/vdg out/demo
	@echo "== import vdg (PYTHONPATH=$(BUILD)/python /usr/bin/python3; docs/python.md)"
	PYTHONPATH=$(BUILD)/python /usr/bin/python3 -c \
	  "import vdg; m = vdg.load('examples/spot/spot.vdg.json'); print(m); print(m.weights([0.7, 0.2, 0.7]))"

# The stages of make test, each also a target of its own.
ci-build:
	cmake --preset ci
	cmake --build build/ci -j $(JOBS)
ci-ctest:
	$(REQUIRE) ctest --test-dir build/ci --output-on-failure -j $(JOBS)
asan-build:
	cmake --preset asan
	cmake --build $(ASAN_BUILD) -j $(JOBS)
# LP_NUM_THREADS=0: Mesa's llvmpipe renders without worker threads under the sanitizers.
# LeakSanitizer's exit check stops every thread from a tracer process, and with llvmpipe's threads
# alive that tracer dies of SIGSEGV ("Tracer caught signal 11 ... LeakSanitizer has encountered a
# fatal error") in whichever rendering process the memory layout of the day picks: a crash of the
# sanitizer, not a finding (vdg render in morph3d's CLI test, 2026-12-03). Leak checks stay on.
# The install and farm tests check the package layout and Slurm's job arrays, not vdg's memory: they
# run in the ci stage only (-LE), as do the client tests (VDG_CLIENT_TESTS=OFF in the asan preset).
# So do the README's and the tutorial's command blocks and the Khronos validator's verdicts (-E): the
# vdg code they run is run under the sanitizers by the CLI tests of the same commands (the glTF
# exports, compressed ones too, are GltfCli's and gltf_compress_test's), and the validator is a Node
# program; under the sanitizers they were two minutes of the stage for no reach of their own.
asan-ctest:
	LP_NUM_THREADS=0 $(REQUIRE) ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS) -LE '^(install|farm)$$' \
	  -E '^cli\.(readme_block|tutorial)$$|Pass(es)?TheKhronosValidator$$'
# libFuzzer + ASan + UBSan (clang): every target FUZZ_SECONDS on a copy of fuzz/corpus in
# build/fuzz, FUZZ_JOBS at a time; fails on any finding (see CONTRIBUTING.md, "Fuzzing").
fuzz-build:
	cmake --preset fuzz
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target vdg_fuzzers
fuzz-run:
	fuzz/run-fuzzers -j $(FUZZ_JOBS) $(FUZZ_BUILD) $(FUZZ_SECONDS)

test-release: deps ci-build ci-ctest
test-asan: deps asan-build asan-ctest
fuzz: deps fuzz-build fuzz-run

test:
	@scripts/run-stages build/test-stages.txt \
	  install-deps  "scripts/install-deps" \
	  "build ci"    "$(MAKE) --no-print-directory ci-build" \
	  "tests ci"    "$(MAKE) --no-print-directory ci-ctest" \
	  "build asan"  "$(MAKE) --no-print-directory asan-build" \
	  "tests asan"  "$(MAKE) --no-print-directory asan-ctest" \
	  "build fuzz"  "$(MAKE) --no-print-directory fuzz-build" \
	  "run fuzz"    "$(MAKE) --no-print-directory fuzz-run"

bench: build
	@for b in $(BUILD)/bench/vdg_bench_*; do echo "== $$b"; $$b; done

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf build out
