//! Compact topological data structures: incidence graph, IS, IA*, simplex tree.
