// The ray benchmark's two scenes and three ray sets (make bench, and test_bvh, which checks them
// against Embree's): a Cornell box of 6 quads and 2 spheres, and a stress scene of N random small
// spheres and N random small quads in the unit cube; primary rays (1024 x 1024 pixels, 4 per
// pixel) and incoherent rays (uniform origins in the scene's box, uniform directions), each set of
// M rays; occlusion rays are the incoherent ones. Traced in fixed blocks, so that every checksum is
// the same for any number of threads (../shared/perf/README.md when it is at hand). Needs only
// the lecture (bdpt.cpp), included before it.
#pragma once

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

