#!/usr/bin/env bash
# Performance benchmark (issue 6): linear and contact runs on Voronoi meshes from
# 1e4 to 4e6 unknowns, time per phase and peak memory, the ratio of vemcontact's
# end-to-end time to CHOLMOD's own analyze + factorize + solve of the same matrix,
# and the cost of a contact iteration against one numeric factorization.  vemcontact
# runs with --solver cholmod here (its `auto` picks CG + GAMG from 2e5 unknowns on
# linear decks), so that the ratio compares the same solver.
# Release build.  Writes bench/results/performance_linear.csv and
# bench/results/performance_contact.csv, then prints the tables and growth
# exponents of docs/performance.md (bench/performance_report.py).
#
#   usage: bench/performance.sh [linear|contact|report|all]   (default all)
#   environment:
#     LINEAR_SIZES   target unknowns of the linear runs   (default 1e4 4e4 1.6e5 1e6 4e6)
#     CONTACT_SIZES  target unknowns of each contact case (default 1e4 4e4 1.6e5 1e6 4e6)
#     CONTACT_CASES  square strip                         (default both)
#     VC_BUILD       an existing Release build directory  (default: scripts/build.sh Release, build/)
#     MIN_FREE_GB    wait (up to 10 min) for this much available memory before a run
#                    of 1e6 unknowns or more (default 14; the 4e6 runs peak at ~10 GB)
#     OPENBLAS_NUM_THREADS  BLAS threads of both vemcontact and CHOLMOD alone (default 1)
#     MESH_ORDER     2: the linear runs on second-order Voronoi meshes (k = 2 VEM, VPE2;
#                    the mesher's `order = 2`, about 10 unknowns per cell), written to
#                    bench/results/performance_linear_k2.csv (default 1)
#
# Meshes come from the Voronoi mesher (vctools.mesh, 10 Lloyd iterations, seed 1);
# the mesher's wall time is the "mesh" phase.  Linear: the unit square, plane
# strain, self-weight, bottom fixed; about 4 unknowns per cell.  Contact: two
# Voronoi blocks meshed independently (non-matching), in frictionless NTS penalty
# contact, bottom fixed, top pressed down by 0.5 % of the height and held in x:
#   square  two unit squares, one above the other: O(sqrt n) slave nodes
#   strip   two strips L x 1 (8 cells through each), L growing with n: O(n) slave nodes
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
command -v /usr/bin/time >/dev/null || { apt-get update -qq; apt-get install -y -qq time >/dev/null; }
what=${1:-all}
if [ -n "${VC_BUILD:-}" ]; then
  build=$VC_BUILD
else
  bash scripts/build.sh Release >/dev/null
  build=$root/build
fi
py=$root/.venv/bin/python
linear_sizes=${LINEAR_SIZES:-"1e4 4e4 1.6e5 1e6 4e6"}
contact_sizes=${CONTACT_SIZES:-"1e4 4e4 1.6e5 1e6 4e6"}
contact_cases=${CONTACT_CASES:-"square strip"}
min_free=${MIN_FREE_GB:-14}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p bench/results
mesh_order=${MESH_ORDER:-1}
# the same BLAS threads for vemcontact and CHOLMOD alone (vemcontact's default is one)
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
lcsv=bench/results/performance_linear.csv
[ "$mesh_order" = 2 ] && lcsv=bench/results/performance_linear_k2.csv
ccsv=bench/results/performance_contact.csv

num() { awk -v x="$1" 'BEGIN{printf "%d", x + 0}'; }
# wait for memory before a big run: other jobs share the machine
wait_mem() {
  local tries=0
  while [ "$(awk '/MemAvailable/{printf "%d", $2/1048576}' /proc/meminfo)" -lt "$min_free" ] && [ $tries -lt 20 ]; do
    echo "  waiting for ${min_free} GB of available memory ..." >&2; sleep 30; tries=$((tries + 1))
  done
}
machine_note() {
  echo "# $(date -u +%FT%TZ) $(nproc) cores,$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)," \
       "$(awk '/MemTotal/{printf "%.0f GiB", $2/1048576}' /proc/meminfo), load $(cut -d' ' -f1-3 /proc/loadavg)"
}
# mesh a scene: $1 scene, $2 output .inp; sets mesh_s and mesh_mb
mesh() {
  PYTHONPATH=$root/postprocess /usr/bin/time -v "$py" -m vctools.mesh scene "$1" -o "$2" \
    > "$work/mesher.out" 2> "$work/mesher.time" || { cat "$work/mesher.out" "$work/mesher.time" >&2; return 1; }
  mesh_s=$(awk -F': ' '/Elapsed \(wall clock\)/{n=split($2,a,":"); s=0; for(i=1;i<=n;i++) s=s*60+a[i]; printf "%.2f", s}' "$work/mesher.time")
  mesh_mb=$(awk '/Maximum resident/{printf "%.0f", $6/1024}' "$work/mesher.time")
}
# timed vemcontact run: $1 deck, $2 output dir; sets log and peak_mb.  Below 1e6
# unknowns (argument $3) the run is repeated three times and the fastest kept: the
# machine is shared and a 0.1 s run is easily doubled by a neighbour
run() {
  local reps=1 r best=""
  [ "${3:-0}" -lt 1000000 ] && reps=3
  for r in $(seq $reps); do
    rm -rf "$2"
    /usr/bin/time -v "$build/vemcontact" -q --solver cholmod -o "$2" "$1" 2> "$work/time.txt" || { cat "$work/time.txt" >&2; return 1; }
    log=$2/$(basename "$1" .inp).log
    local t; t=$(awk '$1=="total"{print $2}' "$log")
    if [ -z "$best" ] || awk -v a="$t" -v b="$best" 'BEGIN{exit !(a < b)}'; then
      best=$t; cp "$log" "$work/best.log"
      cp "$2/$(basename "$1" .inp)_phases.csv" "$work/best_phases.csv"
      peak_mb=$(awk '/Maximum resident/{printf "%.0f", $6/1024}' "$work/time.txt")
    fi
  done
  log=$work/best.log
}
# CHOLMOD alone on a matrix file, the fastest of three below 1e6 unknowns
cholmod() {
  local reps=1 r out best="" t
  [ "$2" -lt 1000000 ] && reps=3
  for r in $(seq $reps); do
    out=$("$build/bench/cholmod_ref" "$1")
    t=$(echo "$out" | awk '$1=="total"{print $2}')
    if [ -z "$best" ] || awk -v a="$t" -v b="$best" 'BEGIN{exit !(a < b)}'; then best=$t; ref=$out; fi
  done
}
# a phase's seconds summed over the steps, from the run's JOB_phases.csv
get() { awk -F, -v k="$1" '$2==k && $3=="" {s+=$4; n++} END{if (n) printf "%.3f", s}' "$work/best_phases.csv"; }

body() {  # name x0 y0 x1 y1 cells
  printf '[[body]]\nname = "%s"\nrectangle = [%s, %s, %s, %s]\nmesher = "voronoi"\ncells = %s\n\n' "$@"
}

linear() {
  echo "unknowns_target,cells,nodes,elements,unknowns,mesh_s,mesh_peak_MB,read_s,pattern_s,assemble_s,analyze_s,factorize_s,solve_s,write_s,total_s,peak_MB,cholmod_analyze_s,cholmod_factorize_s,cholmod_solve_s,cholmod_total_s,ratio,load" > "$lcsv"
  machine_note >> "$lcsv"
  for s in $linear_sizes; do
    local n; n=$(num "$s"); local cells=$((n / 4))
    [ "$mesh_order" = 2 ] && cells=$((n / 10))
    [ "$n" -ge 1000000 ] && wait_mem
    { printf '[mesh]\ntitle = "performance: unit square, %s cells"\nseed = 1\nlloyd = 10\norder = %s\n\n' $cells "$mesh_order"
      body SQUARE 0.0 0.0 1.0 1.0 $cells
      printf '[[selection]]\nname = "BOTTOM"\ny = 0.0\n'; } > "$work/lin.toml"
    mesh "$work/lin.toml" "$work/lin_mesh.inp"
    cat > "$work/lin$n.inp" <<EOF
** performance: Voronoi mesh of the unit square, self-weight, bottom fixed
*INCLUDE, INPUT=lin_mesh.inp
*MATERIAL, NAME=ROCK
*ELASTIC
1.0e10, 0.3
*DENSITY
2400.
*SOLID SECTION, ELSET=SQUARE, MATERIAL=ROCK
*BOUNDARY
BOTTOM, 1, 2
*STEP
*STATIC
*DLOAD
SQUARE, GRAV, 9.81, 0., -1.
*END STEP
EOF
    local load; load=$(cut -d' ' -f1 /proc/loadavg)
    run "$work/lin$n.inp" "$work/r$n" "$n"
    # the matrix for CHOLMOD alone (this run is not timed)
    "$build/vemcontact" -q --solver cholmod --write-matrix -o "$work/m$n" "$work/lin$n.inp"
    rm -f "$work/m$n"/*.vtu "$work/m$n"/*.h5
    cholmod "$work/m$n/lin$n.mtx" "$n"
    rm -rf "$work/m$n"
    local nodes elems ca cf cs ct tot
    nodes=$(awk '/nodes [0-9]+, elements/{gsub(",","");print $2; exit}' "$log")
    elems=$(awk '/nodes [0-9]+, elements/{gsub(",","");print $4; exit}' "$log")
    ca=$(echo "$ref" | awk '$1=="analyze"{print $2}'); cf=$(echo "$ref" | awk '$1=="factorize"{print $2}')
    cs=$(echo "$ref" | awk '$1=="solve"{print $2}'); ct=$(echo "$ref" | awk '$1=="total"{print $2}')
    tot=$(get total)
    echo "$n,$cells,$nodes,$elems,$((2 * nodes)),$mesh_s,$mesh_mb,$(get read),$(get pattern),$(get assemble),$(get analyze),$(get factorize),$(get solve),$(get write),$tot,$peak_mb,$ca,$cf,$cs,$ct,$(awk -v a="$tot" -v b="$ct" 'BEGIN{printf "%.3f", a/b}'),$load" >> "$lcsv"
    tail -1 "$lcsv"
    rm -rf "$work/r$n" "$work/lin_mesh.inp"
  done
}

contact() {
  echo "case,unknowns_target,cells,nodes,unknowns,slave_nodes,master_segments,mesh_s,mesh_peak_MB,read_s,pattern_s,candidates_s,assemble_s,analyze_s,iterations,pattern_rebuilds,factorize_s,solve_s,search_s,write_s,total_s,peak_MB,mean_iter_s,mean_factorize_s,mean_search_s,iter_over_factorize,worst_iter_over_factorize,load" > "$ccsv"
  machine_note >> "$ccsv"
  for c in $contact_cases; do
    for s in $contact_sizes; do
      local n; n=$(num "$s")
      [ "$n" -ge 1000000 ] && wait_mem
      local cells len
      if [ "$c" = square ]; then
        cells=$((n / 8)); len=1.0             # per block
      else
        # h = 1/8: 64 cells per unit area, 8 per unit length along the interface
        len=$(awk -v n="$n" 'BEGIN{printf "%.1f", n / 512}'); cells=$(awk -v l="$len" 'BEGIN{printf "%d", 64 * l}')
      fi
      { printf '[mesh]\ntitle = "performance: two blocks in contact (%s)"\nseed = 1\nlloyd = 10\n\n' "$c"
        body LOWER 0.0 0.0 "$len" 1.0 "$cells"
        body UPPER 0.0 1.0 "$len" 2.0 "$cells"
        printf '[[selection]]\nname = "BOTTOM"\ny = 0.0\n\n[[selection]]\nname = "TOP"\ny = 2.0\n\n'
        printf '[[contact]]\nname = "IFACE"\nslave = "UPPER"\nmaster = "LOWER"\ny = 1.0\n'; } > "$work/con.toml"
      mesh "$work/con.toml" "$work/con_mesh.inp"
      cat > "$work/con$n.inp" <<EOF
** performance: two Voronoi blocks in contact, top pressed down, bottom fixed
*INCLUDE, INPUT=con_mesh.inp
*MATERIAL, NAME=ROCK
*ELASTIC
1.0e9, 0.3
*SOLID SECTION, ELSET=LOWER, MATERIAL=ROCK
*SOLID SECTION, ELSET=UPPER, MATERIAL=ROCK
*SURFACE INTERACTION, NAME=INTERFACE
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
1.0e12
*CONTACT PAIR, INTERACTION=INTERFACE, TYPE=NODE TO SURFACE
IFACE_SLAVE, IFACE_MASTER
*BOUNDARY
BOTTOM, 1, 2
TOP, 1
*STEP
*STATIC
*BOUNDARY
TOP, 2, 2, -0.01
*END STEP
EOF
      local load; load=$(cut -d' ' -f1 /proc/loadavg)
      if ! run "$work/con$n.inp" "$work/c$n" "$n"; then
        echo "$c,$n,$((2 * cells)),failed: $(grep -m1 error "$work/time.txt" | tr ',' ';')" >> "$ccsv"
        continue
      fi
      local nodes ns nm it
      nodes=$(awk '/nodes [0-9]+, elements/{gsub(",","");print $2; exit}' "$log")
      ns=$(awk '/pair 1:/{print $3; exit}' "$log"); nm=$(awk '/pair 1:/{print $7; exit}' "$log")
      it=$(awk '/contact converged in/{print $4}' "$log")
      # per iteration: wall time $7, factorization $8, search $9; the mean ratio is
      # over the iterations after the first, without those that rebuilt the pattern
      local iters
      iters=$(awk '
        /pattern rebuilt/ {skip=1; rb++}
        /^ +[0-9]+ +[0-9]+ +[0-9]+ +[0-9.E+-]+ / {n++; s+=$9; lt=$7; lf=$8;
           if (n>1 && !skip) {t+=$7; f+=$8; m++; if ($7/$8>w) w=$7/$8}; skip=0}
        END {if (m==0) {t=lt; f=lf; m=1; w=t/f}  # one iteration only: that one
             printf "%d,%.4f,%.4f,%.5f,%.3f,%.3f", rb, t/m, f/m, s/n, t/f, w}' "$log")
      echo "$c,$n,$((2 * cells)),$nodes,$((2 * nodes)),$ns,$nm,$mesh_s,$mesh_mb,$(get read),$(get pattern),$(get candidates),$(get assemble),$(get analyze),$it,$(echo "$iters" | cut -d, -f1),$(get factorize),$(get solve),$(get search),$(get write),$(get total),$peak_mb,$(echo "$iters" | cut -d, -f2-),$load" >> "$ccsv"
      tail -1 "$ccsv"
      rm -rf "$work/c$n" "$work/con_mesh.inp"
    done
  done
}

case $what in
  linear) linear ;;
  contact) contact ;;
  report) ;;
  all) linear; contact ;;
  *) echo "usage: bench/performance.sh [linear|contact|report|all]" >&2; exit 1 ;;
esac
"$py" bench/performance_report.py "$lcsv" "$ccsv"
echo "machine: $(nproc) cores,$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2), $(awk '/MemTotal/{printf "%.0f GiB", $2/1048576}' /proc/meminfo), load $(cut -d' ' -f1-3 /proc/loadavg)"
