#!/usr/bin/env bash
# make class: the figures of a class on the slides, for a projector, into build/class/ (every
# image 1920x1080, its labels burned in large; nothing outside build/ is written):
#   six-panels-40spp.png       the slides' six panels (a)-(f) at 40 samples per pixel
#   six-panels-equal-time.png  the same six methods at equal CPU time each: the fair comparison
#   pyramid.png                bdpt's strategies p_{k,s}, row k = path length, s light vertices
#   mistake-*.png              the six deliberate mistakes: right, mistaken, their ratio, the factor named
#   sds-merging.png            sds-point: bdpt cannot reach L S D S E, vcm's merging can
#   metropolis.png             door-hidden: bdpt against Metropolis (mlt) at equal time, the ratio of their squared errors
#   error-vs-time-*.png        error against time, at most six methods a chart, one colour each
# Each comparison a titled 16:9 figure (1920x1080), the slides' captions under their images.
# About 6.5 minutes of CPU, 4.5 on an idle 2-core machine (CLASS_SECONDS=S, default 20, sets the
# equal-time runs: CPU seconds per method; a busy machine gives the same figures, later).
set -euo pipefail
cd "$(dirname "$0")/../.."
command -v gnuplot >/dev/null || { echo "make class: needs gnuplot, which is not installed (apt-get install gnuplot-nox); nothing done" >&2; exit 1; }
OUT=build/class
T=${CLASS_SECONDS:-20}
mkdir -p "$OUT/work"
start=$(date +%s)
step() { echo "make class [$(( $(date +%s) - start )) s]: $*"; }

six="pt,nee,lt,ir,ir --clamp 1e-5,bdpt"
step "the six panels at 40 samples per pixel"
./bdpt scenes/cornell-glass.scene --side-by-side "$six" --spp 40 --res 200x200 --quiet --out "$OUT/six-panels-40spp.png" \
  --title "Results from different techniques: 40 paths per pixel, as on the slides"
step "the six panels at equal CPU time ($T s each on one thread)"
./bdpt scenes/cornell-glass.scene --side-by-side "$six" --time "$T" --res 200x200 --quiet --out "$OUT/six-panels-equal-time.png" \
  --title "Results from different techniques at equal cost: the fair comparison"

step "the strategy pyramid"
./bdpt scenes/cornell.scene --spp 64 --res 224x224 --quiet --strategies "$OUT/work/strategies" --out "$OUT/work/strategies.png" >/dev/null
cp "$OUT/work/strategies/pyramid-weighted.png" "$OUT/pyramid.png"

step "sds-point: bdpt against vcm's merging ($T CPU s each)"
./bdpt scenes/sds-point.scene --side-by-side "pt,bdpt,vcm" --time "$T" --exposure -1 --quiet --out "$OUT/sds-merging.png" \
  --title "L S D S E: a point light's caustic seen through glass: bdpt has no strategy for it, vcm merges"
step "door-hidden: bdpt against mlt ($T CPU s each, RMSE against the reference)"
./bdpt scenes/door-hidden.scene --side-by-side "bdpt,mlt" --time "$T" --res 128x128 --ref scenes/refs/door-hidden.pfm --quiet \
  --ratio-panel error --out "$OUT/metropolis.png" --title "Light through a door ajar: Veach's Metropolis against bdpt"

# A deliberate mistake: right and mistaken side by side at the same samples, and the mistaken over
# the right in blocks (grey where the difference is within the noise), the factor in the title.
# With --ref among the options, the ratio is of the squared errors (a mistake that adds noise).
mistake() {  # name scene "method" spp flag what [option...]
  local name=$1 scene=$2 method=$3 spp=$4 flag=$5 what=$6 kind=mean
  shift 6
  [[ " $* " == *" --ref "* ]] && kind=error
  ./bdpt "$scene" --side-by-side "$method,$method $flag" --spp "$spp" --ratio-panel $kind --quiet \
    --title "A deliberate mistake: $what" --out "$OUT/mistake-$name.png" "$@"
  echo "    $OUT/mistake-$name.png"
}
step "the six deliberate mistakes"
mistake refraction scenes/refraction.scene lt 256 --symmetric-refraction "light tracing into a pool with eta^2, which only radiance has" --exposure -1
mistake shading-normals scenes/shading-normals.scene lt 64 --no-adjoint-correction "light paths through shading normals without the adjoint's correction"
mistake ray-offset tests/thin-gap.scene lt 4096 --fixed-ray-offset "a fixed ray offset over a lamp 0.5 mm above the floor: light lost at the gap" --exposure 1
mistake delta-density-one scenes/glass-box.scene bdpt 256 --delta-density-one "MIS densities after mirror and glass stored as 1: the caustic's noise" \
  --res 64x64 --ref scenes/refs/glass-box.pfm
mistake no-scramble scenes/cornell.scene pt 16 --no-scramble "Sobol points without their scrambles: every pixel draws the same points"
mistake fixed-start scenes/door.scene pssmlt 8 --fixed-start "every Metropolis chain starts from one state: start-up bias" \
  --res 64x64 --ref scenes/refs/door.pfm

# Error against time: each method for the same time on one thread, the RMSE of every pass against
# the scene's reference; two runs at a time. The methods are make charts' (their options and
# their chart styles, one colour each, from classroom/workshop/charts.sh).
chart() {  # scene title label...   (labels as classroom/workshop/charts.sh methods names them)
  local scene=$1 title=$2 plot="" i=0
  shift 2
  for label in "$@"; do
    local opts
    opts=$(classroom/workshop/charts.sh methods "$scene" | sed -n "s/^$label|//p")
    # shellcheck disable=SC2086
    ./bdpt "scenes/$scene.scene" $opts --res 64x64 --time "$((T / 4))" --threads 1 --quiet --ref "scenes/refs/$scene.pfm" \
      --log "$OUT/work/$scene-$label.csv" --out "$OUT/work/$scene-$label.png" &
    (( ++i % 2 == 0 )) && wait
  done
  wait
  # the keys as make charts writes them: a flat curve under another says so, a stub is left out
  while IFS='|' read -r label key; do
    [ -n "$key" ] || { echo "    $scene: $label left out: fewer than 3 passes in $((T / 4)) s (CLASS_SECONDS=$((T * 2)) gives it more)"; continue; }
    plot="$plot${plot:+, }'$OUT/work/$scene-$label.csv' using 6:13 with lines lw 4 $(classroom/workshop/charts.sh lineStyle "$label") title '$key'"
  done < <(classroom/workshop/charts.sh curveKeys "$OUT/work/$scene" "$@")
  gnuplot <<GP
set terminal pngcairo size 1920,1080 font "DejaVu Sans,30"
set output "$OUT/error-vs-time-$scene.png"
set datafile separator ","
set logscale xy
set key outside right
set grid
set autoscale fix
set offsets 0, 0, graph 0.05, graph 0.05
set title "$title\nRMSE against CPU seconds (64x64, one thread each)"
set xlabel "CPU seconds"
set ylabel "RMSE"
set format y "%g"
plot $plot
GP
  echo "    $OUT/error-vs-time-$scene.png"
}
step "error against time ($((T / 4)) s a run, two at a time)"
chart cornell-glass "cornell-glass: a mirror and a glass ball" pt nee-mis lt ir-clamp bdpt-balance vcm
chart sds-point "sds-point: light only along L S D S E" pt nee-mis bdpt-balance vcm
chart door "door: the light comes through a gap" pt lt bdpt-balance vcm mlt mmlt

rm -rf "$OUT/work" "$OUT"/*.pfm  # the panels' PFMs: the figures are the PNGs
step "done: $(ls "$OUT" | wc -l) figures in $OUT/"
