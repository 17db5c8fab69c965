#!/usr/bin/env bash
# make bench-web: the WebAssembly build's time per sample against ./bdpt's, both on one thread,
# cornell with bdpt at 128x128. Each side renders 4 and 36 samples per pixel; the difference of
# their CPU seconds over 32 passes is the time per pass, free of start-up (Node compiling the
# module). Five rounds, the four runs of a round interleaved; medians. Prints only.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p build/web-bench
args=(scenes/cornell.scene --method bdpt --res 128x128 --threads 1 --quiet)
cpu() {  # CPU seconds (user + sys) of the command
  /usr/bin/time -f "%U %S" -o build/web-bench/time "$@" >/dev/null
  awk '{print $1 + $2}' build/web-bench/time
}
native=() wasm=()
for round in 1 2 3 4 5; do
  n4=$(cpu ./bdpt "${args[@]}" --spp 4 --out build/web-bench/n.png)
  w4=$(cpu node build/web-bench/bdpt.js "${args[@]}" --spp 4 --out build/web-bench/w.png)
  n36=$(cpu ./bdpt "${args[@]}" --spp 36 --out build/web-bench/n.png)
  w36=$(cpu node build/web-bench/bdpt.js "${args[@]}" --spp 36 --out build/web-bench/w.png)
  native+=("$(echo "$n36 $n4" | awk '{print ($1 - $2) / 32}')")
  wasm+=("$(echo "$w36 $w4" | awk '{print ($1 - $2) / 32}')")
done
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
mn=$(median "${native[@]}") mw=$(median "${wasm[@]}")
echo "cornell 128x128, bdpt, one thread, CPU seconds per pass (one sample per pixel), median of 5 rounds:"
echo "  ./bdpt (g++ $(grep -o -- '-O[0-9s]' build/flags | head -1))         ${mn} s   (rounds: ${native[*]})"
echo "  WebAssembly (em++ -O3 -msimd128 -msse2, Node $(node --version))  ${mw} s   (rounds: ${wasm[*]})"
echo "$mw $mn" | awk '{printf "  WebAssembly / native: %.2fx\n", $1 / $2}'
