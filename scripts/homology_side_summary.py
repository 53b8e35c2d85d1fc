"""Medians of scripts/homology_side_by_side.sh output: GUDHI (SimplexTree build + persistence, whole
process) against each starplex binary and thread count, with the ratios.

    python3 scripts/homology_side_summary.py OUT.txt
"""
import sys, re, json, statistics as st
from collections import defaultdict
g = defaultdict(lambda: defaultdict(list)); s = defaultdict(lambda: defaultdict(list))
for l in open(sys.argv[1]):
    t = l.split()
    if not t: continue
    if t[0] == 'gudhi':
        j = json.loads(l[l.index('{'):l.index('}')+1])
        g[t[1]]['total_s'].append(j['total_s']); g[t[1]]['pers'].append(j['persistence_betti_s'])
        m = re.search(r'WALL ([0-9.]+) RSS ([0-9]+)', l); g[t[1]]['wall'].append(float(m[1])); g[t[1]]['rss'].append(int(m[2])/1000)
    elif t[0] == 'sp':
        k = (t[1], t[2], t[3]); s[k]['hs'].append(float(t[5])); s[k]['wall'].append(float(t[7])); s[k]['rss'].append(int(t[9])/1000)
for n, d in g.items():
    gm = {k: st.median(v) for k, v in d.items()}
    print(f"{n}: gudhi total {gm['total_s']:.3f} s (persistence {gm['pers']:.3f}) wall {gm['wall']:.2f} rss {gm['rss']:.1f} MB  [{len(d['wall'])} runs]")
    for k, e in sorted(s.items()):
        if k[2] != n: continue
        m = {x: st.median(v) for x, v in e.items()}
        print(f"   {k[0]} {k[1]}: homology {m['hs']:.3f} s ({gm['total_s']/m['hs']:.1f}x) wall {m['wall']:.2f} ({gm['wall']/m['wall']:.1f}x) rss {m['rss']:.1f} MB ({gm['rss']/m['rss']:.1f}x)")
