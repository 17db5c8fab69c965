// One path worked with numbers, for the notes (pages 7 and 10M), as markdown tables; the file
// that includes this has included bdpt.cpp and classroom/physics.h (the weights from the
// densities, definitionWeight). Every density is written out from its definition
// (notes, page 7), with the renderer's own camera, lamp and roulette: the area density with which
// the light side and the camera side would sample each vertex, and from their products every
// strategy's p_{k,s} and weights. build/worked-path prints them; test_notes checks that the pages
// show them.
//   cornell: x_0 the lamp's centre, x_1 on the red wall, x_2 a floor point of row 230,
//            x_3 the pinhole: L D D E, k = 3, strategies s = 0 ... 3 (s = 4 would hit the pinhole)
//   caustic: glass-box's L S S D E under the glass ball, seen through pixel (90, 115) at 128x128:
//            the two able strategies, s = 0 and t = 1, with the true densities and with pbrt's
//   path:    any path of diffuse vertices from a lamp to the pinhole, given by its points (the
//            page's path view draws one sample's paths; make test-web checks its weights here)
#pragma once
#include <cstdio>
#include <string>

namespace worked {

inline std::string format(const char* f, double a) {
    char text[64];
    std::snprintf(text, sizeof text, f, a);
    return text;
}
inline std::string g4(double x) { return format("%.4g", x); }

// Area density of reaching `to` from `from` by a direction of solid-angle density pOmega.
inline double toAreaDensity(double pOmega, Vec3 from, const SurfacePoint& to) {
    Vec3 d = to.p - from;
    double d2 = dot(d, d);
    return pOmega * absDot(to.ng, d / std::sqrt(d2)) / d2;
}
inline double cosine(const SurfacePoint& at, Vec3 toward) { return absDot(at.ng, normalize(toward - at.p)); }

inline int shapeWithLight(const Scene& scene) {
    for (size_t i = 0; i < scene.shapes.size(); ++i)
        if (scene.shapes[i].light >= 0) return int(i);
    return -1;
}

inline SurfacePoint seenThrough(const Scene& scene, float x, float y) {
    Ray ray = cameraRay(scene.camera, x, y);
    return surfaceAt(scene, ray, intersect(scene, ray));
}

// The camera's area density of a point: pdfCameraDirection, made an area density there.
inline double cameraDensity(const Scene& scene, const SurfacePoint& x) {
    Vec3 d = x.p - scene.camera.eye;
    return toAreaDensity(pdfCameraDirection(scene.camera, normalize(d)), scene.camera.eye, x);
}

// The densities of a path x_0 (on a lamp) ... x_{k-1} (diffuse surfaces), x_k the pinhole, with
// which the light side and the camera side would sample each vertex: from the light x_0 uniform on
// the lamp, x_1 by the lamp's cosine emission, x_{i+1} by x_i's diffuse BSDF (cos / pi) after its
// roulette q(x_i), the pinhole never; from the camera the pinhole (1, a delta), x_{k-1} through
// its pixel, x_{i-1} by x_i's BSDF after q(x_i).
struct PathDensities {
    std::vector<double> fromLight, fromCamera;
};
inline PathDensities densitiesOf(const Scene& scene, const std::vector<SurfacePoint>& x, int lamp) {
    const int k = int(x.size());  // vertices before the pinhole
    PathDensities d{std::vector<double>(k + 1, 0), std::vector<double>(k + 1, 1)};
    d.fromLight[0] = pdfLightPoint(scene, lamp);
    for (int i = 1; i < k; ++i)
        d.fromLight[i] = (i == 1 ? 1 : albedoContinuation(scene, x[i - 1])) * toAreaDensity(cosine(x[i - 1], x[i].p) / kPi, x[i - 1].p, x[i]);
    d.fromCamera[k - 1] = cameraDensity(scene, x[k - 1]);
    for (int i = k - 2; i >= 0; --i) d.fromCamera[i] = albedoContinuation(scene, x[i + 1]) * toAreaDensity(cosine(x[i + 1], x[i].p) / kPi, x[i + 1].p, x[i]);
    return d;
}

// Every strategy s = 0 ... k+1 of the path (s light vertices, the rest from the camera): p_{k,s}
// from the densities, relative to p_{k,ref}, and its balance, power and max weights.
inline std::string strategyRows(const PathDensities& d, int ref) {
    const int n = int(d.fromLight.size());  // vertices, the pinhole included
    std::map<int, double> p;
    for (int s = 0; s <= n; ++s) {
        p[s] = 1;
        for (int i = 0; i < n; ++i) p[s] *= i < s ? d.fromLight[i] : d.fromCamera[i];
    }
    const std::string k = std::to_string(n - 1);
    std::string out = "| s | t | $p_{" + k + ",s}$ | $/\\, p_{" + k + "," + std::to_string(ref) + "}$ | balance | power | max |\n|---|---|---|---|---|---|---|\n";
    for (int s = 0; s <= n; ++s)
        out += "| " + std::to_string(s) + " | " + std::to_string(n - s) + " | " + g4(p[s]) + " | " + g4(p[s] / p[ref]) + " | " +
               format("%.4f", definitionWeight(Heuristic::Balance, p, s)) + " | " + format("%.4f", definitionWeight(Heuristic::Power, p, s)) +
               " | " + format("%g", definitionWeight(Heuristic::Max, p, s)) + " |\n";
    return out;
}

// A path given by its points x_0 (on a lamp) ... x_{k-1}: each point's surface is the one the ray
// from the next point (the pinhole, for x_{k-1}) meets there.
inline std::string pathTable(const Scene& scene, const std::vector<Vec3>& points) {
    std::vector<SurfacePoint> x(points.size());
    Vec3 from = scene.camera.eye;
    for (int i = int(points.size()) - 1; i >= 0; --i) {  // (off the surface it starts on, by far more than its rounding)
        Vec3 d = normalize(points[i] - from);
        Ray ray{from + d * (i + 1 < int(points.size()) ? 1e-4f * (1 + length(from)) : 0.0f), d};
        Hit h = intersect(scene, ray);
        if (!h.found() || length(ray.o + ray.d * h.t - points[i]) > 1e-2f * (1 + length(points[i])))
            throw std::runtime_error("worked-path: the ray from the next vertex does not reach x_" + std::to_string(i));
        x[i] = surfaceAt(scene, ray, h);
        from = x[i].p;
    }
    if (scene.shapes[x[0].shape].light < 0) throw std::runtime_error("worked-path: x_0 is not on a lamp");
    for (const SurfacePoint& v : x)
        if (materialAt(scene, v).type != Material::Diffuse && scene.shapes[v.shape].light < 0)
            throw std::runtime_error("worked-path: a path of diffuse vertices only");
    return strategyRows(densitiesOf(scene, x, x[0].shape), int(points.size()) - 1);
}

inline std::string cornellTable() {
    Scene scene = loadScene("scenes/cornell.scene");
    int lamp = shapeWithLight(scene);
    SurfacePoint x0 = sampleShapePoint(scene, lamp, 0.5f, 0.5f);
    // x_2: the first floor point along row 230 from column 96 (left of the middle, the red wall's side) from which the
    // red wall's point (556, 250, 300) is seen; x_1 that point, which sees the lamp's centre.
    SurfacePoint x1, x2;
    for (int px = 96; px < scene.camera.width; ++px) {
        Ray eyeRay = cameraRay(scene.camera, px + 0.5f, 230.5f);
        Hit floorHit = intersect(scene, eyeRay);
        if (floorHit.shape != 0) continue;
        x2 = surfaceAt(scene, eyeRay, floorHit);
        Ray toWall{x2.p + Vec3(0, 1e-3f, 0), normalize(Vec3(556, 250, 300) - x2.p)};
        Hit wallHit = intersect(scene, toWall);
        if (wallHit.shape != 3) continue;
        x1 = surfaceAt(scene, toWall, wallHit);
        if (!occluded(scene, shadowRay(x1, x0))) break;
    }
    Vec3 eye = scene.camera.eye;
    const PathDensities d = densitiesOf(scene, {x0, x1, x2}, lamp);
    const char* where[4] = {"lamp", "red wall", "floor", "pinhole"};  // shapes 3 and 0 of the scene
    Vec3 at[4] = {x0.p, x1.p, x2.p, eye};
    std::string out = "| vertex | where (mm) | from the light | from the camera | light / camera |\n|---|---|---|---|---|\n";
    for (int i = 0; i < 4; ++i)
        out += "| x_" + std::to_string(i) + " | " + where[i] + " (" + format("%.0f", at[i].x) + ", " + format("%.0f", at[i].y) + ", " +
               format("%.0f", at[i].z) + ") | " + g4(d.fromLight[i]) + " | " + (i == 3 ? std::string("1 (delta)") : g4(d.fromCamera[i])) + " | " +
               (i == 3 ? std::string("0") : g4(d.fromLight[i] / d.fromCamera[i])) + " |\n";
    out += "\n" + strategyRows(d, 2);
    return out;
}

// Refraction into a medium of relative index eta (n_in / n_out) at normal n facing the ray.
inline Vec3 refractThrough(Vec3 d, Vec3 n, double eta) {
    double c = -dot(d, n), k = 1 - eta * eta * (1 - c * c);
    return normalize(d * float(eta) + n * float(eta * c - std::sqrt(k)));
}
// The ray from o along d through a sphere: where it enters and leaves, or false if it misses.
inline bool sphereSpan(Vec3 o, Vec3 d, Vec3 c, double r, double& tIn, double& tOut) {
    Vec3 oc = o - c;
    double b = dot(oc, d), disc = b * b - (dot(oc, oc) - r * r);
    if (disc <= 0) return false;
    tIn = -b - std::sqrt(disc), tOut = -b + std::sqrt(disc);
    return tIn > 0;
}

inline std::string causticTable() {
    Scene scene = loadScene("scenes/glass-box.scene");
    setResolution(scene.camera, 128, 128);
    int lamp = shapeWithLight(scene), ball = -1;
    for (size_t i = 0; i < scene.shapes.size(); ++i)
        if (scene.materials[scene.shapes[i].material].type == Material::Glass) ball = int(i);
    const Shape& sphere = scene.shapes[ball];
    const double eta = scene.materials[sphere.material].ior;
    SurfacePoint D = seenThrough(scene, 90.5f, 115.5f), L;
    Vec3 lampCentre = sampleShapePoint(scene, lamp, 0.5f, 0.5f).p, S2, S1, best(0);
    double bestMiss = 1e30;
    // From D, the direction whose way through the ball ends nearest the lamp's centre, on a grid.
    for (int i = 1; i < 400; ++i)
        for (int j = 0; j < 400; ++j) {
            double theta = 0.5 * kPi * i / 400, phi = 2 * kPi * j / 400;
            Vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(std::sin(theta) * std::sin(phi)));
            double tIn, tOut;
            if (!sphereSpan(D.p, d, sphere.p, sphere.radius, tIn, tOut)) continue;
            Vec3 a = D.p + d * float(tIn), inside = refractThrough(d, normalize(a - sphere.p), 1 / eta);
            double t2 = 0, t3 = 0;
            sphereSpan(a - inside * 1e-3f, inside, sphere.p, sphere.radius, t2, t3);
            Vec3 b = a - inside * 1e-3f + inside * float(t3), nOut = normalize(b - sphere.p);
            if (-dot(inside, -nOut) <= 0 || 1 - eta * eta * (1 - dot(inside, nOut) * dot(inside, nOut)) <= 0) continue;  // total reflection
            Vec3 out = refractThrough(inside, -nOut, eta);
            Ray up{b + out * 1e-3f, out};
            Hit h = intersect(scene, up);
            if (!h.found() || h.shape != lamp) continue;
            Ray first{D.p + d * 1e-3f, d};
            if (intersect(scene, first).shape != ball) continue;
            Vec3 hit = up.o + up.d * h.t;
            double miss = length(hit - lampCentre);
            if (miss < bestMiss) bestMiss = miss, best = d, S2 = a, S1 = b, L = surfaceAt(scene, up, h);
        }
    double pCam = cameraDensity(scene, D), q = albedoContinuation(scene, D), pLight = pdfLightPoint(scene, lamp);
    double ratio = pCam * q / pLight;
    double dLS1 = length(L.p - S1), dS2D = length(S2 - D.p);
    double cosD = absDot(D.ng, normalize(S2 - D.p)), cosS2 = absDot(normalize(S2 - sphere.p), normalize(D.p - S2));
    double cosL = absDot(L.ng, normalize(S1 - L.p)), cosS1 = absDot(normalize(S1 - sphere.p), normalize(L.p - S1));
    double stray = (dLS1 / dS2D) * (dLS1 / dS2D) * (cosD * cosS2) / (cosL * cosS1), pbrt = ratio * stray;
    std::string out = "| | value |\n|---|---|\n";
    out += "| D, the floor point (m) | (" + format("%.3f", D.p.x) + ", " + format("%.3f", D.p.y) + ", " + format("%.3f", D.p.z) + ") |\n";
    out += "| p_cam(D) | " + g4(pCam) + " |\n| q(D) | " + g4(q) + " |\n| p_light(L) | " + g4(pLight) + " |\n";
    out += "| $p_{4,0} / p_{4,4} = p_\\text{cam}(D)\\, q(D) / p_\\text{light}(L)$ | " + g4(ratio) + " |\n";
    out += "| balance weights, s = 0 and t = 1 | " + format("%.4f", ratio / (1 + ratio)) + " and " + format("%.4f", 1 / (1 + ratio)) + " |\n";
    out += "| \\|L - S1\\| and \\|S2 - D\\| (m) | " + format("%.3f", dLS1) + " and " + format("%.3f", dS2D) + " |\n";
    out += "| pbrt's stray factor (\\|L - S1\\| / \\|S2 - D\\|)^2 cos_D cos_S2 / (cos_L cos_S1) | " + g4(stray) + " |\n";
    out += "| pbrt's ratio, and its balance weights | " + g4(pbrt) + ": " + format("%.4f", pbrt / (1 + pbrt)) + " and " +
           format("%.4f", 1 / (1 + pbrt)) + " |\n";
    return out;
}

}  // namespace worked
