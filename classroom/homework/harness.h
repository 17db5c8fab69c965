// classroom/homework/harness.h: the grader's harness, apart from its checks (grade.cpp): what a
// check says, the process each task's checks run in (CPU-time and memory limits, the verdict as
// lines through a pipe, a crash or an endless loop costing that task alone), and what the grader
// writes: the report a student reads and Gradescope's results.json. grade.cpp includes it after
// bdpt.cpp; make homework copies it beside the grader.
#pragma once
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>

namespace grade {

// ---- what a check says: pass or fail, and for a failure what it expected, what it measured and,
// where a mistake's fingerprint fits, the mistake in the slides' words with the notes' page.
struct Outcome {
    bool pass = false;
    std::string text;
    std::string mistake;  // the classic mistake named, by its short name (a class's report counts them)
    Outcome(bool p = false, std::string t = "", std::string m = "") : pass(p), text(std::move(t)), mistake(std::move(m)) {}
};
struct Check {
    std::string name;
    int points;
    std::function<Outcome()> run;
    bool hidden = false;  // the teacher's alone (hidden.h): never in a student's folder
};

// ---- the processes: a task's checks in a child, with limits; its results as lines on a pipe
struct CheckResult {
    std::string name, text, mistake;
    int points = 0, max = 0;
    bool hidden = false;
};
struct TaskResult {
    int points = 0, max = 0, hiddenPoints = 0, hiddenMax = 0;
    std::vector<CheckResult> checks;  // in the order run; a check a crash stopped holds its words
    std::vector<std::string> notes;   // what failed, as the report prints it
};
bool gWriteFailed = false;
void say(int fd, const std::string& line) {
    std::string l = line + "\n";
    for (char& ch : l) if (ch == '\n' && &ch != &l.back()) ch = ' ';
    gWriteFailed = gWriteFailed || write(fd, l.data(), l.size()) != ssize_t(l.size());
}

void runChecks(const std::vector<Check>& checks, int fd) {
    for (const Check& c : checks) {
        say(fd, "CHECK\t" + c.name);
        Outcome o;
        try {
            o = c.run();
        } catch (const std::bad_alloc&) {
            say(fd, "MEMORY");
            _exit(3);
        } catch (const std::exception& e) {
            o = {false, std::string("stopped by an exception: ") + e.what(), ""};
        }
        say(fd, std::string(o.pass ? "PASS\t" : "FAIL\t") + c.name + "\t" + o.mistake + "\t" + o.text);
    }
    say(fd, "DONE");
}

const char* signalWords(int sig) {
    switch (sig) {
        case SIGXCPU: case SIGKILL: return "ran past its CPU-time limit: an endless loop? (a path that never ends, a loop whose index never moves)";
        case SIGSEGV: case SIGBUS: return "crashed (segmentation fault): a pointer or an index out of range? (an empty subpath, camera[t] for t = size)";
        case SIGFPE: return "crashed: an integer division by zero";
        case SIGABRT: return "aborted: an exception escaping, or out of memory (the grader allows 2 GB)";
        default: return "was killed by a signal";
    }
}

// On a terminal, the check under way (a slow task is never silent); nothing in a log.
void showCheck(const std::string& name) {
    if (!isatty(2)) return;
    std::string line = "  checking: " + name;
    line.resize(100, ' ');
    std::fprintf(stderr, "\r%s\r", line.c_str());
    if (name.empty()) std::fprintf(stderr, "%s\r", std::string(100, ' ').c_str());
}

TaskResult runTask(const std::vector<Check>& checks, double cpuSeconds) {
    TaskResult r;
    for (const Check& c : checks) (c.hidden ? r.hiddenMax : r.max) += c.points;
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("no pipe");
    std::fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        rlimit cpu{rlim_t(cpuSeconds), rlim_t(cpuSeconds + 2)}, memory{rlim_t(2) << 30, rlim_t(2) << 30};
        setrlimit(RLIMIT_CPU, &cpu);
        setrlimit(RLIMIT_AS, &memory);
        int devnull = open("/dev/null", O_WRONLY);
        if (devnull >= 0) dup2(devnull, 1), dup2(devnull, 2);  // the student's prints: not the report's
        runChecks(checks, fds[1]);
        _exit(0);
    }
    close(fds[1]);
    std::string text, pending;
    char buffer[4096];
    // A hang's guard, not a clock: ten minutes without a word from a child that uses no CPU
    // (one waiting forever) end it; a child computing is stopped by its CPU limit.
    for (;;) {
        pollfd p{fds[0], POLLIN, 0};
        int ready = poll(&p, 1, 600000);
        if (ready == 0) { kill(pid, SIGKILL); break; }
        ssize_t n = read(fds[0], buffer, sizeof buffer);
        if (n <= 0) break;
        text.append(buffer, size_t(n)), pending.append(buffer, size_t(n));
        for (size_t end; (end = pending.find('\n')) != std::string::npos; pending.erase(0, end + 1))
            if (pending.compare(0, 6, "CHECK\t") == 0) showCheck(pending.substr(6, end - 6));
    }
    showCheck("");
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    auto checkNamed = [&](const std::string& name) -> const Check* {
        for (const Check& c : checks) if (c.name == name) return &c;
        return nullptr;
    };
    std::istringstream lines(text);
    bool done = false, memory = false;
    std::string current;
    for (std::string line; std::getline(lines, line);) {
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string x; std::getline(ss, x, '\t');) f.push_back(x);
        if (f[0] == "CHECK") current = f.size() > 1 ? f[1] : "";
        else if ((f[0] == "PASS" || f[0] == "FAIL") && f.size() >= 2 && checkNamed(f[1])) {
            const Check& c = *checkNamed(f[1]);
            CheckResult cr{c.name, f.size() > 3 ? f[3] : "failed", f.size() > 2 ? f[2] : "", f[0] == "PASS" ? c.points : 0, c.points, c.hidden};
            if (f[0] == "PASS") cr.text.clear();
            r.checks.push_back(cr);
        } else if (f[0] == "DONE") done = true;
        else if (f[0] == "MEMORY") memory = true;
    }
    if (!(done && WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
        std::string why = WIFSIGNALED(status) ? signalWords(WTERMSIG(status))
                          : memory ? "ran out of memory (the grader allows 2 GB): an allocation that grows without end, or a size computed wrong?"
                                   : "stopped before its checks ended (exit status " + std::to_string(WEXITSTATUS(status)) + ")";
        const std::string note = "your code " + why + ", in the check '" + current + "': the task gets 0 points (fix it, and the other checks run again)";
        r.checks.clear();  // a task that crashed gets nothing, each of its checks the reason
        for (const Check& c : checks) r.checks.push_back({c.name, note, "", 0, c.points, c.hidden});
        r.notes.push_back(note);
        return r;
    }
    for (const CheckResult& c : r.checks) {
        (c.hidden ? r.hiddenPoints : r.points) += c.points;
        if (c.points < c.max) r.notes.push_back(std::string(c.hidden ? "[hidden] " : "") + c.name + ": " + c.text);
    }
    return r;
}

struct TaskSpec {
    std::string id, title;
    int points;
};

std::string jsonString(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') out += '\\', out += char(c);
        else if (c == '\n') out += "\\n";
        else if (c < 0x20) out += ' ';
        else out += char(c);
    }
    return out + "\"";
}
// Gradescope's results.json (its autograder specification): one test per check, the public ones
// visible, the hidden ones after the due date; extra_data keeps what a class report counts.
bool writeJson(const std::string& path, const std::vector<TaskSpec>& tasks, const std::vector<TaskResult>& results, double seconds) {
    std::ostringstream o;
    int score = 0;
    std::string tests, mistakes, perTask;
    for (size_t i = 0; i < tasks.size(); ++i) {
        const TaskResult& r = results[i];
        score += r.points + r.hiddenPoints;
        perTask += std::string(perTask.empty() ? "" : ",") + jsonString(tasks[i].id) + ":{\"public\":" + std::to_string(r.points) + ",\"public_max\":" +
                   std::to_string(r.max) + ",\"hidden\":" + std::to_string(r.hiddenPoints) + ",\"hidden_max\":" + std::to_string(r.hiddenMax) + "}";
        for (const CheckResult& c : r.checks) {
            tests += std::string(tests.empty() ? "" : ",\n  ") + "{\"name\":" + jsonString(tasks[i].id + " " + tasks[i].title + ": " + c.name) +
                     ",\"score\":" + std::to_string(c.points) + ",\"max_score\":" + std::to_string(c.max) + ",\"output\":" +
                     jsonString(c.points == c.max ? "passed" : c.text) + ",\"tags\":[" + jsonString(tasks[i].id) + "],\"visibility\":" +
                     jsonString(c.hidden ? "after_due_date" : "visible") + "}";
            if (c.points < c.max)
                mistakes += std::string(mistakes.empty() ? "" : ",") + "{\"task\":" + jsonString(tasks[i].id) + ",\"check\":" + jsonString(c.name) +
                            ",\"hidden\":" + (c.hidden ? "true" : "false") + ",\"mistake\":" + jsonString(c.mistake) +
                            ",\"stopped\":" + (c.text.rfind("your code ", 0) == 0 ? "true" : "false") + "}";
        }
    }
    o << "{\"score\":" << score << ",\"execution_time\":" << int(seconds + 0.5) << ",\"output\":"
      << jsonString("graded by the physics: each check's words say what it expected and measured, and the mistake where its fingerprint fits")
      << ",\"tests\":[\n  " << tests << "],\n\"extra_data\":{\"tasks\":{" << perTask << "},\"failed\":[" << mistakes << "]}}\n";
    std::ofstream f(path + ".tmp");
    f << o.str();
    f.close();
    return f && std::rename((path + ".tmp").c_str(), path.c_str()) == 0;
}

void printTask(const TaskSpec& t, const TaskResult& r) {
    std::string head = t.id + " " + t.title + " ";
    while (head.size() < 60) head += '.';
    if (r.hiddenMax > 0) std::printf("%s %2d / %d, hidden %d / %d\n", head.c_str(), r.points, r.max, r.hiddenPoints, r.hiddenMax);
    else std::printf("%s %2d / %d\n", head.c_str(), r.points, r.max);
    for (const std::string& n : r.notes) {  // wrapped at 110 columns, hanging under its dash
        std::string line = "    -";
        std::istringstream words(n);
        for (std::string w; words >> w;) {
            if (line.size() + 1 + w.size() > 110 && line.size() > 6) std::printf("%s\n", line.c_str()), line = "     ";
            line += " " + w;
        }
        std::printf("%s\n", line.c_str());
    }
    std::fflush(stdout);
}

}  // namespace grade
