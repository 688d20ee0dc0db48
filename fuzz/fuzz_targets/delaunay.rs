//! Fuzzes the Delaunay tetrahedralization of `sphaera-medial`: bytes become points (mostly
//! on small integer grids, so ties and duplicates are common), a tetrahedralization is
//! built and a few more points are inserted, and everything is checked
//! (`Delaunay::validate`, duplicates, errors against brute force, determinism).
//!
//! `cargo +nightly fuzz run delaunay` from the repository root. The body is
//! `sphaera_tests::delaunay_fuzz` (`tests/src/delaunay_fuzz.rs`), shared with
//! `tests/tests/delaunay_fuzz_replay.rs`, which runs it on proptest's bytes in CI.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| sphaera_tests::delaunay_fuzz::check(data));
