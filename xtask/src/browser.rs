//! `cargo xtask browser-test`: `sphaera view` pages opened in headless Chromium.
//!
//! For the embedded bunny's page at every level of its tree (the page takes
//! `#level=K`): the page loads without console errors (none uncaught in Chromium's log,
//! none counted by the page's own `console.error` hook), its body reports the level and the
//! number of spheres drawn (equal to the JSON report's count), its side panel shows every
//! level's certified error as the report gives it, and a screenshot is not blank (pixels
//! of the drawing differ from the background). The pages and screenshots stay in
//! `target/browser-test/` as artefacts; `--update-images` also copies two screenshots to
//! `docs/images/` for the README.

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

pub fn browser_test(update_images: bool) -> Result<()> {
    let chromium = chromium()?;
    crate::cargo(&["build", "--locked", "-p", "sphaera-cli"])?;
    let out = Path::new("target/browser-test");
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let page = out.join("bunny.html");
    let report = Command::new("target/debug/sphaera")
        .args(["view", "-q", "--json", "-o"])
        .arg(&page)
        .output()
        .context("cannot run target/debug/sphaera")?;
    if !report.status.success() {
        bail!(
            "sphaera view failed: {}",
            String::from_utf8_lossy(&report.stderr)
        );
    }
    let report: serde_json::Value =
        serde_json::from_slice(&report.stdout).context("sphaera view --json is not JSON")?;
    let diagonal = report["diagonal"]
        .as_f64()
        .context("the report's diagonal")?;
    let levels = report["levels"].as_array().context("the report's levels")?;
    let url = format!(
        "file://{}",
        std::fs::canonicalize(&page)
            .with_context(|| format!("cannot find {}", page.display()))?
            .display()
    );
    let mut problems = Vec::new();
    for (k, level) in levels.iter().enumerate() {
        let count = level["spheres"].as_u64().context("a level's count")?;
        let at = format!("{url}#level={k}");
        let dom = headless(&chromium)
            .arg("--dump-dom")
            .arg(&at)
            .output()
            .context("cannot run Chromium")?;
        let text = String::from_utf8_lossy(&dom.stdout);
        let stderr = String::from_utf8_lossy(&dom.stderr);
        for error in console_errors(&stderr) {
            problems.push(format!("level {k}: console error: {error}"));
        }
        if body_attribute(&text, "data-console-errors").as_deref() != Some("0") {
            problems.push(format!(
                "level {k}: {:?} errors reported on the console",
                body_attribute(&text, "data-console-errors")
            ));
        }
        if body_attribute(&text, "data-ready").as_deref() != Some("true") {
            problems.push(format!("level {k}: the page did not finish loading"));
        }
        if body_attribute(&text, "data-level") != Some(k.to_string()) {
            problems.push(format!(
                "level {k}: the page shows level {:?}",
                body_attribute(&text, "data-level")
            ));
        }
        if body_attribute(&text, "data-drawn-spheres") != Some(count.to_string()) {
            problems.push(format!(
                "level {k}: {:?} spheres drawn, the report has {count}",
                body_attribute(&text, "data-drawn-spheres")
            ));
        }
        // The side panel shows every level's certified error as the report gives it.
        for (j, other) in levels.iter().enumerate() {
            if let Some(upper) = other["error_upper"].as_f64() {
                let shown = format!("{:.3} %", 100.0 * upper / diagonal);
                if !text.contains(&shown) {
                    problems.push(format!(
                        "level {k}: the panel lacks level {j}'s error {shown}"
                    ));
                }
            }
        }
        let shot = out.join(format!("bunny-level{k}.png"));
        let screenshot = headless(&chromium)
            .arg(format!("--screenshot={}", shot.display()))
            .arg(&at)
            .output()
            .context("cannot run Chromium")?;
        if !screenshot.status.success() {
            problems.push(format!("level {k}: no screenshot"));
            continue;
        }
        let image = image::open(&shot)
            .with_context(|| format!("cannot read {}", shot.display()))?
            .to_rgb8();
        // The drawing is right of the side panel.
        let (width, height) = image.dimensions();
        let mut drawn = 0u64;
        let mut total = 0u64;
        for y in 0..height {
            for x in width / 3..width {
                let p = image.get_pixel(x, y).0;
                total += 1;
                if p.iter().zip(BACKGROUND).any(|(&a, b)| a.abs_diff(b) > 8) {
                    drawn += 1;
                }
            }
        }
        let share = drawn as f64 / total.max(1) as f64;
        eprintln!(
            "  level {k}: {count} spheres drawn, {:.1} % of the view drawn",
            100.0 * share
        );
        if share < 0.02 {
            problems.push(format!(
                "level {k}: the canvas is blank ({:.2} % drawn)",
                100.0 * share
            ));
        }
    }
    if !problems.is_empty() {
        bail!("the browser test failed:\n  {}", problems.join("\n  "));
    }
    if update_images {
        std::fs::create_dir_all("docs/images").context("cannot create docs/images")?;
        let last = levels.len().saturating_sub(1);
        for k in [1.min(last), last] {
            let from = out.join(format!("bunny-level{k}.png"));
            let to = PathBuf::from(format!("docs/images/view-bunny-level{k}.png"));
            std::fs::copy(&from, &to)
                .with_context(|| format!("cannot copy {} to {}", from.display(), to.display()))?;
            eprintln!("  wrote {}", to.display());
        }
    }
    eprintln!(
        "browser test passed: {} levels, pages and screenshots in {}",
        levels.len(),
        out.display()
    );
    Ok(())
}
