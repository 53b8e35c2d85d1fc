//! The discrete gradient: a greedy acyclic matching built independently in the lower star of
//! every vertex (Robins–Wood–Sheppard), with faces generated on the fly from the top cells of
//! the vertex's star, and the Morse boundary of a critical cell by following gradient paths.
//!
//! Every cell belongs to the lower star L(v) of its largest vertex v. Per vertex:
//! * `L(v) = {v}` (no incident cell has a smaller vertex): v is critical;
//! * the lower link is a *cone* (an apex `s` such that every lower simplex `S_c` of an incident
//!   simplicial top cell can be completed by `s` inside some `S_c'`): the perfect matching
//!   `v∪T ↔ v∪T∪{s}` is used without enumerating anything — a single 40-simplex is answered
//!   this way, as is every vertex of a Freudenthal grid;
//! * otherwise the lower star is enumerated and matched by elementary expansions (a pair is
//!   made only when the coface's other facets and the face's own facets are all classified;
//!   when none is possible the lowest-dimensional free cell becomes critical). Expansions keep
//!   the matching acyclic, and the classification time orders gradient paths.
use std::collections::{BTreeMap, BinaryHeap, VecDeque};

use smallvec::SmallVec;

use super::cells::{cp_lower_star_faces, Cell, Key};
use crate::ids::{CellId, VertexId};
use crate::topo::{TopCells, VertexStar};

/// `apex[v]` when L(v) = {v}.
pub(crate) const ALONE: u32 = u32::MAX;
/// `apex[v]` when L(v) is enumerated.
pub(crate) const EXPLICIT: u32 = u32::MAX - 1;

/// Scratch buffers of one worker.
#[derive(Default)]
pub(crate) struct Scratch {
    cells: Vec<CellId>,
    verts: Vec<VertexId>,
    /// Lower sets S_c, flat, with offsets.
    lower: Vec<u32>,
    starts: Vec<usize>,
}

/// What [`plan_vertex`] found.
pub(crate) struct VertexPlan {
    /// An apex, [`ALONE`] or [`EXPLICIT`].
    pub apex: u32,
    /// Cells of the lower star if enumerated (upper bound).
    pub estimate: u128,
}

fn is_subset(a: &[u32], b: &[u32]) -> bool {
    // both sorted
    let mut j = 0;
    for &x in a {
        while j < b.len() && b[j] < x {
            j += 1;
        }
        if j == b.len() || b[j] != x {
            return false;
        }
        j += 1;
    }
    true
}

/// Classifies the lower star of `v` (see the module docs) without enumerating it.
pub(crate) fn plan_vertex<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    v: u32,
    w: &mut Scratch,
) -> VertexPlan {
    s.vertex_top_cells(VertexId(v), &mut w.cells);
    if w.cells.is_empty() {
        return VertexPlan {
            apex: ALONE,
            estimate: 1,
        };
    }
    w.lower.clear();
    w.starts.clear();
    let mut all_simplices = true;
    let mut estimate: u128 = 0;
    let mut any_lower = false;
    for i in 0..w.cells.len() {
        let c = w.cells[i];
        let kind = s.top_cell_kind(c);
        w.verts.clear();
        s.top_cell_vertices(c, &mut w.verts);
        w.starts.push(w.lower.len());
        let start = w.lower.len();
        w.lower
            .extend(w.verts.iter().map(|x| x.0).filter(|&x| x < v));
        w.lower[start..].sort_unstable();
        let n = w.lower.len() - start;
        any_lower |= n > 0;
        if kind.is_simplex() {
            let e = if n >= 127 { u128::MAX } else { 1u128 << n };
            estimate = estimate.saturating_add(e);
        } else {
            all_simplices = false;
            estimate = estimate.saturating_add(27);
        }
    }
    w.starts.push(w.lower.len());
    if !any_lower {
        return VertexPlan {
            apex: ALONE,
            estimate: 1,
        };
    }
    if !all_simplices {
        return VertexPlan {
            apex: EXPLICIT,
            estimate,
        };
    }
    let m = w.cells.len();
    let set = |i: usize| &w.lower[w.starts[i]..w.starts[i + 1]];
    let best = (0..m)
        .max_by_key(|&i| (set(i).len(), usize::MAX - i))
        .unwrap_or(0);
    let mut with: Vec<usize> = Vec::with_capacity(m);
    let mut work = 0usize;
    'cand: for &cand in set(best) {
        // the cells whose lower set holds the candidate, largest first
        with.clear();
        with.extend((0..m).filter(|&j| set(j).contains(&cand)));
        with.sort_by_key(|&j| std::cmp::Reverse(set(j).len()));
        for i in 0..m {
            let si = set(i);
            if si.contains(&cand) {
                continue;
            }
            let found = with.iter().any(|&j| {
                work += 1;
                let sj = set(j);
                sj.len() > si.len() && is_subset(si, sj)
            });
            if work > 50_000 {
                break 'cand;
            }
            if !found {
                continue 'cand;
            }
        }
        return VertexPlan {
            apex: cand,
            estimate,
        };
    }
    VertexPlan {
        apex: EXPLICIT,
        estimate,
    }
}

/// Status of a cell in its lower star.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Status {
    Critical,
    /// Paired with a coface (index in the lower star).
    Up(u32),
    /// Paired with a face.
    Down(u32),
}

/// An enumerated and matched lower star.
pub(crate) struct LowerStar {
    /// Sorted by key.
    pub cells: Vec<Cell>,
    pub status: Vec<Status>,
    pub time: Vec<u32>,
}

impl LowerStar {
    pub fn find(&self, key: &[u32]) -> Option<usize> {
        self.cells
            .binary_search_by(|c| c.key.as_slice().cmp(key))
            .ok()
    }
}

/// Enumerates and matches L(v).
pub(crate) fn lower_star<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    v: u32,
    w: &mut Scratch,
) -> LowerStar {
    s.vertex_top_cells(VertexId(v), &mut w.cells);
    let mut cells: Vec<Cell> = Vec::new();
    let mut lower: Vec<u32> = Vec::new();
    for i in 0..w.cells.len() {
        let c = w.cells[i];
        let kind = s.top_cell_kind(c);
        w.verts.clear();
        s.top_cell_vertices(c, &mut w.verts);
        if kind.is_simplex() {
            lower.clear();
            lower.extend(w.verts.iter().map(|x| x.0).filter(|&x| x < v));
            lower.sort_unstable();
            let n = lower.len();
            for mask in 0u64..(1u64 << n) {
                let mut key: Key = SmallVec::new();
                for (b, &x) in lower.iter().enumerate() {
                    if mask >> b & 1 == 1 {
                        key.push(x);
                    }
                }
                key.push(v);
                cells.push(Cell::simplex(key));
            }
        } else {
            let g: Vec<u32> = w.verts.iter().map(|x| x.0).collect();
            cp_lower_star_faces(kind, &g, v, &mut cells);
        }
    }
    cells.sort_unstable_by(|a, b| a.key.cmp(&b.key));
    cells.dedup_by(|a, b| a.key == b.key);
    let n = cells.len();
    // facets inside L(v) (those containing v), and cofacets
    let mut fstart = Vec::with_capacity(n + 1);
    let mut facets: Vec<u32> = Vec::new();
    let mut buf = Vec::new();
    for c in &cells {
        fstart.push(facets.len());
        buf.clear();
        c.facets(&mut buf);
        for (f, _) in &buf {
            if f.key.contains(&v) {
                if let Ok(j) = cells.binary_search_by(|x| x.key.as_slice().cmp(&f.key)) {
                    facets.push(j as u32);
                } else {
                    debug_assert!(false, "facet of a lower-star cell missing");
                }
            }
        }
    }
    fstart.push(facets.len());
    let mut ccount = vec![0u32; n + 1];
    for &f in &facets {
        ccount[f as usize + 1] += 1;
    }
    for i in 0..n {
        ccount[i + 1] += ccount[i];
    }
    let mut cof = vec![0u32; facets.len()];
    let mut fill = ccount.clone();
    for i in 0..n {
        for &f in &facets[fstart[i]..fstart[i + 1]] {
            cof[fill[f as usize] as usize] = i as u32;
            fill[f as usize] += 1;
        }
    }
    let mut remaining: Vec<u32> = (0..n).map(|i| (fstart[i + 1] - fstart[i]) as u32).collect();
    let mut status: Vec<Option<Status>> = vec![None; n];
    let mut time = vec![0u32; n];
    let dims: Vec<u8> = cells.iter().map(|c| c.dim() as u8).collect();
    let mut pairq: VecDeque<u32> = VecDeque::new();
    let mut free: BinaryHeap<std::cmp::Reverse<(u8, u32)>> = BinaryHeap::new();
    for i in 0..n {
        if remaining[i] == 0 {
            free.push(std::cmp::Reverse((dims[i], i as u32)));
        } else if remaining[i] == 1 {
            pairq.push_back(i as u32);
        }
    }
    let mut t = 0u32;
    let mut done = 0usize;
    // classify x: update cofaces' counts
    #[allow(clippy::too_many_arguments)]
    fn classify(
        x: usize,
        remaining: &mut [u32],
        cof: &[u32],
        ccount: &[u32],
        status: &[Option<Status>],
        pairq: &mut VecDeque<u32>,
        free: &mut BinaryHeap<std::cmp::Reverse<(u8, u32)>>,
        dims: &[u8],
    ) {
        for &y in &cof[ccount[x] as usize..ccount[x + 1] as usize] {
            let y = y as usize;
            remaining[y] -= 1;
            if status[y].is_some() {
                continue;
            }
            if remaining[y] == 1 {
                pairq.push_back(y as u32);
            } else if remaining[y] == 0 {
                free.push(std::cmp::Reverse((dims[y], y as u32)));
                for &z in &cof[ccount[y] as usize..ccount[y + 1] as usize] {
                    if remaining[z as usize] == 1 && status[z as usize].is_none() {
                        pairq.push_back(z);
                    }
                }
            }
        }
    }
    while done < n {
        while let Some(a) = pairq.pop_front() {
            let a = a as usize;
            if status[a].is_some() || remaining[a] != 1 {
                continue;
            }
            let tau = facets[fstart[a]..fstart[a + 1]]
                .iter()
                .map(|&f| f as usize)
                .find(|&f| status[f].is_none());
            let Some(tau) = tau else { continue };
            if remaining[tau] != 0 {
                continue;
            }
            status[tau] = Some(Status::Up(a as u32));
            status[a] = Some(Status::Down(tau as u32));
            time[tau] = t;
            time[a] = t;
            t += 1;
            done += 2;
            classify(
                tau,
                &mut remaining,
                &cof,
                &ccount,
                &status,
                &mut pairq,
                &mut free,
                &dims,
            );
            classify(
                a,
                &mut remaining,
                &cof,
                &ccount,
                &status,
                &mut pairq,
                &mut free,
                &dims,
            );
        }
        if done >= n {
            break;
        }
        // a critical cell: the lowest-dimensional free unclassified cell
        let mut g = None;
        while let Some(std::cmp::Reverse((_, i))) = free.pop() {
            if status[i as usize].is_none() {
                g = Some(i as usize);
                break;
            }
        }
        let Some(g) = g else {
            debug_assert!(false, "no free cell left in a lower star");
            break;
        };
        status[g] = Some(Status::Critical);
        time[g] = t;
        t += 1;
        done += 1;
        classify(
            g,
            &mut remaining,
            &cof,
            &ccount,
            &status,
            &mut pairq,
            &mut free,
            &dims,
        );
        // cofaces of g with one unclassified facet may now pair
        for &z in &cof[ccount[g] as usize..ccount[g + 1] as usize] {
            if remaining[z as usize] == 1 && status[z as usize].is_none() {
                pairq.push_back(z);
            }
        }
    }
    LowerStar {
        cells,
        status: status
            .into_iter()
            .map(|s| s.unwrap_or(Status::Critical))
            .collect(),
        time,
    }
}

/// The critical cells of L(v).
pub(crate) fn critical_cells<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    v: u32,
    apex: u32,
    w: &mut Scratch,
    out: &mut Vec<Cell>,
) {
    match apex {
        ALONE => out.push(Cell::simplex(SmallVec::from_slice(&[v]))),
        EXPLICIT => {
            let ls = lower_star(s, v, w);
            for (c, st) in ls.cells.into_iter().zip(ls.status) {
                if st == Status::Critical {
                    out.push(c);
                }
            }
        }
        _ => {}
    }
}

/// What the gradient says of a cell.
pub(crate) enum Look {
    Critical(u32),
    Down,
    /// Paired with `alpha`, in whose boundary the cell has incidence `sign`; `time` orders paths.
    Up {
        alpha: Cell,
        sign: i8,
        time: u32,
    },
}

/// Arithmetic overflow of integer coefficients.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Overflow;

#[inline]
pub(crate) fn add_c(a: i64, b: i64, m: i64) -> Result<i64, Overflow> {
    if m == 0 {
        a.checked_add(b).ok_or(Overflow)
    } else {
        Ok((a + b).rem_euclid(m))
    }
}

#[inline]
pub(crate) fn mul_c(a: i64, b: i64, m: i64) -> Result<i64, Overflow> {
    if m == 0 {
        a.checked_mul(b).ok_or(Overflow)
    } else {
        Ok((a * b).rem_euclid(m))
    }
}

/// The gradient of a complex: the apex plan per vertex and the sorted critical cells per
/// dimension.
pub(crate) struct Gradient<'a, S: ?Sized> {
    pub s: &'a S,
    pub apex: Vec<u32>,
    /// Critical cells per dimension, sorted by key.
    pub crit: Vec<Vec<Cell>>,
}

/// A per-flow cache of enumerated lower stars (vertices above the flow's front are dropped).
pub(crate) type Cache = BTreeMap<u32, LowerStar>;

impl<S: TopCells + VertexStar + ?Sized> Gradient<'_, S> {
    /// Index of a critical cell.
    pub fn crit_index(&self, c: &Cell) -> Option<u32> {
        self.crit
            .get(c.dim())?
            .binary_search_by(|x| x.key.cmp(&c.key))
            .ok()
            .map(|i| i as u32)
    }

    pub fn look(&self, tau: &Cell, cache: &mut Cache, w: &mut Scratch) -> Look {
        let v = tau.max_vertex();
        match self.apex[v as usize] {
            ALONE => match self.crit_index(tau) {
                Some(i) => Look::Critical(i),
                None => Look::Down,
            },
            EXPLICIT => {
                let ls = cache.entry(v).or_insert_with(|| lower_star(self.s, v, w));
                let Some(i) = ls.find(&tau.key) else {
                    debug_assert!(false, "cell not in its lower star");
                    return Look::Down;
                };
                match ls.status[i] {
                    Status::Critical => match self.crit_index(tau) {
                        Some(i) => Look::Critical(i),
                        None => Look::Down,
                    },
                    Status::Down(_) => Look::Down,
                    Status::Up(a) => {
                        let alpha = ls.cells[a as usize].clone();
                        let mut buf = Vec::new();
                        alpha.facets(&mut buf);
                        let sign = buf
                            .iter()
                            .find(|(f, _)| f.key == tau.key)
                            .map_or(1, |(_, s)| *s);
                        Look::Up {
                            alpha,
                            sign,
                            time: ls.time[i],
                        }
                    }
                }
            }
            apex => {
                if tau.key.binary_search(&apex).is_ok() {
                    return Look::Down;
                }
                let mut key = tau.key.clone();
                let pos = key.partition_point(|&x| x < apex);
                key.insert(pos, apex);
                Look::Up {
                    alpha: Cell::simplex(key),
                    sign: if pos % 2 == 0 { 1 } else { -1 },
                    time: 0,
                }
            }
        }
    }

    /// Follows the gradient from the boundary of the critical cell (or chain) `start`: returns
    /// the Morse boundary (critical index, coefficient), and when `chain` is given, adds to it
    /// the cells of the gradient paths with their coefficients (the chain of `start` pushed
    /// into the complex, a cycle when `start` is a Morse cycle).
    pub fn flow(
        &self,
        start: &[(Cell, i64)],
        m: i64,
        mut chain: Option<&mut BTreeMap<Key, (Cell, i64)>>,
        w: &mut Scratch,
    ) -> Result<Vec<(u32, i64)>, Overflow> {
        type Pending = BTreeMap<(u32, u32, Key), (i64, Cell, Cell, i8)>;
        let mut pending: Pending = BTreeMap::new();
        let mut result: BTreeMap<u32, i64> = BTreeMap::new();
        let mut cache: Cache = BTreeMap::new();
        let mut buf: Vec<(Cell, i8)> = Vec::new();
        let add = |tau: Cell,
                   c: i64,
                   pending: &mut Pending,
                   result: &mut BTreeMap<u32, i64>,
                   cache: &mut Cache,
                   w: &mut Scratch|
         -> Result<(), Overflow> {
            match self.look(&tau, cache, w) {
                Look::Critical(i) => {
                    let e = result.entry(i).or_insert(0);
                    *e = add_c(*e, c, m)?;
                }
                Look::Down => {}
                Look::Up { alpha, sign, time } => {
                    let k = (tau.max_vertex(), time, tau.key.clone());
                    let e = pending.entry(k).or_insert((0, tau, alpha, sign));
                    e.0 = add_c(e.0, c, m)?;
                }
            }
            Ok(())
        };
        for (sigma, c0) in start {
            if let Some(ch) = chain.as_deref_mut() {
                let e = ch.entry(sigma.key.clone()).or_insert((sigma.clone(), 0));
                e.1 = add_c(e.1, *c0, m)?;
            }
            buf.clear();
            sigma.facets(&mut buf);
            for (f, s) in buf.drain(..) {
                add(
                    f,
                    mul_c(*c0, s as i64, m)?,
                    &mut pending,
                    &mut result,
                    &mut cache,
                    w,
                )?;
            }
        }
        while let Some(((v, _, _), (c, tau, alpha, sign))) = pending.pop_last() {
            if cache.last_key_value().is_some_and(|(&k, _)| k > v) {
                let _ = cache.split_off(&(v + 1));
            }
            if c == 0 {
                continue;
            }
            // coefficient of alpha cancelling tau
            let ca = mul_c(-c, sign as i64, m)?;
            if let Some(ch) = chain.as_deref_mut() {
                let e = ch.entry(alpha.key.clone()).or_insert((alpha.clone(), 0));
                e.1 = add_c(e.1, ca, m)?;
            }
            buf.clear();
            alpha.facets(&mut buf);
            let facets = std::mem::take(&mut buf);
            for (f, s) in &facets {
                if f.key == tau.key {
                    continue;
                }
                add(
                    f.clone(),
                    mul_c(ca, *s as i64, m)?,
                    &mut pending,
                    &mut result,
                    &mut cache,
                    w,
                )?;
            }
            buf = facets;
        }
        if let Some(ch) = chain {
            ch.retain(|_, (_, c)| *c != 0);
        }
        Ok(result.into_iter().filter(|&(_, c)| c != 0).collect())
    }
}
