#!/usr/bin/env python3
"""Compare `starplex query` (the oracle's vertex queries: VT, VV, link f-vector and maximal
simplices) and `starplex validate` (components, boundary faces, non-manifold vertices and edges of
surfaces) with the third-party oracles, on every dataset found.

usage: scripts/check_queries.py DATA_DIR [SIZE ...] [--structure S]
    DATA_DIR as made by ../shared/datasets/get; SIZE defaults to small medium; S defaults to
    stellar (any of vt ia-star simplex-tree ig is hasse stellar; the structures that hold
    simplices only — simplex-tree, is, hasse — are skipped on CP complexes). Needs `cargo build --release -p starplex-cli`.
Prints one line per dataset and exits 1 on any mismatch.
"""
import json, subprocess, sys, time

from datasets import BIN, with_oracles


def norm(v):
    """Lists of lists compared as sorted lists of sorted lists (the oracle lists link simplices in
    top-cell order)."""
    if isinstance(v, list) and v and isinstance(v[0], list):
        return sorted(sorted(x) for x in v)
    return v


def main():
    args = sys.argv[1:]
    structure = 'stellar'
    if '--structure' in args:
        i = args.index('--structure')
        structure = args[i + 1]
        del args[i:i + 2]
    data = args[0]
    sizes = args[1:] or ['small', 'medium']
    bad = 0
    for size, name, spx, o in with_oracles(data, sizes):
        qs = o.get('vertex_queries') or []
        simplicial = o.get('top_cells') is not None and all(
            t == 'line' or t == 'tri' or t == 'tet' or t.startswith('simplex_') for t in o['top_cells'])
        if not simplicial and structure not in ('stellar', 'vt', 'ig', 'ia-star'):
            print('%-20s %-7s skipped (%s holds simplices only)' % (name, size, structure))
            continue
        problems = []
        t0 = time.time()
        cmd = [BIN, '--quiet', 'query', spx, '--structure', structure,
               '--relation', 'vt', 'vv', 'link' if simplicial else 'vv', '--json', '--vertex']
        cmd += [str(q['vertex']) for q in qs]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            problems.append('query failed: ' + p.stderr.strip())
        else:
            got = json.loads(p.stdout)
            keys = ['incident_top_cells', 'vv']
            if simplicial:
                keys += ['link_f_vector', 'link_maximal_simplices']
            for g, q in zip(got, qs):
                for k in keys:
                    # medium oracles omit what was too costly to compute (sierp: vv, links)
                    if k in q and norm(g.get(k)) != norm(q.get(k)):
                        problems.append('vertex %s %s' % (q['vertex'], k))
        tq = time.time() - t0
        t0 = time.time()
        p = subprocess.run([BIN, '--quiet', 'validate', spx, '--json'], capture_output=True, text=True)
        if p.returncode != 0:
            problems.append('validate failed: ' + p.stderr.strip())
        else:
            v = json.loads(p.stdout)
            for k in ['n_connected_components', 'n_boundary_faces', 'n_non_manifold_vertices',
                      'n_non_manifold_edges']:
                if o.get(k) is not None and v.get(k) != o[k]:
                    problems.append('%s %s != oracle %s' % (k, v.get(k), o[k]))
        tv = time.time() - t0
        status = 'OK' if not problems else 'MISMATCH ' + '; '.join(problems[:5])
        bad += bool(problems)
        print('%-20s %-7s %d vertices  query %.2fs  validate %.2fs  %s'
              % (name, size, len(qs), tq, tv, status), flush=True)
    sys.exit(1 if bad else 0)


if __name__ == '__main__':
    main()
