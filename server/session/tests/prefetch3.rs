//! Regression test of issue 17: a live 3D session's worker, answering column requests with a
//! delay, keeps ahead of a needle that runs down a mesh line of the cube (where the axis lies on
//! tetrahedron edges and faces), so no capture waits for columns.
//!
//! The emulated worker answers one node per `LATENCY_TICKS` ticks, in request order, and the
//! requests follow the live session's policy (pinned nodes, then the approaching ones nearest
//! first, at most two in flight). Before the fix the lookahead located only the axis points,
//! found one of the tetrahedra around each, and every capture waited (14 deferrals with a
//! 4-tick worker).
use needlesim_core::MeshLimits;
use needlesim_core::sim3::{BasePose3, Sim3Params, Simulation3, Target3};
use std::collections::VecDeque;

/// The emulated worker's time per node (a node's columns take the real worker 3–5 ms on this
/// mesh on an idle machine; 20 stands for a loaded one).
const LATENCY_TICKS: u64 = 20;

#[test]
fn issue_17_the_3d_lookahead_keeps_a_slow_worker_ahead_of_the_tip() {
    let scene = needlesim_scene::load_scene3d("cube-phantom-3d", &MeshLimits::default()).unwrap();
    let model = std::sync::Arc::new(scene.tissue_model().unwrap());
    let initial = BasePose3::new(scene.initial_pose.position_m, scene.initial_pose.quat_wxyz).unwrap();
    let mut p = Sim3Params::new(scene.needle.length_m, initial);
    p.spacing_m = scene.needle.contact_spacing_m;
    p.regions = scene.regions.iter().map(|r| r.needle).collect();
    p.max_contacts = scene.needle.max_points;
    p.targets =
        scene.targets.iter().enumerate().map(|(k, t)| Target3 { centre_m: t.center_m, radius_m: t.radius_m, name_idx: k }).collect();
    let mut sim = Simulation3::new(model.clone(), p).unwrap();
    let latency = LATENCY_TICKS;
    let n = model.mesh().n_nodes();
    let mut requested_at = vec![u64::MAX; n];
    let mut queue: VecDeque<u32> = VecDeque::new();
    let mut busy_until = 0u64;
    let mut current: Option<u32> = None;
    let mut scratch = model.column_scratch();
    let q = initial.orientation;
    let mut last_def = 0;
    let mut waits = Vec::new();
    // 5 mm above the top face, down the centre line at 9 mm/s for 4 s (31 mm deep).
    for tick in 0..4000u64 {
        let t = tick as f64 / 1000.0;
        let pos = [0.05, 0.05, 0.205 - 0.009 * t];
        // Worker: one node per `latency` ticks, FIFO.
        if let Some(node) = current
            && tick >= busy_until
        {
            let mut cols = vec![0.0; 3 * model.n_dofs()].into_boxed_slice();
            model.compliance_columns_into(node as usize, &mut cols, &mut scratch).unwrap();
            sim.insert_columns_owned(node as usize, cols).unwrap();
            current = None;
        }
        if current.is_none()
            && let Some(node) = queue.pop_front()
        {
            current = Some(node);
            busy_until = tick + latency;
        }
        let pose = BasePose3::new(pos, [q.w, q.i, q.j, q.k]).unwrap();
        sim.step(pose).unwrap();
        let d = sim.stats().column_deferrals;
        if d != last_def {
            last_def = d;
            // (tick, the first waiting nodes with the tick each was requested at)
            let first: Vec<(usize, u64)> = sim.output().approaching.iter().take(3).map(|&j| (j, requested_at[j])).collect();
            waits.push((tick, first));
        }
        // RT side: pins then approaching, at most 2 outstanding.
        let outstanding = queue.len() + current.is_some() as usize;
        let mut room = 2usize.saturating_sub(outstanding);
        let pins: Vec<usize> = sim.pinned_nodes().to_vec();
        for &node in pins.iter().chain(&sim.output().approaching.clone()) {
            if room == 0 {
                break;
            }
            if requested_at[node] != u64::MAX || sim.cache().contains(node) {
                continue;
            }
            requested_at[node] = tick;
            queue.push_back(node as u32);
            room -= 1;
        }
    }
    assert!(sim.output().contacts.len() >= 3, "the needle captured points: {}", sim.output().contacts.len());
    assert_eq!(sim.stats().column_deferrals, 0, "captures waited for columns (tick, waiting nodes (node, requested at)): {waits:?}");
}
