//! Generated complexes for tests, benchmarks and scale runs: the Freudenthal (Kuhn)
//! triangulation of a regular grid in any dimension. A grid of `n_1 x ... x n_d` unit cubes
//! becomes `d! * n_1 * ... * n_d` d-simplices: cube corner `c` and a permutation `π` of the axes
//! give the simplex `c, c + e_π(0), c + e_π(0) + e_π(1), ...`; the simplices of neighbouring
//! cubes match face to face, so the result is a pure, manifold, orientable d-ball (Euler
//! characteristic 1). `kuhn_grid(&[203, 203, 203])` has 50.2 million tetrahedra.
//!
//! The arrays are written directly (no per-cell checks beyond [`IndexedComplex::from_parts`]'s
//! range and repeat check), so a 50-million-tetrahedron grid costs its 800 MB of cells and
//! 200 MB of coordinates and nothing more.
//!
//! ```
//! use starplex::algo::info::{info, InfoOptions};
//! let k = starplex::generate::kuhn_grid(&[2, 3]).unwrap();
//! assert_eq!((k.n_vertices(), k.n_cells()), (12, 12));
//! let s = info(&k, &InfoOptions::default());
//! assert_eq!(s.euler_characteristic, Some(1));
//! assert_eq!(s.n_boundary_faces, Some(10)); // the perimeter: 2 * (2 + 3) edges
//! ```
use crate::cell::CellKind;
use crate::complex::{ComplexError, IndexedComplex, MAX_AMBIENT_DIM};

pub mod refine;
pub mod sierpinski;

/// The Freudenthal triangulation of a grid of `cubes[0] x cubes[1] x ...` unit cubes (vertex
/// coordinates are the integer grid points; vertex ids run with the first axis fastest).
///
/// # Errors
/// [`ComplexError::BadAmbientDim`] for no axis or more than 8 (8! = 40320 simplices per cube);
/// [`ComplexError::TooLarge`] when the vertex or cell count does not fit the 32-bit ids, or the
/// arrays would not fit in memory (checked before allocating).
///
/// ```
/// let k = starplex::generate::kuhn_grid(&[1, 1, 1]).unwrap();
/// assert_eq!((k.n_vertices(), k.n_cells()), (8, 6)); // a cube into 6 tetrahedra
/// assert!(starplex::generate::kuhn_grid(&[100_000, 100_000, 100_000]).is_err());
/// ```
pub fn kuhn_grid(cubes: &[usize]) -> Result<IndexedComplex, ComplexError> {
    let d = cubes.len();
    if d == 0 || d > 8 || d > MAX_AMBIENT_DIM {
        return Err(ComplexError::BadAmbientDim(d));
    }
    let too_large = |what: &'static str, count: u128| {
        ComplexError::TooLarge(crate::limits::TooLarge::ids(what, count))
    };
    let nv: u128 = cubes.iter().map(|&n| n as u128 + 1).product();
    if nv >= u32::MAX as u128 {
        return Err(too_large("vertices", nv));
    }
    let fact: u128 = (1..=d as u128).product();
    let nc: u128 = fact * cubes.iter().map(|&n| n as u128).product::<u128>();
    if nc >= u32::MAX as u128 {
        return Err(too_large("cells", nc));
    }
    let nv = nv as usize;
    // strides of the vertex numbering
    let mut stride = vec![1usize; d];
    for a in 1..d {
        stride[a] = stride[a - 1] * (cubes[a - 1] + 1);
    }
    let mut coords = Vec::with_capacity(nv * d);
    let mut p = vec![0usize; d];
    for _ in 0..nv {
        coords.extend(p.iter().map(|&x| x as f64));
        for a in 0..d {
            p[a] += 1;
            if p[a] <= cubes[a] {
                break;
            }
            p[a] = 0;
        }
    }
    let perms = permutations(d);
    let mut cells: Vec<u32> = Vec::with_capacity(nc as usize * (d + 1));
    let n_cubes: usize = cubes.iter().product();
    let mut c = vec![0usize; d];
    for _ in 0..n_cubes {
        let base: usize = (0..d).map(|a| c[a] * stride[a]).sum();
        for perm in &perms {
            let mut v = base;
            cells.push(v as u32);
            for &a in perm {
                v += stride[a];
                cells.push(v as u32);
            }
        }
        for a in 0..d {
            c[a] += 1;
            if c[a] < cubes[a] {
                break;
            }
            c[a] = 0;
        }
    }
    IndexedComplex::from_parts(
        d,
        coords.into(),
        vec![(CellKind::Simplex(d as u8), cells.into())],
    )
}

/// Every permutation of `0..d`, in lexicographic order.
fn permutations(d: usize) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut cur: Vec<usize> = (0..d).collect();
    loop {
        out.push(cur.clone());
        // next permutation
        let Some(i) = (0..d.saturating_sub(1))
            .rev()
            .find(|&i| cur[i] < cur[i + 1])
        else {
            return out;
        };
        let j = (i + 1..d).rev().find(|&j| cur[j] > cur[i]).unwrap_or(i);
        cur.swap(i, j);
        cur[i + 1..].reverse();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algo::info::{info, InfoOptions};

    #[test]
    fn grids_are_balls_with_the_right_counts() {
        for dims in [
            vec![3],
            vec![2, 2],
            vec![3, 1, 2],
            vec![1, 1, 1, 1],
            vec![2, 1, 1, 1],
        ] {
            let k = kuhn_grid(&dims).unwrap();
            let d = dims.len();
            let fact: usize = (1..=d).product();
            assert_eq!(k.n_cells(), fact * dims.iter().product::<usize>());
            let s = info(&k, &InfoOptions::default());
            assert_eq!(s.euler_characteristic, Some(1), "{dims:?}");
            assert_eq!(s.n_connected_components, 1, "{dims:?}");
            assert_eq!(
                s.n_faces_shared_by_more_than_2_top_cells,
                Some(0),
                "{dims:?}"
            );
            assert!(s.pure);
        }
        assert_eq!(permutations(3).len(), 6);
        assert!(kuhn_grid(&[]).is_err());
        assert!(kuhn_grid(&[1; 9]).is_err());
    }
}
