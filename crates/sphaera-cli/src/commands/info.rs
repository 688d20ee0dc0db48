//! `sphaera info`: counts, bounding box and topology of a mesh.

use std::time::Instant;

use anyhow::Result;
use serde::Serialize;
use sphaera::mesh::{TriMesh, io::LoadReport, topology::TopologyReport};

use crate::{
    cli::InfoArgs,
    input::read_mesh,
    output::{print_report, thousands, yes_no},
    progress,
};

/// Everything `sphaera info` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Info {
    /// The file, or `<embedded bunny_lowres.obj>`.
    source: String,
    /// `obj`, `ply`, `stl`, `off` or `gltf` (also for `.glb`).
    format: String,
    /// Vertex records in the file (before any merging).
    vertex_records: usize,
    /// Faces in the file (polygons count once).
    faces_in_file: usize,
    /// Triangles after triangulating polygons.
    triangles: usize,
    /// Polygons with more than three vertices that were triangulated.
    polygons_triangulated: usize,
    /// Non-convex polygons (ear-clipped rather than fanned).
    non_convex_polygons: usize,
    /// Bit-identical STL corners merged on read.
    welded_on_read: usize,
    /// glTF: triangle primitives merged into the mesh, once per node drawing them.
    primitives_read: usize,
    /// glTF: points and lines primitives left out, once per node drawing them.
    primitives_skipped: usize,
    /// glTF: primitives placed by a mirroring node transform (their winding reversed).
    mirrored_primitives: usize,
    /// `null` for a mesh without triangles.
    bounding_box: Option<BoundingBox>,
    surface_area: f64,
    topology: Topology,
    seconds: Seconds,
}

#[derive(Debug, Serialize)]
struct BoundingBox {
    min: [f64; 3],
    max: [f64; 3],
    diagonal: f64,
}

/// The topology, computed after merging bit-identical vertex positions (as the
/// statistics in `shared/data/README.md` are).
#[derive(Debug, Serialize)]
struct Topology {
    /// Vertex records merged into an earlier record at the identical position.
    merged_vertices: usize,
    referenced_vertices: usize,
    unreferenced_vertices: usize,
    edges: usize,
    boundary_edges: usize,
    boundary_loops: usize,
    non_manifold_edges: usize,
    non_manifold_vertices: usize,
    inconsistently_oriented_edges: usize,
    components: usize,
    euler_characteristic: i64,
    closed: bool,
    manifold: bool,
    oriented: bool,
    /// `null` when the mesh is not a consistently oriented 2-manifold.
    genus: Option<u64>,
    repeated_index_triangles: usize,
    zero_area_triangles: usize,
    duplicate_triangles: usize,
}

#[derive(Debug, Serialize)]
struct Seconds {
    load: f64,
    topology: f64,
}

pub fn run(args: &InfoArgs, quiet: bool) -> Result<()> {
    let input = read_mesh(args.mesh.as_deref(), quiet)?;
    let spinner = progress::spinner(quiet, "analysing topology");
    let started = Instant::now();
    let report = sphaera::mesh::topology::analyze(&input.loaded.mesh);
    let topology_seconds = started.elapsed().as_secs_f64();
    spinner.finish_and_clear();
    let info = Info::new(
        input.source,
        &input.loaded.mesh,
        &input.loaded.report,
        &report,
        Seconds {
            load: input.seconds,
            topology: topology_seconds,
        },
    );
    print_report(&info, args.output.json)
}

impl Info {
    fn new(
        source: String,
        mesh: &TriMesh,
        load: &LoadReport,
        topology: &TopologyReport,
        seconds: Seconds,
    ) -> Self {
        let bbox = mesh.bounding_box();
        Self {
            source,
            format: load.format.extension().to_owned(),
            vertex_records: load.vertex_records,
            faces_in_file: load.faces_in_file,
            triangles: mesh.triangle_count(),
            polygons_triangulated: load.polygons_triangulated,
            non_convex_polygons: load.non_convex_polygons,
            welded_on_read: load.welded_vertices,
            primitives_read: load.primitives_read,
            primitives_skipped: load.primitives_skipped,
            mirrored_primitives: load.mirrored_primitives,
            bounding_box: (!bbox.is_empty()).then(|| BoundingBox {
                min: bbox.min.to_array(),
                max: bbox.max.to_array(),
                diagonal: bbox.diagonal(),
            }),
            surface_area: mesh.surface_area(),
            topology: Topology {
                merged_vertices: topology.merged_vertex_count,
                referenced_vertices: topology.referenced_vertex_count,
                unreferenced_vertices: topology.unreferenced_vertex_count,
                edges: topology.edge_count,
                boundary_edges: topology.boundary_edge_count,
                boundary_loops: topology.boundary_loop_count,
                non_manifold_edges: topology.non_manifold_edge_count,
                non_manifold_vertices: topology.non_manifold_vertex_count,
                inconsistently_oriented_edges: topology.inconsistent_edge_count,
                components: topology.component_count,
                euler_characteristic: topology.euler_characteristic,
                closed: topology.is_closed,
                manifold: topology.is_manifold,
                oriented: topology.is_oriented,
                genus: topology.genus,
                repeated_index_triangles: topology.repeated_index_triangle_count,
                zero_area_triangles: topology.zero_area_triangle_count,
                duplicate_triangles: topology.duplicate_triangle_count,
            },
            seconds,
        }
    }
}

impl crate::output::Report for Info {
    fn to_text(&self) -> String {
        let t = &self.topology;
        let genus = t.genus.map_or_else(
            || "n/a (not an oriented 2-manifold)".to_owned(),
            |g| g.to_string(),
        );
        let mut lines = vec![
            format!("mesh            {} ({})", self.source, self.format),
            format!(
                "vertices        {} in the file, {} merged into identical positions, {} referenced, {} unreferenced",
                thousands(self.vertex_records),
                thousands(t.merged_vertices),
                thousands(t.referenced_vertices),
                thousands(t.unreferenced_vertices)
            ),
            format!(
                "triangles       {} (from {} faces; {} polygons triangulated, {} non-convex)",
                thousands(self.triangles),
                thousands(self.faces_in_file),
                thousands(self.polygons_triangulated),
                thousands(self.non_convex_polygons)
            ),
            format!("edges           {}", thousands(t.edges)),
            match &self.bounding_box {
                Some(b) => format!(
                    "bounding box    [{:.6}, {:.6}, {:.6}] .. [{:.6}, {:.6}, {:.6}]\ndiagonal        {:.6}",
                    b.min[0], b.min[1], b.min[2], b.max[0], b.max[1], b.max[2], b.diagonal
                ),
                None => "bounding box    none (no triangles)".to_owned(),
            },
            format!("surface area    {:.6}", self.surface_area),
            format!("closed          {}", yes_no(t.closed)),
            format!(
                "2-manifold      {} ({} non-manifold edges, {} non-manifold vertices)",
                yes_no(t.manifold),
                thousands(t.non_manifold_edges),
                thousands(t.non_manifold_vertices)
            ),
            format!(
                "oriented        {} ({} inconsistently oriented edges)",
                yes_no(t.oriented),
                thousands(t.inconsistently_oriented_edges)
            ),
            format!("genus           {genus}"),
            format!("components      {}", thousands(t.components)),
            format!(
                "boundary        {} loops, {} edges",
                thousands(t.boundary_loops),
                thousands(t.boundary_edges)
            ),
            format!("Euler char.     {}", t.euler_characteristic),
            format!(
                "degenerate      {} with a repeated vertex, {} with zero area",
                thousands(t.repeated_index_triangles),
                thousands(t.zero_area_triangles)
            ),
            format!("duplicates      {}", thousands(t.duplicate_triangles)),
        ];
        if self.welded_on_read > 0 {
            lines.push(format!(
                "welded on read  {} (STL corners at identical positions)",
                thousands(self.welded_on_read)
            ));
        }
        if self.format == "gltf" {
            lines.push(format!(
                "glTF primitives {} triangle primitives read ({} mirrored), {} points or lines skipped",
                thousands(self.primitives_read),
                thousands(self.mirrored_primitives),
                thousands(self.primitives_skipped)
            ));
        }
        lines.push(format!(
            "time            {:.3} s to read, {:.3} s for topology",
            self.seconds.load, self.seconds.topology
        ));
        lines.join("\n") + "\n"
    }
}
