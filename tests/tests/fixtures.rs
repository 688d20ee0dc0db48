//! The fixtures themselves: the data README table parses and names files that exist.

use sphaera_tests::{data_dir, expected_stats, mesh_files};

#[test]
fn data_readme_table_lists_every_mesh_file() {
    let Some(data) = data_dir("data_readme_table_lists_every_mesh_file") else {
        return;
    };
    let stats = expected_stats(&data);
    assert_eq!(stats.len(), 39, "the data README lists 39 meshes");
    let files: Vec<String> = mesh_files(&data)
        .iter()
        .map(|p| p.to_string_lossy().replace('\\', "/"))
        .collect();
    for row in &stats {
        assert!(
            files.contains(&row.file),
            "{} is listed but missing",
            row.file
        );
    }
    let bunny = stats
        .iter()
        .find(|s| s.file == "stanford-bunny.obj")
        .unwrap();
    assert_eq!(bunny.boundary_edges, 223);
    assert_eq!(bunny.genus, Some(0));
    assert_eq!(bunny.euler_characteristic, -3);
}
