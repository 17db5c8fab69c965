// make test-homework: the homework's cutter and grader (classroom/homework/), from outside, as a
// teacher and a student use them. The solution (bdpt.cpp) gets every point, the file handed out
// (every task's stubs) none and compiles; each plausible wrong implementation of
// tests/homework/mistakes.txt, applied alone to the solution, loses its task's points, and no
// other task's, and the grader's words name it; a crash, a NaN, an endless loop and a 10-GB
// allocation each cost their task, with the words given, and the grading run goes on; the
// student's folder holds no line of any cut body, nor do the notes; make homework TASKS="H2 H5"
// cuts those two alone and refuses to overwrite a folder a student has worked in. The course's
// side: the teacher's grader (hidden.h) on the solution and on the mistakes only it catches,
// make grade-class on eight folders against the exact gradebook, make gradescope's package in a
// simulated Gradescope tree. Its programs compile side by side, as many as the machine has cores:
// about 60 compiles of the lecture with the grader, at -O1 (the grader's words, not its speed,
// are under test here).
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
    std::map<std::string, std::pair<int, int>> points, hidden;  // hidden: the teacher's grade alone
    int hiddenTotal = -1, hiddenMax = -1;
    std::map<std::string, std::string> notes;
    int total = -1, max = -1;
    std::string notesOf(const std::string& task) const { return notes.count(task) ? notes.at(task) : ""; }
    std::string text;
};
Report readReport(const std::string& text) {
    Report r;
    r.text = text;
    static const std::regex task("^(H[0-9]) .*? ([0-9]+) / ([0-9]+)(, hidden ([0-9]+) / ([0-9]+))?$"), total("^total ([0-9]+) / ([0-9]+)(, hidden ([0-9]+) / ([0-9]+))?$");
    std::istringstream in(text);
    std::string current;
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_match(line, m, task)) {
            current = m[1], r.points[current] = {std::stoi(m[2]), std::stoi(m[3])};
            if (m[4].matched) r.hidden[current] = {std::stoi(m[5]), std::stoi(m[6])};
        } else if (std::regex_match(line, m, total)) {
            r.total = std::stoi(m[1]), r.max = std::stoi(m[2]);
            if (m[3].matched) r.hiddenTotal = std::stoi(m[4]), r.hiddenMax = std::stoi(m[5]);
        }
        else if (line.rfind("    ", 0) == 0 && !current.empty()) r.notes[current] += line + "\n";
    }
    return r;
}

// -- the programs: the grader compiled with each variant, all at once on the machine's cores
struct Job {
    std::string dir, source, gradeArgs, compileArgs = "";  // -DBDPT_HIDDEN_CHECKS: the teacher's grader
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
            std::string command = "g++ -O1 -std=c++17 -Wall -Wextra -pthread " + j.compileArgs + " -I" + j.dir + " -Iclassroom -o " + j.dir + "/grade classroom/homework/grade.cpp -lstb -pthread > " +
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
    Report solution, stubs, answered, solutionTeacher;
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
            jobs.push_back({dir, source, out.mistakes[i].kind == "robust" ? "--cpu-limit 6" : "",
                            out.mistakes[i].kind == "hidden" ? "-DBDPT_HIDDEN_CHECKS" : ""});
        }
        const std::string solution = kDir + "/solution";
        shell("mkdir -p " + solution + " && cp bdpt.cpp " + solution + "/");
        jobs.push_back({solution, "", ""});
        const std::string teacher = kDir + "/solution-teacher";  // the teacher's grade: the public checks and hidden.h's
        shell("mkdir -p " + teacher + " && cp bdpt.cpp " + teacher + "/");
        jobs.push_back({teacher, "", "", "-DBDPT_HIDDEN_CHECKS"});
        runJobs(jobs);
        for (size_t i = 0; i < out.mistakes.size(); ++i) out.reports.push_back(readReport(readFile(kDir + "/m" + std::to_string(i) + "/grade.log")));
        out.solution = readReport(readFile(solution + "/grade.log"));
        out.solutionTeacher = readReport(readFile(teacher + "/grade.log"));
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
    auto trimmed = [](const std::string& line) { return line.substr(std::min(line.size(), line.find_first_not_of(' '))); };
    std::set<std::string> kept;  // a line that stands uncut elsewhere too (materialAt's) reveals nothing
    std::istringstream h(handedOut);
    for (std::string line; std::getline(h, line);) kept.insert(trimmed(line));
    std::vector<std::string> lines;
    std::istringstream s(solution);
    for (std::string line; std::getline(s, line);) {
        std::string t = trimmed(line);
        if (kept.count(t) || t.size() < 24 || t.rfind("//", 0) == 0) continue;
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

TEST_CASE("the teacher's grade: the solution gets every public and every hidden point, and the hidden checks are the teacher's alone") {
    const Report& r = results().solutionTeacher;
    MESSAGE(r.text);
    CHECK(r.max == 60);
    CHECK(r.total == 60);
    CHECK(r.hiddenMax >= 6);  // at least one hidden check a task
    CHECK(r.hiddenTotal == r.hiddenMax);
    for (const char* task : {"H1", "H2", "H3", "H4", "H5", "H6"}) {
        CAPTURE(task);
        REQUIRE(r.hidden.count(task));
        CHECK(r.hidden.at(task).second > 0);
    }
    CHECK(results().solution.hiddenMax == -1);  // the student's grader has none
}

// A mistake loses points in its own task (`caught`: the public points, or the hidden ones), every
// other task keeps all of its public points, and its task's notes name the mistake.
void checkCaughtInItsTaskAlone(const Mistake& m, const Report& r, const std::map<std::string, std::pair<int, int>>& caught) {
    CAPTURE(m.task);
    CAPTURE(m.what);
    CAPTURE(r.text);
    REQUIRE(caught.count(m.task));
    CHECK(caught.at(m.task).first < caught.at(m.task).second);
    for (const auto& [task, p] : r.points)
        if (task != m.task) CHECK(p.first == p.second);
    CHECK(squeeze(r.notesOf(m.task)).find(m.words) != std::string::npos);
}

TEST_CASE("each mistake only a hidden check catches loses hidden points in its task, and no other's, and is named") {
    const Results& all = results();
    int hidden = 0;
    for (size_t i = 0; i < all.mistakes.size(); ++i) {
        const Mistake& m = all.mistakes[i];
        if (m.kind != "hidden") continue;
        const Report& r = all.reports[i];
        checkCaughtInItsTaskAlone(m, r, r.hidden);
        CHECK(squeeze(r.notesOf(m.task)).find("[hidden]") != std::string::npos);
        ++hidden;
    }
    CHECK(hidden >= 2);
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
        checkCaughtInItsTaskAlone(m, r, r.points);
        CAPTURE(m.what);
        CAPTURE(r.text);
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
    std::vector<std::string> files = {folder + "/README.md", folder + "/Makefile", folder + "/grader/grade.cpp", folder + "/grader/harness.h", folder + "/grader/physics.h",
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
    // the folder's notes: every page, none with the answers for the instructor
    int pages = 0, answers = 0;
    DIR* copied = opendir((folder + "/lecture_notes").c_str());
    for (dirent* e; copied && (e = readdir(copied));) {
        const std::string name = e->d_name;
        if (name.size() < 4 || name.substr(name.size() - 3) != ".md") continue;
        ++pages;
        answers += readFile(folder + "/lecture_notes/" + name).find("(for the instructor)") != std::string::npos;
    }
    if (copied) closedir(copied);
    CHECK(pages >= 25);
    CHECK(answers == 0);
    CHECK(shell("test ! -e " + folder + "/grader/hidden.h") == 0);  // the teacher's checks stay the teacher's
    // the notes' worked path, built in the folder from the lecture alone: page 7's table, as here
    REQUIRE(shell("make -s -C " + folder + " build/worked-path > " + kDir + "/worked-path-build.log 2>&1") == 0);
    REQUIRE(shell("(cd " + folder + " && build/worked-path cornell > ../worked-path-folder.txt) && build/worked-path cornell > " + kDir +
                  "/worked-path-repo.txt") == 0);
    CHECK(readFile(kDir + "/worked-path-folder.txt") == readFile(kDir + "/worked-path-repo.txt"));
    CHECK(readFile(kDir + "/worked-path-repo.txt").find("| s | t |") != std::string::npos);
    CHECK(readFile("lecture_notes/07-probabilities.md").find("### Answers (for the instructor)") != std::string::npos);  // the teacher's copy
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

// -- a course: the class graded in one command, and the Gradescope package
// A student's file: the solution with one mistake of mistakes.txt applied (by what it says).
std::string withMistake(const std::string& what) {
    std::string source = readFile("bdpt.cpp");
    for (const Mistake& m : readMistakes())
        if (m.what == what)
            for (const auto& [from, to] : m.edits) source.replace(source.find(from), from.size(), to);
    return source;
}
const Report& reportOf(const std::string& what) {
    const Results& all = results();
    for (size_t i = 0; i < all.mistakes.size(); ++i)
        if (all.mistakes[i].what == what) return all.reports[i];
    throw std::runtime_error("no mistake " + what);
}
// The teacher's tools compile at -O1 here, as the mistakes' graders do (their words are under test).
const std::string kTeacherFlags = "GRADE_CXXFLAGS='-O1 -std=c++17 -pthread' ";

TEST_CASE("make grade-class: seven students into a gradebook, the exact CSV, and a report that counts their mistakes") {
    results();
    const std::string subs = kDir + "/class";
    const std::string firstHit = "emission counted at the first hit only", etaNotSquared = "eta where the rule has eta squared",
                      seenTwice = "the light seen directly weighted 1 for both strategies";
    shell("rm -rf " + subs);
    for (const char* student : {"alice", "bob", "carol", "dave", "erin", "frank", "gina", "hal"}) shell("mkdir -p " + subs + "/" + student);
    writeFile(subs + "/alice/bdpt.cpp", readFile("bdpt.cpp"));
    writeFile(subs + "/bob/bdpt.cpp", readFile(kDir + "/folder/grader/handed-out.cpp"));  // the stubs
    writeFile(subs + "/carol/bdpt.cpp", withMistake(firstHit));
    writeFile(subs + "/dave/homework.cpp", withMistake(firstHit));  // any file name
    writeFile(subs + "/erin/bdpt.cpp", withMistake(seenTwice));
    writeFile(subs + "/frank/bdpt.cpp", withMistake(etaNotSquared));
    writeFile(subs + "/gina/bdpt.cpp", readFile("bdpt.cpp") + "\nint broken( {\n");
    // hal handed in nothing
    REQUIRE(shell(kTeacherFlags + "make -s grade-class SUBMISSIONS=" + subs + " TASKS='H1 H2 H3 H4 H5' GRADE_JOBS=2 > " + kDir + "/class.log 2>&1") == 0);
    MESSAGE(readFile(kDir + "/class.log"));
    // The expected rows: public points from the public grader's own runs of the same mistakes,
    // hidden points from what each hidden check tries (2 a task).
    auto row = [](const std::string& name, const std::map<std::string, std::pair<int, int>>& points, const std::map<std::string, int>& hidden,
                  const std::string& note) {
        std::string r = name;
        int pub = 0, hid = 0;
        for (const char* t : {"H1", "H2", "H3", "H4", "H5"}) {
            const int p = points.count(t) ? points.at(t).first : 0, h = hidden.count(t) ? hidden.at(t) : 0;
            r += "," + std::to_string(p) + "," + std::to_string(h), pub += p, hid += h;
        }
        return r + "," + std::to_string(pub) + "," + std::to_string(hid) + "," + std::to_string(pub + hid) + "," + note;
    };
    const std::map<std::string, int> allHidden = {{"H1", 2}, {"H2", 2}, {"H3", 2}, {"H4", 2}, {"H5", 2}}, none;
    std::map<std::string, int> withoutH3 = allHidden, withoutH5 = allHidden;
    withoutH3["H3"] = 0, withoutH5["H5"] = 0;  // water's eta^2 tells eta from eta^2; the light seen directly is H5's hidden check
    const std::string csv = readFile("build/class/grades.csv");
    std::istringstream lines(csv);
    std::map<std::string, std::string> rows;
    for (std::string l; std::getline(lines, l);) rows[l.substr(0, l.find(','))] = l;
    CHECK(rows["student"] == "student,H1 public,H1 hidden,H2 public,H2 hidden,H3 public,H3 hidden,H4 public,H4 hidden,H5 public,H5 hidden,public,hidden,total,note");
    CHECK(rows["alice"] == row("alice", results().solution.points, allHidden, ""));
    CHECK(rows["bob"] == row("bob", {}, none, ""));
    CHECK(rows["carol"] == row("carol", reportOf(firstHit).points, allHidden, ""));
    CHECK(rows["dave"] == row("dave", reportOf(firstHit).points, allHidden, ""));
    CHECK(rows["erin"] == row("erin", results().solution.points, withoutH5, ""));
    CHECK(rows["frank"] == row("frank", reportOf(etaNotSquared).points, withoutH3, ""));
    CHECK(rows["gina"].rfind(row("gina", {}, none, "does not compile: "), 0) == 0);
    CHECK(rows["hal"] == row("hal", {}, none, "no bdpt.cpp in the folder"));
    CHECK(rows.size() == 9);
    // The report: the mistake two students made, counted twice, in the notes' words
    const std::string report = squeeze(readFile("build/class/report.md"));
    MESSAGE(readFile("build/class/report.md"));
    CHECK(report.find("| 2 | pt in the furnace, depth by depth | emission is counted only where the camera ray first hits |") != std::string::npos);
    CHECK(report.find("| 1 | the light seen directly, with --strategies (hidden) | the light seen directly weighted twice |") != std::string::npos);
    CHECK(report.find("| 1 | refraction by transport mode | eta where the rule has eta^2 |") != std::string::npos);
    CHECK(report.find("8 students, 6 graded") != std::string::npos);
    CHECK(readFile("build/class/mistakes.svg").find("<svg") == 0);
}

TEST_CASE("make gradescope: the package's run_autograder, in a simulated Gradescope tree, writes results.json check by check") {
    results();
    REQUIRE(shell("make -s gradescope TASKS='H1 H2 H3 H4 H5' > " + kDir + "/gradescope.log 2>&1") == 0);
    // Gradescope's layout under AUTOGRADER_ROOT: the zip in source/, the student's files in submission/.
    auto grade = [](const std::string& name, const std::string& file, const std::string& text) {
        const std::string root = kDir + "/gradescope-" + name;
        shell("rm -rf " + root + " && mkdir -p " + root + "/source " + root + "/submission && cd " + root +
              "/source && python3 -m zipfile -e ../../../../build/gradescope/autograder.zip .");
        writeFile(root + "/submission/" + file, text);
        REQUIRE(shell(kTeacherFlags + "AUTOGRADER_ROOT=" + root + " bash " + root + "/source/run_autograder > " + root + "/stdout 2>&1") == 0);
        // results.json, read by Python's json: a line per test, then the whole
        shell("python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); [print(\"%s\\t%s\\t%s\\t%s\\t%s\" % (t[\"name\"], t[\"score\"], t[\"max_score\"], "
              "t[\"visibility\"], t[\"output\"])) for t in d[\"tests\"]]; print(\"score\\t%s\\t%s\\t%s\" % (d[\"score\"], d[\"execution_time\"], d[\"output\"]))' " +
              root + "/results/results.json > " + root + "/tests.txt 2>&1");
        return readFile(root + "/tests.txt");
    };
    struct Test { std::string name, visibility, output; int score = -1, max = -1; };
    auto parse = [](const std::string& text, int& score, std::string& output) {
        std::vector<Test> tests;
        std::istringstream in(text);
        for (std::string l; std::getline(in, l);) {
            std::vector<std::string> f;
            std::stringstream ss(l);
            for (std::string x; std::getline(ss, x, '\t');) f.push_back(x);
            if (f.size() >= 4 && f[0] == "score") score = std::stoi(f[1]), output = f[3];
            else if (f.size() >= 5) tests.push_back({f[0], f[3], f[4], std::stoi(f[1]), std::stoi(f[2])});
        }
        return tests;
    };
    int score = -1;
    std::string output;
    std::vector<Test> solution = parse(grade("solution", "bdpt.cpp", readFile("bdpt.cpp")), score, output);
    CHECK(score == 60);
    int visible = 0, later = 0, full = 0, points = 0;
    for (const Test& t : solution) {
        visible += t.visibility == "visible", later += t.visibility == "after_due_date", full += t.score == t.max && t.output == "passed";
        points += t.max;
        CHECK(t.name.rfind("H", 0) == 0);
    }
    CHECK(later == 5);        // one hidden check a task
    CHECK(visible >= 25);     // the public ones
    CHECK(full == int(solution.size()));
    CHECK(points == 60);
    std::vector<Test> stubs = parse(grade("stubs", "bdpt.cpp", readFile(kDir + "/folder/grader/handed-out.cpp")), score, output);
    CHECK(score == 0);
    CHECK(stubs.size() == solution.size());
    for (const Test& t : stubs) {
        CAPTURE(t.name);
        CHECK(t.score == 0);
        CHECK(t.output.size() > 20);  // the grader's words: what it expected and measured
    }
    std::vector<Test> mistake = parse(grade("mistake", "mine.cpp", withMistake("the light seen directly weighted 1 for both strategies")), score, output);
    CHECK(score == 58);
    bool named = false;
    for (const Test& t : mistake)
        if (t.score < t.max) named = t.visibility == "after_due_date" && t.output.find("goes to s = 0 alone") != std::string::npos;
    CHECK(named);
    std::vector<Test> broken = parse(grade("broken", "bdpt.cpp", "int main( {"), score, output);
    CHECK(score == 0);
    CHECK(broken.empty());
    CHECK(output.find("does not compile") != std::string::npos);
}
