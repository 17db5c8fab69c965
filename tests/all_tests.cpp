// make test: every test file in one program, so that bdpt.cpp is compiled once. Each file keeps
// its own namespace (their helpers may share names); what they include comes first, so that the
// includes inside the namespaces find their guards set. `make test` runs this program once per
// file (doctest's --source-file), one line each.
#include "helpers.h"
#include "bench.h"
#include "classroom/workshop/densities.h"
#include "classroom/physics.h"
#include "classroom/definitions.h"
#include "homework/mistakes.h"
#include <dirent.h>
#include <poll.h>
#include <pty.h>
#include <functional>
#include <locale>
#include <set>
#include <sstream>
// std::regex: test_notes reads the notes with it (first, as above).
#include <regex>

namespace test_bdpt {
#include "test_bdpt.cpp"
}
namespace test_bvh {
#include "test_bvh.cpp"
}
namespace test_core {
#include "test_core.cpp"
}
namespace test_first_hour {
#include "test_first_hour.cpp"
}
namespace test_lecture {
#include "test_lecture.cpp"
}
namespace test_metrics {
#include "test_metrics.cpp"
}
namespace test_mlt {
#include "test_mlt.cpp"
}
namespace test_notes {
#include "test_notes.cpp"
}
namespace test_numerics {
#include "test_numerics.cpp"
}
namespace test_robustness {
#include "test_robustness.cpp"
}
namespace test_sampling {
#include "test_sampling.cpp"
}
namespace test_sampler {
#include "test_sampler.cpp"
}
namespace test_suite_rules {
#include "test_suite_rules.cpp"
}
namespace test_transport {
#include "test_transport.cpp"
}
namespace test_vcm {
#include "test_vcm.cpp"
}
namespace test_veach {
#include "test_veach.cpp"
}
