#!/usr/bin/env bash
# The peers' cantilever (issue 15; bench/peers/case.py): end-to-end time, phases,
# peak memory and tip error of vemcontact on 1e5 Lloyd-Voronoi cells (uniform random
# seeds, 20 Lloyd iterations, seed 1): `auto` with the solver vemcontact picks itself
# (gamg at this size), and CHOLMOD (t1, t2, ...) with 1 and 2 OpenBLAS threads, with and
# without a second busy process on the machine, and with CHOLMOD's own ordering
# instead of METIS on the node graph, and with the PETSc solvers (gamg, hypre, mumps:
# --solver, one BLAS thread).  The variants alternate within each repeat,
# so that their ratios are measured under the same load.
#
#   usage: bench/peers/run.sh
#   environment: CELLS (default 100000), SEED (1), LLOYD (20), REPEATS (3),
#                VARIANTS (default "auto t1 t2 t1busy t2busy cholmod"),
#                VC_BUILD (an existing Release build; default scripts/build.sh Release),
#                REF_BIN (another vemcontact executable, e.g. an older commit's build:
#                the variant `ref` runs it as `auto` runs this one),
#                CSV (default bench/results/peers.csv)
# e.g. VARIANTS="t1 gamg hypre mumps" CSV=bench/results/peers_solvers.csv bench/peers/run.sh
# Writes $CSV (one line per run; total_s is the logged total, wall_s the process's
# wall time from /usr/bin/time, with the loading of the shared libraries) and prints the fastest run of
# each variant.
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
cells=${CELLS:-100000}
seed=${SEED:-1}
lloyd=${LLOYD:-20}
reps=${REPEATS:-3}
variants=${VARIANTS:-"auto t1 t2 t1busy t2busy cholmod"}
if [ -n "${VC_BUILD:-}" ]; then build=$VC_BUILD; else bash scripts/build.sh Release >/dev/null; build=$root/build; fi
py=$root/.venv/bin/python
work=$(mktemp -d)
busy_pid=""
cleanup() { [ -n "$busy_pid" ] && kill "$busy_pid" 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT
csv=${CSV:-bench/results/peers.csv}
mkdir -p bench/results

t0=$(date +%s.%N)
PYTHONPATH=$root/postprocess "$py" bench/peers/case.py deck "$work/case" --cells "$cells" --seed "$seed" --lloyd "$lloyd"
echo "mesh and deck: $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN{printf "%.1f", b - a}') s ($cells cells, seed $seed, $lloyd Lloyd iterations)"

phases="read validate pattern assemble analyze factorize solve system stresses estimate write"
echo "variant,rep,cells,unknowns,$(echo $phases | sed 's/\([a-z-]*\)/\1_s/g; s/ /,/g'),other_s,total_s,user_s,sys_s,peak_MB,tip_uy,tip_exact,tip_err,tip_rel_err,load,solver,wall_s" > "$csv"
for rep in $(seq "$reps"); do
  for v in $variants; do
    opts=()
    case $v in
      auto|ref) ;;
      t1|t1busy) opts=(--solver cholmod --blas-threads 1) ;;
      t2|t2busy) opts=(--solver cholmod --blas-threads 2) ;;
      cholmod) opts=(--solver cholmod --blas-threads 1 --ordering cholmod) ;;
      gamg|hypre|mumps) opts=(--blas-threads 1 --solver "$v") ;;
    esac
    if [[ $v == *busy ]]; then
      # a second busy process (a shell loop) for the duration of the run
      bash -c 'while :; do :; done' & busy_pid=$!
      sleep 1
    fi
    load=$(cut -d' ' -f1 /proc/loadavg)
    out=$work/r_$v
    rm -rf "$out"
    exe=$build/vemcontact
    if [ "$v" = ref ]; then exe=${REF_BIN:?the variant ref needs REF_BIN}; fi
    env -u OPENBLAS_NUM_THREADS -u OMP_NUM_THREADS -u GOTO_NUM_THREADS \
      /usr/bin/time -f "%U %S %M %e" -o "$work/time.txt" "$exe" -q "${opts[@]}" -o "$out" "$work/case/beam.inp"
    if [ -n "$busy_pid" ]; then kill "$busy_pid"; wait "$busy_pid" 2>/dev/null || true; busy_pid=""; fi
    tip=$("$py" bench/peers/case.py tip "$out/beam.h5")
    nodes=$("$py" -c "import h5py,sys; print(h5py.File(sys.argv[1])['mesh/coordinates'].shape[0])" "$out/beam.h5")
    # the solver that ran (HDF5 root attribute `solver`; its first word)
    solver=$("$py" -c "import h5py,sys; a=h5py.File(sys.argv[1]).attrs['solver']; print((a.decode() if isinstance(a, bytes) else str(a)).split()[0])" "$out/beam.h5")
    line=$(awk -F, -v list="$phases" '
      NR > 1 && $3 == "" { if ($2 == "total") tot = $4; else { t[$2] += $4; all += $4 } }
      END { n = split(list, p, " "); s = 0; out = ""
            for (i = 1; i <= n; i++) { out = out sprintf("%.4g,", t[p[i]]); s += t[p[i]] }
            printf "%s%.4g,%.4g", out, all - s, tot }' "$out/beam_phases.csv")
    read -r user sys rss wall < "$work/time.txt"
    echo "$v,$rep,$cells,$((2 * nodes)),$line,$user,$sys,$((rss / 1024)),$tip,$load,$solver,$wall" >> "$csv"
    echo "  $v rep $rep: total $(echo "$line" | awk -F, '{print $NF}') s, load $load"
  done
done
"$py" - "$csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
best = {}
for r in rows:
    if r["variant"] not in best or float(r["total_s"]) < float(best[r["variant"]]["total_s"]):
        best[r["variant"]] = r
print("fastest of each variant (s): variant total wall analyze factorize write user sys peak_MB tip_rel_err load")
for v, r in best.items():
    print(v, r["total_s"], r["wall_s"], r["analyze_s"], r["factorize_s"], r["write_s"], r["user_s"], r["sys_s"], r["peak_MB"],
          r["tip_rel_err"], r["load"])
PY
