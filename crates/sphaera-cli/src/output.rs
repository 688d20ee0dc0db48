//! Printing results as text or JSON.

use std::path::Path;

use anyhow::{Context, Result, bail};
use serde::Serialize;

/// Prints `value` as pretty JSON on stdout.
pub fn print_json(value: &impl Serialize) -> Result<()> {
    let text = serde_json::to_string_pretty(value).context("cannot encode the result as JSON")?;
    println!("{text}");
    Ok(())
}

/// A subcommand's result: its JSON form is its `Serialize`, its text form this.
pub trait Report: Serialize {
    /// The lines people read, ending with a newline.
    fn to_text(&self) -> String;
}

/// Prints `report` on stdout: one JSON document with `--json`, else its text.
pub fn print_report(report: &impl Report, json: bool) -> Result<()> {
    if json {
        print_json(report)
    } else {
        print!("{}", report.to_text());
        Ok(())
    }
}

/// Fails before any work when `path` cannot take an output: its folder is missing, is not
/// a folder or refuses a new file; the path is a folder; or the file is read-only (an
/// atomic write would replace it regardless, which a read-only file says not to do).
pub fn check_target(path: &Path) -> Result<()> {
    let shown = path.display();
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    match std::fs::metadata(folder) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => bail!("cannot write {shown}: {} is not a folder", folder.display()),
        Err(_) => bail!(
            "cannot write {shown}: the folder {} does not exist",
            folder.display()
        ),
    }
    if let Ok(m) = std::fs::metadata(path) {
        if m.is_dir() {
            bail!("cannot write {shown}: it is a folder");
        }
        if m.permissions().readonly() {
            bail!("cannot write {shown}: the file is read-only");
        }
    }
    // The atomic write puts a temporary file beside the target: try one now.
    let probe = folder.join(format!(".sphaera-probe-{}", std::process::id()));
    std::fs::write(&probe, b"").with_context(|| {
        format!(
            "cannot write {shown}: the folder {} refuses new files",
            folder.display()
        )
    })?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Fails before any work when the output's extension is not a format we write.
pub fn check_mesh_format(path: &Path) -> Result<()> {
    match sphaera::mesh::io::Format::from_path(path) {
        Some(sphaera::mesh::io::Format::Obj | sphaera::mesh::io::Format::Ply) => Ok(()),
        Some(format) => bail!(
            "cannot write {}: writing {format} files is not supported (use .obj or .ply)",
            path.display()
        ),
        None => bail!(
            "cannot write {}: the extension is not .obj or .ply",
            path.display()
        ),
    }
}

/// Formats a count with thousands separators: `871414` → `871,414`.
pub fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// `yes` / `no`.
pub fn yes_no(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thousands_separators() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1000), "1,000");
        assert_eq!(thousands(871_414), "871,414");
    }
}
