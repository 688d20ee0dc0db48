//! Load + topology time against triangle count, for every mesh in `shared/data`.

use std::path::Path;

use anyhow::Result;
use sphaera::mesh::topology::{self, HalfEdgeMesh};

use super::{load_mesh, min_time};
use crate::chart::{ChartSpec, Series, log_log_scatter, write_csv};

/// The experiment's name: its files are `load_topology_time.{svg,csv}`.
pub const NAME: &str = "load_topology_time";

/// Timings are the minimum over this many runs.
const RUNS: usize = 3;

pub fn run(data: &Path, out: &Path) -> Result<()> {
    let mut rows = Vec::new();
    let mut load = Series::new("read file");
    let mut analyze = Series::new("topology report");
    let mut half_edge = Series::new("half-edge build");
    let mut total = Series::new("read + report");
    for file in sphaera_tests::mesh_files(data) {
        let path = data.join(&file);
        let (load_s, mesh) = min_time(RUNS, || load_mesh(&path))?;
        let (analyze_s, _) = min_time(RUNS, || Ok(topology::analyze(&mesh)))?;
        let (half_edge_s, _) = min_time(RUNS, || Ok(HalfEdgeMesh::from_trimesh(&mesh)))?;
        let triangles = mesh.triangle_count() as f64;
        eprintln!(
            "{:<48} {:>9} triangles  read {load_s:.4} s  report {analyze_s:.4} s  half-edge {half_edge_s:.4} s",
            file.display(),
            mesh.triangle_count()
        );
        load.points.push((triangles, load_s));
        analyze.points.push((triangles, analyze_s));
        half_edge.points.push((triangles, half_edge_s));
        total.points.push((triangles, load_s + analyze_s));
        rows.push(vec![
            file.to_string_lossy().replace('\\', "/"),
            mesh.triangle_count().to_string(),
            format!("{load_s:.6}"),
            format!("{analyze_s:.6}"),
            format!("{half_edge_s:.6}"),
        ]);
    }
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "file",
            "triangles",
            "read_seconds",
            "report_seconds",
            "half_edge_seconds",
        ],
        &rows,
    )?;
    log_log_scatter(
        &out.join(format!("{NAME}.svg")),
        &ChartSpec {
            title: "Reading a mesh and building its topology (every mesh in shared/data)",
            x_label: "triangles",
            y_label: "seconds (minimum of 3 runs)",
        },
        &[load, analyze, half_edge, total],
    )
}
