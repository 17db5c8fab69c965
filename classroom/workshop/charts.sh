#!/usr/bin/env bash
# Speed against accuracy. Usage:
#   classroom/workshop/charts.sh refs      references of every scene (once; kept in scenes/refs/, reused)
#   classroom/workshop/charts.sh webrefs   the page's own references at the notes' other sizes (classroom/web/refs/)
#   classroom/workshop/charts.sh charts    every method for the same time on every scene: error-vs-time charts,
#                             the failure table and the reference check
#   classroom/workshop/charts.sh efficiency  make efficiency: error at equal samples and 1/(MSE x CPU-s)
#   classroom/workshop/charts.sh metropolisTable  make metropolis: the Markov chains against bdpt over 8 seeds
#   classroom/workshop/charts.sh panels    the six panels at 40 paths per pixel into build/panels/ (make panels)
#   classroom/workshop/charts.sh figures   the slides' six panels (a)-(f) at 40 paths per pixel and at equal time,
#                             the thin-gap figure, the combination-of-estimators example, the
#                             furnace's series and the door's uneven convergence (metropolis)
#   classroom/workshop/charts.sh notes     every figure of lecture_notes/, by the commands the pages show
#   classroom/workshop/charts.sh plots     the charts again from the logs of the last charts run (no rendering)
#   classroom/workshop/charts.sh tables    the failure table and the reference check from the runs' logs
#   classroom/workshop/charts.sh refcheck  the references' noise against the charted errors (also run by charts)
#   classroom/workshop/charts.sh samplers  --sampler sobol against random: pt, nee --mis, bdpt on cornell and
#                             on its direct light alone (also run by charts)
# Where results go: into build/charts/ (a student's run never changes a committed file), unless
# NOTES=1 (make figures), which writes the committed figures and tables of lecture_notes/ and
# splices the tables into the pages. Budgets: quick by default (charts 1.5 s a run, efficiency
# 64 samples and 2 seeds); FULL=1 (implied by NOTES=1) gives the notes' 4 s, 256 samples, 4 seeds.
# SCENES="a b" limits refs and charts to some scenes (the tables always cover all of them).
set -euo pipefail
cd "$(dirname "$0")/../.."
NOTES=${NOTES:-}
FULL=${FULL:-$NOTES}
RES=${RES:-64x64}                 # chart resolution (the references are made at it too)
REF_SECONDS=${REF_SECONDS:-90}    # per reference seed: far more than a run, so its noise is far below
# per method and scene (168 runs: 4 s each take 12 minutes, 1.5 s about 5)
if [ -n "$FULL" ]; then RUN_SECONDS=${RUN_SECONDS:-4}; else RUN_SECONDS=${RUN_SECONDS:-1.5}; fi
ALL_SCENES="cornell cornell-point cornell-glass glass-box indirect furnace refraction shading-normals sds sds-point sds-ior1 door"
SCENES=${SCENES:-$ALL_SCENES}
LOGS=build/charts
if [ -n "$NOTES" ]; then FIG=lecture_notes/figures; else FIG=$LOGS/figures; fi
RECORD=lecture_notes/appendix-a-record.md  # where the generated tables go (NOTES=1)
mkdir -p "$FIG" "$LOGS/refs" scenes/refs

# gnuplot draws every chart and figure: missing, say so before any work (Debian: gnuplot-nox).
case "${1:-charts}" in
  charts|panels|figures|plots|notes|estimators|furnaceseries|thingap|samplers)
    command -v gnuplot >/dev/null || { echo "classroom/workshop/charts.sh ${1:-charts}: needs gnuplot, which is not installed (apt-get install gnuplot-nox); nothing done" >&2; exit 1; } ;;
esac

# splice TABLE PAGE MARKER: the table replaces what stands between <!-- MARKER:start --> and
# <!-- MARKER:end --> in the page (NOTES=1 only: otherwise the table stays in build/).
splice() {
  [ -n "$NOTES" ] || return 0
  awk -v table="$1" -v marker="$3" '
    $0 ~ "<!-- " marker ":start -->" { print; while ((getline line < table) > 0) print line; skip = 1; next }
    $0 ~ "<!-- " marker ":end -->" { skip = 0 }
    !skip' "$2" > build/splice.tmp && mv build/splice.tmp "$2"
  echo "spliced $1 into $2"
}

clampFor() {  # G is in the scene's units: a clamp that removes a visible share in each
  case $1 in cornell*|indirect|shading-normals) echo 1e-5 ;; furnace) echo 0.1 ;; refraction) echo 0.05 ;; *) echo 0.2 ;; esac
}
# One style per method, the same in every chart, and within any one chart a colour per method
# (colour-blind safe: Okabe-Ito, and a few darker tones): pt black, nee blue, lt sky blue, ir
# purple, bdpt vermilion, vcm bluish green, mlt dark gold; a method's variant is dashed where the
# chart that shows it has no other method of its colour.
lineStyle() {
  case $1 in
    pt) echo "lc rgb '#000000' dt 1" ;;          nee) echo "lc rgb '#0072b2' dt 2" ;;
    nee-mis) echo "lc rgb '#0072b2' dt 1" ;;     lt) echo "lc rgb '#56b4e9' dt 1" ;;
    ir) echo "lc rgb '#cc79a7' dt 2" ;;          ir-clamp) echo "lc rgb '#cc79a7' dt 1" ;;
    bdpt-balance) echo "lc rgb '#d55e00' dt 1" ;; bdpt-power) echo "lc rgb '#e69f00' dt 1" ;;
    bdpt-max) echo "lc rgb '#7f2704' dt 1" ;;    bdpt-uniform) echo "lc rgb '#666666' dt 1" ;;
    vcm) echo "lc rgb '#009e73' dt 1" ;;
    mlt) echo "lc rgb '#8c6d00' dt 1" ;;         pssmlt) echo "lc rgb '#56b4e9' dt 2" ;;
    mmlt) echo "lc rgb '#cc79a7' dt 3" ;;
    *) echo "lc rgb '#999999' dt 1" ;;
  esac
}

# Each scene's runs in three charts of at most six curves, each chart a question: which method
# (error-vs-time-SCENE.png), which variant of bdpt, nee and ir (-variants.png), and Metropolis
# against bdpt (-metropolis.png).
chartGroups() {
  echo "|pt nee-mis lt ir-clamp bdpt-balance vcm"
  echo "-variants|bdpt-balance bdpt-power bdpt-max bdpt-uniform nee ir"
  echo "-metropolis|bdpt-balance mlt pssmlt mmlt"
}

styles() {  # every method's chart style, and the charts' groups: tests/test_notes.cpp checks them
  methods cornell | while IFS='|' read -r label opts; do echo "$label $(lineStyle "$label")"; done
  chartGroups | while IFS='|' read -r suffix group; do echo "chart$suffix $group"; done
}

# The fourteen runs of every scene: label|options
methods() {
  printf '%s\n' "pt|--method pt" "nee|--method nee" "nee-mis|--method nee --mis" "lt|--method lt" "ir|--method ir" \
    "ir-clamp|--method ir --clamp $(clampFor "$1")" "bdpt-balance|--method bdpt --heuristic balance" \
    "bdpt-power|--method bdpt --heuristic power" "bdpt-max|--method bdpt --heuristic max" \
    "bdpt-uniform|--method bdpt --heuristic uniform" "vcm|--method vcm" "mlt|--method mlt" "pssmlt|--method pssmlt" "mmlt|--method mmlt"
}

# The method that converges fastest on each scene at the chart resolution (measured: its two seeds
# differ least after equal time), so the reference beats every charted run by the widest margin.
refMethod() {
  case $1 in
    cornell|indirect|door|door-side) echo lt ;;  # diffuse and glossy: one light path lands on many pixels
    shading-normals) echo nee ;;       # lt's adjoint factor at grazing shading normals makes rare huge splats:
                                       # one seed of 2 x 90 s carried a pixel 40 times too bright
    door-hidden) echo mlt ;;                      # every visible path passes the hidden gap
    cornell-glass) echo bdpt ;;                   # on the charts' pixels (the lamp's left out) bdpt beats nee there
    refraction) echo pt ;;                        # light arrives through the water: eye paths hit the sky
    sds) echo vcm ;;                              # merges make L S D S E cheaply; pt's 2 x 90 s were as noisy as vcm's 4 s
    sds-point) echo vcm ;;                        # only merging reaches L S D S E
    sds-ior1) echo nee ;;                         # exact: the room without its index-1 balls (refScene)
    *) echo bdpt ;;                               # point lights: lt would show the light as a pixel
  esac
}
# Extra options of a scene's reference run (none so far: sds-point's vcm keeps the default
# radius, which after its ~17,000 passes has shrunk to 0.3 of a chart run's first one; a
# quarter of it left the two seeds 0.038 apart in RMSE, as noisy as a chart run).
refOptions() { if [ "$1" = door-hidden ]; then echo "--bootstrap 8000000"; fi; }
# door-hidden (not charted; make metropolis measures it at 64x64 and 128x128, averaging the
# reference down) is made at 128x128, by mlt, the method that converges best there.
refRes() { if [ "$1" = door-hidden ]; then echo 128x128; else echo "$RES"; fi; }
refScene() { if [ "$1" = sds-ior1 ]; then echo tests/sds-ior1-open.scene; else echo "scenes/$1.scene"; fi; }

# sds-point's reference (vcm) makes the fewest samples per second: 4 times the time.
refSeconds() {
  case $1 in sds-point) echo $((REF_SECONDS * 4)) ;; door-hidden) echo $((REF_SECONDS * 18)) ;; *) echo "$REF_SECONDS" ;; esac
}

# Per scene: the chosen method with two seeds no chart run uses (charts use seed 1), refSeconds
# each; the reference is their mean, and their difference measures its noise. The furnace has an
# exact answer, Le / (1 - albedo) = 2 in every pixel, written directly. SCENES=... remakes some
# references and keeps the rows of the others in refs.csv.
refs() {
  local csv=scenes/refs/refs.csv row
  [ -f $csv ] || echo "scene,method,seconds_per_seed,spp_seed1,spp_seed2,rmse_between_seeds,relmse_between_seeds,rmse_without_lamp_between_seeds" > $csv
  local list=$SCENES
  [ "$SCENES" != "$ALL_SCENES" ] || list="$ALL_SCENES door-hidden door-side"
  for s in $list; do
    if [ "$s" = furnace ]; then
      furnaceReference scenes/refs/furnace.pfm
      ./bdpt --average scenes/refs/furnace.pfm scenes/refs/furnace.pfm --out scenes/refs/furnace.png --overwrite
      row="furnace,analytic,0,0,0,0,0"
      echo "reference furnace: analytic, 2 in every pixel"
    else
      local m secs
      m=$(refMethod "$s"); secs=$(refSeconds "$s")
      for seed in 101 102; do
        # shellcheck disable=SC2086
        ./bdpt "$(refScene "$s")" --method $m $(refOptions "$s") --res "$(refRes "$s")" --time "$secs" --seed $seed --quiet \
          --out "$LOGS/refs/$s-$seed.png" --log "$LOGS/refs/$s-$seed.csv"
      done
      ./bdpt --average "$LOGS/refs/$s-101.pfm" "$LOGS/refs/$s-102.pfm" --out scenes/refs/$s.png --overwrite
      diff=$(./bdpt --compare "$LOGS/refs/$s-102.pfm" "$LOGS/refs/$s-101.pfm")
      spp1=$(tail -1 "$LOGS/refs/$s-101.csv" | cut -d, -f5); spp2=$(tail -1 "$LOGS/refs/$s-102.csv" | cut -d, -f5)
      row="$s,$m,$secs,$spp1,$spp2,$(echo "$diff" | awk '{print $2","$4","$10}')"
      echo "reference $s: $m, $spp1 + $spp2 spp in 2 x $secs s; seed 101 vs seed 102: $diff"
    fi
    { grep -v "^$s," $csv; echo "$row"; } > $csv.tmp && mv $csv.tmp $csv
  done
}

# The page's own references (classroom/web/refs/NAME-WxH.pfm), for the notes' buttons whose size
# and aspect meet no committed reference at 16 pixels or more: the same methods and seeds as
# refs(), refSeconds / 1.5 a seed (the page's runs are short: their noise stays far below a
# panel's), with the seeds' difference printed. make web-refs.
webrefs() {
  mkdir -p classroom/web/refs
  for entry in cornell-glass:50x50 refraction:64x48 sds:96x64 sds-point:96x64; do
    local s=${entry%:*} res=${entry#*:} m secs
    m=$(refMethod "$s"); secs=$(( $(refSeconds "$s") * 2 / 3 ))
    for seed in 101 102; do
      ./bdpt "scenes/$s.scene" --method $m --res "$res" --time "$secs" --seed $seed --quiet --overwrite --out "$LOGS/refs/$s-$res-$seed.png"
    done
    ./bdpt --average "$LOGS/refs/$s-$res-101.pfm" "$LOGS/refs/$s-$res-102.pfm" --out "$LOGS/refs/$s-$res.png" --overwrite
    mv "$LOGS/refs/$s-$res.pfm" "classroom/web/refs/$s-$res.pfm"
    echo "page reference $s at $res: $m, 2 x $secs s; seed 101 vs 102: $(./bdpt --compare "$LOGS/refs/$s-$res-102.pfm" "$LOGS/refs/$s-$res-101.pfm")"
  done
}

# A PFM of the resolution RES whose every value is 2.0f (bytes 00 00 00 40, little-endian).
furnaceReference() {
  local w=${RES%x*} h=${RES#*x}
  { printf 'PF\n%d %d\n-1.0\n' "$w" "$h"
    for ((i = 0; i < w * h * 3; ++i)); do printf '\x00\x00\x00\x40'; done; } > "$1.tmp" && mv "$1.tmp" "$1"
}

charts() {
  local n; n=$(( $(echo $SCENES | wc -w) * $(methods cornell | wc -l) ))
  # each run's start-up, the samplers' 12 runs and the charts: about 0.5 s a run more (measured)
  echo "charts: $n runs of $RUN_SECONDS s, about $(awk -v n=$n -v t=$RUN_SECONDS 'BEGIN { printf "%.0f", n * (t + 0.5) / 60 }') minutes, into $FIG/"
  for s in $SCENES; do
    [ -f scenes/refs/$s.pfm ] || { echo "no reference scenes/refs/$s.pfm: run make refs" >&2; exit 1; }
    while IFS='|' read -r label opts; do
      # shellcheck disable=SC2086
      ./bdpt scenes/$s.scene $opts --res "$RES" --time "$RUN_SECONDS" --quiet --ref scenes/refs/$s.pfm \
        --log "$LOGS/$s-$label.csv" --out "$LOGS/$s-$label.png"
    done < <(methods "$s")
    plotScene "$s"
  done
  SCENES=$ALL_SCENES tables
  samplers
}

# The two samplers side by side (notes, page 9): pt, nee --mis and bdpt with --sampler sobol
# (solid) and random (dashed) on cornell, and on its direct light alone (--maxdepth 1), where
# stratification helps most; each curve's fitted slope d log RMSE / d log t in its key.
samplerMethods() {
  printf '%s\n' "pt|--method pt" "nee-mis|--method nee --mis" "bdpt-balance|--method bdpt"
}
samplers() {
  local ref=$LOGS/refs/cornell-direct.pfm
  if [ ! -f "$ref" ]; then  # direct light's reference: nee --mis, 2 seeds no chart run uses
    for seed in 101 102; do
      ./bdpt scenes/cornell.scene --method nee --mis --maxdepth 1 --res "$RES" --time 30 --seed $seed --quiet \
        --out "$LOGS/refs/cornell-direct-$seed.png"
    done
    ./bdpt --average "$LOGS/refs/cornell-direct-101.pfm" "$LOGS/refs/cornell-direct-102.pfm" --out "$LOGS/refs/cornell-direct.png" --overwrite
  fi
  for variant in cornell cornell-direct; do
    local depth="" reference=scenes/refs/cornell.pfm
    [ "$variant" = cornell-direct ] && depth="--maxdepth 1" reference=$ref
    while IFS='|' read -r label opts; do
      for sampler in sobol random; do
        log=$LOGS/samplers-$variant-$label-$sampler.csv
        # shellcheck disable=SC2086
        ./bdpt scenes/cornell.scene $opts $depth --sampler $sampler --res "$RES" --time "$RUN_SECONDS" --quiet \
          --ref "$reference" --log "$log" --out "${log%.csv}.png"
      done
    done < <(samplerMethods)
    samplerPlot $variant
  done
}
samplerPlot() {
  local variant=$1 plot="" what="cornell, all light"
  [ "$variant" = cornell-direct ] && what="cornell, direct light only (--maxdepth 1)"
  while IFS='|' read -r label opts; do
    for sampler in sobol random; do
      log=$LOGS/samplers-$variant-$label-$sampler.csv
      # least squares of log RMSE (without the lamp) on log seconds, from the 8th pass on
      slope=$(awk -F, 'NR > 1 && $5 >= 8 && $13 > 0 { x = log($6); y = log($13); n++; sx += x; sy += y; sxx += x * x; sxy += x * y }
        END { if (n > 2) printf "%.2f", (n * sxy - sx * sy) / (n * sxx - sx * sx); else printf "?" }' "$log")
      colour=$(lineStyle "$label" | sed "s/ dt .*//")
      dash=1; [ $sampler = random ] && dash=2
      plot="$plot${plot:+, }'$log' using 6:13 with lines lw 4 $colour dt $dash title '${label%-balance} $sampler (slope $slope)'"
    done
  done < <(samplerMethods)
  gnuplot <<GP
set terminal pngcairo size 1920,1080 font "DejaVu Sans,26"
set output "$FIG/error-vs-time-samplers-$variant.png"
set datafile separator ","
set logscale xy
set key outside right
set grid
set title "$what, $RES, $RUN_SECONDS CPU s a run\n--sampler sobol (solid) and random (dashed)"
set xlabel "CPU seconds (2 threads together)"
set ylabel "RMSE without the lamp's pixels"
set format y "%g"
plot $plot
GP
  echo "chart $FIG/error-vs-time-samplers-$variant.png"
}

# efficiencyRows PATTERN: the efficiency table's rows that match PATTERN, under its header.
efficiencyRows() {
  grep -E "$1" "$FIG/efficiency.md" |
    { echo '| scene | method | MSE | CPU-s | rays/sample | efficiency vs nee --mis | MSE share seen via mirror or glass |'
      echo '|---|---|---|---|---|---|---|'; cat; }
}

# make efficiency (tests/efficiency.cpp): its table in build/efficiency.md; with NOTES=1 also
# lecture_notes/figures/efficiency.md, spliced into Appendix A's record, and page 16's rows of it.
efficiency() {
  make -s build/efficiency
  local budget="--spp 64 --seeds 2" minutes=3
  [ -n "$FULL" ] && budget="--spp 256 --seeds 4" minutes=25
  echo "efficiency: $budget, about $minutes minutes, into build/efficiency.md"
  # shellcheck disable=SC2086
  ./build/efficiency $budget ${EFFICIENCY_ARGS:-} > build/efficiency.md.tmp && mv build/efficiency.md.tmp build/efficiency.md
  cat build/efficiency.md
  [ -n "$NOTES" ] || return 0
  cp build/efficiency.md "$FIG/efficiency.md"
  splice "$FIG/efficiency.md" "$RECORD" efficiency
  efficiencyRows '^\| (door|cornell|cornell-glass|glass-box) \| (nee --mis|lt|bdpt|mlt|pssmlt|mmlt) \|' > build/metropolis-efficiency.md
  splice build/metropolis-efficiency.md "$RECORD" metropolis-efficiency
  efficiencyRows '^\| (cornell|cornell-glass|indirect|glass-box) \| (pt|nee|nee --mis|bdpt)( --sampler random)? \|' > build/samplers-efficiency.md
  splice build/samplers-efficiency.md lecture_notes/appendix-c-quasi-random-numbers.md samplers-efficiency
  # Appendix A's roulette rows: bdpt's three rules, the choice bdpt's banner names
  # shellcheck disable=SC2086
  ./build/efficiency $budget --alternatives --only "bdpt --roulette" --scenes cornell,cornell-glass,indirect,glass-box > "$FIG/roulette.md"
  splice "$FIG/roulette.md" "$RECORD" roulette
}

# make metropolis (tests/efficiency.cpp --metropolis): the Markov chains against bdpt, 8 seeds, into
# build/metropolis.md, and Veach's table of mlt's mutations (--mutations) into build/mutations.md;
# with NOTES=1 also lecture_notes/figures/metropolis.md and mutations.md, spliced into Appendix A's record.
metropolisTable() {
  make -s build/efficiency
  echo "metropolis: 8 seeds of bdpt, mlt, pssmlt and mmlt on door-hidden, door-side and cornell, one thread: about 50 minutes"
  ./build/efficiency --mutations --scenes cornell-glass,glass-box,indirect,door,door-side > build/mutations.md.tmp && mv build/mutations.md.tmp build/mutations.md
  cat build/mutations.md
  ./build/efficiency --metropolis --seeds 8 --scenes door-hidden,door-side,cornell > build/metropolis.md.tmp && mv build/metropolis.md.tmp build/metropolis.md
  cat build/metropolis.md
  [ -n "$NOTES" ] || return 0
  cp build/metropolis.md "$FIG/metropolis.md"
  cp build/mutations.md "$FIG/mutations.md"
  splice "$FIG/metropolis.md" "$RECORD" metropolis
  splice "$FIG/mutations.md" "$RECORD" mutations
}

plots() {  # the charts again from the runs' logs, without rendering (after a change of style)
  for s in $SCENES; do plotScene "$s"; done
  for variant in cornell cornell-direct; do samplerPlot $variant; done
}

# curveKeys PREFIX LABEL...: "label|key" for each run PREFIX-LABEL.csv, the key its curve's title:
# empty for a run of fewer than 3 passes (a Markov chain's bootstrap in a quick run: no curve, left
# out of the chart and its key), "nee-mis (under pt)" for a flat curve at the RMSE of one drawn
# before it (the same method of failure: it lies under the other and would not be seen).
curveKeys() {
  local prefix=$1 flat=() label
  shift
  for label in "$@"; do
    local log=$prefix-$label.csv name=${label%-balance} key rows lo hi
    rows=$(awk -F, 'NR > 1 && $13 > 0' "$log" | wc -l)
    if [ "$rows" -lt 3 ]; then echo "$label|"; continue; fi
    key=$name
    read -r lo hi < <(awk -F, 'NR > 1 && $13 > 0 { if (!n++ || $13 < lo) lo = $13; if ($13 > hi) hi = $13 } END { print lo, hi }' "$log")
    for f in "${flat[@]}"; do
      read -r other value <<< "$f"
      awk -v a="$lo" -v b="$hi" -v v="$value" 'BEGIN { exit !(b < 1.02 * a && a < 1.02 * v && v < 1.02 * b) }' && key="$name (under $other)"
    done
    awk -v a="$lo" -v b="$hi" 'BEGIN { exit !(b < 1.02 * a) }' && flat+=("$name $lo")
    echo "$label|$key"
  done
}

plotScene() {
  local s=$1
  refnoise=$(refNoise "$s")
  while IFS='|' read -r suffix group; do
    local plot="" logs=() left=()
    while IFS='|' read -r label key; do
      if [ -z "$key" ]; then left+=("${label%-balance}"); continue; fi
      # column 13, rmse_without_lamp: the lamp's pixels and their neighbours left out, as make
      # efficiency does, so that the charts and its table rank the methods on the same pixels
      plot="$plot${plot:+, }'$LOGS/$s-$label.csv' using 6:13 with lines lw 4 $(lineStyle "$label") title '$key'"
      logs+=("$LOGS/$s-$label.csv")
    done < <(curveKeys "$LOGS/$s" $group)
    [ ${#left[@]} -eq 0 ] || echo "chart $FIG/error-vs-time-$s$suffix.png: left out ${left[*]}: too few passes in $RUN_SECONDS s (FULL=1 gives 4 s a run)"
    [ ${#logs[@]} -gt 0 ] || continue
    # an exact reference (the furnace) has no noise to draw on a log scale
    [ "${refnoise:-0}" = 0 ] || plot="$plot, $refnoise with lines lw 2 dt 2 lc rgb '#333333' title 'reference noise'"
    # The y range: the curves' own, from the smallest final error (or the reference's noise, if
    # lower) to the largest error, a little wider: no empty decades below the data.
    range=$(awk -F, -v noise="${refnoise:-0}" 'FNR > 1 && $13 > 0 { last[FILENAME] = $13; if ($13 > hi) hi = $13 }
      END { lo = 1e30; for (f in last) if (last[f] < lo) lo = last[f]
            if (noise > 0 && noise < lo) lo = noise
            printf "%g:%g", lo / 1.5, hi * 1.5 }' "${logs[@]}")
    gnuplot <<GP
set terminal pngcairo size 1920,1080 font "DejaVu Sans,26"
set output "$FIG/error-vs-time-$s$suffix.png"
set datafile separator ","
set logscale xy
set yrange [$range]
set key outside right
set grid
set title "$s ($RES): error against CPU time\nRMSE without the lamp's pixels, $RUN_SECONDS CPU s a run on 2 threads"
set xlabel "CPU seconds"
set ylabel "RMSE"
set format y "%g"
plot $plot
GP
    echo "chart $FIG/error-vs-time-$s$suffix.png"
  done < <(chartGroups)
}

# The failure table and the reference check, from the logs of every scene's runs.
tables() {
  local logs=()
  for s in $SCENES; do while IFS='|' read -r label opts; do logs+=("$LOGS/$s-$label.csv"); done < <(methods "$s"); done
  # bdpt --failure-table marks a run of too few passes "(few passes)" and warns of it
  ./bdpt --failure-table "${logs[@]}" > "$FIG/failure-table.md"
  echo "failure table: $FIG/failure-table.md"
  splice "$FIG/failure-table.md" "$RECORD" failure-table
  refcheck
}

# Is every reference far better than what the charts measure? Per scene: the noise of the
# reference (the mean of two seeds: RMSE between them / 2) against the smallest final RMSE of any method.
# A reference's noise, on the pixels the charts measure: half the RMSE between its two seeds
# without the lamp's pixels (the noise of their mean), or, for a reference made before refs.csv
# had that column, over every pixel, which the lamp's edge pixels make larger: an upper bound.
refNoise() {
  awk -F, -v s="$1" '$1 == s { print ($8 != "" ? $8 : $6) / 2 }' scenes/refs/refs.csv
}
refcheck() {
  {
    echo "| scene | reference | spp (2 seeds) | reference noise | smallest charted error at ${RUN_SECONDS} s | ratio |"
    echo "|---|---|---|---|---|---|"
    for s in $SCENES; do
      # the smallest final RMSE of this scene's runs on the charts' pixels (without the lamp's), and which method made it
      best=$(methods "$s" | while IFS='|' read -r label opts; do echo "$(tail -1 "$LOGS/$s-$label.csv" | cut -d, -f13) $label"; done |
        sort -g | head -1)
      awk -F, -v s="$s" -v best="$best" -v n="$(refNoise "$s")" '$1 == s { split(best, b, " "); mark = ($8 != "" ? "" : " (all pixels)")
        if ($2 == "analytic") printf "| %s | analytic | - | 0 | %.4f (%s) | exact |\n", s, b[1], b[2]
        else printf "| %s | %s, 2 x %d s | %d + %d | %.5f%s | %.4f (%s) | %.1f |\n", s, $2, $3, $4, $5, n, mark, b[1], b[2], b[1] / n }' scenes/refs/refs.csv
    done
  } > "$FIG/reference-check.md"
  echo "reference check: $FIG/reference-check.md"
  splice "$FIG/reference-check.md" "$RECORD" reference-check
}

# The slides' six panels (a)-(f) on cornell-glass, one figure per KIND: 40 (paths per pixel) or
# time (every method for the time bdpt needs for 40), in $FIG/six-panels-KIND.png.
sixPanels() {
  local scene=cornell-glass panels="pt|(a) Unidirectional (eye tracing): pt|--method pt
nee|(b) Unidirectional + next event: nee|--method nee
lt|(c) Next event (light tracing): lt|--method lt
ir|(d) Instant radiosity: ir|--method ir
irc|(e) Instant radiosity (clamped): ir --clamp 1e-5|--method ir --clamp 1e-5
bdpt|(f) Bidirectional path tracing: bdpt|--method bdpt"
  mkdir -p "$LOGS/fig" "$FIG"
  for kind in "$@"; do
    if [ "$kind" = 40 ]; then
      while IFS='|' read -r name title opts; do
        ./bdpt scenes/$scene.scene $opts --spp 40 --quiet --out "$LOGS/fig/$name-40.png"
      done <<< "$panels"
    else
      t=$(./bdpt scenes/$scene.scene --method bdpt --spp 40 --out "$LOGS/fig/t.png" | sed -n 's/.* s (\([0-9.e+-]*\) CPU s).*/\1/p')
      while IFS='|' read -r name title opts; do
        ./bdpt scenes/$scene.scene $opts --time "$t" --out "$LOGS/fig/$name-time.png" |
          sed -n 's/.*: \([0-9]*\) samples per pixel in.*/\1/p' > "$LOGS/fig/$name-time.spp"
      done <<< "$panels"
    fi
    caption="40 paths per pixel"; [ "$kind" = time ] && caption="equal CPU time: $t s each (what bdpt needs for 40 paths per pixel)"
    {
      echo 'set terminal pngcairo size 1200,880 font "sans,12"'
      echo "set output '$FIG/six-panels-$kind.png'"
      echo "set multiplot layout 2,3 title '$scene, $caption' font ',14'"
      echo 'unset border; unset tics; unset key; set size ratio -1; set lmargin 0; set rmargin 0; set tmargin 3.5; set bmargin 0'
      while IFS='|' read -r name title opts; do
        spp=40; [ "$kind" = time ] && spp=$(cat "$LOGS/fig/$name-time.spp")
        echo "set title '$title, $spp spp'"
        echo "plot '$LOGS/fig/$name-$kind.png' binary filetype=png with rgbimage"
      done <<< "$panels"
      echo 'unset multiplot'
    } | gnuplot
    echo "figure $FIG/six-panels-$kind.png"
  done
}

# make panels: the six panels at 40 paths per pixel for a class, into build/panels/ (no committed
# file is touched; make figures makes the committed ones).
panels() {
  FIG=build/panels LOGS=build/panels sixPanels 40
}

figures() {
  [ -n "$NOTES" ] && python3 classroom/workshop/diagrams.py  # the pages' path diagrams (figures/path-*.svg)
  thingap
  estimators
  furnaceseries
  metropolis
}

# Page 16's uneven convergence: bdpt, mlt, pssmlt and mmlt on the door at equal time, per region
# (classroom/workshop/uneven.cpp): its figure into $FIG, its table spliced into the page.
metropolis() {
  make -s build/uneven
  ./build/uneven --out "$FIG" | sed -n '/^|/p' > "$FIG/uneven-door.md"
  echo "figure $FIG/uneven-door.png and table $FIG/uneven-door.md"
  splice "$FIG/uneven-door.md" "$RECORD" uneven
}

# Page 10's "Combination of Estimators: Example": four paths of k = 2 segments on cornell, each
# strategy X a rectangle of width p_X and height f/p_X (both relative to the widest), so all three
# have the path's f as their area; max keeps the filled one, balance shares by width.
estimators() {
  make -s build/estimators
  local rows="62 78 94 150" ymax=4
  ./build/estimators $rows > "$LOGS/estimators.txt"
  {
    echo 'set terminal pngcairo size 1000,760 font "sans,11"'
    echo "set output '$FIG/combination-of-estimators.png'"
    echo "set multiplot layout 2,2 title \"cornell: four paths of k = 2 segments, lamp centre -> the point seen in image row R of the middle column -> eye\\nA = p_{2,0} (a BSDF sample hits the lamp), B = p_{2,1} (next event), C = p_{2,2} (light tracing); filled: the one max keeps\" font ',11'"
    echo "set xrange [0:3.6]; set yrange [0:$ymax]; unset xtics; set ytics 1; set key off; set tmargin 4; set bmargin 3"
    echo "set xlabel 'width: p_X / largest p' offset 0,-0.5; set ylabel 'height: (f/p_X) / (f/largest p)'"
    grep -v '^#' "$LOGS/estimators.txt" | while read -r row surface pa pb pc wa wb wc best cosLamp distance; do
      echo "unset object; unset label"
      x=0.1 i=1
      for X in A B C; do
        case $X in A) p=$pa w=$wa ;; B) p=$pb w=$wb ;; C) p=$pc w=$wc ;; esac
        h=$(awk -v p="$p" -v m="$ymax" 'BEGIN { h = 1 / p; print (h > m ? m : h) }')
        x2=$(awk -v x="$x" -v p="$p" 'BEGIN { print x + p }')
        fill="fs empty border lc rgb '#333333'"; [ "$X" = "$best" ] && fill="fc rgb '#d55e00' fs solid 0.8 border lc rgb '#333333'"
        echo "set object $i rect from $x,0 to $x2,$h $fill"
        echo "set label $i '$X' at $(awk -v a="$x" -v b="$x2" 'BEGIN { print (a + b) / 2 }'),-0.2 center font ',11'"
        echo "set label $((i + 3)) '$X: width $(printf %.3g "$p"), height $(awk -v p="$p" 'BEGIN { printf (1 / p >= 100 ? "%.0f" : "%.3g"), 1 / p }'), balance $(printf %.3f "$w")' at graph 0.3,graph $(awk -v i=$i 'BEGIN { print 1.0 - 0.07 * i }') font ',10'"
        x=$(awk -v x="$x2" 'BEGIN { print x + 0.15 }')
        i=$((i + 1))
      done
      echo "set title 'row $row ($surface): max keeps $best' offset 0,-0.3"
      echo "plot -1 notitle"
    done
    echo 'unset multiplot'
  } | gnuplot
  echo "figure $FIG/combination-of-estimators.png"
}

# Page 4's von Neumann series in the furnace: the image mean after D bounces against its partial
# sum Le (1 - a^(D+1)) / (1 - a), a = 0.5 (pt is exact there: no roulette before 3 bounces, and
# cosine sampling gives every path the same weight).
furnaceseries() {
  mkdir -p "$LOGS/fig"
  : > "$LOGS/furnace-series.txt"
  for d in 0 1 2 3 4 5 6 7 8; do
    mean=$(./bdpt scenes/furnace.scene --method pt --maxdepth $d --rr-start 99 --spp 4 --res 32x32 --out "$LOGS/fig/furnace-$d.png" | sed -n 's/.* mean \([0-9.e+-]*\),.*/\1/p')
    echo "$d $mean" >> "$LOGS/furnace-series.txt"
  done
  {
    echo 'set terminal pngcairo size 640,400 font "sans,11"'
    echo "set output '$FIG/furnace-series.png'"
    echo "set title 'the furnace (albedo a = 0.5, Le = 1), term by term'"
    echo "set xlabel '--maxdepth D (the series kept up to the term of D bounces)'; set ylabel 'image mean'"
    echo "set key bottom right; set yrange [0:2.2]; set xrange [-0.3:8.3]; set grid"
    echo "plot (1 - 0.5**(floor(x + 0.5) + 1)) / 0.5 with steps lc rgb '#999999' title 'Le (1 - a^{D+1}) / (1 - a)', \\"
    echo "     2 with lines dt 2 lc rgb '#999999' title 'Le / (1 - a) = 2', \\"
    echo "     '$LOGS/furnace-series.txt' using 1:2 with points pt 7 ps 1.5 lc rgb '#000000' title 'pt, image mean', \\"
    echo "     '' using 1:2:(sprintf('%.4g', \$2)) with labels offset 0,1.2 font ',9' notitle"
  } | gnuplot
  echo "figure $FIG/furnace-series.png"
}

# Section 2's figure: the thin gap with the error-bounded ray offset and with the rule of thumb.
thingap() {
  local panels="pt|pt, error bound|--method pt
lt|lt, error bound|--method lt
ptfixed|pt, --fixed-ray-offset|--method pt --fixed-ray-offset
ltfixed|lt, --fixed-ray-offset|--method lt --fixed-ray-offset"
  mkdir -p "$LOGS/fig"
  {
    echo 'set terminal pngcairo size 1000,300 font "sans,11"'
    echo "set output '$FIG/thin-gap.png'"
    echo "set multiplot layout 1,4 title 'tests/thin-gap.scene: a lamp 0.5 mm above a floor, direct light, 1024 samples per pixel' font ',12'"
    echo 'unset border; unset tics; unset key; set size ratio -1; set lmargin 0; set rmargin 0; set tmargin 3; set bmargin 0'
    while IFS='|' read -r name title opts; do
      # shellcheck disable=SC2086
      mean=$(./bdpt tests/thin-gap.scene $opts --maxdepth 1 --spp 1024 --out "$LOGS/fig/gap-$name.png" | sed -n 's/.* mean \([0-9.e+-]*\),.*/\1/p')
      echo "set title '$title: mean $(printf %.3f "$mean")'"
      echo "plot '$LOGS/fig/gap-$name.png' binary filetype=png with rgbimage"
    done <<< "$panels"
    echo 'unset multiplot'
  } | gnuplot
  echo "figure $FIG/thin-gap.png"
}

notes() {  # every figure of the pages, by the commands they show
  # The pages' commands write into build/notes/ (a student's run never touches the committed
  # figures); here each output that a page shows as figures/NAME is moved into $FIG instead.
  # What each printed goes to $FIG/figure-commands.txt, after the command as the page shows it:
  # the numbers a page quotes from its figures' runs (tests/test_notes.cpp checks them there).
  local log=$FIG/figure-commands.txt
  echo "# make figures: every command the pages show, as the page shows it (after \$), and what it printed" > "$log.tmp"
  grep -h '^\./bdpt ' lecture_notes/*.md | while read -r cmd; do
    echo "\$ $cmd" >> "$log.tmp"
    for path in $(echo "$cmd" | grep -o 'build/notes/[^ ]*'); do
      name=${path#build/notes/}
      stem=${name%.*}
      if grep -q "(figures/$stem\.png)\|(figures/$name/" lecture_notes/*.md; then cmd=${cmd//$path/$FIG/$name}; fi
    done
    dir=$(echo "$cmd" | sed -n 's/.*--strategies \([^ ]*\).*/\1/p')
    [ -n "$dir" ] && mkdir -p "$dir"
    mkdir -p build/notes
    echo "$cmd"
    eval "$cmd --overwrite" 2>/dev/null | sed "s|$FIG/|build/notes/|g" | tee -a "$log.tmp"  # eval: quoted lists
    # --side-by-side's panels' PFMs: a page shows the labelled PNG, its --ratio reads them here
    for pfm in "$FIG"/*-[1-8]-*.pfm; do if [ -e "$pfm" ]; then mv -f "$pfm" build/notes/; fi; done
  done
  mv "$log.tmp" "$log"
}

"${1:-charts}" "${@:2}"
