//! The caps on parameters that size memory (issue 38): a Hausdorff sample budget above its
//! cap is refused by both engines before anything is computed, naming the parameter and
//! the cap.

use sphaera_mesh::shapes;
use sphaera_sweep::{
    HausdorffOptions, MAX_HAUSDORFF_SAMPLES, SweepError, Sweeper, build_hierarchy, hausdorff,
    meshsweeper_hausdorff,
};

fn assert_capped(error: &SweepError) {
    assert!(
        matches!(
            error,
            SweepError::InvalidParameter {
                name: "max_samples",
                ..
            }
        ),
        "{error:?}"
    );
    assert!(
        error.to_string().contains("MAX_HAUSDORFF_SAMPLES"),
        "{error}"
    );
}

#[test]
fn a_sample_budget_above_the_cap_is_refused_by_both_engines() {
    let (a, b) = (
        shapes::cube(1.0, 2).expect("cube"),
        shapes::cube(1.2, 2).expect("cube"),
    );
    let (ha, hb) = (
        build_hierarchy(&a).expect("hierarchy"),
        build_hierarchy(&b).expect("hierarchy"),
    );
    let (sa, sb) = (
        Sweeper::new(&ha).expect("sweeper"),
        Sweeper::new(&hb).expect("sweeper"),
    );
    for budget in [MAX_HAUSDORFF_SAMPLES + 1, usize::MAX] {
        let options = HausdorffOptions::default().with_max_samples(budget);
        assert_capped(&hausdorff(&a, &b, &options).expect_err("trees"));
        assert_capped(&meshsweeper_hausdorff(&sa, &sb, &options).expect_err("paper's"));
    }
    // The cap itself is accepted by both.
    let options = HausdorffOptions::default().with_max_samples(MAX_HAUSDORFF_SAMPLES);
    assert!(hausdorff(&a, &b, &options).expect("trees").converged);
    assert!(
        meshsweeper_hausdorff(&sa, &sb, &options)
            .expect("paper's")
            .converged
    );
}
