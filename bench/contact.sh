#!/usr/bin/env bash
# Contact benchmark (issue 3): cost of an active-set iteration against a numeric
# refactorization, on refined Hertz meshes (Release build).  Each iteration's
# log line carries its wall time and its factorization time; the ratio of the
# two for the iterations after the first is the overhead of contact (copy of
# the matrix, springs, constraints, projection, residual).  Target: <= 1.10.
# The iteration count and the pattern rebuilds are those of the first step of a
# curved contact (docs/contact-robustness.md, "Curved contact: the first step").
#   usage: bench/contact.sh   -> bench/results/contact.csv
#   VEMCONTACT_EXE=path bench/contact.sh   uses that executable instead of build/
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${VEMCONTACT_EXE:-}
if [ -z "$exe" ]; then
  bash scripts/build.sh Release >/dev/null
  exe=./build/vemcontact
fi
work=$(mktemp -d)
mkdir -p bench/results
csv=bench/results/contact.csv
echo "mesh,unknowns,iterations,pattern_rebuilds,peak_pressure,mean_iter_s,mean_factorize_s,overhead_ratio,worst_ratio" > "$csv"
for v in h20k h100k; do
  PYTHONPATH=postprocess .venv/bin/python -m vctools.mesh scene bench/hertz_refined.toml -o "$work/" >/dev/null
  mesh=$(ls "$work"/*"$v"*.inp | head -1)
  sed -e "s#meshes/ex2_hertz_1155_vem.inp#$mesh#" inputs/hertz_1155_vem.inp > "$work/bench_$v.inp"
  "$exe" -q -o "$work/out" "$work/bench_$v.inp"
  log=$work/out/bench_$v.log
  # iterations after the first, except those that also rebuilt the pattern and
  # re-ran the symbolic analysis (reported separately: once per model, when the
  # first iteration's pairing moves far from the undeformed one)
  awk -v v="$v" '
    /nodes [0-9]+, elements/ {gsub(",",""); unk=$6}
    /pattern rebuilt/ {skip=1; rb++}
    /^ +[0-9]+ +[0-9]+ +[0-9]+ +[0-9.E+-]+ / {n++; p=$6;
       if (n>1 && !skip) {t+=$7; f+=$8; m++; if ($7/$8>w) w=$7/$8}; skip=0}
    END {printf "%s,%d,%d,%d,%s,%.4f,%.4f,%.3f,%.3f\n", v, unk, n, rb, p, t/m, f/m, t/f, w}' "$log" >> "$csv"
done
rm -rf "$work"
column -s, -t "$csv"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
