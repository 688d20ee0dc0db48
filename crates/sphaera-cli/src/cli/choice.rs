//! The library's method enums as command-line values: each name comes from the library
//! (its `name()`, read back by its `FromStr`), only the one-line help of each value from
//! here. A name changed in the library changes here with it.

use std::ffi::OsStr;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::error::ErrorKind;
use sphaera::medial::CoverCriterion;
use sphaera::mesh::ParseNameError;
use sphaera::robot::PlannerFormat;
use sphaera::silhouette::{ContourRegion, Contours, DistanceTransform};
use sphaera::simplify::{Order, Placement};
use sphaera::spheretree::{Effort, Method};

/// A library enum users pick by name.
pub trait Named: Copy + Send + Sync + 'static + std::str::FromStr<Err = ParseNameError> {
    /// The name users type and reports show.
    fn name(self) -> &'static str;
}

macro_rules! named {
    ($($enum:ty),*) => {
        $(impl Named for $enum {
            fn name(self) -> &'static str {
                <$enum>::name(self)
            }
        })*
    };
}

named!(
    Method,
    Effort,
    Placement,
    Order,
    Contours,
    ContourRegion,
    DistanceTransform,
    CoverCriterion,
    PlannerFormat
);

/// The values offered for one option: each with its help line, in the order `--help`
/// lists them.
#[derive(Clone, Copy)]
pub struct Choice<T: 'static>(&'static [(T, &'static str)]);

impl<T: Named> Choice<T> {
    /// The parser of an option taking one of `values`.
    pub const fn of(values: &'static [(T, &'static str)]) -> Self {
        Self(values)
    }

    fn possible(&self) -> impl Iterator<Item = PossibleValue> + '_ {
        self.0
            .iter()
            .map(|&(value, help)| PossibleValue::new(value.name()).help(help))
    }
}

impl<T: Named> TypedValueParser for Choice<T> {
    type Value = T;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<T, clap::Error> {
        // clap's own parser for the names offered: its message lists them and suggests
        // the closest.
        let name = PossibleValuesParser::new(self.possible()).parse_ref(cmd, arg, value)?;
        name.parse::<T>()
            .map_err(|error| clap::Error::raw(ErrorKind::InvalidValue, format!("{error}\n")))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(self.possible()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::Cli;
    use clap::CommandFactory;

    /// Every value each option offers reads back as itself.
    fn reads_back<T: Named + PartialEq + std::fmt::Debug>(choice: Choice<T>) {
        let cmd = Cli::command();
        for &(value, _) in choice.0 {
            let parsed = choice
                .parse_ref(&cmd, None, OsStr::new(value.name()))
                .expect("an offered name");
            assert_eq!(parsed, value);
        }
        assert!(choice.parse_ref(&cmd, None, OsStr::new("nowhere")).is_err());
    }

    #[test]
    fn every_offered_name_reads_back() {
        reads_back(Choice::of(super::super::spheretree::METHODS));
        reads_back(Choice::of(super::super::spheretree::EFFORTS));
        reads_back(Choice::of(super::super::simplify::PLACEMENTS));
        reads_back(Choice::of(super::super::simplify::ORDERS));
        reads_back(Choice::of(super::super::silhouette::CONTOURS));
        reads_back(Choice::of(super::super::silhouette::TRANSFORMS));
        reads_back(Choice::of(super::super::silhouette::REGIONS));
        reads_back(Choice::of(super::super::medial::COVERS));
        reads_back(Choice::of(super::super::urdf::FORMATS));
    }

    #[test]
    fn every_method_is_offered() {
        let offered: Vec<Method> = super::super::spheretree::METHODS
            .iter()
            .map(|&(m, _)| m)
            .collect();
        for method in Method::ALL {
            assert!(offered.contains(&method), "{method} is not offered");
        }
        let offered: Vec<Effort> = super::super::spheretree::EFFORTS
            .iter()
            .map(|&(e, _)| e)
            .collect();
        assert_eq!(offered, Effort::ALL);
    }
}
