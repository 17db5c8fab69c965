#!/usr/bin/env bash
# make bench: our BVH against Embree on the same rays, interleaved runs, ratios from one session.
# Two builds of ours: the portable one (SSE2, 4-wide nodes: ./bdpt) and build/bdpt-native
# (-march=native, 8-wide AVX nodes), the fair match for Embree, which picks its CPU's widest SIMD.
# Usage: tests/bench.sh [RUNS] [RAYS]   (defaults 3 runs of 4,194,304 rays per set)
set -euo pipefail
runs=${1:-3}; rays=${2:-4194304}
perf=../shared/perf
out=$(mktemp -d)
for i in $(seq "$runs"); do
  "$perf/run.sh" --rays "$rays" --reps 3 --build-reps 3 | grep -v '^info' > "$out/embree$i.txt"
  ./bdpt --bench-rays --bench-m "$rays" --bench-reps 3 > "$out/bdpt$i.txt"
  build/bdpt-native --bench-rays --bench-m "$rays" --bench-reps 3 | sed 's/^bdpt /bdpt-native /' > "$out/native$i.txt"
done
python3 "$perf/median.py" "$out"/embree*.txt "$out"/bdpt*.txt "$out"/native*.txt | tee "$out/median.txt"
for ours in bdpt bdpt-native; do
  echo "== ratios $ours / embree (median of $runs interleaved runs; cpu_mrays removes time slicing)"
  awk -v ours="$ours" '{ k=$2" "$3" "$4; for (i=5;i<=NF;i++){split($i,a,"="); v[$1,k,a[1]]=a[2]} keys[k]=1 }
     END { for (k in keys) if (v["embree",k,"mrays"] != "" && v[ours,k,"mrays"] != "")
             printf "%-40s mrays %.2fx  cpu_mrays %.2fx  hits %s vs %s\n", k, v[ours,k,"mrays"]/v["embree",k,"mrays"],
                    v[ours,k,"cpu_mrays"]/v["embree",k,"cpu_mrays"], v[ours,k,"hits"], v["embree",k,"hits"];
           else if (v["embree",k,"build_ms"] != "" && v[ours,k,"build_ms"] != "")
             printf "%-40s build %.1f ms vs %.1f ms\n", k, v[ours,k,"build_ms"], v["embree",k,"build_ms"] }' "$out/median.txt" | sort
done
echo "== cost per sample, bdpt / nee on scenes/cornell.scene (32 spp, all threads, interleaved $runs times)"
for i in $(seq "$runs"); do
  for m in nee bdpt; do
    ./bdpt scenes/cornell.scene --method $m --spp 32 --out "$out/cost.png" |
      sed -n "s/.* in \([0-9.e+-]*\) s.*, \([0-9.]*\) rays per sample.*/$m \1 \2/p"
  done
done > "$out/cost.txt"
python3 - "$out/cost.txt" <<'PY'
import statistics, sys
t, rays = {}, {}
for line in open(sys.argv[1]):
    m, s, r = line.split()
    t.setdefault(m, []).append(float(s))
    rays[m] = float(r)
print("nee  seconds:", t["nee"])
print("bdpt seconds:", t["bdpt"])
print("rays per sample: nee %.2f, bdpt %.2f (%.2fx)" % (rays["nee"], rays["bdpt"], rays["bdpt"] / rays["nee"]))
print("median ratio bdpt/nee: %.2fx" % (statistics.median(t["bdpt"]) / statistics.median(t["nee"])))
PY
rm -rf "$out"
