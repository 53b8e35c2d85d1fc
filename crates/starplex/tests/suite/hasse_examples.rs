//! The CASC paper's worked examples (Section 5.1 links, Fig. 5 / Table 1 decimation), checked
//! through the runnable examples' own output.
#[path = "../../examples/casc_link.rs"]
mod casc_link;

#[path = "../../examples/casc_decimate.rs"]
mod casc_decimate;

#[test]
fn section_5_1_links_and_link_condition() {
    assert_eq!(
        casc_link::report(),
        "Link({3}) = {0} {1} {4} {5} {0,1} {0,5} {1,4} {4,5}\n\
         Link({4}) = {1} {2} {3} {5} {1,2} {1,3} {2,5} {3,5}\n\
         Link({3,4}) = {1} {5}\n\
         Link({3}) ∩ Link({4}) = {1} {5}\n\
         link condition holds: true\n"
    );
}

#[test]
fn figure_5_table_1_decimation() {
    assert_eq!(
        casc_decimate::report(),
        "decimate {3,4} into {6}:\n\
         {3} {4} {3,4} -> {6}\n\
         {0,3} -> {0,6}\n\
         {1,3} {1,4} {1,3,4} -> {1,6}\n\
         {2,4} -> {2,6}\n\
         {3,5} {4,5} {3,4,5} -> {5,6}\n\
         {0,1,3} -> {0,1,6}\n\
         {0,3,5} -> {0,5,6}\n\
         {1,2,4} -> {1,2,6}\n\
         {2,4,5} -> {2,5,6}\n\
         triangles: {0,1,6} {0,5,6} {1,2,6} {2,5,6}\n\
         f-vector: [5, 8, 4]\n\
         valid: true\n"
    );
}

#[test]
fn link_of_a_set_matches_the_definition() {
    let h = casc_link::example();
    let v = |i: u32| h.vertex(i.into()).unwrap();
    // Lk({3} ∪ {4}) as a set: Cl(St(S)) \ St(Cl(S))
    let mut s = starplex::hasse::NodeSet::new();
    s.insert(v(3));
    s.insert(v(4));
    let lk = h.link_of(&s);
    assert_eq!(h.format_set(&lk), "{0} {1} {2} {5} {0,1} {0,5} {1,2} {2,5}");
    // the link of a single simplex through the set version agrees with the fast one
    for n in h.nodes().collect::<Vec<_>>() {
        let mut one = starplex::hasse::NodeSet::new();
        one.insert(n);
        assert_eq!(h.link_of(&one), h.link(n), "{:?}", h.vertices(n));
    }
}
