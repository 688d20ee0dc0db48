//! Every method enum of the workspace reads back the name it shows, and a wrong name says
//! what is accepted.

use sphaera::medial::CoverCriterion;
use sphaera::mesh::ParseNameError;
use sphaera::robot::PlannerFormat;
use sphaera::silhouette::{Contours, DistanceTransform};
use sphaera::simplify::{Order, Placement};
use sphaera::spheretree::{Effort, Method};

fn round_trip<T>(values: &[T])
where
    T: std::fmt::Display + std::str::FromStr<Err = ParseNameError> + PartialEq + std::fmt::Debug,
{
    for value in values {
        assert_eq!(value.to_string().parse::<T>().as_ref(), Ok(value));
    }
    let error = "no such name".parse::<T>().expect_err("refused");
    assert!(error.to_string().contains("give "), "{error}");
}

#[test]
fn every_method_enum_reads_back_its_names() {
    round_trip(&Method::ALL);
    round_trip(&Effort::ALL);
    round_trip(&[Placement::Subset, Placement::Optimal]);
    round_trip(&[Order::Auto, Order::Strict, Order::Batched]);
    round_trip(&[DistanceTransform::Euclidean, DistanceTransform::Chamfer]);
    round_trip(&[Contours::External, Contours::All]);
    round_trip(&CoverCriterion::ALL);
    round_trip(&PlannerFormat::ALL);
    assert_eq!("outline".parse(), Ok(Contours::External));
    assert_eq!(Method::Auto.to_string(), "auto");
}
