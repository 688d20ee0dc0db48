//! The page: the template with three.js, the data and the page's script put in.
//!
//! Every array goes in as base64 of little-endian typed arrays (`f32` positions and
//! spheres, `u32` triangles, `u8` colours and grey levels), in page units: moved so that
//! the mesh's bounding box is centred on the origin and scaled so that the mesh reaches
//! to radius 1. A mesh of any size (10⁻⁴⁰ or 10⁴⁰) thus keeps `f32`'s full precision, and
//! the page of a mesh scaled by a power of two is the same page. A point `q` of the page
//! is `offset + scale · q` of the mesh.

use base64::Engine as _;
use serde::Serialize;
use sphaera::mesh::io::colormap;
use sphaera::mesh::{DVec3, Sphere, TriMesh};

use super::layers::{DistanceField, LabelField, Layer, LayerKind};
use super::tree::{Evaluation, largest};

/// three.js 0.160.1 (MIT; `assets/three/LICENSE`), the single-file ES module.
pub(super) const THREE_JS: &str = include_str!("../../../assets/three/three.module.min.js");
/// The page around the data and the scripts.
const TEMPLATE: &str = include_str!("../../../assets/view/view.html");
/// What every page's script starts with (three.js imported, the data, decoders, the
/// renderer and the orbiting camera).
pub(super) const STAGE_JS: &str = include_str!("../../../assets/view/stage.js");
/// The page's own script.
const VIEW_JS: &str = include_str!("../../../assets/view/view.js");

/// Everything the page shows.
pub struct Contents<'a> {
    pub name: &'a str,
    pub mesh: &'a TriMesh,
    pub levels: &'a [Vec<Sphere>],
    pub evaluations: &'a [Option<Evaluation>],
    pub layers: &'a [Layer],
    pub distance: Option<&'a DistanceField>,
    pub labels: Option<&'a LabelField>,
}

#[derive(Serialize)]
struct PageLevel {
    count: usize,
    /// `x, y, z, r` per sphere, f32, base64.
    spheres: String,
    /// The index of the sphere reaching farthest beyond the surface (certified), or the
    /// largest sphere when there is no surface to measure against.
    worst: usize,
    error_lower: Option<f64>,
    error_upper: Option<f64>,
}

#[derive(Serialize)]
struct PageMesh {
    triangles_count: usize,
    positions: String,
    triangles: String,
}

#[derive(Serialize)]
struct PageLayer {
    kind: LayerKind,
    label: String,
    /// `None` when unbounded.
    bound: Option<f64>,
    #[serde(flatten)]
    mesh: PageMesh,
}

pub(super) fn base64_of(bytes: &[u8]) -> String {
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

pub(super) fn f32_base64(values: impl Iterator<Item = f64>) -> String {
    let bytes: Vec<u8> = values.flat_map(|v| (v as f32).to_le_bytes()).collect();
    base64_of(&bytes)
}

/// Mesh coordinates to page units: `(p − center) / scale`.
#[derive(Clone, Copy)]
struct Units {
    center: DVec3,
    scale: f64,
}

impl Units {
    fn point(self, p: DVec3) -> [f64; 3] {
        ((p - self.center) / self.scale).to_array()
    }
}

/// A mesh's arrays, in page units.
fn page_mesh(mesh: &TriMesh, units: Units) -> PageMesh {
    let triangles: Vec<u8> = mesh
        .triangles()
        .iter()
        .flatten()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    PageMesh {
        triangles_count: mesh.triangle_count(),
        positions: f32_base64(mesh.positions().iter().flat_map(|&p| units.point(p))),
        triangles: base64_of(&triangles),
    }
}

/// The colour scale's stops, from 0 to 1, as CSS colours.
fn legend_stops() -> Vec<String> {
    (0..=10)
        .map(|k| {
            let [r, g, b] = colormap::blue_to_red(f64::from(k) / 10.0);
            format!("#{r:02x}{g:02x}{b:02x}")
        })
        .collect()
}

/// The whole page.
pub fn page(contents: &Contents<'_>) -> String {
    let mesh = contents.mesh;
    let center = mesh.bounding_box().center();
    let radius = mesh
        .positions()
        .iter()
        .map(|p| p.distance(center))
        .fold(0.0, f64::max);
    // A mesh of one point (no extent) keeps its scale.
    let scale = if radius > 0.0 && radius.is_finite() {
        radius
    } else {
        1.0
    };
    let units = Units { center, scale };
    let levels: Vec<PageLevel> = contents
        .levels
        .iter()
        .zip(contents.evaluations)
        .map(|(spheres, evaluation)| PageLevel {
            count: spheres.len(),
            spheres: f32_base64(spheres.iter().flat_map(|s| {
                let [x, y, z] = units.point(s.center);
                [x, y, z, s.radius / scale]
            })),
            worst: evaluation.map_or_else(|| largest(spheres), |e| e.worst),
            error_lower: evaluation.map(|e| e.lower),
            error_upper: evaluation.map(|e| e.upper),
        })
        .collect();
    let layers: Vec<PageLayer> = contents
        .layers
        .iter()
        .map(|layer| PageLayer {
            kind: layer.kind,
            label: layer.label.clone(),
            bound: layer.bound.is_finite().then_some(layer.bound),
            mesh: page_mesh(&layer.mesh, units),
        })
        .collect();
    let distance = contents.distance.map(|field| {
        let (farthest, closest) = field.farthest();
        let colors: Vec<u8> = field.colors().into_iter().flatten().collect();
        let moved = |p: [f64; 3]| units.point(DVec3::from_array(p));
        serde_json::json!({
            "other_name": field.other_name,
            "other": page_mesh(&field.other, units),
            "colors": base64_of(&colors),
            "lower": field.distance.lower,
            "upper": field.distance.upper,
            "mesh_to_other_upper": field.distance.a_to_b.upper,
            "dominating": field.dominating(),
            "farthest": moved(farthest),
            "closest": moved(closest),
            "legend": legend_stops(),
        })
    });
    let labels = contents.labels.map(|field| {
        serde_json::json!({
            "directions": f32_base64(field.directions.iter().flatten().copied()),
            "count": field.directions.len(),
            "grey": base64_of(&field.grey),
            "scale": field.scale,
            "step_degrees": field.step_degrees,
            "resolution": field.resolution,
        })
    });
    let data = serde_json::json!({
        "name": contents.name,
        "diagonal": mesh.bounding_box_diagonal(),
        "radius": 1.0,
        "offset": center.to_array(),
        "scale": scale,
        "mesh": page_mesh(mesh, units),
        "levels": levels,
        "layers": layers,
        "distance": distance,
        "labels": labels,
    });
    let data = script_json(&data.to_string());
    fill(
        TEMPLATE,
        &[
            (
                "SPHAERA_TITLE",
                &html_escape(&format!("sphaera view: {}", contents.name)),
            ),
            ("SPHAERA_THREE_BASE64", &base64_of(THREE_JS.as_bytes())),
            ("SPHAERA_DATA", &data),
            ("SPHAERA_VIEW_JS", &format!("{STAGE_JS}\n{VIEW_JS}")),
        ],
    )
}

/// `template` with each placeholder replaced by its value, in one pass (a value that
/// holds a placeholder's name, such as a file name, is left as it is).
pub(super) fn fill(template: &str, values: &[(&str, &str)]) -> String {
    let mut out =
        String::with_capacity(template.len() + values.iter().map(|v| v.1.len()).sum::<usize>());
    let mut rest = template;
    while let Some((at, key, value)) = values
        .iter()
        .filter_map(|&(key, value)| rest.find(key).map(|at| (at, key, value)))
        .min_by_key(|&(at, _, _)| at)
    {
        out.push_str(&rest[..at]);
        out.push_str(value);
        rest = &rest[at + key.len()..];
    }
    out.push_str(rest);
    out
}

/// `text` as HTML text or a quoted attribute value.
pub(super) fn html_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&#39;")
}

/// JSON text made safe as the data of a `<script type="application/json">` element: `<`,
/// `>` and `&` only occur inside JSON strings, where `\u003c`, `\u003e` and `\u0026` mean
/// the same, so no `</script>`, `<!--` or `<script` can close the element or switch the
/// HTML parser into its escaped states (which would swallow the page's own script); the
/// line and paragraph separators, legal in JSON strings but not in older JavaScript, are
/// escaped too. `JSON.parse` gives back the same value.
pub(crate) fn script_json(json: &str) -> String {
    let mut out = String::with_capacity(json.len());
    for c in json.chars() {
        match c {
            '<' => out.push_str("\\u003c"),
            '>' => out.push_str("\\u003e"),
            '&' => out.push_str("\\u0026"),
            '\u{2028}' => out.push_str("\\u2028"),
            '\u{2029}' => out.push_str("\\u2029"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{html_escape, script_json};

    /// Hostile names survive the round trip through a page's script data, and leave no
    /// character that HTML's script-data states react to.
    #[test]
    fn script_data_holds_any_name_and_no_markup() {
        for name in [
            "x</script><script>alert(1)</script>",
            "x<!--<script>y.obj",
            "\"quoted\" & 'single' > <",
            "line\nbreak\r\n\ttab \u{2028}\u{2029}",
            "back\\slash \\u003c \\</script>",
            "\u{fffd}not utf-8\u{fffd}.obj",
        ] {
            let json = serde_json::json!({ "name": name }).to_string();
            let safe = script_json(&json);
            for bad in ['<', '>', '&', '\u{2028}', '\u{2029}'] {
                assert!(!safe.contains(bad), "{safe}");
            }
            let back: serde_json::Value = serde_json::from_str(&safe).unwrap();
            assert_eq!(back["name"], name);
            assert!(!html_escape(name).contains(['<', '>', '"', '\'']));
        }
    }
}
