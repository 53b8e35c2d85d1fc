//! CASC Fig. 5 / Table 1: decimating the edge {3,4} of the constructed example into a new
//! vertex 6. Prints how the simplices of St(Cl({3,4})) group (each group maps to one new
//! simplex), then the triangles left.
//!
//! Run with `cargo run -p starplex --example casc_decimate`. Table 1 of the paper has two
//! misprints: row 3 maps {3,4,5} {3,5} {4,5} to {5,6} (printed {3,6}), and row 7 visits {2,4},
//! which maps to {2,6} (the grab column prints {3,5}).
use starplex::hasse::{Hasse, KeepFirst};
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

/// The report printed by `main`.
pub fn report() -> String {
    let mut h: Hasse<(u32, u32, u32)> = Hasse::new();
    for t in TRIANGLES {
        h.insert(&t.map(VertexId)).expect("valid triangle");
    }
    let e = h.find(&[VertexId(3), VertexId(4)]).expect("edge");
    let plan = h.plan_decimate(e, None).expect("plan");
    let mut s = format!("decimate {{3,4}} into {{{}}}:\n", plan.new_vertex);
    s += &plan.to_string();
    let p = h.decimate(e, &mut KeepFirst).expect("decimate");
    assert_eq!(p, plan.new_vertex);
    let tops: Vec<String> = h
        .level(2)
        .map(|t| {
            let v: Vec<String> = h.vertices(t).iter().map(|x| x.0.to_string()).collect();
            v.join(",")
        })
        .collect();
    let mut tops = tops;
    tops.sort();
    let tops: Vec<String> = tops.iter().map(|t| format!("{{{t}}}")).collect();
    s += &format!("triangles: {}\n", tops.join(" "));
    s += &format!("f-vector: {:?}\n", h.f_vector());
    s += &format!("valid: {}\n", h.is_valid());
    s
}

#[allow(dead_code)]
fn main() {
    print!("{}", report());
}
