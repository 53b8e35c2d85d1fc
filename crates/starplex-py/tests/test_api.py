"""The API on tiny named fixtures: shapes and dtypes, every structure agreeing, round trips."""
import doctest
import threading

import numpy as np
import pytest

import starplex

STRUCTURES = [
    starplex.StellarTree,
    starplex.IaStar,
    starplex.SimplexTree,
    starplex.IncidenceGraph,
    starplex.Is,
    starplex.Hasse,
]


def two_tets():
    """Two tetrahedra sharing the triangle 1-2-3, plus a dangling edge 4-5 (not pure)."""
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1], [2, 2, 2]], dtype=float)
    return starplex.Complex(pts, [np.array([[0, 1, 2, 3], [4, 1, 2, 3]]), np.array([[4, 5]])])


def test_every_structure_answers_the_same():
    c = two_tets()
    answers = []
    for cls in STRUCTURES:
        s = cls(c) if cls is not starplex.StellarTree else cls(c, kv=2)
        a = {
            "vt": [x.tolist() for x in s.vt()],
            "vv": [x.tolist() for x in s.vv()],
            "tv": [x.tolist() for x in s.tv()],
            "tt": [x.tolist() for x in s.tt()],
            "link": [[x.tolist() for x in lvl] for lvl in s.link()],
            "star": [[x.tolist() for x in lvl] for lvl in s.star()],
            "cob": [x.tolist() for x in s.coboundary(q=2)],
            "bd": [x.tolist() for x in s.boundary(np.array([[0, 1, 2, 3]]), q=1)],
            "adj": [x.tolist() for x in s.adjacency(np.array([[1, 2, 3]]))],
            "f": s.f_vector(),
            "faces": [s.faces(p).tolist() for p in range(4)],
        }
        # the order of rows within one answer may differ between structures: sort them
        for key in ("cob", "bd", "adj"):
            off, rows = a[key]
            a[key] = [sorted(map(tuple, rows[off[i]:off[i + 1]])) for i in range(len(off) - 1)]
        a["faces"] = [sorted(map(tuple, f)) for f in a["faces"]]
        # the simplex tree and the Hasse diagram give a top cell's vertices sorted (DESIGN.md)
        off, tv = a["tv"]
        a["tv"] = [sorted(tv[off[i]:off[i + 1]]) for i in range(len(off) - 1)]
        answers.append((cls.__name__, a))
    name0, a0 = answers[0]
    for name, a in answers[1:]:
        for key in a0:
            assert a[key] == a0[key], (name, key)
    assert a0["f"] == [6, 10, 7, 2]
    assert a0["tt"] == [[0, 1, 2, 2], [1, 0]]  # CSR: tet 0 <-> tet 1, the line has none
    vt_off, vt = a0["vt"]
    assert vt[vt_off[4]:vt_off[5]] == [1, 2]


def test_shapes_and_dtypes():
    c = two_tets()
    s = starplex.IaStar(c)
    assert s.vt(0).dtype == np.uint32 and s.vt(0).ndim == 1
    off, vals = s.vt()
    assert off.dtype == np.int64 and off.shape == (7,) and vals.dtype == np.uint32
    off, vals = s.vt([])
    assert off.tolist() == [0] and vals.size == 0
    link = s.link(1)
    assert [lvl.shape[1] for lvl in link] == list(range(1, len(link) + 1))
    per_level = s.star([0, 5])
    for p, (off, vals) in enumerate(per_level):
        assert off.shape == (3,) and vals.shape[1] == p + 1
    assert s.coboundary(0, q=3).shape == (1, 4)
    off, rows = s.coboundary(np.array([[1, 2], [4, 5]]), q=2)
    assert rows.shape[1] == 3 and off.tolist() == [0, 3, 3]
    assert s.adjacency(4).shape[1] == 1
    assert isinstance(s.n_vertices, int) and s.storage_bytes > 0
    assert "IaStar" in repr(s) and "6 vertices" in repr(c)


def test_points_cells_roundtrip(tmp_path):
    c = two_tets()
    assert c.points.shape == (6, 3) and c.points.dtype == np.float64
    assert isinstance(c.cells, list) and [a.shape for a in c.cells] == [(2, 4), (1, 2)]
    assert [k for k, _ in c.cell_blocks] == ["tet", "line"]
    for ext in ("spx", "spb", "vtk", "msh"):  # (Medit groups cells by kind: ids change)
        p = tmp_path / f"x.{ext}"
        c.write(p)
        d = starplex.read(p)
        assert np.array_equal(d.points, c.points), ext
        assert [(k, a.tolist()) for k, a in d.cell_blocks] == [(k, a.tolist()) for k, a in c.cell_blocks], ext
    tri = starplex.Complex(np.eye(3), np.array([[0, 1, 2]], dtype=np.int32))
    assert tri.cells.shape == (1, 3) and tri.cells.dtype == np.uint32


def test_info_validate_homology():
    c = two_tets()
    info = c.info()
    assert info["f_vector"] == [6, 10, 7, 2] and info["pure"] is False
    assert info["top_cells"] == {"line": 1, "tet": 2}
    assert info["euler_characteristic"] == 1
    r = c.validate()
    assert r["pure"] is False
    assert r["lower_dimensional_cells"].tolist() == [2]
    assert r["boundary_faces"].shape == (6, 3)
    assert r["non_manifold_vertices"].dtype == np.uint32
    h = c.homology()
    assert h["betti"] == [1, 0, 0, 0] and h["betti_z2"] == h["betti"]
    assert c.homology("z")["torsion"] == [[], [], [], []]
    torus = torus_complex()
    assert torus.homology()["betti"] == [1, 2, 1]
    assert torus.info(betti=True)["betti_z2"] == [1, 2, 1]
    with pytest.raises(ValueError):
        c.homology("x")


def torus_complex(n=4, m=4):
    pts, tris = [], []
    for i in range(n):
        for j in range(m):
            pts.append([i, j, 0.0])
            a, b = i * m + j, ((i + 1) % n) * m + j
            c_, d = i * m + (j + 1) % m, ((i + 1) % n) * m + (j + 1) % m
            tris += [[a, b, d], [a, d, c_]]
    return starplex.Complex(np.array(pts), np.array(tris))


def test_calls_release_the_gil():
    """Several threads query at once; all answers are equal (and nothing deadlocks)."""
    c = torus_complex(60, 60)
    s = starplex.IaStar(c)
    want = [x.tolist() for x in s.vv()]
    out = []

    def work():
        out.append([x.tolist() for x in s.vv()])

    ts = [threading.Thread(target=work) for _ in range(4)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert out == [want] * 4


def test_docstring_examples():
    """The examples in every docstring run (the module's and the native classes')."""
    assert doctest.testmod(starplex).failed == 0
    finder = doctest.DocTestFinder()
    runner = doctest.DocTestRunner()
    seen = 0
    for obj in [starplex.read, starplex.Complex, *STRUCTURES, starplex.Structure,
                starplex.rips, starplex.flag, starplex.HasseComplex]:
        for name in [None, *dir(obj)]:
            x = obj if name is None else getattr(obj, name)
            if name and name.startswith("__"):
                continue
            doc = getattr(x, "__doc__", None)
            if not isinstance(doc, str) or ">>>" not in doc:
                continue
            for t in finder.find(doc, name=f"{getattr(obj, '__name__', obj)}.{name}", globs={}):
                runner.run(t)
                seen += 1
    assert seen >= 6
    assert runner.failures == 0


def test_helpers():
    import types

    blocks = [types.SimpleNamespace(type="tetra", data=np.array([[0, 1, 2, 3]])),
              types.SimpleNamespace(type="wedge", data=np.array([[4, 5, 6, 7, 8, 9]]))]
    m = types.SimpleNamespace(points=np.arange(30.0).reshape(10, 3), cells=blocks)
    c = starplex.from_meshio(m)
    assert [k for k, _ in c.cell_blocks] == ["tet", "prism"]
    with pytest.raises(ValueError, match="polygon"):
        starplex.from_meshio(types.SimpleNamespace(points=m.points, cells=[types.SimpleNamespace(type="polygon", data=[[0, 1, 2, 3, 4]])]))
    try:
        import trimesh  # noqa: F401
    except ImportError:
        return
    t = starplex.to_trimesh(torus_complex())
    assert t.faces.shape == (32, 3)
