//! Saving and loading a Stellar tree: a small fixed header followed by 8-byte-aligned arrays
//! (little-endian), read back through a memory map with `bytemuck` and checked before use.
//!
//! Layout: `b"SPXSTEL1"`, then 13 `u64` header words (version, ambient dimension, k_V, split,
//! vertices, cells, nodes, leaves, SRE words, vertex references, uniform kind code, stride,
//! flags: bit 0 = graph decomposition), the root block (2 x ambient `f64`), then the arrays: nodes, leaf vertex starts, leaf
//! list offsets, SRE words, cell kinds (mixed only), cell offsets (mixed only), cell vertices,
//! vertex permutation (tree -> input), cell permutation (tree -> input). Version 2 (written only
//! for a tree that carries attributes) appends the attribute section (`save_attrs`): the input's
//! vertex and cell columns in tree order, so they follow the renumbering.
//!
//! ```
//! # use starplex::complex::{ComplexBuilder, BuildOptions};
//! # use starplex::cell::CellKind;
//! use starplex::stellar::{StellarTree, StellarOptions};
//! # let mut b = ComplexBuilder::new(2).unwrap();
//! # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! # let k = b.build(&BuildOptions::default()).unwrap().0;
//! let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
//! let path = std::env::temp_dir().join(format!("starplex-doc-stellar-{}.stl", std::process::id()));
//! t.save(&path).unwrap();
//! let u = StellarTree::load(&path).unwrap();
//! assert_eq!(u.vt_all(), t.vt_all());
//! # std::fs::remove_file(&path).ok();
//! ```
use std::io::Write;
use std::path::Path;

use super::sre::RUN_FLAG;
use super::{
    code_kind, kind_code, BuildTimings, CellStore, Decomposition, SplitMode, StellarError,
    StellarTree, TreeNode,
};

/// The first 8 bytes of a saved Stellar tree.
///
/// ```
/// assert_eq!(starplex::stellar::SAVED_TREE_MAGIC, b"SPXSTEL1");
/// ```
pub const SAVED_TREE_MAGIC: &[u8; 8] = b"SPXSTEL1";

/// True when the file at `path` starts with [`SAVED_TREE_MAGIC`]: a tree written by
/// [`StellarTree::save`], recognised by content whatever its extension (a mesh format never
/// starts with these bytes). An unreadable or shorter file is not a saved tree.
///
/// ```
/// use starplex::stellar::is_saved_tree;
/// let p = std::env::temp_dir().join(format!("starplex_magic_{}.bin", std::process::id()));
/// std::fs::write(&p, b"SPXSTEL1 and the rest").unwrap();
/// assert!(is_saved_tree(&p));
/// std::fs::write(&p, b"OFF\n3 1 0\n").unwrap();
/// assert!(!is_saved_tree(&p));
/// # std::fs::remove_file(&p).ok();
/// assert!(!is_saved_tree(std::path::Path::new("/nonexistent/file")));
/// ```
pub fn is_saved_tree(path: &Path) -> bool {
    use std::io::Read;
    let mut magic = [0u8; 8];
    std::fs::File::open(path)
        .and_then(|mut f| f.read_exact(&mut magic))
        .is_ok()
        && &magic == SAVED_TREE_MAGIC
}
const MAGIC: &[u8; 8] = SAVED_TREE_MAGIC;
const VERSION: u64 = 1;
/// The version of a tree saved with attributes.
const VERSION_ATTRS: u64 = 2;
const N_HEADER: usize = 13;
/// Flags word: the vertices were split by connectivity ([`Decomposition::Graph`]).
const FLAG_GRAPH: u64 = 1;
/// Flags word: the vertices' coordinates follow the cell permutation (tree order).
const FLAG_COORDS: u64 = 2;
/// The header's kind code for a tree whose cells have several kinds (per-cell codes follow).
const MIXED: u8 = 255;

fn write_arr<T: bytemuck::Pod>(w: &mut dyn Write, a: &[T]) -> std::io::Result<()> {
    let bytes: &[u8] = bytemuck::cast_slice(a);
    w.write_all(bytes)?;
    let pad = (8 - bytes.len() % 8) % 8;
    w.write_all(&[0u8; 8][..pad])
}

impl StellarTree {
    /// Writes the tree to `path` (atomically: a temporary file renamed into place).
    ///
    /// # Errors
    /// The file cannot be written.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// use starplex::stellar::SAVED_TREE_MAGIC;
    /// let path = std::env::temp_dir().join(format!("starplex-doc-save-{}.stl", std::process::id()));
    /// t.save(&path).unwrap();
    /// assert_eq!(&std::fs::read(&path).unwrap()[..8], SAVED_TREE_MAGIC);
    /// # std::fs::remove_file(&path).ok();
    /// ```
    pub fn save(&self, path: &Path) -> Result<(), crate::io::IoError> {
        self.save_coords(path, self.coords.as_deref())
    }

    /// [`save`](Self::save) with the vertices' coordinates (`coords`, in the input's vertex
    /// order, as [`IndexedComplex::coords`](crate::complex::IndexedComplex::coords) gives
    /// them): the saved tree then also reads back as its complex
    /// ([`to_complex`](Self::to_complex)), so `info` and `convert` take it like a mesh.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let path = std::env::temp_dir().join(format!("starplex-doc-savec-{}.tree", std::process::id()));
    /// t.save_with_coords(&path, k.coords()).unwrap();
    /// assert!(StellarTree::load(&path).unwrap().has_coords());
    /// assert!(t.save_with_coords(&path, &[0.0]).is_err()); // not 4 points of 2 coordinates
    /// # std::fs::remove_file(&path).ok();
    /// ```
    ///
    /// # Errors
    /// A coordinate array of another length than vertices × ambient dimension; the writer's
    /// errors.
    pub fn save_with_coords(&self, path: &Path, coords: &[f64]) -> Result<(), crate::io::IoError> {
        let d = self.ambient_dim as usize;
        if coords.len() != d * self.v_orig.len() {
            return Err(crate::io::IoError::new(
                path,
                std::io::Error::other(format!(
                    "{} coordinates for {} vertices of {d} coordinates",
                    coords.len(),
                    self.v_orig.len()
                )),
            ));
        }
        let mut tree_order = Vec::with_capacity(coords.len());
        for &v in &self.v_orig {
            tree_order.extend_from_slice(&coords[d * v as usize..d * v as usize + d]);
        }
        self.save_coords(path, Some(&tree_order))
    }

    /// Writes the tree, with `coords` (tree order) when given.
    fn save_coords(&self, path: &Path, coords: Option<&[f64]>) -> Result<(), crate::io::IoError> {
        crate::io::atomic_write(path, |w| {
            w.write_all(MAGIC)?;
            let split = match self.split {
                SplitMode::Kd => 2u64,
                _ => 1,
            };
            let version = if self.attrs.is_empty() {
                VERSION
            } else {
                VERSION_ATTRS
            };
            let header: [u64; N_HEADER] = [
                version,
                self.ambient_dim as u64,
                self.kv as u64,
                split,
                self.v_orig.len() as u64,
                self.c_orig.len() as u64,
                self.nodes.len() as u64,
                self.n_leaves() as u64,
                self.leaf_tops.len() as u64,
                self.cells.verts.len() as u64,
                self.cells.uniform.map_or(MIXED, kind_code) as u64,
                self.cells.stride as u64,
                (u64::from(self.decomposition == Decomposition::Graph) * FLAG_GRAPH)
                    | (u64::from(coords.is_some()) * FLAG_COORDS),
            ];
            write_arr(w, &header)?;
            write_arr(w, &self.bbox.0)?;
            write_arr(w, &self.bbox.1)?;
            write_arr(w, &self.nodes)?;
            write_arr(w, &self.leaf_vstart)?;
            write_arr(w, &self.leaf_toff)?;
            write_arr(w, &self.leaf_tops)?;
            if self.cells.uniform.is_none() {
                write_arr(w, &self.cells.kinds)?;
                write_arr(w, &self.cells.offsets)?;
            }
            write_arr(w, &self.cells.verts)?;
            write_arr(w, &self.v_orig)?;
            write_arr(w, &self.c_orig)?;
            if let Some(c) = coords {
                write_arr(w, c)?;
            }
            if !self.attrs.is_empty() {
                super::save_attrs::write(w, &self.attrs)?;
            }
            Ok(())
        })
    }

    /// Reads a tree written by [`save`](Self::save), checking every array.
    ///
    /// # Errors
    /// A missing, truncated or inconsistent file.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let path = std::env::temp_dir().join(format!("starplex-doc-load-{}.stl", std::process::id()));
    /// t.save(&path).unwrap();
    /// let u = StellarTree::load(&path).unwrap();
    /// assert_eq!((u.n_leaves(), u.vertex_to_input()), (t.n_leaves(), t.vertex_to_input()));
    /// std::fs::write(&path, b"not a tree").unwrap();
    /// assert!(StellarTree::load(&path).is_err());
    /// # std::fs::remove_file(&path).ok();
    /// ```
    pub fn load(path: &Path) -> Result<StellarTree, StellarError> {
        let err = |reason: String| StellarError::File {
            path: path.display().to_string(),
            reason,
        };
        let file = std::fs::File::open(path).map_err(|e| err(e.to_string()))?;
        // SAFETY: the map is read-only and only read through bounds-checked slices; the file
        // may change under us only if another process writes it, which at worst yields data
        // that fails the checks below.
        let map = unsafe { memmap2::Mmap::map(&file) }.map_err(|e| err(e.to_string()))?;
        let mut r = Reader {
            data: &map,
            pos: 0,
            err: &err,
        };
        if r.bytes(8)? != MAGIC {
            return Err(err("not a starplex Stellar tree (bad magic)".into()));
        }
        let h = Header::read(&mut r, &err)?;
        let lo = r.arr::<f64>(h.amb)?;
        let hi = r.arr::<f64>(h.amb)?;
        let nodes = r.arr::<TreeNode>(h.nn)?;
        let leaf_vstart = r.arr::<u32>(h.nl + 1)?;
        let leaf_toff = r.arr::<u32>(h.nl + 1)?;
        let leaf_tops = r.arr::<u32>(h.ntops)?;
        let (kinds, offsets) = if h.uniform == MIXED {
            (r.arr::<u8>(h.nc)?, r.arr::<u32>(h.nc + 1)?)
        } else {
            (Vec::new(), Vec::new())
        };
        let verts = r.arr::<u32>(h.nrefs)?;
        let v_orig = r.arr::<u32>(h.nv)?;
        let c_orig = r.arr::<u32>(h.nc)?;
        let coords = if h.coords {
            let c = r.arr::<f64>(h.amb * h.nv)?;
            if let Some(i) = c.iter().position(|x| !x.is_finite()) {
                return Err(err(format!(
                    "tree vertex {} has a non-finite coordinate",
                    i / h.amb.max(1)
                )));
            }
            Some(c)
        } else {
            None
        };
        let attrs = if h.version == VERSION_ATTRS {
            let a = super::save_attrs::read(&mut |n| r.bytes(n), h.nv, h.nc, &err)?;
            if r.pos != r.data.len() {
                return Err(err(format!(
                    "{} bytes after the attribute section",
                    r.data.len() - r.pos
                )));
            }
            a
        } else {
            crate::attr::Attributes::default()
        };
        // ---- checks
        h.check_ranges(&leaf_vstart, &leaf_toff, &kinds, &offsets, &verts, &err)?;
        let v_new = inverse(&v_orig, "vertex", &err)?;
        let c_new = inverse(&c_orig, "cell", &err)?;
        h.check_leaf_lists(&leaf_toff, &leaf_tops, &err)?;
        h.check_nodes(&nodes, &err)?;
        let Header {
            amb,
            kv,
            split,
            decomposition,
            uniform,
            stride,
            nc,
            ..
        } = h;
        Ok(StellarTree {
            ambient_dim: amb as u32,
            kv,
            split,
            decomposition,
            bbox: (lo, hi),
            nodes,
            leaf_vstart,
            leaf_toff,
            leaf_tops,
            cells: CellStore {
                uniform: (uniform != MIXED).then(|| code_kind(uniform)),
                stride,
                kinds,
                offsets,
                verts,
                n: nc as u32,
            },
            v_orig,
            v_new,
            c_orig,
            c_new,
            timings: BuildTimings::default(),
            coords,
            attrs,
        })
    }
}

/// The counts and codes of a saved tree's header, range-checked.
struct Header {
    version: u64,
    amb: usize,
    kv: u32,
    split: SplitMode,
    nv: usize,
    nc: usize,
    nn: usize,
    nl: usize,
    ntops: usize,
    nrefs: usize,
    uniform: u8,
    stride: u32,
    decomposition: Decomposition,
    /// The coordinates follow the cell permutation.
    coords: bool,
}

/// The error of [`StellarTree::load`] for one reason.
type LoadErr<'a> = &'a dyn Fn(String) -> StellarError;

impl Header {
    /// Reads the header words after the magic: version, sizes (each within its id range),
    /// split and kind codes, flags.
    fn read<F: Fn(String) -> StellarError>(
        r: &mut Reader<'_, F>,
        err: LoadErr<'_>,
    ) -> Result<Header, StellarError> {
        let h: Vec<u64> = r.arr::<u64>(N_HEADER)?;
        if h[0] != VERSION && h[0] != VERSION_ATTRS {
            return Err(err(format!("unsupported version {}", h[0])));
        }
        let lim = |x: u64, what: &str, max: u64| {
            if x > max {
                Err(err(format!("{what} = {x} is out of range")))
            } else {
                Ok(x as usize)
            }
        };
        let amb = lim(h[1], "ambient dimension", 64)?;
        let kv = lim(h[2], "k_V", u32::MAX as u64)? as u32;
        let split = match h[3] {
            1 => SplitMode::Regular,
            2 => SplitMode::Kd,
            x => return Err(err(format!("bad split code {x}"))),
        };
        let nv = lim(h[4], "vertices", u32::MAX as u64 - 1)?;
        let nc = lim(h[5], "cells", RUN_FLAG as u64 - 1)?;
        let nn = lim(h[6], "nodes", u32::MAX as u64)?;
        let nl = lim(h[7], "leaves", u32::MAX as u64 - 1)?;
        let ntops = lim(h[8], "SRE words", u32::MAX as u64)?;
        let nrefs = lim(h[9], "vertex references", u32::MAX as u64)?;
        let uniform = lim(h[10], "kind code", 255)? as u8;
        let stride = lim(h[11], "stride", 65)? as u32;
        if h[12] & !(FLAG_GRAPH | FLAG_COORDS) != 0 {
            return Err(err(format!("unknown flags {:#x}", h[12])));
        }
        let decomposition = if h[12] & FLAG_GRAPH != 0 {
            Decomposition::Graph
        } else {
            Decomposition::Spatial
        };
        Ok(Header {
            version: h[0],
            amb,
            kv,
            split,
            nv,
            nc,
            nn,
            nl,
            ntops,
            nrefs,
            uniform,
            stride,
            decomposition,
            coords: h[12] & FLAG_COORDS != 0,
        })
    }

    /// Leaf vertex ranges and list offsets increasing over their arrays, cell kinds and
    /// offsets consistent, vertex indices in range.
    fn check_ranges(
        &self,
        leaf_vstart: &[u32],
        leaf_toff: &[u32],
        kinds: &[u8],
        offsets: &[u32],
        verts: &[u32],
        err: LoadErr<'_>,
    ) -> Result<(), StellarError> {
        let &Header {
            nv,
            nc,
            ntops,
            nrefs,
            uniform,
            stride,
            ..
        } = self;
        let monotone = |a: &[u32], first: u32, last: usize| {
            a.first() == Some(&first)
                && a.last().map(|&x| x as usize) == Some(last)
                && a.windows(2).all(|w| w[0] <= w[1])
        };
        if !monotone(leaf_vstart, 0, nv) {
            return Err(err(
                "leaf vertex ranges are not increasing over all vertices".into(),
            ));
        }
        if !monotone(leaf_toff, 0, ntops) {
            return Err(err("leaf list offsets are inconsistent".into()));
        }
        if uniform == MIXED {
            if !monotone(offsets, 0, nrefs) || kinds.iter().any(|&k| k > 68) {
                return Err(err("cell offsets or kinds are inconsistent".into()));
            }
            for c in 0..nc {
                if (offsets[c + 1] - offsets[c]) as usize != code_kind(kinds[c]).n_vertices() {
                    return Err(err(format!("cell {c}: wrong vertex count for its kind")));
                }
            }
        } else if uniform > 68
            || code_kind(uniform).n_vertices() != stride as usize
            || nrefs != nc * stride as usize
        {
            return Err(err("uniform cell kind and array size disagree".into()));
        }
        if let Some(v) = verts.iter().find(|&&v| v as usize >= nv) {
            return Err(err(format!("vertex index {v} out of range")));
        }
        // a tree is built from a checked complex: no cell repeats a vertex
        let distinct = |c: &[u32]| (1..c.len()).all(|i| !c[..i].contains(&c[i]));
        let repeated = if uniform == MIXED {
            (0..nc).find(|&c| !distinct(&verts[offsets[c] as usize..offsets[c + 1] as usize]))
        } else {
            verts
                .chunks_exact(stride as usize)
                .position(|c| !distinct(c))
        };
        if let Some(c) = repeated {
            return Err(err(format!("cell {c} repeats a vertex")));
        }
        Ok(())
    }

    /// SRE words: runs complete, ids in range, increasing within each leaf.
    fn check_leaf_lists(
        &self,
        leaf_toff: &[u32],
        leaf_tops: &[u32],
        err: LoadErr<'_>,
    ) -> Result<(), StellarError> {
        for l in 0..self.nl {
            let enc = &leaf_tops[leaf_toff[l] as usize..leaf_toff[l + 1] as usize];
            let mut i = 0;
            let mut last: i64 = -1;
            while i < enc.len() {
                let (s, e) = if enc[i] & RUN_FLAG != 0 {
                    let Some(&rlen) = enc.get(i + 1) else {
                        return Err(err(format!("leaf {l}: truncated run")));
                    };
                    let s = (enc[i] & !RUN_FLAG) as u64;
                    i += 2;
                    (s, s + rlen as u64)
                } else {
                    i += 1;
                    (enc[i - 1] as u64, enc[i - 1] as u64)
                };
                if (s as i64) <= last || e >= self.nc as u64 {
                    return Err(err(format!("leaf {l}: cell list out of order or range")));
                }
                last = e as i64;
            }
        }
        Ok(())
    }

    /// Every node's vertex range and children (or leaf) in range; a root exists.
    fn check_nodes(&self, nodes: &[TreeNode], err: LoadErr<'_>) -> Result<(), StellarError> {
        let &Header { nv, nl, nn, .. } = self;
        for (i, n) in nodes.iter().enumerate() {
            let ok = n.v_start <= n.v_end
                && (n.v_end as usize) <= nv
                && if n.n_children == 0 {
                    (n.first as usize) < nl.max(1)
                } else {
                    (n.first as usize) > i && (n.first as u64 + n.n_children as u64) <= nn as u64
                };
            if !ok {
                return Err(err(format!("node {i} is inconsistent")));
            }
        }
        if nodes.is_empty() {
            return Err(err("no root node".into()));
        }
        Ok(())
    }
}

/// The inverse of a permutation `p` of `0..p.len()`, refused when `p` is not one.
fn inverse(p: &[u32], what: &str, err: LoadErr<'_>) -> Result<Vec<u32>, StellarError> {
    let mut inv = vec![u32::MAX; p.len()];
    for (i, &x) in p.iter().enumerate() {
        if x as usize >= p.len() || inv[x as usize] != u32::MAX {
            return Err(err(format!("{what} permutation is not a bijection")));
        }
        inv[x as usize] = i as u32;
    }
    Ok(inv)
}

struct Reader<'a, F: Fn(String) -> StellarError> {
    data: &'a [u8],
    pos: usize,
    err: &'a F,
}

impl<'a, F: Fn(String) -> StellarError> Reader<'a, F> {
    fn bytes(&mut self, n: usize) -> Result<&'a [u8], StellarError> {
        let data: &'a [u8] = self.data;
        let end = self
            .pos
            .checked_add(n)
            .filter(|&e| e <= self.data.len())
            .ok_or_else(|| (self.err)(format!("truncated at byte {}", self.pos)))?;
        let s = &data[self.pos..end];
        self.pos = end;
        Ok(s)
    }
    fn arr<T: bytemuck::Pod>(&mut self, n: usize) -> Result<Vec<T>, StellarError> {
        let size = n
            .checked_mul(std::mem::size_of::<T>())
            .ok_or_else(|| (self.err)("array size overflows".into()))?;
        let b = self.bytes(size)?;
        let mut v: Vec<T> = vec![T::zeroed(); n];
        bytemuck::cast_slice_mut::<T, u8>(&mut v).copy_from_slice(b);
        let pad = (8 - size % 8) % 8;
        self.bytes(pad)?;
        Ok(v)
    }
}
