//! Every mesh in `shared/data` loads, and its topology matches the statistics table in
//! `shared/data/README.md` (computed there with trimesh and pymeshlab after merging
//! bit-identical positions): closed, 2-manifold, genus, boundary edges, components, χ,
//! triangle and vertex-record counts, and the bounding-box diagonal.

use sphaera_io as io;
use sphaera_mesh::topology;
use sphaera_tests::{data_dir, expected_stats};

#[test]
fn every_shared_mesh_matches_the_data_readme() {
    let Some(data) = data_dir("every_shared_mesh_matches_the_data_readme") else {
        return;
    };
    let stats = expected_stats(&data);
    assert_eq!(stats.len(), 39);
    let mut failures = Vec::new();
    for expected in &stats {
        let loaded = match io::read(data.join(&expected.file)) {
            Ok(loaded) => loaded,
            Err(e) => {
                failures.push(format!("{}: does not load: {e}", expected.file));
                continue;
            }
        };
        let mesh = &loaded.mesh;
        let report = topology::analyze(mesh);
        let diagonal = mesh.bounding_box_diagonal();
        let got = (
            loaded.report.vertex_records,
            mesh.triangle_count(),
            report.is_closed,
            report.is_manifold,
            report.component_count,
            report.boundary_edge_count,
            report.genus.map(|g| i64::try_from(g).unwrap_or(i64::MAX)),
            report.euler_characteristic,
        );
        let want = (
            expected.vertex_records,
            expected.triangles,
            expected.closed,
            expected.manifold,
            expected.components,
            expected.boundary_edges,
            expected.genus,
            expected.euler_characteristic,
        );
        if got != want {
            failures.push(format!(
                "{}: (vertex records, triangles, closed, manifold, components, boundary edges, \
                 genus, χ) = {got:?}, the README says {want:?}",
                expected.file
            ));
        }
        // The README rounds the diagonal to 4 significant digits.
        let relative = (diagonal - expected.bbox_diagonal).abs() / expected.bbox_diagonal;
        if relative > 5e-4 {
            failures.push(format!(
                "{}: diagonal {diagonal}, the README says {}",
                expected.file, expected.bbox_diagonal
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_dirty_scans_report_their_known_defects() {
    let Some(data) = data_dir("the_dirty_scans_report_their_known_defects") else {
        return;
    };
    // The Stanford bunny: 5 holes (223 boundary edges) and 1,113 unreferenced vertices.
    let bunny = io::load(data.join("stanford-bunny.obj")).expect("the bunny loads");
    let report = topology::analyze(&bunny);
    assert_eq!(report.boundary_loop_count, 5);
    assert_eq!(report.boundary_edge_count, 223);
    assert_eq!(report.unreferenced_vertex_count, 1113);
    assert_eq!(report.genus, Some(0));

    // The full dragon: 108 degenerate triangles and 108 non-manifold edges once the ~2,100
    // duplicated positions are merged.
    let dragon = io::load(data.join("dragon_vrip.ply")).expect("the dragon loads");
    let report = topology::analyze(&dragon);
    assert_eq!(report.triangle_count, 871_414);
    assert_eq!(report.repeated_index_triangle_count, 108);
    assert_eq!(report.non_manifold_edge_count, 108);
    assert!(!report.is_manifold);
    assert_eq!(report.genus, None);
}
