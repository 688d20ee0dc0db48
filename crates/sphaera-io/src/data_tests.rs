//! Loads every mesh in `shared/data` and checks the counts of its README table.

use std::path::{Path, PathBuf};

use super::{Format, read};

/// The data folder, or `None` (with a message) when it is absent and not required.
fn data_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("SPHAERA_DATA").map_or_else(
        || PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/data")),
        PathBuf::from,
    );
    if dir.join("README.md").is_file() {
        return Some(dir);
    }
    assert!(
        std::env::var("SPHAERA_REQUIRE_DATA").as_deref() != Ok("1"),
        "SPHAERA_REQUIRE_DATA=1 but the data folder {} is missing",
        dir.display()
    );
    #[allow(clippy::print_stderr)]
    {
        eprintln!("skipping: no mesh data at {}", dir.display());
    }
    None
}

/// `(file, V (file) if listed, triangles)` for every row of the README's tables.
fn expected_counts(readme: &str) -> Vec<(String, Option<usize>, usize)> {
    let number = |cell: &str| cell.trim().replace(',', "").parse::<usize>().ok();
    let mut rows = Vec::new();
    let mut columns: Vec<String> = Vec::new();
    for line in readme.lines() {
        let cells: Vec<&str> = line
            .trim()
            .trim_matches('|')
            .split('|')
            .map(str::trim)
            .collect();
        if !line.trim_start().starts_with('|') {
            columns.clear();
            continue;
        }
        if cells.first() == Some(&"file") {
            columns = cells.iter().map(|c| (*c).to_owned()).collect();
            continue;
        }
        let Some(name) = cells
            .first()
            .and_then(|c| c.strip_prefix('`')?.strip_suffix('`'))
        else {
            continue;
        };
        let column = |title: &str| columns.iter().position(|c| c == title);
        let Some(triangles) = column("triangles").and_then(|i| number(cells[i])) else {
            continue;
        };
        let vertices = column("V (file)").and_then(|i| number(cells[i]));
        rows.push((name.to_owned(), vertices, triangles));
    }
    rows
}

/// Every mesh file under `dir`, except the robot descriptions' assets under
/// `robots/urdf/` (copies of the catalogued Franka meshes and the KUKA collision STLs,
/// laid out as their URDFs expect; the README describes them apart from the table).
fn mesh_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            if path.ends_with("robots/urdf") {
                continue;
            }
            mesh_files(&path, out);
        } else if Format::from_path(&path).is_some() {
            out.push(path);
        }
    }
}

#[test]
fn every_shared_mesh_loads_with_the_readme_counts() {
    let Some(dir) = data_dir() else { return };
    let readme = std::fs::read_to_string(dir.join("README.md")).unwrap();
    let rows = expected_counts(&readme);
    assert!(
        rows.len() >= 39,
        "only {} rows parsed from the README",
        rows.len()
    );
    let mut files = Vec::new();
    mesh_files(&dir, &mut files);
    for file in &files {
        let relative = file
            .strip_prefix(&dir)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        assert!(
            rows.iter().any(|(name, ..)| *name == relative),
            "{relative} is not in the README table"
        );
    }
    for (name, vertices, triangles) in &rows {
        let loaded = read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(loaded.mesh.triangle_count(), *triangles, "{name} triangles");
        assert_eq!(loaded.report.faces_in_file, *triangles, "{name} faces");
        assert_eq!(loaded.report.polygons_triangulated, 0, "{name}");
        if let Some(v) = vertices {
            assert_eq!(loaded.report.vertex_records, *v, "{name} vertex records");
            // Nothing is dropped: unreferenced vertices (the bunny) are kept.
            assert_eq!(loaded.mesh.vertex_count(), *v, "{name} vertices");
        }
    }
}
