// What the benchmark programs share (make bench, make efficiency): CPU time, medians, and the
// ray benchmark's two scenes and three ray sets, traced in fixed blocks so that every checksum is
// the same for any number of threads. The scenes and rays are those of Embree's yardstick
// (../shared/perf/README.md when it is at hand): a Cornell box of 6 quads and 2 spheres, and a
// stress scene of N random small spheres and N random small quads in the unit cube; primary rays
// (1024 x 1024 pixels, 4 per pixel) and incoherent rays (uniform origins in the scene's box,
// uniform directions), each set of M rays; occlusion rays are the incoherent ones.
#pragma once
#ifndef BDPT_NO_MAIN  // helpers.h (the tests) may have included the renderer already
#define BDPT_NO_MAIN
#include "classroom/classroom.cpp"
#endif

// threadCpuSeconds(): the renderer's (--profile's clock).

// A long harness's progress: redrawn in place on a terminal, left out of a log file (where
// carriage returns would pile up on one line).
inline bool progressShown() {
    static const bool terminal = isatty(2);
    return terminal;
}

// scenes/NAME.scene at the resolution of its reference scenes/refs/NAME.pfm (make efficiency,
// make uneven); false, with the reason on stderr, if either cannot be read.
inline bool sceneWithReference(const std::string& name, Scene& scene, Image& ref) {
    try {
        scene = loadScene("scenes/" + name + ".scene");
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return false;
    }
    if (!readPFM("scenes/refs/" + name + ".pfm", ref)) {
        std::fprintf(stderr, "scenes/refs/%s.pfm: no reference (make refs)\n", name.c_str());
        return false;
    }
    setResolution(scene.camera, ref.width, ref.height);
    return true;
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// SplitMix64 (its stream, not PCG: the yardstick's rays must be reproduced exactly).
struct SplitMix64 {
    uint64_t s;
    uint64_t next() {
        uint64_t z = (s += 0x9E3779B97F4A7C15ULL);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    double u() { return double(next() >> 40) * 0x1p-24; }
};

struct BenchScene {
    std::string name;
    std::vector<Shape> shapes;
    Vec3 camera;
    float boxSize;
};

inline Shape benchQuad(Vec3 q, Vec3 u, Vec3 v) {
    Shape s;
    s.type = Shape::Quad;
    s.p = q; s.u = u; s.v = v;
    return s;
}
inline Shape benchSphere(Vec3 c, float r) {
    Shape s;
    s.p = c;
    s.radius = r;
    return s;
}

inline BenchScene benchCornell() {
    BenchScene b{"cornell", {}, Vec3(278, 278, -800), 555};
    b.shapes = {benchQuad({555, 0, 0}, {0, 555, 0}, {0, 0, 555}), benchQuad({0, 0, 0}, {0, 555, 0}, {0, 0, 555}),
                benchQuad({343, 554, 332}, {-130, 0, 0}, {0, 0, -105}), benchQuad({0, 0, 0}, {555, 0, 0}, {0, 0, 555}),
                benchQuad({555, 555, 555}, {-555, 0, 0}, {0, 0, -555}), benchQuad({0, 0, 555}, {555, 0, 0}, {0, 555, 0}),
                benchSphere({190, 90, 190}, 90), benchSphere({370, 110, 370}, 110)};
    return b;
}

inline BenchScene benchStress(uint64_t seed, int n) {
    BenchScene b{"stress", {}, Vec3(0.5f, 0.5f, -1.5f), 1};
    SplitMix64 g{seed ^ 0x1111111111111111ULL};
    for (int i = 0; i < n; ++i) {
        float x = float(g.u()), y = float(g.u()), z = float(g.u());
        b.shapes.push_back(benchSphere({x, y, z}, float(0x1p-10 + 0x1p-8 * g.u())));
    }
    for (int i = 0; i < n; ++i) {
        float v[9];
        for (int k = 0; k < 9; ++k) v[k] = float(k < 3 ? g.u() : (g.u() - 0.5) * 0x1p-6);
        b.shapes.push_back(benchQuad({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}));
    }
    return b;
}

inline Vec3 unitFloat(double x, double y, double z) {
    double l = std::sqrt(x * x + y * y + z * z);
    return Vec3(float(x / l), float(y / l), float(z / l));
}

inline std::vector<Ray> benchPrimaryRays(const BenchScene& b, size_t m) {
    std::vector<Ray> rays(m);
    double h = std::tan(40 * 3.14159265358979323846 / 180 / 2);
    for (size_t k = 0; k < m; ++k) {
        size_t p = k >> 2, i = p % 1024, j = p / 1024, s = k & 3;
        double sx = (s & 1) ? 0.75 : 0.25, sy = (s & 2) ? 0.75 : 0.25;
        rays[k] = {b.camera, unitFloat(-(2 * (i + sx) / 1024 - 1) * h, (1 - 2 * (j + sy) / 1024) * h, 1), kInf};
    }
    return rays;
}

inline std::vector<Ray> benchIncoherentRays(const BenchScene& b, uint64_t seed, size_t m) {
    std::vector<Ray> rays(m);
    SplitMix64 g{seed ^ 0x2222222222222222ULL};
    for (size_t k = 0; k < m; ++k) {
        double L = b.boxSize;
        float ox = float(L * g.u()), oy = float(L * g.u()), oz = float(L * g.u());  // in this order
        double x, y, z, l2;
        do {
            x = 2 * g.u() - 1; y = 2 * g.u() - 1; z = 2 * g.u() - 1;
            l2 = (x * x + y * y) + z * z;
        } while (l2 < 1e-6 || l2 > 1);
        rays[k] = {Vec3(ox, oy, oz), unitFloat(x, y, z), kInf};
    }
    return rays;
}


// One traced ray as a checksum sees it.
struct BenchHit {
    bool hit = false;
    float t = 0;
    bool sphere = false;
};

struct BenchRun {
    double seconds = 0, cpuSeconds = 0, sumT = 0;
    unsigned long long hits = 0, sphereHits = 0;
};

// Rays in blocks of 65,536, contiguous block ranges per thread, per-block sums added in block
// order. trace(ray) -> BenchHit. Denormals are flushed, as Embree requires and does.
template <class Trace>
inline BenchRun traceInBlocks(const std::vector<Ray>& rays, int threads, Trace trace) {
    const size_t kBlock = 65536, blocks = (rays.size() + kBlock - 1) / kBlock;
    std::vector<double> blockSum(blocks, 0.0), cpu(threads, 0.0);
    std::vector<unsigned long long> blockHits(blocks, 0), blockSpheres(blocks, 0);
    auto work = [&](int t) {
#if defined(__SSE2__)
        // Denormals flushed to zero, as Embree's benchmark runs; restored after, since the caller's
        // thread is one of the workers: left set, a later render in the same process (the test
        // suite run as one program) rounds differently from the same render alone.
        const unsigned int callersMode = _mm_getcsr();
        _mm_setcsr(callersMode | 0x8040);
        struct Restore { unsigned int mode; ~Restore() { _mm_setcsr(mode); } } restore{callersMode};
#endif
        double c0 = threadCpuSeconds();
        for (size_t blk = blocks * t / threads; blk < blocks * (t + 1) / threads; ++blk) {
            double sum = 0;
            unsigned long long hits = 0, spheres = 0;
            for (size_t k = blk * kBlock; k < std::min(rays.size(), (blk + 1) * kBlock); ++k) {
                BenchHit h = trace(rays[k]);
                if (!h.hit) continue;
                ++hits;
                sum += h.t;
                spheres += h.sphere;
            }
            blockSum[blk] = sum, blockHits[blk] = hits, blockSpheres[blk] = spheres;
        }
        cpu[t] = threadCpuSeconds() - c0;
    };
    auto t0 = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
    work(0);
    for (std::thread& th : pool) th.join();
    BenchRun r;
    r.seconds = secondsSince(t0);
    r.cpuSeconds = *std::max_element(cpu.begin(), cpu.end());
    for (size_t b = 0; b < blocks; ++b) r.sumT += blockSum[b], r.hits += blockHits[b], r.sphereHits += blockSpheres[b];
    return r;
}

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
