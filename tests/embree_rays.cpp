// make bench, the yardstick's half: Intel Embree 3 (Debian's libembree-dev) on the same scenes and
// rays as build/bench_rays (tests/bench.h), in the same line format. Built only where Embree is
// installed. Quads are parallelograms given by 4 vertices Q, Q+u, Q+u+v, Q+v (geomID 0); spheres
// are RTC_GEOMETRY_TYPE_SPHERE_POINT (geomID 1), so a hit's geomID tells its kind; build quality
// high, one build thread; rays from t = 0 to infinity.
//   build/embree_rays [--seed S] [--n N] [--rays M] [--reps R]
#include "bench.h"
#include <embree3/rtcore.h>

struct EmbreeScene {
    RTCScene scene = nullptr;
};

int main(int argc, char** argv) {
    BenchArgs args = parseBenchArgs(argc, argv);
    RTCDevice device = rtcNewDevice("threads=1");
    if (!device) { std::fprintf(stderr, "embree_rays: rtcNewDevice failed (%d)\n", int(rtcGetDeviceError(nullptr))); return 1; }
    std::vector<RTCScene> built;  // released at the end (the driver rebuilds per repetition)
    auto build = [&](const BenchScene& b, size_t& nodes) {
        std::vector<const Shape*> quads, spheres;
        for (const Shape& s : b.shapes) (s.type == Shape::Quad ? quads : spheres).push_back(&s);
        RTCScene scene = rtcNewScene(device);
        rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry q = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
        float* v = (float*)rtcSetNewGeometryBuffer(q, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4 * quads.size());
        unsigned* index = (unsigned*)rtcSetNewGeometryBuffer(q, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), quads.size());
        for (size_t i = 0; i < quads.size(); ++i) {
            const Shape& s = *quads[i];
            for (int c = 0; c < 3; ++c) {  // each corner summed in double and rounded once
                v[12 * i + c] = s.p[c];
                v[12 * i + 3 + c] = float(double(s.p[c]) + s.u[c]);
                v[12 * i + 6 + c] = float(double(s.p[c]) + s.u[c] + s.v[c]);
                v[12 * i + 9 + c] = float(double(s.p[c]) + s.v[c]);
            }
            for (int c = 0; c < 4; ++c) index[4 * i + c] = unsigned(4 * i + c);
        }
        rtcSetGeometryBuildQuality(q, RTC_BUILD_QUALITY_HIGH);
        rtcCommitGeometry(q);
        rtcAttachGeometryByID(scene, q, 0);
        rtcReleaseGeometry(q);
        RTCGeometry sp = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        float* c4 = (float*)rtcSetNewGeometryBuffer(sp, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), spheres.size());
        for (size_t i = 0; i < spheres.size(); ++i) {
            c4[4 * i] = spheres[i]->p.x, c4[4 * i + 1] = spheres[i]->p.y, c4[4 * i + 2] = spheres[i]->p.z;
            c4[4 * i + 3] = spheres[i]->radius;
        }
        rtcSetGeometryBuildQuality(sp, RTC_BUILD_QUALITY_HIGH);
        rtcCommitGeometry(sp);
        rtcAttachGeometryByID(scene, sp, 1);
        rtcReleaseGeometry(sp);
        rtcCommitScene(scene);
        built.push_back(scene);
        nodes = 0;  // Embree does not say
        return EmbreeScene{scene};
    };
    auto trace = [](const EmbreeScene& s, const Ray& ray, bool anyHit) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh;
        rh.ray.org_x = ray.o.x, rh.ray.org_y = ray.o.y, rh.ray.org_z = ray.o.z;
        rh.ray.dir_x = ray.d.x, rh.ray.dir_y = ray.d.y, rh.ray.dir_z = ray.d.z;
        rh.ray.tnear = 0, rh.ray.tfar = kInf, rh.ray.time = 0, rh.ray.mask = ~0u, rh.ray.id = 0, rh.ray.flags = 0;
        BenchHit h;
        if (anyHit) {
            rtcOccluded1(s.scene, &context, &rh.ray);
            h.hit = rh.ray.tfar < 0;  // Embree marks an occluded ray with tfar = -inf
            return h;
        }
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(s.scene, &context, &rh);
        h.hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        if (h.hit) h.t = rh.ray.tfar, h.sphere = rh.hit.geomID == 1;
        return h;
    };
    runRayBenchmark("embree", args, build, trace);
    for (RTCScene s : built) rtcReleaseScene(s);
    rtcReleaseDevice(device);
    return 0;
}
