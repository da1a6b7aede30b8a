# The two commands a newcomer needs (see README.md):
#   make demo   install dependencies, build, run the main job on the shipped example -> out/demo/
#   make test   install dependencies, build (warnings as errors) and run every test, then the
#               same tests again under AddressSanitizer + UndefinedBehaviorSanitizer, then a
#               bounded run of every fuzz target (make fuzz)
# Other targets: build, bench, fuzz (FUZZ_SECONDS per target, default 40), format, clean.
JOBS ?= 2
BUILD := build/release
ASAN_BUILD := build/asan
FUZZ_BUILD := build/fuzz
FUZZ_SECONDS ?= 40

.PHONY: deps build demo test test-release test-asan fuzz bench format clean

deps:
	@scripts/install-deps

$(BUILD)/CMakeCache.txt:
	cmake --preset release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	scripts/demo $(BUILD)/bin/vdg out/demo

# make test installs the glTF validator, Slurm + munge and Xvfb (scripts/install-deps), so their
# tests (tests/tools, tests/farm, tests/studio's window test) must not skip here.
test-release: deps
	cmake --preset ci
	cmake --build build/ci -j $(JOBS)
	VDG_REQUIRE_GLTF_VALIDATOR=1 VDG_REQUIRE_SLURM=1 VDG_REQUIRE_XVFB=1 ctest --test-dir build/ci --output-on-failure -j $(JOBS)

test-asan: deps
	cmake --preset asan
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	VDG_REQUIRE_GLTF_VALIDATOR=1 VDG_REQUIRE_SLURM=1 VDG_REQUIRE_XVFB=1 ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

# libFuzzer + ASan + UBSan (clang): each target FUZZ_SECONDS on a copy of fuzz/corpus in build/fuzz;
# fails on any finding (see CONTRIBUTING.md, "Fuzzing").
fuzz: deps
	cmake --preset fuzz
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target vdg_fuzzers
	fuzz/run-fuzzers $(FUZZ_BUILD) $(FUZZ_SECONDS)

test: test-release test-asan fuzz

bench: build
	@for b in $(BUILD)/bench/vdg_bench_*; do echo "== $$b"; $$b; done

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf build out
