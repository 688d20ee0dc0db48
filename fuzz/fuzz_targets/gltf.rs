//! Fuzzes the glTF reader of `sphaera-io` on arbitrary JSON text and on GLB containers built around arbitrary chunks: none may panic, hang, or accept invalid data.
//!
//! `cargo +nightly fuzz run gltf -- -rss_limit_mb=2048 -malloc_limit_mb=512 -timeout=10`
//! from the repository root (see `fuzz/README.md`). The body is
//! `sphaera_tests::input_fuzz::gltf` (`tests/src/input_fuzz.rs`), shared with
//! `tests/tests/input_fuzz_replay.rs`, which runs it on proptest's bytes in CI.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| sphaera_tests::input_fuzz::gltf(data));
