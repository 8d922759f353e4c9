#!/usr/bin/env bash
# Assembly rate (issue 15): elements per second of the stiffness assembly at 1e4,
# 1e5 and 1e6 Voronoi cells (unit square, vctools.mesh, 10 Lloyd iterations, seed
# 1), and where the time goes: node graph + CSC pattern, the element kernels alone,
# kernels + scatter by a binary search per node pair (the assembly before issue 15)
# and assemble_stiffness (one walk per column); bench_assembly_rate keeps the fastest of
# REPEATS runs of each, in processor time (the loops are serial, so the load of the
# shared machine does not count).  Each mesh is run as the mesher numbers it (along
# a Hilbert curve, vctools.mesh.mesh.spatial_order) and
# renumbered in Z order (bench/renumber_mesh.py): the effect of the node numbering.
#
#   usage: bench/assembly.sh     environment: SIZES (default "1e4 1e5 1e6"), REPEATS (5),
#                                VC_BUILD (an existing Release build)
# Writes bench/results/assembly.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
sizes=${SIZES:-"1e4 1e5 1e6"}
reps=${REPEATS:-5}
if [ -n "${VC_BUILD:-}" ]; then build=$VC_BUILD; else bash scripts/build.sh Release >/dev/null; build=$root/build; fi
py=$root/.venv/bin/python
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
csv=bench/results/assembly.csv
mkdir -p bench/results
echo "cells,numbering,elements,nodes,nnz,pattern_s,kernel_s,searched_s,assemble_s,max_rel_diff,elements_per_s,load" > "$csv"
for s in $sizes; do
  cells=$(awk -v x="$s" 'BEGIN{printf "%d", x + 0}')
  printf '[mesh]\ntitle = "assembly: unit square, %s cells"\nseed = 1\nlloyd = 10\n\n[[body]]\nname = "SQUARE"\nrectangle = [0.0, 0.0, 1.0, 1.0]\nmesher = "voronoi"\ncells = %s\n' \
    "$cells" "$cells" > "$work/sq.toml"
  PYTHONPATH=$root/postprocess "$py" -m vctools.mesh scene "$work/sq.toml" -o "$work/mesh.inp" > /dev/null
  "$py" bench/renumber_mesh.py "$work/mesh.inp" "$work/mesh_z.inp"
  for numbering in mesher z; do
    m=mesh.inp; [ $numbering = z ] && m=mesh_z.inp
    printf '*INCLUDE, INPUT=%s\n*MATERIAL, NAME=ROCK\n*ELASTIC\n1.0e10, 0.3\n*SOLID SECTION, ELSET=SQUARE, MATERIAL=ROCK\n*STEP\n*STATIC\n*END STEP\n' "$m" > "$work/a.inp"
    load=$(cut -d' ' -f1 /proc/loadavg)
    line=$("$build/bench/bench_assembly_rate" "$work/a.inp" "$reps" | tail -1)
    rate=$(echo "$line" | awk -F, '{printf "%.3g", $1 / $7}')
    echo "$cells,$numbering,$line,$rate,$load" >> "$csv"
    echo "  $cells cells, $numbering numbering: $line -> $rate elements/s (load $load)"
  done
done
