#!/usr/bin/env python3
"""make grade-class: a class's homework graded in one command.

    python3 classroom/homework/grade_class.py SUBMISSIONS OUT TASKS_FILE DATA [JOBS]

SUBMISSIONS holds a folder per student, each with the student's bdpt.cpp (any other .cpp if there
is no bdpt.cpp). Each is compiled with the teacher's grader (classroom/homework/grade.cpp with
hidden.h: -DBDPT_HIDDEN_CHECKS) and graded task by task, JOBS at a time (the cores), each task in
a process of its own with the grader's CPU and memory limits. A folder without a file, a file
that does not compile, a crash: a row with its points (0 where it failed) and the reason, never a
stop. Writes OUT/grades.csv (a gradebook: public and hidden points per task, totals, the note),
OUT/report.md (what the class got wrong: per task, each check failed and the mistake it named,
with how many students) and OUT/mistakes.svg (its chart). Python's standard library only.
"""
import concurrent.futures, csv, html, json, os, shutil, subprocess, sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CXX = os.environ.get("CXX", "g++")
CXXFLAGS = os.environ.get("GRADE_CXXFLAGS", "-O2 -std=c++17 -pthread")


def source_of(folder):
    """The student's file: bdpt.cpp, or else the only .cpp there."""
    if os.path.isfile(os.path.join(folder, "bdpt.cpp")):
        return os.path.join(folder, "bdpt.cpp")
    cpps = sorted(f for f in os.listdir(folder) if f.endswith(".cpp"))
    return os.path.join(folder, cpps[0]) if len(cpps) == 1 else None


def grade_one(student, folder, work, tasks_file, data):
    """One student's results: {'tasks': {id: {public, hidden, ...}}, 'failed': [...], 'note': ...}."""
    os.makedirs(work, exist_ok=True)
    src = source_of(folder)
    if src is None:
        return {"note": "no bdpt.cpp in the folder"}
    shutil.copy(src, os.path.join(work, "bdpt.cpp"))
    compiled = subprocess.run([CXX, *CXXFLAGS.split(), "-DBDPT_HIDDEN_CHECKS", "-I" + work, "-I" + os.path.join(ROOT, "classroom"),
                               "-o", os.path.join(work, "grade"), os.path.join(ROOT, "classroom/homework/grade.cpp"), "-lstb", "-pthread"],
                              capture_output=True, text=True)
    if compiled.returncode != 0:
        first = next((l for l in compiled.stderr.splitlines() if "error" in l), "the compiler's message is in " + work + "/compile.log")
        open(os.path.join(work, "compile.log"), "w").write(compiled.stderr)
        return {"note": "does not compile: " + first.replace(work + "/", "").replace(ROOT + "/", "")}
    results = os.path.join(work, "results.json")
    with open(os.path.join(work, "grade.log"), "w") as log:
        ran = subprocess.run([os.path.join(work, "grade"), "--data", data, "--tasks", tasks_file, "--json", results], cwd=ROOT, stdout=log,
                             stderr=subprocess.STDOUT)
    if ran.returncode != 0 or not os.path.isfile(results):
        return {"note": "the grader stopped (exit status %d): see %s/grade.log" % (ran.returncode, work)}
    extra = json.load(open(results))["extra_data"]
    return {"tasks": extra["tasks"], "failed": extra["failed"], "note": ""}


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    submissions, out, tasks_file, data = sys.argv[1:5]
    jobs = int(sys.argv[5]) if len(sys.argv) > 5 else os.cpu_count() or 2
    if not os.path.isdir(submissions):
        sys.exit("make grade-class: no folder %s (SUBMISSIONS=dir: a folder per student, each with its bdpt.cpp)" % submissions)
    tasks = [line.split(None, 2) for line in open(tasks_file) if line.strip()]  # ID points title
    students = sorted(d for d in os.listdir(submissions) if os.path.isdir(os.path.join(submissions, d)))
    if not students:
        sys.exit("make grade-class: %s holds no student's folder" % submissions)
    print("make grade-class: %d students, %d at a time, tasks %s (the public checks and the hidden ones)" % (len(students), jobs, " ".join(t[0] for t in tasks)))
    os.makedirs(out, exist_ok=True)
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(grade_one, s, os.path.join(submissions, s), os.path.join(out, "work", s), os.path.abspath(tasks_file),
                               os.path.abspath(data)): s for s in students}
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            s = futures[future]
            results[s] = future.result()
            print("  %d/%d %s%s" % (done, len(students), s, ": " + results[s]["note"] if results[s]["note"] else ""), flush=True)
    write_grades(os.path.join(out, "grades.csv"), tasks, students, results)
    write_report(out, tasks, students, results)
    print("make grade-class: %s/grades.csv and %s/report.md" % (out, out))


def write_grades(path, tasks, students, results):
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["student"] + [t[0] + " " + kind for t in tasks for kind in ("public", "hidden")] + ["public", "hidden", "total", "note"])
        for s in students:
            r = results[s]
            cells, public, hidden = [], 0, 0
            for t in tasks:
                got = r.get("tasks", {}).get(t[0], {})
                cells += [got.get("public", 0), got.get("hidden", 0)]
                public += got.get("public", 0)
                hidden += got.get("hidden", 0)
            w.writerow([s] + cells + [public, hidden, public + hidden, r["note"]])
    os.replace(path + ".tmp", path)


def mistake_counts(tasks, students, results):
    """{task: [(what, count)]}: each check failed, with the mistake it named, by how many students."""
    counts = {t[0]: {} for t in tasks}
    for s in students:
        seen = set()
        for f in results[s].get("failed", []):
            what = ("the task stopped: a crash, a loop past its CPU limit or out of memory", "") if f.get("stopped") else \
                   (f["check"] + (" (hidden)" if f["hidden"] else ""), f["mistake"] or "")
            if (f["task"], what) not in seen:
                seen.add((f["task"], what))
                counts.setdefault(f["task"], {})[what] = counts[f["task"]].get(what, 0) + 1
    return {t: sorted(c.items(), key=lambda kv: (-kv[1], kv[0])) for t, c in counts.items()}


def write_report(out, tasks, students, results):
    n = len(students)
    graded = [s for s in students if "tasks" in results[s]]
    counts = mistake_counts(tasks, students, results)
    lines = ["# The class's homework: what it got wrong", "",
             "%d students, %d graded; the others: %s." % (n, len(graded), "; ".join("%s (%s)" % (s, results[s]["note"]) for s in students if s not in graded) or "none"),
             "", "| task | mean public | mean hidden | students with every point |", "|---|---|---|---|"]
    for t in tasks:
        pub = [results[s]["tasks"].get(t[0], {}) for s in graded]
        full = sum(1 for p in pub if p and p["public"] == p["public_max"] and p["hidden"] == p["hidden_max"])
        mean = lambda k: sum(p.get(k, 0) for p in pub) / max(1, len(pub))
        lines.append("| %s %s | %.1f / %s | %.1f / %s | %d of %d |" % (t[0], t[2].strip(), mean("public"), t[1], mean("hidden"),
                                                                      pub[0].get("hidden_max", 0) if pub else 0, full, len(graded)))
    lines += ["", "Each check failed, and the mistake its fingerprint named (in the notes' words, where one fit), by how many "
              "students: the slides to teach again are the longest bars.", "", "![mistakes](mistakes.svg)", ""]
    for t in tasks:
        lines.append("## %s %s" % (t[0], t[2].strip()))
        if not counts.get(t[0]):
            lines += ["", "No check failed.", ""]
            continue
        lines += ["", "| students | check | mistake named |", "|---|---|---|"]
        for (check, mistake), c in counts[t[0]]:
            lines.append("| %d | %s | %s |" % (c, check, mistake or "(not named)"))
        lines.append("")
    with open(os.path.join(out, "report.md.tmp"), "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(os.path.join(out, "report.md.tmp"), os.path.join(out, "report.md"))
    write_chart(os.path.join(out, "mistakes.svg"), tasks, counts, n)


def write_chart(path, tasks, counts, n):
    """A bar per (task, check, mistake): how many students made it, in the report's order."""
    bars = [(t[0], check, mistake, c) for t in tasks for (check, mistake), c in counts.get(t[0], [])]
    width, row, left = 900, 22, 430
    height = 40 + row * max(1, len(bars))
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="DejaVu Sans, sans-serif" font-size="12">' % (width, height),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="10" y="20" font-size="14">Mistakes of the class (%d students): students per check failed</text>' % n]
    for i, (task, check, mistake, c) in enumerate(bars):
        y = 34 + i * row
        label = "%s %s%s" % (task, check, ": " + mistake if mistake else "")
        svg.append('<text x="%d" y="%d" text-anchor="end">%s</text>' % (left - 8, y + 14, html.escape(label[:70])))
        w = (width - left - 60) * c / max(1, n)
        svg.append('<rect x="%d" y="%d" width="%.1f" height="%d" fill="#d9822b"/>' % (left, y + 3, w, row - 6))
        svg.append('<text x="%.1f" y="%d">%d</text>' % (left + w + 6, y + 14, c))
    svg.append("</svg>")
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(svg) + "\n")
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    main()
