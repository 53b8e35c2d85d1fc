#!/bin/bash
# usage: bench.sh FILE... ; prints median read time (info's "time read") old vs new, 7 alternating runs
for f in "$@"; do
  o=(); n=()
  for i in 1 2 3 4 5 6 7; do
    o+=($(/tmp/starplex-old info "$f" 2>/dev/null | awk '/^  time/{print $3}'))
    n+=($(/tmp/starplex-new info "$f" 2>/dev/null | awk '/^  time/{print $3}'))
  done
  mo=$(printf "%s\n" "${o[@]}" | sort -g | sed -n 4p); mn=$(printf "%s\n" "${n[@]}" | sort -g | sed -n 4p)
  sz=$(stat -c %s "$f")
  echo "$f $sz bytes: old $mo s ($(echo "$sz/$mo/1000000" | bc) MB/s), new $mn s ($(echo "$sz/$mn/1000000" | bc) MB/s), new/old $(echo "scale=3; $mn/$mo" | bc)"
done
