#!/usr/bin/env bash
# Finite-sliding contact robustness (docs/contact-robustness.md): contact iterations of
#  - the non-matching interface example (inputs/interface_voronoi_*.inp: two blocks meshed
#    independently, uniform compression) on refined Voronoi meshes of about 1e3 .. 4e5
#    unknowns (bench/interface_refined.toml), with finite sliding and with SMALL SLIDING;
#  - every contact deck under inputs/ (iterations per step);
#  - the refined Hertz meshes of bench/hertz_refined.toml (iterations, pattern rebuilds).
#   usage: bench/contact_sliding.sh            -> bench/results/contact_sliding.csv
#   env:   VEMCONTACT_EXE=path  run that executable (e.g. an older build) instead of
#          building build/vemcontact; LABEL=name  the label column (default "current");
#          MESH_DIR=dir  keep / reuse the generated meshes there (they take about a minute);
#          SIZES="u1e3 u1e4"  only these interface variants (default all six, up to u4e5:
#          about 1 GB and a few seconds per iteration at 4e5 unknowns).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${VEMCONTACT_EXE:-}" ]; then
  bash scripts/build.sh Release >/dev/null
  VEMCONTACT_EXE=$PWD/build/vemcontact
fi
label=${LABEL:-current}
sizes=${SIZES:-"u1e3 u1e4 u2e4 u1e5 u2e5 u4e5"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mesh=${MESH_DIR:-$work/mesh}
mkdir -p "$mesh" bench/results
py() { PYTHONPATH=postprocess .venv/bin/python "$@"; }
if [ ! -f "$mesh/interface_refined_u4e5.inp" ]; then
  py -m vctools.mesh scene bench/interface_refined.toml -o "$mesh/" --processes 1 >/dev/null
fi
if [ ! -f "$mesh/hertz_refined_h100k.inp" ]; then
  py -m vctools.mesh scene bench/hertz_refined.toml -o "$mesh/" >/dev/null
fi
csv=bench/results/contact_sliding.csv
[ -f "$csv" ] || echo "label,case,sliding,unknowns,iterations,pattern_rebuilds,final_residual,status,contact_time_s" > "$csv"

# one run: case name, deck, sliding -> a CSV line (iterations of every step joined by ;)
record() {
  local name=$1 deck=$2 sliding=$3 job rc
  job=$(basename "$deck" .inp)
  set +e
  "$VEMCONTACT_EXE" -q -o "$work/out" "$deck" > /dev/null 2>&1
  rc=$?
  set -e
  awk -v l="$label" -v c="$name" -v s="$sliding" -v rc="$rc" '
    /nodes [0-9]+, elements/ {gsub(",",""); unk=$6}
    /pattern rebuilt/ {rb++}
    /^ +[0-9]+ +[0-9]+ +[0-9]+ +[0-9.E+-]+ / {res=$4; t+=$7}
    /contact converged in/ {its = its (its=="" ? "" : ";") $4}
    END {st = (rc==0 ? "ok" : "exit " rc); if (its=="") its="-";
         printf "%s,%s,%s,%d,%s,%d,%s,%s,%.3f\n", l, c, s, unk, its, rb, res, st, t}' \
    "$work/out/$job.log" >> "$csv"
}

for v in $sizes; do
  for sliding in finite small; do
    opt=""; [ $sliding = small ] && opt=", SMALL SLIDING"
    sed -e "s#meshes/ex3_interface_voronoi_100.inp#$mesh/interface_refined_$v.inp#" \
        -e "s#^\*CONTACT PAIR, INTERACTION=INTERFACE, TYPE=NODE TO SURFACE#&$opt#" \
        inputs/interface_voronoi_100.inp > "$work/interface_$v.inp"
    record "interface_$v" "$work/interface_$v.inp" $sliding
  done
done
for d in inputs/*.inp; do
  grep -q '^\*CONTACT PAIR' "$d" || continue
  record "$(basename "$d" .inp)" "$d" finite
done
for v in h20k h100k; do
  sed -e "s#meshes/ex2_hertz_1155_vem.inp#$mesh/hertz_refined_$v.inp#" inputs/hertz_1155_vem.inp \
    > "$work/hertz_$v.inp"
  record "hertz_$v" "$work/hertz_$v.inp" finite
done
grep "^$label," "$csv" | column -s, -t
