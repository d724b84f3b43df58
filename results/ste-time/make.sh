#!/usr/bin/env bash
# Mission time of STE (issue 47): the field's time metrics (run/mission_times.hpp) of today's STE
# and of its faster settings, the same runs: the nine test maps, 20 random buildings (seed 1001)
# and the three real floors; the faithful world, the mox-fast sensor, seed 1 (README.md here).
#   results/ste-time/make.sh [OUT] [PART...]
#   PART: SET-VARIANT, SET one of test buildings real, VARIANT one of the names in `variant`
#         below; or tuning: the likelihood of the moving protocol chosen on maps of its own
#         (OUT/tuning/SET-mS-kK, OUT/tuning/table.md); or stop-tuning: its confidence stop rule
#         (OUT/tuning/SET-rR-pP, OUT/tuning/stop-table.md). Default: the parts README.md shows.
# Then `scripts/time_table.py OUT` makes table.md.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
source scripts/blas-env.sh
variants=(today today-physics moving lean moving-lean short moving-short moving-lean-short
  adaptive moving-adaptive moving-lean-adaptive moving-k1-adaptive moving-k1-adaptive-paths
  moving-k1-adaptive-confident moving-k1-adaptive-confident-approach default default-paths)
variant() { # the flags of a variant: what it changes from the thesis's protocol (the defaults
  # before issue 47, with the hybrid plume model); `default`: today's defaults, no flag
  local t=(--protocol thesis) m=(--read-while-moving true) a=(--adaptive-stops true)
  local lean=(--sigma-m 100 --sigma-std 1) c=(--confidence-radius 0.3 --confidence-mass 0.95)
  case $1 in
    today) flags=("${t[@]}") ;;
    today-physics) flags=("${t[@]}" --plume-model physics) ;; # issue 47's own baseline
    moving) flags=("${t[@]}" "${m[@]}") ;;
    lean) flags=("${t[@]}" "${lean[@]}") ;;
    moving-lean) flags=("${t[@]}" "${m[@]}" "${lean[@]}") ;;
    short) flags=("${t[@]}" --stop-s 2) ;;
    moving-short) flags=("${t[@]}" "${m[@]}" --stop-s 2) ;;
    moving-lean-short) flags=("${t[@]}" "${m[@]}" "${lean[@]}" --stop-s 2) ;;
    adaptive) flags=("${t[@]}" "${a[@]}") ;;
    moving-adaptive) flags=("${t[@]}" "${m[@]}" "${a[@]}") ;;
    moving-lean-adaptive) flags=("${t[@]}" "${m[@]}" "${lean[@]}" "${a[@]}") ;;
    moving-k1-adaptive) flags=("${t[@]}" "${m[@]}" --sigma-std 1 "${a[@]}") ;; # tuning's pick
    moving-k1-adaptive-paths) flags=("${t[@]}" "${m[@]}" --sigma-std 1 "${a[@]}" --path-scoring) ;;
    moving-k1-adaptive-confident) flags=("${t[@]}" "${m[@]}" --sigma-std 1 "${a[@]}" "${c[@]}") ;;
    moving-k1-adaptive-confident-approach)
      flags=("${t[@]}" "${m[@]}" --sigma-std 1 "${a[@]}" "${c[@]}" --approach) ;;
    default) flags=() ;; # --protocol moving, the defaults since issue 47
    default-paths) flags=(--path-scoring) ;;
    *) echo "$0: unknown variant $1" >&2; exit 2 ;;
  esac
}
parts=("${@:2}")
if [[ ${#parts[@]} -eq 0 ]]; then # what README.md shows: every variant on the test maps, the
  # telling ones on the buildings and the real floors, and the tuning
  # (path scoring changes nothing on the test maps: their navigator is the thesis's lattice)
  for v in "${variants[@]}"; do [[ $v == *-paths || $v == *-approach ]] || parts+=("test-$v"); done
  for set in buildings real; do
    for v in today today-physics moving-short moving-lean-short adaptive moving-adaptive \
      moving-lean-adaptive moving-k1-adaptive moving-k1-adaptive-paths \
      moving-k1-adaptive-confident default; do
      parts+=("$set-$v")
    done
  done
  parts+=(real-moving-k1-adaptive-confident-approach real-default-paths tuning stop-tuning)
fi
[[ -d $out/buildings-1001 ]] || "$plumekit" maps random --families building --count 20 \
  --seed 1001 --sources 3 --out "$out/buildings-1001" >/dev/null
six=rectangle,two-rectangles,l-shape,u-shape,three-rectangles,shape-and-rectangle
tuning_maps() { # the held-out sets of results/ste-hybrid's tuning (never the test maps)
  local t=$out/tuning
  [[ -d $t/maps-4700 ]] || "$plumekit" maps random --families "$six" --count 6 --seed 4700 \
    --sources 10 --out "$t/maps-4700" >/dev/null
  [[ -d $t/buildings-2002 ]] || "$plumekit" maps random --families building --count 12 \
    --seed 2002 --sources 2 --out "$t/buildings-2002" >/dev/null
}
tuning() { # sigma_M and k of the hybrid with readings on the way and adaptive stops, chosen on
  # the held-out sets of results/ste-hybrid's tuning (never the test maps)
  local t=$out/tuning sm k
  tuning_maps
  for sm in 200 100 50; do
    for k in 1 2; do
      [[ -f $t/families-m$sm-k$k/summary.json ]] || "$plumekit" evaluate --map-dir "$t/maps-4700" \
        --runs 3 --gas-sensor mox-fast --threads 2 --sigma-m "$sm" --sigma-std "$k" \
        --protocol thesis --read-while-moving true --adaptive-stops true \
        --table-cache "$out/tables" \
        --out "$t/families-m$sm-k$k" >/dev/null
      [[ -f $t/buildings-m$sm-k$k/summary.json ]] || "$plumekit" evaluate --map-dir \
        "$t/buildings-2002" --runs 1 --gas-sensor mox-fast --threads 2 --sigma-m "$sm" \
        --sigma-std "$k" --protocol thesis --read-while-moving true --adaptive-stops true \
        --table-cache "$out/tables" \
        --out "$t/buildings-m$sm-k$k" >/dev/null
    done
  done
  /usr/bin/python3 scripts/likelihood_table.py --mission "$t" >"$t/table.md"
}
stop_tuning() { # the confidence stop rule of the moving protocol (--confidence-radius,
  # --confidence-mass) on the same held-out sets, with today's defaults otherwise; radius 0: off
  local t=$out/tuning r p
  tuning_maps
  for r in 0 0.3 0.5; do
    for p in 0.8 0.9 0.95; do
      [[ $r == 0 && $p != 0.9 ]] && continue # off is off
      [[ -f $t/families-r$r-p$p/summary.json ]] || "$plumekit" evaluate --map-dir \
        "$t/maps-4700" --runs 3 --gas-sensor mox-fast --threads 2 --confidence-radius "$r" \
        --confidence-mass "$p" --table-cache "$out/tables" --out "$t/families-r$r-p$p" >/dev/null
      [[ -f $t/buildings-r$r-p$p/summary.json ]] || "$plumekit" evaluate --map-dir \
        "$t/buildings-2002" --runs 1 --gas-sensor mox-fast --threads 2 --confidence-radius "$r" \
        --confidence-mass "$p" --table-cache "$out/tables" --out "$t/buildings-r$r-p$p" >/dev/null
    done
  done
  /usr/bin/python3 scripts/likelihood_table.py --stop "$t" >"$t/stop-table.md"
}
for part in "${parts[@]}"; do
  [[ $part == tuning ]] && { tuning; continue; }
  [[ $part == stop-tuning ]] && { stop_tuning; continue; }
  variant "${part#*-}"
  case ${part%%-*} in
    test) maps=(--map-dir data/test-maps --runs 1) ;;
    buildings) maps=(--map-dir "$out/buildings-1001" --runs 1) ;;
    real) maps=(--map-dir data/floors --runs 2 --cell 0.1) ;;
    *) echo "$0: unknown part $part" >&2; exit 2 ;;
  esac
  [[ -f $out/$part/summary.json ]] || "$plumekit" evaluate "${maps[@]}" "${flags[@]}" \
    --gas-sensor mox-fast --threads 2 --table-cache "$out/tables" --out "$out/$part" >/dev/null
done
