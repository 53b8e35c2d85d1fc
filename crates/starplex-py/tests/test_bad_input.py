"""Bad input from Python: exceptions with clear messages, never a crash of the interpreter."""
import os
import subprocess

import numpy as np
import pytest

import starplex

PTS = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
TRIS = np.array([[0, 1, 2], [1, 3, 2]])


def test_wrong_dtypes():
    with pytest.raises(TypeError, match="integer ids"):
        starplex.Complex(PTS, TRIS.astype(float))
    with pytest.raises(TypeError, match="integer ids"):
        starplex.Complex(PTS, TRIS.astype(bool))
    with pytest.raises(TypeError, match="integer ids"):
        starplex.Complex(PTS, [["a", "b", "c"]])
    with pytest.raises(TypeError, match="points"):
        starplex.Complex(np.array([["x", "y"]] * 4), TRIS)
    with pytest.raises(TypeError, match="points"):
        starplex.Complex(PTS.astype(complex), TRIS)
    s = starplex.IaStar(starplex.Complex(PTS, TRIS))
    with pytest.raises(TypeError, match="integer ids"):
        s.vt(np.array([0.5]))
    with pytest.raises(TypeError):
        s.vt("0")


def test_non_contiguous_and_other_dtypes_are_accepted():
    big = np.zeros((4, 6), dtype=np.int16)
    big[:2, ::2] = TRIS
    view = big[:2, ::2]  # strided, not contiguous
    assert not view.flags["C_CONTIGUOUS"]
    c = starplex.Complex(np.asfortranarray(PTS), view)
    assert c.cells.tolist() == TRIS.tolist()
    assert c.points.tolist() == PTS.tolist()
    for dt in (np.uint8, np.int32, np.uint32, np.int64, np.uint64):
        assert starplex.Complex(PTS.astype(np.float32), TRIS.astype(dt)).n_cells == 2
    s = starplex.IaStar(c)
    ids = np.arange(8)[::2] // 2
    off, vals = s.vt(ids)
    assert len(off) == 5


def test_negative_and_out_of_range_ids():
    with pytest.raises(ValueError, match=r"cells\[1, 0\]: -1 is not a valid id"):
        starplex.Complex(PTS, [[0, 1, 2], [-1, 3, 2]])
    with pytest.raises(ValueError, match="out of range"):
        starplex.Complex(PTS, [[0, 1, 2], [1, 4, 2]])
    with pytest.raises(ValueError, match="is not a valid id"):
        starplex.Complex(PTS, np.array([[0, 1, 2**40]], dtype=np.uint64))
    with pytest.raises(ValueError, match="repeated|twice|more than once"):
        starplex.Complex(PTS, [[0, 1, 1]])
    s = starplex.StellarTree(starplex.Complex(PTS, TRIS))
    with pytest.raises(ValueError, match="vertex 4 out of range"):
        s.vt(4)
    with pytest.raises(ValueError, match="not a valid id"):
        s.vt(-1)
    with pytest.raises(ValueError, match="not a valid id"):
        s.vv(np.array([0, -3]))
    with pytest.raises(ValueError, match="vertex 9 out of range"):
        s.link([0, 9])
    with pytest.raises(ValueError, match="cell 2 out of range"):
        s.tv(2)
    with pytest.raises(ValueError, match="out of range"):
        s.boundary(np.array([[0, 7]]), q=0)
    with pytest.raises(ValueError, match="not a simplex"):
        s.coboundary(np.array([[0, 3]]), q=2)
    with pytest.raises(ValueError):
        s.vt(2**70)


def test_ragged_and_misshapen():
    with pytest.raises(ValueError, match="cells"):
        starplex.Complex(PTS, [[0, 1, 2], [1, 3]])
    with pytest.raises(ValueError, match="points"):
        starplex.Complex([[0.0, 0.0], [1.0]], TRIS)
    with pytest.raises(ValueError, match=r"points: expected an \(n, d\) array"):
        starplex.Complex(np.zeros(4), TRIS)
    with pytest.raises(ValueError, match=r"expected an \(m, k\) array"):
        starplex.Complex(PTS, np.array([0, 1, 2]))
    with pytest.raises(ValueError, match="a quad has 4 vertices, not 3"):
        starplex.Complex(PTS, {"quad": TRIS})
    with pytest.raises(ValueError, match="unknown cell type 'octahedron'"):
        starplex.Complex(PTS, [("octahedron", TRIS)])
    with pytest.raises(ValueError, match="non-finite|NaN|nan"):
        starplex.Complex(np.array([[0, 0], [1, np.nan], [0, 1], [1, 1]]), TRIS)
    with pytest.raises(ValueError):
        starplex.Complex(np.zeros((4, 0)), TRIS)
    with pytest.raises(ValueError, match="1-D"):
        starplex.IaStar(starplex.Complex(PTS, TRIS)).vt(np.zeros((2, 2), dtype=int))


def test_structure_refusals_are_value_errors():
    quads = starplex.Complex(np.zeros((4, 3)), {"quad": [[0, 1, 2, 3]]})
    for cls in (starplex.SimplexTree, starplex.Is, starplex.Hasse):
        with pytest.raises(ValueError, match="simpl"):
            cls(quads)
    with pytest.raises(ValueError, match="simplices"):
        starplex.IaStar(quads).link(0)
    with pytest.raises(TypeError):
        starplex.IaStar("not a complex")


def test_duplicates_and_faces():
    with pytest.raises(ValueError, match="duplicate"):
        starplex.Complex(PTS, [[0, 1, 2], [2, 1, 0]])
    assert starplex.Complex(PTS, [[0, 1, 2], [2, 1, 0]], drop_duplicates=True).n_cells == 1
    with pytest.raises(ValueError, match="face"):
        starplex.Complex(PTS, [TRIS, np.array([[0, 1]])])
    assert starplex.Complex(PTS, [TRIS, np.array([[0, 1]])], drop_faces=True).n_cells == 2


def test_file_errors_carry_the_command_line_message(tmp_path, cli):
    missing = tmp_path / "missing.off"
    with pytest.raises(OSError):
        starplex.read(missing)
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
    with pytest.raises(ValueError) as e:
        starplex.read(bad)
    r = subprocess.run([cli, "info", str(bad)], capture_output=True, text=True)
    assert r.returncode == 2
    assert str(e.value) in r.stderr, (str(e.value), r.stderr)
    c = starplex.Complex(np.zeros((4, 3)), [[0, 1, 2, 3]])  # a tetrahedron
    with pytest.raises(ValueError, match="tetra|OFF"):
        c.write(tmp_path / "x.off")
    assert not (tmp_path / "x.off").exists()
    with pytest.raises(ValueError, match="unknown"):
        c.write(tmp_path / "x.spx", format="nope")
    with pytest.raises(OSError):
        c.write(tmp_path / "no" / "such" / "dir.spx")


def test_interpreter_survives_everything_in_a_subprocess():
    """A crash (abort, segfault) would kill the child: run a batch of bad calls there."""
    code = r"""
import numpy as np, starplex
bad = [None, 1, "x", [], [[]], [[0, 1], [2]], np.zeros((0, 3)), np.zeros((2, 2, 2), int),
       np.array([[0, 1, 2]], dtype=object), np.array([[1e30, 0, 0]]), {"tri": None}, [("tri",)],
       np.array([[0, 1, -5]], dtype=np.int8), np.ma.masked_array([[0, 1, 2]])]
pts = [None, [], np.zeros((3,)), np.zeros((3, 65)), np.full((3, 2), np.inf), "abc", [[0, 0], [1, 1], [0, 1]]]
n = 0
for p in pts:
    for c in bad:
        try:
            starplex.Complex(p, c)
        except (ValueError, TypeError):
            n += 1
print("ok", n)
"""
    import sys

    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("ok")


def test_read_options_and_the_errors_that_name_them(tmp_path):
    """Each refusal names the keyword that reads the file; with it, the file is read and the
    reader's notes arrive as UserWarnings."""
    head = "OFF\n4 {nf} 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n"
    cases = [
        # (file body, keyword, cells read with it)
        (head.format(nf=1) + "3 0 1 2\n3 1 3 2\n", "lenient", 2),  # more faces than the header
        (head.format(nf=3) + "3 0 1 2\n3 1 3 2\n", "lenient", 2),  # fewer faces
        (head.format(nf=2) + "3 0 1 2\n3 1 1 2\n", "drop_degenerate", 1),
        (head.format(nf=2) + "3 0 1 2\n3 2 1 0\n", "drop_duplicates", 1),
    ]
    for i, (body, kw, n) in enumerate(cases):
        p = tmp_path / f"m{i}.off"
        p.write_text(body)
        with pytest.raises(ValueError, match=f"{p.name}.*pass {kw}=True"):
            starplex.read(str(p))
        with pytest.warns(UserWarning, match=p.name) as w:
            c = starplex.read(str(p), **{kw: True})
        assert c.n_cells == n, (kw, c.n_cells)
        assert len(w) >= 1
    # a face of another cell: drop_faces
    p = tmp_path / "faces.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\n")
    with pytest.raises(ValueError, match="pass drop_faces=True"):
        starplex.read(str(p))
    with pytest.warns(UserWarning, match="dropped 1 cells that are faces of other cells"):
        assert starplex.read(str(p), drop_faces=True).n_cells == 1
