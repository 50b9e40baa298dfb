//! The after-action report: one self-contained HTML file (no external URL, no script) with the
//! score, the metrics table (each value in a cell with a `data-metric` attribute naming the
//! metric, for machines), the placements, the structures, the timeline markers of a live
//! exercise (`data-marker-t-s`), and three inline SVG plots drawn with
//! plotters' SVG backend: axial force against time, axial force against depth, and the tip's
//! path against the targets (reference centre, tolerance circle, displaced centre at placement)
//! and the structures to spare (2D: the x–y plane; 3D: the two world axes along which the path,
//! targets and structures spread most). When the exercise names an expert run
//! ([`crate::expert`]), its path and force curves are overlaid in magenta with a legend
//! ("trainee", [`expert_label`]) and a table `#expert` compares the two; when it cannot be read
//! (a live session), `#expert-note` says why.

use std::fmt::Write as _;

use plotters::prelude::*;

use crate::geometry::Shape;
use crate::run::ExerciseRun;

/// Escapes text for HTML.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

type PlotResult = Result<String, String>;

fn bounds(pts: impl Iterator<Item = (f64, f64)>) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for (x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        return ((0.0, 1.0), (0.0, 1.0));
    }
    let pad = |a: f64, b: f64| {
        let m = ((b - a) * 0.05).max(1e-9);
        (a - m, b + m)
    };
    (pad(x0, x1), pad(y0, y1))
}

/// The expert's series colour (magenta, apart from the trainee's blue and the marks' red/green).
const EXPERT: RGBColor = RGBColor(200, 0, 160);

/// The legend label of the expert's series in every plot.
pub fn expert_label(file: &str) -> String {
    format!("expert ({file})")
}

/// A line plot of the trainee's `pts` (and the expert's, labelled, when given), with red marks.
fn line_plot(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    pts: &[(f64, f64)],
    marks: &[(f64, f64)],
    expert: Option<(&str, &[(f64, f64)])>,
) -> PlotResult {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (640, 360)).into_drawing_area();
        let e = |e: &dyn std::fmt::Display| e.to_string();
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let ((x0, x1), (y0, y1)) = bounds(pts.iter().chain(expert.map_or(&[][..], |x| x.1)).copied());
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|x| e(&x))?;
        chart.configure_mesh().x_desc(x_desc).y_desc(y_desc).draw().map_err(|x| e(&x))?;
        let trainee = chart.draw_series(LineSeries::new(pts.iter().copied(), BLUE.stroke_width(2))).map_err(|x| e(&x))?;
        if let Some((label, xs)) = expert {
            trainee.label("trainee").legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
            chart
                .draw_series(LineSeries::new(xs.iter().copied(), EXPERT.stroke_width(2)))
                .map_err(|x| e(&x))?
                .label(label)
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], EXPERT.stroke_width(2)));
        }
        chart.draw_series(marks.iter().map(|&p| Circle::new(p, 5, RED.filled()))).map_err(|x| e(&x))?;
        if expert.is_some() {
            chart.configure_series_labels().background_style(WHITE.mix(0.85)).border_style(BLACK).draw().map_err(|x| e(&x))?;
        }
        root.present().map_err(|x| e(&x))?;
    }
    Ok(svg)
}

/// The two world axes the drawing spreads most along (x, y in 2D).
fn view_axes(run: &ExerciseRun) -> (usize, usize) {
    if run.dim == 2 {
        return (0, 1);
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let mut add = |p: [f64; 3]| {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    };
    run.trace.iter().filter(|p| p.depth_m > 0.0).for_each(|p| add(p.tip_m));
    run.expert.iter().flat_map(|x| &x.trace).filter(|p| p.depth_m > 0.0).for_each(|p| add(p.tip_m));
    run.targets.iter().for_each(|t| add(t.centre_m));
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&a, &b| (hi[b] - lo[b]).partial_cmp(&(hi[a] - lo[a])).unwrap_or(std::cmp::Ordering::Equal));
    let (a, b) = (axes[0].min(axes[1]), axes[0].max(axes[1]));
    (a, b)
}

fn path_plot(run: &ExerciseRun) -> PlotResult {
    let (a, b) = view_axes(run);
    let names = ["x", "y", "z"];
    let mm = |p: [f64; 3]| (p[a] * 1e3, p[b] * 1e3);
    let path: Vec<(f64, f64)> = run.trace.iter().filter(|p| p.depth_m > 0.0).map(|p| mm(p.tip_m)).collect();
    let expert_path: Vec<(f64, f64)> = run.expert.iter().flat_map(|x| &x.trace).filter(|p| p.depth_m > 0.0).map(|p| mm(p.tip_m)).collect();
    let mut all = path.clone();
    all.extend(&expert_path);
    for t in &run.targets {
        let (x, y) = mm(t.centre_m);
        let r = t.tolerance_m.max(t.radius_m) * 1e3;
        all.extend([(x - r, y - r), (x + r, y + r)]);
    }
    for s in &run.structures {
        match s.shape {
            Shape::Sphere { centre_m, radius_m } => {
                let (x, y) = mm(centre_m);
                let r = radius_m * 1e3;
                all.extend([(x - r, y - r), (x + r, y + r)]);
            }
            Shape::Box { min_m, max_m } => all.extend([mm(min_m), mm(max_m)]),
        }
    }
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (640, 520)).into_drawing_area();
        let e = |e: &dyn std::fmt::Display| e.to_string();
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let ((x0, x1), (y0, y1)) = bounds(all.iter().copied());
        // Equal scales: widen the narrower range.
        let (w, h) = (x1 - x0, y1 - y0);
        let aspect = 560.0 / 440.0;
        let (x0, x1, y0, y1) = if w / h > aspect {
            let c = 0.5 * (y0 + y1);
            (x0, x1, c - 0.5 * w / aspect, c + 0.5 * w / aspect)
        } else {
            let c = 0.5 * (x0 + x1);
            (c - 0.5 * h * aspect, c + 0.5 * h * aspect, y0, y1)
        };
        let mut chart = ChartBuilder::on(&root)
            .caption("Needle tip path against targets and structures", ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|x| e(&x))?;
        chart.configure_mesh().x_desc(format!("{} (mm)", names[a])).y_desc(format!("{} (mm)", names[b])).draw().map_err(|x| e(&x))?;
        let px_per_mm = 560.0 / (x1 - x0);
        for s in &run.structures {
            let style = RGBColor(200, 120, 0).mix(0.35).filled();
            match s.shape {
                Shape::Sphere { centre_m, radius_m } => {
                    chart.draw_series([Circle::new(mm(centre_m), (radius_m * 1e3 * px_per_mm) as i32, style)]).map_err(|x| e(&x))?;
                }
                Shape::Box { min_m, max_m } => {
                    chart.draw_series([Rectangle::new([mm(min_m), mm(max_m)], style)]).map_err(|x| e(&x))?;
                }
            }
        }
        for t in &run.targets {
            let c = mm(t.centre_m);
            chart
                .draw_series([Circle::new(c, (t.tolerance_m * 1e3 * px_per_mm).max(2.0) as i32, GREEN.stroke_width(1))])
                .map_err(|x| e(&x))?;
            chart.draw_series([Circle::new(c, 3, GREEN.filled())]).map_err(|x| e(&x))?;
        }
        let trainee = chart.draw_series(LineSeries::new(path.iter().copied(), BLUE.stroke_width(2))).map_err(|x| e(&x))?;
        if let Some(x) = &run.expert {
            trainee.label("trainee").legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
            chart
                .draw_series(LineSeries::new(expert_path.iter().copied(), EXPERT.stroke_width(2)))
                .map_err(|x| e(&x))?
                .label(expert_label(&x.file))
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], EXPERT.stroke_width(2)));
            chart.configure_series_labels().background_style(WHITE.mix(0.85)).border_style(BLACK).draw().map_err(|x| e(&x))?;
        }
        for (_, p) in &run.placements {
            chart.draw_series([Cross::new(mm(p.centre_m), 5, RED.stroke_width(2))]).map_err(|x| e(&x))?;
            chart.draw_series([Circle::new(mm(p.tip_m), 4, BLUE.filled())]).map_err(|x| e(&x))?;
        }
        root.present().map_err(|x| e(&x))?;
    }
    Ok(svg)
}

fn row(html: &mut String, key: &str, label: &str, value: f64, unit: &str, scale: f64) {
    let _ = writeln!(
        html,
        "<tr><th>{}</th><td data-metric=\"{key}\" data-value=\"{value:e}\">{:.4}</td><td>{unit}</td></tr>",
        esc(label),
        value * scale
    );
}

/// The report's HTML (module docs). An error only if a plot cannot be drawn.
pub fn report_html(run: &ExerciseRun) -> Result<String, String> {
    let m = &run.result.metrics;
    let s = &run.result.score;
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>After-action report: {}</title>\n<style>\nbody{{font-family:sans-serif;margin:2em;max-width:1400px}}table{{border-collapse:collapse;margin:1em 0}}th,td{{border:1px solid #bbb;padding:3px 8px;text-align:left}}td[data-metric]{{text-align:right}}.plots{{display:flex;flex-wrap:wrap;gap:1em}}.score{{font-size:2em}}\n</style>\n</head>\n<body>\n",
        esc(&run.exercise)
    );
    let _ = writeln!(h, "<h1>After-action report: {}</h1>", esc(&run.exercise));
    let _ = writeln!(h, "<p>{}</p>", esc(&run.description));
    let _ = writeln!(h, "<p>Scene <code>{}</code> ({}D), {} ticks at {} Hz.</p>", esc(&run.scene), run.dim, run.ticks, run.tick_rate_hz);
    let _ =
        writeln!(h, "<p class=\"score\">Score <span data-metric=\"score\" data-value=\"{:e}\">{:.1}</span> / 100</p>", s.total, s.total);
    h.push_str("<h2>Metrics</h2>\n<table id=\"metrics\">\n<tr><th>metric</th><th>value</th><th>unit</th></tr>\n");
    row(&mut h, "time_s", "time", m.time_s, "s", 1.0);
    row(&mut h, "insertions", "insertions", m.insertions as f64, "", 1.0);
    row(&mut h, "reinsertions", "reinsertions", m.reinsertions as f64, "", 1.0);
    row(&mut h, "redirections", "redirections", m.redirections as f64, "", 1.0);
    row(&mut h, "path_length_m", "path length in tissue", m.path_length_m, "mm", 1e3);
    row(&mut h, "max_depth_m", "deepest insertion", m.max_depth_m, "mm", 1e3);
    row(&mut h, "peak_axial_force_n", "peak axial force", m.peak_axial_force_n, "N", 1.0);
    row(&mut h, "mean_axial_force_n", "mean axial force in tissue", m.mean_axial_force_n, "N", 1.0);
    let st = &m.strain;
    if st.strain_samples > 0 {
        row(&mut h, "peak_strain", "peak equivalent tissue strain", st.peak_strain, "%", 100.0);
        row(
            &mut h,
            "damaged_area_m2",
            &format!("largest tissue area above {:.0} % strain", st.damage_strain * 100.0),
            st.damaged_area_m2,
            "mm²",
            1e6,
        );
        row(&mut h, "strain_samples_above", "strain samples above the threshold", st.samples_above as f64, "", 1.0);
        row(&mut h, "strain_samples", "strain samples", st.strain_samples as f64, "", 1.0);
    } else {
        h.push_str("<tr><th>tissue strain above a damage threshold</th><td>not computed</td><td>(computed in 2D only)</td></tr>\n");
    }
    for (k, v) in [
        ("accuracy", s.sub.accuracy),
        ("efficiency", s.sub.efficiency),
        ("path", s.sub.path),
        ("force", s.sub.force),
        ("safety", s.sub.safety),
        ("time", s.sub.time),
    ] {
        row(&mut h, &format!("sub_{k}"), &format!("sub-score: {k}"), v, "", 1.0);
    }
    row(&mut h, "penalty", "penalty (limits exceeded)", s.penalty, "points", 1.0);
    h.push_str("</table>\n<h2>Targets</h2>\n<table id=\"targets\">\n<tr><th>target</th><th>tolerance (mm)</th><th>placed at (s)</th><th>error (mm)</th><th>on target</th><th>closest approach (mm)</th></tr>\n");
    for (i, t) in m.targets.iter().enumerate() {
        let (at, err, on) = match &t.placement {
            Some(p) => (
                format!("{:.3}", p.t_s),
                format!("<td data-metric=\"target_{i}_error_m\" data-value=\"{:e}\">{:.4}</td>", p.error_m, p.error_m * 1e3),
                if p.on_target { "yes" } else { "no" },
            ),
            None => ("—".into(), "<td>not placed</td>".into(), "no"),
        };
        let _ = writeln!(
            h,
            "<tr><th>{}</th><td>{:.3}</td><td>{at}</td>{err}<td>{on}</td><td>{:.4}</td></tr>",
            esc(&t.name),
            t.tolerance_m * 1e3,
            t.closest_m * 1e3
        );
    }
    h.push_str("</table>\n");
    if !m.structures.is_empty() {
        h.push_str("<h2>Structures to spare</h2>\n<table id=\"structures\">\n<tr><th>structure</th><th>min clearance (mm)</th><th>intrusion depth (mm)</th><th>touched</th><th>samples touching</th></tr>\n");
        for (j, st) in m.structures.iter().enumerate() {
            let c = st.min_clearance_m.map_or("—".to_owned(), |c| format!("{:.4}", c * 1e3));
            let _ = writeln!(
                h,
                "<tr><th>{}</th><td data-metric=\"structure_{j}_clearance_m\" data-value=\"{:e}\">{c}</td><td data-metric=\"structure_{j}_intrusion_m\" data-value=\"{:e}\">{:.4}</td><td>{}</td><td>{}</td></tr>",
                esc(&st.name),
                st.min_clearance_m.unwrap_or(f64::INFINITY),
                st.intrusion_depth_m,
                st.intrusion_depth_m * 1e3,
                if st.touched { "yes" } else { "no" },
                st.touching_samples
            );
        }
        h.push_str("</table>\n");
    }
    if !run.markers.is_empty() {
        h.push_str("<h2>Timeline markers</h2>\n<table id=\"markers\">\n<tr><th>t (s)</th><th>tick</th><th>marker</th></tr>\n");
        for m in &run.markers {
            let _ =
                writeln!(h, "<tr><td data-marker-t-s=\"{:e}\">{:.3}</td><td>{}</td><td>{}</td></tr>", m.t_s, m.t_s, m.tick, esc(&m.label));
        }
        h.push_str("</table>\n");
    }
    if !run.refused_placements.is_empty() {
        h.push_str("<h2>Refused declarations</h2>\n<ul>\n");
        for (t, why) in &run.refused_placements.first {
            let _ = writeln!(h, "<li>t = {t:.3} s: {}</li>", esc(why));
        }
        h.push_str("</ul>\n");
        let left_out = run.refused_placements.left_out();
        if left_out > 0 {
            let _ = writeln!(
                h,
                "<p id=\"refused-left-out\">{} declarations refused in all: the first {} are listed, {left_out} more are left out.</p>",
                run.refused_placements.total,
                run.refused_placements.first.len()
            );
        }
    }
    let ft: Vec<(f64, f64)> = run.trace.iter().map(|p| (p.t_s, p.axial_force_n)).collect();
    let fd: Vec<(f64, f64)> = run.trace.iter().map(|p| (p.depth_m * 1e3, p.axial_force_n)).collect();
    let mut place_t: Vec<(f64, f64)> = run.placements.iter().map(|(_, p)| (p.t_s, nearest(&ft, p.t_s))).collect();
    place_t.extend(run.markers.iter().map(|m| (m.t_s, nearest(&ft, m.t_s))));
    let label = run.expert.as_ref().map(|x| expert_label(&x.file));
    type Curves = (Vec<(f64, f64)>, Vec<(f64, f64)>);
    let (eft, efd): Curves =
        run.expert.iter().flat_map(|x| &x.trace).map(|p| ((p.t_s, p.axial_force_n), (p.depth_m * 1e3, p.axial_force_n))).unzip();
    expert_section(&mut h, run);
    h.push_str("<h2>Curves</h2>\n<div class=\"plots\">\n");
    h.push_str(&line_plot(
        "Axial force against time (red: placements and markers)",
        "t (s)",
        "axial force (N)",
        &ft,
        &place_t,
        label.as_deref().map(|l| (l, &eft[..])),
    )?);
    h.push('\n');
    h.push_str(&line_plot(
        "Axial force against depth",
        "inserted length (mm)",
        "axial force (N)",
        &fd,
        &[],
        label.as_deref().map(|l| (l, &efd[..])),
    )?);
    h.push('\n');
    h.push_str(&path_plot(run)?);
    h.push_str("\n</div>\n<p>Path plot: blue, the tip inside the tissue; green, targets at their reference centres with their tolerance circles; red crosses, the displaced centres at each placement (blue dots, the tip there); orange, structures to spare; magenta, the expert's run when there is one.</p>\n</body>\n</html>\n");
    Ok(h)
}

/// The expert comparison: the note when the named expert run could not be read, otherwise a
/// table of trainee against expert (cells `data-trainee` / `data-expert` naming the metric,
/// `data-value` its SI value) and what of the expert's metrics could not be computed.
fn expert_section(h: &mut String, run: &ExerciseRun) {
    if let Some(n) = &run.expert_note {
        let _ = writeln!(h, "<h2>Expert comparison</h2>\n<p id=\"expert-note\">{}</p>", esc(n));
    }
    let Some(x) = &run.expert else { return };
    let (t, e) = (&run.result, &x.result);
    let _ = writeln!(
        h,
        "<h2>Expert comparison</h2>\n<p>Expert run <code>{}</code> ({} rows), drawn in magenta in the plots below; its metrics by the same definitions from its rows.</p>",
        esc(&x.file),
        x.rows
    );
    h.push_str("<table id=\"expert\">\n<tr><th>metric</th><th>trainee</th><th>expert</th><th>unit</th></tr>\n");
    let mut line = |key: &str, label: &str, a: f64, b: f64, unit: &str, scale: f64| {
        let _ = writeln!(
            h,
            "<tr><th>{}</th><td data-trainee=\"{key}\" data-value=\"{a:e}\">{:.4}</td><td data-expert=\"{key}\" data-value=\"{b:e}\">{:.4}</td><td>{unit}</td></tr>",
            esc(label),
            a * scale,
            b * scale
        );
    };
    let (tm, em) = (&t.metrics, &e.metrics);
    line("time_s", "time", tm.time_s, em.time_s, "s", 1.0);
    line("path_length_m", "path length in tissue", tm.path_length_m, em.path_length_m, "mm", 1e3);
    line("peak_axial_force_n", "peak axial force", tm.peak_axial_force_n, em.peak_axial_force_n, "N", 1.0);
    line("mean_axial_force_n", "mean axial force in tissue", tm.mean_axial_force_n, em.mean_axial_force_n, "N", 1.0);
    line("insertions", "insertions", tm.insertions as f64, em.insertions as f64, "", 1.0);
    line("redirections", "redirections", tm.redirections as f64, em.redirections as f64, "", 1.0);
    for (i, (a, b)) in tm.targets.iter().zip(&em.targets).enumerate() {
        if let (Some(pa), Some(pb)) = (a.placement, b.placement) {
            line(&format!("target_{i}_error_m"), &format!("targeting error: {}", a.name), pa.error_m, pb.error_m, "mm", 1e3);
        }
    }
    line("score", "score", t.score.total, e.score.total, "/ 100", 1.0);
    h.push_str("</table>\n");
    for n in &x.notes {
        let _ = writeln!(h, "<p class=\"expert-note\">Expert run: {}</p>", esc(n));
    }
}

fn nearest(pts: &[(f64, f64)], t: f64) -> f64 {
    pts.iter().min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs())).map_or(0.0, |p| p.1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exercise::{ExpertSource, load_exercise};
    use crate::run::run_exercise;
    use needlesim_core::mesh::MeshLimits;

    #[test]
    fn an_unreadable_expert_fails_a_scripted_run_and_is_a_note_in_a_report() {
        let mut ex = load_exercise("biopsy-2d").unwrap();
        ex.expert = Some(ExpertSource { file: "gone.csv".into(), text: Err("cannot read it: not found".into()) });
        let e = run_exercise(&ex, None, None, 100_000, &MeshLimits::default()).unwrap_err().to_string();
        assert_eq!(e, "expert run gone.csv: cannot read it: not found");
        // A live session's report: written, with the note, and no expert series.
        ex.expert = None;
        let mut run = run_exercise(&ex, None, None, 100_000, &MeshLimits::default()).unwrap();
        assert!(run.expert.is_none());
        run.expert_note = Some(format!("the expert run could not be read: {e}"));
        let html = report_html(&run).unwrap();
        assert!(
            html.contains("<p id=\"expert-note\">the expert run could not be read: expert run gone.csv: cannot read it: not found</p>")
        );
        assert!(!html.contains("id=\"expert\"") && !html.contains("expert ("));
    }
}
