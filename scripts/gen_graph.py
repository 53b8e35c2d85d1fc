#!/usr/bin/env python3
"""A seeded random graph as an edge list (two ids per line) for `starplex flag`.

usage: gen_graph.py ba N M SEED OUT     Barabasi-Albert (networkx.barabasi_albert_graph(N, M,
                                        seed=SEED)): N*M - M*M edges, power-law degrees, hubs
       gen_graph.py gnm N E SEED OUT    Erdos-Renyi G(N, E) (networkx.gnm_random_graph)

The ids of the BA graph are shuffled (numpy default_rng(SEED).permutation) so that hubs are
not the first ids.
"""
import sys

import networkx as nx
import numpy as np


def main():
    kind, n, m, seed, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
    if kind == "ba":
        g = nx.barabasi_albert_graph(n, m, seed=seed)
    elif kind == "gnm":
        g = nx.gnm_random_graph(n, m, seed=seed)
    else:
        sys.exit("kind: ba or gnm")
    perm = np.random.default_rng(seed).permutation(n)
    e = np.array(g.edges(), dtype=np.int64)
    e = perm[e]
    np.savetxt(out, e, fmt="%d")
    print(f"{out}: {n} vertices, {len(e)} edges")


if __name__ == "__main__":
    main()
