//! Label files: every set of labels comes back equal, through a writer and through a
//! file; every damaged, forged or foreign file is refused with its own error, never a
//! panic, and never by allocating what a header claims.

use std::io::Read;

use proptest::prelude::*;
use sphaera_io::{FilePolicy, FileRefusal};
use sphaera_mesh::shapes::{self, DEFAULT_SHAPES};
use sphaera_mesh::{DVec3, TriMesh};
use sphaera_silhouette::{
    Contours, DistanceTransform, LABEL_FILE_MAGIC, LABEL_FILE_VERSION, LabelFileProblem,
    LabelOptions, Labels, MeshFingerprint, SilhouetteError, ViewSet,
};
use xxhash_rust::xxh3::xxh3_64;

/// Bytes of the header with its checksum.
const HEADER: usize = 80;

/// A small mesh and its labels: 6 views at 8² cells.
fn small() -> (TriMesh, ViewSet, LabelOptions, Labels) {
    let mesh = shapes::sphere(1.0, 4).unwrap();
    let views = ViewSet::regular(90.0).unwrap();
    let options = LabelOptions::default().with_resolution(8);
    let labels = Labels::compute(&mesh, &views, &options).unwrap();
    (mesh, views, options, labels)
}

fn bytes_of(labels: &Labels, mesh: &TriMesh) -> Vec<u8> {
    let mut bytes = Vec::new();
    labels.write_to(mesh, &mut bytes).unwrap();
    bytes
}

/// The problem of a label file error.
fn problem(error: SilhouetteError) -> LabelFileProblem {
    match error {
        SilhouetteError::LabelFile { problem, .. } => problem,
        other => panic!("not a label file error: {other}"),
    }
}

fn read_problem(bytes: &[u8], mesh: &TriMesh) -> LabelFileProblem {
    problem(Labels::read_from(bytes, mesh).expect_err("refused"))
}

/// Puts the checksums of `bytes` right again after a header field was changed.
fn reseal(bytes: &mut [u8]) {
    let header = xxh3_64(&bytes[..72]);
    bytes[72..80].copy_from_slice(&header.to_le_bytes());
    let end = bytes.len() - 8;
    let file = xxh3_64(&bytes[..end]);
    bytes[end..].copy_from_slice(&file.to_le_bytes());
}

/// The header of `bytes` with `change` applied and its checksum put right.
fn forged_header(bytes: &[u8], change: impl Fn(&mut [u8])) -> Vec<u8> {
    let mut header = bytes[..HEADER].to_vec();
    change(&mut header);
    let checksum = xxh3_64(&header[..72]);
    header[72..80].copy_from_slice(&checksum.to_le_bytes());
    header
}

fn moved(mesh: &TriMesh, f: impl Fn(usize, DVec3) -> DVec3) -> TriMesh {
    let positions = mesh
        .positions()
        .iter()
        .enumerate()
        .map(|(i, &p)| f(i, p))
        .collect();
    TriMesh::new(positions, mesh.triangles().to_vec()).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Labels of random small meshes and settings, orthographic and perspective, read
    /// back equal through a writer and through a file, and match their settings.
    #[test]
    fn labels_come_back_equal(
        shape in 0..DEFAULT_SHAPES.len(),
        extra in 0_usize..4,
        step in prop::sample::select(vec![30.0, 36.0, 45.0, 60.0, 90.0]),
        resolution in 1_usize..40,
        chamfer in any::<bool>(),
        outline in any::<bool>(),
        perspective in prop::option::of(1.05_f64..20.0),
    ) {
        let shape = DEFAULT_SHAPES[shape];
        let mesh = shape.build(shape.min_resolution() + extra).unwrap();
        let mut views = ViewSet::regular(step).unwrap();
        if let Some(distance) = perspective {
            views = views.with_perspective(distance).unwrap();
        }
        let options = LabelOptions::default()
            .with_resolution(resolution)
            .with_transform(if chamfer { DistanceTransform::Chamfer } else { DistanceTransform::Euclidean })
            .with_contours(if outline { Contours::External } else { Contours::All });
        let labels = Labels::compute(&mesh, &views, &options).unwrap();
        let bytes = bytes_of(&labels, &mesh);
        prop_assert_eq!(bytes.len(), HEADER + 2 * mesh.vertex_count() * views.len() + 8);
        let back = Labels::read_from(bytes.as_slice(), &mesh).unwrap();
        prop_assert_eq!(&back, &labels);
        prop_assert!(back.check_settings(&views, &options).is_ok());
        prop_assert_eq!(back.options(), options);
        prop_assert_eq!(back.views(), &views);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("labels.sphl");
        labels.save(&mesh, &path).unwrap();
        prop_assert_eq!(std::fs::read(&path).unwrap(), bytes);
        prop_assert_eq!(Labels::load(&path, &mesh).unwrap(), labels);
    }
}

#[test]
fn the_header_starts_with_the_magic_and_the_version() {
    let (mesh, _, _, labels) = small();
    let bytes = bytes_of(&labels, &mesh);
    assert_eq!(bytes[..8], LABEL_FILE_MAGIC);
    assert_eq!(bytes[8..12], LABEL_FILE_VERSION.to_le_bytes());
    assert_eq!(bytes[12..16], 8_u32.to_le_bytes());
    assert_eq!(bytes[16..24], 90.0_f64.to_le_bytes());
    let fingerprint = MeshFingerprint::of(&mesh);
    assert_eq!(bytes[56..72], fingerprint.hash().to_le_bytes());
    assert_eq!(labels.mesh_fingerprint(), fingerprint);
    // The labels follow the header, view-major, little-endian.
    let first = labels.stored(0);
    assert_eq!(
        bytes[HEADER..HEADER + 2],
        first.first().copied().unwrap().to_le_bytes()
    );
}

#[test]
fn a_file_that_is_not_a_label_file_is_refused() {
    let (mesh, _, _, labels) = small();
    let mut bytes = bytes_of(&labels, &mesh);
    bytes[0] ^= 0x20;
    assert!(matches!(
        read_problem(&bytes, &mesh),
        LabelFileProblem::NotLabelFile
    ));
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let error = Labels::read_from(&obj[..], &mesh).unwrap_err();
    assert!(
        error.to_string().contains("not a sphaera label file"),
        "{error}"
    );
}

#[test]
fn another_version_is_refused_naming_both() {
    let (mesh, _, _, labels) = small();
    let mut bytes = bytes_of(&labels, &mesh);
    bytes[8..12].copy_from_slice(&2_u32.to_le_bytes());
    let problem = read_problem(&bytes, &mesh);
    assert!(matches!(
        problem,
        LabelFileProblem::UnsupportedVersion {
            found: 2,
            supported: 1
        }
    ));
    let message = problem.to_string();
    assert!(
        message.contains("version 2") && message.contains("version 1"),
        "{message}"
    );
}

#[test]
fn a_file_truncated_anywhere_is_an_error() {
    let (mesh, _, _, labels) = small();
    let bytes = bytes_of(&labels, &mesh);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cut.sphl");
    for end in 0..bytes.len() {
        let problem = read_problem(&bytes[..end], &mesh);
        assert!(
            matches!(problem, LabelFileProblem::Truncated { found, .. } if found == end as u64),
            "{end}: {problem}"
        );
        // From a file the length is known: the same error, from the header alone.
        std::fs::write(&path, &bytes[..end]).unwrap();
        let error = Labels::load(&path, &mesh).unwrap_err();
        assert!(error.to_string().contains("cut.sphl"), "{error}");
        assert!(
            matches!(self::problem(error), LabelFileProblem::Truncated { .. }),
            "{end}"
        );
    }
}

#[test]
fn a_flipped_byte_anywhere_is_found() {
    let (mesh, _, _, labels) = small();
    let bytes = bytes_of(&labels, &mesh);
    let end = bytes.len() - 8;
    for i in 0..bytes.len() {
        for bit in [0x01, 0x80] {
            let mut damaged = bytes.clone();
            damaged[i] ^= bit;
            let problem = read_problem(&damaged, &mesh);
            let expected = match i {
                0..8 => matches!(problem, LabelFileProblem::NotLabelFile),
                8..12 => matches!(problem, LabelFileProblem::UnsupportedVersion { .. }),
                12..HEADER => matches!(problem, LabelFileProblem::Checksum { part: "header", .. }),
                _ => matches!(problem, LabelFileProblem::Checksum { part: "file", .. }),
            };
            assert!(expected, "byte {i} of {end} + 8, bit {bit:#x}: {problem}");
        }
    }
}

#[test]
fn trailing_bytes_are_refused() {
    let (mesh, _, _, labels) = small();
    let mut bytes = bytes_of(&labels, &mesh);
    let length = bytes.len() as u64;
    bytes.push(0);
    assert!(matches!(
        read_problem(&bytes, &mesh),
        LabelFileProblem::TrailingBytes { expected } if expected == length
    ));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("long.sphl");
    std::fs::write(&path, &bytes).unwrap();
    let error = Labels::load(&path, &mesh).unwrap_err();
    assert!(error.to_string().contains("bytes after"), "{error}");
}

#[test]
fn the_labels_of_another_mesh_are_refused() {
    let (mesh, _, _, labels) = small();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sphere.sphl");
    labels.save(&mesh, &path).unwrap();
    let refused = |other: &TriMesh| {
        let error = Labels::load(&path, other).unwrap_err();
        assert!(error.to_string().contains("sphere.sphl"), "{error}");
        let message = error.to_string();
        assert!(
            matches!(problem(error), LabelFileProblem::OtherMesh { .. }),
            "{message}"
        );
        message
    };
    // Other counts: the message gives both.
    let finer = shapes::sphere(1.0, 5).unwrap();
    let message = refused(&finer);
    assert!(
        message.contains(&format!("{} vertices", mesh.vertex_count()))
            && message.contains(&format!("{} vertices", finer.vertex_count())),
        "{message}"
    );
    // The same counts, one vertex moved by one unit in the last place.
    let nudged = moved(&mesh, |i, p| {
        if i == 3 {
            DVec3::new(p.x.next_up(), p.y, p.z)
        } else {
            p
        }
    });
    assert!(refused(&nudged).contains("same counts"));
    // The same positions, the triangles in another order.
    let mut triangles = mesh.triangles().to_vec();
    triangles.reverse();
    let reordered = TriMesh::new(mesh.positions().to_vec(), triangles).unwrap();
    assert!(refused(&reordered).contains("other positions or triangles"));
    // The same mesh scaled: another mesh.
    let scaled = moved(&mesh, |_, p| 2.0 * p);
    assert_ne!(MeshFingerprint::of(&scaled), MeshFingerprint::of(&mesh));
    refused(&scaled);
    // And the original is still accepted.
    assert_eq!(Labels::load(&path, &mesh).unwrap(), labels);
}

#[test]
fn labels_are_not_written_for_another_mesh() {
    let (mesh, _, _, labels) = small();
    let other = shapes::sphere(1.0, 5).unwrap();
    let mut bytes = Vec::new();
    let error = labels.write_to(&other, &mut bytes).unwrap_err();
    assert!(matches!(error, SilhouetteError::LabelsOfOtherMesh { .. }));
    assert!(bytes.is_empty());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("never.sphl");
    assert!(labels.save(&other, &path).is_err());
    assert!(!path.exists());
    assert!(labels.check_mesh(&mesh).is_ok());
}

/// A reader that counts the bytes taken from it.
struct Counting<R> {
    inner: R,
    taken: usize,
}

impl<R: Read> Read for Counting<R> {
    fn read(&mut self, buffer: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buffer)?;
        self.taken += n;
        Ok(n)
    }
}

#[test]
fn huge_counts_in_a_forged_header_are_refused_before_allocating() {
    let (mesh, _, _, labels) = small();
    let bytes = bytes_of(&labels, &mesh);
    // Each forged header is followed by an endless stream: the reader stops after the
    // header, so it neither reads nor allocates what the header claims (2⁴⁰ vertices
    // would be terabytes).
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (
            forged_header(&bytes, |h| {
                h[40..48].copy_from_slice(&(1_u64 << 40).to_le_bytes());
            }),
            "vertices × views",
        ),
        (
            forged_header(&bytes, |h| {
                h[40..48].copy_from_slice(&u64::MAX.to_le_bytes());
            }),
            "vertices × views",
        ),
        (
            forged_header(&bytes, |h| {
                h[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
            }),
            "resolution",
        ),
        (
            forged_header(&bytes, |h| {
                h[16..24].copy_from_slice(&0.001_f64.to_le_bytes());
            }),
            "step",
        ),
        (
            forged_header(&bytes, |h| {
                h[36..40].copy_from_slice(&u32::MAX.to_le_bytes());
            }),
            "views",
        ),
    ];
    for (header, name) in cases {
        let mut reader = Counting {
            inner: header.as_slice().chain(std::io::repeat(0)),
            taken: 0,
        };
        let problem = problem(Labels::read_from(&mut reader, &mesh).unwrap_err());
        assert_eq!(reader.taken, HEADER, "{name}");
        let LabelFileProblem::Header { source } = &problem else {
            panic!("{name}: {problem}");
        };
        assert!(source.to_string().contains(name), "{name}: {problem}");
    }
}

/// A change to a header.
type Change = Box<dyn Fn(&mut [u8])>;

#[test]
fn invalid_header_values_are_named() {
    let (mesh, _, _, labels) = small();
    let bytes = bytes_of(&labels, &mesh);
    let cases: Vec<(Change, &str)> = vec![
        (Box::new(|h| h[33] = 7), "transform"),
        (Box::new(|h| h[34] = 2), "contours"),
        (Box::new(|h| h[32] = 9), "projection"),
        (Box::new(|h| h[35] = 1), "reserved"),
        (Box::new(|h| h[12..16].fill(0)), "resolution"),
        (
            Box::new(|h| h[16..24].copy_from_slice(&7.0_f64.to_le_bytes())),
            "step",
        ),
        (
            Box::new(|h| h[24..32].copy_from_slice(&2.0_f64.to_le_bytes())),
            "perspective distance",
        ),
        (
            Box::new(|h| {
                h[32] = 1;
                h[24..32].copy_from_slice(&0.5_f64.to_le_bytes());
            }),
            "inside the bounding sphere",
        ),
        (
            Box::new(|h| h[16..24].copy_from_slice(&f64::NAN.to_le_bytes())),
            "step",
        ),
    ];
    for (change, name) in cases {
        let mut forged = bytes.clone();
        change(&mut forged[..HEADER]);
        reseal(&mut forged);
        let problem = read_problem(&forged, &mesh);
        assert!(
            matches!(problem, LabelFileProblem::Header { .. }),
            "{name}: {problem}"
        );
        assert!(problem.to_string().contains(name), "{name}: {problem}");
    }
    // A header that is valid but for another setting reads fine: the settings check
    // tells the caller.
    let mut chamfer = bytes.clone();
    chamfer[33] = 1;
    reseal(&mut chamfer);
    let back = Labels::read_from(chamfer.as_slice(), &mesh).unwrap();
    assert_eq!(back.transform(), DistanceTransform::Chamfer);
}

#[test]
fn settings_that_differ_are_named() {
    let (mesh, views, options, labels) = small();
    assert!(labels.check_settings(&views, &options).is_ok());
    let setting =
        |views: &ViewSet, options: &LabelOptions| match labels.check_settings(views, options) {
            Err(SilhouetteError::LabelSettingsMismatch { setting, .. }) => setting,
            other => panic!("{other:?}"),
        };
    assert_eq!(setting(&ViewSet::regular(45.0).unwrap(), &options), "step");
    let perspective = views.clone().with_perspective(3.0).unwrap();
    assert_eq!(setting(&perspective, &options), "projection");
    assert_eq!(setting(&views, &options.with_resolution(16)), "resolution");
    assert_eq!(
        setting(&views, &options.with_transform(DistanceTransform::Chamfer)),
        "transform"
    );
    assert_eq!(
        setting(&views, &options.with_contours(Contours::All)),
        "contours"
    );
    let error = labels
        .check_settings(&perspective, &options)
        .unwrap_err()
        .to_string();
    assert_eq!(
        error,
        "the labels were computed with projection orthographic, not perspective at 3 radii"
    );
    // Perspective labels at another distance differ too.
    let labels = Labels::compute(&mesh, &perspective, &options).unwrap();
    let farther = views.with_perspective(4.0).unwrap();
    assert!(labels.check_settings(&farther, &options).is_err());
}

#[test]
fn files_that_are_not_regular_are_refused() {
    let (mesh, _, _, _) = small();
    let dir = tempfile::tempdir().unwrap();
    let mut places = vec![dir.path().to_path_buf()];
    if cfg!(unix) {
        places.push("/dev/zero".into());
    }
    for place in places {
        let error = Labels::load(&place, &mesh).unwrap_err();
        let message = error.to_string();
        assert!(message.contains("not a regular file"), "{message}");
        assert!(
            matches!(
                problem(error),
                LabelFileProblem::Refused {
                    refusal: FileRefusal::NotRegular { .. }
                }
            ),
            "{}: {message}",
            place.display()
        );
    }
    let missing = dir.path().join("missing.sphl");
    let error = Labels::load(&missing, &mesh).unwrap_err();
    assert!(error.to_string().contains("missing.sphl"), "{error}");
    assert!(
        matches!(problem(error), LabelFileProblem::Io { source } if source.kind() == std::io::ErrorKind::NotFound)
    );
    // A file larger than the policy's cap is refused before it is read.
    let (_, _, _, labels) = small();
    let path = dir.path().join("labels.sphl");
    labels.save(&mesh, &path).unwrap();
    let policy = FilePolicy::default().with_max_bytes(100);
    let error = Labels::load_with(&path, &mesh, &policy).unwrap_err();
    assert!(matches!(
        problem(error),
        LabelFileProblem::Refused {
            refusal: FileRefusal::TooLarge { .. }
        }
    ));
    // A policy with a root refuses a file outside it.
    let elsewhere = tempfile::tempdir().unwrap();
    let policy = FilePolicy::default().with_root(elsewhere.path());
    let error = Labels::load_with(&path, &mesh, &policy).unwrap_err();
    assert!(
        error.to_string().contains("outside the allowed folder"),
        "{error}"
    );
}

#[test]
fn a_file_that_cannot_be_written_names_it() {
    let (mesh, _, _, labels) = small();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no").join("such").join("folder.sphl");
    let error = labels.save(&mesh, &path).unwrap_err();
    assert!(error.to_string().contains("folder.sphl"), "{error}");
    assert!(matches!(problem(error), LabelFileProblem::Io { .. }));
}

#[test]
fn saving_replaces_a_file_atomically() {
    let (mesh, views, _, labels) = small();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("labels.sphl");
    std::fs::write(&path, b"old").unwrap();
    labels.save(&mesh, &path).unwrap();
    assert_eq!(Labels::load(&path, &mesh).unwrap(), labels);
    let finer =
        Labels::compute(&mesh, &views, &LabelOptions::default().with_resolution(16)).unwrap();
    finer.save(&mesh, &path).unwrap();
    assert_eq!(Labels::load(&path, &mesh).unwrap(), finer);
    // Nothing but the file is left in the folder.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}
