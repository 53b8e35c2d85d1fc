//! Inputs of complexes built from data: point clouds and edge lists.
//!
//! Point clouds: `.xyz` (whitespace columns, the first three are the coordinates: CGAL's point
//! sets carry normals after them), `.txt`/`.pts`/`.dat` (whitespace columns, all of them),
//! `.csv` (comma-separated, an optional header line), `.npy` (a 2-D array of floats or integers,
//! one point per row), and the vertices of any mesh starplex reads (`.off`, `.ply`, `.obj`,
//! `.spx`, ...). Every row must have the same number of columns.
//!
//! Edge lists: two vertex ids per line (more columns, such as weights, are ignored), or CSV
//! with a header; `#` and `%` start comments.
//!
//! ```
//! use starplex::io::points::{read_points_from, PointFormat};
//! let p = read_points_from("0 0 0\n1 0 0 # a comment\n\n0 1 0\n".as_bytes(), "p.txt".as_ref(), PointFormat::Columns(None)).unwrap();
//! assert_eq!((p.dim, p.coords.len()), (3, 9));
//! let e = read_points_from("0 0\n1 0 0\n".as_bytes(), "p.txt".as_ref(), PointFormat::Columns(None)).unwrap_err();
//! assert_eq!(e.to_string(), "p.txt:2: 3 columns, but the first row has 2 (ragged rows)");
//! ```
use std::io::BufRead;
use std::path::Path;

use super::{IoError, IoErrorKind, Location, PolygonMode, ReadOptions};

/// Points with `dim` coordinates each, flat.
///
/// ```
/// use starplex::io::points::PointCloud;
/// let p = PointCloud { dim: 2, coords: vec![0.0, 1.0, 2.0, 3.0] };
/// assert_eq!(p.len(), 2);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PointCloud {
    /// Coordinates per point.
    pub dim: usize,
    /// Flat coordinates.
    pub coords: Vec<f64>,
}

impl PointCloud {
    /// Number of points.
    ///
    /// ```
    /// # use starplex::io::points::PointCloud;
    /// assert!(PointCloud { dim: 3, coords: vec![] }.is_empty());
    /// ```
    pub fn len(&self) -> usize {
        self.coords.len() / self.dim.max(1)
    }

    /// True without points.
    ///
    /// ```
    /// # use starplex::io::points::PointCloud;
    /// assert_eq!(PointCloud { dim: 3, coords: vec![] }.len(), 0);
    /// ```
    pub fn is_empty(&self) -> bool {
        self.coords.is_empty()
    }
}

/// How a text point file is laid out.
///
/// ```
/// use starplex::io::points::PointFormat;
/// assert_eq!(PointFormat::for_path("a.XYZ".as_ref()), Some(PointFormat::Columns(Some(3))));
/// assert_eq!(PointFormat::for_path("a.csv".as_ref()), Some(PointFormat::Csv));
/// assert_eq!(PointFormat::for_path("a.off".as_ref()), None); // a mesh: its vertices
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointFormat {
    /// Whitespace columns; `Some(k)`: the first k are the coordinates.
    Columns(Option<usize>),
    /// Comma-separated, optional header.
    Csv,
    /// NumPy `.npy`.
    Npy,
}

impl PointFormat {
    /// The layout named by the extension (`None`: read the file as a mesh).
    ///
    /// ```
    /// use starplex::io::points::PointFormat;
    /// assert_eq!(PointFormat::for_path("a.npy".as_ref()), Some(PointFormat::Npy));
    /// ```
    pub fn for_path(path: &Path) -> Option<PointFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "xyz" => Some(PointFormat::Columns(Some(3))),
            "txt" | "pts" | "dat" | "asc" => Some(PointFormat::Columns(None)),
            "csv" => Some(PointFormat::Csv),
            "npy" => Some(PointFormat::Npy),
            _ => None,
        }
    }
}

/// Reads a point cloud, choosing the layout by extension (meshes: their vertices).
///
/// ```
/// use starplex::io::points::read_points;
/// let path = std::env::temp_dir().join(format!("starplex-doc-points-{}.csv", std::process::id()));
/// std::fs::write(&path, "x,y\n0,0\n1,0.5\n").unwrap();
/// let p = read_points(&path).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(p.coords, vec![0.0, 0.0, 1.0, 0.5]);
/// ```
///
/// # Errors
/// OS errors; bad numbers, ragged rows (naming the line); non-finite coordinates; unknown
/// formats.
pub fn read_points(path: &Path) -> Result<PointCloud, IoError> {
    match PointFormat::for_path(path) {
        Some(PointFormat::Npy) => read_npy(path),
        Some(f) => {
            let file = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
            read_points_from(std::io::BufReader::with_capacity(1 << 20, file), path, f)
        }
        None => {
            let opts = ReadOptions {
                polygons: PolygonMode::Simplices,
                ..Default::default()
            };
            let r = super::read(path, &opts)?;
            let k = r.complex;
            Ok(PointCloud {
                dim: k.ambient_dim(),
                coords: k.coords().to_vec(),
            })
        }
    }
}

/// Reads a text point cloud from a stream (`path` names it in errors).
///
/// ```
/// use starplex::io::points::{read_points_from, PointFormat};
/// let p = read_points_from("a,b,c\n1,2,3\n".as_bytes(), "p.csv".as_ref(), PointFormat::Csv).unwrap();
/// assert_eq!((p.dim, p.len()), (3, 1));
/// let e = read_points_from("1 2\n1 nan\n".as_bytes(), "p.txt".as_ref(), PointFormat::Columns(None)).unwrap_err();
/// assert_eq!(e.to_string(), "p.txt:2: coordinate 2 is not a finite number ('nan')");
/// ```
///
/// # Errors
/// As [`read_points`].
pub fn read_points_from(
    r: impl BufRead,
    path: &Path,
    format: PointFormat,
) -> Result<PointCloud, IoError> {
    let (sep, take) = match format {
        PointFormat::Columns(t) => (None, t),
        PointFormat::Csv => (Some(','), None),
        PointFormat::Npy => {
            return Err(IoError::parse(
                path,
                None,
                "a .npy file is binary: read it with read_points",
            ))
        }
    };
    let mut coords = Vec::new();
    let mut dim: Option<usize> = None;
    let mut first_data = true;
    for (i, line) in r.lines().enumerate() {
        let line_no = i as u64 + 1;
        let line = line.map_err(|e| IoError::new(path, e).at(Location::Line(line_no)))?;
        let body = line.split('#').next().unwrap_or("").trim();
        if body.is_empty() {
            continue;
        }
        let fields: Vec<&str> = match sep {
            Some(c) => body.split(c).map(str::trim).collect(),
            None => body.split_ascii_whitespace().collect(),
        };
        let at = |msg: String| IoError::parse(path, Some(Location::Line(line_no)), msg);
        // a CSV header: the first line, when its first field is not a number
        if first_data && sep.is_some() && fields[0].parse::<f64>().is_err() {
            first_data = false;
            continue;
        }
        first_data = false;
        let n = match take {
            Some(k) if fields.len() < k => {
                return Err(at(format!(
                    "{} columns, expected at least {k}",
                    fields.len()
                )))
            }
            Some(k) => k,
            None => fields.len(),
        };
        match dim {
            None => dim = Some(n),
            Some(d) if take.is_none() && d != fields.len() => {
                return Err(at(format!(
                    "{} columns, but the first row has {d} (ragged rows)",
                    fields.len()
                )))
            }
            _ => {}
        }
        for (c, f) in fields[..n].iter().enumerate() {
            let x: f64 = f
                .parse()
                .map_err(|_| at(format!("coordinate {}: '{f}' is not a number", c + 1)))?;
            if !x.is_finite() {
                return Err(at(format!(
                    "coordinate {} is not a finite number ('{f}')",
                    c + 1
                )));
            }
            coords.push(x);
        }
    }
    let dim = dim.unwrap_or(0);
    if dim == 0 {
        return Err(IoError::parse(path, None, "no points"));
    }
    if dim > crate::complex::MAX_AMBIENT_DIM {
        return Err(IoError::new(
            path,
            crate::complex::ComplexError::BadAmbientDim(dim),
        ));
    }
    Ok(PointCloud { dim, coords })
}

/// Reads a NumPy array of float64, float32, int64 or int32 (C or Fortran order): its shape and
/// its values in row-major (C) order, as `f64`. The one `.npy` reader of point clouds and
/// distance matrices; values are not checked (the callers do).
///
/// ```no_run
/// let (shape, values) = starplex::io::points::read_npy_array("d.npy".as_ref()).unwrap();
/// assert_eq!(values.len(), shape.iter().product::<usize>());
/// ```
///
/// # Errors
/// OS errors, a malformed header, an unsupported element type, a value count that does not fit
/// the shape.
pub fn read_npy_array(path: &Path) -> Result<(Vec<usize>, Vec<f64>), IoError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::new(path, e))?;
    let bad = |m: String| IoError::parse(path, None, m);
    let npy = npyz::NpyFile::new(&bytes[..]).map_err(|e| bad(format!("not a .npy file: {e}")))?;
    let shape: Vec<usize> = npy.shape().iter().map(|&x| x as usize).collect();
    let fortran = npy.order() == npyz::Order::Fortran;
    let type_str = match npy.dtype() {
        npyz::DType::Plain(t) => t.to_string(),
        other => return Err(bad(format!("unsupported element type {other:?}"))),
    };
    let e = |e: std::io::Error| bad(e.to_string());
    let flat: Vec<f64> = match &type_str[1..] {
        "f8" => npy.into_vec::<f64>().map_err(e)?,
        "f4" => npy
            .into_vec::<f32>()
            .map_err(e)?
            .into_iter()
            .map(f64::from)
            .collect(),
        "i8" => npy
            .into_vec::<i64>()
            .map_err(e)?
            .into_iter()
            .map(|x| x as f64)
            .collect(),
        "i4" => npy
            .into_vec::<i32>()
            .map_err(e)?
            .into_iter()
            .map(f64::from)
            .collect(),
        _ => {
            return Err(bad(format!(
                "unsupported element type {type_str} (use float64, float32, int64 or int32)"
            )))
        }
    };
    if flat.len() != shape.iter().product::<usize>() {
        return Err(bad(format!("{} values for shape {shape:?}", flat.len())));
    }
    // Fortran order of a 2-D array: column after column; transpose to rows
    let values = match (fortran, &shape[..]) {
        (true, &[rows, cols]) => {
            let mut c = vec![0.0; flat.len()];
            for j in 0..cols {
                for i in 0..rows {
                    c[i * cols + j] = flat[j * rows + i];
                }
            }
            c
        }
        _ => flat,
    };
    Ok((shape, values))
}

/// Reads a 2-D NumPy array (float64, float32 or integers; C or Fortran order), one point per
/// row.
///
/// ```no_run
/// let p = starplex::io::points::read_npy("points.npy".as_ref()).unwrap();
/// ```
///
/// # Errors
/// OS errors, a malformed header, a shape that is not 2-D, an unsupported element type,
/// non-finite values.
pub fn read_npy(path: &Path) -> Result<PointCloud, IoError> {
    let bad = |m: String| IoError::parse(path, None, m);
    let (shape, coords) = read_npy_array(path)?;
    let cols = match shape[..] {
        [_, c] => c,
        [_] => 1,
        _ => {
            return Err(bad(format!(
                "expected a 2-D array (points x coordinates), got shape {shape:?}"
            )))
        }
    };
    if let Some(i) = coords.iter().position(|x| !x.is_finite()) {
        return Err(bad(format!(
            "row {} column {} is not finite ({})",
            i / cols,
            i % cols,
            coords[i]
        )));
    }
    if cols == 0 || cols > crate::complex::MAX_AMBIENT_DIM {
        return Err(IoError::new(
            path,
            crate::complex::ComplexError::BadAmbientDim(cols),
        ));
    }
    Ok(PointCloud { dim: cols, coords })
}

/// An edge list: the edges in file order and the number of vertices (largest id + 1).
///
/// ```
/// use starplex::io::points::EdgeList;
/// let e = EdgeList { edges: vec![(0, 2)], n_vertices: 3 };
/// assert_eq!(e.edges.len(), 1);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EdgeList {
    /// Edges in file order.
    pub edges: Vec<(u32, u32)>,
    /// Largest id + 1 (or the count given).
    pub n_vertices: usize,
}

/// Reads an edge list: two non-negative integer ids per line (whitespace or commas; further
/// columns ignored), `#`/`%` comments, an optional header line in CSV files. With
/// `n_vertices`, ids must be below it; self-loops are errors naming the line.
///
/// ```
/// use starplex::io::points::read_edges_from;
/// let e = read_edges_from("% graph\n0 1\n1 2 0.5\n".as_bytes(), "g.txt".as_ref(), None).unwrap();
/// assert_eq!((e.edges, e.n_vertices), (vec![(0, 1), (1, 2)], 3));
/// let e = read_edges_from("0 1\n3 3\n".as_bytes(), "g.txt".as_ref(), None).unwrap_err();
/// assert_eq!(e.to_string(), "g.txt:2: self-loop at vertex 3 (an edge needs two distinct vertices)");
/// let e = read_edges_from("0 7\n".as_bytes(), "g.txt".as_ref(), Some(5)).unwrap_err();
/// assert_eq!(e.to_string(), "g.txt:1: vertex id 7 out of range (5 vertices, ids 0..4)");
/// ```
///
/// # Errors
/// OS errors; a line without two ids, an id that is not a non-negative integer below 2^32 - 1,
/// a self-loop, an id out of range.
pub fn read_edges_from(
    r: impl BufRead,
    path: &Path,
    n_vertices: Option<usize>,
) -> Result<EdgeList, IoError> {
    let mut edges = Vec::new();
    let mut max_id: Option<u32> = None;
    let mut first = true;
    for (i, line) in r.lines().enumerate() {
        let line_no = i as u64 + 1;
        let line = line.map_err(|e| IoError::new(path, e).at(Location::Line(line_no)))?;
        let body = line.split(['#', '%']).next().unwrap_or("").trim();
        if body.is_empty() {
            continue;
        }
        let at = |msg: String| IoError::parse(path, Some(Location::Line(line_no)), msg);
        let mut it = body
            .split(|c: char| c == ',' || c.is_ascii_whitespace())
            .filter(|s| !s.is_empty());
        let (a, b) = (it.next(), it.next());
        let is_header = first && a.is_some_and(|s| s.parse::<f64>().is_err());
        first = false;
        if is_header {
            continue;
        }
        let (Some(a), Some(b)) = (a, b) else {
            return Err(at("expected two vertex ids".into()));
        };
        let id = |s: &str| -> Result<u32, IoError> {
            match s.parse::<u64>() {
                Ok(v) if v < u32::MAX as u64 - 1 => {
                    if let Some(n) = n_vertices
                        && v as usize >= n
                    {
                        return Err(at(format!(
                            "vertex id {v} out of range ({n} vertices, ids 0..{})",
                            n.saturating_sub(1)
                        )));
                    }
                    Ok(v as u32)
                }
                Ok(v) => Err(at(format!("vertex id {v} is too large (32-bit ids)"))),
                Err(_) => Err(at(format!(
                    "'{s}' is not a vertex id (a non-negative integer)"
                ))),
            }
        };
        let (a, b) = (id(a)?, id(b)?);
        if a == b {
            return Err(at(format!(
                "self-loop at vertex {a} (an edge needs two distinct vertices)"
            )));
        }
        max_id = Some(max_id.unwrap_or(0).max(a).max(b));
        edges.push((a, b));
    }
    let n = match n_vertices {
        Some(n) => n,
        None => max_id.map_or(0, |m| m as usize + 1),
    };
    Ok(EdgeList {
        edges,
        n_vertices: n,
    })
}

/// Reads an edge list file (see [`read_edges_from`]).
///
/// ```
/// use starplex::io::points::read_edges;
/// let path = std::env::temp_dir().join(format!("starplex-doc-edges-{}.csv", std::process::id()));
/// std::fs::write(&path, "source,target\n0,1\n1,2\n").unwrap();
/// let e = read_edges(&path, None).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(e.n_vertices, 3);
/// ```
///
/// # Errors
/// As [`read_edges_from`].
pub fn read_edges(path: &Path, n_vertices: Option<usize>) -> Result<EdgeList, IoError> {
    let file = std::fs::File::open(path).map_err(|e| IoError::new(path, IoErrorKind::Os(e)))?;
    read_edges_from(
        std::io::BufReader::with_capacity(1 << 20, file),
        path,
        n_vertices,
    )
}
