// The slides' "Combination of Estimators: Example", made by the renderer: the paths of k = 2
// segments (x_0 the lamp's centre, x_1 what the camera sees through one pixel, x_2 the pinhole)
// along the image's middle column of scenes/cornell.scene, each with its three densities
//   A = p_{2,0}: the camera samples x_1, then x_0 by the BSDF (x_1's roulette q included)
//   B = p_{2,1}: the camera samples x_1, then x_0 on the lamp (next event)
//   C = p_{2,2}: the lamp samples x_0, then x_1 by its emission (light tracing)
// the same products of pdfFwd as in bdpt's MIS walk. Each strategy X estimates the path's f by
// f / p_X, a rectangle of width p_X and height f / p_X: all three have the area f. The max
// heuristic keeps the widest; balance gives each the share p_X / (p_A + p_B + p_C).
//   build/estimators [ROWS...]   one line per image row (all rows if none given):
//   row  surface  p_A p_B p_C  (relative to the largest)  balance weights  max's choice
#include "bench.h"

int main(int argc, char** argv) {
    Scene scene = loadScene("scenes/cornell.scene");
    const Camera& cam = scene.camera;
    int lamp = -1;
    for (size_t i = 0; i < scene.shapes.size(); ++i)
        if (scene.shapes[i].light >= 0) lamp = int(i);
    const Shape& L = scene.shapes[lamp];
    SurfacePoint x0 = sampleShapePoint(scene, lamp, 0.5f, 0.5f);  // the lamp's centre
    std::vector<int> rows;
    for (int i = 1; i < argc; ++i) rows.push_back(std::atoi(argv[i]));
    if (rows.empty())
        for (int y = 0; y < cam.height; ++y) rows.push_back(y);
    const char* surfaceNames[] = {"floor", "ceiling", "back-wall", "left-wall", "right-wall"};
    std::printf("# row surface pA pB pC wA wB wC max\n");
    for (int row : rows) {
        Ray ray = cameraRay(cam, 0.5f * cam.width, row + 0.5f);
        Hit hit = intersect(scene, ray);
        if (!hit.found() || hit.shape == lamp) continue;
        SurfacePoint x1 = surfaceAt(scene, ray, hit);
        if (occluded(scene, shadowRay(x1, x0))) continue;
        Vec3 d = x0.p - x1.p;
        float dist2 = dot(d, d);
        Vec3 w = d / std::sqrt(dist2);                      // x_1 -> x_0
        float cos0 = -dot(L.normal, w), cos1 = absDot(x1.ng, w);
        if (cos0 <= 0) continue;                            // the lamp's back: no path
        Vec3 toX1 = x1.p - cam.eye;
        float camDist2 = dot(toX1, toX1);
        Vec3 dirCam = toX1 / std::sqrt(camDist2);
        double pCam = pdfCameraDirection(cam, dirCam) * absDot(x1.ng, dirCam) / camDist2;  // area density of x_1
        double q = albedoContinuation(scene, x1);
        double pBsdf = pdfBsdf(scene, x1, -dirCam, w) * cos0 / dist2;  // area density of x_0 from x_1
        double pLight = pdfLightPoint(scene, lamp);
        double pEmit = cos0 / kPi * cos1 / dist2;            // area density of x_1 from x_0
        double p[3] = {pCam * q * pBsdf, pCam * pLight, pLight * pEmit};
        double largest = std::max({p[0], p[1], p[2]}), sum = p[0] + p[1] + p[2];
        int best = int(std::max_element(p, p + 3) - p);
        std::printf("%d %s %.6g %.6g %.6g %.4f %.4f %.4f %c\n", row, hit.shape < 5 ? surfaceNames[hit.shape] : "block",
                    p[0] / largest, p[1] / largest, p[2] / largest, p[0] / sum, p[1] / sum, p[2] / sum, "ABC"[best]);
    }
    return 0;
}
