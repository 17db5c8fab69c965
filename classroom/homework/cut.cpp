// classroom/homework/cut.cpp: make homework's cutter. Reads the task list (classroom/homework/tasks)
// and bdpt.cpp, the solution, and writes the student's bdpt.cpp, each cut of the tasks asked for
// replaced by a TODO and a stub, and the student's README of those tasks; the Makefile copies the
// scenes, the grader and its data beside them. A cut that does not match bdpt.cpp stops it with
// the task list's file:line, before anything is written.
//   cut TASKS_FILE SOURCE OUT_DIR [IDS]     IDS: "H1 H2 ..." (default: every task but the optional)
//   cut TASKS_FILE --list [IDS]             the grader's task list (ID points title) on stdout
//   cut TASKS_FILE SOURCE OUT_DIR IDS --answered   the same with a right answer in each cut's place
//   cut --index FILE...                     every definition of the files (classroom/definitions.h)
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>
#include "../definitions.h"  // where a function is defined: the one index the page and the tests read too

struct Cut {
    int line = 0;                     // in the task list
    std::string function, from, to;   // to empty: the whole body
    std::vector<std::string> stub, todo;
    std::vector<std::string> answer;  // cut-lines: a right answer's lines (make test-homework writes them in)
};
// Lines of the lecture's comments that state a task's answer (a banner's formula): from the first
// line holding `from` to the first after it holding `to`, replaced in the handed-out file by `note`.
struct Hide {
    int line = 0;
    std::string from, to, note;
};
struct Task {
    int line = 0;
    std::string id, title, points, slides, notes, time, teaches, told;
    std::vector<Cut> cuts;
    std::vector<Hide> hides;
    std::vector<std::string> secrets;  // texts that answer the task: none may stand in the folder (make test checks)
    bool optional() const { return title.find("optional") != std::string::npos; }
};

static std::string trim(const std::string& s) {
    size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}
static std::vector<std::string> splitBars(const std::string& s) {
    std::vector<std::string> parts;
    std::stringstream in(s);
    for (std::string p; std::getline(in, p, '|');) parts.push_back(trim(p));
    return parts;
}
[[noreturn]] static void fail(const std::string& where, const std::string& message) {
    throw std::runtime_error(where + ": " + message);
}

static std::vector<Task> readTasks(const std::string& file) {
    std::ifstream in(file);
    if (!in) fail(file, "cannot read the task list");
    std::vector<Task> tasks;
    int n = 0;
    for (std::string raw; std::getline(in, raw);) {
        ++n;
        const std::string where = file + ":" + std::to_string(n);
        if (trim(raw).empty() || trim(raw)[0] == '#') continue;
        const bool indented = raw[0] == ' ';
        std::string line = trim(raw), key = line.substr(0, line.find(' ')), rest = trim(line.substr(key.size()));
        if (key == "task") {
            std::vector<std::string> p = splitBars(rest);
            if (p.size() != 3) fail(where, "a task is 'task ID | title | points'");
            Task t;
            t.line = n, t.id = p[0], t.title = p[1], t.points = p[2];
            tasks.push_back(t);
            continue;
        }
        if (tasks.empty()) fail(where, "'" + key + "' before the first task");
        Task& t = tasks.back();
        if (indented) {
            if (t.cuts.empty()) fail(where, "'" + key + "' before the task's first cut");
            if (key == "stub") t.cuts.back().stub.push_back(rest);
            else if (key == "todo") t.cuts.back().todo.push_back(rest);
            else if (key == "answer") t.cuts.back().answer.push_back(rest);
            else fail(where, "unknown key '" + key + "' under a cut (stub, todo, answer)");
        } else if (key == "cut" || key == "cut-lines") {
            Cut c;
            c.line = n;
            std::vector<std::string> p = splitBars(rest);
            if (key == "cut-lines" && p.size() != 3) fail(where, "cut-lines FUNCTION | FROM | TO");
            c.function = p[0];
            if (key == "cut-lines") c.from = p[1], c.to = p[2];
            t.cuts.push_back(c);
        } else if (key == "hide") {
            std::vector<std::string> p = splitBars(rest);
            if (p.size() != 3) fail(where, "hide FROM | TO | NOTE");
            t.hides.push_back({n, p[0], p[1], p[2]});
        } else if (key == "secret") t.secrets.push_back(rest);
        else if (key == "slides") t.slides = rest;
        else if (key == "notes") t.notes = rest;
        else if (key == "time") t.time = rest;
        else if (key == "teaches") t.teaches = rest;
        else if (key == "told") t.told = rest;
        else fail(where, "unknown key '" + key + "' (slides, notes, time, teaches, told, cut, cut-lines, hide, secret)");
    }
    for (const Task& t : tasks)
        for (const Cut& c : t.cuts) {
            if (c.stub.empty() && c.todo.empty()) fail(file + ":" + std::to_string(c.line), "a cut needs a todo");
            if (!c.to.empty() && c.answer.empty()) fail(file + ":" + std::to_string(c.line), "a cut-lines needs an answer (what a right student writes)");
        }
    return tasks;
}

// The names of a parameter list's named parameters ("const Scene& scene, int, Rng& rng = x").
static std::vector<std::string> parameterNames(const std::string& list) {
    std::vector<std::string> names, params;
    int depth = 0;
    std::string cur;
    for (char ch : list) {
        if (ch == '<' || ch == '(') ++depth;
        if (ch == '>' || ch == ')') --depth;
        if (ch == ',' && depth == 0) params.push_back(cur), cur.clear();
        else cur += ch;
    }
    params.push_back(cur);
    for (std::string p : params) {
        p = trim(p.substr(0, p.find('=')));
        std::vector<std::string> words;
        std::istringstream in(p);
        for (std::string w; in >> w;) words.push_back(w);
        if (words.size() < 2) continue;
        std::string last = words.back();
        if (last.back() == '&' || last.back() == '*' || last == "int" || last == "float" || last == "double") continue;
        while (!last.empty() && (last[0] == '&' || last[0] == '*')) last.erase(0, 1);
        if (!last.empty()) names.push_back(last);
    }
    return names;
}

// Comment lines of at most 100 columns, each starting with `indent` "// ".
static std::string commentLines(const std::string& text, const std::string& indent) {
    std::string out, line;
    std::istringstream words(text);
    for (std::string w; words >> w;) {
        if (!line.empty() && indent.size() + 3 + line.size() + 1 + w.size() > 100) out += indent + "// " + line + "\n", line.clear();
        line += (line.empty() ? "" : " ") + w;
    }
    if (!line.empty()) out += indent + "// " + line + "\n";
    return out;
}
static std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const std::string& l : lines) s += (s.empty() ? "" : " ") + l;
    return s;
}
static std::string notePages(const Task& t) {
    std::string s;
    std::istringstream in(t.notes);
    for (std::string n; in >> n;) s += (s.empty() ? "" : ", ") + std::string("lecture_notes/") + n;
    return s;
}

static std::string todoBlock(const Task& t, const Cut& c, const std::string& indent) {
    return commentLines("TODO (" + t.id + ", " + t.title + "): " + joined(c.todo), indent) +
           commentLines("The slides: " + t.slides + ". The notes: " + notePages(t) + ".", indent) +
           commentLines("Until it is written, the stub below stands here: it compiles and renders, black or wrong.", indent);
}

// answered: the TODO followed by a right answer instead of the stub (the function's own body, or
// a cut-lines' `answer` lines): what a student who solved the task hands in.
static std::string applyCut(const std::string& source, const Task& t, const Cut& c, const std::string& tasksFile, bool answered) {
    const std::string where = tasksFile + ":" + std::to_string(c.line), code = definitions::codeOnly(source);
    definitions::Definition d;
    if (!definitions::topLevelFunction(definitions::index(source), c.function, d)) fail(where, "no definition of " + c.function + "() in the source");
    if (c.to.empty()) {  // the whole body
        std::string body = "\n" + todoBlock(t, c, "    ");
        if (answered) {  // the function's own body, after the TODO (a one-line body on a line of its own)
            const std::string inner = source.substr(d.open + 1, d.end - d.open - 1);
            body += inner.find('\n') == std::string::npos ? "    " + trim(inner) + "\n" : inner.substr(inner.find('\n') + 1);
            return source.substr(0, d.open + 1) + body + source.substr(d.end);
        }
        for (const std::string& p : parameterNames(source.substr(d.paren + 1, d.close - d.paren - 1))) body += "    (void)" + p + ";\n";
        for (const std::string& s : c.stub) body += "    " + s + "\n";
        return source.substr(0, d.open + 1) + body + source.substr(d.end);
    }
    // The anchors are code (found where comments are blanked): a reworded comment moves no cut.
    size_t from = code.find(c.from, d.open), to = from == std::string::npos ? from : code.find(c.to, from);
    if (from == std::string::npos || from > d.end) fail(where, "'" + c.from + "' is not in " + c.function + "()'s code");
    if (to == std::string::npos || to > d.end) fail(where, "'" + c.to + "' does not follow '" + c.from + "' in " + c.function + "()'s code");
    from = source.rfind('\n', from) + 1, to = source.rfind('\n', to) + 1;
    // The comment lines just above the first cut line explain it: they go with it (they would answer the TODO).
    for (size_t above; from > d.open + 1 && (above = source.rfind('\n', from - 2) + 1) > d.open &&
                       source.compare(source.find_first_not_of(' ', above), 2, "//") == 0;)
        from = above;
    const std::string indent = source.substr(from, source.find_first_not_of(' ', from) - from);
    std::string lines = todoBlock(t, c, indent);
    for (const std::string& s : answered ? c.answer : c.stub) lines += indent + s + "\n";
    return source.substr(0, from) + lines + source.substr(to);
}

static std::string applyHide(const std::string& source, const Hide& h, const std::string& tasksFile) {
    const std::string where = tasksFile + ":" + std::to_string(h.line);
    size_t from = source.find(h.from), to = from == std::string::npos ? from : source.find(h.to, from);
    if (from == std::string::npos) fail(where, "'" + h.from + "' is not in the source");
    if (to == std::string::npos) fail(where, "'" + h.to + "' does not follow '" + h.from + "'");
    from = source.rfind('\n', from) + 1, to = source.find('\n', to) + 1;
    const std::string indent = source.substr(from, source.find_first_not_of(' ', from) - from);
    return source.substr(0, from) + commentLines(h.note, indent) + source.substr(to);
}

static std::string readme(const std::vector<const Task*>& tasks) {
    std::ostringstream r;
    r << "# Homework: the slides' methods, graded by the physics\n\n"
      << "This folder is the renderer of the lecture *Bidirectional Path Tracing & Reciprocity*, `bdpt.cpp`, with the\n"
      << "bodies of some of its functions taken out. Each is marked `TODO (Hn, ...)` and holds a stub that compiles\n"
      << "and renders, black or wrong. Write them back, one task at a time, in this order; after each, ask the grader.\n\n"
      << "```sh\n"
      << "make                 # builds ./bdpt from your bdpt.cpp (seconds)\n"
      << "./bdpt scenes/cornell.scene --method pt --out build/cornell.png   # look at what your code renders\n"
      << "make grade           # compiles the grader with your bdpt.cpp (15 seconds), then checks every task (seconds)\n"
      << "make grade TASK=H2   # one task's checks alone\n"
      << "```\n\n"
      << "The grader prints a line per task, `Hn title ... N / M`, what failed under it (the check, what it expected,\n"
      << "what your code gave, and the likely mistake with the notes' page to read) and the total. It knows no\n"
      << "solution: it checks what the physics requires (closed forms, one method against another, weights that\n"
      << "sum to 1, energy), and compares renders with images the complete renderer made (`grader/data/`). Each\n"
      << "task runs in a process of its own with a limit of CPU time and memory: a crash, an endless loop or a\n"
      << "huge allocation costs that task's points, with a message, and not the others'.\n\n"
      << "Read beside each task the slides it names and the notes' pages (`lecture_notes/`, in this folder); the\n"
      << "rest of `bdpt.cpp` is the lecture's code, and the functions a TODO names are there to be called.\n"
      << "`./bdpt --help` lists the options; `--method` chooses the slides' panel, `--res 64x64` makes a render quick.\n"
      << "`make build/worked-path` builds the tool of the notes' page 7 (`build/worked-path cornell`; `build/worked-path path\n"
      << "SCENE WxH X,Y,Z ...` for a path of your own): every strategy's density and weights, to check `misWalk` by hand.\n"
      << "`make grade` builds `./bdpt` too. Until a task is done, the methods that use its code render black or wrong\n"
      << "(measured: each task's stubs alone against the solution, on cornell-glass and shading-normals):\n\n"
      << "| `--method` | needs |\n|---|---|\n"
      << "| `pt`, `nee`, `nee --mis` | H1 |\n| `lt` | H2 |\n| `ir` | H4 |\n| `bdpt`, `vcm` | H2, H5 (light tracing is bdpt's t = 1) |\n"
      << "| `pssmlt`, `mmlt`, `mlt` | H2, H5, H6 |\n\n"
      << "and every method needs H3 where there is glass or a shading normal.\n\n";
    int total = 0;
    for (const Task* t : tasks) total += std::stoi(t->points);
    r << "## The tasks (" << total << " points)\n\n";
    for (const Task* t : tasks) {
        r << "### " << t->id << " " << t->title << " (" << t->points << " points, " << t->time << ")\n\n"
          << t->told << "\n\n"
          << "- **The slides:** " << t->slides << ".\n"
          << "- **The notes:** " << notePages(*t) << ".\n"
          << "- **What it teaches:** " << t->teaches << ".\n";
        for (const Cut& c : t->cuts)
          r << "- **`" << c.function << "()`" << (c.to.empty() ? "" : ", the lines marked in it") << ":** " << joined(c.todo) << "\n";
        r << "\n";
    }
    if (std::any_of(tasks.begin(), tasks.end(), [](const Task* t) { return t->id == "H5"; }))
        r << "## A path through a mirror, and the strategies it leaves (H5)\n\n"
          << "Strategy (s, t) makes the path x_0 ... x_k by joining x_{s-1}, the last vertex of its light subpath, to x_s, the last\n"
          << "of its camera subpath; it can only where neither is a delta vertex (a mirror or glass), and s = 0 only where x_0\n"
          << "lies on a lamp with an area. For x_0 on a lamp, x_1 diffuse, x_2 a mirror, x_3 diffuse and x_4 the pinhole (k = 4):\n\n"
          << "| s | t | joins | makes the path |\n|---|---|---|---|\n"
          << "| 0 | 5 | the camera subpath hits the lamp at x_0 | yes |\n| 1 | 4 | x_0 and x_1 | yes |\n"
          << "| 2 | 3 | x_1 and x_2, the mirror | no |\n| 3 | 2 | x_2, the mirror, and x_3 | no |\n| 4 | 1 | x_3 and the pinhole x_4 | yes |\n\n"
          << "So the walk leaves out (s', t') where x_{s'-1} or x_{s'} is a delta vertex, and the weights of the three left sum to 1.\n\n";
    r << "## What the grader cannot see\n\n"
      << "It checks what a method renders and what a function returns on the scenes it knows: cornell, its\n"
      << "point-lit twin, the furnace, a glass interface, a bumped floor and a few of its own. Code that is right\n"
      << "there and wrong elsewhere (a scene it does not render, an option it does not pass) can pass; so can code\n"
      << "that is slow. Full points say the physics holds on those scenes, not that the code is the lecture's.\n"
      << "Your teacher's grade may add checks this grader does not hold (other scenes, sizes and options): code\n"
      << "right by the physics passes them too.\n";
    return r.str();
}

// cut --index FILE...: every definition of the files, a line each: FILE NAME FIRST LAST (the
// page's code view reads it, web/build_code.js).
static int printIndex(int argc, char** argv) {
    for (int i = 2; i < argc; ++i) {
        std::ifstream in(argv[i], std::ios::binary);
        if (!in) {
            std::fprintf(stderr, "cut --index: cannot read %s\n", argv[i]);
            return 1;
        }
        std::stringstream s;
        s << in.rdbuf();
        for (const definitions::Definition& d : definitions::index(s.str()))
            std::printf("%s %s %d %d\n", argv[i], d.name.c_str(), d.firstLine, d.lastLine);
    }
    return 0;
}

int main(int argc, char** argv) {
    if (argc >= 3 && std::string(argv[1]) == "--index") return printIndex(argc, argv);
    bool answered = false;  // --answered (last): each cut's place holds a right answer, for make test-homework
    if (argc > 1 && std::string(argv[argc - 1]) == "--answered") answered = true, --argc;
    if (argc < 4 && !(argc == 3 && std::string(argv[2]) == "--list")) {
        std::fprintf(stderr, "usage: %s TASKS_FILE SOURCE OUT_DIR [\"H1 H2 ...\"] | %s TASKS_FILE --list [\"H1 H2 ...\"]\n", argv[0], argv[0]);
        return 2;
    }
    try {
        const std::string tasksFile = argv[1], sourceFile = argv[2];
        const bool listOnly = sourceFile == "--list";
        const std::string out = listOnly ? "" : argv[3];
        std::vector<Task> tasks = readTasks(tasksFile);
        std::vector<std::string> wanted;
        const int idsAt = listOnly ? 3 : 4;
        std::istringstream ids(argc > idsAt ? argv[idsAt] : "");
        for (std::string id; ids >> id;) wanted.push_back(id);
        std::vector<const Task*> chosen;
        for (const std::string& id : wanted) {
            auto t = std::find_if(tasks.begin(), tasks.end(), [&](const Task& x) { return x.id == id; });
            if (t == tasks.end()) {
                std::string known;
                for (const Task& x : tasks) known += " " + x.id;
                fail("TASKS", "no task " + id + " (the tasks:" + known + ")");
            }
            chosen.push_back(&*t);
        }
        if (wanted.empty())
            for (const Task& t : tasks)
                if (!t.optional()) chosen.push_back(&t);
        std::sort(chosen.begin(), chosen.end(), [&](const Task* a, const Task* b) { return a->line < b->line; });
        std::string list;
        for (const Task* t : chosen) list += t->id + " " + t->points + " " + t->title + "\n";
        if (listOnly) {
            std::fputs(list.c_str(), stdout);
            return 0;
        }
        std::ifstream in(sourceFile, std::ios::binary);
        if (!in) fail(sourceFile, "cannot read it");
        std::stringstream s;
        s << in.rdbuf();
        std::string source = s.str();
        for (const Task* t : chosen) {
            for (const Cut& c : t->cuts) source = applyCut(source, *t, c, tasksFile, answered);
            for (const Hide& h : t->hides) source = applyHide(source, h, tasksFile);
        }
        auto write = [](const std::string& path, const std::string& text) {
            std::ofstream f(path + ".tmp", std::ios::binary);
            f << text;
            f.close();
            if (!f || std::rename((path + ".tmp").c_str(), path.c_str()) != 0) fail(path, "cannot write it");
        };
        write(out + "/bdpt.cpp", source);
        write(out + "/README.md", readme(chosen));
        write(out + "/grader/tasks.txt", list);
        std::printf("make homework: %s/ holds bdpt.cpp with the tasks", out.c_str());
        for (const Task* t : chosen) std::printf(" %s", t->id.c_str());
        std::printf(" cut out, the scenes, the grader and its data; its README.md says what to do\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make homework: %s\n", e.what());
        return 1;
    }
    return 0;
}
