# Thin wrapper over CMake. `make demo` and `make test` install what is missing first.
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
BUILD ?= build
ASAN_BUILD ?= build-asan
FUZZ_BUILD ?= build-fuzz
# Seconds per fuzz target: `make fuzz` 60; the short run in `make test` 60 on CI (CI=true), else 10.
FUZZ_SECONDS ?= 60
ifeq ($(CI),true)
TEST_FUZZ_SECONDS ?= 60
else
TEST_FUZZ_SECONDS ?= 10
endif

.PHONY: all deps build demo python test test-fast asan fuzz fuzz-build format format-check clean

all: build

deps:
	@sh scripts/install-deps.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	@sh scripts/demo.sh $(BUILD)/ryushi

# The Python package (python/ryushi, docs/python.md) for Debian's python3: the library built and
# the package put on python3's path, so that `python3 -c 'import ryushi'` works.
python: build
	@sh scripts/python-setup.sh $(BUILD)

# Whole suite: release build (unit, physics and command-line tests), then the unit tests
# again under AddressSanitizer and UndefinedBehaviorSanitizer, then a short fuzz run of every
# fuzz target (which must find nothing).
test: build asan fuzz-build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure -L unit -j $(JOBS)
	sh scripts/fuzz.sh $(FUZZ_BUILD) $(TEST_FUZZ_SECONDS)

test-fast: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

$(ASAN_BUILD)/CMakeCache.txt:
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DRY_SANITIZE=ON

asan: deps $(ASAN_BUILD)/CMakeCache.txt
	cmake --build $(ASAN_BUILD) -j $(JOBS)

$(FUZZ_BUILD)/CMakeCache.txt:
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRY_FUZZ=ON

fuzz-build: deps $(FUZZ_BUILD)/CMakeCache.txt
	cmake --build $(FUZZ_BUILD) -j $(JOBS)

# libFuzzer on the case-file reader and the STL reader, FUZZ_SECONDS each (fuzz/, docs/reliability.md).
fuzz: fuzz-build
	sh scripts/fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

format:
	clang-format -i $$(git ls-files '*.c' '*.h')

format-check:
	clang-format --dry-run --Werror $$(git ls-files '*.c' '*.h')

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD)
