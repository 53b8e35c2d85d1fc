"""Answers from Python equal the datasets' oracles and the command line's, for every structure."""
import json
import subprocess

import numpy as np
import pytest

import starplex
from conftest import SMALL, need_data

ALL = ["StellarTree", "IaStar", "SimplexTree", "IncidenceGraph", "Is", "Hasse"]
CP = {"StellarTree", "IaStar", "IncidenceGraph"}  # the ones that hold quads, hexahedra, ...
CLI_NAME = {
    "StellarTree": "stellar",
    "IaStar": "ia-star",
    "SimplexTree": "simplex-tree",
    "IncidenceGraph": "ig",
    "Is": "is",
    "Hasse": "hasse",
}
# structures that store every simplex are built only below this many simplices (time budget)
MAX_SIMPLICES = 400_000

INFO_KEYS = [
    "n_vertices",
    "n_isolated_vertices",
    "ambient_dim",
    "dim",
    "pure",
    "top_cells",
    "n_top_cells",
    "f_vector",
    "euler_characteristic",
    "n_boundary_faces",
    "n_faces_shared_by_more_than_2_top_cells",
    "n_connected_components",
]


def structures_for(oracle):
    simplicial = all(k in ("vertex", "line", "tri", "tet") or k.startswith("simplex_") for k in oracle["top_cells"])
    small = (oracle.get("n_simplices") or 10**9) <= MAX_SIMPLICES
    out = []
    for s in ALL:
        if not simplicial and s not in CP:
            continue
        if s in ("SimplexTree", "IncidenceGraph", "Is", "Hasse") and not small:
            continue
        out.append(s)
    return out


@pytest.fixture(scope="module")
def loaded():
    need_data()
    return {name: (p, starplex.read(p), o) for name, p, o in SMALL}


def test_info_equals_oracle(loaded):
    for name, (p, c, o) in loaded.items():
        info = c.info()
        for k in INFO_KEYS:
            if k in o and info.get(k) is not None:
                assert info[k] == o[k], f"{name}: {k}"
        assert np.allclose(c.info()["bbox"], o["bbox"]), name
        assert c.n_vertices == o["n_vertices"] and c.n_cells == o["n_top_cells"], name


def test_validate_and_homology_equal_oracle(loaded):
    for name, (p, c, o) in loaded.items():
        r = c.validate()
        for k in ("n_boundary_faces", "n_non_manifold_vertices", "n_non_manifold_edges", "n_connected_components"):
            if o.get(k) is not None:
                assert r[k] == o[k], f"{name}: {k}"
        assert len(r["non_manifold_vertices"]) == r["n_non_manifold_vertices"]
        if "betti_z2" in o and o.get("n_simplices", 10**9) <= MAX_SIMPLICES:
            assert c.homology()["betti"] == o["betti_z2"], name


def test_vertex_queries_equal_oracle(loaded):
    for name, (p, c, o) in loaded.items():
        queries = o.get("vertex_queries") or []
        ids = np.array([q["vertex"] for q in queries], dtype=np.int64)
        for sname in structures_for(o):
            s = getattr(starplex, sname)(c)
            off, vals = s.vt(ids)
            for i, q in enumerate(queries):
                one = s.vt(int(q["vertex"]))
                assert sorted(one.tolist()) == sorted(q["incident_top_cells"]), (name, sname)
                assert one.tolist() == vals[off[i]:off[i + 1]].tolist(), (name, sname)
                if "vv" in q:
                    assert sorted(s.vv(q["vertex"]).tolist()) == sorted(q["vv"]), (name, sname)
                if "link_simplices" in q:
                    link = s.link(q["vertex"])
                    got = sorted(sorted(x) for level in link for x in level.tolist())
                    assert got == sorted(sorted(x) for x in q["link_simplices"]), (name, sname)
                    assert [len(level) for level in link] == q["link_f_vector"], (name, sname)


def test_answers_equal_the_command_line(loaded, cli):
    for name, (p, c, o) in loaded.items():
        queries = o.get("vertex_queries") or []
        ids = [str(q["vertex"]) for q in queries]
        for sname in structures_for(o):
            out = subprocess.run(
                [cli, "--quiet", "query", str(p), "--structure", CLI_NAME[sname], "--relation", "vt", "vv", "link", "--json", "--vertex", *ids],
                capture_output=True,
                text=True,
                check=True,
            ).stdout
            want = json.loads(out)
            s = getattr(starplex, sname)(c)
            for w in want:
                v = w["vertex"]
                assert s.vt(v).tolist() == w["incident_top_cells"], (name, sname, v)
                assert s.vv(v).tolist() == w["vv"], (name, sname, v)
                if w["link_f_vector"] is not None:
                    link = s.link(v)
                    assert [len(level) for level in link] == w["link_f_vector"], (name, sname, v)
                    top = [sorted(x) for x in link[-1].tolist()] if link else []
                    # the CLI lists the maximal simplices of the link: the top level is among them
                    assert all(t in w["link_maximal_simplices"] for t in top), (name, sname, v)


def test_every_vertex_vt_equals_tv_transposed(loaded):
    """VT of every vertex as CSR is the transpose of the cells (ids ascending)."""
    for name, (p, c, o) in loaded.items():
        s = starplex.IaStar(c)
        off, vals = s.vt()
        assert off.dtype == np.int64 and vals.dtype == np.uint32
        assert len(off) == c.n_vertices + 1 and off[-1] == len(vals)
        coff, cvals = c.vt()  # straight from the complex: the same CSR
        assert np.array_equal(coff, off) and np.array_equal(cvals, vals), name
        toff, tv = s.tv()
        cell_of = np.repeat(np.arange(c.n_cells), np.diff(toff))
        order = np.lexsort((cell_of, tv))
        assert np.array_equal(vals, cell_of[order]), name
        assert np.array_equal(np.diff(off), np.bincount(tv, minlength=c.n_vertices)), name


def test_cli_export_reads_back_equal_to_python(loaded, cli, tmp_path):
    """`query --all --out` (.npz, .jsonl) holds what the Python calls return."""
    for name, (p, c, o) in loaded.items():
        if name not in ("tri_elephant", "mixed_plate_s", "tet_elephant"):
            continue
        s = starplex.IaStar(c)
        for rel, method in (("vt", s.vt), ("vv", s.vv)):
            out = tmp_path / f"{name}-{rel}.npz"
            subprocess.run([cli, "--quiet", "query", str(p), "--structure", "ia-star", "--relation", rel,
                            "--all", "--out", str(out)], check=True)
            z = np.load(out)
            off, vals = method()
            assert np.array_equal(z["offsets"], off) and np.array_equal(z["values"], vals), (name, rel)
            assert np.array_equal(z["ids"], np.arange(c.n_vertices)), name
            jl = tmp_path / f"{name}-{rel}.jsonl"
            subprocess.run([cli, "--quiet", "query", str(p), "--structure", "ia-star", "--relation", rel,
                            "--all", "--out", str(jl)], check=True)
            with open(jl) as fh:
                for v, line in enumerate(fh):
                    assert json.loads(line)["vertex"] == v
            assert v == c.n_vertices - 1
        if name == "tri_elephant":
            out = tmp_path / "link.npz"
            subprocess.run([cli, "--quiet", "query", str(p), "--relation", "link", "--all", "--out", str(out)], check=True)
            z = np.load(out)
            link = s.link()
            for lvl, (off, vals) in enumerate(link):
                assert np.array_equal(z[f"offsets_{lvl}"], off) and np.array_equal(z[f"values_{lvl}"], vals)
            out = tmp_path / "faces.npz"
            subprocess.run([cli, "--quiet", "query", str(p), "--relation", "pfaces", "--all", "--out", str(out)], check=True)
            z = np.load(out)
            assert [z[f"faces_{d}"].shape[0] for d in range(3)] == o["f_vector"]
