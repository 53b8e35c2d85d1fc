//! The library part of the `starplex` command-line tool: what other front ends (`starplex-mpi`)
//! print exactly as the CLI does.
pub mod alloc;
pub mod error;
pub mod export;
pub mod report;
