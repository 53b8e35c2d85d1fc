#!/bin/bash
# Checks that two starplex binaries give byte-identical saved Stellar trees (default k_V and
# k_V = 7) and equal validation reports (timings removed) on the given inputs.
# usage: scripts/compare_stellar_outputs.sh OLD_BIN NEW_BIN FILE...
# e.g.   scripts/compare_stellar_outputs.sh old/starplex target/release/starplex $STARPLEX_DATA/small/*/*.spx
set -u
A=$1; B=$2; shift 2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
bad=0
norm() { python3 -c "import json,sys;d=json.load(sys.stdin);d.pop('timings',None);print(json.dumps(d,sort_keys=True))"; }
for f in "$@"; do
  for kv in "" "--kv 7"; do
    $A stellar "$f" $kv --save "$tmp/a.spt" --quiet >/dev/null 2>"$tmp/a.err"; ra=$?
    $B stellar "$f" $kv --save "$tmp/b.spt" --quiet >/dev/null 2>"$tmp/b.err"; rb=$?
    if [ $ra != $rb ]; then echo "DIFF exit code $f $kv: $ra $rb"; bad=1; continue; fi
    [ $ra != 0 ] && { echo "both refuse $f $kv: $(head -1 "$tmp/a.err")"; continue; }
    cmp -s "$tmp/a.spt" "$tmp/b.spt" && echo "same tree  $(basename "$f") $kv" || { echo "DIFF tree $f $kv"; bad=1; }
  done
  $A validate "$f" --json --quiet 2>/dev/null | norm > "$tmp/a.json"
  $B validate "$f" --json --quiet 2>/dev/null | norm > "$tmp/b.json"
  cmp -s "$tmp/a.json" "$tmp/b.json" && echo "same report $(basename "$f")" || { echo "DIFF report $f"; bad=1; }
done
exit $bad
