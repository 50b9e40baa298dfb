//! The scripted `simulate` command: a trajectory through the same step function the real-time
//! server uses, written as a CSV time series, with the final state in the exchange format.

use std::fmt::Write as _;

use anyhow::{Context, Result};
use needlesim_core::sim::{SimError, Simulation, StateSnapshot};

use needlesim_scene::exchange::{Load, PrescribedLocal, Scenario};
use needlesim_scene::{Scene, Trajectory};

/// The longest offline simulation, in ticks, by default: the server's Simulate limit and the
/// `simulate` command's `--max-ticks` (10⁶ ticks: 1000 s at 1 kHz, 8 MB of step times).
pub const DEFAULT_MAX_TICKS: u64 = 1_000_000;

/// What a run produced besides the CSV.
#[derive(Debug, Clone, Default)]
pub struct RunSummary {
    pub ticks: u64,
    pub clamped_ticks: u64,
    pub column_misses: u64,
    pub prefetched_columns: u64,
    pub unconverged_ticks: u64,
    pub numeric_factorisations: u64,
    /// Step compute times, seconds, one per tick.
    pub step_times_s: Vec<f64>,
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

/// Runs `traj` through a new simulation of `scene`, ticking at the scene's rate from the
/// trajectory's first to its last time. Each tick's row is appended to `csv` (when given).
/// Columns for the nodes the tip approaches are computed between steps, as a worker would.
/// A trajectory longer than `max_ticks` is an error naming its last line; a step that diverges
/// ([`SimError::Diverged`]) stops the run with an error naming the tick and time.
pub fn run(scene: &Scene, traj: &Trajectory, max_ticks: u64, mut csv: Option<&mut String>) -> Result<(Simulation, RunSummary)> {
    let mut params = scene.params.clone();
    params.initial_pose = needlesim_scene::base_pose(traj.samples[0].1);
    let rate = params.tick_rate_hz;
    let (t0, _) = traj.span_s();
    let n_ticks = traj.tick_count(rate, max_ticks)?;
    let mut sim = Simulation::new(scene.tissue.clone(), params).context("simulation")?;
    let mut summary = RunSummary { step_times_s: Vec::with_capacity(n_ticks as usize + 1), ..Default::default() };
    if let Some(c) = csv.as_deref_mut() {
        c.push_str(&csv_header(&scene.target_names));
        c.push('\n');
    }
    let mut clamp_run_start: Option<u64> = None;
    for k in 0..=n_ticks {
        let t = t0 + k as f64 / rate;
        let pose = needlesim_scene::base_pose(traj.pose_at(t));
        let started = std::time::Instant::now();
        let out = match sim.step(pose) {
            Ok(o) => o,
            Err(e @ SimError::NonFinitePose { .. }) => {
                tracing::warn!("{e}");
                continue;
            }
            // A diverged step names its tick itself.
            Err(e @ SimError::Diverged { .. }) => return Err(e).with_context(|| format!("the run stopped at t = {t:.4} s")),
            Err(e) => return Err(e).with_context(|| format!("the run stopped at tick {k} (t = {t:.4} s)")),
        };
        summary.step_times_s.push(started.elapsed().as_secs_f64());
        match (out.clamped, clamp_run_start) {
            (true, None) => clamp_run_start = Some(k),
            (false, Some(s)) => {
                tracing::warn!(
                    "trajectory jumps faster than max_base_step_m/max_base_step_rad per tick between t = {:.4} s and {:.4} s: the pose was clamped for {} tick(s)",
                    t0 + s as f64 / rate,
                    t,
                    k - s
                );
                clamp_run_start = None;
            }
            _ => {}
        }
        if let Some(c) = csv.as_deref_mut() {
            let b = out.base;
            let _ = write!(
                c,
                "{:.6},{},{},{},{:e},{:e},{:e},{:e},{:e},{},{},{},{},{},{}",
                t0 + out.time_s,
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
        summary.prefetched_columns += sim.prefetch_columns(8)? as u64;
    }
    if let Some(s) = clamp_run_start {
        tracing::warn!("the pose was clamped from t = {:.4} s to the end of the trajectory", t0 + s as f64 / rate);
    }
    let st = sim.stats();
    summary.ticks = st.ticks;
    summary.clamped_ticks = st.clamped_ticks;
    summary.column_misses = st.column_misses;
    summary.unconverged_ticks = st.unconverged_ticks;
    summary.numeric_factorisations = sim.model().cholesky().n_numeric_factorisations();
    Ok((sim, summary))
}

/// The final state as a static problem in the exchange format, with the solver's own results.
pub fn dump_state(scene: &Scene, sim: &Simulation) -> Scenario {
    let mesh = scene.tissue.mesh();
    let mats = scene.tissue.materials();
    let StateSnapshot { conditions, loads_n, needle_nodes } = sim.snapshot();
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
        prescribed_local: conditions
            .iter()
            .map(|c| PrescribedLocal { node: c.node_idx as i64, angle_rad: c.angle_rad, ut: c.ut_m, un: c.un_m })
            .collect(),
        loads: loads_n.iter().map(|&(n, [fx, fy])| Load { node: n as i64, fx, fy }).collect(),
        working_nodes: None,
        output_stresses: false,
        solver_displacements: Some(u.chunks(2).map(|c| [c[0], c[1]]).collect()),
        needle_nodes: Some(serde_json::Value::Array(
            needle_nodes
                .iter()
                .map(|n| serde_json::json!({"node": n.node_idx, "state": n.state.as_str(), "fx": n.force_n[0], "fy": n.force_n[1]}))
                .collect(),
        )),
    }
}
