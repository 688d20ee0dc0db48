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
        ("panda.yml", "self_collision_ignore:"),
        (
            "panda.xml",
            "<exclude body1=\"panda_link0\" body2=\"panda_link1\"/>",
        ),
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
            assert_eq!(link["spheres"], 6, "{link}");
            assert_eq!(link["budget"], 6, "{link}");
            assert!(link["shortfall"].is_null(), "{link}");
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
        // The self-collision matrix: 55 pairs of the 11 links, the 10 joints between
        // links with spheres adjacent, every pair one verdict.
        let matrix = &report["self_collision"];
        assert_eq!(matrix["pairs"], 55);
        assert_eq!(matrix["adjacent"], 10);
        assert_eq!(matrix["samples"], 10_000);
        let verdicts: u64 = ["adjacent", "default", "always", "never", "checked"]
            .iter()
            .map(|k| matrix[k].as_u64().expect("a count"))
            .sum();
        assert_eq!(verdicts, 55, "{matrix}");
        assert!(matrix["never"].as_u64() > Some(0), "{matrix}");
    }
    // Without samples, only the adjacent and default rules; the SRDF says so.
    let srdf = dir.path().join("adjacent.srdf");
    let report = json(&sphaera(&[
        "urdf",
        &urdf,
        "--spheres-per-link",
        "4",
        "--self-collision-samples",
        "0",
        "-o",
        srdf.to_str().expect("utf-8"),
        "--json",
    ]));
    assert_eq!(report["self_collision"]["never"], 0);
    let text = std::fs::read_to_string(&srdf).expect("written");
    assert!(!text.contains("reason=\"Never\"") && text.contains("reason=\"Adjacent\""));
    // The cuRobo file naming its spheres beside it.
    let robot_file = dir.path().join("beside.yml");
    let spheres_file = dir.path().join("beside_spheres.yml");
    let output = sphaera(&[
        "urdf",
        &urdf,
        "--spheres-per-link",
        "3",
        "--curobo-spheres",
        spheres_file.to_str().expect("utf-8"),
        "-o",
        robot_file.to_str().expect("utf-8"),
        "-q",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = std::fs::read_to_string(&robot_file).expect("the robot file");
    let named = format!("collision_spheres: \"{}\"", spheres_file.display());
    assert!(text.contains(&named), "{text}");
    let spheres = std::fs::read_to_string(&spheres_file).expect("the spheres file");
    assert!(spheres.starts_with("collision_spheres:\n  \"panda_link0\":"));
    // A negative clearance and an end effector the robot does not have are refused.
    for (flag, value, needle) in [
        ("--self-collision-padding", "-1", "padding"),
        ("--ee-link", "gripper", "gripper"),
    ] {
        let out = dir.path().join("refused.yml");
        let output = sphaera(&[
            "urdf",
            &urdf,
            "--spheres-per-link",
            "2",
            flag,
            value,
            "-o",
            out.to_str().expect("utf-8"),
        ]);
        assert!(!output.status.success());
        assert!(String::from_utf8_lossy(&output.stderr).contains(needle));
        assert!(!out.exists());
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
        (vec!["--tolerance", "nan"], "finite"),
        (vec!["--tolerance", "0"], "positive and finite"),
        (vec!["--spheres-per-link", "0"], "at least 1"),
        (vec!["--budget", "0"], "at least 1"),
        (
            vec!["--effort", "hard"],
            "[possible values: quick, default, thorough]",
        ),
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

/// `sphaera robot` (the same command): a total divided exactly, a tolerance met by every
/// link, a tolerance that needs too many spheres and a missing mesh refused clearly, a
/// primitive that cannot use its spheres explained.
#[test]
fn robot_budgets_are_exact_and_tolerances_met() {
    let dir = tempfile::tempdir().expect("a folder");
    let write = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).expect("write");
        path.display().to_string()
    };
    let parts = write(
        "parts.urdf",
        r#"<robot name="parts">
             <link name="plate"><collision><geometry><box size="0.3 0.2 0.02"/></geometry></collision></link>
             <link name="ball"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>
             <joint name="j" type="fixed"><parent link="plate"/><child link="ball"/></joint>
           </robot>"#,
    );
    let report = json(&sphaera(&[
        "robot",
        &parts,
        "--spheres-per-link",
        "5",
        "--effort",
        "quick",
        "--json",
    ]));
    assert_eq!(report["asked"], 10, "{report}");
    let ball = &report["links"][1];
    assert_eq!(ball["spheres"], 1, "{report}");
    assert_eq!(ball["shortfall"], "a sphere primitive is its own sphere");
    let output = sphaera(&["robot", &parts, "--spheres-per-link", "5", "-q"]);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains("! ball has 1 of its 5 spheres: a sphere primitive is its own sphere"),
        "{text}"
    );
    for (args, needle) in [
        (
            vec!["--tolerance", "0.0001", "--max-spheres-per-link", "3"],
            "cannot be met within 3 spheres",
        ),
        (vec!["--budget", "1"], "cannot give each of the 2 links"),
    ] {
        let mut all = vec!["robot", parts.as_str()];
        all.extend(args.iter().copied());
        let output = sphaera(&all);
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(
            !output.status.success() && message.contains(needle),
            "{args:?}: {message}"
        );
    }
    let missing = write(
        "missing.urdf",
        r#"<robot name="m"><link name="arm"><collision><geometry><mesh filename="arm.stl"/></geometry></collision></link></robot>"#,
    );
    let output = sphaera(&["robot", &missing]);
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success()
            && message.contains("link \"arm\"")
            && message.contains("`arm.stl` not found"),
        "{message}"
    );

    let Some(urdf) = panda("robot_budgets_are_exact") else {
        return;
    };
    let report = json(&sphaera(&["robot", &urdf, "--budget", "40", "--json"]));
    assert_eq!(report["spheres"], 40, "{report}");
    assert_eq!(report["asked"], 40, "{report}");
    let links = report["links"].as_array().expect("links");
    let sum: u64 = links.iter().map(|l| l["spheres"].as_u64().unwrap()).sum();
    assert_eq!(sum, 40);
    let report = json(&sphaera(&[
        "robot",
        &urdf,
        "--tolerance",
        "0.015",
        "--effort",
        "quick",
        "--json",
    ]));
    assert!(report["asked"].is_null());
    for link in report["links"].as_array().expect("links") {
        assert_eq!(link["meets_tolerance"], true, "{link}");
        assert!(
            link["worst_protrusion"].as_f64().unwrap() <= 0.015,
            "{link}"
        );
        assert_eq!(link["coverage"], 1.0, "{link}");
    }
}
