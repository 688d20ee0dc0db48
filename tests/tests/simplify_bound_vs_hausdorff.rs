//! `sphaera-simplify`'s reported error bound checked by `sphaera-sweep`'s certified
//! Hausdorff distance, and that certificate checked by parry: on every mesh of the shared
//! data, simplified to 10 % of its triangles,
//!
//! - the simplifier's `error_bound` (an upper bound of the symmetric Hausdorff distance
//!   between input and output, by its error spheres) is never below the certified lower
//!   bound of the symmetric `sphaera_sweep::hausdorff` (a distance measured at a point
//!   of one surface, so at most the true distance), up to rounding;
//! - the sampled Hausdorff distance measured with parry3d
//!   ([`sphaera_tests::reference_hausdorff`], a lower bound of the true distance that
//!   shares no code with the sweep) is never above the certified upper bound: the
//!   certified bracket `lower ≤ H ≤ upper` contains the true value, and the sampled value
//!   is at most the true value. (It may lie below the certified lower bound: both are
//!   lower bounds of `H`, neither is ordered against the other.)
//!
//! The certified bracket is computed to `1e-2` of the simplifier's bound (absolute
//! tolerance, at least `1e-9` of the diagonal so that a bound of 0 stays reachable):
//! measured on the bunny and `dragon_vrip_res2.ply`, a tolerance of `1e-2`, `5e-2` or
//! `2e-1` of the bound costs the same within noise, since querying every vertex of both
//! meshes dominates the computation; 1 % keeps the bracket narrow. The sampled distance
//! uses 5,000 random points per mesh on top of every vertex and edge midpoint.
//!
//! # Size limit
//!
//! Meshes above [`MAX_TRIANGLES`] (250,000) are checked through a reduced variant
//! instead. The only one today is `dragon_vrip.ply` (871,414 triangles): in the test
//! profile on the shared 2-core machine it alone took about 54 s (simplification 11 s,
//! the certified Hausdorff distance by the paper's engine 39 s with its hierarchies, the
//! sampled distance 4 s), more than every other mesh together; the tree engine now used
//! takes about 2.3 s of it in release. Its reduced variants are
//! Stanford's own reductions of the same scan, `dragon_vrip_res2.ply`,
//! `dragon_vrip_res3.ply` and `dragon_vrip_res4.ply` (202,520, 47,794 and 11,102
//! triangles), which are in the data set and checked here; the test fails if a mesh above
//! the limit has no variant listed in [`REDUCED_VARIANTS`], or if a listed variant was not
//! checked, so no data is skipped silently. Files with the same bytes as one already
//! checked are checked once and named (the robots' `urdf/` asset copies are not walked
//! at all: see `sphaera_tests::mesh_files`).
//!
//! # Time
//!
//! Measured in the test profile (`opt-level = 1`, dependencies at 2) on the shared 2-core
//! machine: 26 s of CPU time; 15–16 s wall for the file when the cores are free (its two
//! tests side by side: the meshes of more than 40,000 triangles take 15 s alone,
//! `dragon_vrip_res2.ply` most of it, the others 9 s), 27 s wall while two other builds
//! ran.

#![allow(clippy::print_stderr)] // each mesh reports its numbers

use std::collections::HashMap;
use std::path::Path;

use sphaera_io as io;
use sphaera_mesh::{Length, TriMesh};
use sphaera_simplify::{SimplifyOptions, simplify};
use sphaera_sweep::{HausdorffOptions, hausdorff};

/// Meshes above this many triangles are checked through [`REDUCED_VARIANTS`] (see the
/// module documentation for the measured cost).
const MAX_TRIANGLES: usize = 250_000;

/// The reduced variants standing in for the meshes above [`MAX_TRIANGLES`].
const REDUCED_VARIANTS: &[(&str, &[&str])] = &[(
    "dragon_vrip.ply",
    &[
        "dragon_vrip_res2.ply",
        "dragon_vrip_res3.ply",
        "dragon_vrip_res4.ply",
    ],
)];

/// The meshes of more than this many triangles run in their own test, beside the others.
const LARGE: usize = 40_000;

/// The simplification ratio.
const RATIO: f64 = 0.1;

/// The certified bracket's width, relative to the simplifier's bound.
const RELATIVE_GAP: f64 = 1e-2;

/// Random points per mesh of the sampled distance (on top of vertices and midpoints).
const SAMPLES: usize = 5_000;

/// What was checked of one mesh.
struct Checked {
    triangles: usize,
}

#[test]
fn the_bound_holds_against_the_certified_distance_on_meshes_up_to_40k_triangles() {
    let Some(dir) = sphaera_tests::data_dir(
        "the_bound_holds_against_the_certified_distance_on_meshes_up_to_40k_triangles",
    ) else {
        return;
    };
    let checked = check_all(&dir, |triangles| triangles <= LARGE);
    assert!(checked.len() > 30, "only {} meshes checked", checked.len());
}

#[test]
fn the_bound_holds_against_the_certified_distance_on_large_meshes() {
    let Some(dir) =
        sphaera_tests::data_dir("the_bound_holds_against_the_certified_distance_on_large_meshes")
    else {
        return;
    };
    let checked = check_all(&dir, |triangles| triangles > LARGE);
    assert!(
        checked.values().any(|c| c.triangles > 200_000),
        "no mesh of more than 200,000 triangles was checked"
    );
}

/// Checks every distinct mesh file whose triangle count passes `select`; returns them by
/// name.
fn check_all(dir: &Path, select: impl Fn(usize) -> bool) -> HashMap<String, Checked> {
    let mut checked: HashMap<String, Checked> = HashMap::new();
    let mut too_large: Vec<String> = Vec::new();
    let mut seen: HashMap<Vec<u8>, String> = HashMap::new();
    let mut counts: HashMap<String, usize> = HashMap::new();
    for relative in sphaera_tests::mesh_files(dir) {
        let name = relative.display().to_string();
        let path = dir.join(&relative);
        let mesh = io::load(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let triangles = mesh.triangle_count();
        counts.insert(name.clone(), triangles);
        if !select(triangles) {
            continue;
        }
        let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        if let Some(first) = seen.get(&bytes) {
            eprintln!("{name}: the same bytes as {first}, checked there");
            continue;
        }
        seen.insert(bytes, name.clone());
        if triangles > MAX_TRIANGLES {
            eprintln!("{name}: {triangles} triangles, checked through its reduced variants");
            too_large.push(name);
            continue;
        }
        check(&name, &mesh);
        checked.insert(name, Checked { triangles });
    }
    for name in too_large {
        let Some((_, variants)) = REDUCED_VARIANTS.iter().find(|(n, _)| *n == name) else {
            panic!(
                "{name} is above {MAX_TRIANGLES} triangles and has no reduced variant: add one \
                 to REDUCED_VARIANTS, or raise the limit"
            );
        };
        for variant in *variants {
            // A variant this test did not select is checked by the other one.
            let elsewhere = counts.get(*variant).is_some_and(|&t| !select(t));
            assert!(
                checked.contains_key(*variant) || elsewhere,
                "{variant}, the reduced variant of {name}, was not checked"
            );
        }
    }
    checked
}

/// The three checks on one mesh.
fn check(name: &str, mesh: &TriMesh) {
    let diagonal = mesh.bounding_box_diagonal();
    let out = simplify(mesh, &SimplifyOptions::default().with_target_ratio(RATIO))
        .unwrap_or_else(|e| panic!("{name}: simplify: {e}"));
    let tolerance = (RELATIVE_GAP * out.error_bound).max(1e-9 * diagonal);
    let certified = hausdorff(
        mesh,
        &out.mesh,
        &HausdorffOptions::default().with_tolerance(Length::Absolute(tolerance)),
    )
    .unwrap_or_else(|e| panic!("{name}: hausdorff: {e}"));
    let sampled = sphaera_tests::reference_hausdorff(mesh, &out.mesh, SAMPLES, 1).symmetric();
    eprintln!(
        "{name}: {} -> {} triangles, bound {:.4e}, certified [{:.4e}, {:.4e}]{}, sampled {:.4e}",
        mesh.triangle_count(),
        out.mesh.triangle_count(),
        out.error_bound,
        certified.lower,
        certified.upper,
        if certified.converged {
            ""
        } else {
            " (not converged)"
        },
        sampled,
    );
    // Rounding: the distances are computed from coordinates of size about the diagonal.
    let slack = 1e-12 * diagonal;
    assert!(
        certified.lower <= certified.upper,
        "{name}: certified bracket [{}, {}] is empty",
        certified.lower,
        certified.upper
    );
    assert!(
        out.error_bound >= certified.lower - slack,
        "{name}: the simplifier's bound {} is below the certified lower bound {}",
        out.error_bound,
        certified.lower
    );
    let one_sided = [Some(&certified.a_to_b), certified.b_to_a.as_ref()];
    for side in one_sided.into_iter().flatten() {
        assert!(
            out.error_bound >= side.lower - slack,
            "{name}: the simplifier's bound {} is below a one-sided lower bound {}",
            out.error_bound,
            side.lower
        );
    }
    assert!(
        sampled <= certified.upper + slack,
        "{name}: the sampled distance {sampled} (parry) is above the certified upper bound {}",
        certified.upper
    );
}
