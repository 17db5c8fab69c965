# bdpt: make (build), make run (render the default scene), make test, make clean; make help lists all.
SHELL := /bin/bash
# Test programs build in parallel; a make started by a target's script (MAKELEVEL > 0) shares
# its parent's jobs instead of forcing its own, which make would warn about.
ifeq ($(MAKELEVEL),0)
MAKEFLAGS += --jobs=$(shell nproc 2>/dev/null || echo 2)
endif
CXX      ?= g++
CXXFLAGS ?= -O2 -std=c++17 -Wall -Wextra -pthread
# DEBUG=1: debug information for gdb and perf (a third more compile time).
ifeq ($(DEBUG),1)
CXXFLAGS += -g
endif
LDLIBS   ?= -lstb -pthread
# Without Debian's libstb-dev: make STB_DIR=FOLDER, where FOLDER holds stb_image_write.h (and, for
# make test, stb_image.h: public-domain headers of github.com/nothings/stb); they are then
# compiled into each program.
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

TEST_FILES := $(wildcard tests/test_*.cpp)
# ./bdpt is the lecture's renderer (bdpt.cpp) with the classroom's tools (classroom/), one compile.
RENDERER := bdpt.cpp classroom/classroom.cpp $(wildcard classroom/*.h)
TEST_HEADERS := classroom/physics.h tests/homework/mistakes.h tests/helpers.h tests/lecture_test.h tests/bench.h tests/rays.h classroom/workshop/workshop.h classroom/workshop/densities.h classroom/workshop/worked_path.h

all: bdpt

# The compile line, rewritten only when it changes: switching NATIVE (or CXXFLAGS) rebuilds.
build/flags: FORCE
	@mkdir -p build
	@echo '$(CXX) $(CXXFLAGS) $(LDLIBS)' | cmp -s - $@ || echo '$(CXX) $(CXXFLAGS) $(LDLIBS)' > $@
FORCE:

bdpt: $(RENDERER) build/flags
	$(CXX) $(CXXFLAGS) -o $@ classroom/classroom.cpp $(LDLIBS)

# The lecture's file alone, as a student compiles it (g++ -O2 -std=c++17 -pthread bdpt.cpp -lstb):
# make test renders every method with it and checks that ./bdpt renders the same bits.
build/bdpt-lecture: bdpt.cpp build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -o $@ bdpt.cpp $(LDLIBS)

run: bdpt
	@mkdir -p build
	./bdpt scenes/cornell.scene --spp 64 --out build/cornell.png

# One test file alone, as its own program (make build/test_bdpt), for work on it: with debug
# information.
build/%: tests/%.cpp $(RENDERER) $(TEST_HEADERS) build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -g -I. -o $@ $< $(LDLIBS)

# make test: every test file in one program (tests/all_tests.cpp), so that bdpt.cpp is compiled
# once; tests/run_tests.sh runs it file by file, one line each, and sums them on the last line.
build/all_tests: tests/all_tests.cpp $(TEST_FILES) $(RENDERER) $(TEST_HEADERS) build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)

# The BVH tests once more as built by NATIVE=1 (8-wide AVX nodes where the CPU has AVX), and as
# on a CPU without SSE (the scalar box test); the lecture alone (tests/lecture_test.h: no
# classroom) and of it only the BVH's tests (BDPT_BVH_ONLY), at -O1 without debug information,
# which leaves the arithmetic (no fast-math, no fused multiply-adds) as it is: a sixth of the
# compile time of the whole renderer at -O2.
BVH_TEST := tests/test_bvh.cpp bdpt.cpp tests/lecture_test.h tests/rays.h build/flags
build/native/test_bvh: $(BVH_TEST)
	@mkdir -p build/native
	$(CXX) $(filter-out -O2 -g,$(CXXFLAGS)) -O1 $(NATIVE_FLAGS) -DBDPT_BVH_ONLY -I. -o $@ $< $(LDLIBS)
build/scalar/test_bvh: $(BVH_TEST)
	@mkdir -p build/scalar
	$(CXX) $(filter-out -O2 -g,$(CXXFLAGS)) -O1 -U__SSE2__ -U__AVX__ -DBDPT_BVH_ONLY -I. -o $@ $< $(LDLIBS)

# It says what it compiles before it does (about a minute of 2 cores), and its last lines give the
# whole time, compiling included, and the count. The test program holds ./bdpt's main too: a test
# of the running program (Ctrl-C, --live, a memory limit) starts it as ./bdpt (tests/helpers.h),
# so the renderer with the classroom is compiled once, not twice.
TEST_PROGRAMS := build/bdpt-lecture build/all_tests build/native/test_bvh build/scalar/test_bvh
test:
	@echo "make test: compiling bdpt.cpp alone and the test programs (about a minute), then the tests"
	@export TEST_START=$$(date +%s); $(MAKE) --no-print-directory -s $(TEST_PROGRAMS) && \
	  tests/run_tests.sh build/all_tests build/native/test_bvh build/scalar/test_bvh

# Speed against accuracy (gnuplot-nox), classroom/workshop/charts.sh. Quick by default, into build/ only;
# FULL=1 gives the notes' budgets (still into build/). make figures is the one target that
# rewrites the committed figures and tables of lecture_notes/ (NOTES=1); make refs rewrites the
# committed references in scenes/refs/. make help lists them with their durations.
refs: bdpt
	@echo "make refs: rewrites scenes/refs/ (committed), 2 seeds x 90 s per scene (door-hidden 2 x 27 min): about 95 minutes"
	+classroom/workshop/charts.sh refs

# The page's references at the sizes of the notes' buttons that no reference of scenes/refs/ meets
# (committed; classroom/web/refs/).
web-refs: bdpt
	@echo "make web-refs: rewrites classroom/web/refs/ (committed), 2 seeds x 60 s per reference (sds-point 2 x 4 min): about 16 CPU minutes"
	+classroom/workshop/charts.sh webrefs

# The tests' own references (committed), where no scene of scenes/refs/ fits: the room of
# sds-ior1 without its balls (test_vcm) and cornell's direct light (test_sampler). About 3 minutes.
test-refs: bdpt
	@mkdir -p build/test-refs
	./bdpt tests/sds-ior1-open.scene --method nee --res 48x32 --spp 65536 --seed 3 --out build/test-refs/sds-ior1-open.png
	./bdpt scenes/cornell.scene --method nee --mis --maxdepth 1 --sampler random --res 24x24 --spp 262144 --seed 77 --out build/test-refs/cornell-direct.png
	cp build/test-refs/sds-ior1-open.pfm build/test-refs/cornell-direct.pfm tests/refs/

charts: bdpt
	+classroom/workshop/charts.sh charts

# Every figure of a class, for a projector, into build/class/ (classroom/workshop/class.sh).
class: bdpt
	@classroom/workshop/class.sh

# The slides' six panels at 40 paths per pixel, for a class: build/panels/six-panels-40.png.
panels: bdpt
	@echo "make panels: six renders at 40 paths per pixel, about half a minute, into build/panels/"
	+classroom/workshop/charts.sh panels

efficiency: bdpt
	+classroom/workshop/charts.sh efficiency

# The Metropolis methods against bdpt where they should win (door-hidden) and lose (cornell), 8
# seeds, at 64x64 with 1,024 and 128x128 with 256 mutations per pixel: build/metropolis.md
# (NOTES=1: also Appendix A's tables).
metropolis: bdpt
	+classroom/workshop/charts.sh metropolisTable

figures: bdpt build/estimators
	@echo "make figures: rewrites lecture_notes/figures/ and the tables in the pages (committed): about 35 minutes"
	+NOTES=1 classroom/workshop/charts.sh charts
	+NOTES=1 classroom/workshop/charts.sh efficiency
	+NOTES=1 classroom/workshop/charts.sh figures
	+NOTES=1 classroom/workshop/charts.sh notes

help:
	@echo "make            build ./bdpt (seconds)"
	@echo "make run        render scenes/cornell.scene into build/cornell.png (seconds)"
	@echo "Durations: wall-clock on an idle 2-core machine, CPU where said. Budgets (--time, the charts' runs) are CPU"
	@echo "seconds: a busy machine gives the same figures, later."
	@echo "make test       every test file, one line each (about 4.5 CPU minutes, 3 minutes); make test-sanitize (about 12 minutes)"
	@echo "make homework   a student's folder, build/homework/: bdpt.cpp with the tasks cut out, a README, make grade"
	@echo "                (TASKS=\"H2 H5\": some; ANSWERS=1: the notes keep their answers; seconds, 10 s the first time)"
	@echo "make grade      grades build/homework/bdpt.cpp, or HOMEWORK=path/to/bdpt.cpp, by the physics (20 s)"
	@echo "make test-homework  the grader against the solution, the stubs, 43 mistakes, a class and Gradescope (about 12 CPU minutes)"
	@echo "make grade-class SUBMISSIONS=dir  a folder per student graded with the hidden checks: build/class/grades.csv, report.md"
	@echo "make gradescope the teacher's grader for Gradescope: build/gradescope/autograder.zip (seconds)"
	@echo "make panels     the slides' six panels at 40 paths per pixel: build/panels/ (under a minute)"
	@echo "make class      a class's figures for a projector (six panels at equal samples and time, pyramid,"
	@echo "                mistakes, sds, Metropolis, error-vs-time charts): build/class/ (6.5 CPU minutes, 4.5 minutes;"
	@echo "                CLASS_SECONDS=5 shortens its equal-time runs from 20 CPU s)"
	@echo "make uneven     bdpt, mlt, pssmlt and mmlt per region on the door: build/uneven-door.png (about 1 minute)"
	@echo "make charts     error against time, every method and scene, and both samplers, 1.5 CPU s a run: build/charts/ (about 6 minutes)"
	@echo "make efficiency 1/(MSE x CPU-s) of every method, 64 samples, 2 seeds: build/efficiency.md (about 3 minutes)"
	@echo "make metropolis mlt, pssmlt and mmlt against bdpt, 8 seeds, two sizes: build/metropolis.md; mlt's mutations: build/mutations.md (about 50 minutes)"
	@echo "make bench      our BVH against Embree, cost per sample and where it goes: printed only (about 4 minutes)"
	@echo "                FULL=1 after charts, efficiency or bench: the notes' budgets (12, 25 and 15 minutes)"
	@echo "make figures    REWRITES the committed figures and tables of lecture_notes/ (about 35 minutes)"
	@echo "make refs       REWRITES the committed references in scenes/refs/ (about 95 minutes)"
	@echo "make web-refs   REWRITES the page's own references in classroom/web/refs/ (about 16 CPU minutes)"
	@echo "make test-refs  REWRITES the tests' own references in tests/refs/ (about 3 minutes)"
	@echo "make web        the page in the browser, the notes beside the methods: build/web/ (about 30 s; emscripten, libjs-katex, libjs-marked, libjs-highlight.js)"
	@echo "make serve-web  make web, then serves it at http://localhost:8000/ (PORT=...)"
	@echo "make test-web   the page in headless chromium against ./bdpt and the notes' numbers, from a file, a dead worker, phone and laptop sizes (about a minute)"
	@echo "make bench-web  WebAssembly's time per sample against ./bdpt's, one thread each, under Node and in chromium (about 2 minutes)"
	@echo "make fuzz       the scene parser under libFuzzer for FUZZ_SECONDS (60); make clean"

# The page in the browser (classroom/web/): the renderer compiled to WebAssembly by Debian's
# emscripten, with SSE's intrinsics on WebAssembly's SIMD (the BVH's 4-wide box test), the scenes
# and their references embedded, the wasm inlined into its loader (SINGLE_FILE) and that loader
# and worker.js into engine.js, whose text the page starts its workers from (a Blob), so that the
# page opens from a file as well as from a server; the lecture notes rendered by Debian's marked
# and KaTeX (build_notes.js), with their figures and KaTeX's fonts: build/web/, a static folder.
# NODE_PATH: Debian's emscripten finds its optimiser's modules (acorn) there.
WEB_FLAGS := -std=c++17 -O3 -msimd128 -msse -msse2 -fwasm-exceptions -DBDPT_STB_HEADER -I/usr/include/stb
WEB_PAGE := $(addprefix build/web/,index.html app.js style.css)
web: build/web/engine.js build/web/scenes.js build/web/notes.js build/web/code.js build/web/highlight.css build/web/katex/katex.min.css $(WEB_PAGE)
build/web-engine/bdpt-web.js: classroom/web/bdpt-web.cpp bdpt.cpp $(wildcard classroom/*.h) $(wildcard scenes/*.scene scenes/refs/*.pfm classroom/web/refs/*.pfm) tests/refs/cornell-direct.pfm
	@command -v em++ >/dev/null || { echo "make web needs Debian's emscripten: apt-get install emscripten"; exit 1; }
	@mkdir -p build/web-engine
	NODE_PATH=/usr/share/nodejs em++ $(WEB_FLAGS) -o build/web-engine/bdpt-web.tmp.js classroom/web/bdpt-web.cpp \
	  -sMODULARIZE=1 -sEXPORT_NAME=createBdpt -sALLOW_MEMORY_GROWTH=1 -sENVIRONMENT=worker -sSINGLE_FILE=1 \
	  -sEXPORTED_RUNTIME_METHODS=cwrap --embed-file scenes@/scenes --embed-file tests/refs/cornell-direct.pfm@/tests/refs/cornell-direct.pfm --embed-file classroom/web/refs@/web-refs --exclude-file '*.png' --exclude-file '*.csv'
	mv build/web-engine/bdpt-web.tmp.js $@
build/web/engine.js: build/web-engine/bdpt-web.js classroom/web/worker.js
	@mkdir -p build/web
	node -e 'const fs = require("fs"), src = process.argv.slice(1).map((f) => fs.readFileSync(f, "utf8")).join("\n"); fs.writeFileSync("$@.tmp", "const BDPT_WORKER_SOURCE = " + JSON.stringify(src) + ";\n")' $^
	mv $@.tmp $@
# The scenes' texts for the page's scene menu and editor, and two tests' scenes (a notes page names one, a mistake needs the other).
build/web/scenes.js: $(wildcard scenes/*.scene) tests/energy-generator-flat.scene tests/thin-gap.scene tests/glass-camera.scene
	@mkdir -p build/web
	node -e 'const fs = require("fs"), o = {}; for (const f of process.argv.slice(1)) o[f] = fs.readFileSync(f, "utf8"); fs.writeFileSync("$@.tmp", "const BDPT_SCENES = " + JSON.stringify(o, null, 1) + ";\n")' $^
	mv $@.tmp $@
build/web/notes.js: classroom/web/build_notes.js $(wildcard lecture_notes/*.md lecture_notes/figures/*)
	@test -f /usr/share/javascript/marked/marked.umd.js || { echo "make web needs Debian's libjs-marked: apt-get install libjs-marked"; exit 1; }
	@test -f /usr/share/javascript/katex/katex.min.js || { echo "make web needs Debian's libjs-katex: apt-get install libjs-katex"; exit 1; }
	@mkdir -p build/web
	node classroom/web/build_notes.js $@ build/web/notes/figures
# The code view: bdpt.cpp highlighted by Debian's highlight.js at build time (build_code.js).
build/web/code.js: classroom/web/build_code.js bdpt.cpp classroom/metrics.h classroom/figures.h build/homework-tools/cut
	@test -f /usr/share/javascript/highlight.js/highlight.min.js || { echo "make web needs Debian's libjs-highlight.js: apt-get install libjs-highlight.js"; exit 1; }
	@mkdir -p build/web
	node classroom/web/build_code.js $@
build/web/highlight.css: /usr/share/javascript/highlight.js/styles/atom-one-dark.css
	@mkdir -p build/web
	cp $< $@
build/web/katex/katex.min.css: /usr/share/javascript/katex/katex.min.css
	@mkdir -p build/web/katex
	cp -rL /usr/share/javascript/katex/fonts build/web/katex/
	cp $< $@
build/web/%: classroom/web/%
	@mkdir -p build/web
	cp $< $@

# make serve-web: the page at http://localhost:8000/ (PORT=...), from Python's own web server.
PORT ?= 8000
serve-web: web
	@echo "the page: http://localhost:$(PORT)/  (Ctrl-C stops the server)"
	cd build/web && python3 -m http.server $(PORT)

# make test-web: the page in headless Debian chromium, driven over its DevTools protocol
# (python3-websocket): means against ./bdpt's, every method, a scene error, a pixel's strategies,
# a screenshot (build/test-web/page.png); the path view's weights against build/worked-path's.
test-web: web bdpt build/bdpt-lecture build/worked-path
	/usr/bin/python3 tests/test_web.py

# make bench-web: time per sample of the WebAssembly build (under Node, one thread) against
# ./bdpt on one thread, cornell with bdpt, interleaved runs, medians of CPU seconds; then a panel
# of the page in chromium against ./bdpt, samples per CPU second (printed: a benchmark, no test).
build/web-bench/bdpt.js: bdpt.cpp
	@mkdir -p build/web-bench
	NODE_PATH=/usr/share/nodejs em++ $(WEB_FLAGS) -o $@ bdpt.cpp -sNODERAWFS=1 -sALLOW_MEMORY_GROWTH=1 -sSINGLE_FILE=1
bench-web: web bdpt build/web-bench/bdpt.js
	tests/bench_web.sh
	/usr/bin/python3 tests/test_web.py --bench

# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer (CI runs it too).
SANITIZE := -O1 -g -std=c++17 -Wall -Wextra -pthread -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
build/san/all_tests: tests/all_tests.cpp $(TEST_FILES) $(RENDERER) $(TEST_HEADERS)
	@mkdir -p build/san
	$(CXX) $(SANITIZE) -I. -o $@ $< $(LDLIBS)

test-sanitize: bdpt build/bdpt-lecture build/san/all_tests
	@tests/run_tests.sh build/san/all_tests

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
build/bench_rays: tests/bench_rays.cpp $(TEST_HEADERS) $(RENDERER) build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)
build/native/bench_rays: tests/bench_rays.cpp $(TEST_HEADERS) $(RENDERER) build/flags
	@mkdir -p build/native
	$(CXX) $(CXXFLAGS) $(NATIVE_FLAGS) -I. -o $@ $< $(LDLIBS)
build/embree_rays: tests/embree_rays.cpp $(TEST_HEADERS) $(RENDERER) build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS) -lembree3

bench: bdpt build/bench_rays build/native/bench_rays $(if $(EMBREE),build/embree_rays)
	@[ -n "$(EMBREE)" ] || echo "make bench: Embree is not installed (apt-get install libembree-dev), so there are no ratios"
	tests/bench.sh

# Error at equal samples and efficiency 1/(MSE x CPU-s) of every method (tests/efficiency.cpp).
build/efficiency: tests/efficiency.cpp $(TEST_HEADERS) $(RENDERER) build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)

# The densities of page 10's "Combination of Estimators: Example" (classroom/workshop/estimators.cpp).
build/estimators: classroom/workshop/estimators.cpp classroom/workshop/workshop.h classroom/workshop/densities.h $(RENDERER) build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)
# Pages 7 and 10M's paths worked with numbers (classroom/workshop/worked_path.cpp).
build/worked-path: classroom/workshop/worked_path.cpp classroom/workshop/worked_path.h classroom/physics.h bdpt.cpp build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -Iclassroom -Iclassroom/workshop -o $@ $< $(LDLIBS)

# Uneven convergence (classroom/workshop/uneven.cpp): bdpt, mlt, pssmlt and mmlt per region on the door scene at
# equal time, into build/ (make figures puts its figure into the notes).
build/uneven: classroom/workshop/uneven.cpp classroom/workshop/workshop.h $(RENDERER) build/flags
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)
uneven: build/uneven
	@echo "make uneven: bdpt, mlt, pssmlt and mmlt, 8 seeds x 2 s each on one thread: about 1 minute, into build/"
	./build/uneven $(UNEVEN_ARGS)

clean:
	rm -rf bdpt build *.png *.pfm

.PHONY: all run test test-sanitize test-homework homework grade grade-class gradescope web serve-web test-web bench-web fuzz bench efficiency metropolis uneven refs web-refs charts panels class figures help clean FORCE

# ---- Homework (classroom/homework/): tasks cut from bdpt.cpp, graded by the physics.
# make homework [TASKS="H2 H5"] [ANSWERS=1]: the student's folder build/homework/ (bdpt.cpp with the
# tasks' bodies as TODOs and stubs, the scenes, the notes without their answers for the instructor
# (ANSWERS=1 keeps them), README.md, a Makefile with make and make grade, the grader and its data,
# which the complete renderer makes once: build/homework-data/).
# make grade [HOMEWORK=path/to/bdpt.cpp]: grades that file (by default build/homework/bdpt.cpp)
# against the same data. make test-homework: the solution full marks, the stubs none, every
# mistake of tests/homework/mistakes.txt named and no other task's points lost.
build/homework-tools/cut: classroom/homework/cut.cpp classroom/definitions.h
	@mkdir -p build/homework-tools
	$(CXX) -O1 -std=c++17 -Wall -Wextra -o $@ $<
build/homework-tools/grade-solution: classroom/homework/grade.cpp classroom/homework/harness.h classroom/physics.h bdpt.cpp build/flags
	@mkdir -p build/homework-tools
	$(CXX) $(CXXFLAGS) -I. -Iclassroom -o $@ $< $(LDLIBS)
HOMEWORK_DATA_INPUTS := scenes/refs/cornell.pfm scenes/refs/cornell-point.pfm tests/refs/cornell-direct.pfm scenes/cornell.scene scenes/energy-generator.scene
build/homework-data/numbers.txt: build/homework-tools/grade-solution $(HOMEWORK_DATA_INPUTS)
	@echo "make homework: the grader's data, rendered once by the complete renderer (about 10 seconds)"
	@rm -rf build/homework-data.tmp
	build/homework-tools/grade-solution --write-data build/homework-data.tmp
	@rm -rf build/homework-data && mv build/homework-data.tmp build/homework-data
HOMEWORK_DIR ?= build/homework
homework: build/homework-tools/cut build/homework-data/numbers.txt
	@if [ -f $(HOMEWORK_DIR)/bdpt.cpp ] && ! cmp -s $(HOMEWORK_DIR)/bdpt.cpp $(HOMEWORK_DIR)/grader/handed-out.cpp; then \
	  echo "make homework: $(HOMEWORK_DIR)/bdpt.cpp has been worked on since it was handed out: move $(HOMEWORK_DIR) away first (nothing written)"; exit 1; fi
	@rm -rf $(HOMEWORK_DIR).tmp && mkdir -p $(HOMEWORK_DIR).tmp/grader $(HOMEWORK_DIR).tmp/scenes
	@build/homework-tools/cut classroom/homework/tasks bdpt.cpp $(HOMEWORK_DIR).tmp "$(TASKS)" | sed 's|$(HOMEWORK_DIR).tmp/|$(HOMEWORK_DIR)/|'
	@cp scenes/*.scene $(HOMEWORK_DIR).tmp/scenes/
	@mkdir -p $(HOMEWORK_DIR).tmp/lecture_notes && cp -r lecture_notes/figures $(HOMEWORK_DIR).tmp/lecture_notes/
	@for page in lecture_notes/*.md; do awk -v keep=$(if $(ANSWERS),1,0) -f classroom/homework/strip_answers.awk $$page > $(HOMEWORK_DIR).tmp/$$page; done
	@cp classroom/homework/grade.cpp classroom/homework/harness.h classroom/physics.h $(HOMEWORK_DIR).tmp/grader/
	@cp -r build/homework-data $(HOMEWORK_DIR).tmp/grader/data
	@cp classroom/homework/Makefile.student $(HOMEWORK_DIR).tmp/Makefile
	@mkdir -p $(HOMEWORK_DIR).tmp/tools && cp classroom/workshop/worked_path.cpp classroom/workshop/worked_path.h $(HOMEWORK_DIR).tmp/tools/
	@cp $(HOMEWORK_DIR).tmp/bdpt.cpp $(HOMEWORK_DIR).tmp/grader/handed-out.cpp
	@rm -rf $(HOMEWORK_DIR) && mv $(HOMEWORK_DIR).tmp $(HOMEWORK_DIR)
HOMEWORK ?= build/homework/bdpt.cpp
GRADE_DIR := build/homework-grade
# make grade grades any file as a student's folder would: it writes one (the file as bdpt.cpp, the
# grader and its data, the tasks of the folder the file is in, or else the default ones) and runs
# that folder's own Makefile, the one rule that compiles the grader.
grade: build/homework-tools/cut build/homework-data/numbers.txt
	@test -f "$(HOMEWORK)" || { echo "make grade: no $(HOMEWORK) (make homework writes build/homework/; or make grade HOMEWORK=path/to/bdpt.cpp)"; exit 2; }
	@mkdir -p $(GRADE_DIR)/grader
	@cmp -s "$(HOMEWORK)" $(GRADE_DIR)/bdpt.cpp || cp "$(HOMEWORK)" $(GRADE_DIR)/bdpt.cpp
	@for f in classroom/homework/grade.cpp classroom/homework/harness.h classroom/physics.h; do cmp -s $$f $(GRADE_DIR)/grader/$$(basename $$f) || cp $$f $(GRADE_DIR)/grader/; done
	@cmp -s classroom/homework/Makefile.student $(GRADE_DIR)/Makefile || cp classroom/homework/Makefile.student $(GRADE_DIR)/Makefile
	@ln -sfn ../../homework-data $(GRADE_DIR)/grader/data && ln -sfn ../../scenes $(GRADE_DIR)/scenes
	@if [ -f $(dir $(HOMEWORK))grader/tasks.txt ]; then cp $(dir $(HOMEWORK))grader/tasks.txt $(GRADE_DIR)/grader/tasks.txt; \
	  else build/homework-tools/cut classroom/homework/tasks --list "$(TASKS)" > $(GRADE_DIR)/grader/tasks.txt; fi
	@echo "make grade: $(HOMEWORK), in $(GRADE_DIR)/"
	@$(MAKE) --no-print-directory -C $(GRADE_DIR) grade $(if $(TASK),TASK=$(TASK))

# A course's grading: the teacher's grader (grade.cpp with hidden.h's checks, -DBDPT_HIDDEN_CHECKS),
# which no student's folder holds.
# make grade-class SUBMISSIONS=dir [TASKS="H1 H2 ..."]: every student's folder of dir (each with its
# bdpt.cpp) graded, two at a time: build/class/grades.csv, build/class/report.md (what the class got
# wrong, and its chart build/class/mistakes.svg), each student's log in build/class/work/.
grade-class: build/homework-tools/cut build/homework-data/numbers.txt
	@test -n "$(SUBMISSIONS)" || { echo "make grade-class SUBMISSIONS=dir: a folder holding a folder per student, each with its bdpt.cpp"; exit 2; }
	@mkdir -p build/class
	@build/homework-tools/cut classroom/homework/tasks --list "$(TASKS)" > build/class/tasks.txt
	@python3 classroom/homework/grade_class.py "$(SUBMISSIONS)" build/class build/class/tasks.txt build/homework-data $(GRADE_JOBS)

# make gradescope [TASKS="H1 H2 ..."]: build/gradescope/autograder.zip, for Gradescope's autograder:
# setup.sh and run_autograder at its root (classroom/homework/gradescope/), the teacher's grader,
# its data and the scenes. Python's zipfile writes it (keeping run_autograder's mode).
gradescope: build/homework-tools/cut build/homework-data/numbers.txt
	@rm -rf build/gradescope/package && mkdir -p build/gradescope/package/grader build/gradescope/package/scenes
	@cp classroom/homework/gradescope/setup.sh classroom/homework/gradescope/run_autograder build/gradescope/package/
	@cp classroom/homework/grade.cpp classroom/homework/harness.h classroom/homework/hidden.h classroom/physics.h build/gradescope/package/grader/
	@cp -r build/homework-data build/gradescope/package/grader/data
	@cp scenes/*.scene build/gradescope/package/scenes/
	@build/homework-tools/cut classroom/homework/tasks --list "$(TASKS)" > build/gradescope/package/grader/tasks.txt
	@cd build/gradescope/package && rm -f ../autograder.zip.tmp && python3 -m zipfile -c ../autograder.zip.tmp setup.sh run_autograder grader scenes && \
	  mv ../autograder.zip.tmp ../autograder.zip
	@echo "make gradescope: build/gradescope/autograder.zip (tasks $$(cut -d' ' -f1 build/gradescope/package/grader/tasks.txt | tr '\n' ' '))"

build/test_homework: tests/homework/test_homework.cpp tests/homework/mistakes.h
	@mkdir -p build
	$(CXX) -O1 -std=c++17 -Wall -Wextra -o $@ $<
test-homework: build/homework-tools/cut build/homework-data/numbers.txt build/test_homework build/worked-path
	@echo "make test-homework: the solution, the stubs, every mistake of tests/homework/mistakes.txt, a class and Gradescope's package graded (about 60 compiles: 7 minutes of 2 cores)"
	build/test_homework
