//! The figures behind the crate docs: the Franka Panda and the KUKA iiwa spherized at a
//! few budgets, one CSV row per link (spheres asked and given, certified worst protrusion
//! in the link's units and in % of its diagonal, seconds) and one summary line per robot
//! and budget on stderr (spheres given of those asked, the worst protrusion over the
//! links in millimetres and in % of its link's diagonal, the wall time):
//!
//! `cargo run --release -p sphaera-robot --example robot_figures [-- BUDGET...] > figures.csv`
//!
//! A budget is `N` (spheres per link), `total:N`, `P%` (a tolerance per link, in % of its
//! diagonal) or `Dmm` (a tolerance in millimetres); by default `8 16 32 64 total:100
//! total:300 5% 10mm 5mm`. The robots come from the shared data folder (`SPHAERA_DATA`,
//! else `../shared/data` beside the repository).

#![allow(clippy::print_stdout, clippy::print_stderr)]

use std::time::Instant;

use sphaera_robot::{Length, MeshResolver, SphereBudget, SpherizeOptions, Urdf, spherize};

const ROBOTS: [(&str, &str); 2] = [
    ("panda", "franka_panda/panda.urdf"),
    ("kuka", "kuka_iiwa/model.urdf"),
];

fn budget(text: &str) -> Result<SphereBudget, String> {
    if let Some(mm) = text.strip_suffix("mm") {
        let mm: f64 = mm.parse().map_err(|_| format!("bad budget {text}"))?;
        return Ok(SphereBudget::Tolerance(Length::Absolute(mm / 1000.0)));
    }
    if let Some(percent) = text.strip_suffix('%') {
        let p: f64 = percent.parse().map_err(|_| format!("bad budget {text}"))?;
        return Ok(SphereBudget::Tolerance(Length::RelativeToDiagonal(
            p / 100.0,
        )));
    }
    if let Some(total) = text.strip_prefix("total:") {
        return total
            .parse()
            .map(SphereBudget::Total)
            .map_err(|_| format!("bad budget {text}"));
    }
    text.parse()
        .map(SphereBudget::PerLink)
        .map_err(|_| format!("bad budget {text}"))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    let texts: Vec<String> = if arguments.is_empty() {
        [
            "8",
            "16",
            "32",
            "64",
            "total:100",
            "total:300",
            "5%",
            "10mm",
            "5mm",
        ]
        .map(str::to_owned)
        .to_vec()
    } else {
        arguments
    };
    let Some(data) = sphaera_tests::data_dir("robot_figures") else {
        return Err("no shared data folder".into());
    };
    println!(
        "robot,budget,link,triangles,closed,asked,spheres,worst_protrusion,worst_percent,seconds"
    );
    for (robot, file) in ROBOTS {
        let path = data.join(sphaera_tests::URDF_ASSETS).join(file);
        let urdf = Urdf::read(&path)?;
        let resolver = MeshResolver::new(urdf.folder());
        for text in &texts {
            let options = SpherizeOptions::default().with_budget(budget(text)?);
            let started = Instant::now();
            let spheres = spherize(&urdf, &resolver, &options)?;
            let seconds = started.elapsed().as_secs_f64();
            let mut worst_percent: f64 = 0.0;
            for link in &spheres.links {
                let r = &link.report;
                let percent = 100.0 * r.worst_protrusion / r.diagonal;
                worst_percent = worst_percent.max(percent);
                println!(
                    "{robot},{text},{},{},{},{},{},{:.6e},{percent:.3},{:.3}",
                    r.link,
                    r.triangles,
                    r.closed,
                    r.budget.map_or_else(String::new, |n| n.to_string()),
                    r.spheres,
                    r.worst_protrusion,
                    r.seconds
                );
            }
            let worst = spheres
                .links
                .iter()
                .map(|l| l.report.worst_protrusion)
                .fold(0.0, f64::max);
            let asked: Option<usize> = spheres.links.iter().map(|l| l.report.budget).sum();
            eprintln!(
                "{robot:>5} {text:>9}: {:>4} spheres{}, worst {:.2} mm (at most {worst_percent:.2} % of a link's diagonal), {seconds:.2} s",
                spheres.sphere_count(),
                asked.map_or_else(String::new, |a| format!(" of {a}")),
                1000.0 * worst
            );
        }
    }
    Ok(())
}
