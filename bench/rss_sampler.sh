#!/bin/sh
# Samples the resident memory (VmRSS, kB) of every running `vemcontact` process started
# after this script, every 0.5 s, as "seconds_since_start pid kB" lines on stdout, until
# killed.  Used by bench/scale.py's runs to attribute memory to phases (docs/performance.md,
# "Scale: 1e7 unknowns and MPI").  usage: sh bench/rss_sampler.sh > rss.txt &
t0=$(date +%s.%N)
while :; do
  for p in $(pgrep -x vemcontact); do
    kb=$(awk '/^VmRSS/ {print $2}' /proc/$p/status 2>/dev/null)
    [ -n "$kb" ] && echo "$(echo "$(date +%s.%N) - $t0" | bc) $p $kb"
  done
  sleep 0.5
done
