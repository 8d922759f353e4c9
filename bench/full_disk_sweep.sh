#!/usr/bin/env bash
# Full disk at every size: the dam deck (inputs/dam_joint.inp) written into a tmpfs of
# SIZE KiB for SIZE = FROM, FROM+STEP, ..., TO (default 100k..1800k in 10k steps,
# issue 25).  Every run must end with exit status 2 ("No space left on device", one
# message) or 0 (the results fit), never a signal.  Needs root (mount -t tmpfs).
#
#   bash bench/full_disk_sweep.sh [EXE] [FROM] [TO] [STEP]
#
# Prints one line per size that is not 0 or 2 (with the first lines of stderr) and a
# summary; exits 1 if there was any.  About 0.5 s per size (Release).
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
EXE=${1:-$ROOT/build/vemcontact}
FROM=${2:-100}
TO=${3:-1800}
STEP=${4:-10}
DECK=${DECK:-$ROOT/inputs/dam_joint.inp}
WORK=$(mktemp -d)
MNT=$WORK/mnt
mkdir -p "$MNT"
trap 'umount "$MNT" 2>/dev/null; rm -rf "$WORK"' EXIT
declare -A seen=()
bad=0
for ((kib = FROM; kib <= TO; kib += STEP)); do
    if ! mount -t tmpfs -o "size=${kib}k" tmpfs "$MNT"; then
        echo "cannot mount a tmpfs (root needed)" >&2
        exit 2
    fi
    "$EXE" -q -o "$MNT/out" "$DECK" >"$WORK/stdout" 2>"$WORK/stderr"
    rc=$?
    umount "$MNT"
    seen[$rc]=$(( ${seen[$rc]:-0} + 1 ))
    lines=$(wc -l <"$WORK/stderr")
    if [[ $rc -ne 0 && $rc -ne 2 ]] || grep -q -e Backtrace -e Segmentation "$WORK/stderr" ||
       { [[ $rc -eq 2 ]] && ! grep -q "No space left on device" "$WORK/stderr"; }; then
        bad=$((bad + 1))
        echo "size ${kib}k: exit $rc, $lines lines on stderr:"
        head -5 "$WORK/stderr" | sed 's/^/    /'
    fi
done
printf 'sizes %sk..%sk step %sk:' "$FROM" "$TO" "$STEP"
for rc in "${!seen[@]}"; do printf ' exit %s x %s;' "$rc" "${seen[$rc]}"; done
printf ' %s bad\n' "$bad"
[[ $bad -eq 0 ]]
