//! Conversion from and to [`IndexedComplex`] (so every file format works) and export to
//! Graphviz DOT.
use std::fmt::Write as _;

use super::complex::Hasse;
use super::edit::Position;
use super::levels::{At, LevelTypes};
use super::orient::HasseOrientation;
use super::{HasseError, Node};
use crate::cell::CellKind;
use crate::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use crate::ids::VertexId;

/// Options of [`Hasse::to_dot`].
///
/// ```
/// let o = starplex::hasse::DotOptions::default();
/// assert!(o.show_root);
/// ```
#[derive(Clone, Debug)]
pub struct DotOptions {
    /// Draw the root (empty simplex) below the vertices.
    pub show_root: bool,
    /// Refuse to draw more nodes than this (the drawing would be useless).
    pub max_nodes: usize,
}

impl Default for DotOptions {
    fn default() -> Self {
        DotOptions {
            show_root: true,
            max_nodes: 5000,
        }
    }
}

impl<L: LevelTypes> Hasse<L> {
    /// Builds the complex of an indexed complex's simplicial cells (vertex labels = vertex ids
    /// of `k`; vertices used by no cell are not inserted); data gets default values. Complexes
    /// of dimension at most 3 are built level by level by sorting facets (nodes in
    /// lexicographic order, up lists in exactly-sized contiguous blocks); higher dimensions are
    /// inserted cell by cell (Alg. 1).
    ///
    /// # Errors
    /// [`HasseError::NotSimplicial`] for a quad, prism, ...; the errors of
    /// [`insert`](Self::insert).
    ///
    /// ```
    /// use starplex::complex::{ComplexBuilder, BuildOptions};
    /// use starplex::cell::CellKind;
    /// let mut b = ComplexBuilder::new(2).unwrap();
    /// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let h: starplex::hasse::Hasse = starplex::hasse::Hasse::from_indexed(&k).unwrap();
    /// assert_eq!(h.f_vector(), vec![4, 5, 2]);
    /// ```
    pub fn from_indexed(k: &IndexedComplex) -> Result<Self, HasseError> {
        let mut h = Self::new();
        let mut buf: Vec<u32> = Vec::new();
        let top = k.dim().unwrap_or(0);
        let mut per_dim: Vec<Vec<u32>> = vec![Vec::new(); top.min(3) + 1];
        for (cid, c) in k.cells().enumerate() {
            let CellKind::Simplex(d) = c.kind else {
                return Err(crate::limits::NotSimplicial::new(
                    cid as u64,
                    c.kind,
                    "the Hasse complex",
                )
                .with_hint(crate::tds::simplex_tree::CP_STRUCTURES_HINT)
                .into());
            };
            let d = d as usize;
            if d + 1 > super::MAX_INSERT_VERTICES {
                return Err(super::insert::too_many_faces(d + 1));
            }
            buf.clear();
            buf.extend_from_slice(c.vertices);
            buf.sort_unstable();
            if let Some(w) = buf.windows(2).find(|w| w[0] == w[1]) {
                return Err(HasseError::Degenerate {
                    vertices: c.vertices.iter().map(|&x| VertexId(x)).collect(),
                    repeated: VertexId(w[0]),
                });
            }
            if top <= 3 {
                let out = &mut per_dim[d];
                for &x in &buf {
                    out.push(x);
                }
            } else {
                h.insert_sorted(&buf);
            }
        }
        if top <= 3 {
            h.bulk_build(&per_dim);
        }
        h.shrink_to_fit();
        Ok(h)
    }

    /// Copies the first three coordinates of `k`'s vertices (missing ones are 0) into the
    /// level-0 positions (vertex label = vertex id of `k`).
    ///
    /// ```
    /// use starplex::complex::{ComplexBuilder, BuildOptions};
    /// use starplex::cell::CellKind;
    /// let mut b = ComplexBuilder::new(2).unwrap();
    /// for p in [[0.0, 0.0], [1.0, 0.0]] { b.push_vertex(&p).unwrap(); }
    /// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let mut h: starplex::hasse::Hasse<([f64; 3],)> = starplex::hasse::Hasse::from_indexed(&k).unwrap();
    /// h.set_positions_from(&k);
    /// assert_eq!(*h.data::<0>(h.vertex(1.into()).unwrap().id), [1.0, 0.0, 0.0]);
    /// ```
    pub fn set_positions_from(&mut self, k: &IndexedComplex)
    where
        L: At<0>,
        <L as At<0>>::Data: Position,
    {
        let ids: Vec<u32> = self.level(0).map(|v| v.id.0).collect();
        for i in ids {
            let lab = self.levels[0].verts(i)[0];
            if (lab as usize) < k.n_vertices() {
                let c = k.point(VertexId(lab));
                let mut p = [0.0; 3];
                for (j, x) in c.iter().take(3).enumerate() {
                    p[j] = *x;
                }
                self.level_data_mut::<0>()[i as usize].set_position(p);
            }
        }
    }

    /// The maximal simplices (those without cofaces), by dimension then id.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// h.insert(&[2.into(), 3.into()]).unwrap();
    /// assert_eq!(h.maximal_simplices().len(), 2);
    /// ```
    pub fn maximal_simplices(&self) -> Vec<Node> {
        self.nodes().filter(|&n| self.up(n).len() == 0).collect()
    }

    /// An indexed complex of the maximal simplices; vertices renumbered `0..n` in label order
    /// (the labels are returned), coordinates from `coord` (`ambient_dim` values each). When an
    /// orientation of the top dimension is given, top simplices with sign `-1` are written with
    /// their first two vertices swapped.
    ///
    /// # Errors
    /// [`HasseError::Complex`] when the builder refuses (e.g. a NaN coordinate).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[5.into(), 7.into(), 9.into()]).unwrap();
    /// let (k, labels) = h.to_indexed(2, |_| vec![0.0, 0.0], None).unwrap();
    /// assert_eq!(k.n_cells(), 1);
    /// assert_eq!(labels, vec![5.into(), 7.into(), 9.into()]);
    /// ```
    pub fn to_indexed(
        &self,
        ambient_dim: usize,
        mut coord: impl FnMut(Node) -> Vec<f64>,
        orientation: Option<&HasseOrientation>,
    ) -> Result<(IndexedComplex, Vec<VertexId>), HasseError> {
        let mut b = ComplexBuilder::new(ambient_dim)?;
        let mut order: Vec<(u32, u32)> = self
            .level(0)
            .map(|v| (self.levels[0].verts(v.id.0)[0], v.id.0))
            .collect();
        order.sort_unstable();
        let mut index = rustc_hash::FxHashMap::default();
        let mut labels = Vec::with_capacity(order.len());
        for (j, &(lab, i)) in order.iter().enumerate() {
            let mut c = coord(Node::new(0, i.into()));
            c.resize(ambient_dim, 0.0);
            b.push_vertex(&c)?;
            index.insert(lab, j as u32);
            labels.push(VertexId(lab));
        }
        for n in self.maximal_simplices() {
            let mut vs: Vec<u32> = self.vertices(n).iter().map(|v| index[&v.0]).collect();
            if let Some(o) = orientation
                && o.dim == n.dim as usize
                && o.signs.get(n.id.index()) == Some(&-1)
                && vs.len() >= 2
            {
                vs.swap(0, 1);
            }
            b.push_cell(CellKind::Simplex(n.dim as u8), &vs)?;
        }
        let opts = BuildOptions {
            trust_maximality: true,
            ..BuildOptions::default()
        };
        Ok((b.build(&opts)?.0, labels))
    }

    /// The Hasse diagram in Graphviz DOT: one rank per dimension, arrows from faces up to
    /// cofaces, nodes labelled by their vertices.
    ///
    /// # Errors
    /// A message when the complex has more than `opts.max_nodes` simplices.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into()]).unwrap();
    /// let dot = h.to_dot(&Default::default()).unwrap();
    /// assert!(dot.starts_with("digraph hasse {"));
    /// assert!(dot.contains("\"{0,1}\""));
    /// ```
    pub fn to_dot(&self, opts: &DotOptions) -> Result<String, String> {
        if self.len() > opts.max_nodes {
            return Err(format!(
                "{} simplices: more than the {} allowed in a drawing",
                self.len(),
                opts.max_nodes
            ));
        }
        let name = |n: Node| {
            let v: Vec<String> = self.vertices(n).iter().map(|x| x.0.to_string()).collect();
            format!("\"{{{}}}\"", v.join(","))
        };
        let mut s = String::from("digraph hasse {\n  rankdir=BT;\n");
        if opts.show_root {
            s.push_str("  \"{}\" [label=\"root\"];\n");
        }
        for k in 0..self.levels.len() {
            if self.n_simplices(k) == 0 {
                continue;
            }
            s.push_str("  { rank=same;");
            for n in self.level(k) {
                let _ = write!(s, " {};", name(n));
            }
            s.push_str(" }\n");
        }
        for n in self.nodes() {
            if n.dim == 0 {
                if opts.show_root {
                    let _ = writeln!(s, "  \"{{}}\" -> {};", name(n));
                }
                continue;
            }
            for f in self.down(n) {
                let _ = writeln!(s, "  {} -> {};", name(f), name(n));
            }
        }
        s.push_str("}\n");
        Ok(s)
    }
}
