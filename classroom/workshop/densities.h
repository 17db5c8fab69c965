// The three strategies' densities of a path of k = 2 segments, x_0 on a lamp (shape `lamp`), x_1
// a surface point, x_2 the pinhole, computed vertex by vertex as page 7 of the notes writes them:
//   p_0 = p_cam(x_1) q(x_1) p_bsdf(x_1 -> x_0)   (the camera samples x_1, then hits the lamp)
//   p_1 = p_cam(x_1) p_light(x_0)                (next event)
//   p_2 = p_light(x_0) p_emit(x_0 -> x_1)        (light tracing)
// each an area density. Shared by classroom/workshop/estimators.cpp (page 10's figure) and test_notes; the
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
    float pdfToLamp, pdfToCamera;  // x_1's BSDF densities: toward the lamp, having come from the camera, and back
    evalBsdf(scene, x1, -dirCam, t.w, Transport::Radiance, pdfToLamp, pdfToCamera);
    double pBsdf = pdfToLamp * cos0 / t.dist2;
    t.pLight = pdfLightPoint(scene, lamp);
    t.p[0] = pCam * albedoContinuation(scene, x1) * pBsdf;
    t.p[1] = pCam * t.pLight;
    t.p[2] = t.pLight * cos0 / kPi * cos1 / t.dist2;
    t.valid = t.p[1] > 0;
    return t;
}

// Page 10's paths: x_0 the lamp's centre, x_1 what the camera sees through image row `row` of the
// middle column, with the two factors of p_2 that change along a wall: the lamp's emission
// cosine toward x_1 and the distance |x_1 - x_0|.
struct RowPath {
    TwoSegmentPath path;
    int surface = -1;        // the shape x_1 lies on
    double cosLamp = 0, distance = 0;
};

inline int lampShape(const Scene& scene) {
    int lamp = -1;
    for (size_t i = 0; i < scene.shapes.size(); ++i)
        if (scene.shapes[i].light >= 0) lamp = int(i);
    return lamp;
}

inline RowPath rowPath(const Scene& scene, int row) {
    RowPath r;
    int lamp = lampShape(scene);
    Ray ray = cameraRay(scene.camera, 0.5f * scene.camera.width, row + 0.5f);
    Hit hit = intersect(scene, ray);
    if (!hit.found() || hit.shape == lamp) return r;
    SurfacePoint x0 = sampleShapePoint(scene, lamp, 0.5f, 0.5f), x1 = surfaceAt(scene, ray, hit);
    r.path = twoSegmentPath(scene, lamp, x0, x1);
    r.surface = hit.shape;
    Vec3 toX1 = x1.p - x0.p;
    r.distance = length(toX1);
    r.cosLamp = std::abs(dot(toX1, x0.ng)) / r.distance;
    return r;
}
