// make bench, our half: the BVH of bdpt.cpp on the ray benchmark's scenes and rays (tests/bench.h),
// in the same line format as tests/embree_rays.cpp, so that tests/bench.sh can divide the two.
//   build/bench_rays [--seed S] [--n N] [--rays M] [--reps R]
#include "bench.h"

int main(int argc, char** argv) {
    BenchArgs args = parseBenchArgs(argc, argv);
    // Which shapes are spheres, one byte each: Embree reads that off the hit's geomID, and a look
    // into the 96-byte Shape records would add a cache miss per hit (10% of the stress time).
    std::vector<uint8_t> isSphere;
    auto build = [&](const BenchScene& b, size_t& nodes) {
        Bvh bvh = buildBvh(b.shapes);
        nodes = bvh.nodes.size();
        isSphere.resize(b.shapes.size());
        for (size_t i = 0; i < b.shapes.size(); ++i) isSphere[i] = b.shapes[i].type == Shape::Sphere;
        return bvh;
    };
    auto trace = [&](const Bvh& bvh, const Ray& ray, bool anyHit) {
        Hit h = anyHit ? traverseBvh<true>(bvh, ray) : traverseBvh<false>(bvh, ray);
        BenchHit r;
        r.hit = h.found();
        if (r.hit && !anyHit) r.t = h.t, r.sphere = isSphere[h.shape];
        return r;
    };
    runRayBenchmark("bdpt", args, build, trace);
    return 0;
}
