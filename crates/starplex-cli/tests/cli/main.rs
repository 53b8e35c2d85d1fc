//! The integration tests of this crate, as one test binary (one link instead of one per file;
//! run one file's tests with `cargo test --test cli FILE::`).
mod cli_compare;
mod cli_cp;
mod cli_errors;
mod cli_export;
mod cli_generate;
mod cli_homology;
mod cli_io;
mod cli_own_attrs;
mod cli_query;
mod cli_render;
mod cli_rips;
mod cli_saved_tree;
mod cli_simplify;
mod cli_simplify_labels;
mod cli_validate;
