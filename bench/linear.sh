#!/usr/bin/env bash
# Linear-solve benchmark (issue 2): vemcontact end to end on polygon meshes of
# growing size against CHOLMOD's own analyze + factorize + solve of the same
# matrix with its default ordering (vemcontact with --solver cholmod: its `auto`
# would pick CG + GAMG from 2e5 unknowns).  Release build.  Writes bench/results/linear.csv
# and prints a table.   usage: bench/linear.sh [N ...]   (N: grid size, ~2 N^2 nodes)
set -euo pipefail
cd "$(dirname "$0")/.."
command -v /usr/bin/time >/dev/null || { apt-get update -qq; apt-get install -y -qq time >/dev/null; }
bash scripts/build.sh Release >/dev/null
sizes=${*:-"50 160 500"}
work=$(mktemp -d)
mkdir -p bench/results
csv=bench/results/linear.csv
echo "n_grid,nodes,elements,unknowns,read_s,pattern_s,assemble_s,analyze_s,factorize_s,solve_s,write_s,total_s,peak_MB,cholmod_analyze_s,cholmod_factorize_s,cholmod_solve_s,cholmod_total_s,ratio,assembly_elem_per_s" > "$csv"
for n in $sizes; do
  deck=$work/poly$n.inp
  ./build/bench/make_polymesh_deck "$n" "$deck"
  # the matrix for CHOLMOD alone (this run is not timed)
  ./build/vemcontact -q --solver cholmod --write-matrix -o "$work/m$n" "$deck"
  ref=$(./build/bench/cholmod_ref "$work/m$n/poly$n.mtx")
  rm -f "$work/m$n/poly$n.mtx"
  # the timed run
  /usr/bin/time -v ./build/vemcontact -q --solver cholmod -o "$work/r$n" "$deck" 2> "$work/time$n.txt"
  log=$work/r$n/poly$n.log
  get() { awk -v k="$1" '$1==k {print $2; exit}' "$log"; }
  nodes=$(awk '/nodes /{gsub(",","");print $2; exit}' "$log")
  elems=$(awk '/nodes /{gsub(",","");print $4; exit}' "$log")
  peak=$(awk '/Maximum resident/{printf "%.0f", $6/1024}' "$work/time$n.txt")
  ca=$(echo "$ref" | awk '$1=="analyze"{print $2}'); cf=$(echo "$ref" | awk '$1=="factorize"{print $2}')
  cs=$(echo "$ref" | awk '$1=="solve"{print $2}'); ct=$(echo "$ref" | awk '$1=="total"{print $2}')
  tot=$(get total)
  ratio=$(awk -v a="$tot" -v b="$ct" 'BEGIN{printf "%.2f", a/b}')
  rate=$(awk -v e="$elems" -v t="$(get assemble)" 'BEGIN{ if (t>0) printf "%.3g", e/t; else print "inf"}')
  echo "$n,$nodes,$elems,$((2*nodes)),$(get read),$(get pattern),$(get assemble),$(get analyze),$(get factorize),$(get solve),$(get write),$tot,$peak,$ca,$cf,$cs,$ct,$ratio,$rate" >> "$csv"
done
rm -rf "$work"
column -s, -t "$csv"
echo "machine: $(nproc) cores, $(awk '/MemTotal/{printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
