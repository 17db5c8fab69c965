#!/usr/bin/env bash
# make test's runner. The test program (all of tests/test_*.cpp in one, tests/all_tests.cpp) runs
# once per test file (doctest's --source-file), and every other program given runs whole, as many
# at once as there are cores (the tests render on one thread each: see quietOptions); each prints
# one line, in file order: the file, what it checks (its first comment line), its test cases
# passed and failed, and the seconds it took. A failing one's whole output follows its line; every
# output is kept in build/NAME.log. The last two lines give the time and the sum: "tests: N
# passed, N failed".
#   tests/run_tests.sh ALL_TESTS [PROGRAM ...]
set -u
all=$1
shift
passed=0 failed=0 status=0 start=$(date +%s)
rm -rf build/tmp && mkdir -p build/tmp  # the tests' own files, removed at the end
trap 'rm -rf build/tmp' EXIT
line() {  # name, log, exit status, seconds, description
  local counts p f
  counts=$(grep -E "test cases:" "$2" | tail -n 1)
  p=$(echo "$counts" | sed -E 's/.*\| *([0-9]+) passed.*/\1/;t;s/.*/0/')
  f=$(echo "$counts" | sed -E 's/.*\| *([0-9]+) failed.*/\1/;t;s/.*/1/')
  [ "$3" -eq 0 ] && [ "$f" -eq 0 ] && [ "$p" -gt 0 ] || { status=1; [ "$f" -gt 0 ] || f=1; }
  passed=$((passed + p)); failed=$((failed + f))
  printf '%-22s %3d passed %2d failed %5s s  %s\n' "$1" "$p" "$f" "$4" "$5"
  if [ "$f" -gt 0 ]; then sed 's/^/    /' "$2"; fi
}
jobs=${TEST_JOBS:-$(nproc 2>/dev/null || echo 2)}
names=() logs=() descriptions=() printed=0 running=0
start_job() {  # name, log, description, command...: runs in the background, its exit status and
  local log=$2  # seconds then in LOG.done
  names+=("$1") logs+=("$2") descriptions+=("$3")
  shift 3
  rm -f "$log.done"
  ( t0=$(date +%s.%N); "$@" --reporters=notes > "$log" 2>&1; rc=$?
    echo "$rc $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')" > "$log.done" ) &
  running=$((running + 1))
}
print_finished() {  # the lines of the finished jobs, in order, up to the first one still running
  while [ "$printed" -lt "${#names[@]}" ] && [ -s "${logs[$printed]}.done" ]; do
    local rc seconds
    read -r rc seconds < "${logs[$printed]}.done"
    rm -f "${logs[$printed]}.done"
    line "${names[$printed]}" "${logs[$printed]}" "$rc" "$seconds" "${descriptions[$printed]}"
    printed=$((printed + 1))
  done
}
run() {  # name, log, description, command...
  while [ "$running" -ge "$jobs" ]; do wait -n; running=$((running - 1)); print_finished; done
  start_job "$@"
}
for file in tests/test_*.cpp; do
  name=$(basename "$file" .cpp)
  description=$(sed -n "s/^$name //p" <<'TABLE'
test_bdpt bdpt: MIS weights, specular chains, strategy images
test_bvh the BVH against the brute-force loop
test_core hits, BSDFs, the furnace, options, bad input
test_first_hour a first hour's mistakes, each with its message
test_lecture bdpt.cpp alone as ./bdpt; fixed-seed images bit for bit
test_metrics error metrics, --ratio, the failure table
test_mlt Metropolis: the sampler, steps, regions over seeds
test_veach Veach's mutations: acceptance against T from scratch
test_notes the notes: citations, commands, formulas, numbers
test_numerics ray offsets, scales, film coordinates, MIS ranges
test_robustness malformed scenes, Ctrl-C, numerical edge cases
test_sampling chi-square of every sampling routine
test_sampler quasi-random numbers: nets, scrambles, means, error
test_suite_rules the suite's own rules: no test measures time
test_transport lt, ir, refraction, shading normals, clamp, nee --mis
test_vcm vcm: the hash grid, merges, the radius schedule
TABLE
)
  [ -n "$description" ] || description=$(head -n 1 "$file" | sed -E 's|^// *||' | cut -c1-60)
  run "$name" "build/$name.log" "$description" "$all" --source-file="*$file"
done
for program in "$@"; do
  run "$program" "$program.log" "the same tests, built as $(basename "$(dirname "$program")")" "$program"
done
wait
print_finished
# make test sets TEST_START before it compiles: the whole time, compiling included.
if [ -n "${TEST_START:-}" ]; then
  printf 'time: %d s in all, %d s of them compiling\n' "$(( $(date +%s) - TEST_START ))" "$(( start - TEST_START ))"
else
  printf 'time: %d s\n' "$(( $(date +%s) - start ))"
fi
printf 'tests: %d passed, %d failed\n' "$passed" "$failed"
exit $status
