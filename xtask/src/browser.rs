//! `cargo xtask browser-test`: `sphaera view` pages opened in headless Chromium.
//!
//! For the embedded bunny's page at every level of its tree (the page takes
//! `#level=K`): the page loads without console errors (none uncaught in Chromium's log,
//! none counted by the page's own `console.error` hook), its body reports the level and the
//! number of spheres drawn (equal to the JSON report's count), its side panel shows every
//! level's certified error as the report gives it, and a screenshot is not blank (pixels
//! of the drawing differ from the background). The pages and screenshots stay in
//! `browser-test/` in the target directory as artefacts; `--update-images` also copies two
//! screenshots to `docs/images/` for the README.
//!
//! Then the bunny with every layer (`--simplify`, `--hal`, `--hausdorff` against its own
//! simplification, `--silhouette`): every surface of the page's menu is drawn with the
//! report's triangles and its bound in the panel (`#surface=S`), the distance colours show
//! with the certified bounds in their legend (`#colour=distance`), and the silhouette
//! labels of one of the report's cameras colour the mesh in grey levels (`#colour=labels`).
//! Then hostile file names, and the robot page (`browser/robot.rs`).

mod robot;

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context, Result, bail};

/// The page's background, `#f4f5f7`.
const BACKGROUND: [u8; 3] = [0xf4, 0xf5, 0xf7];

/// The Chromium found on the `PATH`, or how to install it.
fn chromium() -> Result<PathBuf> {
    for name in [
        "chromium",
        "chromium-browser",
        "google-chrome",
        "google-chrome-stable",
    ] {
        if let Ok(output) = Command::new("which").arg(name).output()
            && output.status.success()
        {
            let path = String::from_utf8_lossy(&output.stdout).trim().to_owned();
            if !path.is_empty() {
                return Ok(PathBuf::from(path));
            }
        }
    }
    bail!(
        "the browser test needs Chromium, which is not installed: on Debian or Ubuntu, \
         `sudo apt-get install chromium` (`.ci/run` installs it)"
    )
}

/// Chromium's headless flags: software WebGL, no sandbox (CI runs as root), a fixed
/// window, console messages on stderr, and time for the page's script to run.
fn headless(chromium: &Path) -> Command {
    let mut command = Command::new(chromium);
    command.args([
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        "--hide-scrollbars",
        "--window-size=1200,800",
        "--enable-logging=stderr",
        "--v=0",
        "--virtual-time-budget=10000",
    ]);
    command
}

/// Console lines of the page that report an error.
fn console_errors(stderr: &str) -> Vec<String> {
    stderr
        .lines()
        .filter(|line| line.contains("CONSOLE"))
        .filter(|line| {
            let lower = line.to_lowercase();
            lower.contains("uncaught") || lower.contains("error")
        })
        .map(str::to_owned)
        .collect()
}

/// The attribute `name` of the `<body …>` tag in `dom`.
fn body_attribute(dom: &str, name: &str) -> Option<String> {
    let start = dom.find("<body")?;
    let tag = &dom[start..start + dom[start..].find('>')?];
    let key = format!("{name}=\"");
    let at = tag.find(&key)? + key.len();
    Some(tag[at..at + tag[at..].find('"')?].to_owned())
}

/// A page opened in headless Chromium: its DOM after the script ran, and what went wrong
/// on the way (console errors, the page not ready).
fn open(chromium: &Path, url: &str, what: &str, problems: &mut Vec<String>) -> Result<String> {
    let dom = headless(chromium)
        .arg("--dump-dom")
        .arg(url)
        .output()
        .context("cannot run Chromium")?;
    let text = String::from_utf8_lossy(&dom.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&dom.stderr);
    for error in console_errors(&stderr) {
        problems.push(format!("{what}: console error: {error}"));
    }
    if body_attribute(&text, "data-console-errors").as_deref() != Some("0") {
        problems.push(format!(
            "{what}: {:?} errors reported on the console",
            body_attribute(&text, "data-console-errors")
        ));
    }
    if body_attribute(&text, "data-ready").as_deref() != Some("true") {
        problems.push(format!("{what}: the page did not finish loading"));
    }
    Ok(text)
}

/// A screenshot of `url` in `shot`, or `None` (a problem noted) when Chromium took none.
fn screenshot(
    chromium: &Path,
    url: &str,
    shot: &Path,
    what: &str,
    problems: &mut Vec<String>,
) -> Result<Option<image::RgbImage>> {
    let output = headless(chromium)
        .arg(format!("--screenshot={}", shot.display()))
        .arg(url)
        .output()
        .context("cannot run Chromium")?;
    if !output.status.success() {
        problems.push(format!("{what}: no screenshot"));
        return Ok(None);
    }
    let image = image::open(shot)
        .with_context(|| format!("cannot read {}", shot.display()))?
        .to_rgb8();
    Ok(Some(image))
}

/// The share of the drawing (right of the side panel) whose pixels pass `test`.
fn share(image: &image::RgbImage, test: impl Fn([u8; 3]) -> bool) -> f64 {
    let (width, height) = image.dimensions();
    let mut hits = 0u64;
    let mut total = 0u64;
    for y in 0..height {
        for x in width / 3..width {
            total += 1;
            if test(image.get_pixel(x, y).0) {
                hits += 1;
            }
        }
    }
    hits as f64 / total.max(1) as f64
}

/// Pixels that differ from the background.
fn drawn(p: [u8; 3]) -> bool {
    p.iter().zip(BACKGROUND).any(|(&a, b)| a.abs_diff(b) > 8)
}

/// Runs the dev profile's `sphaera` with `args`; its JSON report.
fn sphaera_json<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Result<serde_json::Value> {
    let cli = crate::debug_cli()?;
    let report = Command::new(&cli)
        .args(args)
        .output()
        .with_context(|| format!("cannot run {}", cli.display()))?;
    if !report.status.success() {
        let shown: Vec<String> = args
            .iter()
            .map(|a| a.as_ref().to_string_lossy().into_owned())
            .collect();
        bail!(
            "sphaera {} failed: {}",
            shown.join(" "),
            String::from_utf8_lossy(&report.stderr)
        );
    }
    serde_json::from_slice(&report.stdout).context("sphaera's --json output is not JSON")
}

fn file_url(page: &Path) -> Result<String> {
    Ok(format!(
        "file://{}",
        std::fs::canonicalize(page)
            .with_context(|| format!("cannot find {}", page.display()))?
            .display()
    ))
}

/// `value` as the page writes a share of the diagonal: `1.234 %`.
fn percent(value: f64, diagonal: f64) -> String {
    format!("{:.3} %", 100.0 * value / diagonal)
}

pub fn browser_test(update_images: bool) -> Result<()> {
    let chromium = chromium()?;
    crate::built_cli()?;
    let out = &crate::target_dir()?.join("browser-test");
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let mut problems = Vec::new();
    let levels = tree_levels(&chromium, out, &mut problems)?;
    every_layer(&chromium, out, &mut problems)?;
    hostile_names(&chromium, out, &mut problems)?;
    robot::robot_page(&chromium, out, &mut problems)?;
    if !problems.is_empty() {
        bail!("the browser test failed:\n  {}", problems.join("\n  "));
    }
    if update_images {
        std::fs::create_dir_all("docs/images").context("cannot create docs/images")?;
        let last = levels.saturating_sub(1);
        let mut copies: Vec<(PathBuf, PathBuf)> = [1.min(last), last]
            .into_iter()
            .map(|k| {
                (
                    out.join(format!("bunny-level{k}.png")),
                    PathBuf::from(format!("docs/images/view-bunny-level{k}.png")),
                )
            })
            .collect();
        copies.push((
            out.join("bunny-distance.png"),
            PathBuf::from("docs/images/view-bunny-distance.png"),
        ));
        for (from, to) in copies {
            std::fs::copy(&from, &to)
                .with_context(|| format!("cannot copy {} to {}", from.display(), to.display()))?;
            eprintln!("  wrote {}", to.display());
        }
    }
    eprintln!(
        "browser test passed: {levels} levels, every layer, hostile names, the robot page; pages and screenshots in {}",
        out.display()
    );
    Ok(())
}

/// Pages of meshes whose paths hold what HTML reacts to (a `</script>` across folders, a
/// `<!--<script>`, quotes and an ampersand, a line break, bytes that are not UTF-8): each
/// page loads without a console error, draws its spheres, and shows the name as text.
fn hostile_names(chromium: &Path, out: &Path, problems: &mut Vec<String>) -> Result<()> {
    let base = out.join("hostile");
    if base.exists() {
        std::fs::remove_dir_all(&base)
            .with_context(|| format!("cannot clear {}", base.display()))?;
    }
    let mut meshes = vec![
        base.join("x<").join("script>y").join("m.obj"),
        base.join("x<!--<script>y.obj"),
        base.join("\"q' & <b>.obj"),
        base.join("line\nbreak.obj"),
    ];
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        meshes.push(base.join(std::ffi::OsStr::from_bytes(b"caf\xe9.obj")));
    }
    for (i, mesh) in meshes.iter().enumerate() {
        let what = format!(
            "hostile name {:?}",
            mesh.strip_prefix(&base).unwrap_or(mesh)
        );
        if let Some(folder) = mesh.parent() {
            std::fs::create_dir_all(folder)
                .with_context(|| format!("cannot create {}", folder.display()))?;
        }
        let mesh_arg = mesh.as_os_str();
        sphaera_json(&[
            "simplify".as_ref(),
            "-q".as_ref(),
            "--json".as_ref(),
            "--ratio".as_ref(),
            "0.2".as_ref(),
            "-o".as_ref(),
            mesh_arg,
        ])?;
        let page = base.join(format!("page-{i}.html"));
        let report = sphaera_json(&[
            "view".as_ref(),
            mesh_arg,
            "-q".as_ref(),
            "--json".as_ref(),
            "-o".as_ref(),
            page.as_os_str(),
        ])?;
        let text = open(chromium, &file_url(&page)?, &what, problems)?;
        let drawn = body_attribute(&text, "data-drawn-spheres");
        if drawn.as_deref().is_none_or(|n| n == "0") {
            problems.push(format!("{what}: no sphere drawn ({drawn:?})"));
        }
        let name = report["mesh"].as_str().unwrap_or_default();
        let shown = name
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        if name.is_empty() || !text.contains(&shown) {
            problems.push(format!("{what}: the page does not show the name {name:?}"));
        }
    }
    eprintln!("  hostile names: {} pages load and draw", meshes.len());
    Ok(())
}

/// The embedded bunny's page at every level of its tree; the number of levels.
fn tree_levels(chromium: &Path, out: &Path, problems: &mut Vec<String>) -> Result<usize> {
    let page = out.join("bunny.html");
    let page_arg = page.to_str().context("a UTF-8 path")?;
    let report = sphaera_json(&["view", "-q", "--json", "-o", page_arg])?;
    let diagonal = report["diagonal"]
        .as_f64()
        .context("the report's diagonal")?;
    let levels = report["levels"].as_array().context("the report's levels")?;
    let url = file_url(&page)?;
    for (k, level) in levels.iter().enumerate() {
        let count = level["spheres"].as_u64().context("a level's count")?;
        let at = format!("{url}#level={k}");
        let what = format!("level {k}");
        let text = open(chromium, &at, &what, problems)?;
        if body_attribute(&text, "data-level") != Some(k.to_string()) {
            problems.push(format!(
                "{what}: the page shows level {:?}",
                body_attribute(&text, "data-level")
            ));
        }
        if body_attribute(&text, "data-drawn-spheres") != Some(count.to_string()) {
            problems.push(format!(
                "{what}: {:?} spheres drawn, the report has {count}",
                body_attribute(&text, "data-drawn-spheres")
            ));
        }
        // The side panel shows every level's certified error as the report gives it.
        for (j, other) in levels.iter().enumerate() {
            if let Some(upper) = other["error_upper"].as_f64() {
                let shown = percent(upper, diagonal);
                if !text.contains(&shown) {
                    problems.push(format!("{what}: the panel lacks level {j}'s error {shown}"));
                }
            }
        }
        let shot = out.join(format!("bunny-level{k}.png"));
        let Some(image) = screenshot(chromium, &at, &shot, &what, problems)? else {
            continue;
        };
        let share = share(&image, drawn);
        eprintln!(
            "  level {k}: {count} spheres drawn, {:.1} % of the view drawn",
            100.0 * share
        );
        if share < 0.02 {
            problems.push(format!(
                "{what}: the canvas is blank ({:.2} % drawn)",
                100.0 * share
            ));
        }
    }
    Ok(levels.len())
}

/// The bunny with every layer: each surface of the menu drawn with the report's
/// triangles and its bound in the panel; the distance colours with their legend and
/// certified bounds; the silhouette labels in grey levels from a camera of the set.
fn every_layer(chromium: &Path, out: &Path, problems: &mut Vec<String>) -> Result<()> {
    let other = out.join("bunny-simplified.obj");
    let other_arg = other.to_str().context("a UTF-8 path")?;
    sphaera_json(&[
        "simplify", "-q", "--json", "--ratio", "0.15", "-o", other_arg,
    ])?;
    let page = out.join("bunny-every-layer.html");
    let page_arg = page.to_str().context("a UTF-8 path")?;
    let report = sphaera_json(&[
        "view",
        "-q",
        "--json",
        "--simplify",
        "0.1",
        "--hal",
        "1%",
        "--hausdorff",
        other_arg,
        "--silhouette",
        "-o",
        page_arg,
    ])?;
    let diagonal = report["diagonal"]
        .as_f64()
        .context("the report's diagonal")?;
    let url = file_url(&page)?;
    let surfaces = report["surfaces"]
        .as_array()
        .context("the report's surfaces")?;
    let mut expected = vec![(report["triangles"].as_u64().context("triangles")?, None)];
    for surface in surfaces {
        expected.push((
            surface["triangles"]
                .as_u64()
                .context("a surface's triangles")?,
            surface["bound"].as_f64(),
        ));
    }
    // The input, the first and last rung of the simplification, the first HAL level and
    // the HAL approximation (each page load takes seconds of software rendering).
    let kind = |k: &str| surfaces.iter().position(|s| s["kind"] == k).map(|i| i + 1);
    let last_rung = surfaces
        .iter()
        .rposition(|s| s["kind"] == "simplified")
        .map(|i| i + 1);
    let mut chosen: Vec<usize> = [
        Some(0),
        kind("simplified"),
        last_rung,
        kind("hal_level"),
        kind("hal_tolerance"),
    ]
    .into_iter()
    .flatten()
    .collect();
    chosen.dedup();
    for &s in &chosen {
        let (triangles, bound) = &expected[s];
        let what = format!("surface {s}");
        let text = open(chromium, &format!("{url}#surface={s}"), &what, problems)?;
        if body_attribute(&text, "data-surface") != Some(s.to_string())
            || body_attribute(&text, "data-drawn-triangles") != Some(triangles.to_string())
        {
            problems.push(format!(
                "{what}: surface {:?} with {:?} triangles drawn, the report has {triangles}",
                body_attribute(&text, "data-surface"),
                body_attribute(&text, "data-drawn-triangles")
            ));
        }
        if let Some(bound) = bound {
            let shown = percent(*bound, diagonal);
            if !text.contains(&shown) {
                problems.push(format!("{what}: the panel lacks its bound {shown}"));
            }
        }
    }
    eprintln!(
        "  surfaces {chosen:?} of {} drawn as reported",
        expected.len()
    );

    // The distance to the other mesh: colours, the legend, the certified bounds.
    let at = format!("{url}#colour=distance&spheres=off");
    let text = open(chromium, &at, "distance colours", problems)?;
    let hausdorff = &report["hausdorff"];
    for key in ["lower", "upper"] {
        let shown = percent(hausdorff[key].as_f64().context("a bound")?, diagonal);
        if !text.contains(&shown) {
            problems.push(format!(
                "distance colours: the legend lacks the {key} bound {shown}"
            ));
        }
    }
    if body_attribute(&text, "data-colour").as_deref() != Some("distance") {
        problems.push("distance colours: not shown".to_owned());
    }
    let shot = out.join("bunny-distance.png");
    if let Some(image) = screenshot(chromium, &at, &shot, "distance colours", problems)? {
        // The colour map's hues: strongly saturated pixels, which the plain mesh lacks.
        let coloured = share(&image, |[r, g, b]| r.max(g).max(b) - r.min(g).min(b) > 100);
        eprintln!(
            "  distance colours: {:.1} % of the view coloured",
            100.0 * coloured
        );
        if coloured < 0.02 {
            problems.push(format!(
                "distance colours: {:.2} % of the view coloured",
                100.0 * coloured
            ));
        }
    }

    // Silhouette labels: grey levels from one of the cameras, black at the outline.
    let at = format!("{url}#colour=labels&spheres=off");
    let text = open(chromium, &at, "silhouette labels", problems)?;
    let views = report["silhouette"]["views"].as_u64().context("views")?;
    let shown = body_attribute(&text, "data-label-view").and_then(|v| v.parse::<u64>().ok());
    if shown.is_none_or(|v| v >= views) {
        problems.push(format!(
            "silhouette labels: the labels of view {shown:?} shown, of {views}"
        ));
    }
    let shot = out.join("bunny-labels.png");
    if let Some(image) = screenshot(chromium, &at, &shot, "silhouette labels", problems)? {
        let dark = share(&image, |p| p.iter().all(|&c| c < 70));
        eprintln!(
            "  silhouette labels: {:.1} % of the view dark",
            100.0 * dark
        );
        if dark < 0.002 {
            problems.push(format!(
                "silhouette labels: {:.2} % of the view dark (the outline should be black)",
                100.0 * dark
            ));
        }
    }
    Ok(())
}
