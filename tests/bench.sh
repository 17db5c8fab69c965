#!/usr/bin/env bash
# make bench: our BVH against Embree on the same rays (tests/bench.h), interleaved runs, ratios
# from one session; then bdpt's cost per sample against nee's, vcm's pass and memory against
# bdpt's, and where a sample's time goes in pt, nee, bdpt and vcm (--profile).
# Two builds of ours: portable (SSE2, 4-wide nodes: build/bench_rays) and build/native/bench_rays
# (-march=native, 8-wide AVX nodes), the fair match for Embree, which picks its CPU's widest SIMD.
# Embree's half (build/embree_rays) exists where libembree-dev is installed; without it the
# table has our numbers only.
# Usage: tests/bench.sh [RUNS] [RAYS]   (defaults 3 runs of 524,288 rays per set, about 3 minutes;
# FULL=1: 4,194,304 rays, as Appendix B measured, about 15 minutes). It prints; it writes no file.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -n "${FULL:-}" ]; then default_rays=4194304; else default_rays=524288; fi
runs=${1:-3}; rays=${2:-$default_rays}
echo "bench: $runs interleaved runs of $rays rays per set, about $([ -n "${FULL:-}" ] && echo 15 || echo 3) minutes$([ -n "${FULL:-}" ] || echo " (FULL=1: 4194304, as Appendix B)")"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for i in $(seq "$runs"); do
  [ -x build/embree_rays ] && build/embree_rays --rays "$rays" --reps 3 > "$out/embree$i.txt"
  build/bench_rays --rays "$rays" --reps 3 > "$out/bdpt$i.txt"
  build/native/bench_rays --rays "$rays" --reps 3 | sed 's/^bdpt /bdpt-native /' > "$out/native$i.txt"
done
python3 - "$out" <<'PY'
import glob, statistics, sys
# Median over the runs of every number of every line, keyed by program, scene, kind, threads;
# the checksums must be the same in every run.
values, checks = {}, {}
for path in sorted(glob.glob(sys.argv[1] + "/*.txt")):
    for line in open(path):
        f = line.split()
        key = tuple(f[:4])
        kv = dict(x.split("=") for x in f[1:])
        for k in ("mrays", "cpu_mrays", "build_ms"):
            if k in kv: values.setdefault(key + (k,), []).append(float(kv[k]))
        sums = (kv.get("hits"), kv.get("sum_t"))
        if checks.setdefault(key, sums) != sums: sys.exit("bench: checksums differ between runs of %s" % " ".join(key))
med = {k: statistics.median(v) for k, v in values.items()}
rows = sorted({k[1:4] for k in med})
for ours in ("bdpt", "bdpt-native"):
    print("== %s / embree (median of interleaved runs; cpu_mrays does not see time slicing)" % ours)
    for scene, kind, threads in rows:
        e, o = ("embree", scene, kind, threads), (ours, scene, kind, threads)
        if (o + ("mrays",)) in med:
            ratio = lambda k: ("%.2fx" % (med[o + (k,)] / med[e + (k,)])) if (e + (k,)) in med else "-"
            print("%-36s %7.2f Mrays/s  mrays %s  cpu_mrays %s  hits %s vs %s" % (" ".join(o[1:]), med[o + ("mrays",)], ratio("mrays"),
                  ratio("cpu_mrays"), checks[o][0], checks.get(e, ("-",))[0]))
        elif (o + ("build_ms",)) in med:
            print("%-36s build %.1f ms vs %s ms" % (" ".join(o[1:]), med[o + ("build_ms",)],
                  "%.1f" % med[e + ("build_ms",)] if (e + ("build_ms",)) in med else "-"))
PY
echo "== cost per sample, bdpt / nee on scenes/cornell.scene (32 spp, all threads, CPU seconds, interleaved $runs times)"
for i in $(seq "$runs"); do
  for m in nee bdpt; do
    ./bdpt scenes/cornell.scene --method $m --spp 32 --out "$out/cost.png" |
      sed -n "s/.* s (\([0-9.e+-]*\) CPU s).*, \([0-9.]*\) rays per sample.*/$m \1 \2/p"
  done
done > "$out/cost.txt"
python3 - "$out/cost.txt" <<'PY'
import statistics, sys
t, rays = {}, {}
for line in open(sys.argv[1]):
    m, s, r = line.split()
    t.setdefault(m, []).append(float(s))
    rays[m] = float(r)
print("rays per sample: nee %.2f, bdpt %.2f (%.2fx); median CPU seconds nee %.2f, bdpt %.2f: %.2fx" % (rays["nee"], rays["bdpt"],
      rays["bdpt"] / rays["nee"], statistics.median(t["nee"]), statistics.median(t["bdpt"]),
      statistics.median(t["bdpt"]) / statistics.median(t["nee"])))
PY
# vcm's price: a pass against a bdpt pass (CPU seconds of the whole process, so the light pass's
# threads count), medians of interleaved runs; and the memory of one pass's light subpaths and
# grid, as vcm's summary line reports it, at the scene's resolution, 256x256 and 1024x1024.
python3 - "$runs" "$out" <<'PY'
import resource, statistics, subprocess, sys, re
runs, out = int(sys.argv[1]), sys.argv[2]
def cpu(args):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    text = subprocess.run(["./bdpt"] + args + ["--out", out + "/vcm.png"], capture_output=True, text=True, check=True).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, text
for scene in ("cornell", "sds-point"):
    t = {"bdpt": [], "vcm": []}
    for i in range(runs):
        for m in ("bdpt", "vcm"):
            t[m].append(cpu(["scenes/%s.scene" % scene, "--method", m, "--spp", "8"])[0])
    b, v = statistics.median(t["bdpt"]), statistics.median(t["vcm"])
    print("== cost per pass, vcm / bdpt on scenes/%s.scene (8 passes, CPU s, median of %d): bdpt %.2f, vcm %.2f: %.2fx" % (scene, runs, b, v, v / b))
    for res in ("", "256x256", "1024x1024"):
        text = cpu(["scenes/%s.scene" % scene, "--method", "vcm", "--spp", "1"] + (["--res", res] if res else []))[1]
        m = re.search(r"([0-9.]+) light vertices per pixel and pass, ([0-9.]+) of them mergeable; light subpaths and grid ([0-9.]+) MB \(([0-9]+) bytes", text)
        print("   memory of one pass's light subpaths and grid at %s: %s MB, %s bytes per light vertex (%s light vertices per pixel, %s mergeable)" %
              (res or "the scene's resolution", m.group(3), m.group(4), m.group(1), m.group(2)))
PY
# Where a sample's time goes: --profile's split (one thread, the time stamp counter), medians of
# interleaved runs, on cornell at 128x128.
python3 - "$runs" "$out" <<'PY'
import statistics, subprocess, sys, re
runs, out = int(sys.argv[1]), sys.argv[2]
methods = [("pt", []), ("nee --mis", ["--mis"]), ("bdpt", []), ("vcm", [])]
parts = ["tracing", "MIS", "merging", "shading and sampling"]
got = {m: [] for m, _ in methods}
for i in range(runs):
    for m, extra in methods:
        text = subprocess.run(["./bdpt", "scenes/cornell.scene", "--method", m.split()[0], "--spp", "8", "--res", "128x128", "--profile",
                               "--out", out + "/profile.png"] + extra, capture_output=True, text=True, check=True).stdout
        rays = float(re.search(r"([0-9.]+) rays per sample", text).group(1))
        line = re.search(r"profile \(one thread\): ([0-9.e+-]+) us per sample:(.*)", text)
        split = {p: float(re.search(re.escape(p) + r" ([0-9.e+-]+) \(", line.group(2)).group(1)) for p in parts}
        got[m].append((float(line.group(1)), rays, split))
print("== where a sample's time goes on scenes/cornell.scene (128x128, 8 spp, one thread, --profile; microseconds, median of %d)" % runs)
print("%-10s %6s %9s" % ("method", "rays", "us/sample") + "".join(" %21s" % p for p in parts))
for m, _ in methods:
    total = statistics.median(t for t, _, _ in got[m])
    row = "%-10s %6.2f %9.2f" % (m, got[m][0][1], total)
    for p in parts:
        v = statistics.median(s[p] for _, _, s in got[m])
        row += " %13.2f (%3.0f%%)" % (v, 100 * v / total)
    print(row)
PY
