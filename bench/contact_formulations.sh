#!/usr/bin/env bash
# Cost of the contact formulations against node-to-segment penalty contact
# (docs/performance.md, "Contact formulations"): the square case of bench/performance.sh
# (two unit squares of n/8 Voronoi cells each, meshed independently, E = 1e9, nu = 0.3,
# top pressed down by 0.01) with
#   nts-pen    TYPE=NODE TO SURFACE, LINEAR K = 1e12 (the performance.sh deck)
#   nts-hard   TYPE=NODE TO SURFACE, PRESSURE-OVERCLOSURE=HARD
#   nts-hard-s the same with SMALL SLIDING (pairing fixed: factor reuse possible)
#   s2s-hard   TYPE=SURFACE TO SURFACE, HARD (interface nodes inserted)
# one after the other on the same mesh, so the ratios are within one run.  Per run:
# the log's phases, contact iterations and numeric factorizations, and "other" =
# total - the logged phases (the insertion of SURFACE TO SURFACE is not logged as a
# phase: it is in "other", next to the same term of the other formulations).
#   usage: bench/contact_formulations.sh   -> bench/results/contact_formulations.csv
#   env:   SIZES="1e4 1e5 1e6" (target unknowns), REPEAT=3 below 1e6 (fastest kept)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
bash scripts/build.sh Release >/dev/null
exe=$root/build/vemcontact
py=$root/.venv/bin/python
sizes=${SIZES:-"1e4 1e5 1e6"}
forms=${FORMS:-"nts-pen nts-hard nts-hard-s s2s-hard"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p bench/results
csv=bench/results/contact_formulations.csv
echo "formulation,unknowns_target,cells,unknowns,inserted,slave_nodes,iterations,factorizations,read_s,pattern_s,candidates_s,assemble_s,analyze_s,factorize_s,solve_s,search_s,write_s,other_s,total_s,mean_factorize_s,max_pressure,status,load" > "$csv"
echo "# $(date -u +%FT%TZ) $(nproc) cores,$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2), load $(cut -d' ' -f1-3 /proc/loadavg), vemcontact $(git rev-parse --short HEAD)" >> "$csv"

deck() {  # formulation mesh -> deck text
  local ctype="NODE TO SURFACE" beh="LINEAR" k="1.0e12" opt=""
  case $1 in
    nts-hard) beh=HARD ;;
    nts-hard-s) beh=HARD; opt=", SMALL SLIDING" ;;
    s2s-hard) beh=HARD; ctype="SURFACE TO SURFACE" ;;
  esac
  printf '** contact formulations: %s\n*INCLUDE, INPUT=%s\n*MATERIAL, NAME=ROCK\n*ELASTIC\n1.0e9, 0.3\n' "$1" "$2"
  printf '*SOLID SECTION, ELSET=LOWER, MATERIAL=ROCK\n*SOLID SECTION, ELSET=UPPER, MATERIAL=ROCK\n'
  printf '*SURFACE INTERACTION, NAME=INTERFACE\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=%s\n' "$beh"
  [ "$beh" = LINEAR ] && printf '%s\n' "$k"
  printf '*CONTACT PAIR, INTERACTION=INTERFACE, TYPE=%s%s\nIFACE_SLAVE, IFACE_MASTER\n' "$ctype" "$opt"
  printf '*BOUNDARY\nBOTTOM, 1, 2\nTOP, 1\n*STEP\n*STATIC\n*BOUNDARY\nTOP, 2, 2, -0.01\n*END STEP\n'
}

for s in $sizes; do
  n=$(awk -v x="$s" 'BEGIN{printf "%d", x}'); cells=$((n / 8))
  { printf '[mesh]\ntitle = "contact formulations: two blocks"\nseed = 1\nlloyd = 10\n\n'
    printf '[[body]]\nname = "LOWER"\nrectangle = [0.0, 0.0, 1.0, 1.0]\nmesher = "voronoi"\ncells = %d\n\n' $cells
    printf '[[body]]\nname = "UPPER"\nrectangle = [0.0, 1.0, 1.0, 2.0]\nmesher = "voronoi"\ncells = %d\n\n' $cells
    printf '[[selection]]\nname = "BOTTOM"\ny = 0.0\n\n[[selection]]\nname = "TOP"\ny = 2.0\n\n'
    printf '[[contact]]\nname = "IFACE"\nslave = "UPPER"\nmaster = "LOWER"\ny = 1.0\n'; } > "$work/m.toml"
  PYTHONPATH=$root/postprocess "$py" -m vctools.mesh scene "$work/m.toml" -o "$work/m$n.inp" >/dev/null
  reps=1; [ "$n" -lt 1000000 ] && reps=${REPEAT:-3}
  for f in $forms; do
    deck "$f" "m$n.inp" > "$work/$f$n.inp"
    best=""; status=ok; load=$(cut -d' ' -f1 /proc/loadavg)
    for r in $(seq "$reps"); do
      rm -rf "$work/o"
      if ! "$exe" -q -o "$work/o" "$work/$f$n.inp" > "$work/run.out" 2>&1; then
        status="exit $(grep -m1 -o 'error: .*' "$work/run.out" | tr ',' ';' | cut -c1-80)"
        cp "$work/o/$f$n.log" "$work/best.log" 2>/dev/null || true; best=x; break
      fi
      t=$(awk '$1=="total"{print $2}' "$work/o/$f$n.log")
      if [ -z "$best" ] || awk -v a="$t" -v b="$best" 'BEGIN{exit !(a < b)}'; then
        best=$t; cp "$work/o/$f$n.log" "$work/best.log"; cp "$work/o/$f$n.log" "bench/results/contact_formulations_${f}_$s.log"
      fi
    done
    awk -v f="$f" -v s="$n" -v c="$((2 * cells))" -v st="$status" -v load="$load" '
      /nodes [0-9]+, elements/ {gsub(",",""); unk=2*$2}
      /interface nodes inserted/ {ins+=$7}
      /pair 1:/ {sl=$3}
      /contact converged in/ {it+=$4; gsub("\\(","",$6); fa+=$6}
      /max pressure/ && /slave nodes closed/ {mp=$(NF-3); sub(",", "", mp)}
      $1=="read"||$1=="pattern"||$1=="candidates"||$1=="assemble"||$1=="analyze"||$1=="factorize"||$1=="solve"||$1=="search"||$1=="write" {t[$1]=$2; sum+=$2}
      $1=="total" {tot=$2}
      END {printf "%s,%s,%s,%d,%d,%d,%d,%d,%s,%s,%s,%s,%s,%s,%s,%s,%s,%.3f,%s,%.4f,%s,%s,%s\n", f, s, c, unk, ins, sl, it, fa,
             t["read"], t["pattern"], t["candidates"], t["assemble"], t["analyze"], t["factorize"], t["solve"], t["search"],
             t["write"], tot-sum, tot, (fa>0 ? t["factorize"]/fa : 0), mp, st, load}' "$work/best.log" >> "$csv"
    tail -1 "$csv"
  done
  rm -f "$work/m$n.inp"
done
column -s, -t "$csv"
