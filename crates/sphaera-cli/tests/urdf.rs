//! End-to-end tests of `sphaera urdf`.

mod common;

use common::{json, sphaera};

fn panda(test: &str) -> Option<String> {
    let data = sphaera_tests::data_dir(test)?;
    Some(
        data.join(sphaera_tests::URDF_ASSETS)
            .join("franka_panda/panda.urdf")
            .display()
            .to_string(),
    )
}

#[test]
fn the_panda_is_spherized_and_written_in_every_format() {
    let Some(urdf) = panda("the_panda_is_spherized") else {
        return;
    };
    let dir = tempfile::tempdir().expect("a folder");
    for (file, needle) in [
        (
            "panda.srdf",
            "<link_sphere_approximation link=\"panda_link0\">",
        ),
        ("panda.yml", "collision_spheres:"),
        ("panda.urdf", "<sphere radius="),
        ("panda.json", "\"levels\""),
    ] {
        let out = dir.path().join(file);
        let report = json(&sphaera(&[
            "urdf",
            &urdf,
            "--spheres-per-link",
            "6",
            "-o",
            out.to_str().expect("utf-8"),
            "--json",
        ]));
        let text = std::fs::read_to_string(&out).expect("written");
        assert!(text.contains(needle), "{file}");
        assert_eq!(report["robot"], "panda");
        let links = report["links"].as_array().expect("links");
        assert_eq!(links.len(), 11);
        for link in links {
            assert!(link["spheres"].as_u64().unwrap() <= 6, "{link}");
            assert_eq!(link["coverage"], 1.0);
            assert_eq!(link["coverage_certified"], true);
            assert!(
                link["worst_protrusion"].as_f64().unwrap()
                    >= link["p95_protrusion"].as_f64().unwrap()
            );
        }
        assert_eq!(
            report["links_without_geometry"].as_array().map(Vec::len),
            Some(2)
        );
    }
    // A tolerance and a per-link override, as text.
    let output = sphaera(&[
        "urdf",
        &urdf,
        "--tolerance",
        "6%",
        "--per-link",
        "panda_hand=3",
        "-q",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains("tolerance 6%") && text.contains("panda_hand"),
        "{text}"
    );
}

#[test]
fn bad_arguments_and_files_give_clear_errors() {
    let dir = tempfile::tempdir().expect("a folder");
    let missing = dir.path().join("none.urdf");
    let output = sphaera(&["urdf", missing.to_str().expect("utf-8")]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("none.urdf"));

    let broken = dir.path().join("broken.urdf");
    std::fs::write(&broken, "<robot name=\"r\">\n<link name=\"a\">\n</robot>\n").expect("write");
    let output = sphaera(&["urdf", broken.to_str().expect("utf-8")]);
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && message.contains("malformed XML") && message.contains("3:"),
        "{message}"
    );

    let fine = dir.path().join("fine.urdf");
    std::fs::write(
        &fine,
        "<robot name=\"r\"><link name=\"a\"><collision><geometry><sphere radius=\"0.1\"/></geometry></collision></link></robot>",
    )
    .expect("write");
    let fine = fine.to_str().expect("utf-8");
    for (args, needle) in [
        (vec!["--per-link", "ghost=3"], "no link \"ghost\""),
        (vec!["--per-link", "a=zero"], "positive whole number"),
        (vec!["-o", "out.txt"], "extension"),
        (vec!["--tolerance", "-1"], "non-negative"),
        (vec!["-o", fine], "it is the input URDF"),
        (
            vec!["--budget", "18446744073709551615"],
            "at most 10,000 per link",
        ),
        (
            vec!["--spheres-per-link", "1000000000"],
            "at most 10,000 per link",
        ),
        (
            vec!["--visual"],
            "no link of robot \"r\" has visual geometry",
        ),
    ] {
        let mut all = vec!["urdf", fine];
        all.extend(args.iter().copied());
        let output = sphaera(&all);
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(
            !output.status.success() && message.contains(needle),
            "{args:?}: {message}"
        );
    }
    // The input is left as it was when -o names it.
    assert!(
        std::fs::read_to_string(fine)
            .expect("read")
            .starts_with("<robot name=\"r\">")
    );
    // A sphere link is its own single sphere, its coverage full.
    let report = json(&sphaera(&["urdf", fine, "--json"]));
    assert_eq!(report["spheres"], 1);
    assert_eq!(report["worst_protrusion"], 0.0);
    assert_eq!(report["links"][0]["coverage"], 1.0, "{report}");
}
