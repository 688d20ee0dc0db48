//! Fuzzes every mesh reader of `sphaera-io` (OBJ, PLY, STL, OFF, glTF/GLB, and the sniffed format) on arbitrary bytes: none may panic, hang, or accept invalid data.
//!
//! `cargo +nightly fuzz run mesh_files -- -rss_limit_mb=2048 -malloc_limit_mb=512 -timeout=10`
//! from the repository root (see `fuzz/README.md`). The body is
//! `sphaera_tests::input_fuzz::mesh_files` (`tests/src/input_fuzz.rs`), shared with
//! `tests/tests/input_fuzz_replay.rs`, which runs it on proptest's bytes in CI.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| sphaera_tests::input_fuzz::mesh_files(data));
