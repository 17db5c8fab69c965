# bdpt: make (build), make run (render the default scene), make test, make clean.
CXX      ?= g++
CXXFLAGS ?= -O2 -g -std=c++17 -Wall -Wextra -pthread
LDLIBS   ?= -lstb -pthread
ifeq ($(NATIVE),1)
CXXFLAGS += -march=native
endif

TESTS := $(patsubst tests/%.cpp,build/%,$(wildcard tests/test_*.cpp))

all: bdpt

bdpt: bdpt.cpp
	$(CXX) $(CXXFLAGS) -o $@ $< $(LDLIBS)

run: bdpt
	./bdpt scenes/cornell.scene --spp 64 --out cornell.png

build/%: tests/%.cpp bdpt.cpp
	@mkdir -p build
	$(CXX) $(CXXFLAGS) -I. -o $@ $< $(LDLIBS)

test: bdpt $(TESTS)
	@set -e; for t in $(TESTS); do echo "== $$t"; ./$$t; done

# BVH against Embree (installs libembree-dev for the yardstick in ../shared/perf).
bench: bdpt
	tests/bench.sh

clean:
	rm -rf bdpt build *.png *.pfm

.PHONY: all run test bench clean
