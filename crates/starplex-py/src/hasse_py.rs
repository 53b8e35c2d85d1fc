//! `HasseComplex`: the editable CASC Hasse complex with user data per level as NumPy columns.
//!
//! The Rust complex carries, per simplex of dimension 0 to 11, the *row* of its data in the
//! level's columns (and, for vertices, a 3D position for smoothing). Edits move rows with the
//! simplices: a merge (collapse, decimate) keeps the row of the first merged simplex, as
//! `KeepFirst`, and averages the positions; simplices an edit creates have no row (NaN in float
//! columns, 0 in int ones, False in `has_data`).

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use starplex::attr::{AttrValues, Attribute};
use starplex::hasse::{Hasse, Merge, Node, Position};
use starplex::ids::VertexId;

use crate::{arr1, arr2, attrs, index_array, value_err, Complex};

const NONE: u32 = u32::MAX;
/// Levels with data: dimensions 0 to 11, as many as the Rust `Hasse` levels go (a Rips or
/// flag complex of 3D points has simplices well above dimension 3).
const LEVELS: usize = 12;

#[derive(Clone, Copy, Debug)]
struct Row(u32);

impl Default for Row {
    fn default() -> Self {
        Row(NONE)
    }
}

#[derive(Clone, Copy, Debug)]
struct V0 {
    pos: [f64; 3],
    row: u32,
}

impl Default for V0 {
    fn default() -> Self {
        V0 {
            pos: [0.0; 3],
            row: NONE,
        }
    }
}

impl Position for V0 {
    fn position(&self) -> [f64; 3] {
        self.pos
    }
    fn set_position(&mut self, p: [f64; 3]) {
        self.pos = p;
    }
}

type L = (V0, Row, Row, Row, Row, Row, Row, Row, Row, Row, Row, Row);

/// `$body` with `$d` bound to the level data of dimension `$k` (1 to 11, each a `[Row]`), for
/// the runtime dimension `$k`; `$other` for any other dimension.
macro_rules! on_row_level {
    ($k:expr, |$d:ident : $get:ident| $body:expr, $other:expr) => {
        match $k {
            1 => {
                let $d = $get!(1);
                $body
            }
            2 => {
                let $d = $get!(2);
                $body
            }
            3 => {
                let $d = $get!(3);
                $body
            }
            4 => {
                let $d = $get!(4);
                $body
            }
            5 => {
                let $d = $get!(5);
                $body
            }
            6 => {
                let $d = $get!(6);
                $body
            }
            7 => {
                let $d = $get!(7);
                $body
            }
            8 => {
                let $d = $get!(8);
                $body
            }
            9 => {
                let $d = $get!(9);
                $body
            }
            10 => {
                let $d = $get!(10);
                $body
            }
            11 => {
                let $d = $get!(11);
                $body
            }
            _ => $other,
        }
    };
}

/// Merges keep the first row; a merged vertex sits at the mean of the merged positions.
struct PyMerge;

impl Merge<0, V0> for PyMerge {
    fn merge(&mut self, _new: &[VertexId], old: &[(&[VertexId], &V0)]) -> V0 {
        let mut p = [0.0; 3];
        for (_, v) in old {
            for (a, b) in p.iter_mut().zip(v.pos) {
                *a += b / old.len() as f64;
            }
        }
        V0 {
            pos: p,
            row: old[0].1.row,
        }
    }
}

impl<const K: usize> Merge<K, Row> for PyMerge {
    fn merge(&mut self, _new: &[VertexId], old: &[(&[VertexId], &Row)]) -> Row {
        *old[0].1
    }
}

/// An editable Hasse complex (CASC) with per-level data columns.
///
/// `HasseComplex(c)` builds every simplex of a simplicial complex `c` (at most 3 coordinates);
/// `c.point_data` becomes the vertex columns (`data(0)`) and, when every top cell is a
/// simplex of one dimension at most 11, `c.cell_data` that level's columns. Simplices are named
/// by their vertex labels (the vertex ids of `c`; edits add fresh labels).
///
/// >>> import numpy as np, starplex
/// >>> c = starplex.Complex(np.eye(4)[:, :3], [[0, 1, 2], [1, 3, 2]], cell_data={"t": [5, 6]})
/// >>> h = starplex.HasseComplex(c)
/// >>> h.f_vector()
/// [4, 5, 2]
/// >>> h.set_data(1, "w", np.arange(5.0))
/// >>> h.flip([1, 2])
/// [0, 3]
/// >>> h.data(1)["w"].ravel().tolist()  # the new edge took the freed slot, without data
/// [0.0, 1.0, nan, 3.0, 4.0]
/// >>> h.to_complex().n_cells
/// 2
#[pyclass(module = "starplex._starplex")]
pub(crate) struct HasseComplex {
    h: Hasse<L>,
    /// Columns per level, indexed by row.
    cols: Vec<Vec<Attribute>>,
    ambient_dim: usize,
}

fn labels(v: &[u32]) -> Vec<VertexId> {
    v.iter().map(|&x| VertexId(x)).collect()
}

impl HasseComplex {
    fn row(&self, n: Node) -> u32 {
        let i = n.id.0 as usize;
        if n.dim == 0 {
            return self.h.level_data::<0>()[i].row;
        }
        macro_rules! get {
            ($k:literal) => {
                self.h.level_data::<$k>()
            };
        }
        on_row_level!(n.dim, |d: get| d[i].0, NONE)
    }

    fn set_row(&mut self, n: Node, r: u32) {
        let i = n.id.0 as usize;
        if n.dim == 0 {
            self.h.level_data_mut::<0>()[i].row = r;
            return;
        }
        macro_rules! get {
            ($k:literal) => {
                self.h.level_data_mut::<$k>()
            };
        }
        on_row_level!(n.dim, |d: get| d[i].0 = r, ())
    }

    fn check_level(&self, k: usize) -> PyResult<()> {
        if k >= LEVELS {
            return Err(value_err(format!(
                "level {k}: data is kept on levels 0 to {}",
                LEVELS - 1
            )));
        }
        Ok(())
    }

    /// The live simplices of level k, in id order.
    fn live(&self, k: usize) -> Vec<Node> {
        self.h.level(k).collect()
    }

    /// Column `c` gathered by the rows of `nodes` (missing rows: NaN / 0).
    fn gather(&self, c: &Attribute, nodes: &[Node]) -> Attribute {
        let w = c.components;
        let rows: Vec<u32> = nodes.iter().map(|&n| self.row(n)).collect();
        let values = match &c.values {
            AttrValues::Int(v) => AttrValues::Int(
                rows.iter()
                    .flat_map(|&r| {
                        (0..w).map(move |j| if r == NONE { 0 } else { v[r as usize * w + j] })
                    })
                    .collect(),
            ),
            AttrValues::Float(v) => AttrValues::Float(
                rows.iter()
                    .flat_map(|&r| {
                        (0..w).map(move |j| {
                            if r == NONE {
                                f64::NAN
                            } else {
                                v[r as usize * w + j]
                            }
                        })
                    })
                    .collect(),
            ),
        };
        Attribute {
            name: c.name.clone(),
            components: w,
            values,
        }
    }

    /// Renumbers the rows of level k to the live simplices in id order (columns gathered).
    fn normalize(&mut self, k: usize) -> Vec<Node> {
        let nodes = self.live(k);
        let cols: Vec<Attribute> = self.cols[k]
            .iter()
            .map(|c| self.gather(c, &nodes))
            .collect();
        for (i, &n) in nodes.iter().enumerate() {
            self.set_row(n, i as u32);
        }
        self.cols[k] = cols;
        nodes
    }

    fn node(&self, obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Node> {
        let (v, shape) = index_array(obj, what)?;
        if shape.len() > 1 || v.is_empty() {
            return Err(value_err(format!(
                "{what}: expected the vertex labels of one simplex, got shape {shape:?}"
            )));
        }
        self.h
            .find(&labels(&v))
            .ok_or_else(|| value_err(format!("{what} {v:?}: not a simplex of the complex")))
    }
}

#[pymethods]
impl HasseComplex {
    #[new]
    fn new(py: Python<'_>, c: PyRef<'_, Complex>) -> PyResult<Self> {
        let k = c.k();
        let d = k.ambient_dim();
        if d > 3 {
            return Err(value_err(format!(
                "HasseComplex: positions have at most 3 coordinates, these have {d}"
            )));
        }
        let mut h: Hasse<L> = py
            .detach(|| Hasse::<L>::from_indexed(&k))
            .map_err(value_err)?;
        let mut cols: Vec<Vec<Attribute>> = vec![Vec::new(); LEVELS];
        let verts: Vec<Node> = h.level(0).collect();
        for v in verts {
            let label = h.vertices(v)[0].0 as usize;
            let mut pos = [0.0; 3];
            pos[..d].copy_from_slice(k.point(VertexId(label as u32)));
            let has_rows = !k.attributes().vertex.is_empty();
            h.level_data_mut::<0>()[v.id.0 as usize] = V0 {
                pos,
                row: if has_rows { label as u32 } else { NONE },
            };
        }
        cols[0] = k.attributes().vertex.clone();
        let mut out = HasseComplex {
            h,
            cols,
            ambient_dim: d,
        };
        // cell data on a level when every top cell is a simplex of that dimension (<= 11)
        let top: Vec<_> = k.cells().map(|c| c.kind.dim()).collect();
        if let Some(&t) = top.first()
            && t < LEVELS
            && top.iter().all(|&x| x == t)
            && k.is_simplicial()
            && !k.attributes().cell.is_empty()
        {
            let cells: Vec<(u32, Vec<VertexId>)> = k
                .cells()
                .map(|c| (c.id.0, c.vertices.iter().map(|&v| VertexId(v)).collect()))
                .collect();
            for (id, vs) in cells {
                if let Some(n) = out.h.find(&vs) {
                    out.set_row(n, id);
                }
            }
            out.cols[t] = k.attributes().cell.clone();
        }
        Ok(out)
    }

    /// Number of simplices per dimension.
    fn f_vector(&self) -> Vec<usize> {
        self.h.f_vector()
    }

    /// The p-simplices: `(ids, vertices)`, ids the uint32 slots (stable under edits of other
    /// simplices), vertices the `(n, p + 1)` labels, in id order (the order of `data(p)`).
    fn simplices<'py>(&self, py: Python<'py>, p: usize) -> PyResult<Bound<'py, PyTuple>> {
        let nodes = self.live(p);
        let ids: Vec<u32> = nodes.iter().map(|n| n.id.0).collect();
        let v: Vec<u32> = nodes
            .iter()
            .flat_map(|&n| self.h.vertices(n).iter().map(|x| x.0))
            .collect();
        PyTuple::new(py, [arr1(py, ids), arr2(py, v, p + 1)?])
    }

    /// The columns of level p: a dict name -> `(n_p, components)` array aligned with
    /// `simplices(p)`; simplices without data (created by an edit) read NaN / 0.
    fn data<'py>(&self, py: Python<'py>, p: usize) -> PyResult<Bound<'py, PyDict>> {
        self.check_level(p)?;
        let nodes = self.live(p);
        let cols: Vec<Attribute> = self.cols[p]
            .iter()
            .map(|c| self.gather(c, &nodes))
            .collect();
        attrs::columns_out(py, &cols)
    }

    /// Whether each p-simplex (in `simplices(p)` order) has a row of data.
    fn has_data<'py>(&self, py: Python<'py>, p: usize) -> PyResult<Bound<'py, PyAny>> {
        self.check_level(p)?;
        let v: Vec<bool> = self.live(p).iter().map(|&n| self.row(n) != NONE).collect();
        Ok(arr1(py, v))
    }

    /// Sets (or replaces) column `name` of level p: one row per p-simplex, in `simplices(p)`
    /// order.
    fn set_data(&mut self, p: usize, name: String, values: &Bound<'_, PyAny>) -> PyResult<()> {
        self.check_level(p)?;
        let d = PyDict::new(values.py());
        d.set_item(&name, values)?;
        let mut col = attrs::columns_in(Some(d.as_any()), &format!("level {p} data"))?;
        let col = col.pop().expect("one column");
        let n = self.h.f_vector().get(p).copied().unwrap_or(0);
        if col.n_items() != n || col.values.len() != n * col.components {
            return Err(value_err(format!(
                "level {p} data '{name}': {} rows, expected {n} (one per {p}-simplex)",
                col.values.len() / col.components.max(1)
            )));
        }
        self.normalize(p);
        self.cols[p].retain(|c| c.name != name);
        self.cols[p].push(col);
        Ok(())
    }

    /// Vertex positions, `(n_0, 3)` in `simplices(0)` order (settable; `to_complex` and
    /// `smooth` use them).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let d = self.h.level_data::<0>();
        let v: Vec<f64> = self
            .live(0)
            .iter()
            .flat_map(|n| d[n.id.0 as usize].pos)
            .collect();
        arr2(py, v, 3)
    }

    #[setter]
    fn set_positions(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let (v, d) = crate::points_array(value)?;
        let nodes = self.live(0);
        if d != 3 || v.len() != nodes.len() * 3 {
            return Err(value_err(format!(
                "positions: expected an ({}, 3) array, got {} rows of {d}",
                nodes.len(),
                v.len().checked_div(d).unwrap_or(0)
            )));
        }
        let data = self.h.level_data_mut::<0>();
        for (n, p) in nodes.iter().zip(v.chunks_exact(3)) {
            data[n.id.0 as usize].pos = [p[0], p[1], p[2]];
        }
        Ok(())
    }

    /// Collapses the edge `(a, b)` (link condition checked) into one vertex at their midpoint;
    /// returns the label kept.
    fn collapse(&mut self, edge: &Bound<'_, PyAny>) -> PyResult<u32> {
        let e = self.node(edge, "edge")?;
        self.h.can_collapse(e).map_err(value_err)?;
        Ok(self.h.collapse(e, &mut PyMerge).map_err(value_err)?.0)
    }

    /// Bistellar flip of a simplex (an edge of a triangle mesh: the two triangles at it turn
    /// into the two at the other diagonal); returns the labels of the new simplex.
    fn flip(&mut self, simplex: &Bound<'_, PyAny>) -> PyResult<Vec<u32>> {
        let s = self.node(simplex, "simplex")?;
        let n = self.h.flip(s).map_err(value_err)?;
        Ok(self.h.vertices(n).iter().map(|v| v.0).collect())
    }

    /// Stellar split of a simplex at a new vertex placed at its centroid; returns its label.
    fn split(&mut self, simplex: &Bound<'_, PyAny>) -> PyResult<u32> {
        let s = self.node(simplex, "simplex")?;
        let centroid = self.centroid(s);
        let p = self.h.split(s).map_err(value_err)?;
        if let Some(v) = self.h.vertex(p) {
            self.h.level_data_mut::<0>()[v.id.0 as usize].pos = centroid;
        }
        Ok(p.0)
    }

    /// Decimates a simplex into one new vertex (CASC generalized decimation) at the mean of
    /// its vertices; data merges keep the first row. Returns the new label.
    fn decimate(&mut self, simplex: &Bound<'_, PyAny>) -> PyResult<u32> {
        let s = self.node(simplex, "simplex")?;
        let centroid = self.centroid(s);
        let p = self.h.decimate(s, &mut PyMerge).map_err(value_err)?;
        if let Some(v) = self.h.vertex(p) {
            self.h.level_data_mut::<0>()[v.id.0 as usize].pos = centroid;
        }
        Ok(p.0)
    }

    /// Laplacian smoothing of the positions (`lam` step, `iterations`, boundary vertices
    /// fixed unless `fix_boundary=False`).
    #[pyo3(signature = (lam = 0.5, iterations = 1, fix_boundary = true))]
    fn smooth(&mut self, py: Python<'_>, lam: f64, iterations: usize, fix_boundary: bool) {
        let h = &mut self.h;
        py.detach(|| h.smooth_laplacian(lam, iterations, fix_boundary));
    }

    /// The maximal simplices as a Complex: vertices renumbered in label order (their labels in
    /// `point_data["label"]` when `labels=True`), the vertex columns as `point_data`.
    #[pyo3(signature = (*, labels = false))]
    fn to_complex(&self, py: Python<'_>, labels: bool) -> PyResult<Complex> {
        let d = self.ambient_dim;
        let pos = self.h.level_data::<0>();
        let h = &self.h;
        let (mut k, lab) = py
            .detach(|| h.to_indexed(d, |n| pos[n.id.0 as usize].pos[..d].to_vec(), None))
            .map_err(value_err)?;
        let nodes: Vec<Node> = lab
            .iter()
            .map(|&l| self.h.vertex(l).expect("a label of the complex"))
            .collect();
        let mut a = k.take_attributes();
        a.vertex = self.cols[0]
            .iter()
            .map(|c| self.gather(c, &nodes))
            .collect();
        if labels {
            a.vertex.retain(|c| c.name != "label");
            a.vertex.push(Attribute::int(
                "label",
                1,
                lab.iter().map(|l| l.0 as i64).collect(),
            ));
        }
        k.set_attributes(a).map_err(value_err)?;
        Ok(Complex::wrap(k))
    }

    fn __repr__(&self) -> String {
        format!("<starplex.HasseComplex: f-vector {:?}>", self.h.f_vector())
    }
}

impl HasseComplex {
    fn centroid(&self, s: Node) -> [f64; 3] {
        let vs = self.h.vertices(s);
        let d = self.h.level_data::<0>();
        let mut c = [0.0; 3];
        for v in vs {
            if let Some(n) = self.h.vertex(*v) {
                for (a, b) in c.iter_mut().zip(d[n.id.0 as usize].pos) {
                    *a += b / vs.len() as f64;
                }
            }
        }
        c
    }
}
