//! The `delaunay` fuzz target's body ([`sphaera_tests::delaunay_fuzz`]) on bytes from
//! proptest: `sphaera-medial`'s tetrahedralization checked by the shared harness, so that every CI run exercises what `cargo +nightly fuzz run delaunay`
//! explores for hours, plus a few hand-made byte strings for the edge cases of the
//! decoder.

// The decoder produces exact values: exact comparisons are the point.
#![allow(clippy::float_cmp)]

use proptest::prelude::*;
use sphaera_medial::DVec3;
use sphaera_tests::delaunay_fuzz::{check, decode};

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(1024)))]

    /// Arbitrary bytes: any mode, any grid side, any number of late insertions.
    #[test]
    fn arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        check(&bytes);
    }

    /// The integer-grid mode on a 3×3×3 grid (header 4): dense ties and duplicates.
    #[test]
    fn small_integer_grid(
        inserted in 0u8..17,
        body in prop::collection::vec(any::<u8>(), 12..300),
    ) {
        let mut bytes = vec![4, inserted];
        bytes.extend(body);
        check(&bytes);
    }
}

#[test]
fn empty_and_short_inputs_are_input_errors() {
    for bytes in [
        &[][..],
        &[0],
        &[0, 0],
        &[0, 0, 1, 2, 3],
        &[3, 0, 1, 2, 3, 4],
    ] {
        check(bytes);
    }
}

#[test]
fn decoder_modes() {
    // Mode 0, side 2 + (8 >> 2) % 7 = 4, two late insertions, three points.
    let decoded = decode(&[8, 2, 1, 2, 3, 5, 6, 7, 0, 0, 0]);
    assert_eq!(decoded.initial.len(), 1);
    assert_eq!(decoded.inserted.len(), 2);
    assert_eq!(decoded.initial[0], DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(decoded.inserted[0], DVec3::new(1.0, 2.0, 3.0));
    // Mode 3: little-endian i32 / 65536.
    let mut bytes = vec![3, 0];
    for value in [65_536_i32, -32_768, 0] {
        bytes.extend(value.to_le_bytes());
    }
    assert_eq!(decode(&bytes).initial[0], DVec3::new(1.0, -0.5, 0.0));
}

#[test]
fn whole_cube_grid_with_insertions() {
    // Every point of a 4×4×4 grid, then 16 more grid points (all duplicates).
    let mut bytes = vec![8, 16];
    for i in 0..80_u8 {
        bytes.extend([i % 4, i / 4 % 4, i / 16 % 4]);
    }
    check(&bytes);
}
