//! tmp
#![allow(missing_docs)]
use plotters::prelude::*;
fn main() -> anyhow::Result<()> {
    let root = SVGBackend::new("/tmp/t.svg", (640, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption("Load time", ("sans-serif", 20))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d((1e2f64..1e6f64).log_scale(), 0f64..2f64)?;
    chart
        .configure_mesh()
        .x_desc("triangles")
        .y_desc("seconds")
        .draw()?;
    chart.draw_series(PointSeries::of_element(
        vec![(1e3, 0.5), (1e5, 1.0)],
        4,
        &RED,
        &|c, s, st| EmptyElement::at(c) + Circle::new((0, 0), s, st.filled()),
    ))?;
    root.present()?;
    Ok(())
}
