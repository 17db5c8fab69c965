# bdpt: make (build), make run (render the default scene), make test, make clean.
SHELL := /bin/bash
MAKEFLAGS += --jobs=$(shell nproc 2>/dev/null || echo 2)  # test programs build in parallel
CXX      ?= g++
CXXFLAGS ?= -O2 -g -std=c++17 -Wall -Wextra -pthread
LDLIBS   ?= -lstb -pthread
# Without Debian's libstb-dev: make STB_DIR=FOLDER, where FOLDER holds stb_image_write.h (the one
# public-domain header of github.com/nothings/stb); it is then compiled into each program.
ifdef STB_DIR
CXXFLAGS += -isystem $(STB_DIR) -DBDPT_STB_HEADER
LDLIBS := $(filter-out -lstb,$(LDLIBS))
endif
# NATIVE=1: this CPU's instructions (8-wide BVH nodes with AVX); no fused multiply-adds, so
# images and ray checksums stay bit-identical to the portable (SSE2, 4-wide) build.
NATIVE_FLAGS := -march=native -ffp-contract=off
ifeq ($(NATIVE),1)
CXXFLAGS += $(NATIVE_FLAGS)
endif

TESTS := $(patsubst tests/%.cpp,build/%,$(wildcard tests/test_*.cpp))

all: bdpt

# The compile line, rewritten only when it changes: switching NATIVE (or CXXFLAGS) rebuilds.
build/flags: FORCE
	@mkdir -p build
	@echo '$(CXX) $(CXXFLAGS) $(LDLIBS)' | cmp -s - $@ || echo '$(CXX) $(CXXFLAGS) $(LDLIBS)' > $@
FORCE:

bdpt: bdpt.cpp build/flags
	$(CXX) $(CXXFLAGS) -o $@ $< $(LDLIBS)

run: bdpt
	./bdpt scenes/cornell.scene --spp 64 --out cornell.png

build/%: tests/%.cpp bdpt.cpp tests/helpers.h tests/bench.h tests/densities.h build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)

# Runs the test programs $(1); the last line sums their test cases ("N passed, N failed").
define run-tests
	@status=0; for t in $(1); do echo "== $$t"; ./$$t --reporters=notes 2>&1 | tee $$t.log; [ $${PIPESTATUS[0]} -eq 0 ] || status=1; done; \
	cat $(addsuffix .log,$(1)) | awk '/test cases:/ { p += $$6; f += $$9 } END { printf "tests: %d passed, %d failed\n", p, f }'; \
	exit $$status
endef

# The BVH tests once more as built by NATIVE=1 (8-wide AVX nodes where the CPU has AVX), and as
# on a CPU without SSE (the scalar box test).
build/native/test_bvh: tests/test_bvh.cpp bdpt.cpp tests/helpers.h tests/bench.h build/flags
	@mkdir -p build/native
	$(CXX) $(CXXFLAGS) $(NATIVE_FLAGS) -I. -o $@ $< $(LDLIBS)
build/scalar/test_bvh: tests/test_bvh.cpp bdpt.cpp tests/helpers.h tests/bench.h build/flags
	@mkdir -p build/scalar
	$(CXX) $(CXXFLAGS) -U__SSE2__ -U__AVX__ -I. -o $@ $< $(LDLIBS)

test: bdpt $(TESTS) build/native/test_bvh build/scalar/test_bvh
	$(call run-tests,$(TESTS) build/native/test_bvh build/scalar/test_bvh)

# Speed against accuracy (gnuplot-nox): references once, then charts and the failure table,
# and the slides' six-panel figure. See tests/charts.sh for the budgets.
refs: bdpt
	tests/charts.sh refs

charts: bdpt
	tests/charts.sh charts

# The slides' six panels at 40 paths per pixel, for a class: build/panels/six-panels-40.png.
panels: bdpt
	tests/charts.sh panels

figures: bdpt build/estimators
	tests/charts.sh figures
	tests/charts.sh notes

# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer (CI runs it too).
SANITIZE := -O1 -g -std=c++17 -Wall -Wextra -pthread -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
SAN_TESTS := $(patsubst tests/%.cpp,build/san/%,$(wildcard tests/test_*.cpp))

build/san/%: tests/%.cpp bdpt.cpp tests/helpers.h tests/bench.h tests/densities.h
	@mkdir -p build/san
	$(CXX) $(SANITIZE) -I. -o $@ $< $(LDLIBS)

test-sanitize: bdpt $(SAN_TESTS)
	$(call run-tests,$(SAN_TESTS))

# Fuzz the scene parser with libFuzzer (clang), from the bad-scene corpus, for FUZZ_SECONDS.
FUZZ_SECONDS ?= 60
build/fuzz_scene: tests/fuzz_scene.cpp bdpt.cpp
	@mkdir -p build
	clang++ -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -I. -o $@ $< $(LDLIBS)

fuzz: build/fuzz_scene
	@mkdir -p build/fuzz-corpus
	cp tests/bad_scenes/*.scene scenes/*.scene build/fuzz-corpus/
	./build/fuzz_scene -max_total_time=$(FUZZ_SECONDS) -max_len=4096 -timeout=10 -print_final_stats=1 build/fuzz-corpus

# The BVH against Embree on the same rays (tests/bench.sh). Embree's half is built only where
# Debian's libembree-dev is installed.
EMBREE := $(wildcard /usr/include/embree3/rtcore.h)
build/bench_rays: tests/bench_rays.cpp tests/bench.h bdpt.cpp build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)
build/native/bench_rays: tests/bench_rays.cpp tests/bench.h bdpt.cpp build/flags
	@mkdir -p build/native
	$(CXX) $(CXXFLAGS) $(NATIVE_FLAGS) -I. -o $@ $< $(LDLIBS)
build/embree_rays: tests/embree_rays.cpp tests/bench.h bdpt.cpp build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS) -lembree3

bench: bdpt build/bench_rays build/native/bench_rays $(if $(EMBREE),build/embree_rays)
	@[ -n "$(EMBREE)" ] || echo "make bench: Embree is not installed (apt-get install libembree-dev), so there are no ratios"
	tests/bench.sh

# Error at equal samples and efficiency 1/(MSE x CPU-s) of every method (tests/efficiency.cpp).
build/efficiency: tests/efficiency.cpp tests/bench.h bdpt.cpp build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)

# The densities of page 10's "Combination of Estimators: Example" (tests/estimators.cpp).
build/estimators: tests/estimators.cpp tests/bench.h tests/densities.h bdpt.cpp build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)

# Uneven convergence (tests/uneven.cpp): bdpt, mlt and mmlt per region on the door scene at
# equal time, into build/ (make figures puts its figure into the notes).
build/uneven: tests/uneven.cpp tests/bench.h bdpt.cpp build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)
uneven: build/uneven
	./build/uneven $(UNEVEN_ARGS)

# The table goes to lecture_notes/figures/efficiency.md and into Appendix A of the notes.
efficiency: build/efficiency
	./build/efficiency $(EFFICIENCY_ARGS) > build/efficiency.md.tmp && mv build/efficiency.md.tmp lecture_notes/figures/efficiency.md
	awk -v table=lecture_notes/figures/efficiency.md ' \
	  /<!-- efficiency:start -->/ { print; while ((getline line < table) > 0) print line; skip = 1; next } \
	  /<!-- efficiency:end -->/ { skip = 0 } \
	  !skip' lecture_notes/appendix-a-speed-and-accuracy.md > build/appendix-a.tmp && mv build/appendix-a.tmp lecture_notes/appendix-a-speed-and-accuracy.md
	grep -E '^\| (door|cornell|cornell-glass|glass-box) \| (nee --mis|lt|bdpt|mlt|mmlt) \|' lecture_notes/figures/efficiency.md | \
	  { echo '| scene | method | MSE | CPU-s | rays/sample | efficiency vs nee --mis | MSE share seen via mirror or glass |'; \
	    echo '|---|---|---|---|---|---|---|'; cat; } > build/metropolis-efficiency.md
	awk -v table=build/metropolis-efficiency.md ' \
	  /<!-- metropolis-efficiency:start -->/ { print; while ((getline line < table) > 0) print line; skip = 1; next } \
	  /<!-- metropolis-efficiency:end -->/ { skip = 0 } \
	  !skip' lecture_notes/16-metropolis-sampling.md > build/page16.tmp && mv build/page16.tmp lecture_notes/16-metropolis-sampling.md
	cat lecture_notes/figures/efficiency.md

clean:
	rm -rf bdpt build *.png *.pfm

.PHONY: all run test test-sanitize fuzz bench efficiency uneven refs charts panels figures clean FORCE
