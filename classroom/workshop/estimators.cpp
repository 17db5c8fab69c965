// The slides' "Combination of Estimators: Example", made by the renderer: the paths of k = 2
// segments (x_0 the lamp's centre, x_1 what the camera sees through one pixel, x_2 the pinhole)
// along the image's middle column of scenes/cornell.scene, each with its three densities
// (tests/densities.h): A = p_{2,0} (the camera samples x_1, then x_0 by the BSDF, x_1's roulette
// q included), B = p_{2,1} (next event), C = p_{2,2} (light tracing), the same products of
// pdfFwd as in bdpt's MIS walk. Each strategy X estimates the path's f by
// f / p_X, a rectangle of width p_X and height f / p_X: all three have the area f. The max
// heuristic keeps the widest; balance gives each the share p_X / (p_A + p_B + p_C).
//   build/estimators [ROWS...]   one line per image row (all rows if none given):
//   row  surface  p_A p_B p_C  (relative to the largest)  balance weights  max's choice
//   then the lamp's emission cosine toward x_1 and the distance |x_1 - x_0|, the two factors of
//   p_C that change along the wall (page 10 explains row 94 by them)
#include "classroom/workshop/workshop.h"
#include "classroom/workshop/densities.h"

int main(int argc, char** argv) {
    Scene scene = loadScene("scenes/cornell.scene");
    std::vector<int> rows;
    for (int i = 1; i < argc; ++i) rows.push_back(std::atoi(argv[i]));
    if (rows.empty())
        for (int y = 0; y < scene.camera.height; ++y) rows.push_back(y);
    const char* surfaceNames[] = {"floor", "ceiling", "back-wall", "left-wall", "right-wall"};
    std::printf("# row surface pA pB pC wA wB wC max cos_lamp distance\n");
    for (int row : rows) {
        RowPath r = rowPath(scene, row);
        if (!r.path.valid) continue;
        const double* p = r.path.p;
        double largest = std::max({p[0], p[1], p[2]}), sum = p[0] + p[1] + p[2];
        int best = int(std::max_element(p, p + 3) - p);
        std::printf("%d %s %.6g %.6g %.6g %.4f %.4f %.4f %c %.3f %.0f\n", row, r.surface < 5 ? surfaceNames[r.surface] : "block",
                    p[0] / largest, p[1] / largest, p[2] / largest, p[0] / sum, p[1] / sum, p[2] / sum, "ABC"[best], r.cosLamp,
                    r.distance);
    }
    return 0;
}
