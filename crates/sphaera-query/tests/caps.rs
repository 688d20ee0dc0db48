//! The caps on parameters that size memory (issue 38): each is refused just above its cap,
//! quickly and without allocating, with an error naming the parameter and the cap.

use sphaera_mesh::{DVec3, Length, shapes};
use sphaera_query::grid::UniformGrid;
use sphaera_query::hausdorff::{HausdorffOptions, Rows, hausdorff};
use sphaera_query::measure::{SampleOptions, SurfaceSamples};
use sphaera_query::{MAX_GRID_CELLS, MAX_HAUSDORFF_SAMPLES, MAX_SAMPLES, QueryError, sampling};

/// Asserts `error` is an `InvalidParameter` named `name` whose message names `cap`.
fn assert_capped(error: &QueryError, name: &str, cap: &str) {
    assert!(
        matches!(error, QueryError::InvalidParameter { name: n, .. } if *n == name),
        "{error:?}"
    );
    let message = error.to_string();
    assert!(message.contains(name) && message.contains(cap), "{message}");
}

#[test]
fn sample_counts_above_the_cap_are_refused() {
    let mesh = shapes::cube(1.0, 1).expect("cube");
    for n in [MAX_SAMPLES + 1, usize::MAX] {
        let error = sampling::random(&mesh, n, 1).expect_err("too many samples");
        assert_capped(&error, "n", "MAX_SAMPLES");
        let error = sampling::poisson_disk(&mesh, n, 1).expect_err("too many samples");
        assert_capped(&error, "n", "MAX_SAMPLES");
    }
    let options = SampleOptions::default().with_random_points(MAX_SAMPLES + 1);
    let error = SurfaceSamples::new(&mesh, &options).expect_err("too many random points");
    assert_capped(&error, "random_points", "MAX_SAMPLES");
}

#[test]
fn a_hausdorff_budget_above_the_cap_is_refused_and_the_cap_accepted() {
    let (a, b) = (
        shapes::cube(1.0, 1).expect("cube"),
        shapes::cube(1.1, 1).expect("cube"),
    );
    for budget in [MAX_HAUSDORFF_SAMPLES + 1, usize::MAX] {
        let options = HausdorffOptions::default().with_max_samples(budget);
        let error = hausdorff(&a, &b, &options).expect_err("too large a budget");
        assert_capped(&error, "max_samples", "MAX_HAUSDORFF_SAMPLES");
    }
    // The cap itself is a budget like any other: two cubes converge long before it.
    let options = HausdorffOptions::default()
        .with_max_samples(MAX_HAUSDORFF_SAMPLES)
        .with_tolerance(Length::RelativeToDiagonal(1e-3));
    let h = hausdorff(&a, &b, &options).expect("the cap is accepted");
    assert!(h.converged && h.lower <= h.upper);
    // The default is within the cap.
    assert!(HausdorffOptions::default().max_samples <= MAX_HAUSDORFF_SAMPLES);
}

#[test]
fn a_grid_of_more_cells_than_the_cap_is_refused_before_allocating() {
    let none = || std::iter::empty::<Option<(DVec3, DVec3)>>();
    for dims in [
        [MAX_GRID_CELLS + 1, 1, 1],
        [1 << 13, 1 << 13, 2],
        [usize::MAX, usize::MAX, 2],
    ] {
        let error = UniformGrid::new(DVec3::ZERO, 1.0, dims, none()).expect_err("too many cells");
        assert_capped(&error, "dims", "MAX_GRID_CELLS");
    }
    // A small grid is fine.
    assert!(UniformGrid::new(DVec3::ZERO, 1.0, [4, 4, 4], none()).is_ok());
}

#[test]
fn rows_are_sized_by_their_pairs_not_by_the_row_count() {
    // A row count no memory could hold costs nothing: only rows with pairs are stored.
    let rows = Rows::from_pairs(usize::MAX, vec![(3, 1), (0, 2), (3, 0)]);
    assert_eq!(rows.row(0), &[2]);
    assert!(rows.row(1).is_empty());
    assert_eq!(rows.row(3), &[0, 1]);
    assert!(rows.row(u32::MAX).is_empty());
}
