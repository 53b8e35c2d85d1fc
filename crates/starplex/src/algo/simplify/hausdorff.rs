//! A sampled estimate of the Hausdorff distance between two surfaces (a simplified mesh and its
//! input): each one-sided distance is the largest distance from a *vertex* of one surface to the
//! closest *triangle* of the other (exact point–triangle distances, found with a bounding-volume
//! hierarchy over the triangles). It is an estimate from below of the true one-sided distance,
//! which may be reached inside a triangle rather than at a vertex; the mean over the vertices
//! is reported too.
//!
//! The surface of a triangle mesh is its triangles; the surface of a tetrahedral mesh is its
//! boundary triangles (and the samples are the vertices on it). Points of 2 coordinates are
//! taken in the plane z = 0.
//!
//! ```
//! use starplex::algo::simplify::hausdorff::hausdorff_estimate;
//! use starplex::generate::kuhn_grid;
//! let a = kuhn_grid(&[4, 4, 4]).unwrap(); // a cube of tetrahedra: its surface is the cube's
//! let b = kuhn_grid(&[1, 1, 1]).unwrap(); // the same cube, 6 tetrahedra
//! # let b = { let mut b = b; b.set_coords(b.coords().iter().map(|x| x * 4.0).collect()).unwrap(); b };
//! let h = hausdorff_estimate(&a, &b).unwrap();
//! assert!(h.max() < 1e-12);
//! assert_eq!(h.n_samples, [98, 8]); // the surface vertices of each
//! ```
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use crate::complex::IndexedComplex;

/// The two one-sided estimates (see the module docs).
///
/// ```
/// let h = starplex::algo::simplify::hausdorff::HausdorffEstimate::default();
/// assert_eq!(h.max(), 0.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HausdorffEstimate {
    /// Largest distance from a vertex of the first surface to the second surface.
    pub a_to_b: f64,
    /// Largest distance from a vertex of the second surface to the first surface.
    pub b_to_a: f64,
    /// Mean distance from the vertices of the first surface to the second.
    pub mean_a_to_b: f64,
    /// Mean distance from the vertices of the second surface to the first.
    pub mean_b_to_a: f64,
    /// Vertices sampled on each surface.
    pub n_samples: [usize; 2],
    /// Length of the diagonal of the first surface's bounding box (to read the distances
    /// relative to the size of the mesh).
    pub diagonal: f64,
}

impl HausdorffEstimate {
    /// The symmetric estimate: the larger one-sided one.
    ///
    /// ```
    /// use starplex::algo::simplify::hausdorff::HausdorffEstimate;
    /// let h = HausdorffEstimate { a_to_b: 1.0, b_to_a: 2.0, ..Default::default() };
    /// assert_eq!(h.max(), 2.0);
    /// ```
    pub fn max(&self) -> f64 {
        self.a_to_b.max(self.b_to_a)
    }
}

/// The surface triangles of a complex: every triangle of a pure triangle mesh, or the boundary
/// triangles of a pure tetrahedral mesh (each in exactly one tetrahedron), with 2 or 3
/// coordinates; `None` for anything else.
///
/// ```
/// use starplex::algo::simplify::hausdorff::surface_triangles;
/// use starplex::generate::kuhn_grid;
/// assert_eq!(surface_triangles(&kuhn_grid(&[1, 1, 1]).unwrap()).unwrap().len(), 12);
/// assert_eq!(surface_triangles(&kuhn_grid(&[2, 2]).unwrap()).unwrap().len(), 8);
/// assert!(surface_triangles(&kuhn_grid(&[1]).unwrap()).is_none()); // edges
/// ```
pub fn surface_triangles(k: &IndexedComplex) -> Option<Vec<[u32; 3]>> {
    if !(2..=3).contains(&k.ambient_dim()) || k.n_cells() == 0 || !k.is_simplicial() {
        return None;
    }
    let d = k.dim()?;
    if k.cells().any(|c| c.vertices.len() != d + 1) {
        return None;
    }
    match d {
        2 => Some(
            k.cells()
                .map(|c| [c.vertices[0], c.vertices[1], c.vertices[2]])
                .collect(),
        ),
        3 => {
            let mut count: FxHashMap<[u32; 3], u32> = FxHashMap::default();
            for c in k.cells() {
                let t = c.vertices;
                for skip in 0..4 {
                    let mut f = [0u32; 3];
                    let mut j = 0;
                    for (i, &v) in t.iter().enumerate() {
                        if i != skip {
                            f[j] = v;
                            j += 1;
                        }
                    }
                    f.sort_unstable();
                    *count.entry(f).or_insert(0) += 1;
                }
            }
            let mut out: Vec<[u32; 3]> = count
                .into_iter()
                .filter(|&(_, c)| c == 1)
                .map(|(f, _)| f)
                .collect();
            out.sort_unstable();
            Some(out)
        }
        _ => None,
    }
}

/// Estimates the Hausdorff distance between the surfaces of `a` and `b` (see the module docs);
/// `None` when either is not a triangle or tetrahedral mesh ([`surface_triangles`]) or has no
/// surface. The queries run on the current rayon pool; the answer does not depend on it.
///
/// ```
/// use starplex::algo::simplify::hausdorff::hausdorff_estimate;
/// use starplex::generate::kuhn_grid;
/// let a = kuhn_grid(&[2, 2]).unwrap();
/// let mut b = a.clone();
/// b.set_coords(a.coords().iter().map(|x| x * 1.5).collect()).unwrap(); // 3x3 instead of 2x2
/// let h = hausdorff_estimate(&a, &b).unwrap();
/// assert!(h.a_to_b < 1e-12); // the small square lies in the big one
/// assert!((h.b_to_a - 2f64.sqrt()).abs() < 1e-12); // the far corner (3, 3) is √2 from (2, 2)
/// ```
pub fn hausdorff_estimate(a: &IndexedComplex, b: &IndexedComplex) -> Option<HausdorffEstimate> {
    let (ta, tb) = (surface_triangles(a)?, surface_triangles(b)?);
    if ta.is_empty() || tb.is_empty() {
        return None;
    }
    let (pa, pb) = (points3(a), points3(b));
    let (ba, bb) = (Bvh::new(&pa, &ta), Bvh::new(&pb, &tb));
    let one_way = |p: &[[f64; 3]], tris: &[[u32; 3]], bvh: &Bvh| {
        let mut used = vec![false; p.len()];
        for t in tris {
            for &v in t {
                used[v as usize] = true;
            }
        }
        let samples: Vec<[f64; 3]> = p
            .iter()
            .zip(&used)
            .filter(|(_, u)| **u)
            .map(|(x, _)| *x)
            .collect();
        let d: Vec<f64> = samples
            .par_iter()
            .with_min_len(1024)
            .map(|q| bvh.nearest(*q).sqrt())
            .collect();
        let max = d.iter().fold(0.0f64, |m, &x| m.max(x));
        let mean = d.iter().sum::<f64>() / d.len().max(1) as f64;
        (max, mean, d.len())
    };
    let (ab, mab, na) = one_way(&pa, &ta, &bb);
    let (ba_, mba, nb) = one_way(&pb, &tb, &ba);
    let (lo, hi) = ba.nodes[0].bounds;
    Some(HausdorffEstimate {
        a_to_b: ab,
        b_to_a: ba_,
        mean_a_to_b: mab,
        mean_b_to_a: mba,
        n_samples: [na, nb],
        diagonal: dot(sub(hi, lo), sub(hi, lo)).sqrt(),
    })
}

fn points3(k: &IndexedComplex) -> Vec<[f64; 3]> {
    let s = k.ambient_dim();
    k.coords()
        .chunks_exact(s)
        .map(|p| [p[0], p[1], p.get(2).copied().unwrap_or(0.0)])
        .collect()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn add_scaled(a: [f64; 3], u: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] + s * u[0], a[1] + s * u[1], a[2] + s * u[2]]
}
fn dist2(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d)
}

/// Squared distance from `p` to the segment `ab`.
fn segment_dist2(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = sub(b, a);
    let l = dot(ab, ab);
    let t = if l > 0.0 {
        (dot(sub(p, a), ab) / l).clamp(0.0, 1.0)
    } else {
        0.0
    };
    dist2(p, add_scaled(a, ab, t))
}

/// Squared distance from `p` to the triangle `abc` (Ericson, Real-Time Collision Detection
/// 5.1.5; degenerate triangles by their sides).
pub fn triangle_dist2(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return dist2(p, a);
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return dist2(p, b);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return segment_dist2(p, a, b);
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return dist2(p, c);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return segment_dist2(p, a, c);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return segment_dist2(p, b, c);
    }
    let denom = va + vb + vc;
    let q = add_scaled(add_scaled(a, ab, vb / denom), ac, vc / denom);
    let d = dist2(p, q);
    if d.is_finite() {
        d
    } else {
        segment_dist2(p, a, b)
            .min(segment_dist2(p, b, c))
            .min(segment_dist2(p, a, c))
    }
}

struct Node {
    bounds: ([f64; 3], [f64; 3]),
    /// Leaf: `(first, count)` into `order`; inner: `(left child, 0)`, the right child follows
    /// the left subtree at `right`.
    first: u32,
    count: u32,
    right: u32,
}

/// A bounding-volume hierarchy over triangles, for nearest-triangle queries.
struct Bvh {
    nodes: Vec<Node>,
    tris: Vec<[[f64; 3]; 3]>,
}

const LEAF: usize = 4;

impl Bvh {
    fn new(p: &[[f64; 3]], tris: &[[u32; 3]]) -> Bvh {
        let mut t: Vec<[[f64; 3]; 3]> = tris.iter().map(|t| t.map(|v| p[v as usize])).collect();
        let mut nodes = Vec::with_capacity(2 * t.len() / LEAF + 1);
        Self::build(&mut nodes, &mut t, 0);
        Bvh { nodes, tris: t }
    }

    fn bounds(t: &[[[f64; 3]; 3]]) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for tri in t {
            for p in tri {
                for i in 0..3 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
        }
        (lo, hi)
    }

    fn build(nodes: &mut Vec<Node>, t: &mut [[[f64; 3]; 3]], first: usize) -> u32 {
        let id = nodes.len();
        let bounds = Self::bounds(t);
        nodes.push(Node {
            bounds,
            first: first as u32,
            count: t.len() as u32,
            right: 0,
        });
        if t.len() <= LEAF {
            return id as u32;
        }
        let (lo, hi) = bounds;
        let axis = (0..3)
            .max_by(|&i, &j| (hi[i] - lo[i]).total_cmp(&(hi[j] - lo[j])))
            .unwrap_or(0);
        let key = |x: &[[f64; 3]; 3]| x[0][axis] + x[1][axis] + x[2][axis];
        let mid = t.len() / 2;
        t.select_nth_unstable_by(mid, |x, y| key(x).total_cmp(&key(y)));
        let (l, r) = t.split_at_mut(mid);
        Self::build(nodes, l, first);
        let right = Self::build(nodes, r, first + mid);
        nodes[id].count = 0;
        nodes[id].right = right;
        id as u32
    }

    fn box_dist2(b: &([f64; 3], [f64; 3]), p: [f64; 3]) -> f64 {
        let mut d = 0.0;
        for ((lo, hi), x) in b.0.iter().zip(&b.1).zip(&p) {
            let e = (lo - x).max(0.0).max(x - hi);
            d += e * e;
        }
        d
    }

    /// Squared distance from `p` to the closest triangle.
    fn nearest(&self, p: [f64; 3]) -> f64 {
        let mut best = f64::INFINITY;
        let mut stack: Vec<(f64, u32)> = vec![(0.0, 0)];
        while let Some((d, n)) = stack.pop() {
            if d >= best {
                continue;
            }
            let node = &self.nodes[n as usize];
            if node.count > 0 {
                let f = node.first as usize;
                for t in &self.tris[f..f + node.count as usize] {
                    best = best.min(triangle_dist2(p, t[0], t[1], t[2]));
                }
                continue;
            }
            let (l, r) = (n + 1, node.right);
            let dl = Self::box_dist2(&self.nodes[l as usize].bounds, p);
            let dr = Self::box_dist2(&self.nodes[r as usize].bounds, p);
            // the nearer child is popped first
            if dl <= dr {
                stack.push((dr, r));
                stack.push((dl, l));
            } else {
                stack.push((dl, l));
                stack.push((dr, r));
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bvh_matches_brute_force() {
        // a seeded cloud of small triangles and query points
        let mut rng = crate::testkit::XorShift::new(0x2545f4914f6cdd1d);
        let mut rnd = || {
            let s = rng.next_u64();
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut p = Vec::new();
        let mut tris = Vec::new();
        for i in 0..500u32 {
            let c = [rnd() * 10.0, rnd() * 10.0, rnd() * 2.0];
            for _ in 0..3 {
                p.push([c[0] + rnd(), c[1] + rnd(), c[2] + rnd()]);
            }
            tris.push([3 * i, 3 * i + 1, 3 * i + 2]);
        }
        // a degenerate one (three collinear points)
        p.extend([[0.0, 0.0, 5.0], [1.0, 0.0, 5.0], [2.0, 0.0, 5.0]]);
        tris.push([1500, 1501, 1502]);
        let bvh = Bvh::new(&p, &tris);
        for _ in 0..300 {
            let q = [rnd() * 12.0 - 1.0, rnd() * 12.0 - 1.0, rnd() * 6.0 - 1.0];
            let brute = tris
                .iter()
                .map(|t| triangle_dist2(q, p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]))
                .fold(f64::INFINITY, f64::min);
            assert_eq!(bvh.nearest(q), brute);
        }
        // the degenerate triangle: distance to its segment
        let d = triangle_dist2([1.0, 1.0, 5.0], p[1500], p[1501], p[1502]);
        assert!((d - 1.0).abs() < 1e-12);
    }

    #[test]
    fn point_triangle_regions() {
        let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert_eq!(triangle_dist2([0.2, 0.2, 3.0], a, b, c), 9.0); // above the face
        assert_eq!(triangle_dist2([-1.0, -1.0, 0.0], a, b, c), 2.0); // vertex a
        assert_eq!(triangle_dist2([0.5, -2.0, 0.0], a, b, c), 4.0); // edge ab
        assert!((triangle_dist2([1.0, 1.0, 0.0], a, b, c) - 0.5).abs() < 1e-15);
        // edge bc
    }
}
