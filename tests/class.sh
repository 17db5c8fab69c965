#!/usr/bin/env bash
# make class: the figures of a class on the slides, for a projector, into build/class/ (every
# image at least 1280x720, its labels burned in large; nothing outside build/ is written):
#   six-panels-40spp.png       the slides' six panels (a)-(f) at 40 samples per pixel
#   six-panels-equal-time.png  the same six methods with the same time each: the fair comparison
#   pyramid.png                bdpt's strategies p_{k,s}, row k = path length, s light vertices
#   mistake-*.png              each deliberate mistake as the ratio mistaken / right, its factor named
#   sds-merging.png            sds-point: bdpt cannot reach L S D S E, vcm's merging can
#   metropolis.png             door-hidden: bdpt against Metropolis (mlt) at equal time, with RMSE
#   error-vs-time-*.png        error against time, at most six methods a chart, one colour each
# About 4 minutes on a 2-core machine (CLASS_SECONDS=S, default 40, sets the equal-time runs).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v gnuplot >/dev/null || { echo "make class: needs gnuplot, which is not installed (apt-get install gnuplot-nox); nothing done" >&2; exit 1; }
OUT=build/class
T=${CLASS_SECONDS:-40}
mkdir -p "$OUT/work"
start=$(date +%s)
step() { echo "make class [$(( $(date +%s) - start )) s]: $*"; }

six="pt,nee,lt,ir,ir --clamp 1e-5,bdpt"
step "the six panels at 40 samples per pixel"
./bdpt scenes/cornell-glass.scene --side-by-side "$six" --spp 40 --quiet --out "$OUT/six-panels-40spp.png"
step "the six panels at equal time ($T s, all six at once)"
./bdpt scenes/cornell-glass.scene --side-by-side "$six" --time "$T" --quiet --out "$OUT/six-panels-equal-time.png"

step "the strategy pyramid"
./bdpt scenes/cornell.scene --spp 64 --res 224x224 --quiet --strategies "$OUT/work/strategies" --out "$OUT/work/strategies.png" >/dev/null
cp "$OUT/work/strategies/pyramid-weighted.png" "$OUT/pyramid.png"

step "sds-point: bdpt against vcm's merging ($T s each)"
./bdpt scenes/sds-point.scene --side-by-side "pt,bdpt,vcm" --time "$T" --exposure -1 --quiet --out "$OUT/sds-merging.png"
step "door-hidden: bdpt against mlt ($T s each, RMSE against the reference)"
./bdpt scenes/door-hidden.scene --side-by-side "bdpt,mlt" --time "$T" --res 128x128 --ref scenes/refs/door-hidden.pfm --quiet \
  --out "$OUT/metropolis.png"

# A deliberate mistake: the ratio image mistaken / right over 4x4 blocks (white equal, red the
# mistake brighter, blue darker, full colour at a factor of 2, its key above it), titled with its
# mean ratio.
mistake() {  # name scene method spp flag what
  local name=$1 scene=$2 method=$3 spp=$4 flag=$5 what=$6 ratio dir=$OUT/work/$1
  mkdir -p "$dir"  # files named right and mistake: the ratio figure's own title reads "mistake / right"
  ./bdpt "$scene" --method "$method" --spp "$spp" --quiet --out "$dir/right.png"
  ./bdpt "$scene" --method "$method" --spp "$spp" "$flag" --quiet --out "$dir/mistake.png"
  ratio=$(./bdpt --ratio "$dir/mistake.pfm" "$dir/right.pfm" --out "$dir/ratio.png" |
    sed -n 's/.*ratio of means \([0-9.]*\).*/\1/p')
  {
    echo 'set terminal pngcairo size 1280,720 font "sans,22"'
    echo "set output '$OUT/mistake-$name.png'"
    echo "set multiplot title \"$what\\n$flag: mistake / right = $ratio on average\" font 'sans,26'"
    echo "unset border; unset tics; unset key; set size ratio -1; set lmargin 1; set rmargin 1; set bmargin 1; set tmargin 2"
    local i=0
    for part in right mistake ratio; do
      echo "set origin $i / 3.0, 0; set size 1 / 3.0, 0.8; set title '$part'"
      echo "plot '$dir/$part.png' binary filetype=png with rgbimage"
      i=$((i + 1))
    done
    echo "unset multiplot"
  } | gnuplot
  echo "    $OUT/mistake-$name.png: ratio of means $ratio"
}
step "the deliberate mistakes"
mistake refraction scenes/refraction.scene lt 64 --symmetric-refraction "light tracing into the pool, eta^2 where radiance needs it"
mistake shading-normals scenes/shading-normals.scene lt 64 --no-adjoint-correction "light tracing with shading normals"
mistake ray-offset tests/thin-gap.scene lt 64 --fixed-ray-offset "a lamp 0.5 mm above the floor"

# Error against time: each method for the same time on one thread, the RMSE of every pass against
# the scene's reference; two runs at a time. The methods are make charts' (their options and
# their chart styles, one colour each, from tests/charts.sh).
chart() {  # scene title label...   (labels as tests/charts.sh methods names them)
  local scene=$1 title=$2 plot="" i=0
  shift 2
  for label in "$@"; do
    local opts
    opts=$(tests/charts.sh methods "$scene" | sed -n "s/^$label|//p")
    # shellcheck disable=SC2086
    ./bdpt "scenes/$scene.scene" $opts --res 64x64 --time "$((T / 4))" --threads 1 --quiet --ref "scenes/refs/$scene.pfm" \
      --log "$OUT/work/$scene-$label.csv" --out "$OUT/work/$scene-$label.png" &
    (( ++i % 2 == 0 )) && wait
  done
  wait
  for label in "$@"; do
    plot="$plot${plot:+, }'$OUT/work/$scene-$label.csv' using 6:13 with lines lw 4 $(tests/charts.sh lineStyle "$label") title '${label%-balance}'"
  done
  gnuplot <<GP
set terminal pngcairo size 1280,720 font "sans,22"
set output "$OUT/error-vs-time-$scene.png"
set datafile separator ","
set logscale xy
set key outside right
set grid
set autoscale fix
set offsets 0, 0, graph 0.05, graph 0.05
set title "$title (64x64, one thread each)"
set xlabel "seconds"
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
