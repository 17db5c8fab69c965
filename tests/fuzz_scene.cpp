// libFuzzer harness for the scene parser (make fuzz): any input must either parse or be rejected
// with an InputError; a crash, a leak, a sanitizer report or a hang is a bug, and its input
// becomes a file in tests/bad_scenes/.
#define BDPT_NO_MAIN
#include "bdpt.cpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        Scene scene = parseScene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.scene");
        if (scene.shapes.size() > 0) intersect(scene, cameraRay(scene.camera, 0.5f, 0.5f));  // the BVH it built works
    } catch (const InputError&) {
    }
    return 0;
}
