// The tests' start: the lecture (bdpt.cpp) without its main, doctest with make test's reporter,
// and what a test of the lecture alone needs. helpers.h puts the classroom before it; the BVH's
// builds as make NATIVE=1 and without SSE (build/native/test_bvh, build/scalar/test_bvh) include
// this alone, so that they compile the lecture and not the classroom's tools.
#pragma once
#ifndef BDPT_NO_MAIN  // helpers.h has included the classroom, and the lecture with it
#define BDPT_NO_MAIN
#include "bdpt.cpp"
#endif
#define DOCTEST_CONFIG_IMPLEMENT
// Each assertion one function call, not a try block of its own: the test programs compile in 15%
// less time; an exception inside an assertion fails its test case instead (doctest's manual).
#define DOCTEST_CONFIG_SUPER_FAST_ASSERTS
#include <doctest/doctest.h>

// make test's reporter (`--reporters=notes`): doctest's console output, except that a MESSAGE,
// which reports a measured number and is no failure, becomes one line "  note file:line: text"
// instead of a block between rules under the test case's name, which looked like a failure.
namespace doctest {
namespace {  // as doctest's own reporters: one per test program
struct NotesReporter : ConsoleReporter {
    using ConsoleReporter::ConsoleReporter;
    void log_message(const MessageData& mb) override {
        if (!(mb.m_severity & assertType::is_warn)) return ConsoleReporter::log_message(mb);
        DOCTEST_LOCK_MUTEX(mutex)
        s << "  note " << mb.m_file << ":" << mb.m_line << ": " << mb.m_string << "\n";
    }
};
}  // namespace
}  // namespace doctest
DOCTEST_REGISTER_REPORTER("notes", 1, doctest::NotesReporter);

// The test program's main: doctest's; or, given --as-bdpt first (helpers.h, where the classroom
// is included), ./bdpt's own main (classroomMain), so that a test of the running program (Ctrl-C,
// --live, a memory limit) starts the program the tests were built with, not a second compile.
int main(int argc, char** argv) {
#ifdef BDPT_TEST_PROGRAM_IS_BDPT
    if (argc > 1 && std::string(argv[1]) == "--as-bdpt") {
        argv[1] = argv[0];
        return classroomMain(argc - 1, argv + 1);
    }
#endif
    return doctest::Context(argc, argv).run();
}

inline Scene sceneAt(const std::string& file, int width, int height) {
    Scene s = loadScene(file);
    setResolution(s.camera, width, height);
    return s;
}

// One thread: make test runs as many test files at once as there are cores, and a render's
// threads, started afresh every pass, cost the small images of the tests 5-8% more CPU. The image
// does not depend on the number of threads (tests that say so set it).
inline RenderOptions quietOptions(Method m, int spp, uint64_t seed = 1) {
    RenderOptions o;
    o.method = m;
    o.spp = spp;
    o.seed = seed;
    o.threads = 1;
    return o;
}
