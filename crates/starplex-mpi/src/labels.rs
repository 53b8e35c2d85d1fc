//! Classes across ranks with parity: the merge behind distributed connected components (of
//! vertices), facet classes (of top cells) and orientation.
//!
//! Each rank holds some elements (global ids), each with an owner rank, grouped into local
//! classes (its local union-find), each element with a sign relative to its class root (+1
//! everywhere for plain components; the relative orientation for the orientation walk). Every
//! owner keeps, for each element it owns, a label `(L, p)`: the smallest element id known to be in
//! its global class and the element's sign relative to it, initially `(own id, +1)`. A round: the
//! owners send the labels of ghost elements to the ranks holding them; every rank takes, per local
//! class, the smallest label and proposes it to every element of the class (with the sign carried
//! along the class); owners keep the smaller. Rounds stop when no label changes (at most the number
//! of rank hops along a class). Every sign is a real path parity, so two different signs for the
//! same `(element, L)` prove an odd cycle: the classes cannot be oriented.
use rustc_hash::FxHashMap;

use mpi::traits::Communicator;

use crate::comm::{self, Failure, World};

/// The merged classes.
pub struct Merged {
    /// Number of global classes.
    pub n_classes: u64,
    /// True when the signs cannot agree (non-orientable), on every rank.
    pub conflict: bool,
    /// Global ids of the elements this rank owns whose sign is -1 relative to their class's
    /// smallest element (the cells to flip).
    pub negative: Vec<u32>,
    /// When `conflict`: the final sign of every element this rank holds (owned and ghost)
    /// relative to its class's smallest element, which some pair must contradict; else empty.
    pub signs: Vec<i8>,
}

/// One rank's elements: global id, owner rank, local class and sign relative to the class root.
pub struct Elements {
    /// Global ids.
    pub gid: Vec<u32>,
    /// Owner rank of each.
    pub owner: Vec<u32>,
    /// Local class of each (`0..n_classes`).
    pub class: Vec<u32>,
    /// Number of local classes.
    pub n_classes: usize,
    /// Sign relative to the class root (+1 or -1).
    pub sign: Vec<i8>,
    /// A local conflict already found (an odd local cycle).
    pub conflict: bool,
}

fn enc(p: i8) -> u32 {
    u32::from(p < 0)
}

fn dec(x: u32) -> i8 {
    if x == 0 {
        1
    } else {
        -1
    }
}

/// An owner receives the label `(l, s)` for its element `i`: keeps the smaller label; the same
/// label with the other sign is a conflict.
fn offer(
    lab: &mut [u32],
    par: &mut [i8],
    i: usize,
    (l, s): (u32, i8),
    changed: &mut bool,
    conflict: &mut bool,
) {
    if l < lab[i] {
        lab[i] = l;
        par[i] = s;
        *changed = true;
    } else if l == lab[i] && s != par[i] {
        *conflict = true;
    }
}

/// Merges the local classes of every rank (collective).
pub fn merge(w: &World, e: &Elements) -> Result<Merged, Failure> {
    let (me, p) = (w.rank() as u32, w.size() as usize);
    let n = e.gid.len();
    // owned state
    let mut lab: Vec<u32> = e.gid.clone();
    let mut par: Vec<i8> = vec![1; n];
    // ghosts by owner, in a fixed order
    let mut req: Vec<Vec<u32>> = vec![Vec::new(); p];
    let mut req_idx: Vec<Vec<usize>> = vec![Vec::new(); p];
    for i in 0..n {
        if e.owner[i] != me {
            req[e.owner[i] as usize].push(e.gid[i]);
            req_idx[e.owner[i] as usize].push(i);
        }
    }
    let asked = comm::exchange(w, req)?;
    let index: FxHashMap<u32, usize> = (0..n)
        .filter(|&i| e.owner[i] == me)
        .map(|i| (e.gid[i], i))
        .collect();
    let asked: Result<Vec<Vec<usize>>, String> = asked
        .parts()
        .map(|ids| {
            ids.iter()
                .map(|g| {
                    index.get(g).copied().ok_or_else(|| {
                        format!("internal: element {g} asked of a rank that does not own it")
                    })
                })
                .collect()
        })
        .collect();
    let asked = comm::agree(w, asked)?;
    let mut conflict = e.conflict;
    let mut best: Vec<(u32, i8)> = vec![(u32::MAX, 1); e.n_classes];
    loop {
        // owners send the labels of the elements others hold
        let reply: Vec<Vec<u32>> = asked
            .iter()
            .map(|ix| ix.iter().flat_map(|&i| [lab[i], enc(par[i])]).collect())
            .collect();
        let got = comm::exchange(w, reply)?;
        let (mut glab, mut gpar) = (lab.clone(), par.clone());
        for (r, g) in got.parts().enumerate() {
            for (k, &i) in req_idx[r].iter().enumerate() {
                glab[i] = g[2 * k];
                gpar[i] = dec(g[2 * k + 1]);
            }
        }
        // the smallest label of each local class, with the sign of the class root
        best.iter_mut().for_each(|b| *b = (u32::MAX, 1));
        for i in 0..n {
            let c = e.class[i] as usize;
            let root = e.sign[i] * gpar[i];
            if glab[i] < best[c].0 {
                best[c] = (glab[i], root);
            }
        }
        for i in 0..n {
            let c = e.class[i] as usize;
            if glab[i] == best[c].0 && e.sign[i] * gpar[i] != best[c].1 {
                conflict = true;
            }
        }
        // proposals: own elements directly, ghosts to their owners
        let mut changed = false;
        let mut prop: Vec<Vec<u32>> = vec![Vec::new(); p];
        for i in 0..n {
            let c = e.class[i] as usize;
            let (l, s) = (best[c].0, e.sign[i] * best[c].1);
            if e.owner[i] == me {
                offer(&mut lab, &mut par, i, (l, s), &mut changed, &mut conflict);
            }
        }
        for (r, ix) in req_idx.iter().enumerate() {
            prop[r] = ix
                .iter()
                .flat_map(|&i| {
                    let c = e.class[i] as usize;
                    [best[c].0, enc(e.sign[i] * best[c].1)]
                })
                .collect();
        }
        let got = comm::exchange(w, prop)?;
        for (r, g) in got.parts().enumerate() {
            for (k, &i) in asked[r].iter().enumerate() {
                let ls = (g[2 * k], dec(g[2 * k + 1]));
                offer(&mut lab, &mut par, i, ls, &mut changed, &mut conflict);
            }
        }
        if comm::max(w, u64::from(changed)) == 0 {
            break;
        }
    }
    let owned = (0..n).filter(|&i| e.owner[i] == me);
    let n_roots = owned.clone().filter(|&i| lab[i] == e.gid[i]).count() as u64;
    let mut negative: Vec<u32> = owned.filter(|&i| par[i] < 0).map(|i| e.gid[i]).collect();
    negative.sort_unstable();
    let conflict = comm::max(w, u64::from(conflict)) > 0;
    let mut signs = Vec::new();
    if conflict {
        // the owners' final signs, to the ranks holding ghost copies
        let reply: Vec<Vec<u32>> = asked
            .iter()
            .map(|ix| ix.iter().map(|&i| enc(par[i])).collect())
            .collect();
        let got = comm::exchange(w, reply)?;
        signs = par.clone();
        for (r, g) in got.parts().enumerate() {
            for (k, &i) in req_idx[r].iter().enumerate() {
                signs[i] = dec(g[k]);
            }
        }
    }
    Ok(Merged {
        n_classes: comm::sum(w, n_roots),
        conflict,
        negative,
        signs,
    })
}
