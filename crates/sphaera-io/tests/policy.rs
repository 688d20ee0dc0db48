//! The file policy: only regular files, within the cap, inside the root once links and `..`
//! are resolved; refused files are never opened (a named pipe cannot hang the reader).

use std::path::Path;
use std::time::{Duration, Instant};

use sphaera_io::{FilePolicy, FileRefusal, IoError, read, read_with};

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

fn refusal(result: Result<impl std::fmt::Debug, IoError>) -> FileRefusal {
    match result {
        Err(IoError::Refused { refusal, .. }) => refusal,
        other => panic!("expected a refusal, got {other:?}"),
    }
}

#[test]
fn devices_folders_and_pipes_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let policy = FilePolicy::default();
    assert_eq!(
        refusal(policy.read(dir.path())),
        FileRefusal::NotRegular { kind: "a folder" }
    );
    assert_eq!(
        refusal(read(dir.path())),
        FileRefusal::NotRegular { kind: "a folder" }
    );
    #[cfg(unix)]
    {
        let started = Instant::now();
        assert_eq!(
            refusal(read("/dev/zero")),
            FileRefusal::NotRegular { kind: "a device" }
        );
        let pipe = dir.path().join("pipe.obj");
        let made = std::process::Command::new("mkfifo").arg(&pipe).status();
        assert!(
            made.is_ok_and(|s| s.success()),
            "mkfifo is part of coreutils"
        );
        assert_eq!(
            refusal(read(&pipe)),
            FileRefusal::NotRegular {
                kind: "a named pipe"
            }
        );
        assert!(started.elapsed() < Duration::from_secs(5));
        let message = read("/dev/zero").unwrap_err().to_string();
        assert_eq!(
            message,
            "refused to read /dev/zero: it is a device, not a regular file"
        );
    }
}

#[test]
fn the_cap_is_checked_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tri.obj");
    std::fs::write(&path, TRIANGLE).unwrap();
    let length = TRIANGLE.len() as u64;
    assert_eq!(
        refusal(read_with(
            &path,
            &FilePolicy::default().with_max_bytes(length - 1)
        )),
        FileRefusal::TooLarge {
            bytes: length,
            cap: length - 1
        }
    );
    let exact = FilePolicy::default().with_max_bytes(length);
    assert_eq!(read_with(&path, &exact).unwrap().mesh.triangle_count(), 1);
    assert_eq!(exact.read(&path).unwrap(), TRIANGLE.as_bytes());
}

#[test]
fn a_root_confines_paths_links_and_climbs() {
    let outer = tempfile::tempdir().unwrap();
    let root = outer.path().join("root");
    std::fs::create_dir_all(root.join("sub")).unwrap();
    let inside = root.join("sub").join("tri.obj");
    let outside = outer.path().join("secret.obj");
    std::fs::write(&inside, TRIANGLE).unwrap();
    std::fs::write(&outside, TRIANGLE).unwrap();
    let policy = FilePolicy::default().with_root(&root);
    let outside_root = FileRefusal::OutsideRoot { root: root.clone() };

    assert!(policy.admits(&inside));
    assert_eq!(
        read_with(&inside, &policy).unwrap().mesh.triangle_count(),
        1
    );
    // Through `..` that stays inside: fine; climbing out: refused, absolute or not.
    assert!(policy.admits(&root.join("sub").join("..").join("sub").join("tri.obj")));
    assert_eq!(refusal(policy.read(&outside)), outside_root);
    assert_eq!(
        refusal(policy.read(&root.join("..").join("secret.obj"))),
        outside_root
    );
    assert!(!policy.admits(&outside));
    #[cfg(unix)]
    {
        // A link is followed only where it ends inside the root.
        let out_link = root.join("out.obj");
        std::os::unix::fs::symlink(&outside, &out_link).unwrap();
        assert_eq!(refusal(policy.read(&out_link)), outside_root);
        let in_link = root.join("in.obj");
        std::os::unix::fs::symlink(&inside, &in_link).unwrap();
        assert_eq!(policy.read(&in_link).unwrap(), TRIANGLE.as_bytes());
        // A linked folder leading out is refused too.
        std::os::unix::fs::symlink(outer.path(), root.join("up")).unwrap();
        assert_eq!(
            refusal(policy.read(&root.join("up").join("secret.obj"))),
            outside_root
        );
        // Without a root, links are followed (a user's own command line).
        assert!(FilePolicy::default().admits(&out_link));
    }
    // A missing file is an I/O error naming it, not a refusal.
    let missing = root.join("missing.obj");
    match policy.read(&missing) {
        Err(IoError::Io { path, source }) => {
            assert_eq!(path, missing);
            assert_eq!(source.kind(), std::io::ErrorKind::NotFound);
        }
        other => panic!("{other:?}"),
    }
    // A root that does not exist is an I/O error naming the root.
    let nowhere = FilePolicy::default().with_root(outer.path().join("nowhere"));
    match nowhere.read(&inside) {
        Err(IoError::Io { path, .. }) => assert_eq!(path, outer.path().join("nowhere")),
        other => panic!("{other:?}"),
    }
}

#[test]
fn text_must_be_utf8() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("latin1.txt");
    std::fs::write(&path, [0x63, 0x61, 0x66, 0xe9]).unwrap();
    let error = FilePolicy::default().read_to_string(&path).unwrap_err();
    assert!(
        matches!(&error, IoError::Io { source, .. } if source.kind() == std::io::ErrorKind::InvalidData),
        "{error}"
    );
    std::fs::write(&path, "café").unwrap();
    assert_eq!(
        FilePolicy::default()
            .read_to_string(Path::new(&path))
            .unwrap(),
        "café"
    );
}
