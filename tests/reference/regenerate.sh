#!/usr/bin/env bash
# Rebuild the reference results under tests/reference/ from the decks under inputs/.
#
#   bash tests/reference/regenerate.sh [inputs/DECK.inp ...]     (default: every inputs/*.inp)
#
# Only for a deliberate change of the results (a new deck, a changed mesh, a
# fix that moves the numbers): the references are what the regress_* tests
# compare every run with.  The executable is the Release build (scripts/build.sh
# Release, build/vemcontact) unless VEMCONTACT_EXE names another one.  Each
# result is rewritten compressed (python -m vctools.compare.repack, bit-for-bit
# the same values), compared with the fresh run, and recorded in MANIFEST.tsv
# (commit, machine, compiler, checksums).
#
# AFTER regenerating, re-run the checks that make a reference trustworthy
# (tests/reference/README.md lists them) and look at the diff of MANIFEST.tsv:
#   bash scripts/run-tests.sh          (or: ctest --test-dir build-debug)
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
py=${VC_PYTHON:-$root/.venv/bin/python}
if [ -z "${VEMCONTACT_EXE:-}" ]; then
  bash scripts/build.sh Release
  exe=$root/build/vemcontact
else
  exe=$VEMCONTACT_EXE
fi
decks=("$@")
[ ${#decks[@]} -eq 0 ] && decks=(inputs/*.inp)

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
commit=$(git rev-parse HEAD 2>/dev/null || echo unknown)
if [ -n "$(git status --porcelain -- src CMakeLists.txt cmake inputs 2>/dev/null)" ]; then
  commit="$commit+uncommitted-changes"
fi
machine="$(uname -m) $(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: //' | tr -s ' ')"
compiler=$(gfortran --version 2>/dev/null | head -1 || echo unknown)
version=$("$exe" --version)
stamp=$(date -u +%Y-%m-%dT%H:%M:%SZ)
manifest=tests/reference/MANIFEST.tsv
[ -f "$manifest" ] || printf 'reference\treference_sha256\tdeck_sha256\tcommit\tdate\tmachine\tcompiler\texecutable\n' > "$manifest"

for deck in "${decks[@]}"; do
  job=$(basename "$deck" .inp)
  ref=tests/reference/$job.h5
  "$exe" -q -o "$tmp" "$deck"
  PYTHONPATH=postprocess "$py" -m vctools.compare.repack "$tmp/$job.h5" "$ref"
  PYTHONPATH=postprocess "$py" -m vctools.compare --top 0 --rtol 0 --atol-u 0 --atol-s 0 "$tmp/$job.h5" "$ref" >/dev/null
  # the deck and the files it includes
  incs=$(sed -n 's/^\*INCLUDE, *INPUT=\(.*\)$/\1/Ip' "$deck" | tr -d '\r' | sed "s|^|$(dirname "$deck")/|")
  deck_sum=$(cat "$deck" $incs | sha256sum | cut -c1-16)
  ref_sum=$(sha256sum "$ref" | cut -c1-16)
  grep -v "^$job.h5	" "$manifest" > "$tmp/manifest" || true
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$job.h5" "$ref_sum" "$deck_sum" "$commit" "$stamp" \
    "$machine" "$compiler" "$version (Release)" >> "$tmp/manifest"
  { head -1 "$tmp/manifest"; tail -n +2 "$tmp/manifest" | sort; } > "$manifest"
  echo "$ref ($(du -k "$ref" | cut -f1) KiB)"
done
"$py" tests/reference/check.py tests/reference
echo "now re-run the checks listed in tests/reference/README.md (bash scripts/run-tests.sh)"
