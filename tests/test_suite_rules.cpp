// The suite's own rules, checked on its files: tests/README.md's "No test measures time".
#include "helpers.h"
#include <dirent.h>
#include <functional>
#include <regex>

// tests/README.md's rule "No test measures time", checked on the suite's own files: every
// assertion whose code (its strings and comments aside) names a clock, a duration or a speed
// carries the words "not a timing threshold:" on its lines or the comment above, with the budget it
// compares (--time T against the CPU seconds spent) or why no time is compared (the formatting of
// a duration). A threshold on how fast the machine is has no such reason to give. It reads names:
// a test keeps a duration in a variable named for its clock (cpuUsed, wallSeconds).
static std::vector<std::string> checksWithoutBudget(const std::string& file, const std::string& text) {
    const bool python = file.size() > 3 && file.substr(file.size() - 3) == ".py";
    // "second" but not std::pair's .second (r.seconds is a clock).
    static const std::regex clockWord("(^|[^.])second|\\.seconds|elapsed|wall|speed|duration|millis|micros|nanos|minute|hour|cpu|clock|timing|timeout|"
                                      "latency|perf_counter|monotonic|rusage|\\btime\\b|\\bfps\\b|per_?sec|\\bhz\\b",
                                      std::regex::icase);
    // Units in names, any case: tookMs, tookMS, elapsed_us, rayNs; not the "ms" of "items".
    static const std::regex milliseconds("\\b(ms|us|ns|MS|US|NS)\\b|[a-z](Ms|MS|Us|US|Ns|NS)\\b|_(ms|us|ns|MS|US|NS)\\b");
    const std::regex assertion(python ? "(^|[^a-z_.])check\\(" : "\\b(CHECK|REQUIRE|WARN)(_[A-Z]+)?\\s*\\(");
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    std::vector<std::string> found;
    for (size_t i = 0; i < lines.size(); ++i) {
        std::smatch m;
        const std::string head = lines[i].substr(0, lines[i].find(python ? "#" : "//"));
        if (!std::regex_search(head, m, assertion) || (python && head.find("def check(") != std::string::npos)) continue;
        // The statement from its "(" to the matching ")", strings and comments left out.
        std::string code;
        int depth = 0;
        size_t line = i, at = size_t(m.position(0) + m.length(0)) - 1;
        for (bool done = false; !done && line < lines.size(); ++line, at = 0) {
            const std::string& l = lines[line];
            for (; at < l.size(); ++at) {
                char c = l[at];
                if ((!python && c == '/' && at + 1 < l.size() && l[at + 1] == '/') || (python && c == '#')) break;
                if (c == '"' || (python && c == '\'')) {
                    for (++at; at < l.size() && l[at] != c; ++at) at += l[at] == '\\';
                    continue;
                }
                code += c;
                if (c == '(') ++depth;
                if (c == ')' && --depth == 0) { done = true; break; }
            }
            if (done) break;
        }
        if (!std::regex_search(code, clockWord) && !std::regex_search(code, milliseconds)) continue;
        size_t first = i;  // the comment lines right above belong to it
        while (first > 0 && lines[first - 1].find_first_not_of(' ') != std::string::npos &&
               lines[first - 1].compare(lines[first - 1].find_first_not_of(' '), python ? 1 : 2, python ? "#" : "//") == 0)
            --first;
        bool marked = false;
        for (size_t k = first; k <= std::min(line, lines.size() - 1); ++k)
            marked = marked || lines[k].find("not a timing threshold:") != std::string::npos;
        if (!marked) found.push_back(file + ":" + std::to_string(i + 1) + ": " + lines[i].substr(lines[i].find_first_not_of(' ')));
    }
    return found;
}
TEST_CASE("no test measures time: every check that names a clock says which budget it compares") {
    // The rule's own check must bite: a speed threshold, a share of CPU, a wall budget are found;
    // a count, a clock named in a string, and a budget with its reason are not.
    CHECK(checksWithoutBudget("x.cpp", "    CHECK(seconds < 5);\n").size() == 1);
    CHECK(checksWithoutBudget("x.cpp", "    CHECK(wallSeconds(t0) <\n          2.5);\n").size() == 1);
    CHECK(checksWithoutBudget("x.py", "    check(ratio >= 0.5, \"speed\", \"%.2f\" % (page_cpu, cpu))\n").size() == 1);
    CHECK(checksWithoutBudget("x.py", "    check(first_frame_ms < 500, \"fast\")\n").size() == 1);
    // Clock names with capitals, other units, Python's clocks.
    CHECK(checksWithoutBudget("x.cpp", "    CHECK(tookMS < 500);\n").size() == 1);
    CHECK(checksWithoutBudget("x.cpp", "    REQUIRE(WallSeconds(t0) < 2);\n").size() == 1);
    CHECK(checksWithoutBudget("x.cpp", "    CHECK(rayNs < 90);\n    CHECK(Minutes < 2);\n").size() == 2);
    CHECK(checksWithoutBudget("x.py", "    check(time.perf_counter() - t0 < 3, \"quick\")\n").size() == 1);
    CHECK(checksWithoutBudget("x.cpp", "    CHECK(r.seconds < 3);\n").size() == 1);
    CHECK(checksWithoutBudget("x.cpp", "    CHECK(items.size() == 4);\n    CHECK(forms == 2);\n    CHECK(p.second == 10);\n").empty());
    CHECK(checksWithoutBudget("x.cpp", "    CHECK(redraws <= 12);\n    CHECK(contains(r.out, \"CPU s on 1 thread\"));\n").empty());
    CHECK(checksWithoutBudget("x.cpp", "    // not a timing threshold: --time's budget\n    CHECK(cpuUsed < 0.85);\n").empty());
    CHECK(checksWithoutBudget("x.py", "def check(ok, what, detail=\"\"):\n    check(n == 4, \"a --time run\")\n").empty());
    // Every file of tests/ and its folders that holds checks: C++, headers and Python.
    std::vector<std::string> found, files;
    std::function<void(const std::string&)> walk = [&](const std::string& folder) {
        DIR* dir = opendir(folder.c_str());
        REQUIRE(dir);
        for (dirent* e; (e = readdir(dir));) {
            const std::string n = e->d_name, path = folder + "/" + n;
            auto endsWith = [&](const std::string& x) { return n.size() > x.size() && n.compare(n.size() - x.size(), x.size(), x) == 0; };
            if (n[0] == '.' || n == "refs" || n == "bad_scenes") continue;
            if (e->d_type == DT_DIR) walk(path);
            else if (endsWith(".cpp") || endsWith(".h") || endsWith(".py")) files.push_back(path);
        }
        closedir(dir);
    };
    walk("tests");
    for (const std::string& f : files)
        for (const std::string& w : checksWithoutBudget(f, readFile(f))) found.push_back(w);
    int homework = 0;
    for (const std::string& f : files) homework += f.rfind("tests/homework/", 0) == 0;
    for (const std::string& f : found) MESSAGE(f);
    MESSAGE(files.size() << " files read, " << homework << " of them in tests/homework/");
    CHECK(files.size() >= 20);
    CHECK(homework >= 2);
    CHECK(found.empty());
}

