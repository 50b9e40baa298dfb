//! The bridge's report at exit: counts, latency percentiles and the final pose and stiffness,
//! as text or JSON.

use needlesim_bridge::render::Pose6;
use needlesim_channel::spatial::restrict_planar_stiffness;

#[derive(Debug, Default)]
pub(crate) struct Report {
    pub(crate) device: String,
    pub(crate) periods: u64,
    pub(crate) missed_periods: u64,
    pub(crate) fresh_forces: u64,
    pub(crate) watchdog_periods: u64,
    pub(crate) limited_periods: u64,
    pub(crate) pose_to_force_ns: Vec<u64>,
    pub(crate) force_age_ns: Vec<u64>,
    /// The loop ran phase-aligned with the session's ticks (--phase-lead-us).
    pub(crate) aligned: bool,
    /// Poses a force answered (by its pose counter), and poses superseded before any tick took them.
    pub(crate) answered_poses: u64,
    pub(crate) unanswered_poses: u64,
    /// Poses answered within the period that wrote them (phase-aligned), and waits that ended at
    /// --force-wait-us without a force written after the pose.
    pub(crate) answered_in_period: u64,
    pub(crate) waits_timed_out: u64,
    pub(crate) last_counter: u64,
    pub(crate) last_tick: Option<u64>,
    pub(crate) max_rendered_force_n: f64,
    pub(crate) final_pose: Pose6,
    /// The session's dimension (2 or 3): the report and the trace give 2D or 6-DOF values.
    pub(crate) dimension: u32,
    pub(crate) exit: String,
    pub(crate) link: String,
    pub(crate) render: String,
    pub(crate) inject_rtt_ms: f64,
    pub(crate) dropped_poses: u64,
    pub(crate) last_stiffness: Option<[[f64; 6]; 6]>,
}

fn percentile_us(v: &mut [u64], p: f64) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_unstable();
    let i = ((p * (v.len() - 1) as f64).round() as usize).min(v.len() - 1);
    Some(v[i] as f64 / 1e3)
}

fn json_num(x: Option<f64>) -> String {
    match x {
        Some(v) if v.is_finite() => format!("{v}"),
        _ => "null".into(),
    }
}

fn json_str(s: &str) -> String {
    let mut o = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            c if (c as u32) < 0x20 => o.push_str(&format!("\\u{:04x}", c as u32)),
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

impl Report {
    pub(crate) fn print(&mut self, json: bool) {
        let p2f = [
            percentile_us(&mut self.pose_to_force_ns, 0.5),
            percentile_us(&mut self.pose_to_force_ns, 0.99),
            percentile_us(&mut self.pose_to_force_ns, 0.999),
            percentile_us(&mut self.pose_to_force_ns, 1.0),
        ];
        let age = [percentile_us(&mut self.force_age_ns, 0.5), percentile_us(&mut self.force_age_ns, 0.99)];
        // A 2D session: (x, y, θ) and the 3×3 ∂(Fx, Fy, τ)/∂(x, y, θ); 3D: (x, y, z, qw, qx, qy, qz) and the 6×6, row-major.
        let planar = self.dimension != 3;
        let final_pose: Vec<f64> = if planar {
            self.final_pose.to_planar().to_vec()
        } else {
            self.final_pose.position_m.iter().chain(&self.final_pose.orientation).copied().collect()
        };
        let stiffness: Option<Vec<f64>> = self
            .last_stiffness
            .map(|k| if planar { restrict_planar_stiffness(&k).to_vec() } else { k.iter().flatten().copied().collect() });
        if json {
            println!(
                "{{\"device\":{},\"periods\":{},\"missed_periods\":{},\"fresh_forces\":{},\"watchdog_periods\":{},\"limited_periods\":{},\
                 \"pose_counter\":{},\"last_server_tick\":{},\"pose_to_force_us\":{{\"p50\":{},\"p99\":{},\"p999\":{},\"max\":{}}},\
                 \"force_age_us\":{{\"p50\":{},\"p99\":{}}},\"aligned\":{},\"answered_poses\":{},\"unanswered_poses\":{},\
                 \"answered_in_period\":{},\"waits_timed_out\":{},\
                 \"max_rendered_force_n\":{},\"dimension\":{},\"final_pose\":[{}],\"final_wrench\":[{}],\"link\":{},\"render\":{},\"inject_rtt_ms\":{},\
                 \"dropped_poses\":{},\"stiffness\":{},\"exit\":{}}}",
                json_str(&self.device),
                self.periods,
                self.missed_periods,
                self.fresh_forces,
                self.watchdog_periods,
                self.limited_periods,
                self.last_counter,
                self.last_tick.map_or("null".into(), |t| t.to_string()),
                json_num(p2f[0]),
                json_num(p2f[1]),
                json_num(p2f[2]),
                json_num(p2f[3]),
                json_num(age[0]),
                json_num(age[1]),
                self.aligned,
                self.answered_poses,
                self.unanswered_poses,
                self.answered_in_period,
                self.waits_timed_out,
                self.max_rendered_force_n,
                self.dimension,
                final_pose.iter().map(|v| json_num(Some(*v))).collect::<Vec<_>>().join(","),
                if planar { "0,0,0" } else { "0,0,0,0,0,0" },
                json_str(&self.link),
                json_str(&self.render),
                self.inject_rtt_ms,
                self.dropped_poses,
                stiffness.map_or("null".into(), |j| format!("[{}]", j.iter().map(|v| json_num(Some(*v))).collect::<Vec<_>>().join(","))),
                json_str(&self.exit),
            );
        } else {
            let f = |x: Option<f64>| x.map_or("-".into(), |v| format!("{v:.1}"));
            eprintln!(
                "needlesim-bridge: {} periods ({} missed), {} fresh forces, {} periods under the watchdog, {} limited; \
                 pose→force p50 {} µs p99 {} µs p99.9 {} µs max {} µs ({}: {} poses answered, {} in their period, {} unanswered), \
                 force age p50 {} µs p99 {} µs; exit: {}",
                self.periods,
                self.missed_periods,
                self.fresh_forces,
                self.watchdog_periods,
                self.limited_periods,
                f(p2f[0]),
                f(p2f[1]),
                f(p2f[2]),
                f(p2f[3]),
                if self.aligned { "phase-aligned" } else { "own phase" },
                self.answered_poses,
                self.answered_in_period,
                self.unanswered_poses,
                f(age[0]),
                f(age[1]),
                self.exit
            );
            if let Some(j) = self.last_stiffness.filter(|_| planar).map(|k| restrict_planar_stiffness(&k)) {
                eprintln!(
                    "needlesim-bridge: last stiffness J = ∂(Fx,Fy,τ)/∂(x,y,θ): [{:.1} {:.1} {:.4}; {:.1} {:.1} {:.4}; {:.4} {:.4} {:.5}]",
                    j[0], j[1], j[2], j[3], j[4], j[5], j[6], j[7], j[8]
                );
            }
        }
    }
}
