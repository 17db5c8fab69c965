// build/worked-path [cornell|caustic]: pages 7 and 10M's paths worked with numbers, as the
// markdown tables those pages show (classroom/workshop/worked_path.h computes them).
// build/worked-path path SCENE WxH X,Y,Z ...: any path of diffuse vertices from a lamp (x_0) to the
// pinhole of SCENE rendered at WxH, given by its points x_0 ... x_{k-1}: every strategy's density
// and weights (the page's path view draws one sample's paths; make test-web compares them).
// It needs the lecture alone: make homework hands it out (tools/), built there by make build/worked-path.
#define BDPT_NO_MAIN
#include "bdpt.cpp"
#include "physics.h"  // classroom/, or the student's grader/
#include "worked_path.h"

static int usage() {
    std::fprintf(stderr, "usage: build/worked-path [cornell|caustic]\n       build/worked-path path SCENE WxH X,Y,Z X,Y,Z ...\n");
    return 2;
}

int main(int argc, char** argv) {
    std::string which = argc > 1 ? argv[1] : "cornell";
    if (which == "path") {
        int w = 0, h = 0;
        if (argc < 6 || std::sscanf(argv[3], "%dx%d", &w, &h) != 2) return usage();
        std::vector<Vec3> points;
        for (int i = 4; i < argc; ++i) {
            Vec3 p;
            if (std::sscanf(argv[i], "%f,%f,%f", &p.x, &p.y, &p.z) != 3) return usage();
            points.push_back(p);
        }
        try {
            Scene scene = loadScene(argv[2]);
            setResolution(scene.camera, w, h);
            std::fputs(worked::pathTable(scene, points).c_str(), stdout);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s\n", e.what());
            return 1;
        }
        return 0;
    }
    if (which != "cornell" && which != "caustic") return usage();
    std::fputs((which == "cornell" ? worked::cornellTable() : worked::causticTable()).c_str(), stdout);
    return 0;
}
