//! Shared by tests, doc examples and benchmarks: a seeded generator and small named complexes.
//! Not part of the stable interface; it exists so that every test draws from one generator and
//! the same fixtures instead of each file growing its own.
//!
//! ```
//! use starplex::testkit::{fixture, XorShift};
//! let mut r = XorShift::new(7);
//! let x = r.below(10);
//! assert!(x < 10);
//! assert_eq!(XorShift::new(7).below(10), x); // seeded: the same sequence every run
//! let book = fixture::book();
//! assert_eq!((book.n_vertices(), book.n_cells()), (5, 3));
//! ```

/// Marsaglia's xorshift64 generator (13, 7, 17): fast, seeded, reproducible; for tests only.
///
/// ```
/// use starplex::testkit::XorShift;
/// let mut r = XorShift::new(1);
/// let a = r.next_u64();
/// assert_ne!(a, r.next_u64());
/// ```
#[derive(Clone, Debug)]
pub struct XorShift(u64);

impl XorShift {
    /// A generator from a seed (a zero seed is replaced, since zero is a fixed point).
    ///
    /// ```
    /// use starplex::testkit::XorShift;
    /// assert_ne!(XorShift::new(0).next_u64(), 0);
    /// ```
    pub fn new(seed: u64) -> XorShift {
        XorShift(if seed == 0 {
            0x9E37_79B9_7F4A_7C15
        } else {
            seed
        })
    }
    /// The next 64 random bits.
    ///
    /// ```
    /// use starplex::testkit::XorShift;
    /// assert_eq!(XorShift::new(12345).next_u64(), XorShift::new(12345).next_u64());
    /// ```
    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }
    /// A value in `0..m` (`m > 0`; modulo bias is irrelevant for tests).
    ///
    /// ```
    /// use starplex::testkit::XorShift;
    /// let mut r = XorShift::new(3);
    /// assert!((0..100).all(|_| r.below(6) < 6));
    /// ```
    pub fn below(&mut self, m: u64) -> u64 {
        self.next_u64() % m
    }
}

/// Small named complexes that the tests and examples talk about.
pub mod fixture {
    use crate::cell::CellKind;
    use crate::complex::{BuildOptions, ComplexBuilder, IndexedComplex};

    fn build(ambient: usize, points: &[&[f64]], cells: &[(CellKind, &[u32])]) -> IndexedComplex {
        let mut b = ComplexBuilder::new(ambient).expect("ambient dimension of a fixture");
        for p in points {
            b.push_vertex(p).expect("a fixture's point");
        }
        for (k, c) in cells {
            b.push_cell(*k, c).expect("a fixture's cell");
        }
        b.build(&BuildOptions::default()).expect("a fixture").0
    }

    /// The triangles 0-1-2 and 1-3-2 of the unit square, sharing the edge 1-2.
    ///
    /// ```
    /// let k = starplex::testkit::fixture::two_triangles();
    /// assert_eq!((k.n_vertices(), k.n_cells()), (4, 2));
    /// ```
    pub fn two_triangles() -> IndexedComplex {
        let t = CellKind::Simplex(2);
        build(
            2,
            &[&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], &[1.0, 1.0]],
            &[(t, &[0, 1, 2]), (t, &[1, 3, 2])],
        )
    }

    /// The "book": three triangles 0-1-2, 0-1-3, 0-1-4 on the non-manifold edge 0-1.
    ///
    /// ```
    /// let k = starplex::testkit::fixture::book();
    /// assert_eq!(k.n_cells(), 3);
    /// ```
    pub fn book() -> IndexedComplex {
        let t = CellKind::Simplex(2);
        build(
            3,
            &[
                &[0.0, 0.0, 0.0],
                &[1.0, 0.0, 0.0],
                &[0.0, 1.0, 0.0],
                &[0.0, 0.0, 1.0],
                &[0.0, -1.0, 0.0],
            ],
            &[(t, &[0, 1, 2]), (t, &[0, 1, 3]), (t, &[0, 1, 4])],
        )
    }

    /// The bowtie: triangles 0-1-2 and 0-3-4 meeting at the non-manifold vertex 0 only.
    ///
    /// ```
    /// let k = starplex::testkit::fixture::bowtie();
    /// assert_eq!((k.n_vertices(), k.n_cells()), (5, 2));
    /// ```
    pub fn bowtie() -> IndexedComplex {
        let t = CellKind::Simplex(2);
        build(
            2,
            &[
                &[0.0, 0.0],
                &[1.0, 0.5],
                &[1.0, -0.5],
                &[-1.0, 0.5],
                &[-1.0, -0.5],
            ],
            &[(t, &[0, 1, 2]), (t, &[0, 3, 4])],
        )
    }
}
