//! The motion suite's reports: the per-tick CSV, the JSON record and the Markdown table.

use std::fmt::Write as _;

use serde_json::{Value, json};

use super::measure::{Suite, TickRecord};
use super::{ContactChoice, JACOBIAN_EVERY_TICKS, Motion, MotionOptions, TARGET_MAX_S, TARGET_P999_S, WORST_TICKS};
use crate::bench::machine;

pub(super) fn us(v: f64) -> String {
    if v.is_finite() { format!("{:.1}", v * 1e6) } else { "—".to_owned() }
}

fn num(v: f64) -> Value {
    if v.is_finite() { json!(v) } else { Value::Null }
}

fn targets_cell(misses: &[String], notes: &[String]) -> String {
    let mut cell = if misses.is_empty() { "met".to_owned() } else { format!("**misses**: {}", misses.join(", ")) };
    if !notes.is_empty() {
        let _ = write!(cell, "; _{}_", notes.join(", "));
    }
    cell
}

fn contact_label(c: ContactChoice, spacing_m: f64) -> String {
    match c {
        ContactChoice::Points => format!("material points every {:.1} mm", spacing_m * 1e3),
        ContactChoice::Nodes => "node capture, radius ½ mean edge".to_owned(),
    }
}

fn record_json(r: &TickRecord, phase: &str) -> Value {
    json!({
        "tick": r.tick, "phase": phase, "step_s": r.step_s, "converged": r.converged,
        "active_set_iterations": r.active_set_iterations, "pivots": r.pivots, "rotations": r.rotations,
        "stick_slip_changes": r.stick_slip_changes, "captures": r.captures, "releases": r.releases,
        "deferrals": r.deferrals, "shape_passes": r.shape_passes, "d": r.d, "cpu_wait_s": r.cpu_wait_ns as f64 * 1e-9,
        "page_faults": r.page_faults, "columns_before": r.columns_before,
        "stage_us": needlesim_core::sim::STAGE_NAMES.iter().zip(r.stage_ns).map(|(name, ns)| (name.to_string(), json!(ns as f64 * 1e-3))).collect::<serde_json::Map<_, _>>(),
    })
}

/// Every tick of every case as CSV: the case, the tick and its phase, the step time, the
/// counters of [`TickRecord`] and the time of each stage ([`needlesim_core::sim::STAGE_NAMES`]).
pub fn ticks_csv(suite: &Suite) -> String {
    use std::fmt::Write as _;
    let mut out = String::from(
        "motion,mesh,tick,phase,step_us,cpu_wait_us,page_faults,columns_before,active_set_iterations,pivots,rotations,stick_slip_changes,captures,releases,deferrals,shape_passes,d",
    );
    for name in needlesim_core::sim::STAGE_NAMES {
        let _ = write!(out, ",{}_us", name.replace(' ', "_"));
    }
    out.push('\n');
    for c in &suite.cases {
        let script = suite.scripts.iter().find(|s| s.motion == c.motion);
        for r in &c.ticks {
            let phase = script.map_or("", |sc| sc.phase_of(r.tick));
            let _ = write!(
                out,
                "{},{}x{},{},{phase},{:.3},{:.3},{},{},{},{},{},{},{},{},{},{},{}",
                c.motion.name(),
                c.n,
                c.n,
                r.tick,
                r.step_s * 1e6,
                r.cpu_wait_ns as f64 * 1e-3,
                r.page_faults,
                r.columns_before,
                r.active_set_iterations,
                r.pivots,
                r.rotations,
                r.stick_slip_changes,
                r.captures,
                r.releases,
                r.deferrals,
                r.shape_passes,
                r.d
            );
            for ns in r.stage_ns {
                let _ = write!(out, ",{:.3}", ns as f64 * 1e-3);
            }
            out.push('\n');
        }
    }
    out
}

/// The suite as one JSON object.
pub fn to_json(suite: &Suite, opts: &MotionOptions) -> Value {
    let script_of = |m: Motion| suite.scripts.iter().find(|s| s.motion == m);
    let cases: Vec<Value> = suite
        .cases
        .iter()
        .map(|c| {
            let [p50, p99, p999, max] = c.step_quantiles();
            let [j50, j99, jmax] = c.jacobian_quantiles();
            let s = &c.stats;
            let phase = |r: &TickRecord| script_of(c.motion).map_or("", |sc| sc.phase_of(r.tick));
            let worst: Vec<Value> = c.worst(WORST_TICKS, false).iter().map(|r| record_json(r, phase(r))).collect();
            let worst_unpreempted: Vec<Value> = c.worst(WORST_TICKS, true).iter().map(|r| record_json(r, phase(r))).collect();
            let unconverged: Vec<Value> = c
                .ticks
                .iter()
                .filter(|r| !r.converged)
                .take(20)
                .map(|r| record_json(r, script_of(c.motion).map_or("", |sc| sc.phase_of(r.tick))))
                .collect();
            // Columns prefetched before the ticks of each phase.
            let mut by_phase = serde_json::Map::new();
            if let Some(sc) = script_of(c.motion) {
                for r in &c.ticks {
                    let e = by_phase.entry(sc.phase_of(r.tick)).or_insert(json!(0));
                    *e = json!(e.as_u64().unwrap_or(0) + r.columns_before);
                }
            }
            let slow: Vec<&TickRecord> = c.ticks.iter().filter(|r| r.step_s > TARGET_P999_S).collect();
            let mut o = json!({
                "motion": c.motion.name(), "mesh": format!("{}x{}", c.n, c.n), "n_nodes": c.n * c.n,
                "needle": c.needle_label, "contact": contact_label(c.contact, opts.spacing_m),
                "ticks": c.ticks.len(), "script_ticks": c.script_ticks,
                "step_p50_s": num(p50), "step_p99_s": num(p99), "step_p999_s": num(p999), "step_max_s": num(max),
                "ticks_over_500us": slow.len(), "ticks_over_1ms": c.ticks.iter().filter(|r| r.step_s > TARGET_MAX_S).count(),
                "jacobian_p50_s": num(j50), "jacobian_p99_s": num(j99), "jacobian_max_s": num(jmax),
                "jacobian_count": c.jacobian_s.len(), "jacobian_errors": c.jacobian_errors,
                "unconverged_ticks": s.unconverged_ticks, "column_misses": s.column_misses, "column_deferrals": s.column_deferrals,
                "d_deepest": c.d_deepest, "d_max": c.d_max, "d_final": c.d_final,
                "setup_s": c.setup_s, "prefetch_s": c.prefetch_s, "prefetched_nodes": c.prefetched_nodes, "column_cache_bytes": c.column_cache_bytes,
                "preempted_ticks": c.preempted_ticks(),
                "unpreempted_step_p999_s": num(c.unpreempted_quantiles()[0]), "unpreempted_step_max_s": num(c.unpreempted_quantiles()[1]),
            });
            let counters = json!({
                "captures": s.captures, "releases": s.releases, "punctures": s.punctures,
                "stick_to_slip": s.stick_to_slip, "slip_to_stick": s.slip_to_stick, "shape_passes": s.shape_passes,
                "shape_unconverged": s.shape_unconverged, "dependent_points": s.dependent_points, "bevel_flips": s.bevel_flips,
                "active_set_capped_ticks": s.active_set_capped_ticks, "shape_capped_ticks": s.shape_capped_ticks,
                "hybrid_checks": s.hybrid_checks, "hybrid_rebuilds": s.hybrid_rebuilds,
                "clamped_ticks": s.clamped_ticks, "overflows": s.overflows(),
                "pivots": c.solver.n_pivots, "rotations": c.solver.n_rotations, "rebuilds": c.solver.n_rebuilds,
                "max_active_set_iterations": c.ticks.iter().map(|r| r.active_set_iterations).max().unwrap_or(0),
                "tip_depth_max_m": num(c.tip_depth_max_m), "tip_deepest_m": [num(c.tip_deepest_m[0]), num(c.tip_deepest_m[1])],
                "theta_range_rad": [num(c.theta_range_rad[0]), num(c.theta_range_rad[1])],
                "tip_x_range_m": [num(c.tip_x_range_m[0]), num(c.tip_x_range_m[1])],
                "load_avg_1min": [num(c.load_avg[0]), num(c.load_avg[1])], "wall_s": c.wall_s,
                "worst_ticks": worst, "worst_unpreempted_ticks": worst_unpreempted, "unconverged": unconverged, "prefetched_nodes_by_phase": by_phase, "misses": c.misses(), "notes": c.notes(), "failed": c.failed,
            });
            let overflows = json!({
                "capacity_drops": s.capacity_drops, "capture_overflow": s.capture_overflow,
                "approaching_overflow": s.approaching_overflow, "candidate_growths": s.candidate_growths,
                "curve_capacity_drops": s.curve_capacity_drops,
            });
            for more in [counters, overflows] {
                if let (Some(o), Value::Object(more)) = (o.as_object_mut(), more) {
                    o.extend(more);
                }
            }
            o
        })
        .collect();
    let scripts: Vec<Value> = suite
        .scripts
        .iter()
        .map(|s| json!({"motion": s.motion.name(), "needle": s.needle_label, "ticks": s.poses.len(), "script": s.description}))
        .collect();
    json!({
        "machine": machine(),
        "quick": opts.quick,
        "contact": contact_label(opts.contact, opts.spacing_m),
        "prefetch_nodes_per_tick": opts.prefetch_nodes_per_tick,
        "jacobian_every_ticks": JACOBIAN_EVERY_TICKS,
        "targets": {"step_p999_s": TARGET_P999_S, "step_max_s": TARGET_MAX_S, "unconverged_ticks": 0, "column_misses": 0},
        "scripts": scripts,
        "cases": cases,
    })
}

/// The suite as markdown: the set-up, the main table, and the slowest tick of every case.
pub fn to_markdown(suite: &Suite, opts: &MotionOptions) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "machine: {}\n", machine());
    let _ = writeln!(
        s,
        "phantom: 0.1 m square, E = 30 kPa, ν = 0.45, plane stress 1 cm, bottom fixed; entry at the top centre, tip starting 5 mm above the surface; 1 kHz; contact: {}; `columns_in_step: false`, columns of approaching nodes prefetched between steps ({} nodes per tick, not timed as the step); Jacobian every {JACOBIAN_EVERY_TICKS} ticks, timed apart.\n",
        contact_label(opts.contact, opts.spacing_m),
        opts.prefetch_nodes_per_tick
    );
    for sc in &suite.scripts {
        let _ = writeln!(s, "- **{}** ({}, {} ticks): {}", sc.motion.name(), sc.needle_label, sc.poses.len(), sc.description);
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "| motion | mesh | ticks | step p50 µs | p99 µs | p99.9 µs | max µs | preempted ticks: count, p99.9 / max µs without them | Jacobian p50 / p99 / max µs | unconverged | column misses | deferrals | d deepest (max) | setup s | prefetch s (nodes, GB cached) | targets |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for c in &suite.cases {
        let [p50, p99, p999, max] = c.step_quantiles();
        let [j50, j99, jmax] = c.jacobian_quantiles();
        let misses = c.misses();
        let _ = writeln!(
            s,
            "| {} | {}² | {} | {} | {} | {} | {} | {}: {} / {} | {} / {} / {} | {} | {} | {} | {} ({}) | {:.3} | {:.2} ({}, {:.2}) | {} |",
            c.motion.name(),
            c.n,
            c.ticks.len(),
            us(p50),
            us(p99),
            us(p999),
            us(max),
            c.preempted_ticks(),
            us(c.unpreempted_quantiles()[0]),
            us(c.unpreempted_quantiles()[1]),
            us(j50),
            us(j99),
            us(jmax),
            c.stats.unconverged_ticks,
            c.stats.column_misses,
            c.stats.column_deferrals,
            c.d_deepest,
            c.d_max,
            c.setup_s,
            c.prefetch_s,
            c.prefetched_nodes,
            c.column_cache_bytes as f64 / 1e9,
            targets_cell(&misses, &c.notes())
        );
    }
    let _ = writeln!(
        s,
        "\nPreempted ticks waited on a run queue during the step (`/proc/thread-self/schedstat`): another process had the core. The targets are judged on all ticks.\n"
    );
    let _ = writeln!(
        s,
        "The slowest tick of each case that did not wait on a run queue (its counters; pivots and rotations of the mixed solver within the tick):\n"
    );
    let _ = writeln!(
        s,
        "| motion | mesh | tick (phase) | step µs | active-set iterations | pivots | rotations | stick↔slip | captures / releases | shape passes | d | page faults | columns prefetched before | ticks > 500 µs (preempted) | case totals: pivots / rotations / stick↔slip |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for c in &suite.cases {
        let phase_of = |t: usize| suite.scripts.iter().find(|sc| sc.motion == c.motion).map_or("", |sc| sc.phase_of(t));
        let over = c.ticks.iter().filter(|r| r.step_s > TARGET_P999_S).count();
        let over_preempted = c.ticks.iter().filter(|r| r.step_s > TARGET_P999_S && r.cpu_wait_ns > 0).count();
        let worst = c.ticks.iter().filter(|r| r.cpu_wait_ns == 0).max_by(|a, b| a.step_s.total_cmp(&b.step_s));
        if let Some(w) = worst {
            let _ = writeln!(
                s,
                "| {} | {}² | {} ({}) | {} | {} | {} | {} | {} | {} / {} | {} | {} | {} | {} | {over} ({over_preempted}) | {} / {} / {} |",
                c.motion.name(),
                c.n,
                w.tick,
                phase_of(w.tick),
                us(w.step_s),
                w.active_set_iterations,
                w.pivots,
                w.rotations,
                w.stick_slip_changes,
                w.captures,
                w.releases,
                w.shape_passes,
                w.d,
                w.page_faults,
                w.columns_before,
                c.solver.n_pivots,
                c.solver.n_rotations,
                c.stats.stick_to_slip + c.stats.slip_to_stick
            );
        }
    }
    s
}
