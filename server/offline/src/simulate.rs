//! The scripted `simulate` command: a trajectory through the same step function the real-time
//! server uses, written as a CSV time series, with the final state in the exchange format.

use std::fmt::Write as _;
use std::ops::ControlFlow;

use needlesim_core::sim::{LocalCondition, Simulation, StateSnapshot, StepOutput};

use crate::convergence::ConvergencePolicy;
use crate::driver::{RunError, RunOptions, Script, ScriptedRun, Tick};

use needlesim_scene::exchange::{Load, PointCondition, PrescribedLocal, Scenario};
use needlesim_scene::{Scene, Trajectory};

pub use crate::driver::DEFAULT_MAX_TICKS;

/// What a run produced besides the CSV.
#[derive(Debug, Clone, Default)]
pub struct RunSummary {
    pub ticks: u64,
    pub clamped_ticks: u64,
    pub column_misses: u64,
    /// Ticks at which a new contact waited for its columns (admitted a tick later).
    pub column_deferrals: u64,
    pub prefetched_columns: u64,
    pub unconverged_ticks: u64,
    /// Ticks whose stick/slip iteration stopped at its cap (issue 19).
    pub active_set_capped_ticks: u64,
    /// Ticks whose flexible needle's shape passes stopped at their cap (issue 19).
    pub shape_capped_ticks: u64,
    /// Contacts that asked for a patch across the needle's width and stayed material points
    /// (`spread_contact`; a patch not wholly inside the tissue).
    pub patch_fallbacks: u64,
    pub numeric_factorisations: u64,
    /// Step compute times, seconds, one per tick.
    pub step_times_s: Vec<f64>,
    /// Whether the observer of [`run_observed`] ended the run before the trajectory's end.
    pub stopped_early: bool,
}

/// The CSV header for a scene's targets.
pub fn csv_header(target_names: &[String]) -> String {
    let mut h =
        String::from("t_s,x_m,y_m,theta_rad,fx_n,fy_n,torque_nm,f_axial_n,f_lateral_n,tip_x_m,tip_y_m,inserted_m,n_stuck,n_slipping,n_tip");
    for n in target_names {
        let _ = write!(h, ",target_{n}_distance_m,target_{n}_x_m,target_{n}_y_m,target_{n}_hit");
    }
    h
}

/// Runs `traj` through a new simulation of `scene` with the run driver ([`ScriptedRun`]),
/// ticking at the scene's rate from the trajectory's first to its last time. Each tick's row is
/// appended to `csv` (when given). Columns for the nodes the tip approaches are computed between
/// steps, as a worker would. A trajectory longer than `max_ticks` is an error naming its last
/// line; a failed step (a diverged solve, a pose that is not finite, …) stops the run with an
/// error naming the tick and time ([`RunError`]).
///
/// A tick that did not converge stops the run too ([`RunError::Unconverged`]) unless
/// `convergence` is [`ConvergencePolicy::Keep`]; the CSV then ends each row with a `converged`
/// column (1, or 0 for a kept unconverged tick).
pub fn run(
    scene: &Scene,
    traj: &Trajectory,
    max_ticks: u64,
    convergence: ConvergencePolicy,
    csv: Option<&mut String>,
) -> Result<(Simulation, RunSummary), RunError> {
    run_observed(scene, traj, max_ticks, convergence, csv, |_, _| ControlFlow::Continue(()))
}

/// [`run`], calling `observe` with each tick and its step's output after the CSV row is written
/// (before the columns for the next tick are computed): the Python package's `Simulation.run`
/// collects its time series and reports progress here. `ControlFlow::Break` ends the run after
/// that tick, without error ([`RunSummary::stopped_early`]); the simulation returned is then in
/// that tick's state.
pub fn run_observed(
    scene: &Scene,
    traj: &Trajectory,
    max_ticks: u64,
    convergence: ConvergencePolicy,
    mut csv: Option<&mut String>,
    mut observe: impl FnMut(&Tick, &StepOutput) -> ControlFlow<()>,
) -> Result<(Simulation, RunSummary), RunError> {
    let opts = RunOptions { max_ticks, convergence, ..RunOptions::default() };
    let mark = convergence == ConvergencePolicy::Keep;
    let mut run = ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), Script::trajectory(traj), opts)?;
    let rate = scene.params.tick_rate_hz;
    let t0 = run.t0_s();
    let mut summary =
        RunSummary { step_times_s: Vec::with_capacity(crate::driver::preallocated_ticks(run.ticks_total())), ..Default::default() };
    if let Some(c) = csv.as_deref_mut() {
        c.push_str(&csv_header(&scene.target_names));
        if mark {
            c.push_str(",converged");
        }
        c.push('\n');
    }
    let mut clamp_run_start: Option<u64> = None;
    let totals = run.run(|tick, sim| {
        let out = sim.output();
        let k = tick.k;
        summary.step_times_s.push(tick.step_s);
        match (out.clamped, clamp_run_start) {
            (true, None) => clamp_run_start = Some(k),
            (false, Some(s)) => {
                tracing::warn!(
                    "trajectory jumps faster than max_base_step_m/max_base_step_rad per tick between t = {:.4} s and {:.4} s: the pose was clamped for {} tick(s)",
                    t0 + s as f64 / rate,
                    tick.t_s,
                    k - s
                );
                clamp_run_start = None;
            }
            _ => {}
        }
        if let Some(c) = csv.as_deref_mut() {
            write_csv_row(c, out, t0);
            if mark {
                c.pop();
                c.push_str(if out.unconverged().is_some() { ",0\n" } else { ",1\n" });
            }
        }
        observe(tick, out)
    })?;
    if let Some(s) = clamp_run_start {
        tracing::warn!("the pose was clamped from t = {:.4} s to the end of the trajectory", t0 + s as f64 / rate);
    }
    let (sim, finished) = run.finish()?;
    let st = sim.stats();
    summary.ticks = st.ticks;
    summary.clamped_ticks = st.clamped_ticks;
    summary.column_misses = st.column_misses;
    summary.column_deferrals = st.column_deferrals;
    summary.prefetched_columns = finished.prefetched_columns;
    summary.stopped_early = totals.stopped_early;
    summary.unconverged_ticks = st.unconverged_ticks;
    summary.active_set_capped_ticks = st.active_set_capped_ticks;
    summary.shape_capped_ticks = st.shape_capped_ticks;
    summary.patch_fallbacks = st.patch_fallbacks;
    summary.numeric_factorisations = sim.model().cholesky().n_numeric_factorisations();
    Ok((sim, summary))
}

/// One row of the CSV ([`csv_header`]'s columns) for a step's output; `t0_s` is the
/// trajectory's start.
pub fn write_csv_row(c: &mut String, out: &StepOutput, t0_s: f64) {
    let b = out.base;
    let _ = write!(
        c,
        "{:.6},{},{},{},{:e},{:e},{:e},{:e},{:e},{},{},{},{},{},{}",
        t0_s + out.time_s,
        b.x_m,
        b.y_m,
        b.theta_rad,
        out.force_n[0],
        out.force_n[1],
        out.torque_nm,
        out.force_axial_n,
        out.force_lateral_n,
        out.tip_m[0],
        out.tip_m[1],
        out.inserted_length_m,
        out.n_stuck,
        out.n_slipping,
        out.n_tip
    );
    for tg in &out.targets {
        let _ = write!(c, ",{:e},{},{},{}", tg.distance_m, tg.position_m[0], tg.position_m[1], tg.hit as u8);
    }
    c.push('\n');
}

/// The final state as a static problem in the exchange format, with the solver's own results.
///
/// Nodes are written as `prescribed_local` conditions, material points as `points`. A contact
/// patch (`needle.spread_contact`) has no constraint in the format (its condition is on the
/// mean displacement of a segment): its force, which the solver found, is written as the nodal
/// loads $w_k f$ it puts on its nodes, and the patch itself (its nodes and weights, frame angle
/// and prescribed values) under `needle_nodes[i].patch`, so that a reference solution can be
/// checked against the condition: $\sum_k w_k\,u_k \cdot t = u_t$, $\cdot\, n = u_n$.
pub fn dump_state(scene: &Scene, sim: &Simulation) -> Scenario {
    let mesh = scene.tissue.mesh();
    let mats = scene.tissue.materials();
    let StateSnapshot { conditions, needle_nodes } = sim.snapshot();
    let (nodal, rest): (Vec<&LocalCondition>, Vec<&LocalCondition>) = conditions.iter().partition(|c| c.contact.as_node().is_some());
    let points: Vec<&LocalCondition> = rest.into_iter().filter(|c| !c.contact.is_patch()).collect();
    // A patch's force as the loads on its nodes (conditions and output nodes share the order).
    let mut patch_loads = std::collections::BTreeMap::<usize, [f64; 2]>::new();
    for (c, nn) in conditions.iter().zip(&needle_nodes) {
        if c.contact.is_patch() {
            for (k, w) in c.contact.terms() {
                let l = patch_loads.entry(k.index()).or_default();
                l[0] += w * nn.force_n[0];
                l[1] += w * nn.force_n[1];
            }
        }
    }
    let mut u = vec![0.0; 2 * mesh.n_nodes()];
    sim.displacement_field_into(&mut u);
    let plane = mats.plane();
    Scenario {
        name: Some(format!("{}-state", scene.name)),
        description: Some(format!("needlesim simulate --dump-state: {} at tick {}", scene.name, sim.output().tick)),
        nodes: mesh.nodes_m().to_vec(),
        triangles: mesh.triangles().iter().map(|t| t.map(|i| i as i64)).collect(),
        young_modulus_pa: mats.material_of_tri()[0].young_modulus_pa,
        nu: mats.material_of_tri()[0].poisson_ratio,
        plane: if plane.is_strain() { "strain" } else { "stress" }.to_owned(),
        thickness: plane.thickness_m(),
        young_modulus_elem_pa: Some(mats.material_of_tri().iter().map(|m| m.young_modulus_pa).collect()),
        nu_elem: Some(mats.material_of_tri().iter().map(|m| m.poisson_ratio).collect()),
        fixed_nodes: scene.fixed_nodes.iter().map(|&n| n as i64).collect(),
        prescribed: vec![],
        prescribed_local: nodal
            .iter()
            .map(|c| PrescribedLocal { node: c.node_idx as i64, angle_rad: c.angle_rad, ut: c.ut_m, un: c.un_m })
            .collect(),
        loads: nodal
            .iter()
            .filter(|c| c.load_n != [0.0; 2])
            .map(|c| Load { node: c.node_idx as i64, fx: c.load_n[0], fy: c.load_n[1] })
            .chain(patch_loads.iter().map(|(&k, l)| Load { node: k as i64, fx: l[0], fy: l[1] }))
            .collect(),
        points: points
            .iter()
            .map(|c| PointCondition {
                x: c.reference_m,
                angle_rad: c.angle_rad,
                ut: c.ut_m,
                un: c.un_m,
                f: (c.load_n != [0.0; 2]).then_some(c.load_n),
            })
            .collect(),
        working_points: None,
        working_nodes: None,
        output_stresses: false,
        solver_displacements: Some(u.chunks(2).map(|c| [c[0], c[1]]).collect()),
        needle_nodes: Some(serde_json::Value::Array(
            needle_nodes
                .iter()
                .zip(&conditions)
                .map(|(n, c)| match n.contact.as_node() {
                    Some(_) => serde_json::json!({"node": n.node_idx, "state": n.state.as_str(), "fx": n.force_n[0], "fy": n.force_n[1]}),
                    None => {
                        let mut point = serde_json::json!({
                            "node": n.node_idx,
                            "point": n.reference_m,
                            "state": n.state.as_str(),
                            "fx": n.force_n[0],
                            "fy": n.force_n[1],
                        });
                        if n.contact.is_patch() {
                            point["patch"] = serde_json::json!({
                                "terms": n.contact.terms().map(|(k, w)| serde_json::json!([k.index(), w])).collect::<Vec<_>>(),
                                "angle_rad": c.angle_rad,
                                "ut": c.ut_m,
                                "un": c.un_m,
                            });
                        }
                        point
                    }
                })
                .collect(),
        )),
    }
}
