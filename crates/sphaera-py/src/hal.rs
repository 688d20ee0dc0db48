//! HAL trees (Veltkamp) as Python classes: a closed outline or an open polyline in the
//! plane, and a closed genus-0 mesh, with point inclusion over numpy arrays (GIL
//! released) and intersection, as shapely users expect of a prepared geometry.

use numpy::PyArray1;
use pyo3::prelude::*;
use sphaera::hal::{Containment, HalTree2 as Tree2, HalTree3 as Tree3, Polyline2};
use sphaera::mesh::geometry::Similarity;

use crate::arrays;
use crate::errors::{IntoPy, value_error};
use crate::mesh::Mesh;

/// What `HalTree2.__reduce__` returns: the class and its constructor's arguments.
type Reduced2<'py> = (Bound<'py, PyAny>, (Bound<'py, numpy::PyArray2<f64>>, bool));

/// What `HalTree2.nearest_edge` returns: distances, edges and nearest points.
type NearestArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<i64>>,
    Bound<'py, numpy::PyArray2<f64>>,
);

/// 1 inside, 0 on the boundary, −1 outside.
pub fn code(c: Containment) -> i8 {
    match c {
        Containment::Inside => 1,
        Containment::Boundary => 0,
        Containment::Outside => -1,
    }
}

/// A 2D HAL tree over `points` (`(n, 2)`): a closed outline (`closed=True`, the default;
/// the last point joins the first) or an open polyline.
///
/// `contains(points)` answers every point of an `(m, 2)` array exactly: an `int8` array of
/// 1 (inside), 0 (on an edge or a vertex) and −1 (outside), with the GIL released.
/// `intersects(other)` says whether two outlines (or polylines) meet, solids included.
///
/// Raises `ValueError` for fewer than 3 points of a closed outline (2 of a polyline),
/// repeated consecutive points or points that are not finite.
#[pyclass(module = "sphaera", frozen)]
pub struct HalTree2 {
    inner: Tree2,
}

impl HalTree2 {
    /// The tree.
    pub fn tree(&self) -> &Tree2 {
        &self.inner
    }
}

#[pymethods]
impl HalTree2 {
    #[new]
    #[pyo3(signature = (points, closed=true))]
    fn new(py: Python<'_>, points: &Bound<'_, PyAny>, closed: bool) -> PyResult<Self> {
        let points = arrays::points2(points, "points")?;
        let inner = py
            .detach(|| {
                let outline = if closed {
                    Polyline2::polygon(points)
                } else {
                    Polyline2::open(points)
                }?;
                Tree2::build(&outline)
            })
            .py_err()?;
        Ok(Self { inner })
    }

    /// Whether the tree is over a closed outline.
    #[getter]
    fn closed(&self) -> bool {
        self.inner.polyline().is_closed()
    }

    /// The tree's deepest level.
    #[getter]
    fn depth(&self) -> usize {
        self.inner.depth()
    }

    /// The outline's points, `(n, 2)`.
    fn points<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<f64>> {
        let flat: Vec<f64> = self
            .inner
            .polyline()
            .points()
            .iter()
            .flat_map(|p| [p.x, p.y])
            .collect();
        arrays::rows(py, flat, 2)
    }

    /// Point inclusion for every row of `points` (`(m, 2)`): 1 inside, 0 on the
    /// boundary, −1 outside (`int8`). Raises `ValueError` for an open polyline.
    fn contains<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        if !self.inner.polyline().is_closed() {
            return Err(value_error(
                "an open polyline has no inside: build the tree with closed=True",
            ));
        }
        let queries = arrays::points2(points, "points")?;
        let tree = &self.inner;
        let answers: Result<Vec<i8>, _> = py.detach(|| {
            queries
                .iter()
                .map(|&x| tree.contains(x).map(code))
                .collect()
        });
        Ok(arrays::vector(py, answers.py_err()?))
    }

    /// Whether this outline and `other` meet (edges crossing or touching, or one lying
    /// inside the other's closed outline: GEOS's `intersects`).
    fn intersects(&self, py: Python<'_>, other: &HalTree2) -> bool {
        py.detach(|| self.inner.intersects(&other.inner))
    }

    /// Every pair of intersecting edges, `(k, 2)` `int64` rows: an edge here, one of
    /// `other` (edge `i` runs from point `i` to the next).
    fn intersecting_edges<'py>(
        &self,
        py: Python<'py>,
        other: &HalTree2,
    ) -> Bound<'py, numpy::PyArray2<i64>> {
        let pairs = py.detach(|| self.inner.intersecting_edges(&other.inner));
        let flat: Vec<i64> = pairs
            .into_iter()
            .flat_map(|(i, j)| [i as i64, j as i64])
            .collect();
        arrays::rows(py, flat, 2)
    }

    /// The nearest edge to every row of `points` (`(m, 2)`): `(distance, edge, point)`
    /// arrays (`float64`, `int64`, `(m, 2)`).
    fn nearest_edge<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<NearestArrays<'py>> {
        let queries = arrays::points2(points, "points")?;
        let tree = &self.inner;
        let nearest: Vec<_> = py.detach(|| queries.iter().map(|&x| tree.nearest_edge(x)).collect());
        let distance: Vec<f64> = nearest.iter().map(|n| n.distance).collect();
        let edge: Vec<i64> = nearest.iter().map(|n| n.edge as i64).collect();
        let point: Vec<f64> = nearest
            .iter()
            .flat_map(|n| [n.point.x, n.point.y])
            .collect();
        Ok((
            arrays::vector(py, distance),
            arrays::vector(py, edge),
            arrays::rows(py, point, 2),
        ))
    }

    fn __len__(&self) -> usize {
        self.inner.polyline().points().len()
    }

    fn __repr__(&self) -> String {
        format!(
            "HalTree2({} points, {}, depth {})",
            self.inner.polyline().points().len(),
            if self.closed() { "closed" } else { "open" },
            self.inner.depth()
        )
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>, py: Python<'py>) -> PyResult<Reduced2<'py>> {
        let this = slf.get();
        Ok((slf.get_type().into_any(), (this.points(py), this.closed())))
    }
}

/// A 3D HAL tree over a closed, manifold, genus-0 `mesh`.
///
/// `contains(points)` answers every point of an `(m, 3)` array exactly: an `int8` array of
/// 1 (inside), 0 (on the surface) and −1 (outside), with the GIL released.
/// `intersects(other)` says whether the two solids meet.
///
/// Raises `ValueError` for a mesh that is not closed, manifold, one piece and genus 0.
#[pyclass(module = "sphaera", frozen)]
pub struct HalTree3 {
    inner: Tree3,
    mesh: Py<Mesh>,
}

#[pymethods]
impl HalTree3 {
    #[new]
    fn new(py: Python<'_>, mesh: Bound<'_, Mesh>) -> PyResult<Self> {
        let inner = {
            let m = &mesh.get().inner;
            py.detach(|| Tree3::build(m)).py_err()?
        };
        Ok(Self {
            inner,
            mesh: mesh.unbind(),
        })
    }

    /// The mesh the tree was built on.
    #[getter]
    fn mesh(&self, py: Python<'_>) -> Py<Mesh> {
        self.mesh.clone_ref(py)
    }

    /// The tree's deepest level.
    #[getter]
    fn depth(&self) -> u32 {
        self.inner.depth()
    }

    /// Point inclusion for every row of `points` (`(m, 3)`): 1 inside, 0 on the surface,
    /// −1 outside (`int8`).
    fn contains<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        let queries = arrays::points(points, "points", true)?;
        let tree = &self.inner;
        let answers: Vec<i8> =
            py.detach(|| queries.iter().map(|&x| code(tree.contains(x))).collect());
        Ok(arrays::vector(py, answers))
    }

    /// Whether this solid and `other`'s meet.
    fn intersects(&self, py: Python<'_>, other: &HalTree3) -> bool {
        py.detach(|| self.inner.intersects(&other.inner, &Similarity::IDENTITY))
    }

    /// Every pair of faces that meet, `(k, 2)` `int64` rows: a face of this mesh, one of
    /// `other`'s.
    fn intersecting_faces<'py>(
        &self,
        py: Python<'py>,
        other: &HalTree3,
    ) -> Bound<'py, numpy::PyArray2<i64>> {
        let pairs = py.detach(|| {
            self.inner
                .intersecting_faces(&other.inner, &Similarity::IDENTITY)
        });
        let flat: Vec<i64> = pairs
            .into_iter()
            .flat_map(|(i, j)| [i as i64, j as i64])
            .collect();
        arrays::rows(py, flat, 2)
    }

    /// The nearest face to every row of `points` (`(m, 3)`): `(distance, face, point)`
    /// arrays (`float64`, `int64`, `(m, 3)`).
    fn nearest_face<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<NearestArrays<'py>> {
        let queries = arrays::points(points, "points", true)?;
        let tree = &self.inner;
        let nearest: Option<Vec<_>> = py.detach(|| {
            queries
                .iter()
                .map(|&x| tree.nearest_face(x))
                .collect::<Option<Vec<_>>>()
        });
        // The points are finite (checked above), so every query has an answer.
        let nearest = nearest.ok_or_else(|| value_error("points: not finite"))?;
        let distance: Vec<f64> = nearest.iter().map(|n| n.distance).collect();
        let face: Vec<i64> = nearest.iter().map(|n| n.face as i64).collect();
        let point: Vec<f64> = nearest.iter().flat_map(|n| n.point.to_array()).collect();
        Ok((
            arrays::vector(py, distance),
            arrays::vector(py, face),
            arrays::rows(py, point, 3),
        ))
    }

    fn __repr__(&self) -> String {
        format!(
            "HalTree3({} triangles, depth {})",
            self.inner.mesh().triangle_count(),
            self.inner.depth()
        )
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (Py<Mesh>,))> {
        Ok((slf.get_type().into_any(), (slf.get().mesh.clone_ref(py),)))
    }
}
