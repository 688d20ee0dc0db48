//! GeoJSON and WKT outlines: every geometry kind, holes and islands, and every malformed
//! input named.

use glam::DVec2;
use sphaera_io::{FilePolicy, IoError, ShapeFormat, parse_shapes, read_shapes};

const COUNTRY: &str = r#"{
  "type": "FeatureCollection",
  "features": [
    { "type": "Feature", "properties": { "name": "main" },
      "geometry": { "type": "Polygon", "coordinates": [
        [[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]],
        [[4, 4], [6, 4], [6, 6], [4, 4]] ] } },
    { "type": "Feature", "properties": { "name": "islands" },
      "geometry": { "type": "MultiPolygon", "coordinates": [
        [[[12, 0, 5], [13, 0, 5], [13, 1, 5], [12, 0, 5]]],
        [[[14, 0], [15, 0], [15, 1], [14, 0]]] ] } },
    { "type": "Feature", "properties": {}, "geometry": null },
    { "type": "Feature", "properties": {},
      "geometry": { "type": "LineString", "coordinates": [[0, -1], [20, -1]] } },
    { "type": "Feature", "properties": {},
      "geometry": { "type": "Point", "coordinates": [3, 3] } }
  ]
}"#;

#[test]
fn a_feature_collection_with_holes_islands_lines_and_points() {
    let shapes = parse_shapes(COUNTRY, ShapeFormat::GeoJson).unwrap();
    assert_eq!(shapes.polygons.len(), 3);
    assert_eq!(shapes.polygons[0].len(), 2, "exterior and hole");
    assert_eq!(shapes.polygons[0][1][2], DVec2::new(6.0, 6.0));
    assert_eq!(
        shapes.polygons[1][0][1],
        DVec2::new(13.0, 0.0),
        "elevation dropped"
    );
    assert_eq!(
        shapes.lines,
        vec![vec![DVec2::new(0.0, -1.0), DVec2::new(20.0, -1.0)]]
    );
    assert_eq!(shapes.ignored_points, 1);
    assert_eq!(shapes.vertex_count(), 5 + 4 + 4 + 4 + 2);
}

#[test]
fn wkt_multipolygons_collections_and_lines() {
    let shapes = parse_shapes(
        "MULTIPOLYGON (((0 0, 10 0, 10 10, 0 10, 0 0), (4 4, 6 4, 6 6, 4 4)), ((12 0, 13 0, 13 1, 12 0)))",
        ShapeFormat::Wkt,
    )
    .unwrap();
    assert_eq!(shapes.polygons.len(), 2);
    assert_eq!(shapes.polygons[0].len(), 2);
    let collection = parse_shapes(
        "GEOMETRYCOLLECTION (POINT (1 2), LINESTRING Z (0 0 1, 1 1 1), POLYGON EMPTY)",
        ShapeFormat::Wkt,
    )
    .unwrap();
    assert_eq!(collection.lines, vec![vec![DVec2::ZERO, DVec2::ONE]]);
    assert_eq!(collection.ignored_points, 1);
    assert!(collection.polygons.is_empty());
}

#[test]
fn malformed_input_is_named() {
    let error = parse_shapes(
        "{\n  \"type\": \"Polygon\",\n  \"coordinates\": [[[0, 0], [1]",
        ShapeFormat::GeoJson,
    )
    .unwrap_err();
    assert!(matches!(error, IoError::MalformedShapes { .. }), "{error}");
    assert!(
        error.to_string().starts_with("malformed GeoJSON data: "),
        "{error}"
    );
    let short = parse_shapes(
        r#"{"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1], [0, 0]]]}"#,
        ShapeFormat::GeoJson,
    )
    .unwrap_err()
    .to_string();
    assert!(short.contains("position 2"), "{short}");
    let bad = parse_shapes("POLYGON ((0 0, 1 0, x 1))", ShapeFormat::Wkt).unwrap_err();
    assert!(bad.to_string().starts_with("malformed WKT data: "), "{bad}");
    assert!(parse_shapes("", ShapeFormat::Wkt).is_err());
    assert!(parse_shapes("[]", ShapeFormat::GeoJson).is_err());
}

#[test]
fn files_through_the_policy() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("Country.GeoJSON");
    std::fs::write(&path, COUNTRY).unwrap();
    assert_eq!(ShapeFormat::from_path(&path), Some(ShapeFormat::GeoJson));
    let shapes = read_shapes(&path, &FilePolicy::default()).unwrap();
    assert_eq!(shapes.polygons.len(), 3);
    let broken = dir.path().join("broken.wkt");
    std::fs::write(&broken, "POLYGON ((").unwrap();
    let error = read_shapes(&broken, &FilePolicy::default())
        .unwrap_err()
        .to_string();
    assert!(error.contains("broken.wkt"), "{error}");
    let other = dir.path().join("country.shp");
    std::fs::write(&other, "").unwrap();
    assert!(matches!(
        read_shapes(&other, &FilePolicy::default()),
        Err(IoError::UnknownShapeFormat { .. })
    ));
    let small = FilePolicy::default().with_max_bytes(10);
    assert!(matches!(
        read_shapes(&path, &small),
        Err(IoError::Refused { .. })
    ));
    let elsewhere = FilePolicy::default().with_root(dir.path().join("inner"));
    assert!(read_shapes(&path, &elsewhere).is_err());
    assert!(matches!(
        read_shapes(dir.path().join("missing.wkt"), &FilePolicy::default()),
        Err(IoError::Io { .. } | IoError::Refused { .. })
    ));
}
