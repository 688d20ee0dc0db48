//! The caps on the parameters that size memory: view steps, grid resolutions, label
//! storage. Every one is checked before anything is allocated, so a typo (`--step
//! 0.00001`, `--resolution 4000000000`) is refused with an error naming the parameter
//! and its cap instead of exhausting memory.

use crate::SilhouetteError;

/// The most cells a side of a view's grid (4,096, so 16.8 million cells a view).
///
/// Checked by every function taking a `resolution` ([`crate::label_view`],
/// [`crate::Labels::compute`] through [`crate::LabelOptions::resolution`],
/// [`crate::coverage`], [`crate::shaded_picture`], [`crate::FaceGrid::new`]): beyond it
/// they return [`SilhouetteError::InvalidParameter`] named `"resolution"`. Labelling
/// keeps about 10 bytes per cell per worker thread (170 MB a thread at the cap), a
/// shaded picture about 19 bytes per cell.
pub const MAX_RESOLUTION: usize = 4096;

/// The most views of a [`crate::ViewSet`] (32,768).
///
/// [`crate::ViewSet::regular`] refuses a step that would give more: a step below
/// 180° / 128 = 1.40625° (which gives 32,514 views) is
/// [`SilhouetteError::InvalidParameter`] named `"step"`.
pub const MAX_VIEWS: usize = 32_768;

/// The most labels (vertices × views) [`crate::Labels::compute`] stores: 2²⁹, 1 GiB of
/// `u16`.
///
/// Beyond it [`crate::Labels::compute`] returns [`SilhouetteError::InvalidParameter`]
/// named `"vertices × views"` before allocating: label fewer views (a larger step) or a
/// simpler mesh. The 69k-vertex bunny at the default 15° (266 views) needs 18 million
/// labels.
pub const MAX_LABELS: usize = 1 << 29;

/// The most (face, cell) pairs a [`crate::FaceGrid`] lists: 2²⁸, 1 GiB of `u32`.
///
/// Beyond it [`crate::FaceGrid::new`] returns [`SilhouetteError::InvalidParameter`] named
/// `"faces × cells"`, as soon as the count passes it (before the list is allocated).
pub const MAX_FACE_GRID_ENTRIES: usize = 1 << 28;

/// The most intervals of 180° a regular view set may have: `2 + (k − 1) · 2k` views
/// for `k` intervals stay within [`MAX_VIEWS`] up to `k = 128`.
pub(crate) const MAX_INTERVALS: usize = 128;

/// `Ok` for a resolution of 1 to [`MAX_RESOLUTION`] cells a side.
pub(crate) fn check_resolution(resolution: usize) -> Result<(), SilhouetteError> {
    if resolution == 0 {
        return Err(SilhouetteError::InvalidResolution { resolution });
    }
    if resolution > MAX_RESOLUTION {
        return Err(SilhouetteError::InvalidParameter {
            name: "resolution",
            value: resolution as f64,
            requirement: "at most `MAX_RESOLUTION` (4,096 cells a side)",
        });
    }
    Ok(())
}

/// `Ok` if `vertices × views` labels fit [`MAX_LABELS`].
pub(crate) fn check_label_count(vertices: usize, views: usize) -> Result<(), SilhouetteError> {
    match vertices.checked_mul(views) {
        Some(labels) if labels <= MAX_LABELS => Ok(()),
        _ => Err(SilhouetteError::InvalidParameter {
            name: "vertices × views",
            value: vertices as f64 * views as f64,
            requirement: "at most `MAX_LABELS` (2^29 labels, 1 GiB): use fewer views (a \
                          larger step) or a simpler mesh",
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_regular_set_fits_the_view_cap() {
        let views = |k: usize| 2 + (k - 1) * 2 * k;
        assert!(views(MAX_INTERVALS) <= MAX_VIEWS);
        assert!(views(MAX_INTERVALS + 1) > MAX_VIEWS);
    }

    #[test]
    fn label_counts_that_overflow_are_refused() {
        assert!(check_label_count(usize::MAX, 2).is_err());
        assert!(check_label_count(MAX_LABELS, 1).is_ok());
        assert!(check_label_count(MAX_LABELS / 2 + 1, 2).is_err());
    }
}
