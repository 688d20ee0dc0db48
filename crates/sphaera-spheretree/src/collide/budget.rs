//! The budget of a traversal: the paper's cost model, or wall time.

use std::time::Duration;

use crate::SphereTreeError;

/// The paper's cost model (eq. 1), `T = Nu·Cu + Nv·Cv`: `Nu` spheres updated (placed in
/// the scene), `Nv` sphere pairs tested for overlap.
///
/// The defaults are the paper's section 6.4 values, `Cu = 2` and `Cv = 1`: updating a
/// sphere (rotating and translating its centre, 21 floating-point operations) costs about
/// twice an overlap test (10 operations).
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::collide::CostModel;
///
/// let model = CostModel::default();
/// assert_eq!((model.update_cost, model.test_cost), (2.0, 1.0));
/// assert_eq!(model.cost(3, 4), 10.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CostModel {
    /// `Cu`: the cost of updating one sphere (default 2).
    pub update_cost: f64,
    /// `Cv`: the cost of one sphere-pair overlap test (default 1).
    pub test_cost: f64,
}

impl Default for CostModel {
    fn default() -> Self {
        Self {
            update_cost: 2.0,
            test_cost: 1.0,
        }
    }
}

impl CostModel {
    /// `updates·Cu + tests·Cv`.
    #[must_use]
    pub fn cost(&self, updates: u64, tests: u64) -> f64 {
        updates as f64 * self.update_cost + tests as f64 * self.test_cost
    }
}

/// When [`collide`](super::collide) stops descending.
///
/// - [`Budget::Unlimited`]: down to the leaves (the exact answer of the trees).
/// - [`Budget::Cost`]: a level is started only when its whole cost (known in advance: the
///   children to place and the child pairs to test) fits in what is left of `limit`, so
///   the cost spent never exceeds `limit` and no work is thrown away. The root pair (cost
///   5 by default) is always tested, whatever the limit.
/// - [`Budget::Time`]: the clock is read before each level and every 64 pair tests; when
///   the time is up during a level, that level's partial work is dropped and the previous
///   level is returned. The time spent can exceed the limit by about 64 pair tests.
///
/// # Examples
///
/// ```
/// use std::time::Duration;
/// use sphaera_spheretree::collide::{Budget, CostModel};
///
/// assert_eq!(Budget::default(), Budget::Unlimited);
/// assert_eq!(Budget::cost(100.0), Budget::Cost { limit: 100.0, model: CostModel::default() });
/// let _frame = Budget::Time(Duration::from_micros(500));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Budget {
    /// No limit: descend to the leaves.
    #[default]
    Unlimited,
    /// A limit on the paper's cost `Nu·Cu + Nv·Cv`.
    Cost {
        /// The largest cost to spend.
        limit: f64,
        /// `Cu` and `Cv`.
        model: CostModel,
    },
    /// A wall-time limit.
    Time(Duration),
}

impl Budget {
    /// A cost limit with the paper's costs ([`CostModel::default`]).
    #[must_use]
    pub fn cost(limit: f64) -> Self {
        Self::Cost {
            limit,
            model: CostModel::default(),
        }
    }

    /// `Ok` unless a [`Budget::Cost`]'s limit or costs are NaN or negative.
    ///
    /// # Errors
    ///
    /// [`SphereTreeError::InvalidParameter`] naming the bad number.
    pub fn validate(&self) -> Result<(), SphereTreeError> {
        if let Self::Cost { limit, model } = self {
            for (name, value) in [
                ("limit", *limit),
                ("update_cost", model.update_cost),
                ("test_cost", model.test_cost),
            ] {
                if value.is_nan() || value < 0.0 {
                    return Err(SphereTreeError::InvalidParameter {
                        name,
                        value,
                        requirement: "not NaN or negative",
                    });
                }
            }
        }
        Ok(())
    }
}
