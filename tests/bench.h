// What the benchmark programs share (make bench, make efficiency): the workshop's helpers
// (classroom/workshop/workshop.h: the renderer, medians, scenes at their references' size) and
// the ray benchmark's scenes and rays (rays.h), run in the yardstick's format.
#pragma once
#include "classroom/workshop/workshop.h"
#include "rays.h"

struct BenchArgs {
    uint64_t seed = 1;
    int n = 100000, reps = 5;
    size_t rays = 4194304;
};

inline BenchArgs parseBenchArgs(int argc, char** argv) {
    BenchArgs a;
    for (int i = 1; i + 1 < argc; i += 2) {
        std::string k = argv[i];
        double v = std::atof(argv[i + 1]);
        if (k == "--seed") a.seed = uint64_t(v);
        else if (k == "--n" && v >= 1) a.n = int(v);
        else if (k == "--rays" && v >= 64) a.rays = size_t(v);
        else if (k == "--reps" && v >= 1) a.reps = int(v);
        else { std::fprintf(stderr, "usage: %s [--seed S] [--n N] [--rays M] [--reps R]\n", argv[0]); std::exit(2); }
    }
    if (argc % 2 == 0) { std::fprintf(stderr, "usage: %s [--seed S] [--n N] [--rays M] [--reps R]\n", argv[0]); std::exit(2); }
    return a;
}

// Per scene: the build (median of reps), then each ray set with 1 and 2 threads (medians of reps,
// after one untimed warm-up), one line each in the yardstick's key=value format.
// build(scene) -> an acceleration structure A and its node count; trace(A, ray, anyHit) -> BenchHit.
template <class Build, class Trace>
inline void runRayBenchmark(const char* name, const BenchArgs& args, Build build, Trace trace) {
    for (const BenchScene& b : {benchCornell(), benchStress(args.seed, args.n)}) {
        std::vector<double> ms;
        size_t nodes = 0;
        auto accel = build(b, nodes);
        for (int r = 0; r < args.reps; ++r) {
            auto t0 = std::chrono::steady_clock::now();
            accel = build(b, nodes);
            ms.push_back(1e3 * secondsSince(t0));
        }
        std::printf("%s scene=%s kind=build threads=1 prims=%zu build_ms=%.3f build_ms_min=%.3f nodes=%zu\n", name, b.name.c_str(),
                    b.shapes.size(), median(ms), *std::min_element(ms.begin(), ms.end()), nodes);
        std::fflush(stdout);
        std::vector<Ray> primary = benchPrimaryRays(b, args.rays), incoherent = benchIncoherentRays(b, args.seed, args.rays);
        struct Set { const char* kind; const std::vector<Ray>* rays; bool anyHit; };
        for (Set set : {Set{"primary", &primary, false}, Set{"incoherent", &incoherent, false}, Set{"occluded", &incoherent, true}}) {
            auto one = [&](const Ray& ray) { return trace(accel, ray, set.anyHit); };
            traceInBlocks(*set.rays, 2, one);  // warm-up
            for (int threads : {1, 2}) {
                std::vector<double> mr, mc;
                BenchRun last;
                for (int r = 0; r < args.reps; ++r) {
                    last = traceInBlocks(*set.rays, threads, one);
                    mr.push_back(set.rays->size() / last.seconds * 1e-6);
                    mc.push_back(set.rays->size() / last.cpuSeconds * 1e-6);
                }
                std::printf("%s scene=%s kind=%s threads=%d mrays=%.3f mrays_min=%.3f mrays_max=%.3f cpu_mrays=%.3f "
                            "rays=%zu hits=%llu sum_t=%.9e sphere_hits=%llu\n",
                            name, b.name.c_str(), set.kind, threads, median(mr), *std::min_element(mr.begin(), mr.end()),
                            *std::max_element(mr.begin(), mr.end()), median(mc), set.rays->size(), last.hits,
                            set.anyHit ? 0.0 : last.sumT, set.anyHit ? 0ULL : last.sphereHits);
                std::fflush(stdout);
            }
        }
    }
}
