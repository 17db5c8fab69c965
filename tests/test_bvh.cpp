// The BVH against the brute-force loop, on random scenes and the degenerate cases.
#include "lecture_test.h"
#include "rays.h"

static Shape randomShape(Rng& rng, float size, bool axisAligned) {
    Shape s;
    Vec3 p(rng.uniform(), rng.uniform(), rng.uniform());
    if (!axisAligned && rng.uniform() < 0.5f) {
        s.type = Shape::Sphere;
        s.p = p;
        s.radius = size * (0.05f + rng.uniform());
        s.area = 4 * kPi * s.radius * s.radius;
        return s;
    }
    s.type = Shape::Quad;
    s.p = p;
    if (axisAligned) {  // box faces: coplanar neighbours, shared edges, zero-thickness bounds
        int axis = int(rng.uniform() * 3) % 3;
        Vec3 e[3] = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
        s.p = Vec3(std::floor(p.x * 8) / 8, std::floor(p.y * 8) / 8, std::floor(p.z * 8) / 8);
        s.u = e[(axis + 1) % 3] * 0.125f;
        s.v = e[(axis + 2) % 3] * 0.125f;
    } else {
        s.u = size * Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
        s.v = size * Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
    }
    s.area = length(cross(s.u, s.v));
    s.normal = cross(s.u, s.v) / s.area;
    return s;
}

static Ray randomRay(Rng& rng, const std::vector<Shape>& shapes, int kind) {
    Vec3 o(rng.uniform() * 1.4f - 0.2f, rng.uniform() * 1.4f - 0.2f, rng.uniform() * 1.4f - 0.2f);
    Vec3 d = sampleUniformSphere(rng.uniform(), rng.uniform());
    if (kind == 1) {  // axis-parallel: two direction components exactly zero
        int axis = int(rng.uniform() * 3) % 3;
        d = Vec3(0, 0, 0);
        (axis == 0 ? d.x : axis == 1 ? d.y : d.z) = rng.uniform() < 0.5f ? -1.0f : 1.0f;
        o = Vec3(std::floor(o.x * 16) / 16, o.y, std::floor(o.z * 16) / 16);  // on box planes
    } else if (kind == 2 && !shapes.empty()) {  // from inside a sphere, or on a quad's plane
        const Shape& s = shapes[size_t(rng.uniform() * shapes.size()) % shapes.size()];
        o = s.type == Shape::Sphere ? s.p + 0.5f * s.radius * sampleUniformSphere(rng.uniform(), rng.uniform())
                                    : s.p + rng.uniform() * s.u + rng.uniform() * s.v;
    }
    return {o, d, kInf};
}

TEST_CASE("BVH closest hit and occlusion equal the brute-force loop on 150,000 random rays") {
    struct Case { int shapes; float size; bool axisAligned; };
    long long rays = 0, hits = 0, mismatches = 0, ties = 0;
    int sceneIndex = 0;
    for (Case c : {Case{0, 0.1f, false}, Case{1, 0.3f, false}, Case{2, 0.3f, true}, Case{50, 0.2f, false},
                   Case{300, 0.05f, true}, Case{2000, 0.03f, false}}) {
        Rng rng = makeRng(99, uint64_t(sceneIndex++), 0);
        std::vector<Shape> shapes;
        for (int i = 0; i < c.shapes; ++i) shapes.push_back(randomShape(rng, c.size, c.axisAligned));
        Bvh bvh = buildBvh(shapes);
        for (int k = 0; k < 25000; ++k) {
            Ray r = randomRay(rng, shapes, k % 3);
            if (k % 7 == 0) r.tmax = rng.uniform();  // a bounded ray, like a shadow ray
            Hit a = intersectBruteForce(shapes, r), b = traverseBvh<false>(bvh, r);
            bool same = a.shape == b.shape && a.t == b.t;
            bool tie = !same && a.found() && b.found() && a.t == b.t;  // two shapes at one distance
            ties += tie;
            mismatches += !same && !tie;
            mismatches += occludedBruteForce(shapes, r) != traverseBvh<true>(bvh, r).found();
            hits += a.found();
            ++rays;
        }
    }
    CHECK(rays == 150000);
    CHECK(hits > 30000);   // the rays do meet the shapes
    CHECK(mismatches == 0);
    CHECK(ties < rays / 100);  // duplicate coplanar quads in the grid scene meet rays at one t
}

// An axis-aligned quad's box is flat: entry and exit on its axis are one distance, and a ray that
// meets the quad at its rim meets the box's other slabs at that distance too, equal only up to
// rounding. The slab test widens its exit by 2 gamma_3 (pbrt's margin) so that such a ray is not
// lost: rays aimed at points of the rims and corners of flat quads placed off the grid (no exact
// binary coordinates), from every side, must meet what the brute-force loop meets.
TEST_CASE("BVH: rays that meet a flat box at its rim, within a rounding, find what the brute-force loop finds") {
    Rng rng = makeRng(7, 1, 0);
    std::vector<Shape> shapes;
    for (int i = 0; i < 400; ++i) {
        Shape s;
        s.type = Shape::Quad;
        int axis = i % 3;
        Vec3 e[3] = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
        s.p = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 3.7f - Vec3(1.3f);
        s.u = e[(axis + 1) % 3] * (0.05f + 0.3f * rng.uniform());
        s.v = e[(axis + 2) % 3] * (0.05f + 0.3f * rng.uniform());
        s.area = length(cross(s.u, s.v));
        s.normal = cross(s.u, s.v) / s.area;
        shapes.push_back(s);
    }
    Bvh bvh = buildBvh(shapes);
    long long rays = 0, hits = 0, mismatches = 0;
    for (int k = 0; k < 60000; ++k) {
        const Shape& s = shapes[size_t(k) % shapes.size()];
        float a = rng.uniform(), b = rng.uniform();
        if (k % 3 == 0) a = float(k / 3 % 2);               // on an edge along v
        else if (k % 3 == 1) b = float(k / 3 % 2);          // on an edge along u
        else a = float(k / 3 % 2), b = float(k / 6 % 2);    // a corner
        Vec3 target = s.p + a * s.u + b * s.v;
        Vec3 o = target + (0.2f + 2 * rng.uniform()) * sampleUniformSphere(rng.uniform(), rng.uniform());
        Ray r{o, normalize(target - o), kInf};
        Hit x = intersectBruteForce(shapes, r), y = traverseBvh<false>(bvh, r);
        mismatches += !(x.shape == y.shape && x.t == y.t) && !(x.found() && y.found() && x.t == y.t);
        mismatches += occludedBruteForce(shapes, r) != traverseBvh<true>(bvh, r).found();
        hits += x.found();
        ++rays;
    }
    MESSAGE(rays << " rays at rims and corners, " << hits << " hits, " << mismatches << " differ from the brute-force loop");
    CHECK(hits > rays / 3);
    CHECK(mismatches == 0);
}

TEST_CASE("BVH edge cases: empty scene, one shape, ray starting on a box face, axis-parallel") {
    std::vector<Shape> none;
    Bvh empty = buildBvh(none);
    CHECK(!traverseBvh<false>(empty, {Vec3(0), Vec3(0, 0, 1), kInf}).found());
    CHECK(!traverseBvh<true>(empty, {Vec3(0), Vec3(0, 0, 1), kInf}).found());
    Shape q;
    q.type = Shape::Quad;
    q.p = Vec3(0, 0, 1);
    q.u = Vec3(1, 0, 0);
    q.v = Vec3(0, 1, 0);
    Bvh one = buildBvh({q});
    Hit h = traverseBvh<false>(one, {Vec3(0.5f, 0.5f, 0), Vec3(0, 0, 1), kInf});
    CHECK(h.shape == 0);
    CHECK(h.t == 1.0f);
    // Along the quad's own edge x = 0 with a zero x component: on the box's face.
    h = traverseBvh<false>(one, {Vec3(0, 0.5f, 0), Vec3(0, 0, 1), kInf});
    CHECK(h.shape == 0);
    CHECK(!traverseBvh<false>(one, {Vec3(-0.001f, 0.5f, 0), Vec3(0, 0, 1), kInf}).found());
    CHECK(!traverseBvh<false>(one, {Vec3(0.5f, 0.5f, 0), Vec3(0, 0, 1), 0.999f}).found());
}

// Not in the builds as make NATIVE=1 and without SSE (BDPT_BVH_ONLY): they compile the BVH and
// the random rays above, not the scene parser and a method, which are the same in every build.
#ifndef BDPT_BVH_ONLY
TEST_CASE("cornell rendered through the BVH equals the brute-force loop bit for bit") {
    // Both call the same sphere/quad routines (the BVH stores w = n/(n.n) computed as the loop
    // does), so the only possible difference would be a tie between two shapes at one distance.
    // nee's samples pixel by pixel (the renderer's loop and its other methods are not this
    // file's: its NATIVE and scalar builds compile the BVH and one method).
    Scene scene = sceneAt("scenes/cornell.scene", 48, 48);
    RenderOptions o = quietOptions(Method::NEE, 2);
    auto image = [&] {
        std::vector<Vec3> pixels;
        RowOutput out;
        for (int pass = 0; pass < 2; ++pass)
            for (int y = 0; y < 48; ++y)
                for (int x = 0; x < 48; ++x) {
                    Rng rng = sampleRng(o, kCameraStream, uint64_t(y * 48 + x), uint64_t(pass));
                    pixels.push_back(sampleNEE(scene, o, PassData{}, x, y, rng, out));
                }
        return pixels;
    };
    std::vector<Vec3> withBvh = image();
    scene.bruteForce = true;
    std::vector<Vec3> loop = image();
    double mean = 0;
    for (const Vec3& p : loop) mean += average(p) / double(loop.size());
    CHECK(std::memcmp(withBvh.data(), loop.data(), loop.size() * sizeof(Vec3)) == 0);
    CHECK(mean > 0.05);
}
#endif

TEST_CASE("the benchmark generators follow ../shared/perf/README.md (first rays, checksum of Embree)") {
    BenchScene cornell = benchCornell();
    std::vector<Ray> incoherent = benchIncoherentRays(cornell, 1, 4);
    // The first incoherent ray, from embree_bench --dump.
    CHECK(incoherent[0].o.x == doctest::Approx(515.8355102539062));
    CHECK(incoherent[0].o.y == doctest::Approx(551.0530395507812));
    CHECK(incoherent[0].o.z == doctest::Approx(35.64055252075195));
    CHECK(incoherent[0].d.x == doctest::Approx(-0.5956858396530151));
    Bvh bvh = buildBvh(cornell.shapes);
    BenchRun r = traceInBlocks(benchPrimaryRays(cornell, 4194304), 2, [&](const Ray& ray) {
        Hit h = traverseBvh<false>(bvh, ray);
        BenchHit b;
        b.hit = h.found();
        if (b.hit) b.t = h.t, b.sphere = cornell.shapes[h.shape].type == Shape::Sphere;
        return b;
    });
    // README's reference table (Embree 3.13.5): hits within 0.01%, sum of t within 1e-5.
    CHECK(std::fabs(double(r.hits) - 3810304) <= 381);
    CHECK(std::fabs(double(r.sphereHits) - 432620) <= 43);
    CHECK(r.sumT == doctest::Approx(4.314020066e+09).epsilon(1e-5));
}
