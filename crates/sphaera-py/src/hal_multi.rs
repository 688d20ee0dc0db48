//! Polygons with holes and multipolygons as a Python class: point inclusion that says
//! where, the nearest edge, and intersection, over numpy arrays with the GIL released.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use sphaera::hal::{HalMultiPolygon2 as Tree, MultiPolygon2, RingEdge};
use sphaera::mesh::glam::DVec2;
use sphaera::mesh::io::{ShapeFormat, parse_shapes};

use crate::arrays;
use crate::errors::{IntoPy, value_error};
use crate::hal::{HalTree2, code};

/// What `HalMultiPolygon2.__reduce__` returns: the class and its rings.
type Reduced<'py> = (Bound<'py, PyAny>, (Bound<'py, PyList>,));

/// HAL trees over every ring of polygons with holes: a country with its islands and
/// lakes, one answer for the whole, as GEOS and shapely give it.
///
/// `polygons` is a list of polygons, each a list of rings (`(n, 2)` arrays or nested
/// lists), the exterior first and then the holes: GeoJSON's layout (a repeated closing
/// point is dropped). `from_geojson(text)` and `from_wkt(text)` read their polygons.
/// Rings of fewer than three distinct points bound no area and are dropped
/// (`dropped_rings` lists them as `(polygon, ring)`).
///
/// `contains(points)` gives `int8`: 1 inside, 0 on a ring, −1 outside; `locate(points)`
/// adds the ring holding each point; `nearest_edge(points)` the nearest edge and its
/// distance; `intersects(other)` (another multipolygon or a `HalTree2`) and
/// `intersecting_edges(other)` compare two shapes. The GIL is released during queries.
#[pyclass(module = "sphaera", frozen)]
pub struct HalMultiPolygon2 {
    inner: Tree,
    dropped: Vec<(usize, usize)>,
}

/// `(m,)` arrays of ring ids: polygon and ring, −1 for none.
fn ring_columns(ids: impl Iterator<Item = Option<(usize, usize)>>) -> (Vec<i64>, Vec<i64>) {
    ids.map(|id| id.map_or((-1, -1), |(p, r)| (p as i64, r as i64)))
        .unzip()
}

impl HalMultiPolygon2 {
    fn from_rings(py: Python<'_>, rings: Vec<Vec<Vec<DVec2>>>) -> PyResult<Self> {
        let (inner, dropped) = py
            .detach(|| {
                let (shape, dropped) = MultiPolygon2::from_rings_dropping_degenerate(rings)?;
                Tree::build(&shape).map(|tree| (tree, dropped))
            })
            .py_err()?;
        Ok(Self {
            inner,
            dropped: dropped.iter().map(|r| (r.polygon, r.ring)).collect(),
        })
    }

    fn from_text(py: Python<'_>, text: &str, format: ShapeFormat) -> PyResult<Self> {
        let shapes = parse_shapes(text, format).py_err()?;
        if shapes.polygons.is_empty() {
            return Err(value_error(format!("the {format} text holds no polygon")));
        }
        Self::from_rings(py, shapes.polygons)
    }
}

#[pymethods]
impl HalMultiPolygon2 {
    #[new]
    fn new(py: Python<'_>, polygons: &Bound<'_, PyAny>) -> PyResult<Self> {
        let mut rings = Vec::new();
        for (i, polygon) in polygons.try_iter()?.enumerate() {
            let mut out = Vec::new();
            for (j, ring) in polygon?.try_iter()?.enumerate() {
                out.push(arrays::points2(&ring?, &format!("polygon {i}, ring {j}"))?);
            }
            rings.push(out);
        }
        Self::from_rings(py, rings)
    }

    /// The polygons of a GeoJSON text (a geometry, a feature or a feature collection).
    #[staticmethod]
    fn from_geojson(py: Python<'_>, text: &str) -> PyResult<Self> {
        Self::from_text(py, text, ShapeFormat::GeoJson)
    }

    /// The polygons of a WKT text.
    #[staticmethod]
    fn from_wkt(py: Python<'_>, text: &str) -> PyResult<Self> {
        Self::from_text(py, text, ShapeFormat::Wkt)
    }

    /// The number of polygons.
    #[getter]
    fn polygon_count(&self) -> usize {
        self.inner.polygon_count()
    }

    /// The rings dropped as bounding no area, as `(polygon, ring)` in the input's
    /// numbering.
    #[getter]
    fn dropped_rings(&self) -> Vec<(usize, usize)> {
        self.dropped.clone()
    }

    /// Every polygon's rings as `(n, 2)` arrays, the exterior first.
    fn polygons<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let out = PyList::empty(py);
        let mut current: Option<Bound<'py, PyList>> = None;
        for (id, tree) in self.inner.rings() {
            if id.ring == 0 {
                if let Some(done) = current.take() {
                    out.append(done)?;
                }
                current = Some(PyList::empty(py));
            }
            let flat: Vec<f64> = tree
                .polyline()
                .points()
                .iter()
                .flat_map(|p| [p.x, p.y])
                .collect();
            if let Some(list) = &current {
                list.append(arrays::rows(py, flat, 2))?;
            }
        }
        if let Some(done) = current {
            out.append(done)?;
        }
        Ok(out)
    }

    /// Point inclusion for every row of `points` (`(m, 2)`): 1 inside, 0 on a ring, −1
    /// outside (`int8`).
    fn contains<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        let queries = arrays::points2(points, "points")?;
        let tree = &self.inner;
        let answers: Vec<i8> =
            py.detach(|| queries.iter().map(|&x| code(tree.contains(x))).collect());
        Ok(arrays::vector(py, answers))
    }

    /// Inclusion that says where, for every row of `points`: a dict of `containment`
    /// (`int8` as `contains`), and `polygon` and `ring` (`int64`; ring 0 the exterior,
    /// `k` the hole `k − 1`) of the innermost ring holding the point: the polygon's
    /// exterior inside, the ring it lies on, the hole (lake) it is in; −1 for none.
    fn locate<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let queries = arrays::points2(points, "points")?;
        let tree = &self.inner;
        let located: Vec<_> = py.detach(|| queries.iter().map(|&x| tree.locate(x)).collect());
        let containment: Vec<i8> = located.iter().map(|l| code(l.containment)).collect();
        let (polygon, ring) =
            ring_columns(located.iter().map(|l| l.ring.map(|r| (r.polygon, r.ring))));
        let out = PyDict::new(py);
        out.set_item("containment", arrays::vector(py, containment))?;
        out.set_item("polygon", arrays::vector(py, polygon))?;
        out.set_item("ring", arrays::vector(py, ring))?;
        Ok(out)
    }

    /// The nearest edge to every row of `points`: a dict of `distance` (`float64`),
    /// `polygon`, `ring`, `edge` (`int64`; edge `i` runs from the ring's vertex `i` to the
    /// next) and `point` (`(m, 2)`, the edge's nearest point).
    fn nearest_edge<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let queries = arrays::points2(points, "points")?;
        let tree = &self.inner;
        let nearest: Vec<_> = py.detach(|| queries.iter().map(|&x| tree.nearest_edge(x)).collect());
        let out = PyDict::new(py);
        let distance: Vec<f64> = nearest.iter().map(|n| n.distance).collect();
        let (polygon, ring) = ring_columns(
            nearest
                .iter()
                .map(|n| Some((n.at.ring.polygon, n.at.ring.ring))),
        );
        let edge: Vec<i64> = nearest.iter().map(|n| n.at.edge as i64).collect();
        let point: Vec<f64> = nearest
            .iter()
            .flat_map(|n| [n.point.x, n.point.y])
            .collect();
        out.set_item("distance", arrays::vector(py, distance))?;
        out.set_item("polygon", arrays::vector(py, polygon))?;
        out.set_item("ring", arrays::vector(py, ring))?;
        out.set_item("edge", arrays::vector(py, edge))?;
        out.set_item("point", arrays::rows(py, point, 2))?;
        Ok(out)
    }

    /// Whether the regions meet (GEOS's `intersects`): `other` a `HalMultiPolygon2`, or a
    /// `HalTree2` (a polyline inside a polygon meets it).
    fn intersects(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        if let Ok(multi) = other.cast::<HalMultiPolygon2>() {
            let other = &multi.get().inner;
            return Ok(py.detach(|| self.inner.intersects(other)));
        }
        if let Ok(tree) = other.cast::<HalTree2>() {
            let other = tree.get().tree();
            return Ok(py.detach(|| self.inner.intersects_outline(other)));
        }
        Err(value_error(
            "other: expected a HalMultiPolygon2 or a HalTree2",
        ))
    }

    /// Every pair of intersecting edges, `(k, 6)` `int64` rows: polygon, ring and edge
    /// here, then polygon, ring and edge of `other` (a `HalMultiPolygon2`; for a
    /// `HalTree2`, `-1, -1` and its edge).
    fn intersecting_edges<'py>(
        &self,
        py: Python<'py>,
        other: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let row = |a: RingEdge| [a.ring.polygon as i64, a.ring.ring as i64, a.edge as i64];
        let flat: Vec<i64> = if let Ok(multi) = other.cast::<HalMultiPolygon2>() {
            let other = &multi.get().inner;
            let pairs = py.detach(|| self.inner.intersecting_edges(other));
            pairs
                .into_iter()
                .flat_map(|(a, b)| row(a).into_iter().chain(row(b)))
                .collect()
        } else if let Ok(tree) = other.cast::<HalTree2>() {
            let other = tree.get().tree();
            let pairs = py.detach(|| self.inner.intersecting_outline_edges(other));
            pairs
                .into_iter()
                .flat_map(|(a, j)| row(a).into_iter().chain([-1, -1, j as i64]))
                .collect()
        } else {
            return Err(value_error(
                "other: expected a HalMultiPolygon2 or a HalTree2",
            ));
        };
        Ok(arrays::rows(py, flat, 6))
    }

    fn __len__(&self) -> usize {
        self.inner.polygon_count()
    }

    fn __repr__(&self) -> String {
        let rings = self.inner.rings().count();
        format!(
            "HalMultiPolygon2({} polygons, {} holes)",
            self.inner.polygon_count(),
            rings - self.inner.polygon_count()
        )
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>, py: Python<'py>) -> PyResult<Reduced<'py>> {
        Ok((slf.get_type().into_any(), (slf.get().polygons(py)?,)))
    }
}
