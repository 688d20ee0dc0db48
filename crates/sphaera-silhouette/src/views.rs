//! Camera sets regularly distributed over a sphere (section 3.2 of the paper: "regularly
//! distributed, allowing the detection of the closest views to take a constant time").

use glam::DVec3;

use crate::SilhouetteError;
use crate::caps::MAX_INTERVALS;

/// How a view projects the mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Parallel rays along the view direction.
    Orthographic,
    /// A pinhole camera on the view direction at `distance` bounding radii from the
    /// mesh's bounding-sphere centre (more than 1), looking at the centre, its field of
    /// view just holding the bounding sphere.
    Perspective {
        /// The camera's distance from the centre, in bounding radii.
        distance: f64,
    },
}

/// Views on a latitude–longitude grid: elevations from −90° to 90° by `step`, and on each
/// ring strictly between the poles `360° / step` azimuths from 0° (one view at each
/// pole). Every 15° gives 266 views. View `k` looks from `direction(k)` toward the centre.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewSet {
    /// The angular step, in radians.
    step: f64,
    /// Rings from the south pole (index 0) to the north pole.
    rings: usize,
    /// Azimuths per ring strictly between the poles.
    azimuths: usize,
    projection: Projection,
    directions: Vec<DVec3>,
}

/// The unit direction at elevation `e` and azimuth `a` (radians): `z` up.
fn direction(e: f64, a: f64) -> DVec3 {
    DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
}

impl ViewSet {
    /// The regular set every `step_degrees` (which must divide 180 and lie in `(0, 90]`),
    /// orthographic.
    ///
    /// The step is at least 180° / 128 = 1.40625° (32,514 views), so that the set has at
    /// most [`MAX_VIEWS`](crate::MAX_VIEWS) views: the labels store a value per vertex
    /// per view.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::InvalidStep`]; [`SilhouetteError::InvalidParameter`] named
    /// `"step"` for a step below 1.40625° (more than [`MAX_VIEWS`](crate::MAX_VIEWS)
    /// views), checked before anything is allocated.
    pub fn regular(step_degrees: f64) -> Result<Self, SilhouetteError> {
        let bad = SilhouetteError::InvalidStep {
            degrees: step_degrees,
        };
        if !(step_degrees > 0.0 && step_degrees <= 90.0) {
            return Err(bad);
        }
        let halves = 180.0 / step_degrees;
        if halves.round() > MAX_INTERVALS as f64 {
            return Err(SilhouetteError::InvalidParameter {
                name: "step",
                value: step_degrees,
                requirement: "at least 1.40625° (180°/128), so that the set has at most \
                              `MAX_VIEWS` (32,768) views",
            });
        }
        if (halves - halves.round()).abs() > 1e-9 {
            return Err(bad);
        }
        let intervals = halves.round() as usize;
        let step = std::f64::consts::PI / intervals as f64;
        let rings = intervals + 1;
        let azimuths = 2 * intervals;
        let mut directions = Vec::with_capacity(2 + (rings - 2) * azimuths);
        directions.push(DVec3::NEG_Z);
        for ring in 1..rings - 1 {
            let e = -std::f64::consts::FRAC_PI_2 + ring as f64 * step;
            for j in 0..azimuths {
                directions.push(direction(e, j as f64 * step));
            }
        }
        directions.push(DVec3::Z);
        Ok(Self {
            step,
            rings,
            azimuths,
            projection: Projection::Orthographic,
            directions,
        })
    }

    /// The same views through perspective cameras at `distance` bounding radii.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::CameraInside`] unless `distance > 1` (and finite).
    pub fn with_perspective(mut self, distance: f64) -> Result<Self, SilhouetteError> {
        if !(distance.is_finite() && distance > 1.0) {
            return Err(SilhouetteError::CameraInside { distance });
        }
        self.projection = Projection::Perspective { distance };
        Ok(self)
    }

    /// The angular step between neighbouring views, in degrees: `180 / k` for the `k`
    /// intervals of 180° the set has, so that [`ViewSet::regular`] of it gives the same
    /// set again.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_silhouette::ViewSet;
    ///
    /// let views = ViewSet::regular(15.0)?;
    /// assert_eq!(views.step_degrees(), 15.0);
    /// let odd = ViewSet::regular(180.0 / 7.0)?;
    /// assert_eq!(ViewSet::regular(odd.step_degrees())?, odd);
    /// # Ok::<(), sphaera_silhouette::SilhouetteError>(())
    /// ```
    #[must_use]
    pub fn step_degrees(&self) -> f64 {
        180.0 / (self.rings - 1) as f64
    }

    /// The projection of every view.
    #[must_use]
    pub fn projection(&self) -> Projection {
        self.projection
    }

    /// The number of views.
    #[must_use]
    pub fn len(&self) -> usize {
        self.directions.len()
    }

    /// Whether the set has no view (never: a set has at least its two poles).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.directions.is_empty()
    }

    /// The unit direction from the centre toward view `k`'s camera.
    ///
    /// # Panics
    ///
    /// If `k >= self.len()`.
    #[must_use]
    pub fn direction(&self, k: usize) -> DVec3 {
        self.directions[k]
    }

    /// All view directions, by index.
    #[must_use]
    pub fn directions(&self) -> &[DVec3] {
        &self.directions
    }

    /// The index of the view on `ring` at azimuth index `j` (wrapped).
    fn index(&self, ring: usize, j: i64) -> usize {
        if ring == 0 {
            return 0;
        }
        if ring == self.rings - 1 {
            return self.directions.len() - 1;
        }
        let n = self.azimuths as i64;
        1 + (ring - 1) * self.azimuths + j.rem_euclid(n) as usize
    }

    /// The views near `direction` in constant time: on the `reach` rings either side of
    /// the nearest ring, the `reach` azimuths either side of the nearest azimuth.
    fn neighbourhood(&self, direction: DVec3, reach: usize) -> Vec<usize> {
        let e = direction.z.clamp(-1.0, 1.0).asin();
        let a = direction.y.atan2(direction.x);
        let ring = ((e + std::f64::consts::FRAC_PI_2) / self.step).round() as i64;
        let j = (a / self.step).round() as i64;
        let mut out = Vec::new();
        let reach = reach as i64;
        for r in (ring - reach).max(0)..=(ring + reach).min(self.rings as i64 - 1) {
            let r = r as usize;
            if r == 0 || r == self.rings - 1 {
                out.push(self.index(r, 0));
                continue;
            }
            for dj in -reach..=reach {
                out.push(self.index(r, j + dj));
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Candidates sorted by angle to `direction` (the lower index on ties).
    fn by_angle(&self, direction: DVec3, mut candidates: Vec<usize>) -> Vec<usize> {
        let key = |k: &usize| -self.directions[*k].dot(direction);
        candidates.sort_by(|a, b| key(a).total_cmp(&key(b)).then(a.cmp(b)));
        candidates
    }

    /// The view nearest to `direction` (smallest angle; the lowest index on ties), in
    /// constant time: the nearest view lies on the nearest ring or one either side (a
    /// view two rings away is more than `1.5·step` off, the nearest on the nearest ring at
    /// most `step`), at the nearest azimuth of its ring.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::InvalidDirection`] for a zero or non-finite direction.
    pub fn nearest(&self, direction: DVec3) -> Result<usize, SilhouetteError> {
        Ok(self.nearest_n(direction, 1)?[0])
    }

    /// The `n` views nearest to `direction`, nearest first (the lowest index on ties).
    /// Constant time for `n ≤ 8` (a bounded neighbourhood of the grid); a full sort
    /// beyond.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::InvalidDirection`] for a zero or non-finite direction;
    /// [`SilhouetteError::InvalidNearest`] unless `1 ≤ n ≤ self.len()`.
    pub fn nearest_n(&self, direction: DVec3, n: usize) -> Result<Vec<usize>, SilhouetteError> {
        let length = direction.length();
        if !(length.is_finite() && length > 0.0) {
            return Err(SilhouetteError::InvalidDirection {
                direction: direction.to_array(),
            });
        }
        if n == 0 || n > self.len() {
            return Err(SilhouetteError::InvalidNearest {
                asked: n,
                available: self.len(),
            });
        }
        let direction = direction / length;
        let candidates = if n <= 8 {
            self.neighbourhood(direction, 1 + n.div_ceil(2))
        } else {
            (0..self.len()).collect()
        };
        let mut sorted = self.by_angle(direction, candidates);
        sorted.truncate(n);
        Ok(sorted)
    }
}
