//! The robot page (`sphaera view ROBOT.urdf`) in headless Chromium: a generated arm with
//! revolute, prismatic, fixed and mimic joints. The page loads without console errors,
//! draws every sphere of the report and lists every pair left out of self-collision
//! checks; it poses the links where the CLI's kinematics does, at the configuration it
//! opens with and at another given in its address (`#q=`), and moving the joints moves
//! the spheres; its screenshot is not blank.

use std::path::Path;

use anyhow::{Context, Result};

use super::{body_attribute, drawn, file_url, open, screenshot, share, sphaera_json};

/// A small arm of boxes and capsules (no mesh files): a base, a shoulder, an elbow, a
/// fixed flange and two fingers, one mimicking the other.
const ARM: &str = r#"<robot name="test arm">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="upper"><collision><origin xyz="0 0 0.2"/><geometry><capsule radius="0.04" length="0.3"/></geometry></collision></link>
  <link name="fore"><collision><origin xyz="0 0 0.15"/><geometry><capsule radius="0.03" length="0.25"/></geometry></collision></link>
  <link name="flange"/>
  <link name="finger_a"><collision><origin xyz="0 0 0.03"/><geometry><box size="0.01 0.02 0.06"/></geometry></collision></link>
  <link name="finger_b"><collision><origin xyz="0 0 0.03"/><geometry><box size="0.01 0.02 0.06"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 0.05"/><axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0 0 0.4" rpy="0 0 0.3"/><axis xyz="0 1 0"/><limit lower="-2" upper="2"/></joint>
  <joint name="wrist" type="fixed"><parent link="fore"/><child link="flange"/><origin xyz="0 0 0.3"/></joint>
  <joint name="grip_a" type="prismatic"><parent link="flange"/><child link="finger_a"/><origin xyz="0.02 0 0"/><axis xyz="1 0 0"/><limit lower="0" upper="0.04"/></joint>
  <joint name="grip_b" type="prismatic"><parent link="flange"/><child link="finger_b"/><origin xyz="-0.02 0 0"/><axis xyz="1 0 0"/><limit lower="-0.04" upper="0"/><mimic joint="grip_a" multiplier="-1"/></joint>
</robot>
"#;

/// `link:x,y,z;…` as the page writes its probe, parsed.
fn probes(text: &str) -> Vec<(String, [f64; 3])> {
    text.split(';')
        .filter_map(|entry| {
            let (link, xyz) = entry.rsplit_once(':')?;
            let v: Vec<f64> = xyz.split(',').filter_map(|t| t.parse().ok()).collect();
            Some((link.to_owned(), [*v.first()?, *v.get(1)?, *v.get(2)?]))
        })
        .collect()
}

/// Whether the page's probes are the report's, within the page's `f32` sphere centres.
fn same_places(page: &[(String, [f64; 3])], report: &serde_json::Value) -> bool {
    let Some(expected) = report["probes"].as_object() else {
        return false;
    };
    page.len() == expected.len()
        && page.iter().all(|(link, p)| {
            expected[link.as_str()].as_array().is_some_and(|e| {
                e.iter()
                    .zip(p)
                    .all(|(a, b)| a.as_f64().is_some_and(|a| (a - b).abs() <= 2e-5))
            })
        })
}

pub(super) fn robot_page(chromium: &Path, out: &Path, problems: &mut Vec<String>) -> Result<()> {
    let dir = out.join("robot");
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let urdf = dir.join("arm.urdf");
    std::fs::write(&urdf, ARM).with_context(|| format!("cannot write {}", urdf.display()))?;
    let page = dir.join("arm.html");
    let rest = sphaera_json(&[
        "view".as_ref(),
        urdf.as_os_str(),
        "-q".as_ref(),
        "-o".as_ref(),
        page.as_os_str(),
        "--spheres-per-link".as_ref(),
        "6".as_ref(),
        "--json".as_ref(),
    ])?;
    let posed_page = dir.join("arm-posed.html");
    let posed = sphaera_json(&[
        "view".as_ref(),
        urdf.as_os_str(),
        "-q".as_ref(),
        "-o".as_ref(),
        posed_page.as_os_str(),
        "--spheres-per-link".as_ref(),
        "6".as_ref(),
        "--joint".as_ref(),
        "shoulder=0.7".as_ref(),
        "--joint".as_ref(),
        "elbow=-1.1".as_ref(),
        "--joint".as_ref(),
        "grip_a=0.03".as_ref(),
        "--json".as_ref(),
    ])?;
    let url = file_url(&page)?;
    let dom = open(chromium, &url, "robot page", problems)?;
    let spheres = rest["spheres"].as_u64().unwrap_or(0);
    if body_attribute(&dom, "data-drawn-spheres") != Some(spheres.to_string()) || spheres == 0 {
        problems.push(format!(
            "robot page: {:?} spheres drawn, the report has {spheres}",
            body_attribute(&dom, "data-drawn-spheres")
        ));
    }
    let disabled: u64 = rest["disabled"].as_object().map_or(0, |d| {
        d.values().filter_map(serde_json::Value::as_u64).sum()
    });
    if body_attribute(&dom, "data-disabled-pairs") != Some(disabled.to_string()) || disabled == 0 {
        problems.push(format!(
            "robot page: {:?} pairs listed as left out, the report has {disabled}",
            body_attribute(&dom, "data-disabled-pairs")
        ));
    }
    let at_rest = probes(&body_attribute(&dom, "data-probe").unwrap_or_default());
    if !same_places(&at_rest, &rest) {
        problems.push(format!(
            "robot page: the links are not where the CLI puts them at rest: page {at_rest:?}, report {}",
            rest["probes"]
        ));
    }
    // The joints of the posed report, in the sliders' order, through the address.
    let order = ["shoulder", "elbow", "grip_a"];
    let values: Vec<String> = order
        .iter()
        .map(|j| posed["joints"][j].as_f64().unwrap_or(f64::NAN).to_string())
        .collect();
    let moved_url = format!("{url}#q={}", values.join(","));
    let dom = open(chromium, &moved_url, "robot page, joints moved", problems)?;
    let moved = probes(&body_attribute(&dom, "data-probe").unwrap_or_default());
    if !same_places(&moved, &posed) {
        problems.push(format!(
            "robot page: the links are not where the CLI puts them with the joints moved: page {moved:?}, report {}",
            posed["probes"]
        ));
    }
    if moved == at_rest {
        problems.push("robot page: moving the joints did not move the spheres".to_owned());
    }
    if let Some(image) = screenshot(
        chromium,
        &moved_url,
        &dir.join("arm.png"),
        "robot page",
        problems,
    )? && share(&image, drawn) < 0.002
    {
        problems.push("robot page: the screenshot is blank".to_owned());
    }
    Ok(())
}
