//! The spherized URDF: every spherized link's collision elements replaced by its spheres.

use sphaera_mesh::Sphere;

use super::{number, triple};
use crate::RobotError;
use crate::spherize::RobotSpheres;
use crate::urdf::Urdf;

/// The URDF it was read from with every spherized link's `<collision>` elements replaced
/// by one `<collision>` per sphere (`<sphere>` geometry at an `<origin>`); everything else
/// is kept byte for byte. A link spherized from its visual geometry without collision
/// elements gets the spheres before its closing tag.
///
/// # Errors
///
/// [`RobotError::Write`] when a link of `robot` is not in `urdf` (spheres of another
/// robot).
pub fn spherized_urdf(urdf: &Urdf, robot: &RobotSpheres) -> Result<String, RobotError> {
    let text = &urdf.text;
    // (start, end, replacement), in text order.
    let mut edits: Vec<(usize, usize, String)> = Vec::new();
    let by_name: std::collections::HashMap<&str, &crate::urdf::Link> =
        urdf.links.iter().map(|l| (l.name.as_str(), l)).collect();
    for spheres in &robot.links {
        let link = by_name
            .get(spheres.link.as_str())
            .ok_or_else(|| RobotError::Write {
                path: urdf.path.clone(),
                message: format!("link \"{}\" is not in the URDF", spheres.link),
            })?;
        let indent = |at: usize| -> String {
            let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
            text[line_start..at]
                .chars()
                .take_while(|c| c.is_whitespace())
                .collect()
        };
        match link.collisions.split_first() {
            Some((first, rest)) => {
                let block = collisions(&spheres.link, &spheres.spheres, &indent(first.range.start));
                edits.push((first.range.start, first.range.end, block));
                for element in rest {
                    // Remove the element with the indentation before it.
                    let start = text[..element.range.start]
                        .rfind(|c: char| !c.is_whitespace())
                        .map_or(element.range.start, |i| i + 1);
                    edits.push((start, element.range.end, String::new()));
                }
            }
            None => {
                let inner = &text[link.range.clone()];
                let Some(close) = inner.rfind("</") else {
                    continue;
                };
                let at = link.range.start + close;
                let inner_indent = format!("{}  ", indent(link.range.start));
                let block = collisions(&spheres.link, &spheres.spheres, &inner_indent);
                edits.push((at, at, format!("  {block}\n{}", indent(link.range.start))));
            }
        }
    }
    edits.sort_by_key(|e| e.0);
    let mut out = String::with_capacity(text.len());
    let mut at = 0;
    for (start, end, replacement) in edits {
        out.push_str(&text[at..start]);
        out.push_str(&replacement);
        at = end;
    }
    out.push_str(&text[at..]);
    Ok(out)
}

/// One `<collision>` per sphere, joined by newlines at `indent`.
fn collisions(link: &str, spheres: &[Sphere], indent: &str) -> String {
    let name = quick_xml::escape::escape(link);
    spheres
        .iter()
        .enumerate()
        .map(|(i, s)| {
            format!(
                "<collision name=\"{name}_sphere_{i}\"><origin xyz=\"{}\" rpy=\"0 0 0\"/><geometry><sphere radius=\"{}\"/></geometry></collision>",
                triple(s.center),
                number(s.radius)
            )
        })
        .collect::<Vec<_>>()
        .join(&format!("\n{indent}"))
}
