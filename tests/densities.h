// The three strategies' densities of a path of k = 2 segments, x_0 on a lamp (shape `lamp`), x_1
// a surface point, x_2 the pinhole, computed vertex by vertex as page 7 of the notes writes them:
//   p_0 = p_cam(x_1) q(x_1) p_bsdf(x_1 -> x_0)   (the camera samples x_1, then hits the lamp)
//   p_1 = p_cam(x_1) p_light(x_0)                (next event)
//   p_2 = p_light(x_0) p_emit(x_0 -> x_1)        (light tracing)
// each an area density. Shared by tests/estimators.cpp (page 10's figure) and test_notes; the
// file that includes it has included bdpt.cpp.
#pragma once

struct TwoSegmentPath {
    bool valid = false;  // x_1 sees the lamp's front, unoccluded
    double p[3] = {0, 0, 0};
    double pLight = 0;   // p_light(x_0), area density on the lamp
    Vec3 w;              // unit, x_1 -> x_0
    double dist2 = 0;    // |x_0 - x_1|^2
};

inline TwoSegmentPath twoSegmentPath(const Scene& scene, int lamp, const SurfacePoint& x0, const SurfacePoint& x1) {
    TwoSegmentPath t;
    Vec3 d = x0.p - x1.p;
    t.dist2 = dot(d, d);
    t.w = d / std::sqrt(t.dist2);
    double cos0 = -dot(scene.shapes[lamp].normal, t.w), cos1 = absDot(x1.ng, t.w);
    if (cos0 <= 0 || occluded(scene, shadowRay(x1, x0))) return t;  // the lamp's back, or hidden
    Vec3 toX1 = x1.p - scene.camera.eye;
    double camDist2 = dot(toX1, toX1);
    Vec3 dirCam = toX1 / std::sqrt(camDist2);
    double pCam = pdfCameraDirection(scene.camera, dirCam) * absDot(x1.ng, dirCam) / camDist2;
    double pBsdf = pdfBsdf(scene, x1, -dirCam, t.w) * cos0 / t.dist2;
    t.pLight = pdfLightPoint(scene, lamp);
    t.p[0] = pCam * albedoContinuation(scene, x1) * pBsdf;
    t.p[1] = pCam * t.pLight;
    t.p[2] = t.pLight * cos0 / kPi * cos1 / t.dist2;
    t.valid = t.p[1] > 0;
    return t;
}
