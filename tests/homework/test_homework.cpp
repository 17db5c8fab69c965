// make test-homework: the homework's cutter and grader (classroom/homework/), from outside, as a
// teacher and a student use them. The solution (bdpt.cpp) gets every point, the file handed out
// (every task's stubs) none and compiles; each plausible wrong implementation of
// tests/homework/mistakes.txt, applied alone to the solution, loses its task's points, and no
// other task's, and the grader's words name it; a crash, a NaN, an endless loop and a 10-GB
// allocation each cost their task, with the words given, and the grading run goes on; the
// student's folder holds no line of any cut body, nor do the notes; make homework TASKS="H2 H5"
// cuts those two alone and refuses to overwrite a folder a student has worked in.
// Its programs compile side by side, as many as the machine has cores: about 35 compiles of the
// lecture with the grader, at -O1 (the grader's words, not its speed, are under test here).
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
#include <dirent.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>
#include "mistakes.h"

namespace {

const std::string kDir = "build/homework-test";

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
void writeFile(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }
std::string squeeze(const std::string& s) {  // runs of white space as one space: wrapped words still match
    std::string out;
    for (char c : s) {
        bool space = c == ' ' || c == '\n' || c == '\t';
        if (!(space && !out.empty() && out.back() == ' ')) out += space ? ' ' : c;
    }
    return out;
}
int shell(const std::string& command) {
    int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// -- a grading's report: each task's points and its notes
struct Report {
    std::map<std::string, std::pair<int, int>> points;
    std::map<std::string, std::string> notes;
    int total = -1, max = -1;
    std::string notesOf(const std::string& task) const { return notes.count(task) ? notes.at(task) : ""; }
    std::string text;
};
Report readReport(const std::string& text) {
    Report r;
    r.text = text;
    static const std::regex task("^(H[0-9]) .* ([0-9]+) / ([0-9]+)$"), total("^total ([0-9]+) / ([0-9]+)$");
    std::istringstream in(text);
    std::string current;
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_match(line, m, task)) current = m[1], r.points[current] = {std::stoi(m[2]), std::stoi(m[3])};
        else if (std::regex_match(line, m, total)) r.total = std::stoi(m[1]), r.max = std::stoi(m[2]);
        else if (line.rfind("    ", 0) == 0 && !current.empty()) r.notes[current] += line + "\n";
    }
    return r;
}

// -- the programs: the grader compiled with each variant, all at once on the machine's cores
struct Job {
    std::string dir, source, gradeArgs;
};
void runJobs(const std::vector<Job>& jobs) {
    const size_t cores = std::max(1u, std::thread::hardware_concurrency());
    std::vector<pid_t> running;
    auto reap = [&] {
        pid_t done = wait(nullptr);
        running.erase(std::remove(running.begin(), running.end(), done), running.end());
    };
    for (const Job& j : jobs) {
        while (running.size() >= cores) reap();
        pid_t pid = fork();
        if (pid == 0) {
            std::string command = "g++ -O1 -std=c++17 -Wall -Wextra -pthread -I" + j.dir + " -Iclassroom -o " + j.dir + "/grade classroom/homework/grade.cpp -lstb -pthread > " +
                                  j.dir + "/compile.log 2>&1 && " + j.dir + "/grade --data build/homework-data --tasks " + kDir + "/tasks.txt " +
                                  j.gradeArgs + " > " + j.dir + "/grade.log 2>&1";
            execl("/bin/sh", "sh", "-c", command.c_str(), (char*)nullptr);
            _exit(127);
        }
        running.push_back(pid);
    }
    while (!running.empty()) reap();
}

struct Results {
    std::vector<Mistake> mistakes;
    std::vector<Report> reports;  // one per mistake
    Report solution, stubs, answered;
    std::string solutionSource;
};
const Results& results() {
    static Results r = [] {
        Results out;
        shell("rm -rf " + kDir + " && mkdir -p " + kDir);
        // every task, the optional one too
        REQUIRE(shell("build/homework-tools/cut classroom/homework/tasks --list 'H1 H2 H3 H4 H5 H6' > " + kDir + "/tasks.txt") == 0);
        out.solutionSource = readFile("bdpt.cpp");
        out.mistakes = readMistakes();
        std::vector<Job> jobs;
        for (size_t i = 0; i < out.mistakes.size(); ++i) {
            std::string source = out.solutionSource;
            for (const auto& [from, to] : out.mistakes[i].edits) {
                size_t at = source.find(from);
                CAPTURE(out.mistakes[i].what);
                CAPTURE(from);
                REQUIRE(at != std::string::npos);
                REQUIRE(source.find(from, at + 1) == std::string::npos);  // once: the mistake is where it says
                source.replace(at, from.size(), to);
            }
            const std::string dir = kDir + "/m" + std::to_string(i);
            shell("mkdir -p " + dir);
            writeFile(dir + "/bdpt.cpp", source);
            // an endless loop meets a short CPU limit here (it is the same limit, a tenth of it)
            jobs.push_back({dir, source, out.mistakes[i].kind == "robust" ? "--cpu-limit 6" : ""});
        }
        const std::string solution = kDir + "/solution";
        shell("mkdir -p " + solution + " && cp bdpt.cpp " + solution + "/");
        jobs.push_back({solution, "", ""});
        runJobs(jobs);
        for (size_t i = 0; i < out.mistakes.size(); ++i) out.reports.push_back(readReport(readFile(kDir + "/m" + std::to_string(i) + "/grade.log")));
        out.solution = readReport(readFile(solution + "/grade.log"));
        // the folder a student gets, every task cut, graded by its own Makefile
        shell("make -s homework HOMEWORK_DIR=" + kDir + "/folder TASKS='H1 H2 H3 H4 H5 H6' > " + kDir + "/make-homework.log 2>&1");
        shell("make -s -C " + kDir + "/folder grade > " + kDir + "/stubs.log 2>&1");
        out.stubs = readReport(readFile(kDir + "/stubs.log"));
        // then a right answer written into the file handed out (each TODO kept, its stub replaced
        // by the task's answer), graded again in the same folder by its own Makefile
        shell("mkdir -p " + kDir + "/answered/grader && build/homework-tools/cut classroom/homework/tasks bdpt.cpp " + kDir +
              "/answered 'H1 H2 H3 H4 H5 H6' --answered > /dev/null && cp " + kDir + "/answered/bdpt.cpp " + kDir + "/folder/bdpt.cpp");
        shell("make -s -C " + kDir + "/folder grade > " + kDir + "/answered.log 2>&1");
        out.answered = readReport(readFile(kDir + "/answered.log"));
        return out;
    }();
    return r;
}

// The non-trivial code lines of a body cut from bdpt.cpp: what a student's folder must not hold.
std::vector<std::string> cutLines(const std::string& solution, const std::string& handedOut) {
    std::set<std::string> kept;
    std::istringstream h(handedOut);
    for (std::string line; std::getline(h, line);) kept.insert(line);
    std::vector<std::string> lines;
    std::istringstream s(solution);
    for (std::string line; std::getline(s, line);) {
        std::string t = line.substr(std::min(line.size(), line.find_first_not_of(' ')));
        if (kept.count(line) || t.size() < 24 || t.rfind("//", 0) == 0) continue;
        lines.push_back(t);
    }
    return lines;
}

}  // namespace

TEST_CASE("the solution, bdpt.cpp, gets every point of every task") {
    const Report& r = results().solution;
    MESSAGE(r.text);
    REQUIRE(r.max == 60);
    CHECK(r.total == 60);
}

TEST_CASE("a right answer written into the file handed out, graded in the same folder after its stubs, gets every point") {
    const Report& r = results().answered;
    MESSAGE(r.text);
    const std::string answered = readFile(kDir + "/answered/bdpt.cpp");
    CHECK(answered.find("TODO (H3, ") != std::string::npos);  // the handed-out file, its TODOs kept
    CHECK(answered.find("float etaScale = 1;") == std::string::npos);  // its stubs replaced
    REQUIRE(r.max == 60);
    CHECK(r.total == 60);
}

TEST_CASE("the file handed out compiles, and its stubs get no point in any task") {
    const Report& r = results().stubs;
    MESSAGE(readFile(kDir + "/make-homework.log"));
    CHECK(r.points.size() == 6);
    for (const auto& [task, p] : r.points) {
        CAPTURE(task);
        CHECK(p.first == 0);
        CHECK(p.second == 10);
    }
    CHECK(r.total == 0);
}

TEST_CASE("each plausible mistake loses its task's points and no other's, and the grader names it") {
    const Results& all = results();
    int mistakes = 0;
    std::map<std::string, int> perTask;
    for (size_t i = 0; i < all.mistakes.size(); ++i) {
        const Mistake& m = all.mistakes[i];
        if (m.kind != "mistake") continue;
        const Report& r = all.reports[i];
        CAPTURE(m.task);
        CAPTURE(m.what);
        CAPTURE(r.text);
        REQUIRE(r.points.count(m.task));
        CHECK(r.points.at(m.task).first < r.points.at(m.task).second);
        for (const auto& [task, p] : r.points)
            if (task != m.task) CHECK(p.first == p.second);
        CHECK(squeeze(r.notesOf(m.task)).find(m.words) != std::string::npos);
        for (const std::string& other : m.never) {  // a mistake that is not this one is not named
            CAPTURE(other);
            CHECK(squeeze(r.notesOf(m.task)).find(other) == std::string::npos);
        }
        MESSAGE(m.task << " " << m.what << ": " << r.points.at(m.task).first << " / " << r.points.at(m.task).second);
        ++mistakes, ++perTask[m.task];
    }
    for (const char* task : {"H1", "H2", "H3", "H4", "H5", "H6"}) {
        CAPTURE(task);
        CHECK(perTask[task] >= 3);
    }
    CHECK(mistakes >= 18);
}

TEST_CASE("a crash, a NaN, an endless loop and a 10-GB allocation cost their task, and the grading goes on") {
    const Results& all = results();
    std::set<std::string> kinds;
    for (size_t i = 0; i < all.mistakes.size(); ++i) {
        const Mistake& m = all.mistakes[i];
        if (m.kind != "robust") continue;
        const Report& r = all.reports[i];
        CAPTURE(m.what);
        CAPTURE(r.text);
        CHECK(r.total >= 0);  // the report's last line: the run went on to the end
        REQUIRE(r.points.count(m.task));
        CHECK(r.points.at(m.task).first < r.points.at(m.task).second);
        for (const auto& [task, p] : r.points)
            if (task != m.task) CHECK(p.first == p.second);
        CHECK(squeeze(r.notesOf(m.task)).find(m.words) != std::string::npos);
        kinds.insert(m.what.substr(0, m.what.find(' ', 2)));
    }
    CHECK(kinds.size() == 4);
}

TEST_CASE("the student's folder holds no line of a cut body, and the notes none either") {
    results();
    const std::string folder = kDir + "/folder";
    const std::string handedOut = readFile(folder + "/grader/handed-out.cpp");  // the folder's bdpt.cpp as handed out (it was answered since)
    std::vector<std::string> cut = cutLines(results().solutionSource, handedOut);
    MESSAGE(cut.size() << " code lines cut from bdpt.cpp");
    CHECK(cut.size() > 60);
    std::vector<std::string> files = {folder + "/README.md", folder + "/Makefile", folder + "/grader/grade.cpp", folder + "/grader/physics.h",
                                      folder + "/grader/tasks.txt", folder + "/grader/handed-out.cpp"};
    DIR* notes = opendir("lecture_notes");
    for (dirent* e; notes && (e = readdir(notes));)
        if (std::string(e->d_name).size() > 3 && std::string(e->d_name).substr(std::string(e->d_name).size() - 3) == ".md")
            files.push_back(std::string("lecture_notes/") + e->d_name);
    if (notes) closedir(notes);
    int found = 0;
    for (const std::string& f : files) {
        const std::string text = readFile(f);
        REQUIRE(!text.empty());
        for (const std::string& line : cut)
            if (text.find(line) != std::string::npos) {
                MESSAGE(f << " holds a cut line: " << line);
                ++found;
            }
    }
    CHECK(found == 0);
    // and no binary of the solution: the folder's only programs are what its own Makefile builds
    CHECK(shell("test -z \"$(find " + folder + " -type f -perm -u+x ! -path '*/build/*' ! -name bdpt)\"") == 0);
}

TEST_CASE("make homework TASKS='H2 H5' cuts those two alone, and never overwrites a folder worked in") {
    results();
    const std::string folder = kDir + "/two";
    REQUIRE(shell("make -s homework HOMEWORK_DIR=" + folder + " TASKS='H2 H5' > " + kDir + "/two.log 2>&1") == 0);
    const std::string text = readFile(folder + "/bdpt.cpp"), readme = readFile(folder + "/README.md");
    CHECK(text.find("TODO (H2, ") != std::string::npos);
    CHECK(text.find("TODO (H5, ") != std::string::npos);
    for (const char* other : {"TODO (H1, ", "TODO (H3, ", "TODO (H4, ", "TODO (H6, "}) CHECK(text.find(other) == std::string::npos);
    CHECK(text.find("L += beta * emittedRadiance(scene, sp, wo);") != std::string::npos);  // H1's body is there, the lecture's
    CHECK(readme.find("### H2 ") != std::string::npos);
    CHECK(readme.find("### H1 ") == std::string::npos);
    CHECK(readFile(folder + "/grader/tasks.txt").substr(0, 3) == "H2 ");
    // a student's work is not overwritten: the folder is left as it was
    writeFile(folder + "/bdpt.cpp", text + "\n// a student's line\n");
    CHECK(shell("make -s homework HOMEWORK_DIR=" + folder + " TASKS='H2 H5' > " + kDir + "/again.log 2>&1") != 0);
    CHECK(readFile(kDir + "/again.log").find("has been worked on since it was handed out") != std::string::npos);
    CHECK(readFile(folder + "/bdpt.cpp").find("// a student's line") != std::string::npos);
    // a task the list does not have is named as such, with the ones it has
    CHECK(shell("make -s homework HOMEWORK_DIR=" + kDir + "/none TASKS='H9' > " + kDir + "/none.log 2>&1") != 0);
    CHECK(readFile(kDir + "/none.log").find("no task H9 (the tasks: H1 H2 H3 H4 H5 H6)") != std::string::npos);
}

TEST_CASE("make grade HOMEWORK=FILE grades a file anywhere, with the tasks of the folder it is in") {
    results();
    const std::string file = kDir + "/two/bdpt.cpp";  // its student line added above: still the stubs of H2 and H5
    REQUIRE(shell("make -s grade HOMEWORK=" + file + " > " + kDir + "/grade-two.log 2>&1") == 0);
    Report r = readReport(readFile(kDir + "/grade-two.log"));
    MESSAGE(r.text);
    CHECK(r.points.size() == 2);
    CHECK(r.total == 0);
    CHECK(r.max == 20);
}
