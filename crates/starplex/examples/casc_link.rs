//! CASC Section 5.1: links on the constructed example of six triangles and the link condition
//! for contracting the edge {3,4}.
//!
//! Run with `cargo run -p starplex --example casc_link`. The paper's printout of Link({3}) drops
//! the vertex {0} (an erratum): {0,1} and {0,5} are in the link, so {0} is too.
use starplex::hasse::Hasse;
use starplex::ids::VertexId;

/// The six triangles of the example.
pub const TRIANGLES: [[u32; 3]; 6] = [
    [0, 1, 3],
    [0, 3, 5],
    [1, 3, 4],
    [3, 4, 5],
    [1, 2, 4],
    [2, 4, 5],
];

/// The example complex.
pub fn example() -> Hasse {
    let mut h = Hasse::new();
    for t in TRIANGLES {
        h.insert(&t.map(VertexId)).expect("valid triangle");
    }
    h
}

/// The report printed by `main`.
pub fn report() -> String {
    let h = example();
    let v = |i: u32| h.vertex(VertexId(i)).expect("vertex");
    let a = h.link(v(3));
    let b = h.link(v(4));
    let e = h.find(&[VertexId(3), VertexId(4)]).expect("edge");
    let ab = h.link(e);
    let both = a.intersection(&b);
    let mut s = String::new();
    s += &format!("Link({{3}}) = {}\n", h.format_set(&a));
    s += &format!("Link({{4}}) = {}\n", h.format_set(&b));
    s += &format!("Link({{3,4}}) = {}\n", h.format_set(&ab));
    s += &format!("Link({{3}}) ∩ Link({{4}}) = {}\n", h.format_set(&both));
    s += &format!(
        "link condition holds: {}\n",
        both == ab && h.can_collapse(e).is_ok()
    );
    s
}

#[allow(dead_code)]
fn main() {
    print!("{}", report());
}
