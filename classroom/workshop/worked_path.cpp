// build/worked-path [cornell|caustic]: pages 7 and 10M's paths worked with numbers, as the
// markdown tables those pages show (classroom/workshop/worked_path.h computes them).
#include "classroom/workshop/workshop.h"
#include "classroom/workshop/worked_path.h"

int main(int argc, char** argv) {
    std::string which = argc > 1 ? argv[1] : "cornell";
    if (which != "cornell" && which != "caustic") {
        std::fprintf(stderr, "usage: build/worked-path [cornell|caustic]\n");
        return 2;
    }
    std::fputs((which == "cornell" ? worked::cornellTable() : worked::causticTable()).c_str(), stdout);
    return 0;
}
