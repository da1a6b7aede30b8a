# The two commands a newcomer needs (see README.md):
#   make demo   install dependencies, build, run the main job on the shipped example -> out/demo/
#   make test   install dependencies, build (warnings as errors) and run every test, then the
#               same tests again under AddressSanitizer + UndefinedBehaviorSanitizer
# Other targets: build, bench, format, clean.
JOBS ?= 2
BUILD := build/release
ASAN_BUILD := build/asan

.PHONY: deps build demo test test-release test-asan bench format clean

deps:
	@scripts/install-deps

$(BUILD)/CMakeCache.txt:
	cmake --preset release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	scripts/demo $(BUILD)/bin/vdg out/demo

test-release: deps
	cmake --preset ci
	cmake --build build/ci -j $(JOBS)
	ctest --test-dir build/ci --output-on-failure -j $(JOBS)

test-asan: deps
	cmake --preset asan
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

test: test-release test-asan

bench: build
	@for b in $(BUILD)/bench/vdg_bench_*; do echo "== $$b"; $$b; done

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf build out
