//! The reported bound against the measured Hausdorff distance on a real scan.

#![allow(clippy::print_stderr)]

use sphaera_mesh::io;
use sphaera_simplify::Simplifier;

#[test]
fn bunny_lowres_bound_is_never_below_the_measured_distance() {
    let Some(dir) =
        sphaera_tests::data_dir("bunny_lowres_bound_is_never_below_the_measured_distance")
    else {
        return;
    };
    let mesh = io::load(dir.join("bunny_lowres.obj")).unwrap();
    for ratio in [0.5, 0.1] {
        let out = Simplifier::new(&mesh).target_ratio(ratio).build().unwrap();
        let measured = sphaera_tests::sampled_hausdorff(&mesh, &out.mesh, 20_000, 1).symmetric();
        assert!(
            out.error_bound >= measured,
            "ratio {ratio}: bound {} below measured {measured}",
            out.error_bound
        );
        eprintln!(
            "bunny_lowres at {ratio}: {} triangles, bound {:.3e}, measured {measured:.3e}, bound/measured {:.2}, locked {:?}",
            out.mesh.triangle_count(),
            out.error_bound,
            out.error_bound / measured,
            out.locked
        );
    }
}
