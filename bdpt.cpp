// ============================================================================================
// bdpt.cpp: the methods of the slides "Bidirectional Path Tracing & Reciprocity"
// (Realistic Image Synthesis; Slusallek, Myszkowski, Singh), side by side, in one file.
//
// Read it top to bottom with the slides open:
//   1 math & random numbers   2 geometry            3 the scene and its two queries
//   4 materials (BSDFs)       5 lights              6 camera
//   7 integrators: the slides' panels (a)-(f): pt, nee, lt, ir, bdpt
//   8 later: the slides' "later" methods, vcm and Metropolis (pssmlt, mmlt, mlt)
//   9 film & rendering loop  10 scene file         11 command line
//   appendices, at the end: the data structures no slide shows: B the BVH, C Sobol points (the
//   notes' appendices B and C), D vcm's hash grid
// Units: radiance L, intensity I, power Phi, importance W_e. Directions point away from surfaces.
// It compiles alone: g++ -O2 -std=c++17 -pthread bdpt.cpp -lstb. The classroom's tools (side by
// side, live images, error against a reference, figures) are in classroom/, which includes it
// and fills the one hook it has here: PROFILE_PART, empty in the lecture, --profile's clock there.
// ============================================================================================
#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>
#include <sys/stat.h>
#include <unistd.h>
// stb_image_write: Debian's libstb-dev, or without it the header compiled here (make STB_DIR=FOLDER).
#ifdef BDPT_STB_HEADER
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#else
#include <stb/stb_image_write.h>
#endif

// == 1. Math & random numbers ================================================================
// Float vectors for geometry and colour (RGB); the film accumulates in double.
constexpr float kPi = 3.14159265358979323846f;
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Vec3 {
    float x = 0, y = 0, z = 0;
    Vec3() = default;
    constexpr Vec3(float a, float b, float c) : x(a), y(b), z(c) {}
    explicit constexpr Vec3(float a) : x(a), y(a), z(a) {}
    float operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
    float& operator[](int i) { return i == 0 ? x : i == 1 ? y : z; }
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator*(float s, Vec3 a) { return a * s; }
inline Vec3 operator/(Vec3 a, float s) { return a * (1.0f / s); }
// A colour times a factor beyond float's range, the product within it: 1/f, f a grazing path's 1e-42.
inline Vec3 scaled(Vec3 a, double s) { return {float(a.x * s), float(a.y * s), float(a.z * s)}; }
inline Vec3& operator+=(Vec3& a, Vec3 b) { return a = a + b; }
inline Vec3& operator*=(Vec3& a, Vec3 b) { return a = a * b; }
inline Vec3& operator*=(Vec3& a, float s) { return a = a * s; }
inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float absDot(Vec3 a, Vec3 b) { return std::fabs(dot(a, b)); }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { return a / length(a); }
inline float maxComponent(Vec3 a) { return std::max(a.x, std::max(a.y, a.z)); }
inline float average(Vec3 a) { return (a.x + a.y + a.z) / 3.0f; }
inline bool isBlack(Vec3 a) { return a.x == 0 && a.y == 0 && a.z == 0; }
inline bool isFinite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
inline float sqr(float x) { return x * x; }

// PCG32 (O'Neill): small state, good statistics, and independent streams: every pixel and pass has
// its own generator, and the image does not depend on the number of threads. Every number a method
// draws passes Rng::uniform, which has three sources: PCG32 itself; a Sobol point (appendix C), whose
// coordinates it hands out in order; and a Metropolis chain's state (section 8 (h), replay), which
// hands a walker its chain's numbers so that a mutation can change them.
struct PrimaryStream;
float replayUniform(PrimaryStream& stream);
constexpr uint32_t kLowDiscrepancyDimensions = 32;  // the dimensions drawn from a Sobol point
struct Rng {
    uint64_t state = 0, inc = 1;
    PrimaryStream* replay = nullptr;  // pssmlt, mmlt: numbers come from this state (and are recorded there)
    uint32_t nextUint() {
        uint64_t old = state;
        state = old * 6364136223846793005ULL + inc;
        uint32_t shifted = uint32_t(((old >> 18u) ^ old) >> 27u), rot = uint32_t(old >> 59u);
        return (shifted >> rot) | (shifted << ((-rot) & 31));
    }
    // Low-discrepancy mode (sampleRng sets it): the next number is coordinate `dimension` of Sobol
    // point `sobolIndex`, computed with the three after it when the first of the four is drawn.
    bool lowDiscrepancy = false, scrambled = true;
    uint32_t dimension = 0, sobolIndex = 0;
    uint64_t scrambleKey = 0;
    uint32_t block[4] = {};
    inline void drawCoordinates(uint32_t first);
    // [0,1), 24 exact bits. Inlined always: every number of every method passes here.
    [[gnu::always_inline]] float uniform() {
        if (replay) return replayUniform(*replay);
        if (lowDiscrepancy && dimension < kLowDiscrepancyDimensions) {
            if (dimension % 4 == 0) drawCoordinates(dimension);
            return float(block[dimension++ % 4]) * 0x1p-24f;
        }
        return float(nextUint() >> 8) * 0x1p-24f;
    }
};
inline uint64_t mix64(uint64_t z) {  // SplitMix64 finaliser: decorrelates nearby seeds
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}
inline Rng makeRng(uint64_t seed, uint64_t a, uint64_t b) {
    Rng r;
    r.inc = (mix64(seed * 0x9E3779B97F4A7C15ULL + b) << 1u) | 1u;
    r.state = mix64(mix64(seed + 0x632BE59BD9B4E019ULL) ^ (a * 0xD1B54A32D192ED03ULL) ^ b);
    r.nextUint();
    return r;
}

// -- Quasi-random numbers ("stratification"): by default a path's numbers are one point of a
// scrambled Sobol sequence, which fills the unit cube more evenly than independent numbers do
// (notes, page 9 and Appendix C). No slide needs its construction: appendix C, at the end.
inline uint32_t shuffledIndex(uint32_t index, uint32_t seed);         // a stream's own order of the points
inline float sobolSample(uint32_t index, uint32_t d, uint32_t seed);  // coordinate d, by the definition
// Orthonormal frame around a unit normal (Duff et al. 2017), to express BSDFs locally.
struct Frame {
    Vec3 s, t, n;
    explicit Frame(Vec3 normal) : n(normal) {
        float sign = std::copysign(1.0f, n.z), a = -1.0f / (sign + n.z), b = n.x * n.y * a;
        s = {1 + sign * n.x * n.x * a, sign * b, -sign * n.x};
        t = {b, sign + n.y * n.y * a, -n.y};
    }
    Vec3 toWorld(Vec3 v) const { return s * v.x + t * v.y + n * v.z; }
};

// Sampling routines; each says its density and measure.
inline Vec3 sampleCosineHemisphere(float u1, float u2) {  // pdf = cos(theta)/pi  [solid angle]
    float r = std::sqrt(u1), phi = 2 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1 - u1))};
}
inline Vec3 sampleUniformSphere(float u1, float u2) {  // pdf = 1/(4 pi)  [solid angle]
    float z = 1 - 2 * u1, r = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline Vec3 samplePowerCosine(float u1, float u2, float exponent) {  // pdf = (n+1)/(2 pi) cos^n
    float cosT = std::pow(u1, 1.0f / (exponent + 1)), sinT = std::sqrt(std::max(0.0f, 1 - cosT * cosT));
    float phi = 2 * kPi * u2;
    return {sinT * std::cos(phi), sinT * std::sin(phi), cosT};
}
inline Vec3 reflect(Vec3 w, Vec3 n) { return 2 * dot(w, n) * n - w; }  // mirror w about n
inline float luminance(Vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }  // Rec. 709

// The lecture's deliberate mistakes, all here, off by default; where applied, the right rule comes first.
struct Conventions {
    bool fixedRayOffset = false;       // --fixed-ray-offset: push rays off by a rule of thumb (section 2)
    bool symmetricRefraction = false;  // --symmetric-refraction: the eta^2 rule on the wrong side (section 4)
    bool noAdjointCorrection = false;  // --no-adjoint-correction: light paths use the shading BSDF (section 4)
    bool deltaDensityOne = false;      // --delta-density-one: pbrt's density of 1 after a delta event (bdpt)
};

// == 2. Geometry: spheres and parallelograms ===================================================
// A ray is o + t d with t in (0, tmax). A hit point computed in floats lies off the surface by a
// rounding error, and a new ray started there may hit its own surface again ("acne"). So every hit
// point carries a bound on its error, pError per coordinate (pbrt-v3 3.9), and a new ray starts
// from the point pushed off along ng by |ng|.pError, rounded away from the surface: the smallest
// push that provably clears it, at both ends of a shadow ray, so that visibility is the same
// whichever side a method traces it from. A fixed rule of thumb, 5e-5 (1 + max|p|), is far too
// large for small scenes: a lamp 0.5 mm above a floor (tests/thin-gap.scene) then loses part of its
// light in lt but not in pt, and methods disagree; with the bound all agree (tests).
struct Ray {
    Vec3 o, d;
    float tmax = kInf;
};

struct Shape {
    enum Type { Sphere, Quad } type = Sphere;
    Vec3 p;               // sphere centre, or quad corner Q
    Vec3 u, v;            // quad edges: points Q + a u + b v, a,b in [0,1]
    float radius = 0;     // sphere
    float side = 1;       // sphere: +1 front side outside, -1 front side inside ("inside" keyword)
    Vec3 normal;          // quad: unit u x v, the front side
    float area = 0;
    int material = 0;
    Vec3 emission;        // radiance Le leaving the front side (black: not a light)
    // The shading normal (section 4): ng itself, a procedural bump, or a quad's constant tilt.
    enum class ShadingNormal : unsigned char { Geometric, Bump, Tilt } shading = ShadingNormal::Geometric;
    float bumpAmplitude = 0, bumpFrequency = 0;
    Vec3 tiltedNormal;
    int light = -1;       // index into Scene::lights when emissive
    int line = 0;         // where the scene file defines it (for warnings)
};

struct Hit {
    float t = kInf;
    int shape = -1;
    bool found() const { return shape >= 0; }
};

// Ray-sphere with Haines et al.'s two precision fixes (Ray Tracing Gems ch. 7): the discriminant from
// the closest-approach vector, the smaller root from c/q. The nearest t in (0, tmax), or kInf.
inline float intersectSphere(Vec3 centre, float radius, const Ray& r) {
    Vec3 f = r.o - centre;
    float b = dot(f, r.d);                       // d is unit length
    Vec3 closest = f - b * r.d;
    float disc = radius * radius - dot(closest, closest);
    if (disc < 0) return kInf;
    float c = dot(f, f) - radius * radius;
    float q = -b - std::copysign(std::sqrt(disc), b);
    float t0 = c / q, t1 = q;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > 0 && t0 < r.tmax) return t0;
    if (t1 > 0 && t1 < r.tmax) return t1;        // from inside the sphere: its far side
    return kInf;
}

// Ray-parallelogram: plane hit, then the point's (a,b) in the edge basis, w = n/(n.n), n = u x v.
inline Vec3 quadW(Vec3 u, Vec3 v) {
    Vec3 n = cross(u, v);
    return n / dot(n, n);
}
inline float intersectQuad(Vec3 q, Vec3 u, Vec3 v, Vec3 w, const Ray& r) {
    float denom = dot(w, r.d);
    if (denom == 0) return kInf;                 // parallel: no hit (double-sided otherwise)
    float t = dot(w, q - r.o) / denom;
    if (!(t > 0 && t < r.tmax)) return kInf;
    Vec3 rel = r.o + t * r.d - q;
    float a = dot(w, cross(rel, v)), b = dot(w, cross(u, rel));
    return (a >= 0 && a <= 1 && b >= 0 && b <= 1) ? t : kInf;
}
inline float intersectQuad(const Shape& s, const Ray& r) { return intersectQuad(s.p, s.u, s.v, quadW(s.u, s.v), r); }

inline float intersectShape(const Shape& s, const Ray& r) {
    return s.type == Shape::Sphere ? intersectSphere(s.p, s.radius, r) : intersectQuad(s, r);
}

// What the shading code needs at a hit: position and its error bound, geometric normal ng (the
// shape's front side), shading normal ns (ng unless the shape has a bump or tilt), and the shape.
struct SurfacePoint {
    Vec3 p, ng, ns;
    Vec3 pError;       // |computed p - exact surface point| <= pError, per coordinate
    int shape = -1;
};

// gamma_n = n u / (1 - n u), u = 2^-24: the relative error of n float operations (Higham).
constexpr float gammaBound(int n) { return n * 0x1p-24f / (1 - n * 0x1p-24f); }
inline Vec3 absVec(Vec3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }

inline Vec3 geometricNormal(const Shape& s, Vec3 p) {
    return s.type == Shape::Sphere ? s.side * normalize(p - s.p) : s.normal;
}

// A shape's "bump" tilts the shading normal by a smooth pattern, ns = normalize(ng + A (g - (g.ng)
// ng)), g = (sin f x, sin f y, sin f z); a quad's "tilt" turns ns by one angle toward its edge u:
// the slides' "energy generator" at its plainest, one ratio |wo.ns|/|wo.ng| (notes, page 13).
inline Vec3 shadingNormal(const Shape& s, Vec3 p, Vec3 ng) {
    if (s.shading == Shape::ShadingNormal::Geometric) return ng;  // one test on the common path
    if (s.shading == Shape::ShadingNormal::Tilt) return s.tiltedNormal;
    float f = s.bumpFrequency;
    Vec3 g(std::sin(f * p.x), std::sin(f * p.y), std::sin(f * p.z));
    return normalize(ng + s.bumpAmplitude * (g - dot(g, ng) * ng));
}

// The point of shape s nearest to p (a hit o + t d, or a sample), with its error bound:
//   sphere: c + r (p-c)/|p-c|, error gamma_5 |p-c| + gamma_1 |p|  (pbrt's reprojection)
//   quad:   q + a u + b v with (a,b) of p, error gamma_3 (|q| + |a u| + |b v|); (a,b) may be off,
//           which moves the point along the surface only.
// fixedOffset: the deliberate mistake --fixed-ray-offset, the bound replaced by 5e-5 (1 + max|p|).
inline SurfacePoint makeSurfacePoint(const Shape& s, int shapeIndex, Vec3 p, bool fixedOffset) {
    SurfacePoint sp;
    if (s.type == Shape::Sphere) {
        Vec3 local = p - s.p;
        local = local * (s.radius / length(local));
        sp.p = s.p + local;
        sp.pError = gammaBound(5) * absVec(local) + gammaBound(1) * absVec(sp.p);
    } else {
        Vec3 w = quadW(s.u, s.v), rel = p - s.p;
        float a = std::min(1.0f, std::max(0.0f, dot(w, cross(rel, s.v))));
        float b = std::min(1.0f, std::max(0.0f, dot(w, cross(s.u, rel))));
        sp.p = s.p + a * s.u + b * s.v;
        sp.pError = gammaBound(3) * (absVec(s.p) + absVec(a * s.u) + absVec(b * s.v));
    }
    if (fixedOffset) sp.pError = Vec3(5e-5f * (1.0f + maxComponent(absVec(sp.p))));
    sp.ng = geometricNormal(s, sp.p);
    sp.ns = shadingNormal(s, sp.p, sp.ng);
    sp.shape = shapeIndex;
    return sp;
}

// p pushed off its surface (normal ng, error pError) to the side of dir by |ng|.pError, each
// coordinate rounded one float further away (pbrt-v3 OffsetRayOrigin). Inlined always: every ray
// and both ends of every shadow ray pass here; as a call it costs ir 4% of its time.
[[gnu::always_inline]] inline Vec3 offsetRayOrigin(Vec3 p, Vec3 pError, Vec3 ng, Vec3 dir) {
    float d = dot(absVec(ng), pError);
    Vec3 offset = (dot(dir, ng) > 0 ? d : -d) * ng, o = p + offset;
    for (int i = 0; i < 3; ++i)
        if (offset[i] != 0) o[i] = std::nextafter(o[i], offset[i] > 0 ? kInf : -kInf);
    return o;
}
inline Ray spawnRay(const SurfacePoint& sp, Vec3 dir) { return {offsetRayOrigin(sp.p, sp.pError, sp.ng, dir), dir, kInf}; }

// A shadow ray between two points, each pushed off its own surface toward the other; the far end
// 1e-4 of the length closer (pbrt's ShadowEpsilon): the hit distance's error grows with the length.
inline Ray shadowRay(const SurfacePoint& from, const SurfacePoint& to) {
    Vec3 d = to.p - from.p;
    Vec3 o = isBlack(from.ng) ? from.p : offsetRayOrigin(from.p, from.pError, from.ng, d);
    Vec3 e = isBlack(to.ng) ? to.p : offsetRayOrigin(to.p, to.pError, to.ng, -d);
    Vec3 oe = e - o;
    float dist = length(oe);
    return {o, oe / dist, dist * (1 - 1e-4f)};
}

// == 3. The scene, and the two queries every method makes of it ==============================
// What a scene file describes besides shapes: plain data; the sections below give it behaviour.
struct Material {
    enum Type { Diffuse, Mirror, Glass, Glossy } type = Diffuse;
    std::string name;
    Vec3 albedo{0.5f};     // diffuse/glossy albedo, mirror reflectance
    float ior = 1.5f;      // glass: index of refraction inside (the back side of the surface)
    float exponent = 0;    // glossy: Phong exponent n
};

struct Light {
    enum Type { Area, Point } type = Area;
    int shape = -1;        // area light: the emitting shape
    Vec3 position;         // point light
    Vec3 intensity;        // point light: I [W/sr] per colour channel
    float power = 0;       // Phi, averaged over channels: chooses lights proportionally
    int line = 0;          // where the scene file defines it (for warnings)
};

struct Camera {
    Vec3 eye, forward, right, up;  // right = forward x up: looking down +z with +y up, right is -x
    float fovDegrees = 40, tanHalfFov = 0, aspect = 1;
    int width = 0, height = 0;
    float imageArea = 0;           // A: area of the image rectangle at distance 1 from the pinhole
};

// A bounding volume hierarchy over the shapes answers both queries in about log N box tests
// instead of N shape tests: Appendix B, at the end of the file, builds and traverses it.
struct Bvh;

// The scene, and the two queries: the closest hit, and a shadow ray.
struct Scene {
    std::string file;
    Camera camera;
    std::vector<Shape> shapes;
    std::vector<Material> materials;
    std::vector<Light> lights;
    std::vector<float> lightCdf;   // cumulative Phi / total Phi, for choosing a light by power
    float totalPower = 0;
    std::shared_ptr<const Bvh> bvh;    // shared by copies: a copy of a Scene costs its few shapes
    bool bruteForce = false;           // true: the plain loop over shapes, for tests and teaching
    // The run's deliberate mistakes (section 1): the functions that apply them all read the scene.
    Conventions conventions;
    float exposure = 0;                // the PNG's default exposure in stops (--exposure overrides)
};

inline Hit intersectBruteForce(const std::vector<Shape>& shapes, const Ray& ray) {
    Hit hit;
    Ray r = ray;
    for (size_t i = 0; i < shapes.size(); ++i) {
        float t = intersectShape(shapes[i], r);
        if (t < r.tmax) { r.tmax = t; hit.t = t; hit.shape = int(i); }
    }
    return hit;
}
inline bool occludedBruteForce(const std::vector<Shape>& shapes, const Ray& ray) {
    for (const Shape& s : shapes)
        if (intersectShape(s, ray) < ray.tmax) return true;
    return false;
}
template <bool anyHit>
inline Hit traverseBvh(const Bvh& bvh, const Ray& ray);  // Appendix B
inline void buildAcceleration(Scene& scene);              // Appendix B: scene.bvh over scene.shapes

// Rays traced by this thread: the slides' "more costly", counted where paid (parallelRows sums them).
struct RayCount {
    long long closest = 0, shadow = 0;
};
inline thread_local RayCount gRaysTraced;
// classroom/'s --profile defines PROFILE_PART to time a sample's parts (tracing, MIS, merging); here nothing.
#ifndef PROFILE_PART
#define PROFILE_PART(part)
#endif

inline Hit intersect(const Scene& scene, const Ray& ray) {
    PROFILE_PART(Tracing);
    ++gRaysTraced.closest;
    return scene.bruteForce ? intersectBruteForce(scene.shapes, ray) : traverseBvh<false>(*scene.bvh, ray);
}
inline bool occluded(const Scene& scene, const Ray& ray) {
    PROFILE_PART(Tracing);
    ++gRaysTraced.shadow;
    return scene.bruteForce ? occludedBruteForce(scene.shapes, ray) : traverseBvh<true>(*scene.bvh, ray).found();
}
inline SurfacePoint surfaceAt(const Scene& scene, const Ray& ray, const Hit& hit) {
    return makeSurfacePoint(scene.shapes[hit.shape], hit.shape, ray.o + hit.t * ray.d, scene.conventions.fixedRayOffset);
}

// == 4. Materials: BSDFs, and where transport stops being symmetric ===========================
// Slides: "Extension of paths at hit points" ("reciprocity of BRDF under reflection, but be
// careful with refraction!"), "Use of shading normals", "Power versus radiance".
// Every query takes wo, the direction the path arrived from, and wi, the next one. On a camera
// path wo points toward the eye and radiance flows wi -> wo; on a light path wo points toward the
// light and importance flows wi -> wo. evalBsdf gives the factor a vertex contributes, cosine in:
//   Radiance:    f(wo,wi) |wi.ns|
//   Importance:  f(wi,wo) |wi.ns| * |wo.ns||wi.ng| / (|wo.ng||wi.ns|)      (Veach 1997, ch. 5)
// The second factor is the adjoint of a shading-normal BSDF: G(x,y) holds geometric cosines, the
// shading model replaces one by a shading cosine, and only on the radiance side does the ratio
// cancel; on the importance side it is unbounded as |wo.ng| -> 0. The "energy generator" is the
// BSDF itself: eye paths render its extra light as a bright surface, light paths as large weights
// (notes, page 13). G's two cosines live here, one at each end of a segment; a connection
// multiplies two such factors (or an emitter's or the camera's cosine) by V/d^2.
// Refraction: radiance crossing into a denser medium is compressed into a smaller solid angle,
// L_t = (eta_t/eta_i)^2 (1-F) L_i, while power/importance keeps (1-F) only.
enum class Transport { Radiance, Importance };

struct BsdfSample {
    Vec3 wi;
    Vec3 weight;       // evalBsdf's f |cos| / pdf; for a delta lobe, (f cos / delta) / probability
    float pdf = 0;     // solid-angle density, or for delta lobes the discrete probability
    bool delta = false;
};

inline const Material& materialAt(const Scene& scene, const SurfacePoint& sp) { return scene.materials[scene.shapes[sp.shape].material]; }
inline bool isSpecular(const Material& m) { return m.type == Material::Mirror || m.type == Material::Glass; }

// Fresnel reflectance of a smooth dielectric; eta = eta_incident / eta_transmitted.
inline float fresnelDielectric(float cosI, float eta) {
    float sin2T = eta * eta * std::max(0.0f, 1 - cosI * cosI);
    if (sin2T >= 1) return 1;  // total internal reflection
    float cosT = std::sqrt(1 - sin2T);
    float rs = (eta * cosI - cosT) / (eta * cosI + cosT);
    float rp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5f * (rs * rs + rp * rp);
}

// The shading normal on wo's side of the surface (shapes are two-sided for scattering).
inline Vec3 facingShadingNormal(const SurfacePoint& sp, Vec3 wo) { return dot(wo, sp.ng) >= 0 ? sp.ns : -sp.ns; }

inline float adjointCorrection(const Scene& scene, const SurfacePoint& sp, Vec3 wo, Vec3 wi, Transport mode) {
    if (mode == Transport::Radiance || scene.conventions.noAdjointCorrection || (sp.ns.x == sp.ng.x && sp.ns.y == sp.ng.y && sp.ns.z == sp.ng.z))
        return 1;  // the last: no bump, the factor is 1 exactly
    float denom = absDot(wo, sp.ng) * absDot(wi, sp.ns);
    return denom == 0 ? 0 : absDot(wo, sp.ns) * absDot(wi, sp.ng) / denom;
}

// Non-delta part only: mirrors and glass return 0 (a connection cannot hit a delta direction).
// wo and wi must lie on one side of the geometric surface (no light leaks) and above the shading
// normal, so that radiance and importance transport agree on where the BSDF vanishes. One call
// gives what a connection needs at a vertex (as SmallVCM's BSDF::Evaluate): f |cos wi| and, in pdf
// and pdfReverse, the solid-angle densities of sampling wi from wo and wo from wi.
inline Vec3 evalBsdf(const Scene& scene, const SurfacePoint& sp, Vec3 wo, Vec3 wi, Transport mode, float& pdf, float& pdfReverse) {
    pdf = pdfReverse = 0;
    const Material& m = materialAt(scene, sp);
    if (isSpecular(m) || dot(wo, sp.ng) * dot(wi, sp.ng) <= 0) return Vec3(0);  // no light leaks
    Vec3 n = facingShadingNormal(sp, wo);
    float cosI = dot(wi, n), cosO = dot(wo, n);
    if (cosI <= 0 || cosO <= 0) return Vec3(0);
    float f = 1 / kPi;  // Lambert: f = rho/pi, sampled with density cos/pi
    if (m.type == Material::Diffuse) {
        pdf = cosI / kPi;
        pdfReverse = cosO / kPi;
    } else {  // normalized Phong: f = rho (n+2)/(2 pi) cos^n(alpha), density (n+1)/(2 pi) cos^n(alpha)
        float cosA = dot(wi, reflect(wo, n));  // = dot(wo, reflect(wi, n)): the lobe is symmetric
        if (cosA <= 0) return Vec3(0);
        float lobe = std::pow(cosA, m.exponent);
        f = (m.exponent + 2) / (2 * kPi) * lobe;
        pdf = pdfReverse = (m.exponent + 1) / (2 * kPi) * lobe;
    }
    return m.albedo * (f * cosI * adjointCorrection(scene, sp, wo, wi, mode));
}

// A mirror's or glass's probability of reflecting light arriving along wo (F, or 1 for a mirror).
inline float specularReflectance(const Scene& scene, const SurfacePoint& sp, Vec3 wo) {
    const Material& m = materialAt(scene, sp);
    if (m.type == Material::Mirror) return 1;
    bool entering = dot(wo, sp.ng) > 0;  // the front side (ng) is outside, ior 1
    return fresnelDielectric(dot(wo, facingShadingNormal(sp, wo)), entering ? 1 / m.ior : m.ior);
}

// The delta lobe of a mirror or glass: reflection or (glass) refraction of wo. pdf is the lobe's
// probability (F or 1-F), weight (f cos / delta) / pdf. Veach's perturbations keep a path's lobes.
inline bool specularScatter(const Scene& scene, const SurfacePoint& sp, Vec3 wo, Transport mode, bool refract, BsdfSample& bs) {
    const Material& m = materialAt(scene, sp);
    Vec3 n = facingShadingNormal(sp, wo);
    bs.delta = true;
    float cosO = dot(wo, n);
    if (cosO <= 0 || (refract && m.type == Material::Mirror)) return false;
    float F = specularReflectance(scene, sp, wo);
    if (!refract) {
        bs.wi = reflect(wo, n);
        bs.pdf = F;
        bs.weight = (m.type == Material::Mirror ? m.albedo : Vec3(1)) * adjointCorrection(scene, sp, wo, bs.wi, mode);
        return bs.pdf > 0 && dot(bs.wi, sp.ng) * dot(wo, sp.ng) > 0;
    }
    // Smooth dielectric: reflect with probability F, refract with 1-F, so weight = 1 (x eta rule).
    bool entering = dot(wo, sp.ng) > 0;
    // eta_o on wo's side, eta_i on wi's: the slides' eta_t and eta_i ("Power versus Radiance").
    float etaO = entering ? 1 : m.ior, etaI = entering ? m.ior : 1, eta = etaO / etaI;
    float cosT = std::sqrt(std::max(0.0f, 1 - eta * eta * (1 - cosO * cosO)));
    bs.wi = normalize(-eta * wo + (eta * cosO - cosT) * n);
    bs.pdf = 1 - F;
    // Radiance flows wi -> wo: L_wo = (etaO/etaI)^2 L_wi. Importance carries no such factor.
    float etaScale = mode == Transport::Radiance ? sqr(etaO / etaI) : 1;
    // The mistake swaps the rules: eye tracing scales like power (smallpt), particles like radiance.
    if (scene.conventions.symmetricRefraction) etaScale = mode == Transport::Radiance ? 1 : sqr(etaI / etaO);
    bs.weight = Vec3(etaScale * adjointCorrection(scene, sp, wo, bs.wi, mode));
    return bs.pdf > 0 && dot(bs.wi, sp.ng) * dot(wo, sp.ng) < 0;
}

inline bool sampleBsdf(const Scene& scene, const SurfacePoint& sp, Vec3 wo, Transport mode, Rng& rng, BsdfSample& bs) {
    const Material& m = materialAt(scene, sp);
    Vec3 n = facingShadingNormal(sp, wo);
    float u1 = rng.uniform(), u2 = rng.uniform();
    bs.delta = isSpecular(m);
    if (dot(wo, n) <= 0) return false;  // below the shading hemisphere: nothing scatters
    if (m.type == Material::Diffuse || m.type == Material::Glossy) {
        Vec3 axis = m.type == Material::Diffuse ? n : reflect(wo, n);
        Vec3 local = m.type == Material::Diffuse ? sampleCosineHemisphere(u1, u2) : samplePowerCosine(u1, u2, m.exponent);
        bs.wi = Frame(axis).toWorld(local);
        float pdfReverse;
        Vec3 f = evalBsdf(scene, sp, wo, bs.wi, mode, bs.pdf, pdfReverse);
        if (bs.pdf <= 0) return false;  // below the surface: the path ends (the energy is lost)
        bs.weight = f / bs.pdf;
        return !isBlack(bs.weight);
    }
    if (u1 < specularReflectance(scene, sp, wo)) return specularScatter(scene, sp, wo, mode, false, bs);
    return specularScatter(scene, sp, wo, mode, true, bs);
}

// == 5. Lights: area lights and point lights ===================================================
// Slide "Generating light paths": p(x, Theta_x) = Le(x,Theta_x) |Theta_x . N_x| / Phi. A light is
// chosen with probability Phi_light / Phi, a point uniformly on its area (pdf 1/A), a direction
// with density |cos| / pi; then Le |cos| / (p_A p_omega) = Phi for every sample. Point lights have
// a delta position (nothing can hit them) and emit I uniformly: Phi = 4 pi I. Emitters radiate
// from their front side only: a quad's u x v side, a sphere's outside ("inside" flips it).
inline Vec3 emittedRadiance(const Scene& scene, const SurfacePoint& sp, Vec3 w) {
    return dot(w, sp.ng) > 0 ? scene.shapes[sp.shape].emission : Vec3(0);
}

inline float lightPower(const Light& light, const std::vector<Shape>& shapes) {
    if (light.type == Light::Point) return 4 * kPi * average(light.intensity);
    const Shape& s = shapes[light.shape];
    return kPi * s.area * average(s.emission);  // Phi = pi Le A (one-sided Lambertian)
}

inline float lightChoiceProbability(const Scene& scene, int light) { return scene.lights[light].power / scene.totalPower; }

inline int chooseLight(const Scene& scene, float u) {
    int i = int(std::upper_bound(scene.lightCdf.begin(), scene.lightCdf.end(), u) - scene.lightCdf.begin());
    return std::min(i, int(scene.lights.size()) - 1);
}

// A uniformly distributed point on a shape (pdf 1/area) and its front normal.
inline SurfacePoint sampleShapePoint(const Scene& scene, int shapeIndex, float u1, float u2) {
    const Shape& s = scene.shapes[shapeIndex];
    Vec3 p = s.type == Shape::Sphere ? s.p + s.radius * sampleUniformSphere(u1, u2) : s.p + u1 * s.u + u2 * s.v;
    return makeSurfacePoint(s, shapeIndex, p, scene.conventions.fixedRayOffset);
}

struct LightPoint {
    SurfacePoint sp;    // a point light: ng = 0 (no surface), shape -1
    Vec3 emission;      // Le for area lights, I for point lights
    float pdfArea = 0;  // P(light) / area; for a point light P(light) (a discrete position)
    bool deltaPosition = false;
    int light = -1;
};

// Next-event estimation's light sample (slide: "Next Event Estimator: try to find a direct connection").
inline LightPoint sampleLightPoint(const Scene& scene, Rng& rng) {
    LightPoint lp;
    lp.light = chooseLight(scene, rng.uniform());
    const Light& light = scene.lights[lp.light];
    float choice = lightChoiceProbability(scene, lp.light);
    float u1 = rng.uniform(), u2 = rng.uniform();
    if (light.type == Light::Point) {
        lp.sp.p = light.position;
        lp.emission = light.intensity;
        lp.pdfArea = choice;
        lp.deltaPosition = true;
        return lp;
    }
    lp.sp = sampleShapePoint(scene, light.shape, u1, u2);
    lp.emission = scene.shapes[light.shape].emission;
    lp.pdfArea = choice / scene.shapes[light.shape].area;
    return lp;
}

// The density sampleLightPoint has at a point of an emitting shape (needed by MIS).
inline float pdfLightPoint(const Scene& scene, int shapeIndex) {
    const Shape& s = scene.shapes[shapeIndex];
    return s.light < 0 ? 0 : lightChoiceProbability(scene, s.light) / s.area;
}

// A light path's first vertex and direction, with density p(x,Theta) = Le |cos| / Phi per light.
struct EmissionSample {
    LightPoint point;
    Vec3 dir;
    float pdfDir = 0;   // solid angle
    Vec3 weight;        // Le |cos| / (pdfArea pdfDir): the light path's starting throughput
};

// A direction from the light point es.point (Veach's mutations, section 8 (h), resample it alone).
inline void sampleEmissionDirection(EmissionSample& es, float u1, float u2) {
    if (es.point.deltaPosition) {
        es.dir = sampleUniformSphere(u1, u2);
        es.pdfDir = 1 / (4 * kPi);
        es.weight = es.point.emission / (es.point.pdfArea * es.pdfDir);
        return;
    }
    Vec3 local = sampleCosineHemisphere(u1, u2);
    es.dir = Frame(es.point.sp.ng).toWorld(local);
    es.pdfDir = local.z / kPi;
    es.weight = local.z <= 0 ? Vec3(0) : es.point.emission * (local.z / (es.point.pdfArea * es.pdfDir));
}

inline EmissionSample sampleEmission(const Scene& scene, Rng& rng) {
    EmissionSample es;
    es.point = sampleLightPoint(scene, rng);
    float u1 = rng.uniform(), u2 = rng.uniform();
    sampleEmissionDirection(es, u1, u2);
    return es;
}

// == 6. Camera: a pinhole, and its importance ==================================================
// Slide "Generating eye paths": p(y,Theta_y) ~ W(y,Theta_y) |Theta_y . N_y|. The pinhole's image
// rectangle sits at distance 1 with area A; a direction at angle theta to the axis meets it where
// dA = d omega / cos^3(theta), so a uniform point on the rectangle gives
//   p_omega = 1 / (A cos^3 theta),   and   W_e = 1 / (A cos^4 theta)
// makes W_e cos / p_omega = 1 and integrates, with cos, to 1 over the image. Per pixel (area
// A / (width*height)), W_j = width*height / (A cos^4 theta) inside pixel j: a camera sample
// measures the pixel's mean radiance, and a light path connected to the pinhole splats with W_j.
// A uniform film coordinate in pixel x: x + u rounds up to x + 1 for large x and u near 1 (in
// float, 16383 + 0.99999994 = 16384), which would lie outside the image; keep it below x + 1.
inline float filmCoordinate(int x, float u) { return std::min(float(x) + u, std::nextafter(float(x + 1), 0.0f)); }

inline Ray cameraRay(const Camera& cam, float filmX, float filmY) {  // film coordinates in pixels
    float x = (2 * filmX / cam.width - 1) * cam.tanHalfFov * cam.aspect;
    float y = (1 - 2 * filmY / cam.height) * cam.tanHalfFov;
    return {cam.eye, normalize(cam.forward + x * cam.right + y * cam.up), kInf};
}

// A camera sample of pixel (x, y): a uniform point in it, x drawn first in every method.
struct FilmPoint {
    float x, y;
};
inline FilmPoint jitteredFilmPoint(int x, int y, Rng& rng) {
    float u1 = rng.uniform(), u2 = rng.uniform();
    return {filmCoordinate(x, u1), filmCoordinate(y, u2)};
}
// A uniform point on the whole film (the Metropolis methods'); pixelAt names its pixel.
inline FilmPoint uniformFilmPoint(const Camera& cam, Rng& rng) {
    float fx = rng.uniform() * cam.width, fy = rng.uniform() * cam.height;
    int px = std::min(int(fx), cam.width - 1), py = std::min(int(fy), cam.height - 1);
    return {filmCoordinate(px, fx - px), filmCoordinate(py, fy - py)};
}
inline int pixelAt(const Camera& cam, FilmPoint f) { return int(f.y) * cam.width + int(f.x); }
inline Ray pixelRay(const Camera& cam, int x, int y, Rng& rng) {
    FilmPoint f = jitteredFilmPoint(x, y, rng);
    return cameraRay(cam, f.x, f.y);
}

// Where on the film the point p appears (false: behind the camera or outside the image).
inline bool projectToFilm(const Camera& cam, Vec3 p, float& filmX, float& filmY) {
    Vec3 d = p - cam.eye;
    float z = dot(d, cam.forward);
    if (z <= 0) return false;
    float x = dot(d, cam.right) / (z * cam.tanHalfFov * cam.aspect), y = dot(d, cam.up) / (z * cam.tanHalfFov);
    filmX = (x + 1) * 0.5f * cam.width;
    filmY = (1 - y) * 0.5f * cam.height;
    return filmX >= 0 && filmX < cam.width && filmY >= 0 && filmY < cam.height;
}
// The pixel where p appears, or -1. Rounding can put a point just inside the edge at filmX = width
// after the int conversion's neighbour: clamp it to the last pixel.
inline int pixelOf(const Camera& cam, Vec3 p) {
    float fx, fy;
    if (!projectToFilm(cam, p, fx, fy)) return -1;
    return std::min(int(fy), cam.height - 1) * cam.width + std::min(int(fx), cam.width - 1);
}

// W_e of one pixel for the unit direction dir leaving the pinhole (0 behind it).
inline float pixelImportance(const Camera& cam, Vec3 dir) {
    float cosT = dot(dir, cam.forward);
    if (cosT <= 0) return 0;
    return float(cam.width) * cam.height / (cam.imageArea * sqr(sqr(cosT)));
}

// The solid-angle density of the camera's direction sample, normalized per sensor: 1/(A cos^3).
// BDPT's MIS compares it with light-path densities; with one light path per camera sample the
// per-pixel factor W*H appears on both sides and cancels (forgetting it was pbrt-v4 #347, #456).
// A direction the camera sampled at the film's border must not read as outside after the round
// trip through normalize and projection, hence a slack of 1e-5 of the image's half-size.
inline float pdfCameraDirection(const Camera& cam, Vec3 dir) {
    float cosT = dot(dir, cam.forward);
    if (!(cosT > 0)) return 0;
    float x = dot(dir, cam.right) / (cosT * cam.tanHalfFov * cam.aspect), y = dot(dir, cam.up) / (cosT * cam.tanHalfFov);
    constexpr float kSlack = 1 + 1e-5f;
    if (!(std::fabs(x) <= kSlack && std::fabs(y) <= kSlack)) return 0;
    return 1 / (cam.imageArea * cosT * cosT * cosT);
}

// --res: the same camera with another image size (the field of view spans the image's height).
inline void setResolution(Camera& cam, int width, int height) {
    cam.width = width;
    cam.height = height;
    cam.aspect = float(width) / height;
    cam.imageArea = 4 * sqr(cam.tanHalfFov) * cam.aspect;
}

// == 7. Integrators ============================================================================
// Slides "Path sampling techniques" and "Results from different techniques": panels (a) to (f);
// section 8 adds the slides' "later" methods, (g) vcm and (h) Metropolis. Every method is one
// function of the same shape over the shared pieces above,
//     Vec3 sampleXX(scene, options, pass data, pixel x, pixel y, the pixel's Rng, row output):
// one sample of pixel (x, y), what its camera path brings back returned, what its light paths
// bring to other pixels splatted; a diff of two methods shows how they differ. ir, vcm and the
// Metropolis methods first prepare what the whole pass shares (section 9's preparePass).
// Paths are counted in bounces (scattering vertices): a path of k segments has k-1 bounces, and
// --maxdepth D keeps paths with at most D bounces. Of what follows, pt needs the options, the
// Rng's streams, RowOutput and roulette; (a) begins at samplePT.
enum class Method { PT, NEE, LT, IR, BDPT, VCM, PSSMLT, MMLT, MLT };
inline bool isMetropolis(Method m) { return m == Method::PSSMLT || m == Method::MMLT || m == Method::MLT; }  // section 8 (h)
// How a subpath ends: Throughput, q from its throughput after rrStart bounces (pt and nee always);
// Albedo, q = the albedo at every vertex, in bdpt's MIS densities (albedoContinuation); Off, depth only.
enum class Roulette { Throughput, Albedo, Off };
enum class Sampler { Sobol, Random };  // section 1: Owen-scrambled Sobol points, or PCG32 alone
enum class Heuristic { Balance, Power, Max, Uniform };  // bdpt's MIS heuristics (its banner)

// What a sample reads: the method and the parameters every method shares, then each later or
// slide method's own, in a group named after it (opt.vcm.radius says whose it is).
struct IrOptions {
    int vplPaths = 16;         // light paths traced per pass, each leaving VPLs
    float clamp = 0;           // > 0 bounds the geometry term G at this value (panel (e))
};
struct VcmOptions {  // later: (g)
    float radius = -1;         // r_0 of merging; 0: none (vcm is bdpt); < 0: defaultMergeRadius
    float alpha = 0.75f;       // r(n) = r_0 n^((alpha-1)/2) in pass n
};
struct MetropolisOptions {  // later: (h)
    float largeStep = 0.3f;    // pssmlt, mmlt: probability of a large step (every number afresh)
    float sigma = 0.01f;       // pssmlt, mmlt: a small step's standard deviation, per number
    int bootstrap = 0;         // samples that estimate b and choose the chains' starts (0: bootstrapSamples)
    int chains = 0;            // Markov chains, each its own random stream (0: chainCount)
    bool fixedStart = false;   // the deliberate mistake, every chain from one state
    int mutations = 15;        // mlt: which of Veach's mutations run (bits: 1 bidirectional, 2 lens, 4 caustic, 8 multi-chain)
    bool chainShortPaths = false;  // the chains render paths of 1 and 2 segments too (else a bdpt sample)
};
struct SampleOptions {
    Method method = Method::BDPT;
    uint64_t seed = 1;
    int maxDepth = 32;         // bounces
    int rrStart = 3;           // Russian roulette from this many bounces on (Roulette::Throughput)
    Roulette roulette = Roulette::Albedo;  // how lt, ir and bdpt end their subpaths (pt, nee: Throughput)
    Sampler sampler = Sampler::Sobol;  // every pixel sample's numbers (section 1)
    bool noScramble = false;   // --no-scramble: the deliberate mistake, one point set for every pixel and pair
    bool mis = false;          // nee: combine light and BSDF sampling (power heuristic)
    IrOptions ir;
    Heuristic heuristic = Heuristic::Balance;  // bdpt and the methods built on it: how strategies are weighted
    int minDepth = 0;          // bdpt's connections: paths of fewer bounces are left out (the Metropolis chains' own)
    VcmOptions vcm;
    MetropolisOptions metropolis;
};
// What a run reads besides: how many passes, and on how many threads.
struct RenderOptions : SampleOptions {
    int spp = 16;              // passes of one sample per pixel
    double seconds = 0;        // > 0: render passes until this many CPU seconds (all threads) are spent
    bool wallTime = false;     // --wall-time: seconds counts the wall clock instead
    int threads = 0;           // 0: all cores
    int strategyMaxLength = 0; // bdpt, vcm: > 0 adds up each strategy's contribution up to this path length (--strategies)
};

// The kinds of random stream, each its own salt of the seed: numbers that meet in one path must come
// from different streams (bdpt's camera and light subpaths; a pixel and ir's VPLs), or they are
// correlated (shuffledIndex, section 1). Within a kind, `stream` numbers the pixel, path or chain.
enum StreamKind : uint64_t {
    kCameraStream = 0,                        // a pixel's camera path (every method)
    kLightPathStream = 0x3c6ef372fe94f82bULL, // bdpt's and vcm's light subpath of a pixel
    kVplStream = 0x5bd1e995ULL,               // ir's light paths that leave VPLs
    kBootstrapStream = 0x2545f4914f6cdd1dULL, // Metropolis: the bootstrap's samples
    kChainStream = 0x7a3f1c2b9e5d4081ULL,     // Metropolis: each chain's steps
};

// The numbers of sample `index` of a stream: PCG32, or Sobol points scrambled per stream and seed,
// in the stream's own order (the camera's own order is the plain one: it is cached per thread).
inline Rng sampleRng(const SampleOptions& opt, uint64_t salt, uint64_t stream, uint64_t index) {  // salt: a StreamKind
    Rng rng = makeRng(opt.seed ^ salt, stream, index);
    if (opt.sampler == Sampler::Random) return rng;
    rng.lowDiscrepancy = true;
    rng.scrambled = !opt.noScramble;
    rng.scrambleKey = mix64(mix64(opt.seed ^ salt) + stream);
    rng.sobolIndex = salt == kCameraStream || !rng.scrambled ? uint32_t(index) : shuffledIndex(uint32_t(index), uint32_t(rng.scrambleKey));
    return rng;
}

struct Splat {                 // a light-path contribution that lands on some pixel
    int pixel;
    Vec3 value;
};

// One strategy's contribution to a pixel and its MIS weight: the slides' "contributions of different
// paths" (section 9), and mlt's candidate starts; a merge (vcm) of light vertex s with camera t-1.
struct StrategySplat {
    int pixel;
    Vec3 value;
    float weight;
    int s, t;
    bool merge = false;
};

// What one image row's samples leave besides their pixels' values; rows are merged in order.
struct RowOutput {
    std::vector<Splat> splats;
    int strategyMaxLength = 0;                   // the film's strategy images: paths of at most this many segments
    std::vector<StrategySplat> strategySplats;  // ... each strategy's contribution to them
    long long nonFinite = 0;
    double energyUnclamped = 0, energyClamped = 0;  // ir --clamp: what the clamp removed
};

// What a method prepared for the whole pass: ir's VPLs, vcm's light subpaths, the Metropolis chains.
struct Vpl;
struct VcmPass;
struct MetropolisPass;
struct PassData {
    int pass = 0;
    const std::vector<Vpl>* vpls = nullptr;
    const VcmPass* vcm = nullptr;
    const MetropolisPass* metropolis = nullptr;
};

// Runs body(row) for every row on `threads` threads, the caller among them (section 9).
template <class Body>
inline void parallelRows(int rows, int threads, const Body& body);

// Russian roulette ("Path tracing with Russian roulette"): continue with probability q and divide
// the throughput by q, so E[beta 1(u<q)/q] = beta: the mean is unchanged, only paths that would
// contribute little are cut. For pt and nee q follows the throughput relative to the path's start,
// capped below 1 so that every path ends; lt, ir and bdpt use the albedo (albedoContinuation: why).
inline bool russianRoulette(Vec3& beta, float startThroughput, int bounces, const SampleOptions& opt, Rng& rng) {
    if (bounces < opt.rrStart) return true;
    float q = std::min(0.95f, maxComponent(beta) / startThroughput);
    if (!(rng.uniform() < q)) return false;
    beta = beta / q;
    return true;
}

inline float powerHeuristic(float pdfA, float pdfB) {  // Veach's power heuristic, beta = 2
    float a = pdfA * pdfA, b = pdfB * pdfB;
    return a + b == 0 ? 0 : a / (a + b);
}

// -- (a) pt: "unidirectional (eye tracing)". Only p_{k,0}: emission counts when a path happens to
// hit an emitter, so a point light (nothing can hit it) stays black: "especially for point lights".
inline Vec3 samplePT(const Scene& scene, const SampleOptions& opt, const PassData&, int x, int y, Rng& rng, RowOutput&) {
    Ray ray = pixelRay(scene.camera, x, y, rng);
    Vec3 L(0), beta(1);
    for (int bounces = 0;; ++bounces) {
        Hit hit = intersect(scene, ray);
        if (!hit.found()) break;
        SurfacePoint sp = surfaceAt(scene, ray, hit);
        Vec3 wo = -ray.d;
        L += beta * emittedRadiance(scene, sp, wo);
        if (bounces >= opt.maxDepth) break;
        BsdfSample bs;
        if (!sampleBsdf(scene, sp, wo, Transport::Radiance, rng, bs)) break;
        beta *= bs.weight;
        if (!russianRoulette(beta, 1, bounces, opt, rng)) break;
        ray = spawnRay(sp, bs.wi);
    }
    return L;
}

// Next event: one light point y for the vertex x, contribution
//   f(x) |cos_x| * Le(y->x) |cos_y| / |x-y|^2 * V(x,y) / p_A(y)     (G(x,y) split as in section 4)
// With mis, weighted against the chance that BSDF sampling had found y (power heuristic).
inline Vec3 estimateDirect(const Scene& scene, const SurfacePoint& sp, Vec3 wo, Rng& rng, bool mis) {
    LightPoint lp = sampleLightPoint(scene, rng);
    Vec3 d = lp.sp.p - sp.p;
    float dist2 = dot(d, d);
    if (!(dist2 > 0)) return Vec3(0);
    Vec3 wi = d / std::sqrt(dist2);
    float cosLight = lp.deltaPosition ? 1 : dot(-wi, lp.sp.ng);
    if (cosLight <= 0) return Vec3(0);  // the back of a one-sided emitter
    float pdfBsdf, pdfReverse;
    Vec3 f = evalBsdf(scene, sp, wo, wi, Transport::Radiance, pdfBsdf, pdfReverse);
    if (isBlack(f) || occluded(scene, shadowRay(sp, lp.sp))) return Vec3(0);
    Vec3 contribution = f * lp.emission * (cosLight / (dist2 * lp.pdfArea));
    if (mis && !lp.deltaPosition) contribution *= powerHeuristic(lp.pdfArea * dist2 / cosLight, pdfBsdf);
    return contribution;
}

// -- (b) nee: "unidirectional + next event". Uses p_{k,0} and p_{k,1}: a light point is connected
// at every non-specular vertex. Without mis an emitter hit by a BSDF sample counts only after the
// camera or a specular bounce ("make sure no path is counted multiple times, either!").
inline Vec3 sampleNEE(const Scene& scene, const SampleOptions& opt, const PassData&, int x, int y, Rng& rng, RowOutput&) {
    Ray ray = pixelRay(scene.camera, x, y, rng);
    Vec3 L(0), beta(1);
    bool afterDelta = true;   // the camera counts as a delta vertex
    float pdfPrevBsdf = 0;    // solid-angle density of the BSDF sample that made this ray
    Vec3 prevP = ray.o;       // the vertex that ray left (not its pushed-off origin)
    for (int bounces = 0;; ++bounces) {
        Hit hit = intersect(scene, ray);
        if (!hit.found()) break;
        SurfacePoint sp = surfaceAt(scene, ray, hit);
        Vec3 wo = -ray.d;
        Vec3 Le = emittedRadiance(scene, sp, wo);
        if (!isBlack(Le)) {
            if (afterDelta) {
                L += beta * Le;
            } else if (opt.mis) {  // the distance between the vertices, as estimateDirect's weight has it
                Vec3 d = prevP - sp.p;
                float dist2 = dot(d, d), pdfLight = pdfLightPoint(scene, sp.shape) * dist2 * std::sqrt(dist2) / dot(d, sp.ng);
                L += beta * Le * powerHeuristic(pdfPrevBsdf, pdfLight);
            }
        }
        if (bounces >= opt.maxDepth) break;
        const Material& m = materialAt(scene, sp);
        if (!isSpecular(m)) L += beta * estimateDirect(scene, sp, wo, rng, opt.mis);
        BsdfSample bs;
        if (!sampleBsdf(scene, sp, wo, Transport::Radiance, rng, bs)) break;
        afterDelta = bs.delta;
        pdfPrevBsdf = bs.pdf;
        beta *= bs.weight;
        if (!russianRoulette(beta, 1, bounces, opt, rng)) break;
        ray = spawnRay(sp, bs.wi);
        prevP = sp.p;
    }
    return L;
}

// -- The camera connection shared by light tracing and BDPT's t=1 strategy. For a point x seen by
// the pinhole, W_j(x->eye) G(x,eye) with the camera-side cosine, W_j cos_cam / d^2, divided by the
// number of light paths per pass (one per pixel: the W*H in W_j cancels it; forgetting either is
// light tracing's classic bug, pbrt-v4 #347 and #456). The scene-side cosine is the caller's.
struct CameraConnection {
    int pixel = -1;          // -1: behind the camera, outside the image, or occluded
    Vec3 toCamera;           // unit direction from x to the pinhole
    float importance = 0;    // W_j cos_cam / (d^2 N_lightpaths)
};

inline CameraConnection connectToCamera(const Scene& scene, const SurfacePoint& x) {
    CameraConnection c;
    const Camera& cam = scene.camera;
    const int pixel = pixelOf(cam, x.p);
    if (pixel < 0) return c;
    Vec3 d = cam.eye - x.p;
    float dist2 = dot(d, d);
    c.toCamera = d / std::sqrt(dist2);
    float cosCamera = dot(-c.toCamera, cam.forward);
    float lightPathsPerPass = float(cam.width) * cam.height;
    c.importance = pixelImportance(cam, -c.toCamera) * cosCamera / (dist2 * lightPathsPerPass);
    SurfacePoint eye;  // no surface: ng = 0
    eye.p = cam.eye;
    if (!occluded(scene, shadowRay(x, eye))) c.pixel = pixel;
    return c;
}

// -- Subpaths, shared by lt, ir and bdpt (slides: "Generating light paths", "Extension of paths
// at hit points", "Mathematical Formulation"): a list of vertices, each with the throughput beta
// that reached it. A connection joins a light-side vertex y to a camera-side vertex x and
// multiplies the factor G f f of T(pi) that neither side sampled: both scattering factors
// (cosines included, section 4), 1/d^2 and V. The densities and roulette below use strategies and
// density ratios that (f)'s banner defines: read them again after it.
// lt is the connection to the pinhole (t = 1) alone, ir that of one camera vertex to stored light
// vertices, bdpt every connection.
struct PathVertex {
    double pdfFwd = 0, pdfRev = 0;  // area densities of sampling it from its own side and from the other
    bool delta = false;             // a delta BSDF was sampled here
    bool deltaPosition = false;     // the pinhole, a point light
    enum Type : unsigned char { Camera, Light, Surface } type = Surface;
    float continuation = 1;         // Roulette::Albedo: probability that a walk goes on from here
    SurfacePoint sp;        // p and ng for every type; sp.shape < 0 for the pinhole and point lights
    Vec3 wo;                // surface: unit vector toward the previous vertex of its own subpath
    float prevDist2 = 0;    // squared distance to that vertex
    Vec3 beta;              // subpath throughput up to this vertex (light: Le/p_A or I/P(light))
    int light = -1;         // the light y_0 was sampled on
};

// Roulette::Albedo's continuation probability: the material's largest albedo (SmallVCM's).
// Russian roulette is part of the densities (Veach 1997, 10.3; SmallVCM): a subpath continues from
// a surface vertex with q = its albedo (this function), so both densities sampled there carry
// q, and the strategy whose subpath survived more roulette gets less weight. q depends on the
// vertex alone, so both walks through it have it, and MIS counts it both ways. A throughput-relative
// q (pt's) cannot be counted so: the other subpath's q depends on its unknown throughput.
// Appendix A compares the three rules: albedo roulette costs least per sample and is the most efficient.
inline float albedoContinuation(const Scene& scene, const SurfacePoint& sp) {
    const Material& m = materialAt(scene, sp);
    return m.type == Material::Glass ? 1.0f : std::min(1.0f, maxComponent(m.albedo));
}

// The cosine a density picks up at a vertex hit from direction w: 1 at the pinhole and point lights.
inline float cosAt(const PathVertex& v, Vec3 w) {
    return v.type == PathVertex::Surface || (v.type == PathVertex::Light && !v.deltaPosition) ? absDot(v.sp.ng, w) : 1;
}

// The emission direction density at a light vertex (or a surface that emits): cos/pi, front only.
inline float pdfEmissionDirection(const PathVertex& light, Vec3 w) {
    if (light.deltaPosition) return 1 / (4 * kPi);
    return std::max(0.0f, dot(light.sp.ng, w)) / kPi;
}

// A vertex v looking along w: the factor it multiplies into a connection, cosine in (1 at the
// pinhole), and the densities of sampling w having arrived along v.wo (pdf) and back (pdfReverse).
inline Vec3 evalVertex(const Scene& scene, const PathVertex& v, Vec3 w, Transport mode, float& pdf, float& pdfReverse) {
    pdfReverse = 0;
    if (v.type == PathVertex::Camera) {
        pdf = pdfCameraDirection(scene.camera, w);
        return Vec3(1);
    }
    if (v.type == PathVertex::Light) {
        pdf = pdfEmissionDirection(v, w);
        return Vec3(v.deltaPosition ? 1 : std::max(0.0f, dot(v.sp.ng, w)));
    }
    return evalBsdf(scene, v.sp, v.wo, w, mode, pdf, pdfReverse);
}

// A solid-angle density as an area density at `next`, dist2 away along w: p_A = p_omega |cos| / d^2.
inline double toArea(double pdfOmega, const PathVertex& next, Vec3 w, float dist2) { return pdfOmega * cosAt(next, w) / dist2; }

// The density, up to the delta itself, with which a specular vertex sends its subpath along the
// unit direction w: eta_w^2 |w . ns|, eta_w the index on w's side.
// A strategy that would connect at a delta vertex (mirror, glass) or hit a point light has density
// 0 and is skipped (counting it gave single huge fireflies in Mitsuba #132, pbrt-v4 #326, SmallVCM
// #5). Every other strategy crosses a specular vertex x_j inside one subpath: the delta cancels
// between strategies; the geometry around it must be kept. The delta is one in the measure
// eta^2 |cos| d omega, which mirrors and Snell's law keep (etendue) whichever way x_j is crossed;
// left in pdfFwd and pdfRev are eta^2 |cos| at x_j (here) and the |cos|/d^2 of the
// conversion to area at the next vertex. Kept, they cancel along a chain a S..S b, all but its ends':
//     p(a ... b) / p(b ... a) = [p_omega(a) / (eta_a^2 |cos_a|)] / [p_omega(b) / (eta_b^2 |cos_b|)].
// pbrt stores 0 after a delta event and its MISWeight counts a 0 as 1 (remap0; --delta-density-one):
// for a caustic millimetres below a glass ball it is huge, and pbrt's convention hands the caustic
// to the noisy s = 0 instead of light tracing (notes, page 10M).
inline float specularDensity(const Scene& scene, const SurfacePoint& sp, Vec3 w) {
    const Material& m = materialAt(scene, sp);
    float eta = m.type == Material::Glass && dot(w, sp.ng) < 0 ? m.ior : 1;  // the back side is inside
    return sqr(eta) * absDot(w, sp.ns);
}

// The densities at a vertex v whose subpath moved on along w: specularDensity's after a delta event, else evalVertex's.
inline void scatteringDensities(const Scene& scene, const PathVertex& v, Vec3 w, Transport mode, float& pdf, float& pdfReverse) {
    if (!v.delta) {
        evalVertex(scene, v, w, mode, pdf, pdfReverse);
        return;
    }
    pdf = specularDensity(scene, v.sp, w);
    pdfReverse = specularDensity(scene, v.sp, v.wo);
}

// Adds v, reached from path.back(): v's pdfFwd and the pdfRev of the vertex before path.back(), on
// the vertices' positions (not the offset ray's), each with its sampling vertex's continuation.
inline void appendVertex(const Scene& scene, std::vector<PathVertex>& path, const PathVertex& vertex, Transport mode) {
    path.push_back(vertex);
    const size_t i = path.size() - 1;
    PathVertex& v = path[i];
    const PathVertex& prev = path[i - 1];
    float pdf, pdfReverse;
    scatteringDensities(scene, prev, -v.wo, mode, pdf, pdfReverse);
    v.pdfFwd = toArea(pdf * prev.continuation, v, v.wo, v.prevDist2);
    if (i >= 2) path[i - 2].pdfRev = toArea(pdfReverse * prev.continuation, path[i - 2], prev.wo, prev.prevDist2);
    if (prev.delta && scene.conventions.deltaDensityOne) {  // the deliberate mistake: pbrt's area density of 1
        v.pdfFwd = prev.continuation;
        if (i >= 2) path[i - 2].pdfRev = prev.continuation;
    }
}

// Extends a subpath by BSDF sampling, each new vertex by appendVertex.
inline void randomWalk(const Scene& scene, const SampleOptions& opt, Ray ray, Vec3 beta, int maxSurfaceVertices,
                       Transport mode, Rng& rng, std::vector<PathVertex>& path) {
    const float start = maxComponent(beta);  // Russian roulette follows the throughput relative to it
    for (int bounces = 0; bounces < maxSurfaceVertices; ++bounces) {
        Hit hit = intersect(scene, ray);
        if (!hit.found()) return;
        PathVertex v;
        v.sp = surfaceAt(scene, ray, hit);
        v.beta = beta;
        Vec3 d = path.back().sp.p - v.sp.p;
        v.prevDist2 = dot(d, d);
        if (!(v.prevDist2 > 0)) return;
        v.wo = d / std::sqrt(v.prevDist2);
        if (opt.roulette == Roulette::Albedo) v.continuation = albedoContinuation(scene, v.sp);
        appendVertex(scene, path, v, mode);
        if (bounces + 1 == maxSurfaceVertices) return;
        BsdfSample bs;
        if (!sampleBsdf(scene, v.sp, v.wo, mode, rng, bs)) return;
        path.back().delta = bs.delta;
        beta *= bs.weight;
        if (opt.roulette == Roulette::Albedo) {
            if (!(rng.uniform() < v.continuation)) return;
            beta = beta / v.continuation;
        } else if (opt.roulette == Roulette::Throughput && !russianRoulette(beta, start, bounces, opt, rng)) {
            return;  // bounces so far, as in sampleNEE
        }
        ray = spawnRay(v.sp, bs.wi);
    }
}

inline PathVertex pinholeVertex(const Scene& scene) {
    PathVertex z0;
    z0.type = PathVertex::Camera;
    z0.sp.p = scene.camera.eye;
    z0.beta = Vec3(1);  // W_j cos / p = 1 for a pixel sample
    z0.pdfFwd = 1;
    z0.deltaPosition = true;  // never hit (no t = 0 strategy), but connected to: not a delta BSDF
    return z0;
}

// Subpaths of up to --maxdepth bounces, or (mmlt) of exactly `vertices` vertices where they survive.
inline void cameraSubpath(const Scene& scene, const SampleOptions& opt, float filmX, float filmY, Rng& rng,
                          std::vector<PathVertex>& path, int vertices = 0) {
    path.clear();
    path.push_back(pinholeVertex(scene));
    Ray ray = cameraRay(scene.camera, filmX, filmY);
    randomWalk(scene, opt, ray, Vec3(1), vertices > 0 ? vertices - 1 : opt.maxDepth + 1, Transport::Radiance, rng, path);
}

// y_0: a point sampled on a light, its throughput Le/p_A (or I/P(light)) and density p_A.
inline PathVertex lightVertex(const LightPoint& lp) {
    PathVertex y0;
    y0.type = PathVertex::Light;
    y0.sp = lp.sp;
    y0.light = lp.light;
    y0.beta = lp.emission / lp.pdfArea;
    y0.pdfFwd = lp.pdfArea;
    y0.deltaPosition = lp.deltaPosition;
    return y0;
}

inline void lightSubpath(const Scene& scene, const SampleOptions& opt, Rng& rng, std::vector<PathVertex>& path, int vertices = 0) {
    path.clear();
    EmissionSample es = sampleEmission(scene, rng);
    path.push_back(lightVertex(es.point));
    const PathVertex& y0 = path[0];
    if (isBlack(es.weight)) return;
    Ray ray = es.point.deltaPosition ? Ray{y0.sp.p, es.dir, kInf} : spawnRay(y0.sp, es.dir);
    randomWalk(scene, opt, ray, es.weight, vertices > 0 ? vertices - 1 : opt.maxDepth, Transport::Importance, rng, path);
}

// Mirrors and glass cannot be connected to: the direction is fixed by the other vertex.
inline bool connectable(const Scene& scene, const PathVertex& v) {
    return v.type != PathVertex::Surface || !isSpecular(materialAt(scene, v.sp));
}

// A light-side vertex seen through the pinhole (the t = 1 connection); pixel -1 if it is not seen.
inline Vec3 connectToPinhole(const Scene& scene, const PathVertex& y, int& pixel) {
    CameraConnection c = connectToCamera(scene, y.sp);
    pixel = c.pixel;
    if (c.pixel < 0) return Vec3(0);
    float pdf, pdfReverse;
    return y.beta * evalVertex(scene, y, c.toCamera, Transport::Importance, pdf, pdfReverse) * c.importance;
}

// The segment from a light-side vertex y to a camera-side vertex x, both ends evaluated by evalVertex.
struct Connection {
    Vec3 w;           // unit, from y to x
    float dist2 = 0;
    Vec3 fy, fx;
    float pdfY = 0, pdfYReverse = 0, pdfX = 0, pdfXReverse = 0;
};

inline void evalConnection(const Scene& scene, const PathVertex& y, const PathVertex& x, Connection& c) {
    Vec3 d = x.sp.p - y.sp.p;
    c.dist2 = dot(d, d);
    if (!(c.dist2 > 0)) return;
    c.w = d / std::sqrt(c.dist2);
    c.fy = evalVertex(scene, y, c.w, Transport::Importance, c.pdfY, c.pdfYReverse);
    if (!isBlack(c.fy)) c.fx = evalVertex(scene, x, -c.w, Transport::Radiance, c.pdfX, c.pdfXReverse);
}

// Light-side vertex y joined to camera-side vertex x, before the visibility test.
inline Vec3 connectVertices(const PathVertex& y, const PathVertex& x, const Connection& c) {
    return c.dist2 > 0 ? y.beta * c.fy * c.fx * x.beta / c.dist2 : Vec3(0);
}

inline bool mutuallyVisible(const Scene& scene, const PathVertex& a, const PathVertex& b) {
    return !occluded(scene, shadowRay(a.sp, b.sp));
}

// -- (c) lt: "next event (light tracing)". Paths start on the lights with p(x,Theta) = Le|cos|/Phi
// and every vertex is connected to the pinhole (the strategies with one camera vertex), BSDFs
// sampled in Transport::Importance. It renders the caustic under the glass sphere, which eye paths
// find only by hitting the light after the refraction (noisy) and never for a point light: no
// connection passes through glass, a light path does by sampling. Each pixel's stream traces one
// light path; what reaches the pixel itself comes as splats too.
inline Vec3 sampleLT(const Scene& scene, const SampleOptions& opt, const PassData&, int, int, Rng& rng, RowOutput& out) {
    thread_local std::vector<PathVertex> light;
    lightSubpath(scene, opt, rng, light);
    for (const PathVertex& y : light) {
        int pixel = -1;
        Vec3 c = connectable(scene, y) ? connectToPinhole(scene, y, pixel) : Vec3(0);
        if (pixel >= 0) out.splats.push_back({pixel, c});
    }
    return Vec3(0);
}

// -- (d), (e) ir: "instant radiosity" (Keller 1997), "(clamped)". A few light paths leave virtual
// point lights (VPLs) at their non-specular vertices; the first non-specular vertex x of a camera
// path gathers from all of them:
//   sum_VPL  beta_y / N  f_y(y->x) f_x(y->x->eye) G(x,y) V(x,y)
// Unbiased for the paths it can make, but G = cos cos / d^2 is unbounded where x and y come close
// (corners): panel (d)'s splotches. --clamp C uses min(G, C): panel (e), smooth but darker, and the
// loss does not shrink with more passes (bias; the same 1/d^2 was pbrt-v3 #73).
struct Vpl {
    PathVertex y;       // a light-subpath vertex, its beta divided by the number of VPL paths
    int bounces = 0;    // scattering vertices before y on its light path
};

inline std::vector<Vpl> traceVpls(const Scene& scene, const SampleOptions& opt, int pass) {
    std::vector<Vpl> vpls;
    std::vector<PathVertex> path;
    for (int i = 0; i < opt.ir.vplPaths; ++i) {
        Rng rng = sampleRng(opt, kVplStream, uint64_t(i), uint64_t(pass));
        lightSubpath(scene, opt, rng, path);
        for (size_t k = 0; k < path.size(); ++k) {
            if (!connectable(scene, path[k])) continue;
            vpls.push_back({path[k], int(k)});
            vpls.back().y.beta = path[k].beta / float(opt.ir.vplPaths);
        }
    }
    return vpls;
}

inline Vec3 gatherVpls(const Scene& scene, const SampleOptions& opt, const std::vector<Vpl>& vpls, const PathVertex& x,
                       int cameraBounces, RowOutput& out) {
    Vec3 sum(0);
    for (const Vpl& v : vpls) {
        if (v.bounces + cameraBounces + 1 > opt.maxDepth) continue;
        Connection k;
        evalConnection(scene, v.y, x, k);
        Vec3 c = connectVertices(v.y, x, k);
        if (isBlack(c) || !mutuallyVisible(scene, v.y, x)) continue;
        if (opt.ir.clamp > 0) {
            float G = absDot(k.w, x.sp.ng) * cosAt(v.y, k.w) / k.dist2;
            double before = average(c);
            if (G > opt.ir.clamp) c *= opt.ir.clamp / G;
            out.energyUnclamped += before;
            out.energyClamped += average(c);
        }
        sum += c;
    }
    return sum;
}

// The camera half of ir: follow specular bounces, gather at the first non-specular vertex.
inline Vec3 sampleIR(const Scene& scene, const SampleOptions& opt, const PassData& pass, int x, int y, Rng& rng, RowOutput& out) {
    Ray ray = pixelRay(scene.camera, x, y, rng);
    Vec3 L(0), beta(1);
    for (int bounces = 0; bounces <= opt.maxDepth; ++bounces) {
        Hit hit = intersect(scene, ray);
        if (!hit.found()) break;
        PathVertex z;  // a camera subpath's vertex
        z.sp = surfaceAt(scene, ray, hit);
        z.wo = -ray.d;
        z.beta = Vec3(1);
        L += beta * emittedRadiance(scene, z.sp, z.wo);
        if (connectable(scene, z)) return L + beta * gatherVpls(scene, opt, *pass.vpls, z, bounces, out);
        BsdfSample bs;
        if (bounces == opt.maxDepth || !sampleBsdf(scene, z.sp, z.wo, Transport::Radiance, rng, bs)) break;
        beta *= bs.weight;
        ray = spawnRay(z.sp, bs.wi);
    }
    return L;
}

// -- (f) bdpt: "bidirectional path tracing" (Lafortune & Willems 1993; Veach & Guibas 1995).
// Slides "Solving the Rendering Equation" ("one pair of paths per pixel sample"), "Notation",
// "Bidirectional Probabilities" (p_{k,m}) and "Implementation" (the max heuristic's loop: below,
// connectSubpaths). One camera subpath z_0..z_{t-1} (z_0 the pinhole) and one light subpath
// y_0..y_{s-1} (y_0 on a light) per sample; every pair is connected, which makes the path x_0..x_k = y_0..y_{s-1}
// z_{t-1}..z_0 of k = s+t-1 segments with the strategy the slides call p_{k,s} ("m vertices from
// the light"): s = 0 the camera path hits an emitter, s = 1 next event, t = 1 light tracing, the
// rest "connect paths deterministically (every pair of two hit points)". Each strategy alone is
// unbiased for the paths it can make; MIS combines them: C = sum w_ij C_ij.
// The weights, pbrt-style: every vertex stores pdfFwd, the area density with which its own
// subpath sampled it, and pdfRev, the density with which the other side would have. Strategy s
// samples x_0..x_{s-1} from the light and x_s..x_k from the camera; strategy s+1 differs only in
// x_s, which changes sides:
//     p_{s+1}/p_s = pdfRev(x_s) / pdfFwd(x_s),   and likewise on the light side,
// so r_i = p_i/p_s costs one multiplication per vertex, and a heuristic maps the r_i to w_s:
//     balance w_s = 1/(1 + sum r_i)   power w_s = 1/(1 + sum r_i^2)   (Veach ch. 9)
//     max     w_s = 1 if no r_i > 1   (the slides' "choose p_X(pi) maximum"; ties, to 1e-4, share)
//     uniform w_s = 1/(1 + #{r_i > 0})   (every strategy able to make the path, equally)
// One walk serves all four heuristics and vcm's merges (section 8: one more term per vertex); its
// O(k) per connection is a few percent of a sample, most of whose time is shading and sampling
// (Appendix A; SmallVCM's cached recursion is page 10's exercise).
// The walk is in double: near corners, with sharp lobes, one density can be 1e-31 and another 1e+8.
// A subpath, or the first vertices of one: bdpt's own vectors, and vcm's light subpaths, which
// lie one after another in arrays shared by the whole pass.
struct Subpath {
    const PathVertex* v = nullptr;
    int n = 0;
    Subpath() = default;
    Subpath(const PathVertex* first, int count) : v(first), n(count) {}
    Subpath(const std::vector<PathVertex>& path) : v(path.data()), n(int(path.size())) {}
    const PathVertex& operator[](int i) const { return v[i]; }
    int size() const { return n; }
};

inline double misPower(Heuristic heuristic, double r) {  // what each r_i adds to the sum
    return heuristic == Heuristic::Power ? r * r : heuristic == Heuristic::Uniform ? 1.0 : r;
}

// pdfRev/pdfFwd of a vertex changing sides; a pdfFwd of 0 (a cosine of exactly 0) gives 0, not infinity.
inline double densityRatio(double pdfRev, double pdfFwd) { return pdfFwd > 0 ? pdfRev / pdfFwd : 0; }

// Where the two subpaths meet, the reverse densities of the (up to) four vertices next to the
// junction are not the stored ones: pt = camera[t-1], qs = light[s-1] and the one before each.
struct Junction {
    double ptRev = 0, ptMinusRev = 0, qsRev = 0, qsMinusRev = 0;
    bool lightEndDelta = false;  // a merge: light[s-1] sampled its way to the merged vertex
};

// The junction of strategy (s,t): the connection c joins qs and pt (unused for s = 0).
inline Junction connectionJunction(const Scene& scene, Subpath light, int s, Subpath camera, int t, const Connection& c) {
    Junction j;
    const PathVertex &pt = camera[t - 1], *ptMinus = t > 1 ? &camera[t - 2] : nullptr;
    if (s > 0) {  // each density sampled at a connection vertex carries that vertex's continuation
        const PathVertex &qs = light[s - 1], *qsMinus = s > 1 ? &light[s - 2] : nullptr;
        j.ptRev = t > 1 ? toArea(c.pdfY * qs.continuation, pt, c.w, c.dist2) : 0;  // the pinhole is never sampled (no t = 0)
        j.qsRev = toArea(c.pdfX * pt.continuation, qs, c.w, c.dist2);
        if (qsMinus) j.qsMinusRev = toArea(c.pdfYReverse * qs.continuation, *qsMinus, qs.wo, qs.prevDist2);
        if (ptMinus) j.ptMinusRev = toArea(c.pdfXReverse * pt.continuation, *ptMinus, pt.wo, pt.prevDist2);
    } else {  // pt lies on an emitter: how a light path would have started there
        j.ptRev = pdfLightPoint(scene, pt.sp.shape);
        if (ptMinus) j.ptMinusRev = toArea(pdfEmissionDirection(pt, pt.wo), *ptMinus, pt.wo, pt.prevDist2);
    }
    return j;
}

// The strategies able to make one path, each added as r_i = p_i / p_ref (p_ref the weighted strategy's
// density, r = 1 itself); w = 1 / sum_i misPower(r_i). Max gives the path to all strategies within 1e-4
// (rounding) of the largest density: the same set whichever strategy weighs, so the shares sum to 1.
struct MisSum {
    static constexpr double kTie = 1e-4;
    Heuristic heuristic;
    double sum = 0;
    std::vector<double>* maxRatios = nullptr;  // max's r_i until the largest is known (the thread's buffer: one MisSum at a time)
    explicit MisSum(Heuristic h) : heuristic(h) {
        thread_local std::vector<double> buffer;
        if (h == Heuristic::Max) maxRatios = &buffer, buffer.clear();
    }
    void add(double r) { if (heuristic == Heuristic::Max) maxRatios->push_back(r); else sum += misPower(heuristic, r); }
    float weight() const {
        if (heuristic != Heuristic::Max) return sum > 0 ? float(1 / sum) : 0;
        auto largest = std::max_element(maxRatios->begin(), maxRatios->end());
        if (largest == maxRatios->end() || *largest > 1 + kTie) return 0;  // none, or itself (r = 1) not among the largest
        auto sharing = std::count_if(maxRatios->begin(), maxRatios->end(), [&](double r) { return r * (1 + kTie) >= *largest; });
        return 1.0f / float(sharing);
    }
};

// The walk: adds to m the r_i of every other strategy able to make the path light[0..s-1] +
// camera[t-1..0] met at `j`, r relative to p_ref = p_{s,t} / r0 (r0 = 1 weighs (s,t) itself; a
// merge passes its own density relative to p_{s,t}). Moving vertex x to the other side multiplies
// the density by pdfRev(x)/pdfFwd(x): the strategies (s+1, t-1), (s+2, t-2), ... one way and
// (s-1, t+1), ... the other. Strategy (s', t') is left out where x_{s'-1} or x_{s'} is a delta
// vertex (a mirror, glass, a point light's position): no connection is made there. Merges (vcm,
// mergeEta > 0): the merge at x, once x has moved to the other side, has the density
// p * mergeEta * pdfFwd(x), with its own subpath's pdfFwd.
inline void misWalk(Subpath light, int s, Subpath camera, int t, double mergeEta, const Junction& j, double r0, MisSum& m) {
    auto cameraRev = [&](int i) { return i == t - 1 ? j.ptRev : i == t - 2 ? j.ptMinusRev : camera[i].pdfRev; };
    auto lightRev = [&](int i) { return i == s - 1 ? j.qsRev : i == s - 2 ? j.qsMinusRev : light[i].pdfRev; };
    // A connection is made only at non-delta vertices, whatever was sampled there afterwards.
    auto cameraDelta = [&](int i) { return i != t - 1 && camera[i].delta; };
    auto lightDelta = [&](int i) { return (i != s - 1 || j.lightEndDelta) && light[i].delta; };
    double r = r0;
    for (int i = t - 1; i > 0; --i) {  // more light vertices: strategies (s+1, t-1), ...
        r *= densityRatio(cameraRev(i), camera[i].pdfFwd);
        if (!cameraDelta(i) && !cameraDelta(i - 1)) m.add(r);  // (s + t - i, i)
        bool becomesLightVertex0 = s == 0 && i == t - 1;  // the light's own vertex is not merged
        if (mergeEta > 0 && !cameraDelta(i) && !becomesLightVertex0) m.add(r * mergeEta * camera[i].pdfFwd);
    }
    r = r0;
    for (int i = s - 1; i >= 0; --i) {  // more camera vertices: strategies (s-1, t+1), ...
        r *= densityRatio(lightRev(i), light[i].pdfFwd);
        bool deltaBefore = i > 0 ? lightDelta(i - 1) : light[0].deltaPosition;
        if (!lightDelta(i) && !deltaBefore) m.add(r);  // (i, s + t - i)
        if (mergeEta > 0 && i > 0 && !lightDelta(i)) m.add(r * mergeEta * light[i].pdfFwd);
    }
}

// w_{s,t} of the path (s,t) made of light[0..s-1] and camera[0..t-1] joined by c (vcm passes its
// mergeEta). The light seen directly is left to s = 0, as in pbrt: a point light stays invisible.
inline float misWeight(const Scene& scene, Subpath light, int s, Subpath camera, int t, Heuristic heuristic, const Connection& c,
                       double mergeEta) {
    if (s + t == 2) return s == 0 ? 1.0f : 0.0f;
    PROFILE_PART(Mis);
    MisSum m{heuristic};
    m.add(1);  // (s,t) itself
    misWalk(light, s, camera, t, mergeEta, connectionJunction(scene, light, s, camera, t, c), 1, m);
    return m.weight();
}

// The unweighted contribution of strategy (s,t) and, for s > 0, its connection c; for t = 1 also
// the pixel it lands on. light[0] serves s = 1 too: y_0 is next event's light sample (pbrt and
// SmallVCM draw a fresh one per camera vertex: a few shadow rays more, hardly less error; notes,
// Appendix A). Inlined always: it runs for every (s,t) of every sample, from two callers.
[[gnu::always_inline]]
inline Vec3 connectStrategy(const Scene& scene, Subpath light, int s, Subpath camera, int t, Connection& c, int& pixel) {
    const PathVertex& pt = camera[t - 1];
    if (s == 0) {  // the camera subpath's last vertex is on an emitter
        if (pt.type != PathVertex::Surface) return Vec3(0);
        return pt.beta * emittedRadiance(scene, pt.sp, pt.wo);
    }
    const PathVertex& qs = light[s - 1];
    if (!connectable(scene, qs) || (t > 1 && !connectable(scene, pt))) return Vec3(0);
    evalConnection(scene, qs, pt, c);
    if (isBlack(c.fy)) return Vec3(0);
    if (t == 1) return connectToPinhole(scene, qs, pixel);  // light tracing (c serves the weight)
    Vec3 contribution = connectVertices(qs, pt, c);
    return isBlack(contribution) || !mutuallyVisible(scene, qs, pt) ? Vec3(0) : contribution;
}

// The light subpath of a pixel and pass, a stream of its own: vcm makes the same ones as bdpt.
inline Rng lightPathRng(const SampleOptions& opt, int pixel, int pass) {
    return sampleRng(opt, kLightPathStream, uint64_t(pixel), uint64_t(pass));
}

// Every connection (s,t) of a camera and a light subpath, MIS-weighted. visit(C_{s,t} and w_{s,t})
// sees each strategy of at most visitLength segments as it is made: the film's strategy images
// (below), or mlt's bootstrap choosing a start (section 8 (h)).
template <class Visit>
inline Vec3 connectSubpaths(const Scene& scene, const SampleOptions& opt, Subpath light, const std::vector<PathVertex>& camera,
                            int ownPixel, double mergeEta, RowOutput& out, int visitLength, const Visit& visit) {
    Vec3 L(0);
    for (int t = 1; t <= int(camera.size()); ++t)
        for (int s = 0; s <= light.size(); ++s) {
            int bounces = s + t - 2;
            if (bounces < opt.minDepth || bounces > opt.maxDepth || (s == 0 && t == 1)) continue;
            bool visited = s + t - 1 <= visitLength;
            if (s == 1 && t == 1 && !visited) continue;  // weight 0 (misWeight): spare its shadow ray
            int pixel = ownPixel;
            Connection connection;
            Vec3 c = connectStrategy(scene, light, s, camera, t, connection, pixel);
            if (isBlack(c)) continue;
            float w = misWeight(scene, light, s, camera, t, opt.heuristic, connection, mergeEta);
            if (t == 1) out.splats.push_back({pixel, c * w});
            else L += c * w;
            if (visited) visit(StrategySplat{pixel, c, w, s, t});
        }
    return L;
}
inline Vec3 connectSubpaths(const Scene& scene, const SampleOptions& opt, Subpath light, const std::vector<PathVertex>& camera,
                            int ownPixel, double mergeEta, RowOutput& out) {
    return connectSubpaths(scene, opt, light, camera, ownPixel, mergeEta, out, out.strategyMaxLength,
                           [&out](const StrategySplat& c) { out.strategySplats.push_back(c); });
}

// One bdpt sample: a camera subpath through (filmX, filmY), a light subpath, all their connections.
inline Vec3 bdptSample(const Scene& scene, const SampleOptions& opt, float filmX, float filmY, int ownPixel, Rng& cameraRng,
                       Rng& lightRng, RowOutput& out) {
    thread_local std::vector<PathVertex> camera, light;
    cameraSubpath(scene, opt, filmX, filmY, cameraRng, camera);
    lightSubpath(scene, opt, lightRng, light);
    return connectSubpaths(scene, opt, light, camera, ownPixel, 0, out);
}

inline Vec3 sampleBDPT(const Scene& scene, const SampleOptions& opt, const PassData& pass, int x, int y, Rng& rng, RowOutput& out) {
    FilmPoint f = jitteredFilmPoint(x, y, rng);
    int ownPixel = y * scene.camera.width + x;
    Rng lightRng = lightPathRng(opt, ownPixel, pass.pass);
    return bdptSample(scene, opt, f.x, f.y, ownPixel, rng, lightRng, out);
}

// == 8. Later: vertex merging and Metropolis ==================================================
// The slides' methods (a)-(f) end here. The slides name two more for "later": (g) "Vertex
// Connection and Merging (VCM, later)" and (h) "Metropolis-Sampling [Veach '97] (see later)".
// Both reuse section 7's subpaths, connections and MIS walk; notes pages 15-17 teach them.

// -- (g) vcm: "Vertex Connection and Merging (VCM, later)" (Georgiev, Krivanek, Davidovic and
// Slusallek 2012; Hachisuka, Pantaleoni and Jensen 2012). Panel (f)'s limit, the slides' "problem
// of insufficient techniques" for SDS paths: a connection needs
// two non-specular vertices side by side, so a path L S D S E (a caustic seen in a mirror, a point
// light in a glass ball seen through glass) has no strategy but s = 0, and none for a point light.
// Merging adds one: a light subpath that lands at y within radius r of a camera vertex x counts as
// if it had reached x,
//     C_merge = beta_camera(x) f(x) beta_light(y) / (pi r^2 N),
// a density estimate (a disk kernel, photon mapping's) over the pass's N = width x height light
// subpaths. Relative to the connection that samples x from the camera, its density is that of
// landing on the disk:
//     p_merge(x) = p_{s,t} * pi r^2 N * p_light(x)      (p_light(x): the light side's pdfFwd of x)
// so a merge is one more term per non-specular vertex in misWeight's walk, mergeEta = pi r^2 N the
// only new number, and every heuristic applies as to connections. The kernel blurs over the disk,
// a bias of about r; each pass shrinks the radius, r(n) = r_0 n^((alpha-1)/2) (Knaus and Zwicker
// 2011, as SmallVCM), slowly enough (alpha in (0,1)) that the variance, growing like 1/r^2, is
// still averaged away: bias and variance both vanish (consistent), the error falling more slowly
// than N^-1/2. Per pass: trace every pixel's light subpath (bdpt's), keep them, put their
// mergeable vertices in a hash grid; every camera subpath makes bdpt's connections with its own
// pixel's light subpath and merges at each non-specular vertex with the grid's within r.

// A uniform grid of cells of side 2r, hashed into as many buckets as points: a query sphere of
// radius r overlaps at most 8 cells (a bucket shared by two is visited once). The caller keeps its
// records in bucket order, so that a query reads a bucket's records one after another: merging's
// cost is the queries', and that is memory, not math.
struct HashGrid {
    float radius = 0, cellsPerUnit = 0;  // cells of side 2 r
    uint32_t bucketMask = 0;             // a power of two of buckets, at least one per point, minus 1
    std::vector<uint32_t> bucketStart;  // bucket b holds records bucketStart[b] .. bucketStart[b+1] - 1
};

// Appendix D, at the end of the file, builds the grid (returning the records' bucket order: record
// e is points[order[e]]) and queries it (visit(e) for every record within r of p, in a fixed order).
inline std::vector<uint32_t> buildHashGrid(HashGrid& g, const std::vector<Vec3>& points, float radius);
template <class Record, class Visit>
inline void forEachNeighbour(const HashGrid& g, const std::vector<Record>& records, Vec3 p, Visit&& visit);

// The pass's light subpaths: pixel p's is paths[p], its vertices stored row by row; the grid adds
// only where each mergeable vertex lies and which it is (24 bytes), not a copy of the vertices.
struct VcmPass {
    float radius = 0;
    double mergeEta = 0;                  // pi r^2 N_light; 0: no merging (vcm is bdpt)
    std::vector<std::vector<PathVertex>> rowVertices;
    std::vector<Subpath> paths;
    struct Stored {                       // the mergeable vertex first[index] of a light subpath, at p
        Vec3 p;
        uint32_t index;
        const PathVertex* first;
    };
    std::vector<Stored> stored;           // in the grid's bucket order
    HashGrid grid;
};

// r_0 when --radius is not given: one pixel's footprint, d * 2 tan(fov/2) / height, where the
// central camera ray meets the first non-specular surface (straight through glass and mirrors). A
// merge then blurs by about a pixel in the first pass, less later; a smaller r_0 is noisier, a
// larger one blurs more and costs more per query (Appendix A). It is also about SmallVCM's default.
inline float defaultMergeRadius(const Scene& scene) {
    const Camera& cam = scene.camera;
    Ray ray = cameraRay(cam, 0.5f * cam.width, 0.5f * cam.height);
    float distance = 0;
    for (int crossed = 0; crossed < 16; ++crossed) {
        Hit hit = intersect(scene, ray);
        if (!hit.found()) break;
        distance += hit.t;
        SurfacePoint sp = surfaceAt(scene, ray, hit);
        if (!isSpecular(materialAt(scene, sp))) break;
        ray = spawnRay(sp, ray.d);
    }
    return (distance > 0 ? distance : 1) * 2 * cam.tanHalfFov / cam.height;
}

inline float mergeRadius(const Scene& scene, const SampleOptions& opt, int pass) {  // r(n) = r_0 n^((alpha-1)/2), n = pass + 1
    float r0 = opt.vcm.radius >= 0 ? opt.vcm.radius : defaultMergeRadius(scene);
    return r0 * std::pow(float(pass + 1), (opt.vcm.alpha - 1) / 2);
}

inline void traceVcmLightPass(const Scene& scene, const SampleOptions& opt, int pass, int threads, VcmPass& vp) {
    const int W = scene.camera.width, H = scene.camera.height;
    vp.radius = mergeRadius(scene, opt, pass);
    vp.mergeEta = double(kPi) * vp.radius * vp.radius * double(W) * H;
    // Rows are kept from pass to pass, refilled at their exact length (doubling would waste a third).
    vp.rowVertices.resize(H);
    std::vector<std::vector<int>> rowLengths(H);
    parallelRows(H, threads, [&](int y) {
        thread_local std::vector<PathVertex> path, row;
        row.clear();
        for (int x = 0; x < W; ++x) {
            Rng rng = lightPathRng(opt, y * W + x, pass);
            lightSubpath(scene, opt, rng, path);
            row.insert(row.end(), path.begin(), path.end());
            rowLengths[y].push_back(int(path.size()));
        }
        vp.rowVertices[y].assign(row.begin(), row.end());
    });
    PROFILE_PART(Merging);  // what bdpt does not: keeping the subpaths, the grid
    vp.paths.clear();
    vp.stored.clear();
    std::vector<VcmPass::Stored> mergeable;  // in path order, then (stored) in the grid's
    std::vector<Vec3> points;
    for (int y = 0; y < H; ++y) {
        const PathVertex* v = vp.rowVertices[y].data();
        for (int n : rowLengths[y]) {
            vp.paths.emplace_back(v, n);
            for (int i = 1; i < n && vp.radius > 0; ++i)
                if (connectable(scene, v[i])) {
                    mergeable.push_back({v[i].sp.p, uint32_t(i), v});
                    points.push_back(v[i].sp.p);
                }
            v += n;
        }
    }
    if (vp.radius <= 0) return;
    vp.stored.reserve(mergeable.size());  // exactly, where it grows
    for (uint32_t i : buildHashGrid(vp.grid, points, vp.radius)) vp.stored.push_back(mergeable[i]);
}

// w of the merge of camera[t-1] with y = light[j]: the path is light[0..j-1] + camera[t-1..0] as
// for the connection (j, t), y's density of reaching the merged vertex counted once. pdf and
// pdfReverse: camera[t-1]'s BSDF densities of sampling y.wo from camera[t-1].wo and back. The max
// heuristic takes one geometry, the connection (j, t)'s (one more BSDF evaluation, at light[j-1]):
// in the furnace many strategies have exactly equal densities, and y's mixed with x's would flip
// ties from one photon to the next (a visible bias; notes, page 15); the other heuristics change
// by O(r) only. After a delta event at light[j-1] only y lies on the sampled direction.
inline float mergeWeight(const Scene& scene, Subpath light, int j, Subpath camera, int t, Heuristic heuristic, double mergeEta, float pdf,
                         float pdfReverse) {
    PROFILE_PART(Mis);
    const PathVertex &x = camera[t - 1], &y = light[j], &qs = light[j - 1];
    Junction jn;
    double self = mergeEta * y.pdfFwd;  // p_merge / p_{j,t}
    if (heuristic == Heuristic::Max && !qs.delta) {
        Connection c;
        evalConnection(scene, qs, x, c);
        jn = connectionJunction(scene, light, j, camera, t, c);
        self = mergeEta * jn.ptRev;
    } else {
        jn.ptRev = y.pdfFwd;
        jn.qsRev = pdf * x.continuation * (cosAt(qs, y.wo) / double(y.prevDist2));  // at x, toward qs, as an area density at qs
        jn.ptMinusRev = toArea(pdfReverse * x.continuation, camera[t - 2], x.wo, x.prevDist2);
        jn.qsMinusRev = j >= 2 ? light[j - 2].pdfRev : 0;
    }
    jn.lightEndDelta = true;
    if (!(self > 0)) return 0;  // a light vertex sampled with density 0 cannot be merged
    MisSum m{heuristic};
    if (!qs.delta) m.add(1 / self);  // the connection (j, t)
    misWalk(light, j, camera, t, mergeEta, jn, 1 / self, m);  // the merge itself among them
    return m.weight();
}

// Every merge at the camera vertices z_1..z_{t-1} with all the pass's light vertices within r (its
// own pixel's too); a query's merges are found first and fetched at once (their misses overlap).
inline Vec3 mergeCameraVertices(const Scene& scene, const SampleOptions& opt, const VcmPass& vp, const std::vector<PathVertex>& camera,
                                int ownPixel, RowOutput& out) {
    thread_local std::vector<const VcmPass::Stored*> found;
    PROFILE_PART(Merging);
    Vec3 L(0);
    for (int t = 2; t <= int(camera.size()); ++t) {
        const PathVertex& x = camera[t - 1];
        if (!connectable(scene, x)) continue;
        found.clear();
        forEachNeighbour(vp.grid, vp.stored, x.sp.p, [&](uint32_t n) {
            const VcmPass::Stored& merge = vp.stored[n];
            if (int(merge.index) + t - 2 > opt.maxDepth) return;  // k - 1 bounces, k = index + t - 1
            __builtin_prefetch(&merge.first[merge.index]);
            __builtin_prefetch(&merge.first[merge.index].beta);
            found.push_back(&merge);
        });
        for (const VcmPass::Stored* merge : found) {
            Subpath light(merge->first, int(merge->index) + 1);
            const PathVertex& y = light[int(merge->index)];
            float pdf, pdfReverse;
            Vec3 f = evalBsdf(scene, x.sp, x.wo, y.wo, Transport::Radiance, pdf, pdfReverse);
            float cosLight = absDot(y.wo, x.sp.ng);  // the light subpath's flux arrived through ng
            if (isBlack(f) || cosLight == 0) continue;
            Vec3 c = x.beta * f * y.beta / (cosLight * float(vp.mergeEta));
            float w = mergeWeight(scene, light, int(merge->index), camera, t, opt.heuristic, vp.mergeEta, pdf, pdfReverse);
            L += c * w;
            int k = int(merge->index) + t - 1;  // path length: index + 1 light vertices, t camera, one shared
            if (k <= out.strategyMaxLength) out.strategySplats.push_back({ownPixel, c, w, int(merge->index), t, true});
        }
    }
    return L;
}

inline Vec3 sampleVCM(const Scene& scene, const SampleOptions& opt, const PassData& pass, int x, int y, Rng& rng, RowOutput& out) {
    thread_local std::vector<PathVertex> camera;
    const VcmPass& vp = *pass.vcm;
    FilmPoint f = jitteredFilmPoint(x, y, rng);
    cameraSubpath(scene, opt, f.x, f.y, rng, camera);
    int ownPixel = y * scene.camera.width + x;
    Vec3 L = connectSubpaths(scene, opt, vp.paths[ownPixel], camera, ownPixel, vp.mergeEta, out);
    return vp.mergeEta > 0 ? L + mergeCameraVertices(scene, opt, vp, camera, ownPixel, out) : L;
}

// -- (h) "Metropolis-Sampling [Veach '97] (see later): random variation and mutations of
// bidirectional paths; very well suited for very complex light paths; unbiased but relatively
// complex algorithms; uneven convergence". pssmlt and mmlt mutate the random numbers of a sample,
// mlt (below) the path itself, as the slide says.
// pssmlt: primary-sample-space MLT (Kelemen, Szirmay-Kalos, Antal and Csonka 2002) over bdpt's own
// sample. A state u is the list of uniform numbers one bdpt sample draws (section 1: every number
// passes Rng::uniform), in three streams so that a number keeps its meaning when the other subpath
// changes length: the camera subpath's (film position first), the light subpath's and (mmlt) the
// strategy's. The sample's MIS-weighted contributions h_j(u) to pixels j give the image,
//     I_j = W H  integral h_j(u) du      (the sample's pixel is one of W H, chosen by u),
// and Metropolis draws states with density f(u)/b, f = luminance of sum_j h_j(u), b = integral f:
//     I_j = W H b E_{f/b}[ h_j / f ]:   each of the W H x spp mutations adds b h_j / f / spp.
// A step proposes v from u with a symmetric T(u->v) = T(v->u) and accepts it with
//     a(u->v) = min(1, f(v) T(v->u) / (f(u) T(u->v))) = min(1, f(v) / f(u)),
// which gives detailed balance, f(u) T(u->v) a(u->v) = f(v) T(v->u) a(v->u): states distributed
// as f/b stay so. Two steps: large (probability --large-step), every number afresh, finds new
// paths; small, each number moved by a normal of deviation --sigma (pbrt's kernel; Kelemen's is
// exponential), wrapped into [0,1), explores around a path that carries light. A number a state
// never drew is drawn when first used.
// Expected-value splats (Veach 1997, 11.5): the proposal adds a h(v)/f(v) and the current state
// (1-a) h(u)/f(u), whichever wins, so a rejected proposal still counts.
// Start-up bias: a chain started anywhere follows f/b only after a while. A bootstrap of
// --bootstrap independent samples estimates b (their mean f), and each chain starts from one of
// them chosen in proportion to f: with b the same bootstrap mean, E[b g(X_m)] = integral f g at every
// step m (Veach), as far as the bootstrap saw every kind of path (--fixed-start, the deliberate
// mistake: one fixed state). Large steps are independent states too: each pass pools them into b
// for the next, so that b's error, which scales the whole image, keeps falling, at the price of an
// O(1/N_b) bias far below the noise (notes, page 16).
// --chains chains, each its own random stream, share a pass's W H mutations; their splats are
// added in chain order, so the image does not depend on --threads.
// mmlt (Hachisuka, Kaplanyan and Dachsbacher 2014; pbrt's MLT): the state also holds a path length
// k and one strategy s of the k+1 that make it; its contribution is (k+1) w_{s,t} C_{s,t}: one
// connection per sample, weighted by bdpt's MIS. A chain keeps its k; each length gets chains in
// proportion to its b_k (f's integral over paths of length k), and its chains' splats are scaled
// by b_k over their mutations, so that each length's share of the image is its own estimate. Its
// subpaths have exactly the lengths the state chose: no roulette (it would only end some).
// One stream of a state: its numbers, replayed in the order the walk asks for them.
struct PrimaryStream {
    std::vector<float> values;
    size_t used = 0;
    Rng* fresh = nullptr;  // draws the numbers the state has not used yet
};
inline float replayUniform(PrimaryStream& stream) {
    if (stream.used == stream.values.size()) stream.values.push_back(stream.fresh->uniform());
    return stream.values[stream.used++];
}

struct PrimarySampleState {
    PrimaryStream camera, light, strategy;
    int length = 0;                    // mmlt: the path length k (segments); pssmlt: 0, every length
    std::vector<Splat> contributions;  // h_j(u)
    float f = 0;
};

// mmlt's sample: strategy (s, t = k+1-s) alone, its subpaths exactly s and t vertices long.
inline Vec3 strategySample(const Scene& scene, const SampleOptions& opt, int k, int s, float filmX, float filmY, int ownPixel,
                           Rng& cameraRng, Rng& lightRng, int& pixel) {
    thread_local std::vector<PathVertex> camera, light;
    int t = k + 1 - s;
    cameraSubpath(scene, opt, filmX, filmY, cameraRng, camera, t);
    light.clear();
    if (s > 0) lightSubpath(scene, opt, lightRng, light, s);
    if (int(camera.size()) != t || int(light.size()) != s) return Vec3(0);  // ended early (roulette, escape)
    Connection c;
    pixel = ownPixel;
    Vec3 C = connectStrategy(scene, light, s, camera, t, c, pixel);
    if (isBlack(C)) return Vec3(0);
    return C * misWeight(scene, light, s, camera, t, opt.heuristic, c, 0) * float(k + 1);
}

// A generator replaying a state's stream, the numbers it never drew from `fresh`: "replay u, draw the rest".
inline Rng replaying(PrimaryStream& stream, Rng& fresh) {
    Rng rng;
    rng.replay = &stream;
    stream.used = 0;
    stream.fresh = &fresh;
    return rng;
}

// h(u) and f(u) of state u; numbers it has not drawn yet come from the three fresh streams.
inline void evaluateState(const Scene& scene, const SampleOptions& opt, PrimarySampleState& u, Rng& cameraFresh, Rng& lightFresh,
                          Rng& strategyFresh) {
    Rng cameraRng = replaying(u.camera, cameraFresh), lightRng = replaying(u.light, lightFresh);
    Rng strategyRng = replaying(u.strategy, strategyFresh);
    FilmPoint film = uniformFilmPoint(scene.camera, cameraRng);
    const int ownPixel = pixelAt(scene.camera, film);
    u.contributions.clear();
    if (opt.method == Method::PSSMLT) {
        thread_local RowOutput out;
        out.splats.clear();
        Vec3 L = bdptSample(scene, opt, film.x, film.y, ownPixel, cameraRng, lightRng, out);
        u.contributions.swap(out.splats);
        u.contributions.push_back({ownPixel, L});
    } else {
        int s = std::min(int(strategyRng.uniform() * float(u.length + 1)), u.length), pixel = -1;
        Vec3 C = strategySample(scene, opt, u.length, s, film.x, film.y, ownPixel, cameraRng, lightRng, pixel);
        if (pixel >= 0) u.contributions.push_back({pixel, C});
    }
    u.f = 0;
    for (Splat& h : u.contributions) {
        if (!isFinite(h.value)) h.value = Vec3(0);  // dropped, as every method drops them
        u.f += luminance(h.value);
    }
}

// f of independent uniform states: the bootstrap's, and every large step's proposal.
struct FSum {
    double sum = 0, sumSquares = 0, count = 0;
    void add(double f) { sum += f, sumSquares += f * f, count += 1; }
    void add(const FSum& o) { sum += o.sum, sumSquares += o.sumSquares, count += o.count; }
};

struct PrimarySampleChain {
    Rng rng;                   // its steps, acceptances and fresh numbers
    PrimarySampleState current, proposal;
    double currentWeight = 0;  // the current state's expected-value splats not yet added
    long long accepted = 0, proposed = 0;
    FSum largeSteps;           // this pass's large-step proposals (for b)
};

inline float symmetricAcceptance(float fCurrent, float fProposal) { return fProposal > 0 ? std::min(1.0f, fProposal / fCurrent) : 0.0f; }

// A small step of one number: symmetric in v and the result, wrapped into [0,1), never 1.
inline float smallStep(float v, float step) {
    float x = v + step;
    x -= std::floor(x);
    return x < 1 ? x : 0;
}
// Box-Muller: two independent standard normals from two uniforms (a small step needs one per number).
inline void standardNormals(Rng& rng, float& a, float& b) {
    float r = std::sqrt(-2 * std::log(1 - rng.uniform())), phi = 2 * kPi * rng.uniform();
    a = r * std::cos(phi);
    b = r * std::sin(phi);
}

inline bool proposeStep(const SampleOptions& opt, PrimarySampleChain& chain) {
    PrimarySampleState &v = chain.proposal, &u = chain.current;
    v.length = u.length;
    v.camera.values = u.camera.values;
    v.light.values = u.light.values;
    v.strategy.values = u.strategy.values;
    bool large = chain.rng.uniform() < opt.metropolis.largeStep;
    if (large) {
        for (PrimaryStream* stream : {&v.camera, &v.light, &v.strategy}) stream->values.clear();  // afresh, when first used
        return true;
    }
    float normal[2];
    int left = 0;
    for (PrimaryStream* stream : {&v.camera, &v.light, &v.strategy})
        for (float& x : stream->values) {
            if (left == 0) standardNormals(chain.rng, normal[0], normal[1]), left = 2;
            x = smallStep(x, opt.metropolis.sigma * normal[--left]);
        }
    return false;
}

// The end of every Metropolis step: the proposal's h/f splatted with weight a, the current's with 1 - a.
template <class Chain, class SplatState>
inline void splatAndAccept(Chain& chain, double a, const SplatState& splat) {
    if (a > 0) splat(chain.proposal, a / chain.proposal.f);
    chain.currentWeight += (1 - a) / chain.current.f;
    ++chain.proposed;
    if (chain.rng.uniform() < a) {
        splat(chain.current, chain.currentWeight);
        chain.currentWeight = 0;
        std::swap(chain.current, chain.proposal);
        ++chain.accepted;
    }
}

// One step of pssmlt's or mmlt's chain: propose, evaluate, splat, accept (a test passes other rules).
template <class Evaluate, class SplatState>
inline void metropolisStep(const SampleOptions& opt, PrimarySampleChain& chain, const Evaluate& evaluate, const SplatState& splat,
                           float (*accept)(float, float) = symmetricAcceptance) {
    bool large = proposeStep(opt, chain);
    evaluate(chain.proposal);
    if (large) chain.largeSteps.add(chain.proposal.f);
    splatAndAccept(chain, accept(chain.current.f, chain.proposal.f), splat);
}

// -- (h) mlt: Veach's Metropolis light transport (Veach and Guibas 1997; Veach 1997, ch. 11), the
// slide's "random variation and mutations of bidirectional paths". The chain's state is a path
// x = x_0..x_k (x_0 on a light, x_k the pinhole), and a mutation changes a few of its vertices and
// keeps the rest: a path that has found a narrow gap keeps its crossing while the chain varies the
// rest, where pssmlt's steps re-roll the whole path and must find the gap again (notes, page 17).
// The target is f(x), the path's measurement contribution (its luminance): with bdpt's pieces,
// f(x) = C_{s,t}(x) p_{s,t}(x) for any strategy (s,t) able to make x, C its unweighted contribution,
// p_{s,t} the product of its area densities (mirrors and glass in bdpt's measure: deltas cancel).
// A proposal y, made from x with the tentative transition density T(y|x), is accepted with
//     a(y|x) = min(1, f(y) T(x|y) / (f(x) T(y|x)))
// (detailed balance: f/b stays the chain's stationary density). Four mutations, each chosen
// uniformly among those that apply to x:
// - the bidirectional mutation: delete the vertices x_a..x_{b-1} (kd = b-a+1 edges; kd = 1 deletes
//   none), add n new ones (ka = n+1 edges): s by a walk from x_{a-1} (a new light point when
//   a = 0), n-s by a walk from x_b, joined by one connection, with bdpt's walkers. y could have
//   come from any split s, so T(y|x) = P(kd) P(ka|kd) / (#a (n+1)) sum_s p_s(y), p_s the product
//   of the n new vertices' densities, x_a..x_{a+s-1} from the light side (pL) and the rest from
//   the camera side (pE), the densities bdpt's MIS walk reads (a split whose connection would
//   fall on a mirror or glass vertex cannot make y: its p_s is 0).
// - the lens perturbation, for paths that end ... D S* E: move the point on the film by a small
//   offset (density 1/R on [r1, r2] pixels, symmetric in x and y), trace the new camera ray through
//   the same mirror and glass lobes as before, and connect the first other vertex to the old
//   path. The offset's density cancels; left is the camera walk's density of the new vertices:
//   T(y|x)/T(x|y) = pE(y's new vertices)/pE(x's old ones).
// - the caustic perturbation, for paths that end (L|D) S* D E: turn the direction leaving x_l by
//   an angle theta (density 1/theta, scaled so that the move on the film is a few pixels), follow
//   the same specular lobes, and connect the new x_{k-1} to the pinhole. Its range of theta
//   depends on the path's lengths, so its density does not cancel and is part of T.
// - the multi-chain perturbation, for what is seen through mirrors and glass when its light came
//   through them too (... D S+ D S* E, L S+ E): the lens perturbation's move, then at each diffuse
//   vertex a small turn of the direction toward the next specular chain, to a connection or the
//   lamp hit. The turns' densities cancel too; left are pE and, after a turn, |cos| / d^2.
// Walks have no roulette (their lengths are chosen); glass adds the probability of the lobe a walk
// took (F or 1-F) to T and to f alike, and a perturbation, which keeps the lobes, has none. f and
// T are in double (products of densities span hundreds of decades); only their ratios are used.
// Start (Veach's answer to start-up bias): a bootstrap of bdpt samples, every strategy's MIS-
// weighted luminance w_{s,t} f/p_{s,t} a candidate; their mean is b = integral f, and a chain starts
// from one chosen in proportion to it (sum_s w_s f/p_s p_s = f: the start is exact, as page 16's is).
// Paths of one and two segments are a bdpt sample's, as Veach has them (--chain-short-paths).

// A path of the chain: pL[i], pE[i] the area densities of x_i sampled from x_{i-1} (pL[0] the light
// point's) and from x_{i+1} (0 at a point light); lobe[i] its glass lobe's probability (else 1).
struct MutatedPath {
    std::vector<PathVertex> x;
    std::vector<double> pL, pE, lobe;
    Vec3 colour;   // f's colour, of luminance 1
    double f = 0;  // luminance of f(x)
    int pixel = -1;
    int mutation = 0;  // the mutation that proposed it (kBidirectional ...): Veach's table counts them
    int k() const { return int(x.size()) - 1; }  // segments
};

// y_0 as lightSubpath would have made it, for a vertex found on a light by either side.
inline PathVertex lightVertexAt(const Scene& scene, const PathVertex& v) {
    if (v.type == PathVertex::Light) return v;
    LightPoint lp;
    lp.sp = v.sp;
    lp.light = scene.shapes[v.sp.shape].light;
    lp.emission = scene.shapes[v.sp.shape].emission;
    lp.pdfArea = pdfLightPoint(scene, v.sp.shape);
    return lightVertex(lp);
}

// What a walk multiplies into its throughput leaving vertex v along w (f |cos| / p, or the weight
// of the lobe w takes at a mirror or glass), and v's delta flag, as sampleBsdf would set them.
inline Vec3 scatteringWeight(const Scene& scene, PathVertex& v, Vec3 w, Transport mode) {
    if (v.type == PathVertex::Camera) return Vec3(1);
    if (v.type == PathVertex::Light) {
        float pdf = pdfEmissionDirection(v, w);
        return Vec3(pdf > 0 ? (v.deltaPosition ? 1 : dot(v.sp.ng, w)) / pdf : 0);
    }
    v.delta = !connectable(scene, v);
    BsdfSample bs;
    if (v.delta) return specularScatter(scene, v.sp, v.wo, mode, dot(w, v.sp.ng) * dot(v.wo, v.sp.ng) < 0, bs) ? bs.weight : Vec3(0);
    float pdf, pdfReverse;
    Vec3 f = evalVertex(scene, v, w, mode, pdf, pdfReverse);
    return pdf > 0 ? f / pdf : Vec3(0);
}

// The first n vertices of x from its light end or its pinhole, with the walkers' throughputs and densities.
inline void subpathThrough(const Scene& scene, const std::vector<PathVertex>& x, int n, Transport mode, std::vector<PathVertex>& out) {
    const int k = int(x.size()) - 1;
    out.clear();
    if (n == 0) return;
    out.push_back(mode == Transport::Importance ? lightVertexAt(scene, x[0]) : pinholeVertex(scene));
    for (int i = 1; i < n; ++i) {
        PathVertex v;
        v.sp = x[mode == Transport::Importance ? i : k - i].sp;
        Vec3 d = out.back().sp.p - v.sp.p;
        v.prevDist2 = dot(d, d);
        v.wo = d / std::sqrt(v.prevDist2);
        v.beta = out.back().beta * scatteringWeight(scene, out.back(), -v.wo, mode);
        appendVertex(scene, out, v, mode);
    }
}

// Extends a subpath by exactly n vertices sampled from its last one; false if the walk ends sooner.
inline bool extendSubpath(const Scene& scene, const SampleOptions& walk, std::vector<PathVertex>& path, int n, Transport mode, Rng& rng) {
    if (n == 0) return true;
    PathVertex& v = path.back();
    Ray ray;
    Vec3 beta;
    if (v.type == PathVertex::Camera) {
        FilmPoint film = uniformFilmPoint(scene.camera, rng);
        ray = cameraRay(scene.camera, film.x, film.y);
        beta = Vec3(1);
    } else if (v.type == PathVertex::Light) {
        EmissionSample es;
        es.point.sp = v.sp;
        es.point.emission = v.beta;  // Le/p_A: the weight comes out as beta |cos| / p_omega
        es.point.pdfArea = 1;
        es.point.deltaPosition = v.deltaPosition;
        float u1 = rng.uniform(), u2 = rng.uniform();
        sampleEmissionDirection(es, u1, u2);
        if (isBlack(es.weight)) return false;
        ray = v.deltaPosition ? Ray{v.sp.p, es.dir, kInf} : spawnRay(v.sp, es.dir);
        beta = es.weight;
    } else {
        BsdfSample bs;
        if (!sampleBsdf(scene, v.sp, v.wo, mode, rng, bs)) return false;
        v.delta = bs.delta;
        beta = v.beta * bs.weight;
        ray = spawnRay(v.sp, bs.wi);
    }
    size_t before = path.size();
    randomWalk(scene, walk, ray, beta, n, mode, rng, path);
    return path.size() == before + size_t(n);
}

// The path strategy (s,t) makes of light[0..s-1] and camera[0..t-1], with f, its pixel and its
// vertices' densities from both sides (misWalk's); false if it carries nothing or leaves the image.
inline bool joinPath(const Scene& scene, Subpath light, int s, Subpath camera, int t, MutatedPath& y) {
    Connection c;
    int pixel = -1;
    Vec3 C = connectStrategy(scene, light, s, camera, t, c, pixel);
    if (isBlack(C) || !isFinite(C) || !(luminance(C) > 0)) return false;
    Junction j = connectionJunction(scene, light, s, camera, t, c);
    const int k = s + t - 1;
    y.x.resize(k + 1);
    y.pL.assign(k + 1, 0);
    y.pE.assign(k + 1, 0);
    y.lobe.assign(k + 1, 1);
    double p = 1;
    for (int i = 0; i < s; ++i) {
        y.x[i] = light[i];
        y.pL[i] = light[i].pdfFwd;
        y.pE[i] = i == s - 1 ? j.qsRev : i == s - 2 ? j.qsMinusRev : light[i].pdfRev;
        p *= light[i].pdfFwd;
    }
    for (int i = 0; i < t; ++i) {
        y.x[k - i] = camera[i];
        y.pE[k - i] = camera[i].pdfFwd;
        y.pL[k - i] = i == t - 1 ? j.ptRev : i == t - 2 ? j.ptMinusRev : camera[i].pdfRev;
        p *= camera[i].pdfFwd;
    }
    if (y.x[0].deltaPosition) y.pE[0] = 0;
    y.pL[k] = 0;  // the pinhole
    for (int i = 1; i < k; ++i) {
        const Material& m = materialAt(scene, y.x[i].sp);
        if (m.type != Material::Glass) continue;
        float F = specularReflectance(scene, y.x[i].sp, normalize(y.x[i + 1].sp.p - y.x[i].sp.p));
        bool refracted = dot(y.x[i + 1].sp.p - y.x[i].sp.p, y.x[i].sp.ng) * dot(y.x[i - 1].sp.p - y.x[i].sp.p, y.x[i].sp.ng) < 0;
        y.lobe[i] = refracted ? 1 - F : F;
        p *= y.lobe[i];
    }
    y.pixel = t == 1 ? pixel : pixelOf(scene.camera, y.x[k - 1].sp.p);
    float lum = luminance(C);
    y.colour = scaled(C, 1.0 / lum);
    y.f = lum * p;
    return y.pixel >= 0 && y.f > 0 && std::isfinite(y.f);
}

// -- The bidirectional mutation. Veach's probabilities (1997, p. 347): delete kd edges with 1/4,
// 1/2, then 2^-kd; add ka = kd with 1/2, kd +- 1 with 0.15, kd +- j with 0.2 * 2^-j; renormalised.
inline double deletionWeight(int kd) { return kd == 1 ? 0.25 : kd == 2 ? 0.5 : 1.0 / double(1ull << std::min(kd, 63)); }
inline double additionWeight(int ka, int kd) {
    int j = std::abs(ka - kd);
    return j == 0 ? 0.5 : j == 1 ? 0.15 : 0.2 / double(1ull << std::min(j, 63));
}

// Path lengths (segments) the chain may visit.
struct LengthRange {
    int min, max;
};

// P(kd) on a path of k segments: kd from 1 to k+1 (all vertices but the pinhole).
inline double deletionProbability(int kd, int k) {
    double total = 0;
    for (int d = 1; d <= k + 1; ++d) total += deletionWeight(d);
    return kd >= 1 && kd <= k + 1 ? deletionWeight(kd) / total : 0;
}
// P(ka | kd): the new length k - kd + ka stays in range, and kd = ka = 1 (no change) is not drawn.
inline bool additionAllowed(int ka, int kd, int k, LengthRange r) {
    int newK = k - kd + ka;
    return ka >= 1 && newK >= r.min && newK <= r.max && !(ka == 1 && kd == 1);
}
inline double additionProbability(int ka, int kd, int k, LengthRange r) {
    double total = 0;
    for (int a = 1; a <= r.max + 1; ++a)
        if (additionAllowed(a, kd, k, r)) total += additionWeight(a, kd);
    return additionAllowed(ka, kd, k, r) && total > 0 ? additionWeight(ka, kd) / total : 0;
}

// Where the deletion may start: the kept x_{a-1} and x_b (b = a+kd-1) must not be mirrors or glass
// (walks and connections start there); a = 0 deletes the light point, which needs a new one.
inline bool deletionAllowed(const Scene& scene, const MutatedPath& x, int a, int kd, int ka) {
    int b = a + kd - 1;
    if (a < 0 || b > x.k()) return false;
    if (a == 0) return kd > 1 && ka > 1 && connectable(scene, x.x[b]);
    return connectable(scene, x.x[a - 1]) && connectable(scene, x.x[b]);
}
inline int deletionPlaces(const Scene& scene, const MutatedPath& x, int kd, int ka) {
    int n = 0;
    for (int a = 0; a + kd - 1 <= x.k(); ++a) n += deletionAllowed(scene, x, a, kd, ka);
    return n;
}

// T's density of y's n new vertices x_a.. over every split, lobes in: sum_s prod_{i<a+s} pL[i] prod pE[i].
inline double splitDensitySum(const Scene& scene, const MutatedPath& y, int a, int n) {
    double sum = 0;
    for (int s = 0; s <= n; ++s) {
        int lightEnd = a + s - 1, cameraEnd = a + s;  // the connection (lightEnd -1: the camera walk found the light)
        if ((lightEnd >= 0 && !connectable(scene, y.x[lightEnd])) || !connectable(scene, y.x[cameraEnd])) continue;
        double p = 1;
        for (int i = a; i < a + n; ++i) p *= i < a + s ? y.pL[i] : y.pE[i];
        sum += p;
    }
    for (int i = a; i < a + n; ++i) sum *= y.lobe[i];
    return sum;
}

// T(y|x) of the bidirectional mutation that replaced x_a..x_{a+kd-2} by y_a..y_{a+ka-2}; a point
// light deleted (a = 0) and drawn again makes the same y as kept (a = 1): T sums both ways.
inline double deletionDensity(const Scene& scene, const MutatedPath& x, const MutatedPath& y, int a, int kd, int ka, LengthRange r) {
    int places = deletionPlaces(scene, x, kd, ka);
    if (places == 0) return 0;
    return deletionProbability(kd, x.k()) * additionProbability(ka, kd, x.k(), r) / (double(places) * ka) *
           splitDensitySum(scene, y, a, ka - 1);
}
inline double bidirectionalDensity(const Scene& scene, const MutatedPath& x, const MutatedPath& y, int a, int kd, int ka, LengthRange r) {
    double T = deletionDensity(scene, x, y, a, kd, ka, r);
    if (a == 1 && x.x[0].deltaPosition) T += deletionDensity(scene, x, y, 0, kd + 1, ka + 1, r);
    return T;
}

template <class Pick>
inline int pickIndex(int first, int last, Rng& rng, const Pick& weight) {  // index drawn in proportion to weight(i)
    double total = 0;
    for (int i = first; i <= last; ++i) total += weight(i);
    if (!(total > 0)) return -1;
    double u = rng.uniform() * total;
    for (int i = first; i <= last; ++i)
        if ((u -= weight(i)) < 0 && weight(i) > 0) return i;
    for (int i = last; i >= first; --i)
        if (weight(i) > 0) return i;
    return -1;
}

// A proposal y and its ratio f(y) T(x|y) / (f(x) T(y|x)); 0: no proposal, counted as a rejection.
inline double bidirectionalMutation(const Scene& scene, const SampleOptions& walk, LengthRange r, const MutatedPath& x, Rng& rng, MutatedPath& y) {
    thread_local std::vector<PathVertex> light, camera;
    const int k = x.k();
    // Drawn from the unnormalised weights (pickIndex normalises); T uses the probabilities.
    int kd = pickIndex(1, k + 1, rng, deletionWeight);
    int ka = pickIndex(1, r.max + 1, rng, [&](int e) { return additionAllowed(e, kd, k, r) ? additionWeight(e, kd) : 0.0; });
    if (ka < 0) return 0;
    int a = pickIndex(0, k + 1 - kd, rng, [&](int i) { return double(deletionAllowed(scene, x, i, kd, ka)); });
    if (a < 0) return 0;
    const int b = a + kd - 1, n = ka - 1, s = std::min(int(rng.uniform() * (n + 1)), n);
    if (a == 0) {
        light.clear();
        if (s > 0) lightSubpath(scene, walk, rng, light, s);
        if (int(light.size()) != s) return 0;
    } else {
        subpathThrough(scene, x.x, a, Transport::Importance, light);
        if (!extendSubpath(scene, walk, light, s, Transport::Importance, rng)) return 0;
    }
    subpathThrough(scene, x.x, k - b + 1, Transport::Radiance, camera);
    if (!extendSubpath(scene, walk, camera, n - s, Transport::Radiance, rng)) return 0;
    if (!joinPath(scene, light, int(light.size()), camera, int(camera.size()), y)) return 0;
    if (a == 0 && x.x[0].deltaPosition && y.x[0].light == x.x[0].light) a = 1, --kd, --ka;  // the same point light: x_0 kept
    double forward = bidirectionalDensity(scene, x, y, a, kd, ka, r);
    double backward = bidirectionalDensity(scene, y, x, a, ka, kd, r);
    return forward > 0 ? y.f * backward / (x.f * forward) : 0;
}

// -- The perturbations keep a path's mirror and glass lobes: from x's vertex `from`, the walk along
// `ray` meets a specular surface wherever x had one, takes the same lobe, and a diffuse one at `to`.
inline bool followLobes(const Scene& scene, const MutatedPath& x, int from, int to, Ray ray, Transport mode, std::vector<PathVertex>& path) {
    int step = to > from ? 1 : -1;
    Vec3 beta = path.back().beta * scatteringWeight(scene, path.back(), ray.d, mode);
    for (int i = from + step;; i += step) {
        Hit hit = intersect(scene, ray);
        if (!hit.found() || isBlack(beta)) return false;
        PathVertex v;
        v.sp = surfaceAt(scene, ray, hit);
        v.beta = beta;
        Vec3 d = path.back().sp.p - v.sp.p;
        v.prevDist2 = dot(d, d);
        if (!(v.prevDist2 > 0)) return false;
        v.wo = d / std::sqrt(v.prevDist2);
        appendVertex(scene, path, v, mode);
        if (connectable(scene, path.back()) != (i == to)) return false;
        if (i == to) return true;
        const SurfacePoint& old = x.x[i].sp;
        bool refracted = dot(x.x[i + step].sp.p - old.p, old.ng) * dot(x.x[i - step].sp.p - old.p, old.ng) < 0;
        BsdfSample bs;
        if (!specularScatter(scene, path.back().sp, path.back().wo, mode, refracted, bs)) return false;
        path.back().delta = true;
        beta = beta * bs.weight;
        ray = spawnRay(path.back().sp, bs.wi);
    }
}

// Lens perturbation's reach, in pixels (Veach 1997, p. 354): 0.1 to the radius of 5% of the image.
inline void lensRadii(const Camera& cam, double& r1, double& r2) {
    r1 = 0.1;
    r2 = std::max(1.0, std::sqrt(0.05 * cam.width * cam.height / kPi));
}

// The lens perturbation applies to paths ending ... D S* E: c, the first vertex seen that is not specular.
inline int lensVertex(const Scene& scene, const MutatedPath& x) {
    int c = x.k() - 1;
    while (c > 0 && !connectable(scene, x.x[c])) --c;
    return c >= 1 && connectable(scene, x.x[c]) && connectable(scene, x.x[c - 1]) ? c : -1;
}

// The multi-chain perturbation (Veach 1997, p. 357) goes on where the lens perturbation stops at a
// diffuse vertex seen through mirrors or glass whose light also came through them (... D S+ D S* E,
// and the light itself: L S+ D S* E, L S+ E): its walk ends at c, the first vertex from the camera
// whose predecessor can be connected to, or at the light, hit (c = 0). -1: not such a path.
inline int multiChainEnd(const Scene& scene, const MutatedPath& x) {
    if (lensVertex(scene, x) >= 0) return -1;
    int c = x.k();
    do {
        for (--c; c > 0 && !connectable(scene, x.x[c]); --c) {}
    } while (c > 0 && !connectable(scene, x.x[c - 1]));
    return c > 0 || (x.k() > 1 && !x.x[0].deltaPosition) ? c : -1;
}

// Both move the film point by an offset of density 1/R on [r1, r2] pixels, follow x's lobes to the
// next diffuse vertex, and there (multi-chain) turn the direction toward the next one by an angle of
// density 1/theta on Veach's fixed [1e-4, 0.1] degrees, until x_end, joined to x_{end-1}. Offset and
// angles have the same density both ways; left is the walk's density of the new vertices: pE, but
// after a turned direction only the solid angle's conversion to area, |cos| / d^2.
inline double perturbedWalkDensity(const Scene& scene, const MutatedPath& x, int end) {
    double p = 1;
    for (int i = end; i < x.k(); ++i) {
        Vec3 d = x.x[i + 1].sp.p - x.x[i].sp.p;
        bool turned = i + 1 < x.k() && connectable(scene, x.x[i + 1]);
        p *= turned ? cosAt(x.x[i], normalize(d)) / dot(d, d) : x.pE[i];
    }
    return p;
}
inline double chainPerturbation(const Scene& scene, const MutatedPath& x, int end, Rng& rng, MutatedPath& y) {
    thread_local std::vector<PathVertex> light, camera;
    const Camera& cam = scene.camera;
    const int k = x.k();
    float fx, fy;
    if (end < 0 || !projectToFilm(cam, x.x[k - 1].sp.p, fx, fy)) return 0;
    double r1, r2, a1 = 1e-4 * kPi / 180, a2 = 0.1 * kPi / 180;
    lensRadii(cam, r1, r2);
    double R = r2 * std::exp(-std::log(r2 / r1) * rng.uniform()), phi = 2 * kPi * rng.uniform();
    float nx = float(fx + R * std::cos(phi)), ny = float(fy + R * std::sin(phi));
    if (!(nx >= 0 && nx < cam.width && ny >= 0 && ny < cam.height)) return 0;  // off the film: rejected, never wrapped
    camera.assign(1, pinholeVertex(scene));
    Ray ray = cameraRay(cam, nx, ny);
    for (int from = k, c = k - 1;; from = c--) {
        while (c > end && !connectable(scene, x.x[c])) --c;
        if (!followLobes(scene, x, from, c, ray, Transport::Radiance, camera)) return 0;
        if (c == end) break;
        double theta = a2 * std::exp(-std::log(a2 / a1) * rng.uniform()), turn = 2 * kPi * rng.uniform();
        Vec3 w = Frame(normalize(x.x[c - 1].sp.p - x.x[c].sp.p))
                     .toWorld(Vec3(float(std::sin(theta) * std::cos(turn)), float(std::sin(theta) * std::sin(turn)), float(std::cos(theta))));
        ray = spawnRay(camera.back().sp, w);
    }
    subpathThrough(scene, x.x, end, Transport::Importance, light);
    if (!joinPath(scene, light, end, camera, k - end + 1, y)) return 0;
    double pNew = perturbedWalkDensity(scene, y, end);
    return pNew > 0 ? (y.f / pNew) / (x.f / perturbedWalkDensity(scene, x, end)) : 0;
}
inline double lensPerturbation(const Scene& scene, const MutatedPath& x, Rng& rng, MutatedPath& y) {
    return chainPerturbation(scene, x, lensVertex(scene, x), rng, y);
}
inline double multiChainPerturbation(const Scene& scene, const MutatedPath& x, Rng& rng, MutatedPath& y) {
    return chainPerturbation(scene, x, multiChainEnd(scene, x), rng, y);
}

// The caustic perturbation applies to paths ending (L|D) S* D E: l, where the chain S* starts.
inline int causticVertex(const Scene& scene, const MutatedPath& x) {
    int k = x.k();
    if (k < 2 || !connectable(scene, x.x[k - 1])) return -1;
    int l = k - 2;
    while (l > 0 && !connectable(scene, x.x[l])) --l;
    return l;
}

// Its angles: the lens radii in radians per pixel, scaled by |x_{k-1} x_k| over the caustic chain's
// length, so that the film moves about as many pixels; and the angle's density in solid angle.
inline bool causticAngleRange(const Scene& scene, const MutatedPath& x, int l, double& t1, double& t2) {
    const Camera& cam = scene.camera;
    double chain = 0;
    for (int i = l; i < x.k() - 1; ++i) chain += length(x.x[i + 1].sp.p - x.x[i].sp.p);
    double r1, r2;
    lensRadii(cam, r1, r2);
    double perPixel = 2 * std::atan(cam.tanHalfFov) / cam.height * length(x.x[x.k()].sp.p - x.x[x.k() - 1].sp.p) / chain;
    t1 = r1 * perPixel;
    t2 = std::min(r2 * perPixel, 0.5 * kPi);
    return t2 > t1;
}
inline double causticDensity(const Scene& scene, const MutatedPath& x, int l, double theta) {
    double t1, t2;
    if (!causticAngleRange(scene, x, l, t1, t2) || !(theta >= t1 && theta <= t2)) return 0;
    return 1 / (2 * kPi * std::log(t2 / t1) * theta * std::sin(theta));
}

// T(y|x) of a caustic perturbation: the angle's density as an area density at y_{l+1}, then the chain's.
inline double causticTransition(const Scene& scene, const MutatedPath& from, const MutatedPath& to, int l) {
    Vec3 wOld = normalize(from.x[l + 1].sp.p - from.x[l].sp.p), d = to.x[l + 1].sp.p - to.x[l].sp.p;
    double theta = std::acos(std::clamp(double(dot(wOld, normalize(d))), -1.0, 1.0));
    double p = causticDensity(scene, from, l, theta) * cosAt(to.x[l + 1], normalize(d)) / dot(d, d);
    for (int i = l + 2; i < to.k(); ++i) p *= to.pL[i];
    return p;
}

inline double causticPerturbation(const Scene& scene, const MutatedPath& x, Rng& rng, MutatedPath& y) {
    thread_local std::vector<PathVertex> light;
    const int k = x.k(), l = causticVertex(scene, x);
    double t1, t2;
    if (l < 0 || !causticAngleRange(scene, x, l, t1, t2)) return 0;
    double theta = t2 * std::exp(-std::log(t2 / t1) * rng.uniform()), phi = 2 * kPi * rng.uniform();
    Vec3 w = normalize(x.x[l + 1].sp.p - x.x[l].sp.p);
    Vec3 turned = Frame(w).toWorld(Vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))));
    subpathThrough(scene, x.x, l + 1, Transport::Importance, light);
    const PathVertex& xl = light.back();
    Ray ray = xl.deltaPosition ? Ray{xl.sp.p, turned, kInf} : spawnRay(xl.sp, turned);
    if (!followLobes(scene, x, l, k - 1, ray, Transport::Importance, light)) return 0;
    PathVertex pinhole = pinholeVertex(scene);
    if (!joinPath(scene, light, k, Subpath(&pinhole, 1), 1, y)) return 0;
    double forward = causticTransition(scene, x, y, l), backward = causticTransition(scene, y, x, l);
    return forward > 0 ? y.f * backward / (x.f * forward) : 0;
}

// The mutations that apply to x (the bidirectional one always), each chosen with probability 1/count.
enum MutationBits { kBidirectional = 1, kLens = 2, kCaustic = 4, kMultiChain = 8 };
inline int mutationIndex(int bit) { return bit == kLens ? 1 : bit == kCaustic ? 2 : bit == kMultiChain ? 3 : 0; }  // a row of Veach's table
inline int applicableMutations(const Scene& scene, const MutatedPath& x, int enabled) {
    return (enabled & kBidirectional) | (enabled & kLens && lensVertex(scene, x) >= 0 ? kLens : 0) |
           (enabled & kCaustic && causticVertex(scene, x) >= 0 ? kCaustic : 0) |
           (enabled & kMultiChain && multiChainEnd(scene, x) >= 0 ? kMultiChain : 0);
}
inline int bitCount(int bits) { return (bits & 1) + (bits >> 1 & 1) + (bits >> 2 & 1) + (bits >> 3 & 1); }

// One proposal from x and its acceptance a(y|x), the choice of the mutation counted both ways.
inline double mutate(const Scene& scene, const SampleOptions& walk, LengthRange r, const MutatedPath& x, Rng& rng, MutatedPath& y) {
    const int applicable = applicableMutations(scene, x, walk.metropolis.mutations), count = bitCount(applicable);
    if (count == 0) return 0;  // (tests run the perturbations alone)
    int pick = std::min(int(rng.uniform() * count), count - 1), bit = 1;
    for (;; bit <<= 1)
        if (applicable & bit && pick-- == 0) break;
    double ratio = bit == kBidirectional ? bidirectionalMutation(scene, walk, r, x, rng, y)
                   : bit == kLens        ? lensPerturbation(scene, x, rng, y)
                   : bit == kCaustic     ? causticPerturbation(scene, x, rng, y)
                                         : multiChainPerturbation(scene, x, rng, y);
    y.mutation = bit;
    if (!(ratio > 0) || !std::isfinite(ratio)) return 0;
    return std::min(1.0, ratio * count / bitCount(applicableMutations(scene, y, walk.metropolis.mutations)));
}

// One of mlt's chains: its own random stream, its path and the one proposed from it.
struct PathChain {
    Rng rng;
    MutatedPath current, proposal;
    double currentWeight = 0;
    long long accepted = 0, proposed = 0;
    long long acceptedBy[4] = {0, 0, 0, 0}, proposedBy[4] = {0, 0, 0, 0};  // per mutation: bidirectional, lens, caustic, multi-chain
};

// -- The three Metropolis methods' passes. Paths of one and two segments (direct light, the lamp
// seen) are bright and easy: a chain would spend most of its mutations there, where a bdpt sample
// is better. A bdpt sample per pixel renders them and the chains the rest (Veach; pbrt-v2,
// Mitsuba); --chain-short-paths gives the chains all lengths (notes, page 16).
inline int shortestChainPath(const SampleOptions& opt) { return opt.metropolis.chainShortPaths ? 1 : 3; }  // segments

// The chains' own samples: no shorter path, and no roulette where lengths are chosen (mmlt, mlt).
inline SampleOptions chainOptions(const SampleOptions& opt) {
    SampleOptions o = opt;
    o.minDepth = shortestChainPath(opt) - 1;
    if (opt.method != Method::PSSMLT) o.roulette = Roulette::Off;
    return o;
}

// What the Metropolis methods keep from pass to pass.
struct MetropolisPass {
    double b = 0, bStandardError = 0;  // the estimate of b = integral f this pass uses
    std::vector<FSum> fByLength;       // f of independent states, per path length (pssmlt, mlt: one)
    std::vector<PrimarySampleChain> chains;  // pssmlt, mmlt
    std::vector<PathChain> paths;      // mlt
    std::vector<std::vector<Splat>> chainSplats;  // this pass's, per chain
    std::vector<Vec3> image;                      // this pass's: b sum h/f over W H mutations
    SampleOptions shortPaths;                     // the per-pixel bdpt sample of paths of 1 and 2 segments
    double lengthB(int i) const { return fByLength[i].count > 0 ? fByLength[i].sum / fByLength[i].count : 0; }
};

// The bootstrap's size: 100,000 samples for pssmlt; 200,000 for mlt, whose b comes from its
// bootstrap alone and scales the whole image (a tenth of a 4-second run at 64x64); 1,000,000 for
// mmlt, which spreads them over the path lengths: a length the bootstrap leaves dark gets no chain,
// and one that a single strategy finds (sds's lamp through glass, s = 0 only) needs tens of
// thousands to be seen (notes, page 17).
inline int bootstrapSamples(const SampleOptions& opt) {
    return opt.metropolis.bootstrap > 0 ? opt.metropolis.bootstrap : opt.method == Method::PSSMLT ? 100000 : opt.method == Method::MLT ? 200000 : 1000000;
}
// mlt's chains make one path's move each, where pssmlt's splat a whole bdpt sample: more and
// shorter chains spread its starts (drawn as f) over the image (measured: 1,024 over 256 halves
// the error on the glass scenes at 256 mutations per pixel; see the notes' Metropolis page).
inline int chainCount(const SampleOptions& opt) { return opt.metropolis.chains > 0 ? opt.metropolis.chains : opt.method == Method::MLT ? 1024 : 256; }

// Independent numbers, whatever --sampler: mmlt deals them to the lengths by index (every L-th Sobol point is uneven).
inline Rng bootstrapRng(const SampleOptions& opt, int sample, int stream) {
    return makeRng(opt.seed ^ kBootstrapStream, uint64_t(sample), uint64_t(stream));
}
inline Rng chainRng(const SampleOptions& opt, size_t chain) { return makeRng(opt.seed ^ kChainStream, uint64_t(chain), 0); }

// f of the bootstrap's n samples, f(i) each, on the pass's threads.
template <class F>
inline std::vector<double> bootstrapValues(int n, int threads, const F& f) {
    std::vector<double> values(n);
    parallelRows(n, threads, [&](int i) { values[i] = f(i); });
    return values;
}

inline int lengthCount(const SampleOptions& opt) {  // mmlt: one b_k per path length (none: all are short); pssmlt, mlt: one b
    return opt.method == Method::MMLT ? std::max(0, opt.maxDepth + 2 - shortestChainPath(opt)) : 1;
}

// Bootstrap sample i (mmlt: of the i-th length, in turn) into u, from its own streams.
inline void bootstrapSample(const Scene& scene, const SampleOptions& opt, int i, PrimarySampleState& u) {
    Rng camera = bootstrapRng(opt, i, 0), light = bootstrapRng(opt, i, 1), strategy = bootstrapRng(opt, i, 2);
    u.camera.values.clear();
    u.light.values.clear();
    u.strategy.values.clear();
    u.length = opt.method == Method::MMLT ? shortestChainPath(opt) + i % lengthCount(opt) : 0;
    evaluateState(scene, chainOptions(opt), u, camera, light, strategy);
}

// b = sum over lengths k of the mean f of length k's independent samples, and its standard error.
inline void estimateB(MetropolisPass& mp) {
    double b = 0, variance = 0;
    for (size_t k = 0; k < mp.fByLength.size(); ++k) {
        const FSum& s = mp.fByLength[k];
        if (s.count == 0) continue;
        double mean = mp.lengthB(int(k));
        b += mean;
        variance += std::max(0.0, s.sumSquares / s.count - mean * mean) / std::max(1.0, s.count - 1);
    }
    mp.b = b;
    mp.bStandardError = std::sqrt(variance);
}

// The chains' lengths (mmlt): in proportion to each length's b_k, by largest remainders, a length
// without a chain counting one more (+1 below), so that every lit length gets a chain before any
// gets a second; then by b_k again. Drawn from the bootstrap, each share would be left to chance.
inline std::vector<int> chainLengths(const MetropolisPass& mp, int chains) {
    const int L = int(mp.fByLength.size());
    std::vector<int> count(L, 0);
    std::vector<double> remainder(L, 0);
    int given = 0;
    for (int k = 0; k < L; ++k) {
        double share = chains * mp.lengthB(k) / mp.b;
        count[k] = int(share);
        remainder[k] = mp.lengthB(k) > 0 ? share - count[k] + (count[k] == 0) : -1;  // a lit length without a chain first
        given += count[k];
    }
    for (; given < chains; ++given) {
        int k = int(std::max_element(remainder.begin(), remainder.end()) - remainder.begin());
        ++count[k];
        remainder[k] = -1;
        if (*std::max_element(remainder.begin(), remainder.end()) < 0)  // every length served: the rest by b_k again
            for (int j = 0; j < L; ++j) remainder[j] = mp.lengthB(j) > 0 ? chains * mp.lengthB(j) / mp.b - count[j] : -1;
    }
    std::vector<int> length;
    for (int k = 0; k < L; ++k) length.insert(length.end(), count[k], k);
    return length;
}

// A chain's start: entry j of the running sums `cdf` of the bootstrap's f, with probability
// f_j / sum f (upper_bound: the first sum above the pick, so f_j > 0); `pick` is u sum f.
inline int pickInProportion(const std::vector<double>& cdf, float u, double& pick) {
    pick = double(u) * cdf.back();
    return std::min(int(std::upper_bound(cdf.begin(), cdf.end(), pick) - cdf.begin()), int(cdf.size()) - 1);
}
// --fixed-start, the deliberate mistake: every chain from the first sample that carries light.
inline int firstLitSample(const std::vector<double>& f) {
    return int(std::find_if(f.begin(), f.end(), [](double x) { return x > 0; }) - f.begin());
}

// pssmlt's and mmlt's first pass: b from the bootstrap, and each chain's start drawn in proportion to f.
inline void startPrimarySampleChains(const Scene& scene, const SampleOptions& opt, int threads, MetropolisPass& mp) {
    const int n = bootstrapSamples(opt), lengths = lengthCount(opt);
    mp.chains.assign(chainCount(opt), PrimarySampleChain());
    if (lengths == 0) return;  // --maxdepth leaves the chains no path: b = 0, the image is bdpt's short paths
    std::vector<double> f = bootstrapValues(n, threads, [&](int i) {
        thread_local PrimarySampleState u;
        bootstrapSample(scene, opt, i, u);
        return u.f;
    });
    mp.fByLength.assign(lengths, FSum());
    for (int i = 0; i < n; ++i) mp.fByLength[i % lengths].add(f[i]);
    estimateB(mp);
    if (!(mp.b > 0)) return;  // no sample found light: the chains' image stays black
    std::vector<int> length = lengths > 1 ? chainLengths(mp, int(mp.chains.size())) : std::vector<int>(mp.chains.size(), 0);
    std::vector<std::vector<double>> cdf(lengths);  // per length, over its samples i = k, k + L, ...
    for (int i = 0; i < n; ++i) cdf[i % lengths].push_back((cdf[i % lengths].empty() ? 0 : cdf[i % lengths].back()) + f[i]);
    for (size_t c = 0; c < mp.chains.size(); ++c) {
        PrimarySampleChain& chain = mp.chains[c];
        chain.rng = chainRng(opt, c);
        double pick;
        int i = length[c] + pickInProportion(cdf[length[c]], chain.rng.uniform(), pick) * lengths;
        if (opt.metropolis.fixedStart) i = firstLitSample(f);
        bootstrapSample(scene, opt, i, chain.current);
    }
}

// A pass's N mutations over C chains: N / C each, and one more for N % C of them, in turn by pass.
inline long long mutationsOfChain(long long N, long long C, long long c, int pass) {
    return N / C + ((c + C - pass * (N % C) % C) % C < N % C);
}

// The pass's image from the chains' splats, in chain order, scaled by b (mmlt: b_k N / M_k per length).
inline void addChainSplats(MetropolisPass& mp, long long N, int pass, const std::vector<int>& lengthOfChain) {
    const long long C = (long long)lengthOfChain.size();
    std::vector<double> scale(mp.fByLength.size(), 0), done(mp.fByLength.size(), 0);
    for (long long c = 0; c < C; ++c) done[lengthOfChain[c]] += double(mutationsOfChain(N, C, c, pass));
    for (size_t k = 0; k < scale.size(); ++k)
        scale[k] = done[k] > 0 ? (scale.size() > 1 ? mp.lengthB(int(k)) : mp.b) * double(N) / done[k] : 0;
    mp.image.assign(size_t(N), Vec3(0));
    for (size_t c = 0; c < mp.chainSplats.size(); ++c)
        for (const Splat& s : mp.chainSplats[c]) mp.image[s.pixel] += s.value * float(scale[lengthOfChain[c]]);
}

// The expected-value splats of a state, weight h/f: a primary-sample state's, or a path's one pixel.
inline void splatState(const PrimarySampleState& u, double weight, std::vector<Splat>& out) {
    for (const Splat& h : u.contributions)
        if (!isBlack(h.value)) out.push_back({h.pixel, scaled(h.value, weight)});
}
inline void splatState(const MutatedPath& x, double weight, std::vector<Splat>& out) {
    out.push_back({x.pixel, scaled(x.colour, x.f * weight)});
}

// One pass of a method's chains: W H mutations shared among them, each chain's splats kept apart
// (added in chain order: the image does not depend on --threads); step(chain, splat) makes one.
template <class Chain, class Step>
inline void mutateChains(std::vector<Chain>& chains, MetropolisPass& mp, long long N, int pass, int threads, const Step& step) {
    const long long C = (long long)chains.size();
    mp.chainSplats.resize(size_t(C));
    parallelRows(int(C), threads, [&](int c) {
        Chain& chain = chains[c];
        std::vector<Splat>& out = mp.chainSplats[c];
        out.clear();
        if (!(chain.current.f > 0)) return;  // its start found no path (mlt)
        auto splat = [&](const auto& state, double weight) { splatState(state, weight, out); };
        for (long long i = 0, n = mutationsOfChain(N, C, c, pass); i < n; ++i) step(chain, splat);
        splat(chain.current, chain.currentWeight);
        chain.currentWeight = 0;
    });
}

// One pass of pssmlt or mmlt.
inline void tracePrimarySamplePass(const Scene& scene, const SampleOptions& opt, int pass, int threads, MetropolisPass& mp) {
    const long long N = (long long)scene.camera.width * scene.camera.height;
    if (pass == 0) startPrimarySampleChains(scene, opt, threads, mp);
    mp.image.assign(size_t(N), Vec3(0));
    if (!(mp.b > 0)) return;
    const SampleOptions chainOpt = chainOptions(opt);
    mutateChains(mp.chains, mp, N, pass, threads, [&](PrimarySampleChain& chain, const auto& splat) {
        auto evaluate = [&](PrimarySampleState& u) { evaluateState(scene, chainOpt, u, chain.rng, chain.rng, chain.rng); };
        metropolisStep(opt, chain, evaluate, splat);
    });
    std::vector<int> lengthOfChain(mp.chains.size(), 0);  // mmlt: its length's index; pssmlt: one b
    for (size_t c = 0; c < mp.chains.size(); ++c)
        if (opt.method == Method::MMLT) lengthOfChain[c] = mp.chains[c].current.length - shortestChainPath(opt);
    addChainSplats(mp, N, pass, lengthOfChain);
    for (size_t c = 0; c < mp.chains.size(); ++c) {  // the next pass's b, with this pass's large steps
        mp.fByLength[lengthOfChain[c]].add(mp.chains[c].largeSteps);
        mp.chains[c].largeSteps = FSum();
    }
    estimateB(mp);
}

// mlt's bootstrap sample i: a bdpt sample of a uniform film point; each strategy's MIS-weighted
// luminance w_{s,t} f/p_{s,t} (the chains' lengths only) is a candidate start. Returns their sum;
// `pick` in [0, sum) chooses one into `start`, rebuilt as the walkers would have made it.
inline double pathBootstrapSample(const Scene& scene, const SampleOptions& opt, int i, double pick, MutatedPath* start) {
    thread_local std::vector<PathVertex> light, camera, full, startLight, startCamera;
    thread_local RowOutput out;
    SampleOptions walk = opt;
    walk.minDepth = shortestChainPath(opt) - 1;  // the chains' lengths only
    Rng cameraRng = bootstrapRng(opt, i, 0), lightRng = bootstrapRng(opt, i, 1);
    FilmPoint film = uniformFilmPoint(scene.camera, cameraRng);
    cameraSubpath(scene, walk, film.x, film.y, cameraRng, camera);
    lightSubpath(scene, walk, lightRng, light);
    out.splats.clear();
    double sum = 0;
    connectSubpaths(scene, walk, light, camera, pixelAt(scene.camera, film), 0, out, walk.maxDepth + 1, [&](const StrategySplat& c) {
        double w = luminance(c.value * c.weight);
        if (!(w > 0) || !std::isfinite(w)) return;
        sum += w;
        if (!start || pick >= sum) return;
        full.assign(light.begin(), light.begin() + c.s);
        for (int j = c.t - 1; j >= 0; --j) full.push_back(camera[j]);
        subpathThrough(scene, full, c.s, Transport::Importance, startLight);
        subpathThrough(scene, full, c.t, Transport::Radiance, startCamera);
        if (!joinPath(scene, startLight, c.s, startCamera, c.t, *start)) start->f = 0;
        start = nullptr;
    });
    return sum;
}

// mlt's first pass: b and each chain's start from the bootstrap.
inline void startPathChains(const Scene& scene, const SampleOptions& opt, int threads, MetropolisPass& mp) {
    const int n = bootstrapSamples(opt);
    std::vector<double> f = bootstrapValues(n, threads, [&](int i) { return pathBootstrapSample(scene, opt, i, 0, nullptr); });
    mp.fByLength.assign(1, FSum());
    for (double x : f) mp.fByLength[0].add(x);
    estimateB(mp);
    mp.paths.assign(chainCount(opt), PathChain());
    if (!(mp.b > 0)) return;
    std::vector<double> cdf(n);
    std::partial_sum(f.begin(), f.end(), cdf.begin());
    for (size_t c = 0; c < mp.paths.size(); ++c) {
        PathChain& chain = mp.paths[c];
        chain.rng = chainRng(opt, c);
        for (int attempt = 0; attempt < 16 && !(chain.current.f > 0); ++attempt) {
            double pick;
            int i = pickInProportion(cdf, chain.rng.uniform(), pick);
            if (opt.metropolis.fixedStart) i = firstLitSample(f);
            pathBootstrapSample(scene, opt, i, pick - (cdf[i] - f[i]), &chain.current);
        }
    }
}

// One pass of mlt; each chain counts its proposals and acceptances per mutation (Veach's table).
inline void tracePathPass(const Scene& scene, const SampleOptions& opt, int pass, int threads, MetropolisPass& mp) {
    const long long N = (long long)scene.camera.width * scene.camera.height;
    if (pass == 0) startPathChains(scene, opt, threads, mp);
    mp.image.assign(size_t(N), Vec3(0));
    if (!(mp.b > 0)) return;
    const SampleOptions walk = chainOptions(opt);
    const LengthRange lengths{shortestChainPath(opt), opt.maxDepth + 1};
    mutateChains(mp.paths, mp, N, pass, threads, [&](PathChain& chain, const auto& splat) {
        chain.proposal.mutation = 0;
        double a = mutate(scene, walk, lengths, chain.current, chain.rng, chain.proposal);
        const int m = mutationIndex(chain.proposal.mutation);
        long long before = chain.accepted;
        splatAndAccept(chain, a, splat);
        ++chain.proposedBy[m];
        chain.acceptedBy[m] += chain.accepted - before;
    });
    addChainSplats(mp, N, pass, std::vector<int>(mp.paths.size(), 0));
}

// The options of the bdpt sample per pixel: paths of one and two segments.
inline SampleOptions shortPathOptions(const SampleOptions& opt) {
    SampleOptions o = opt;
    o.method = Method::BDPT;
    o.maxDepth = std::min(opt.maxDepth, 1);
    return o;
}

// The Metropolis methods: the pixel's share of the chains' pass, and a bdpt sample of the short paths.
inline Vec3 sampleMLT(const Scene& scene, const SampleOptions& opt, const PassData& pass, int x, int y, Rng& rng, RowOutput& out) {
    Vec3 chains = pass.metropolis->image[size_t(y) * scene.camera.width + x];
    if (opt.metropolis.chainShortPaths) return chains;
    return chains + sampleBDPT(scene, pass.metropolis->shortPaths, pass, x, y, rng, out);
}

// == 9. Film, rendering loop, image files =======================================================
// A pass gives every pixel one camera sample (and, for light-path methods, one light path from its
// stream, splatted wherever it lands). Splats are kept per image row and added in row order, so
// the image is the same bit for bit whatever the number of threads: (sum of passes) / passes.
struct Image {
    int width = 0, height = 0;
    std::vector<Vec3> pixels;
    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(size_t(w) * h) {}
    Vec3& at(int x, int y) { return pixels[size_t(y) * width + x]; }
    const Vec3& at(int x, int y) const { return pixels[size_t(y) * width + x]; }
};

inline double imageMean(const Image& img) {
    double s = 0;
    for (const Vec3& p : img.pixels) s += double(p.x) + p.y + p.z;
    return s / (3.0 * std::max<size_t>(1, img.pixels.size()));
}

// A render's time is CPU time, every thread's it uses: a machine busy with other work gives the
// same images for --time T, only later, and methods compare fairly (the wall clock would charge
// each for the others' load).
inline double threadCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}
inline thread_local double gWorkerCpuSeconds = 0;  // what the workers of this thread's parallelRows ran

// parallelRows: the rows shared out by an atomic counter; each worker's rays and CPU time added to the caller's.
template <class Body>
inline void parallelRows(int rows, int threads, const Body& body) {
    std::atomic<int> nextRow{0};
    std::atomic<bool> outOfMemory{false};
    std::vector<RayCount> traced(std::max(1, threads));
    std::vector<double> cpu(std::max(1, threads), 0.0);
    auto worker = [&](int i) {
        RayCount before = gRaysTraced;
        const double cpuBefore = i > 0 ? threadCpuSeconds() : 0;
        try {
            for (int y; (y = nextRow.fetch_add(1)) < rows;) body(y);
        } catch (const std::bad_alloc&) {  // thrown on, by the calling thread, once all have stopped
            outOfMemory = true;
            nextRow = rows;
        }
        traced[i] = {gRaysTraced.closest - before.closest, gRaysTraced.shadow - before.shadow};
        if (i > 0) cpu[i] = threadCpuSeconds() - cpuBefore + gWorkerCpuSeconds;  // and its own workers'
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker, i);
    worker(0);
    for (std::thread& t : pool) t.join();
    for (int i = 1; i < threads; ++i) gRaysTraced.closest += traced[i].closest, gRaysTraced.shadow += traced[i].shadow;
    for (int i = 1; i < threads; ++i) gWorkerCpuSeconds += cpu[i];
    if (outOfMemory) throw std::bad_alloc();
}

// What the methods prepare per pass and keep (vcm's buffers, the chains); after a render, their last pass's.
struct PassStorage {
    std::vector<Vpl> vpls;
    VcmPass vcm;
    MetropolisPass metropolis;
};

// Per-strategy images (--strategies): strategy (s,t) of path length k = s+t-1 <= maxLength, rows
// by k and s = 0..k within a row (the slides' pyramid), then (vcm) one image per path length of
// all its merges. Each comes twice: unweighted and MIS-weighted.
struct StrategyImages {
    int maxLength = 0;
    bool merges = false;       // vcm: one image of all merges of each path length
    std::vector<Image> images; // [2 index + weighted], index(s, t) or mergeIndex(k)
    StrategyImages() = default;
    explicit StrategyImages(const RenderOptions& opt)
        : maxLength(opt.method == Method::BDPT || opt.method == Method::VCM ? opt.strategyMaxLength : 0), merges(opt.method == Method::VCM) {}
    static int index(int s, int t) { return (s + t - 1) * (s + t) / 2 - 1 + s; }
    int mergeIndex(int k) const { return maxLength * (maxLength + 3) / 2 + k - 1; }
    int count() const { return merges ? mergeIndex(maxLength + 1) : maxLength * (maxLength + 3) / 2; }
    int of(const StrategySplat& c) const { return c.merge ? mergeIndex(c.s + c.t - 1) : index(c.s, c.t); }
    const Image& at(int s, int t, bool weighted) const { return images[2 * size_t(index(s, t)) + weighted]; }
    const Image& merged(int k, bool weighted) const { return images[2 * size_t(mergeIndex(k)) + weighted]; }
    // fn(k, s, image index) row by row: s = 0..k the strategies of length k, s = k + 1 its merges.
    template <class Fn>
    void forEach(const Fn& fn) const {
        for (int k = 1; k <= maxLength; ++k)
            for (int s = 0; s <= k + merges; ++s) {
                bool merge = s == k + 1;
                if (merge && k == 1) continue;  // a merge needs a vertex between the light and the camera
                fn(k, s, merge ? mergeIndex(k) : index(s, k + 1 - s));
            }
    }
};

struct RenderResult {
    Image image;                    // mean over passes
    Image variance;                 // per pixel and channel: variance of that mean (from the passes)
    int passes = 0;
    long long nonFinite = 0;        // NaN/inf samples and splats dropped
    double seconds = 0;             // wall-clock seconds
    double cpuSeconds = 0;          // CPU seconds, all the render's threads together (--time's budget)
    double energyUnclamped = 0, energyClamped = 0;  // ir --clamp: the energy gathered, before and after
    double clampRemoved() const { return energyUnclamped > 0 ? 1 - energyClamped / energyUnclamped : 0; }
    StrategyImages strategies;      // --strategies
    RayCount rays;                  // all threads, all passes (ir's VPL paths included)
    PassStorage method;             // what the method's last pass left
};

inline double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

inline PassData preparePass(const Scene& scene, const SampleOptions& opt, int pass, int threads, PassStorage& storage) {
    PassData data;
    data.pass = pass;
    switch (opt.method) {
        case Method::IR:
            storage.vpls = traceVpls(scene, opt, pass);
            data.vpls = &storage.vpls;
            break;
        case Method::VCM:
            traceVcmLightPass(scene, opt, pass, threads, storage.vcm);
            data.vcm = &storage.vcm;
            break;
        case Method::PSSMLT: case Method::MMLT: case Method::MLT:
            if (opt.method == Method::MLT) tracePathPass(scene, opt, pass, threads, storage.metropolis);
            else tracePrimarySamplePass(scene, opt, pass, threads, storage.metropolis);
            storage.metropolis.shortPaths = shortPathOptions(opt);
            data.metropolis = &storage.metropolis;
            break;
        case Method::PT: case Method::NEE: case Method::LT: case Method::BDPT: break;  // nothing before the pixels
    }
    return data;
}

// Each method's sampleXX, all of the one shape section 7's banner gives.
using SampleFunction = Vec3 (*)(const Scene&, const SampleOptions&, const PassData&, int x, int y, Rng&, RowOutput&);
inline SampleFunction sampleFunction(Method m) {
    switch (m) {
        case Method::PT: return samplePT;
        case Method::NEE: return sampleNEE;
        case Method::LT: return sampleLT;
        case Method::IR: return sampleIR;
        case Method::BDPT: return sampleBDPT;
        case Method::VCM: return sampleVCM;
        case Method::PSSMLT: case Method::MMLT: case Method::MLT: return sampleMLT;
    }
    return nullptr;  // not reached: every method has its case (-Wswitch checks)
}

// The film: per pixel the sums of the passes and their squares (image, variance), and the strategy images'.
struct Film {
    int width, height;
    StrategyImages strategies;  // their layout (the images come with finish())
    std::vector<double> sum, sumSq;
    std::vector<std::vector<double>> strategySum;
    Film(int w, int h, const RenderOptions& opt)
        : width(w), height(h), strategies(opt), sum(3 * size_t(w) * h, 0.0), sumSq(sum.size(), 0.0),
          strategySum(2 * strategies.count(), std::vector<double>(sum.size(), 0.0)) {}
    void addStrategy(int image, int pixel, Vec3 value) {
        if (isFinite(value))
            for (int c = 0; c < 3; ++c) strategySum[image][3 * size_t(pixel) + c] += value[c];
    }
    // A pass: the pixels' samples in `pass`, the splats added in row order. Returns the pass's mean.
    void addPass(std::vector<Vec3>& pass, const std::vector<RowOutput>& rows, RenderResult& result) {
        for (const RowOutput& row : rows) {
            result.nonFinite += row.nonFinite;
            result.energyUnclamped += row.energyUnclamped;
            result.energyClamped += row.energyClamped;
            for (const Splat& s : row.splats) {
                if (isFinite(s.value)) pass[s.pixel] += s.value;
                else ++result.nonFinite;
            }
            for (const StrategySplat& s : row.strategySplats) {
                int image = strategies.of(s);
                addStrategy(2 * image, s.pixel, s.value);
                addStrategy(2 * image + 1, s.pixel, s.value * s.weight);
            }
        }
        for (size_t i = 0; i < pass.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                sum[3 * i + c] += pass[i][c];
                sumSq[3 * i + c] += double(pass[i][c]) * pass[i][c];
            }
    }
    // The image (mean over n passes), its variance, and the strategy images.
    void finish(int n, RenderResult& result) const {
        result.image = result.variance = Image(width, height);
        result.strategies = strategies;
        for (const std::vector<double>& s : strategySum) {
            Image img(width, height);
            for (size_t i = 0; i < img.pixels.size(); ++i)
                for (int c = 0; c < 3; ++c) img.pixels[i][c] = float(s[3 * i + c] / n);
            result.strategies.images.push_back(img);
        }
        for (size_t i = 0; i < result.image.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                double mean = sum[3 * i + c] / n;
                result.image.pixels[i][c] = float(mean);
                result.variance.pixels[i][c] = n > 1 ? float(std::max(0.0, sumSq[3 * i + c] / n - mean * mean) / (n - 1)) : 0.0f;
            }
    }
};

// A render in progress, pass by pass: addPass() renders the next pass and adds it to the film;
// `pass` then holds that pass's image. render() below runs as many passes as the options ask;
// classroom/'s tools run them one at a time and look at each (a live image, the error so far).
struct Rendering {
    const Scene& scene;
    const RenderOptions opt;
    const int threads;
    Film film;
    PassStorage storage;
    std::vector<Vec3> pass;
    std::vector<RowOutput> rows;
    RenderResult result;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    std::atomic<int> rowsDone{0};  // of the pass in flight (classroom/'s progress bar reads it)
    PassData passData;             // the pass in flight's light paths, VPLs or chains,
    RayCount raysBefore;           // and what was counted before it (parallelRows adds the other
    double cpuBefore = 0;          // threads' rays and CPU time to this one's)
    Rendering(const Scene& s, const RenderOptions& o)
        : scene(s), opt(o), threads(o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()))),
          film(s.camera.width, s.camera.height, o), pass(size_t(s.camera.width) * s.camera.height), rows(s.camera.height) {}

    // The slides' estimator for one pass: every pixel's sample, then the splats, then the film.
    void addPass() {
        beginPass();
        parallelRows(scene.camera.height, threads, [&](int y) { renderRow(y); });
        endPass();
    }
    // The same pass in three steps, for a caller that shows a pass's rows as they come (the page).
    void beginPass() {
        raysBefore = gRaysTraced;
        cpuBefore = threadCpuSeconds() + gWorkerCpuSeconds;
        rowsDone = 0;
        passData = preparePass(scene, opt, result.passes, threads, storage);
    }
    void renderRow(int y) {
        const int W = scene.camera.width, p = result.passes;
        const SampleFunction sample = sampleFunction(opt.method);
        RowOutput& row = rows[y];
        row.splats.clear();
        row.strategySplats.clear();
        row.strategyMaxLength = opt.strategyMaxLength;
        row.nonFinite = 0;
        row.energyUnclamped = row.energyClamped = 0;
        for (int x = 0; x < W; ++x) {
            Rng rng = sampleRng(opt, kCameraStream, uint64_t(y) * W + x, uint64_t(p));
            Vec3 v = sample(scene, opt, passData, x, y, rng, row);
            if (!isFinite(v)) { v = Vec3(0); ++row.nonFinite; }
            pass[size_t(y) * W + x] = v;
        }
        rowsDone.fetch_add(1, std::memory_order_relaxed);
    }
    void endPass() {
        result.rays.closest += gRaysTraced.closest - raysBefore.closest;
        result.rays.shadow += gRaysTraced.shadow - raysBefore.shadow;
        film.addPass(pass, rows, result);
        result.passes += 1;
        result.cpuSeconds += threadCpuSeconds() + gWorkerCpuSeconds - cpuBefore;
    }
    RenderResult finish() {
        result.seconds = secondsSince(start);
        film.finish(result.passes, result);
        result.method = std::move(storage);
        return std::move(result);
    }
};

// Passes until --spp of them are done, or until --time's CPU seconds (--wall-time's) are spent (at least one).
inline bool morePasses(const Rendering& r) {
    if (!(r.opt.seconds > 0)) return r.result.passes < r.opt.spp;
    return (r.opt.wallTime ? secondsSince(r.start) : r.result.cpuSeconds) < r.opt.seconds;
}
inline RenderResult render(const Scene& scene, const RenderOptions& opt) {
    Rendering r(scene, opt);
    do r.addPass();
    while (morePasses(r));
    return r.finish();
}

// The folder a file goes into, made if missing (mkdir -p): false if some part of it cannot be.
inline std::string folderOf(const std::string& path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
}
inline bool makeFolders(const std::string& path) {
    for (size_t i = 1; i <= path.size(); ++i) {
        if (i < path.size() && path[i] != '/') continue;
        std::string part = path.substr(0, i);
        struct stat st;
        if (stat(part.c_str(), &st) == 0 ? !S_ISDIR(st.st_mode) : mkdir(part.c_str(), 0777) != 0) return false;
    }
    return true;
}
// Files appear whole or not at all: written under a temporary name, then renamed.
inline std::string tempName(const std::string& path) { return path + ".tmp" + std::to_string(getpid()); }
inline bool commitFile(const std::string& tmp, const std::string& path, bool ok) {
    bool done = ok && std::rename(tmp.c_str(), path.c_str()) == 0;
    if (!done) std::remove(tmp.c_str());
    return done;
}

// PFM: linear floats, little-endian (scale -1), rows from the bottom up.
inline bool writePFM(const Image& img, const std::string& path) {
    std::string tmp = tempName(path);
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) return false;
    bool ok = std::fprintf(f, "PF\n%d %d\n-1.0\n", img.width, img.height) > 0;
    for (int y = img.height - 1; y >= 0 && ok; --y)
        ok = std::fwrite(&img.at(0, y), sizeof(Vec3), img.width, f) == size_t(img.width);
    ok = (std::fclose(f) == 0) && ok;
    return commitFile(tmp, path, ok);
}

// And back: false for a file that is not a whole PFM of this kind (a reference, a test's output).
inline bool readPFM(const std::string& path, Image& img) {
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return false;
    char magic[3] = {0};
    int w = 0, h = 0;
    float scale = 0;
    bool ok = std::fscanf(f, "%2s %d %d %f", magic, &w, &h, &scale) == 4 && std::string(magic) == "PF" && w > 0 && h > 0 &&
              w <= 16384 && h <= 16384 && scale < 0 && std::fgetc(f) != EOF;
    if (ok) {
        img = Image(w, h);
        for (int y = h - 1; y >= 0 && ok; --y) ok = std::fread(&img.at(0, y), sizeof(Vec3), size_t(w), f) == size_t(w);
    }
    std::fclose(f);
    return ok;
}

// PNG: sRGB bytes of the image scaled by 2^exposure.
inline unsigned char toSRGB8(float linear) {
    float v = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1 / 2.4f) - 0.055f;
    return (unsigned char)(std::min(1.0f, std::max(0.0f, v)) * 255.0f + 0.5f);
}
inline std::vector<unsigned char> toSRGBBytes(const Image& img, float exposure) {
    std::vector<unsigned char> bytes(img.pixels.size() * 3);
    float scale = std::exp2(exposure);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) bytes[3 * i + c] = toSRGB8(img.pixels[i][c] * scale);
    return bytes;
}
inline bool writePNGBytes(const std::vector<unsigned char>& bytes, int width, int height, const std::string& path) {
    std::string tmp = tempName(path);
    bool ok = stbi_write_png(tmp.c_str(), width, height, 3, bytes.data(), width * 3) != 0;
    return commitFile(tmp, path, ok);
}
inline bool writePNG(const Image& img, const std::string& path, float exposure) {
    return writePNGBytes(toSRGBBytes(img, exposure), img.width, img.height, path);
}

inline bool hasExtension(const std::string& path, const std::string& ext) {  // case-insensitive
    if (path.size() <= ext.size() || path[path.size() - ext.size() - 1] == '/') return false;
    for (size_t i = 0; i < ext.size(); ++i)
        if (std::tolower((unsigned char)path[path.size() - ext.size() + i]) != ext[i]) return false;
    return true;
}
inline std::string replaceExtension(const std::string& path, const std::string& ext) {
    size_t slash = path.find_last_of('/'), dot = path.find_last_of('.');
    bool hasExt = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    return (hasExt ? path.substr(0, dot) : path) + ext;
}

// The slides' "contributions of different paths", one file per strategy: dir/s1_t3_weighted.png
// (and .pfm), and for vcm dir/merge_k3_weighted.png.
inline bool writeStrategyImages(const StrategyImages& strategies, const std::string& dir, float exposure) {
    bool ok = true;
    for (int weighted = 0; weighted < 2; ++weighted)
        strategies.forEach([&](int k, int s, int index) {
            std::string name = dir + (s == k + 1 ? "/merge_k" + std::to_string(k) : "/s" + std::to_string(s) + "_t" + std::to_string(k + 1 - s)) +
                               (weighted ? "_weighted" : "_unweighted");
            const Image& img = strategies.images[2 * size_t(index) + weighted];
            ok = ok && writePNG(img, name + ".png", exposure) && writePFM(img, name + ".pfm");
        });
    return ok;
}

// == 10. Scene file ============================================================================
// One directive per line, '#' starts a comment; the README documents each one with an example.
//   camera     ex ey ez  lx ly lz  ux uy uz  fov  width height
//   material   NAME diffuse R G B | mirror R G B | glass IOR | glossy R G B EXPONENT
//   sphere     cx cy cz  radius  MATERIAL  [emit R G B] [inside] [bump AMPLITUDE FREQUENCY]
//   quad       qx qy qz  ux uy uz  vx vy vz  MATERIAL  [emit R G B] [bump AMPLITUDE FREQUENCY] [tilt DEGREES]
//   pointlight x y z  R G B
//   exposure   STOPS   (the PNG's default brightness, 2^STOPS; --exposure overrides it)
// Every mistake is reported as "file:line: message" and the program exits with status 2.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

inline std::string printable(const std::string& s) {  // binary garbage must not reach the terminal
    std::string out;
    for (char c : s.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
    return s.size() > 40 ? out + "..." : out;
}

// The distance of two short words: how many letters to add, drop or change, or neighbours to swap
// ("bpdt" is one swap from "bdpt"; Damerau's optimal string alignment).
inline size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i)
        for (size_t j = 0; j <= b.size(); ++j) {
            if (i == 0 || j == 0) { d[i][j] = i + j; continue; }
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}
// The known words closest to a misspelt one, if within a quarter of its letters or two, each in
// quotes, joined as "a or b" (which of two equally close words was meant, only the writer knows);
// "" if none is that close.
inline std::string closestWords(const std::string& word, const std::vector<std::string>& known, const std::string& quote = "") {
    auto lower = [](std::string s) {
        for (char& c : s) c = char(std::tolower((unsigned char)c));
        return s;
    };
    std::vector<std::string> best;
    size_t bestDistance = std::max<size_t>(2, word.size() / 4) + 1;  // past the limit: nothing
    for (const std::string& k : known) {  // BDPT is bdpt: capitals cost nothing
        size_t d = editDistance(lower(word), lower(k));
        if (d < bestDistance) best = {k}, bestDistance = d;
        else if (d == bestDistance && !best.empty() && std::find(best.begin(), best.end(), k) == best.end()) best.push_back(k);
    }
    std::sort(best.begin(), best.end());
    std::string words;
    for (size_t i = 0; i < best.size(); ++i)
        words += (i == 0 ? "" : i + 1 == best.size() ? " or " : ", ") + quote + best[i] + quote;
    return words;
}

struct SceneParser {
    std::string file;
    int line = 0;
    std::vector<std::string> tok;
    size_t next = 0;
    Scene scene;
    std::map<std::string, int> materialIndex;
    bool haveCamera = false;

    [[noreturn]] void fail(const std::string& message) const {
        throw InputError(file + ":" + std::to_string(line) + ": " + message);
    }
    bool more() const { return next < tok.size(); }
    std::string word(const char* what) {
        if (!more()) fail(std::string("missing ") + what + " in '" + tok[0] + "'");
        return tok[next++];
    }
    float number(const char* what) {
        std::string t = word(what);
        char* end = nullptr;
        errno = 0;
        double v = std::strtod(t.c_str(), &end);
        if (end == t.c_str() || *end != 0 || t.find_first_not_of("0123456789+-.eE") != std::string::npos)  // decimal only
            fail(std::string("malformed number '") + printable(t) + "' for " + what);
        if (errno == ERANGE || !(std::fabs(v) <= 1e30))  // checked before the cast to float (UB if too large)
            fail(std::string("number out of range '") + printable(t) + "' for " + what);
        return float(v);
    }
    Vec3 vec3(const char* what) {
        float x = number(what), y = number(what), z = number(what);
        return {x, y, z};
    }
    Vec3 colour(const char* what, bool atMostOne) {
        Vec3 c = vec3(what);
        for (int i = 0; i < 3; ++i)
            if (c[i] < 0 || (atMostOne && c[i] > 1)) {
                std::ostringstream got;
                got << c[i];
                fail(std::string(what) + (atMostOne ? " must lie in [0,1]" : " must be >= 0") + ", got " + got.str());
            }
        return c;
    }
    int integer(const char* what, int lo, int hi) {
        float v = number(what);
        if (v != std::floor(v) || v < lo || v > hi)
            fail(std::string(what) + " must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
        return int(v);
    }
    void done() {
        if (more()) fail("unexpected '" + printable(tok[next]) + "' after '" + tok[0] + "' (too many values?)");
    }

    void parseCamera() {
        if (haveCamera) fail("second camera (one per scene)");
        Camera& c = scene.camera;
        c.eye = vec3("camera position");
        Vec3 lookAt = vec3("camera look-at point"), up = vec3("camera up vector");
        c.fovDegrees = number("camera field of view");
        c.width = integer("image width", 1, 16384);
        c.height = integer("image height", 1, 16384);
        done();
        if (!(c.fovDegrees > 0 && c.fovDegrees < 180)) fail("field of view must lie in (0, 180) degrees");
        if (length(lookAt - c.eye) == 0) fail("camera look-at point equals its position");
        c.forward = normalize(lookAt - c.eye);
        Vec3 right = cross(c.forward, up);
        if (!(length(right) > 1e-6f * length(up))) fail("camera up vector is zero or parallel to the view direction");
        c.right = normalize(right);
        c.up = cross(c.right, c.forward);
        c.tanHalfFov = std::tan(c.fovDegrees * kPi / 360);
        c.aspect = float(c.width) / c.height;
        c.imageArea = 4 * sqr(c.tanHalfFov) * c.aspect;
        if (double(c.width) * c.height > 64e6) fail("image larger than 64 megapixels");
        haveCamera = true;
    }
    void parseMaterial() {
        Material m;
        m.name = word("material name");
        std::string type = word("material type");
        if (type == "diffuse" || type == "mirror" || type == "glossy") {
            m.type = type == "diffuse" ? Material::Diffuse : type == "mirror" ? Material::Mirror : Material::Glossy;
            m.albedo = colour(type == "mirror" ? "reflectance" : "albedo", true);
            if (type == "glossy") {
                m.exponent = number("glossy exponent");
                if (m.exponent < 0 || m.exponent > 1e5f) fail("glossy exponent must lie in [0, 100000]");
            }
        } else if (type == "glass") {
            m.type = Material::Glass;
            m.ior = number("index of refraction");
            if (!(m.ior > 0)) fail("index of refraction must be > 0");
        } else {
            fail("unknown material type '" + printable(type) + "' (diffuse, mirror, glass, glossy)");
        }
        done();
        if (materialIndex.count(m.name)) fail("duplicate material name '" + printable(m.name) + "'");
        materialIndex[m.name] = int(scene.materials.size());
        scene.materials.push_back(m);
    }
    void parseShapeOptions(Shape& s) {  // the optional words after the material name
        std::string name = word("material name");
        auto it = materialIndex.find(name);
        if (it == materialIndex.end()) {
            std::vector<std::string> known;
            for (const auto& m : materialIndex) known.push_back(m.first);
            std::string near = closestWords(name, known, "'");
            fail("unknown material '" + printable(name) + "' (" + (near.empty() ? "define it first" : "did you mean " + near + "?") + ")");
        }
        s.material = it->second;
        while (more()) {
            std::string opt = word("option");
            if (opt == "emit") {
                s.emission = colour("emitted radiance", false);
            } else if (opt == "inside" && s.type == Shape::Sphere) {
                s.side = -1;
            } else if (opt == "bump") {
                s.bumpAmplitude = number("bump amplitude");
                s.bumpFrequency = number("bump frequency");
                if (s.bumpAmplitude < 0 || s.bumpAmplitude > 10) fail("bump amplitude must lie in [0, 10]");
                if (!(s.bumpFrequency > 0)) fail("bump frequency must be > 0");
                if (s.shading == Shape::ShadingNormal::Tilt) fail("tilt and bump both given: a quad has one shading normal");
                if (s.bumpAmplitude > 0) s.shading = Shape::ShadingNormal::Bump;
            } else if (opt == "tilt" && s.type == Shape::Quad) {
                float degrees = number("tilt angle (degrees)");
                if (!(degrees > -90 && degrees < 90)) fail("tilt angle must lie between -90 and 90 degrees");
                float a = degrees * kPi / 180;
                if (s.shading == Shape::ShadingNormal::Bump) fail("tilt and bump both given: a quad has one shading normal");
                s.shading = Shape::ShadingNormal::Tilt;
                s.tiltedNormal = normalize(std::cos(a) * s.normal + std::sin(a) * normalize(s.u));
            } else {
                fail("unknown option '" + printable(opt) + "' (emit, bump" +
                     (s.type == Shape::Sphere ? ", inside)" : ", tilt)"));
            }
        }
    }
    void parseSphere() {
        Shape s;
        s.type = Shape::Sphere;
        s.line = line;
        s.p = vec3("sphere centre");
        s.radius = number("sphere radius");
        if (!(s.radius > 0)) fail("sphere radius must be > 0");
        s.area = 4 * kPi * s.radius * s.radius;
        parseShapeOptions(s);
        scene.shapes.push_back(s);
    }
    void parseQuad() {
        Shape s;
        s.type = Shape::Quad;
        s.line = line;
        s.p = vec3("quad corner");
        s.u = vec3("quad edge u");
        s.v = vec3("quad edge v");
        Vec3 n = cross(s.u, s.v);
        s.area = length(n);
        if (!(s.area > 0) || !std::isfinite(s.area)) fail("quad has zero area (edges u and v parallel or zero)");
        s.normal = n / s.area;
        parseShapeOptions(s);
        scene.shapes.push_back(s);
    }
    void parsePointLight() {
        Light l;
        l.type = Light::Point;
        l.line = line;
        l.position = vec3("light position");
        l.intensity = colour("intensity", false);
        done();
        scene.lights.push_back(l);
    }

    void parseLine(const std::string& text) {
        std::string content = text.substr(0, text.find('#'));
        std::istringstream in(content);
        tok.clear();
        next = 1;
        for (std::string t; in >> t;) tok.push_back(t);
        if (tok.empty()) return;
        const std::string& d = tok[0];
        if (d == "camera") parseCamera();
        else if (d == "material") parseMaterial();
        else if (d == "sphere") parseSphere();
        else if (d == "quad") parseQuad();
        else if (d == "pointlight") parsePointLight();
        else if (d == "exposure") {
            scene.exposure = number("exposure");
            done();
            if (!(std::fabs(scene.exposure) <= 50)) fail("exposure must lie in [-50, 50] stops");
        }
        else fail("unknown directive '" + printable(d) + "' (camera, material, sphere, quad, pointlight, exposure)");
    }

    void finish() {  // after the last line: what the scene as a whole must have
        if (!haveCamera) fail("no camera (add: camera ex ey ez lx ly lz ux uy uz fov width height)");
        for (size_t i = 0; i < scene.shapes.size(); ++i) {
            if (isBlack(scene.shapes[i].emission)) continue;
            Light l;
            l.shape = int(i);
            l.line = scene.shapes[i].line;
            scene.shapes[i].light = int(scene.lights.size());
            scene.lights.push_back(l);
        }
        for (Light& l : scene.lights) {
            l.power = lightPower(l, scene.shapes);
            scene.totalPower += l.power;
        }
        if (!(scene.totalPower > 0)) fail("no light (add a pointlight, or 'emit R G B' to a sphere or quad)");
        float sum = 0;
        for (const Light& l : scene.lights) scene.lightCdf.push_back((sum += l.power) / scene.totalPower);
        scene.file = file;
    }
};

// Line endings of any system ("\r\n", a lone '\r') end a line like '\n'; a UTF-8 byte-order mark is skipped.
inline Scene parseScene(const std::string& text, const std::string& fileName) {
    SceneParser parser;
    parser.file = fileName;
    std::string unified;
    unified.reserve(text.size());
    for (size_t i = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0; i < text.size(); ++i) {
        if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') continue;
        unified += text[i] == '\r' ? '\n' : text[i];
    }
    std::istringstream in(unified);
    for (std::string l; std::getline(in, l);) {
        ++parser.line;
        parser.parseLine(l);
    }
    parser.finish();
    buildAcceleration(parser.scene);
    return parser.scene;
}

inline Scene loadScene(const std::string& path) {
    struct stat st;
    if (stat(path.c_str(), &st) != 0) throw InputError(path + ": cannot open the scene file: " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw InputError(path + ": is a folder, not a scene file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open the scene file: " + std::strerror(errno));
    std::stringstream buffer;
    buffer << in.rdbuf();
    std::string text = buffer.str();
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        throw InputError(path + ": the file is empty (a scene needs at least a camera and a light: README, scene format)");
    return parseScene(text, path);
}

// == 11. Command line ==========================================================================
// One table of options drives parsing, the refusal of an option the method would ignore, and
// --help. classroom/ adds its tools' rows (side by side, live images, references, figures).
constexpr const char* kMethodNames[] = {"pt", "nee", "lt", "ir", "bdpt", "vcm", "pssmlt", "mmlt", "mlt"};  // in Method's order
constexpr const char* kHeuristicNames[] = {"balance", "power", "max", "uniform"};                   // in Heuristic's order
constexpr const char* kRouletteNames[] = {"throughput", "albedo", "off"};                           // in Roulette's order
constexpr const char* kSamplerNames[] = {"sobol", "random"};                                         // in Sampler's order
inline const char* methodName(Method m) { return kMethodNames[int(m)]; }
// Each method's slide: the caption of its panel of "Results from Different Techniques", or of the
// later method's slide; what it does; the notes' pages. --help, ./bdpt's side-by-side figures and
// the page all read this one table (in Method's order).
struct MethodCaption {
    const char *caption, *what, *pages;
};
constexpr MethodCaption kMethodCaptions[] = {
    {"(a) Unidirectional (eye tracing)", "emission counted only when a path hits a light", "1"},
    {"(b) Unidirectional + next event", "at every diffuse hit a shadow ray to a point on a light", "2"},
    {"(c) Next event (light tracing)", "light paths, each vertex joined to the camera and splatted; no mirror or glass seen", "2"},
    {"(d) Instant radiosity", "camera paths gather the virtual point lights light paths left", "1"},
    {"(f) Bidirectional path tracing", "every (s,t) strategy of a path, weighted by MIS (the default method)", "3-11"},
    {"Vertex Connection and Merging (VCM, later)", "bdpt's connections plus merges of a camera vertex with nearby light vertices: the SDS paths of (f)", "15"},
    {"Metropolis-Sampling (see later): pssmlt", "Kelemen's primary-sample-space MLT, chains that mutate the random numbers of bdpt's sample", "16"},
    {"Metropolis-Sampling (see later): mmlt", "multiplexed MLT (pbrt's), pssmlt whose state also picks one path length and one strategy (s,t)", "16"},
    {"Metropolis-Sampling (see later): Veach's mlt", "Markov chains of paths, mutated by replacing a few vertices or moving them a little; --spp N: N mutations per pixel", "17"},
};
// --method's help, from the table: a method's line, wrapped at 58 characters under its name.
inline const char* methodHelp() {
    static const std::string text = [] {
        std::string all;
        for (int m = 0; m < int(std::size(kMethodNames)); ++m) {
            const MethodCaption& c = kMethodCaptions[m];
            const bool colon = std::string(c.caption).find(':') != std::string::npos;
            std::string words = std::string(c.caption) + (colon ? ", " : ": ") + c.what, line = kMethodNames[m];
            line.resize(std::max<size_t>(line.size() + 1, 5), ' ');
            for (size_t at = 0, next; at < words.size(); at = next + 1) {
                next = std::min(words.find(' ', at), words.size());
                if (line.size() + (next - at) > 58 && line.find_first_not_of(' ') < line.size() - 1)
                    all += line.substr(0, line.size() - 1) + "\n", line = "     ";
                line += words.substr(at, next - at) + " ";
            }
            all += line.substr(0, line.size() - 1) + (m + 1 < int(std::size(kMethodNames)) ? "\n" : "");
        }
        return all;
    }();
    return text.c_str();
}

struct CommandLine {
    std::string scenePath, out = "render.png";
    RenderOptions opt;
    Conventions conventions;     // the deliberate mistakes, given to the scene once it is loaded
    int width = 0, height = 0;   // --res; 0: the scene's
    int strategyLength = 5;
    std::string strategiesDir;
    float exposure = 0;          // stops, for the PNG only; the scene's exposure directive unless given
    bool exposureGiven = false, quiet = false, help = false;
    std::set<std::string> given; // the options on the line
};

// The words after the scene, read one option at a time. Every mistake ends in "(see --help)".
struct ArgReader {
    const std::vector<std::string>& args;
    size_t i = 0;
    [[noreturn]] static void fail(const std::string& m) { throw InputError("bdpt: " + m + " (see --help)"); }
    std::string value() {
        if (i + 1 >= args.size()) fail("option " + args[i] + " needs a value");
        return args[++i];
    }
    double number(double lo, double hi) {
        std::string name = args[i], v = value();
        char* end = nullptr, range[64];
        double x = std::strtod(v.c_str(), &end);
        std::snprintf(range, sizeof range, "a number from %g to %g", lo, hi);
        if (end == v.c_str() || *end != 0 || !std::isfinite(x) || x < lo || x > hi)
            fail("option " + name + " needs " + range + ", got '" + printable(v) + "'");
        return x;
    }
    long long integer(double lo, double hi) {
        std::string name = args[i];
        double x = number(lo, hi);
        if (x != std::floor(x)) fail("option " + name + " needs a whole number, got '" + printable(args[i]) + "'");
        return (long long)x;
    }
    template <class E, size_t N>
    E choice(const char* what, const char* const (&names)[N]) {  // one of names, as the enum E in the same order
        std::string v = value(), list;
        for (size_t k = 0; k < N; ++k) {
            if (v == names[k]) return E(k);
            list += (k ? ", " : "") + std::string(names[k]);
        }
        std::string near = closestWords(v, std::vector<std::string>(names, names + N));
        fail(std::string("unknown ") + what + " '" + printable(v) + "' (" + (near.empty() ? list : "did you mean " + near + "? " + list) + ")");
    }
    int mutationList() {  // --mutations: MutationBits, the bidirectional mutation among them
        std::string name = args[i], v = value(), word;
        int bits = 0;
        std::istringstream in(v);
        while (std::getline(in, word, ','))
            bits |= word == "bidir" ? kBidirectional : word == "lens" ? kLens : word == "caustic" ? kCaustic : word == "multichain" ? kMultiChain
                  : (fail("unknown mutation '" + printable(word) + "' in " + name + " (bidir, lens, caustic, multichain)"), 0);
        if (!(bits & kBidirectional)) fail(name + " needs bidir: only the bidirectional mutation changes a path's length or kind");
        return bits;
    }
};

// A row of the table: the option and its value, the methods it applies to (none listed: every
// method) and how a refusal names them, its help, and what it sets in a command line of type
// Line (classroom/'s extends CommandLine). A row without a name is a line of --help.
template <class Line>
struct OptionRow {
    const char* name;
    const char* value;
    std::vector<Method> methods;
    const char* whose;
    const char* help;
    std::function<void(Line&, ArgReader&)> apply;
};
// inline as kOptions, which copies them: its initialization is ordered only after inline ones (C++17)
inline const std::vector<Method> kBdptFamily = {Method::BDPT, Method::VCM, Method::PSSMLT, Method::MMLT, Method::MLT};
inline const std::vector<Method> kLightPathMethods = {Method::LT, Method::IR, Method::BDPT, Method::VCM, Method::PSSMLT, Method::MMLT, Method::MLT};
inline const std::vector<Method> kMetropolis = {Method::PSSMLT, Method::MMLT, Method::MLT};
inline const std::vector<Method> kPrimarySample = {Method::PSSMLT, Method::MMLT};
constexpr const char* kBdptFamilyName = "--method bdpt, vcm, mlt, pssmlt and mmlt";
constexpr const char* kLightPathName = "the methods that trace light paths (lt, ir, bdpt, vcm, mlt, pssmlt, mmlt)";
constexpr const char* kMetropolisName = "--method mlt, pssmlt and mmlt";
inline const std::vector<OptionRow<CommandLine>> kOptions = [] {
    using CL = CommandLine;  // the table's setters are short lambdas
    using A = ArgReader;
    return std::vector<OptionRow<CommandLine>>{
        {nullptr, "", {}, "", "usage: bdpt SCENE [options]\n"
         "Renders SCENE (see README: scene format) with one of the slides' methods; writes a PNG (sRGB)\n"
         "and, beside it, a PFM with the linear values. For example:\n"
         "  ./bdpt scenes/cornell.scene --method bdpt --spp 64 --out build/cornell.png\n\nMethod", nullptr},
        {"--method", "M", {}, "", methodHelp(),
         [](CL& cl, A& a) { cl.opt.method = a.choice<Method>("method", kMethodNames); }},
        {"--mis", "", {Method::NEE}, "--method nee", "nee: weight light and BSDF sampling with the power heuristic",
         [](CL& cl, A&) { cl.opt.mis = true; }},
        {"--vpls", "N", {Method::IR}, "--method ir", "ir: light paths traced per pass, each leaving VPLs (default 16)",
         [](CL& cl, A& a) { cl.opt.ir.vplPaths = int(a.integer(1, 1e6)); }},
        {"--clamp", "C", {Method::IR}, "--method ir", "ir: bound the geometry term G by C (panel (e)); prints the energy removed",
         [](CL& cl, A& a) { cl.opt.ir.clamp = float(a.number(1e-30, 1e30)); }},
        {"--heuristic", "H", kBdptFamily, kBdptFamilyName, "bdpt, vcm, and the Metropolis methods' bdpt samples: MIS weights balance\n"
         "(default), power, max (the slides' maximum heuristic) or uniform (1 /\nnumber of strategies able to make the path)",
         [](CL& cl, A& a) { cl.opt.heuristic = a.choice<Heuristic>("heuristic", kHeuristicNames); }},
        {"--radius", "R", {Method::VCM}, "--method vcm", "vcm: merging radius r_0 of the first pass (default: one pixel's footprint\n"
         "where the central camera ray meets the scene); 0: no merging, as bdpt.\n"
         "vcm keeps a pass's light subpaths, about 140 bytes per light vertex (the\n"
         "vertex, and a grid record if mergeable), 1 to 6 light vertices per pixel on\n"
         "the scenes",
         [](CL& cl, A& a) { cl.opt.vcm.radius = float(a.number(0, 1e30)); }},
        {"--alpha", "A", {Method::VCM}, "--method vcm", "vcm: radius schedule r(n) = r_0 n^((A-1)/2) in pass n, 0 < A <= 1\n(default 0.75)",
         [](CL& cl, A& a) { cl.opt.vcm.alpha = float(a.number(1e-3, 1)); }},
        {"--strategies", "DIR", {Method::BDPT, Method::VCM}, "--method bdpt and vcm", "bdpt, vcm: also write one image per strategy (s,t) up to --strategy-length\n"
         "(vcm: and one of all merges per path length), unweighted and MIS-weighted,\n"
         "into DIR",
         [](CL& cl, A& a) { cl.strategiesDir = a.value(); }},
        {"--strategy-length", "K", {Method::BDPT, Method::VCM}, "--method bdpt and vcm (with --strategies)",
         "longest path (segments) with per-strategy images (default 5)", [](CL& cl, A& a) { cl.strategyLength = int(a.integer(1, 12)); }},
        {"--large-step", "P", kPrimarySample, "--method pssmlt and mmlt", "pssmlt, mmlt: probability of a large step, every number drawn afresh (0.3)",
         [](CL& cl, A& a) { cl.opt.metropolis.largeStep = float(a.number(0, 1)); }},
        {"--sigma", "S", kPrimarySample, "--method pssmlt and mmlt", "pssmlt, mmlt: a small step moves each number by a normal of deviation S,\nwrapped into [0,1) (default 0.01)",
         [](CL& cl, A& a) { cl.opt.metropolis.sigma = float(a.number(1e-6, 10)); }},
        {"--bootstrap", "N", kMetropolis, kMetropolisName, "mlt, pssmlt, mmlt: independent samples that estimate the image's\n"
         "normalisation b and choose the chains' starts in proportion to their\n"
         "brightness (default 100000 for pssmlt, 200000 for mlt, 1000000 for mmlt,\nwhich spreads them over the path lengths)",
         [](CL& cl, A& a) { cl.opt.metropolis.bootstrap = int(a.integer(1, 1e8)); }},
        {"--chains", "N", kMetropolis, kMetropolisName, "mlt, pssmlt, mmlt: Markov chains, each its own random stream\n(default 1024 for mlt, 256 otherwise)",
         [](CL& cl, A& a) { cl.opt.metropolis.chains = int(a.integer(1, 1e6)); }},
        {"--mutations", "LIST", {Method::MLT}, "--method mlt", "mlt: Veach's mutations to use, among bidir, lens, caustic and multichain,\n"
         "comma-separated; bidir is always among them (default: all four)",
         [](CL& cl, A& a) { cl.opt.metropolis.mutations = a.mutationList(); }},
        {"--chain-short-paths", "", kMetropolis, kMetropolisName, "mlt, pssmlt, mmlt: the chains render paths of one and two segments too\n"
         "(by default a bdpt sample per pixel renders them, and the chains the rest)",
         [](CL& cl, A&) { cl.opt.metropolis.chainShortPaths = true; }},
        {"--maxdepth", "D", {}, "", "at most D bounces (scattering vertices) per path (default 32)",
         [](CL& cl, A& a) { cl.opt.maxDepth = int(a.integer(0, 10000)); }},
        {"--roulette", "R", kLightPathMethods, kLightPathName, "lt, ir, bdpt, vcm and the Metropolis methods' bdpt samples (mlt's and\n"
         "mmlt's own walks have chosen lengths): how subpaths end: throughput (q from\n"
         "the throughput after --rr-start bounces, as pt and nee), albedo (q = the\n"
         "material's albedo at every vertex, counted in bdpt's MIS densities) or off\n"
         "(only --maxdepth); default albedo",
         [](CL& cl, A& a) { cl.opt.roulette = a.choice<Roulette>("roulette", kRouletteNames); }},
        {"--rr-start", "N", {}, "", "pt, nee (and --roulette throughput): Russian roulette from bounce N on\n"
         "(default 3); N > --maxdepth turns it off (lecture notes, page 9)",
         [](CL& cl, A& a) { cl.opt.rrStart = int(a.integer(0, 10001)); }},
        {nullptr, "", {}, "", "Deliberate mistakes (slides: \"Non-symmetric scattering\")", nullptr},
        {"--symmetric-refraction", "", {}, "", "swap the two refraction rules: eye paths scale refracted radiance\n"
         "like power (no eta^2), light paths scale power like radiance (eta^2)",
         [](CL& cl, A&) { cl.conventions.symmetricRefraction = true; }},
        {"--no-adjoint-correction", "", kLightPathMethods, kLightPathName, "light paths use the shading-normal BSDF unchanged (not its adjoint)",
         [](CL& cl, A&) { cl.conventions.noAdjointCorrection = true; }},
        {"--fixed-ray-offset", "", {}, "", "push new rays off surfaces by the rule of thumb 5e-5 (1 + max|p|)\n"
         "instead of the hit point's error bound (see tests/thin-gap.scene)",
         [](CL& cl, A&) { cl.conventions.fixedRayOffset = true; }},
        {"--delta-density-one", "", kBdptFamily, kBdptFamilyName, "bdpt, vcm, Metropolis: after a mirror or glass, store the MIS densities\n"
         "as 1 (pbrt's convention) instead of the true ones: caustics go to the noisy\ns = 0",
         [](CL& cl, A&) { cl.conventions.deltaDensityOne = true; }},
        {"--fixed-start", "", kMetropolis, kMetropolisName, "mlt, pssmlt, mmlt: every chain starts from one fixed state (the first bootstrap\n"
         "sample that carries light) instead of one chosen in proportion to its\n"
         "brightness: start-up bias, visible at short runs",
         [](CL& cl, A&) { cl.opt.metropolis.fixedStart = true; }},
        {"--no-scramble", "", {}, "", "--sampler sobol without its random scrambles: every pixel draws the same\n"
         "point in each pass, so neighbouring pixels' film positions, bounces and\n"
         "lamp points move together (a biased, patterned image)",
         [](CL& cl, A&) { cl.opt.noScramble = true; }},
        {nullptr, "", {}, "", "Sampling", nullptr},
        {"--spp", "N", {}, "", "N passes of one sample per pixel (default 16)", [](CL& cl, A& a) { cl.opt.spp = int(a.integer(1, 1e8)); }},
        {"--time", "SECONDS", {}, "", "render passes until SECONDS of CPU time are spent, all threads together\n"
         "(replaces --spp): a busy machine gives the same image, later; two threads\n"
         "finish in about half as many wall seconds",
         [](CL& cl, A& a) { cl.opt.seconds = a.number(1e-3, 1e7); }},
        {"--wall-time", "SECONDS", {}, "", "render passes until SECONDS of wall-clock time have passed (replaces --spp)",
         [](CL& cl, A& a) { cl.opt.seconds = a.number(1e-3, 1e7), cl.opt.wallTime = true; }},
        {"--sampler", "S", {}, "", "where each pixel sample's numbers come from: sobol (default), the points\n"
         "of an Owen-scrambled Sobol sequence in its first 32 dimensions (PCG32\n"
         "past them), or random (independent PCG32 numbers throughout)",
         [](CL& cl, A& a) { cl.opt.sampler = a.choice<Sampler>("sampler", kSamplerNames); }},
        {"--seed", "S", {}, "", "seed of every pixel's random stream and scrambles (default 1)", [](CL& cl, A& a) { cl.opt.seed = uint64_t(a.integer(0, 9e15)); }},
        {"--threads", "N", {}, "", "worker threads (default: all cores); the image does not depend on N",
         [](CL& cl, A& a) { cl.opt.threads = int(a.integer(1, 1024)); }},
        {nullptr, "", {}, "", "Output", nullptr},
        {"--out", "FILE.png", {}, "", "PNG file (default render.png); the PFM goes to FILE.pfm", [](CL& cl, A& a) { cl.out = a.value(); }},
        {"--res", "WxH", {}, "", "override the scene's resolution (e.g. --res 128x128)",
         [](CL& cl, A& a) {
             std::string v = a.value();
             char tail = 0;
             if (std::sscanf(v.c_str(), "%dx%d%c", &cl.width, &cl.height, &tail) != 2 || cl.width < 1 || cl.height < 1 ||
                 cl.width > 16384 || cl.height > 16384)
                 a.fail("option --res needs WIDTHxHEIGHT, each 1 to 16384, got '" + printable(v) + "'");
             if (double(cl.width) * cl.height > 64e6) a.fail("option --res: " + printable(v) + " is larger than 64 megapixels (as in scene files)");
         }},
        {"--exposure", "STOPS", {}, "", "scale the PNG by 2^STOPS (the PFM stays linear)",
         [](CL& cl, A& a) { cl.exposure = float(a.number(-50, 50)), cl.exposureGiven = true; }},
        {"--quiet", "", {}, "", "no summary line", [](CL& cl, A&) { cl.quiet = true; }},
        {"--help", "", {}, "", "this text", [](CL& cl, A&) { cl.help = true; }},
        {nullptr, "", {}, "", "Exit status: 0 done, 1 an output file cannot be written, 2 bad scene file or option.", nullptr},
    };
}();

// --help, from a table: each option's name and value, its help beside it from column 20.
template <class Line>
std::string usage(const std::vector<OptionRow<Line>>& table) {
    std::string text;
    for (const OptionRow<Line>& o : table) {
        if (!o.name) { text += std::string(o.help) + "\n"; continue; }
        std::string head = "  " + std::string(o.name) + (*o.value ? " " + std::string(o.value) : "");
        text += head + std::string(head.size() < 20 ? 20 - head.size() : 2, ' ');
        for (const char* c = o.help; *c; ++c) text += *c == '\n' ? "\n" + std::string(20, ' ') : std::string(1, *c);
        text += "\n";
    }
    return text;
}

// The options ./bdpt adds (classroom/): the lecture's program names the program that has them.
constexpr const char* kClassroomOptions[] = {"--side-by-side", "--title", "--ratio-panel", "--live", "--log", "--ref", "--compare",
                                             "--average", "--ratio", "--failure-table", "--profile", "--overwrite"};
// A command line's words, each an option, a value or the scene; a misspelt option gets the closest
// of the table's (or suggest()'s, the classroom's, which knows other programs' names too).
template <class Line>
Line parseOptions(const std::vector<std::string>& args, const std::vector<OptionRow<Line>>& table,
                  std::string (*suggest)(const std::string&) = nullptr) {
    Line cl;
    ArgReader in{args};
    for (; in.i < args.size(); ++in.i) {
        const std::string& a = args[in.i] == "-h" ? "--help" : args[in.i];
        if (a.size() > 2 && a[0] == '-' && a[1] == '-' && !cl.given.insert(a).second)
            in.fail("option " + printable(a) + " given twice (which one did you mean?)");
        auto option = std::find_if(table.begin(), table.end(), [&](const OptionRow<Line>& o) { return o.name && a == o.name; });
        if (option != table.end()) {
            option->apply(cl, in);
        } else if (!a.empty() && a[0] == '-') {
            size_t equals = a.find('=');
            if (equals != std::string::npos)
                in.fail("unknown option '" + printable(a) + "' (write '" + printable(a.substr(0, equals)) + " " + printable(a.substr(equals + 1)) + "')");
            if (std::count(std::begin(kClassroomOptions), std::end(kClassroomOptions), a))
                in.fail(printable(a) + " is an option of ./bdpt, the classroom's program (make builds it), not of bdpt.cpp alone");
            std::vector<std::string> names;
            for (const OptionRow<Line>& o : table)
                if (o.name) names.push_back(o.name);
            std::string near = suggest ? suggest(a) : closestWords(a, names);
            in.fail("unknown option '" + printable(a) + "'" + (near.empty() ? "" : " (did you mean " + near + "?)"));
        } else if (cl.scenePath.empty()) {
            cl.scenePath = a;
        } else {
            in.fail("more than one scene file ('" + printable(cl.scenePath) + "', '" + printable(a) + "')");
        }
    }
    return cl;
}

// What no single option can check: combinations, and options the method would ignore (checkMethods).
template <class Line>
void checkCombinations(Line& cl, const std::vector<OptionRow<Line>>& table, bool checkMethods = true) {
    auto given = [&](const char* o) { return cl.given.count(o) > 0; };
    for (const OptionRow<Line>& o : table)
        if (checkMethods && o.name && given(o.name) && !o.methods.empty() &&
            std::find(o.methods.begin(), o.methods.end(), cl.opt.method) == o.methods.end())
            ArgReader::fail(std::string(o.name) + " applies to " + o.whose + ", not to --method " + methodName(cl.opt.method));
    if (given("--strategy-length") && cl.strategiesDir.empty()) ArgReader::fail("--strategy-length applies with --strategies DIR");
    // Only the throughput rule has a start: the albedo rule acts from the first bounce on.
    bool throughputRoulette = cl.opt.method == Method::PT || cl.opt.method == Method::NEE || cl.opt.roulette == Roulette::Throughput;
    if (given("--rr-start") && !throughputRoulette)
        ArgReader::fail(std::string("--rr-start applies to pt, nee and --roulette throughput; --method ") + methodName(cl.opt.method) +
                        (cl.opt.roulette == Roulette::Albedo ? " ends its subpaths by --roulette albedo (the default), which acts from the first bounce on"
                                                             : " has --roulette off: no roulette at all"));
    std::vector<std::string> budgets;
    for (const char* o : {"--time", "--wall-time", "--spp"})
        if (given(o)) budgets.push_back(o);
    if (budgets.size() > 1)
        ArgReader::fail(budgets[0] + " and " + budgets[1] + " both given: --time (CPU) and --wall-time render passes until the time "
                        "is up, --spp a number of them; give one");
    if (!cl.strategiesDir.empty()) cl.opt.strategyMaxLength = cl.strategyLength;
}

// What a sample costs in rays, the slides' "more costly" counted: the summary line's figure.
inline std::string raysPerSample(const RenderResult& r) {
    double samples = double(r.passes) * r.image.width * r.image.height;
    char text[128];
    std::snprintf(text, sizeof text, "%.2f rays per sample (%.2f closest-hit, %.2f shadow)",
                  (r.rays.closest + r.rays.shadow) / samples, r.rays.closest / samples, r.rays.shadow / samples);
    return text;
}

// What a render did: its passes and time, the image's mean, what it cost in rays, what it wrote.
inline std::string summaryLine(const CommandLine& cl, const RenderResult& r, const std::string& pfm) {
    char seconds[64];
    std::snprintf(seconds, sizeof seconds, "%.2f s (%.2f CPU s)", r.seconds, r.cpuSeconds);  // a hundredth: the clocks' noise is larger
    std::ostringstream line;
    line << cl.scenePath << ": " << r.passes << " samples per pixel in " << seconds << ", mean " << imageMean(r.image) << ", "
         << r.nonFinite << " non-finite samples dropped, " << raysPerSample(r) << "; wrote " << cl.out << " and " << pfm << "\n";
    return line.str();
}

// What a method's last pass leaves to say: the chains' b and acceptance (Veach's per mutation for
// mlt), and the share of the energy ir's clamp removed (its bias, panel (e)).
inline std::string methodSummary(const SampleOptions& opt, const MetropolisPass& mp, double clampRemoved) {
    long long accepted = 0, proposed = 0, acceptedBy[4] = {0, 0, 0, 0}, proposedBy[4] = {0, 0, 0, 0};
    for (const PrimarySampleChain& c : mp.chains) accepted += c.accepted, proposed += c.proposed;
    for (const PathChain& c : mp.paths) {
        accepted += c.accepted, proposed += c.proposed;
        for (int m = 0; m < 4; ++m) acceptedBy[m] += c.acceptedBy[m], proposedBy[m] += c.proposedBy[m];
    }
    char text[256];
    std::string s;
    if (isMetropolis(opt.method)) {
        std::snprintf(text, sizeof text, "%s: b = %.6g +- %.2g (bootstrap of %d samples); %d chains accepted %.1f%% of %lld mutations\n",
                      methodName(opt.method), mp.b, mp.bStandardError, bootstrapSamples(opt), chainCount(opt),
                      100.0 * double(accepted) / double(std::max(1LL, proposed)), proposed);
        s += text;
    }
    if (opt.method == Method::MLT) {
        s += "mlt: accepted";
        const char* names[4] = {"bidirectional", "lens", "caustic", "multi-chain"};
        for (int m = 0; m < 4; ++m) {
            std::snprintf(text, sizeof text, "%s %s %.1f%% of %lld", m ? "," : "", names[m],
                          100.0 * double(acceptedBy[m]) / double(std::max(1LL, proposedBy[m])), proposedBy[m]);
            s += text;
        }
        s += " (a proposal that could not be made counts as refused)\n";
    }
    if (opt.method == Method::IR && opt.ir.clamp > 0) {
        std::snprintf(text, sizeof text, "clamp %g removed %g%% of the energy gathered from VPLs\n", opt.ir.clamp, 100 * clampRemoved);
        s += text;
    }
    return s;
}

// The scene as the command line asks for it: its resolution, its mistakes, its PNG's exposure.
inline void applyToScene(CommandLine& cl, Scene& scene) {
    if (cl.width > 0) setResolution(scene.camera, cl.width, cl.height);
    scene.conventions = cl.conventions;
    if (!cl.exposureGiven) cl.exposure = scene.exposure;
}

// The lecture's program: parse, render, write the PNG, the PFM and the strategy images, summarise.
inline int runLecture(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    CommandLine cl;
    Scene scene;
    try {
        cl = parseOptions(args, kOptions);
        if (cl.help) { out << usage(kOptions); return 0; }
        if (cl.scenePath.empty()) ArgReader::fail("no scene file given");
        if (!hasExtension(cl.out, ".png")) ArgReader::fail("--out must name a .png file (the PFM goes beside it), got '" + printable(cl.out) + "'");
        checkCombinations(cl, kOptions);
        scene = loadScene(cl.scenePath);
        applyToScene(cl, scene);
    } catch (const InputError& e) {
        err << e.what() << "\n";
        return 2;
    }
    RenderResult r = render(scene, cl.opt);
    const std::string pfm = replaceExtension(cl.out, ".pfm");
    if (!makeFolders(folderOf(cl.out)) || !writePNG(r.image, cl.out, cl.exposure) || !writePFM(r.image, pfm) ||
        (!cl.strategiesDir.empty() && (!makeFolders(cl.strategiesDir) || !writeStrategyImages(r.strategies, cl.strategiesDir, cl.exposure)))) {
        err << "bdpt: cannot write " << cl.out << ", " << pfm << " or the strategy images\n";
        return 1;
    }
    if (!cl.quiet) out << summaryLine(cl, r, pfm) << methodSummary(cl.opt, r.method.metropolis, r.clampRemoved());
    return 0;
}

#ifndef BDPT_NO_MAIN
int main(int argc, char** argv) { return runLecture(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr); }
#endif

// == Appendix B. The BVH ====================================================================
// Not a slide's topic but the notes' appendix B: section 3's intersect() and occluded() call it. A
// bounding volume hierarchy finds the closest of N shapes in about log N box tests instead of N.
// Build: binned SAH. Split a set of shapes where the surface area heuristic
//   cost = A(left)/A * N(left) + A(right)/A * N(right)
// is smallest, over 16 bins of centroids per axis; split the child with the largest area again
// until a node has W children (W = 4 with SSE, 8 with AVX). A leaf is one shape, in leaf order:
// the W-wide box test screens W shapes at once, and a shape's exact test reads only what its kind
// needs; incoherent rays wait on memory, not arithmetic (appendix B; `make bench` races Embree).
// Traverse: each node keeps its W child boxes as structure-of-arrays, so one SIMD slab test checks
// all children; closest hit visits them front to back and skips boxes beyond the hit so far; any
// hit (shadow rays) stops at the first. A zero direction component gives an infinite inverse, and
// 0*inf = NaN where the origin lies on a slab's plane: the operand order of min/max below ignores
// it (SSE returns the second operand on NaN). Box exits are widened by 1+2gamma_3 so that
// rounding never loses a hit at a box edge (pbrt).
#if defined(__SSE2__)
#include <immintrin.h>
#endif

struct Aabb {
    Vec3 lo{kInf}, hi{-kInf};
    void grow(Vec3 p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    void grow(const Aabb& b) {
        if (b.lo.x <= b.hi.x) grow(b.lo), grow(b.hi);  // an empty box (an empty SAH bin) adds nothing
    }
    float halfArea() const {
        Vec3 d = hi - lo;
        return lo.x > hi.x ? 0 : d.x * d.y + d.y * d.z + d.z * d.x;
    }
};

inline Aabb shapeBounds(const Shape& s) {
    Aabb b;
    if (s.type == Shape::Sphere) {
        b.grow(s.p - Vec3(s.radius));
        b.grow(s.p + Vec3(s.radius));
    } else {
        for (Vec3 c : {s.p, s.p + s.u, s.p + s.v, s.p + s.u + s.v}) b.grow(c);
    }
    return b;
}

// What the leaves hold, in leaf order: just enough to intersect (a sphere 16 bytes, a quad 48).
struct SpherePrimitive { Vec3 centre; float radius; };
struct QuadPrimitive { Vec3 q, u, v, w; };  // corner, edges, w = n/(n.n)

// Node width: 8 children with AVX (make NATIVE=1), else 4 (SSE); SIMD(op) names that width's intrinsic.
#if defined(__AVX__)
constexpr int kWidth = 8;
using Lanes = __m256;
#define SIMD(op) _mm256_##op
inline Lanes lessEqual(Lanes a, Lanes b) { return _mm256_cmp_ps(a, b, _CMP_LE_OQ); }
#elif defined(__SSE2__)
constexpr int kWidth = 4;
using Lanes = __m128;
#define SIMD(op) _mm_##op
inline Lanes lessEqual(Lanes a, Lanes b) { return _mm_cmple_ps(a, b); }
#else
constexpr int kWidth = 4;
#endif

struct alignas(64) BvhNode {
    float box[6][kWidth];   // [min x, max x, min y, max y, min z, max z][child]; empty child: min > max
    int32_t child[kWidth];  // >= 0 inner node index; < 0 a leaf: ~(primitive index * 2 + is sphere)
};

struct Bvh {
    std::vector<BvhNode> nodes;
    std::vector<SpherePrimitive> spheres;
    std::vector<QuadPrimitive> quads;
    std::vector<int32_t> sphereShape, quadShape;  // the scene's shape index of each primitive
};

struct BvhBuilder {
    struct Ref {  // one shape during the build; partitioned in place, so every pass is sequential
        Aabb box;
        Vec3 centroid;
        int shape;
    };
    std::vector<Ref> refs;
    Bvh& bvh;
    const std::vector<Shape>& shapes;

    // Leaves are made in leaf order, so a node's leaf children lie side by side in memory.
    int32_t leafCode(int shape) {
        const Shape& s = shapes[shape];
        if (s.type == Shape::Sphere) {
            bvh.spheres.push_back({s.p, s.radius});
            bvh.sphereShape.push_back(shape);
            return ~int32_t((bvh.spheres.size() - 1) * 2 + 1);
        }
        bvh.quads.push_back({s.p, s.u, s.v, quadW(s.u, s.v)});
        bvh.quadShape.push_back(shape);
        return ~int32_t((bvh.quads.size() - 1) * 2);
    }

    Aabb rangeBounds(int b, int e) const {
        Aabb box;
        for (int i = b; i < e; ++i) box.grow(refs[i].box);
        return box;
    }
    // Binned SAH on all three axes; returns the right half's first index and the halves' boxes.
    int split(int b, int e, Aabb& leftBox, Aabb& rightBox) {
        constexpr int kBins = 16;
        Aabb cb;
        for (int i = b; i < e; ++i) cb.grow(refs[i].centroid);
        Aabb bin[3][kBins];
        int count[3][kBins] = {{0}};
        float scale[3];
        for (int a = 0; a < 3; ++a) scale[a] = cb.hi[a] > cb.lo[a] ? kBins / (cb.hi[a] - cb.lo[a]) : 0;
        auto binOf = [&](const Ref& r, int a) { return std::min(kBins - 1, int((r.centroid[a] - cb.lo[a]) * scale[a])); };
        for (int i = b; i < e; ++i)
            for (int a = 0; a < 3; ++a) {
                int k = binOf(refs[i], a);
                bin[a][k].grow(refs[i].box);
                ++count[a][k];
            }
        float bestCost = kInf;
        int bestAxis = -1, bestBin = 0;
        for (int a = 0; a < 3; ++a) {
            if (scale[a] == 0) continue;
            float rightArea[kBins];
            int rightCount[kBins];
            Aabb acc;
            int n = 0;
            for (int k = kBins - 1; k > 0; --k) {
                acc.grow(bin[a][k]);
                n += count[a][k];
                rightArea[k] = acc.halfArea();
                rightCount[k] = n;
            }
            acc = Aabb();
            n = 0;
            for (int k = 0; k < kBins - 1; ++k) {
                acc.grow(bin[a][k]);
                n += count[a][k];
                float cost = acc.halfArea() * n + rightArea[k + 1] * rightCount[k + 1];
                if (n > 0 && rightCount[k + 1] > 0 && cost < bestCost) { bestCost = cost; bestAxis = a; bestBin = k; }
            }
        }
        if (bestAxis < 0) {  // all centroids in one point: split by count
            int mid = (b + e) / 2;
            leftBox = rangeBounds(b, mid);
            rightBox = rangeBounds(mid, e);
            return mid;
        }
        leftBox = rightBox = Aabb();
        for (int k = 0; k < kBins; ++k) (k <= bestBin ? leftBox : rightBox).grow(bin[bestAxis][k]);
        return int(std::partition(refs.begin() + b, refs.begin() + e, [&](const Ref& r) { return binOf(r, bestAxis) <= bestBin; }) -
                   refs.begin());
    }
    int build(int b, int e, const Aabb& box) {
        int index = int(bvh.nodes.size());
        bvh.nodes.emplace_back();
        struct Range { int b, e; Aabb box; } r[kWidth];
        int n = 1;
        r[0] = {b, e, box};
        while (n < kWidth) {  // open the largest child that is more than one shape
            int pick = -1;
            for (int i = 0; i < n; ++i)
                if (r[i].e - r[i].b > 1 && (pick < 0 || r[i].box.halfArea() > r[pick].box.halfArea())) pick = i;
            if (pick < 0) break;
            Aabb left, right;
            int mid = split(r[pick].b, r[pick].e, left, right);
            r[n++] = {mid, r[pick].e, right};
            r[pick] = {r[pick].b, mid, left};
        }
        BvhNode node;
        for (int i = 0; i < kWidth; ++i) {
            Aabb childBox = i < n ? r[i].box : Aabb();
            for (int a = 0; a < 3; ++a) {
                node.box[2 * a][i] = childBox.lo[a];
                node.box[2 * a + 1][i] = childBox.hi[a];
            }
            node.child[i] = i < n && r[i].e - r[i].b == 1 ? leafCode(refs[r[i].b].shape) : 0;
        }
        for (int i = 0; i < n; ++i)  // inner children after all the leaves, which stay side by side
            if (r[i].e - r[i].b > 1) node.child[i] = build(r[i].b, r[i].e, r[i].box);
        bvh.nodes[index] = node;
        return index;
    }
};

inline Bvh buildBvh(const std::vector<Shape>& shapes) {
    Bvh bvh;
    if (shapes.empty()) return bvh;
    BvhBuilder builder{{}, bvh, shapes};
    builder.refs.reserve(shapes.size());
    for (size_t i = 0; i < shapes.size(); ++i) {
        Aabb box = shapeBounds(shapes[i]);
        builder.refs.push_back({box, (box.lo + box.hi) * 0.5f, int(i)});
    }
    bvh.nodes.reserve(2 * shapes.size() / (kWidth - 1) + 1);
    builder.build(0, int(shapes.size()), builder.rangeBounds(0, int(shapes.size())));
    return bvh;
}

// The ray's constants for the slab tests.
struct RayBoxTest {
    int nearX, nearY, nearZ;   // which row of BvhNode::box is the entry plane on each axis
#if defined(__SSE2__)
    Lanes ox, oy, oz, ix, iy, iz;
#else
    Vec3 o, inv;
#endif
    explicit RayBoxTest(const Ray& r) {
        Vec3 inv(1 / r.d.x, 1 / r.d.y, 1 / r.d.z);  // +-inf for +-0
        nearX = inv.x >= 0 ? 0 : 1;
        nearY = inv.y >= 0 ? 2 : 3;
        nearZ = inv.z >= 0 ? 4 : 5;
#if defined(__SSE2__)
        ox = SIMD(set1_ps)(r.o.x), oy = SIMD(set1_ps)(r.o.y), oz = SIMD(set1_ps)(r.o.z);
        ix = SIMD(set1_ps)(inv.x), iy = SIMD(set1_ps)(inv.y), iz = SIMD(set1_ps)(inv.z);
#else
        o = r.o;
        this->inv = inv;
#endif
    }
    // Bit i set when the ray meets child i's box within (0, tmax); tEntry receives the entry distances.
    int test(const BvhNode& n, float tmax, float tEntry[kWidth]) const {
        constexpr float kWiden = 1 + 2 * (3 * 0x1p-24f) / (1 - 3 * 0x1p-24f);  // 1 + 2 gamma_3
        // Each candidate (possibly NaN) is the first operand, the running bound the second.
#if defined(__SSE2__)
        auto slab = [&](int row, Lanes o, Lanes inv) { return SIMD(mul_ps)(SIMD(sub_ps)(SIMD(load_ps)(n.box[row]), o), inv); };
        Lanes t0 = SIMD(max_ps)(slab(nearZ, oz, iz), SIMD(setzero_ps)());
        t0 = SIMD(max_ps)(slab(nearX, ox, ix), SIMD(max_ps)(slab(nearY, oy, iy), t0));
        Lanes t1 = SIMD(min_ps)(slab(nearZ ^ 1, oz, iz), SIMD(set1_ps)(tmax));
        t1 = SIMD(min_ps)(slab(nearX ^ 1, ox, ix), SIMD(min_ps)(slab(nearY ^ 1, oy, iy), t1));
        SIMD(storeu_ps)(tEntry, t0);
        return SIMD(movemask_ps)(lessEqual(t0, SIMD(mul_ps)(t1, SIMD(set1_ps)(kWiden))));
#else
        int mask = 0;
        for (int i = 0; i < kWidth; ++i) {
            // fmax/fmin ignore a NaN operand, like the operand order of the SIMD paths.
            float t0 = std::fmax(std::fmax((n.box[nearX][i] - o.x) * inv.x, (n.box[nearY][i] - o.y) * inv.y),
                                 std::fmax((n.box[nearZ][i] - o.z) * inv.z, 0.0f));
            float t1 = std::fmin(std::fmin((n.box[nearX ^ 1][i] - o.x) * inv.x, (n.box[nearY ^ 1][i] - o.y) * inv.y),
                                 std::fmin((n.box[nearZ ^ 1][i] - o.z) * inv.z, tmax));
            tEntry[i] = t0;
            mask |= (t0 <= t1 * kWiden) << i;
        }
        return mask;
#endif
    }
};

// Closest hit: nearest child first, each hit shortening the ray; any hit (shadow rays): the first ends it.
template <bool anyHit>
inline Hit traverseBvh(const Bvh& bvh, const Ray& ray) {
    Hit hit;
    if (bvh.nodes.empty()) return hit;
    RayBoxTest boxTest(ray);
    Ray r = ray;
    struct Entry { int32_t node; float t; } stack[64 * kWidth];  // at most W-1 more per level
    int top = 0;
    stack[top++] = {0, 0};
    while (top > 0) {
        Entry e = stack[--top];
        if (!anyHit && e.t > r.tmax) continue;  // a closer hit was found since this was pushed
        const BvhNode& n = bvh.nodes[e.node];
        float tEntry[kWidth];
        int base = top;
        for (int mask = boxTest.test(n, r.tmax, tEntry); mask; mask &= mask - 1) {
            int i = __builtin_ctz(mask);
            if (n.child[i] < 0) {  // a leaf: test its shape now, which may shorten the ray
                int code = ~n.child[i], k = code >> 1;
                float t = code & 1 ? intersectSphere(bvh.spheres[k].centre, bvh.spheres[k].radius, r)
                                   : intersectQuad(bvh.quads[k].q, bvh.quads[k].u, bvh.quads[k].v, bvh.quads[k].w, r);
                if (t < r.tmax) {
                    if (anyHit) return {t, 0};  // a shadow ray: that something is there is all it asks
                    r.tmax = hit.t = t;
                    hit.shape = code & 1 ? bvh.sphereShape[k] : bvh.quadShape[k];
                }
                continue;
            }
            // Ask for the child's cache lines now, long before it is popped (large scenes wait on them).
            const char* child = reinterpret_cast<const char*>(&bvh.nodes[n.child[i]]);
            for (size_t line = 0; line < sizeof(BvhNode); line += 64) __builtin_prefetch(child + line);
            // A shadow ray's hits do not shorten it: sorting its children costs more than it saves.
            if (anyHit) { stack[top++] = {n.child[i], tEntry[i]}; continue; }
            // Insert so that the nearest child ends on top of the stack (front to back).
            int j = top++;
            while (j > base && stack[j - 1].t < tEntry[i]) { stack[j] = stack[j - 1]; --j; }
            stack[j] = {n.child[i], tEntry[i]};
        }
    }
    return hit;
}
inline void buildAcceleration(Scene& scene) { scene.bvh = std::make_shared<const Bvh>(buildBvh(scene.shapes)); }

// == Appendix C. Sobol points: the definition, then the same numbers fast ====================
// -- Quasi-random numbers ("stratification"). N independent samples leave gaps and clumps: the
// error falls as N^-1/2. N points filling the unit square evenly, one in every cell of every grid
// of N equal cells (the "elementary intervals"), miss no region: the RMSE falls as N^-3/2 for smooth
// 2D integrands with Owen's scramble, N^-3/4 across a shadow's edge (page 9 measures N^-0.7). A
// path's numbers (film position, then per vertex the lamp choice, the lamp point, the BSDF's
// direction, roulette) are one point in many dimensions, stratified jointly by the Sobol sequence:
// dimension d is x_d(i) = C_d i (i's bits times a binary matrix, read as a binary fraction), and
// its first 2^m points, and every aligned block of 2^m after them, fill the elementary intervals of
// every low-dimensional projection nearly evenly. C_0 is the identity (the radical inverse); the
// others come from a primitive polynomial and Joe and Kuo's (2008) direction numbers m_k. Each
// pixel's sequence is randomised by a nested uniform scramble (Owen 1995): every binary digit of
// every coordinate flipped by a random function of the digits before it, which keeps the
// stratification, makes each point uniform in [0,1)^d (the estimator stays unbiased) and pixels'
// errors independent. Dimensions past kLowDiscrepancyDimensions (deep bounces) come from PCG32.

constexpr uint32_t reverseBits(uint32_t x) {
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00FF00FFu) << 8) | ((x >> 8) & 0x00FF00FFu);
    x = ((x & 0x0F0F0F0Fu) << 4) | ((x >> 4) & 0x0F0F0F0Fu);
    x = ((x & 0x33333333u) << 2) | ((x >> 2) & 0x33333333u);
    return ((x & 0x55555555u) << 1) | ((x >> 1) & 0x55555555u);
}

// Dimension d >= 1: the polynomial x^s + a_1 x^(s-1) + ... + 1 (a_1.. the bits of `a`) and m_1..m_s.
struct SobolPolynomial {
    uint32_t degree, a, m[7];
};
constexpr SobolPolynomial kJoeKuo[kLowDiscrepancyDimensions - 1] = {
    {1, 0, {1}}, {2, 1, {1, 3}}, {3, 1, {1, 3, 1}}, {3, 2, {1, 1, 1}}, {4, 1, {1, 1, 3, 3}},
    {4, 4, {1, 3, 5, 13}}, {5, 2, {1, 1, 5, 5, 17}}, {5, 4, {1, 1, 5, 5, 5}}, {5, 7, {1, 1, 7, 11, 19}},
    {5, 11, {1, 1, 5, 1, 1}}, {5, 13, {1, 1, 1, 3, 11}}, {5, 14, {1, 3, 5, 5, 31}},
    {6, 1, {1, 3, 3, 9, 7, 49}}, {6, 13, {1, 1, 1, 15, 21, 21}}, {6, 16, {1, 3, 1, 13, 27, 49}},
    {6, 19, {1, 1, 1, 15, 7, 5}}, {6, 22, {1, 3, 1, 15, 13, 25}}, {6, 25, {1, 1, 5, 5, 19, 61}},
    {7, 1, {1, 3, 7, 11, 23, 15, 103}}, {7, 4, {1, 3, 7, 13, 13, 15, 69}}, {7, 7, {1, 1, 3, 13, 7, 35, 63}},
    {7, 8, {1, 3, 5, 9, 1, 25, 53}}, {7, 14, {1, 3, 1, 13, 9, 35, 107}}, {7, 19, {1, 3, 1, 5, 27, 61, 31}},
    {7, 21, {1, 1, 5, 11, 19, 41, 61}}, {7, 28, {1, 3, 5, 3, 3, 13, 69}}, {7, 31, {1, 1, 7, 13, 1, 19, 1}},
    {7, 32, {1, 3, 7, 5, 13, 19, 59}}, {7, 37, {1, 1, 3, 9, 25, 29, 41}}, {7, 41, {1, 3, 5, 13, 23, 1, 55}},
    {7, 42, {1, 3, 7, 3, 13, 59, 17}},
};
// The generator matrices' columns in digit order (bit j = the fraction's digit j+1): column k is
// m_k / 2^k, then Sobol's recurrence m_k = 2 a_1 m_(k-1) ^ 4 a_2 m_(k-2) ^ ... ^ 2^s m_(k-s) ^ m_(k-s).
struct SobolMatrices {
    uint32_t column[32][kLowDiscrepancyDimensions];  // [k][d]: column k of every C_d side by side
};
constexpr SobolMatrices makeSobolMatrices() {
    SobolMatrices C{};
    for (uint32_t k = 0; k < 32; ++k) C.column[k][0] = 1u << k;
    for (uint32_t d = 1; d < kLowDiscrepancyDimensions; ++d) {
        const SobolPolynomial& p = kJoeKuo[d - 1];
        uint32_t m[32] = {};
        for (uint32_t k = 0; k < 32; ++k) {
            if (k < p.degree) {
                m[k] = p.m[k];
            } else {
                m[k] = m[k - p.degree] ^ (m[k - p.degree] << p.degree);
                for (uint32_t j = 1; j < p.degree; ++j)
                    if ((p.a >> (p.degree - 1 - j)) & 1) m[k] ^= m[k - j] << j;
            }
            C.column[k][d] = reverseBits(m[k] << (31 - k));
        }
    }
    return C;
}
constexpr SobolMatrices kSobol = makeSobolMatrices();

// The nested uniform scramble in digit order: each bit flipped by a hash of the bits below it, as
// adding the seed and xor-ing even multiples does (Laine and Karras 2011, Burley's constants 2020).
inline uint32_t scrambleDigits(uint32_t digits, uint32_t seed) {
    digits += seed;
    digits ^= digits * 0x6C50B47Cu;
    digits ^= digits * 0xB82F1E52u;
    digits ^= digits * 0xC7AFE638u;
    digits ^= digits * 0x8D22F6E6u;
    return digits;
}
// A stream's own order of the sequence (Burley 2020): index's bits scrambled like a coordinate's
// digits, from the top: the first 2^m indices map onto one aligned block of 2^m (a net) in a random
// order. Two streams whose numbers meet in one path (bdpt's camera and light subpaths, a pixel and
// ir's VPLs) must not draw the same point i: x_d(i) and y_d(i) would share i's digits and cluster
// along a scrambled diagonal (bdpt's MSE falling as N^-0.7, not N^-1). Within blocks of 2^16
// passes: fewer bits set, fewer columns to add up in drawCoordinates.
inline uint32_t shuffledIndex(uint32_t index, uint32_t seed) {
    uint32_t low = reverseBits(scrambleDigits(reverseBits(index & 0xFFFFu), seed)) & 0xFFFFu;
    return (index & ~0xFFFFu) | low;
}
// Coordinate d of point `index`, its digits scrambled by `seed`, as a fraction of 24 digits: the
// definition above, word for word. Below, the same numbers fast (four coordinates at once, the
// seeds composed at compile time); test_sampler holds the two equal.
inline float sobolSample(uint32_t index, uint32_t d, uint32_t seed) {
    uint32_t digits = 0;
    for (uint32_t k = 0; k < 32; ++k)
        if ((index >> k) & 1) digits ^= kSobol.column[k][d];  // x_d(i) = C_d i
    return float(reverseBits(scrambleDigits(digits, seed)) >> 8) * 0x1p-24f;
}
// -- Fast: the same numbers as sobolSample (test_sampler holds them equal), for every path's
// first 32 dimensions: the xor of columns done four dimensions per instruction, the per-dimension
// scramble seeds composed at compile time, the bit reversal by a table.
// Dimension d's scramble seed: step d+1 of an LCG from the stream's key, the steps composed at compile time.
struct LcgJump {
    uint64_t mul, add;
};
struct LcgJumps {
    LcgJump step[kLowDiscrepancyDimensions];
};
constexpr LcgJumps makeLcgJumps() {
    LcgJumps J{};
    uint64_t mul = 1, add = 0;
    for (uint32_t d = 0; d < kLowDiscrepancyDimensions; ++d) {
        mul *= 6364136223846793005ULL;
        add = add * 6364136223846793005ULL + 1442695040888963407ULL;
        J.step[d] = {mul, add};
    }
    return J;
}
constexpr LcgJumps kScrambleSeeds = makeLcgJumps();

// Digit order back to a fraction's 24 leading digits: the bits' order reversed a byte at a time.
struct ByteReversal {
    uint8_t reversed[256];
};
constexpr ByteReversal makeByteReversal() {
    ByteReversal R{};
    for (uint32_t i = 0; i < 256; ++i) R.reversed[i] = uint8_t(reverseBits(i) >> 24);
    return R;
}
constexpr ByteReversal kByteReversal = makeByteReversal();
inline uint32_t fractionDigits(uint32_t digits) {
    const uint8_t* r = kByteReversal.reversed;
    return uint32_t(r[digits & 255]) << 16 | uint32_t(r[(digits >> 8) & 255]) << 8 | r[(digits >> 16) & 255];
}

// Coordinates first..first+3 of point sobolIndex: the xor of C_d's columns picked by the index's
// bits, four dimensions per instruction, then each scrambled by its own seed (not with
// --no-scramble, the mistake) and made a fraction. Only the blocks a path reaches are computed.
inline void Rng::drawCoordinates(uint32_t first) {
    typedef uint32_t FourDimensions __attribute__((vector_size(16)));
    FourDimensions digits = {};
    for (uint32_t i = sobolIndex; i; i &= i - 1) {  // bit k of the index set: column k
        FourDimensions c;
        std::memcpy(&c, kSobol.column[__builtin_ctz(i)] + first, sizeof c);
        digits ^= c;
    }
    for (uint32_t q = 0; q < 4; ++q) {
        const LcgJump& jump = kScrambleSeeds.step[first + q];
        uint32_t seed = uint32_t((jump.mul * scrambleKey + jump.add) >> 32);
        block[q] = fractionDigits(scrambled ? scrambleDigits(digits[q], seed) : digits[q]);
    }
}

// == Appendix D. vcm's hash grid ==============================================================
// Section 8 (g)'s HashGrid: cells of side 2r hashed into a power of two of buckets, the records
// sorted by bucket (a counting sort), a query visiting the at most 8 buckets its sphere overlaps.
inline int64_t gridCell(const HashGrid& g, float x) { return int64_t(std::floor(x * g.cellsPerUnit)); }
inline uint32_t gridBucket(const HashGrid& g, int64_t x, int64_t y, int64_t z) {
    return (uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u ^ uint32_t(z) * 83492791u) & g.bucketMask;
}

// Builds the grid of `points`; returns the bucket order (the grid's record e is points[order[e]]).
inline std::vector<uint32_t> buildHashGrid(HashGrid& g, const std::vector<Vec3>& points, float radius) {
    g.radius = radius;
    g.cellsPerUnit = radius > 0 ? 0.5f / radius : 0;
    size_t buckets = 1;
    while (buckets < points.size()) buckets *= 2;
    g.bucketMask = uint32_t(buckets - 1);
    g.bucketStart.assign(buckets + 1, 0);
    std::vector<uint32_t> bucket(points.size()), order(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        Vec3 p = points[i];
        ++g.bucketStart[(bucket[i] = gridBucket(g, gridCell(g, p.x), gridCell(g, p.y), gridCell(g, p.z))) + 1];
    }
    for (size_t b = 1; b < g.bucketStart.size(); ++b) g.bucketStart[b] += g.bucketStart[b - 1];
    std::vector<uint32_t> fill(g.bucketStart.begin(), g.bucketStart.end() - 1);
    for (size_t i = 0; i < points.size(); ++i) order[fill[bucket[i]]++] = uint32_t(i);
    return order;
}

// Calls visit(e), in a fixed order, for every record e (in bucket order, with its point .p) within r of p.
template <class Record, class Visit>
inline void forEachNeighbour(const HashGrid& g, const std::vector<Record>& records, Vec3 p, Visit&& visit) {
    if (records.empty()) return;
    const float r2 = g.radius * g.radius;
    // The cells of p - r and p + r on each axis (at most 3 apart by rounding), as the build computes them.
    int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) lo[a] = gridCell(g, p[a] - g.radius), hi[a] = gridCell(g, p[a] + g.radius);
    uint32_t buckets[27], begin[27], end[27];  // 8 unless rounding puts p - r and p + r three cells apart
    int count = 0;
    for (int64_t z = lo[2]; z <= hi[2]; ++z)
        for (int64_t y = lo[1]; y <= hi[1]; ++y)
            for (int64_t x = lo[0]; x <= hi[0]; ++x) {
                uint32_t b = gridBucket(g, x, y, z);
                if (std::find(buckets, buckets + count, b) != buckets + count) continue;
                buckets[count++] = b;
                __builtin_prefetch(&g.bucketStart[b]);
            }
    // Each bucket is two cache misses: asked for all at once, they overlap (two misses, not sixteen).
    for (int i = 0; i < count; ++i) {
        begin[i] = g.bucketStart[buckets[i]];
        end[i] = g.bucketStart[buckets[i] + 1];
        if (begin[i] < end[i]) __builtin_prefetch(&records[begin[i]]);
    }
    for (int i = 0; i < count; ++i)
        for (uint32_t e = begin[i]; e < end[i]; ++e) {
            Vec3 d = records[e].p - p;
            if (dot(d, d) <= r2) visit(e);
        }
}
