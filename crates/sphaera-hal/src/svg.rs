//! A HAL approximation drawn as SVG: the outline in grey, the approximation in blue, and
//! the bounding area of each edge that is not original, shaded (the paper's Figs. 4 and 6).

use std::fmt::Write as _;

use glam::DVec2;

use crate::{Approximation, HalTree2, Node2};

/// The SVG drawing of `approximation` of `tree`'s outline, 1000 units across, y up.
///
/// # Examples
///
/// ```
/// use sphaera_hal::{HalTree2, Polyline2, approximation_svg, parse_points};
///
/// let outline = Polyline2::polygon(parse_points("0 0\n4 0\n4 1\n2 3\n0 1\n")?)?;
/// let tree = HalTree2::build(&outline)?;
/// let svg = approximation_svg(&tree, &tree.approximate(0.5));
/// assert!(svg.starts_with("<svg ") && svg.trim_end().ends_with("</svg>"));
/// # Ok::<(), sphaera_hal::HalError>(())
/// ```
#[must_use]
pub fn approximation_svg(tree: &HalTree2, approximation: &Approximation) -> String {
    let points = tree.polyline().points();
    let (lo, hi) = tree.polyline().bounds();
    let size = (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let margin = 0.05 * size;
    let scale = 1000.0 / (size + 2.0 * margin);
    let map = |p: DVec2| ((p.x - lo.x + margin) * scale, (hi.y - p.y + margin) * scale);
    let path = |vertices: &mut dyn Iterator<Item = DVec2>, close: bool| {
        let mut d = String::new();
        for (k, p) in vertices.enumerate() {
            let (x, y) = map(p);
            let _ = write!(d, "{}{x:.2},{y:.2} ", if k == 0 { "M" } else { "L" });
        }
        if close {
            d.push('Z');
        }
        d
    };
    let width = (hi.x - lo.x + 2.0 * margin) * scale;
    let height = (hi.y - lo.y + 2.0 * margin) * scale;
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width:.1} {height:.1}" width="{width:.0}" height="{height:.0}">"#
    );
    let _ = writeln!(
        out,
        r##"<rect width="100%" height="100%" fill="#ffffff"/>"##
    );
    for &id in &approximation.frontier {
        let Some(node) = tree.nodes().get(id) else {
            continue;
        };
        let outline = lens_outline(tree, node);
        if !outline.is_empty() {
            let _ = writeln!(
                out,
                r##"<path d="{}" fill="#f4a261" fill-opacity="0.25" stroke="#e76f51" stroke-width="0.6"/>"##,
                path(&mut outline.into_iter(), true)
            );
        }
    }
    let closed = tree.polyline().is_closed();
    let _ = writeln!(
        out,
        r##"<path d="{}" fill="none" stroke="#8d99ae" stroke-width="0.8"/>"##,
        path(&mut points.iter().copied(), closed)
    );
    let _ = writeln!(
        out,
        r##"<path d="{}" fill="none" stroke="#1d3557" stroke-width="1.4"/>"##,
        path(
            &mut approximation
                .vertices
                .iter()
                .filter_map(|&v| points.get(v).copied()),
            closed
        )
    );
    let _ = writeln!(out, "</svg>");
    out
}

/// The boundary of a node's bounding area as a polygon: the left disc's arc from the
/// chord's start to its end, then the right disc's arc back (a side without vertices is
/// the chord itself). Empty for an unbounded area (a half-plane on a vertex's side).
fn lens_outline(tree: &HalTree2, node: &Node2) -> Vec<DVec2> {
    let (a, b) = (tree.point_at(node.first), tree.point_at(node.last));
    let (w1, w2) = node.lens.widths(a, b);
    if !(w1.is_finite() && w2.is_finite()) || a == b {
        return Vec::new();
    }
    let normal = (b - a).perp().normalize();
    let middle = a.midpoint(b);
    let mut outline = arc(a, b, middle + normal * w1);
    outline.extend(arc(b, a, middle - normal * w2).into_iter().skip(1));
    outline
}

/// Points along the circle through `from`, `apex` and `to`, from `from` to `to` through
/// `apex` (the straight segment when the three are collinear).
fn arc(from: DVec2, to: DVec2, apex: DVec2) -> Vec<DVec2> {
    let Some(center) = circumcenter(from, to, apex) else {
        return vec![from, to];
    };
    let radius = center.distance(from);
    let angle = |p: DVec2| (p - center).to_angle();
    let tau = std::f64::consts::TAU;
    let turn = |x: f64| (x - angle(from)).rem_euclid(tau);
    let (to_end, to_apex) = (turn(angle(to)), turn(angle(apex)));
    let sweep = if to_apex <= to_end {
        to_end
    } else {
        to_end - tau
    };
    (0..=32)
        .map(|k| {
            let t = angle(from) + sweep * f64::from(k) / 32.0;
            center + DVec2::from_angle(t) * radius
        })
        .collect()
}

/// The center of the circle through three points, if they are not collinear.
fn circumcenter(a: DVec2, b: DVec2, c: DVec2) -> Option<DVec2> {
    let (ab, ac) = (b - a, c - a);
    let d = 2.0 * ab.perp_dot(ac);
    if d.abs() <= 1e-14 * ab.length_squared().max(ac.length_squared()) {
        return None;
    }
    let (lb, lc) = (ab.length_squared(), ac.length_squared());
    Some(a + DVec2::new(ac.y * lb - ab.y * lc, ab.x * lc - ac.x * lb) / d)
}
