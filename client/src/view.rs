//! How frames are shown: one `key=value` line per frame (`--plain`, replay), or a compact view
//! redrawn in place with ANSI escapes; a 3D session's frames (those with `d3`) in 3D.

use std::fmt::Write as _;

use needlesim_proto::v1 as pb;

/// Needle nodes stuck, slipping and at the tip.
pub fn node_counts(f: &pb::Frame) -> (usize, usize, usize) {
    let mut c = (0, 0, 0);
    for n in &f.needle_nodes {
        match pb::NodeState::try_from(n.state) {
            Ok(pb::NodeState::Stuck) => c.0 += 1,
            Ok(pb::NodeState::Slipping) => c.1 += 1,
            Ok(pb::NodeState::Tip) => c.2 += 1,
            _ => {}
        }
    }
    c
}

/// Contacts of a 3D tick stuck, slipping and at the tip.
pub fn contact_counts3(d: &pb::Tick3) -> (usize, usize, usize) {
    let mut c = (0, 0, 0);
    for p in &d.contacts {
        match pb::NodeState::try_from(p.state) {
            Ok(pb::NodeState::Stuck) => c.0 += 1,
            Ok(pb::NodeState::Slipping) => c.1 += 1,
            Ok(pb::NodeState::Tip) => c.2 += 1,
            _ => {}
        }
    }
    c
}

/// The components of an optional vector (zeros when unset).
pub fn xyz(v: Option<&pb::Vec3>) -> [f64; 3] {
    v.map_or([0.0; 3], |v| [v.x, v.y, v.z])
}

/// Position (m) and quaternion (w, x, y, z) of an optional 3D pose.
pub fn pose3_parts(p: Option<&pb::Pose3>) -> ([f64; 3], [f64; 4]) {
    let p = p.cloned().unwrap_or_default();
    let q = p.orientation.unwrap_or_default();
    (xyz(p.position_m.as_ref()), [q.w, q.x, q.y, q.z])
}

/// One line per frame, stable and easy to parse:
/// `tick=… t_s=… depth_mm=… f_axial_n=… f_lateral_n=… torque_nm=… tip_mm=x,y stuck=… slipping=… tip=… [target_<name>_mm=… target_<name>_hit=0|1]… [missed=…]`;
/// for a 3D frame [`plain_line3`].
pub fn plain_line(f: &pb::Frame) -> String {
    if let Some(d) = &f.d3 {
        return plain_line3(f, d);
    }
    let (stuck, slipping, tip) = node_counts(f);
    let t = f.tip_m.unwrap_or_default();
    let mut s = format!(
        "tick={} t_s={:.4} depth_mm={:.3} f_axial_n={:.5} f_lateral_n={:.5} torque_nm={:.3e} tip_mm={:.2},{:.2} stuck={stuck} slipping={slipping} tip={tip}",
        f.tick,
        f.time_s,
        f.inserted_length_m * 1e3,
        f.force_axial_n,
        f.force_lateral_n,
        f.torque_nm,
        t.x * 1e3,
        t.y * 1e3,
    );
    // Recordings leave the names out: an unnamed target is shown by its index.
    for (i, tg) in f.targets.iter().enumerate() {
        let name = if tg.name.is_empty() { i.to_string() } else { tg.name.clone() };
        let _ = write!(s, " target_{name}_mm={:.3} target_{name}_hit={}", tg.distance_m * 1e3, u8::from(tg.hit));
    }
    if f.missed_ticks > 0 {
        let _ = write!(s, " missed={}", f.missed_ticks);
    }
    s
}

/// One line per 3D frame: `tick=… t_s=… depth_mm=… f_n=fx,fy,fz f_axial_n=… torque_nm=tx,ty,tz
/// base_mm=x,y,z quat=w,x,y,z tip_mm=x,y,z contacts=… stuck=… slipping=… tip=…
/// [target_<name>_mm=… target_<name>_hit=0|1 target_<name>_missed=0|1]… [missed=…]` (forces in N
/// and torques in N·m of the tissue on the needle base, world frame; `f_axial_n` positive while
/// the tissue resists pushing in).
pub fn plain_line3(f: &pb::Frame, d: &pb::Tick3) -> String {
    let (stuck, slipping, tip) = contact_counts3(d);
    let (p, q) = pose3_parts(d.base.as_ref());
    let (force, torque, t) = (xyz(d.force_n.as_ref()), xyz(d.torque_nm.as_ref()), xyz(d.tip_m.as_ref()));
    let mut s = format!(
        "tick={} t_s={:.4} depth_mm={:.3} f_n={:.5},{:.5},{:.5} f_axial_n={:.5} torque_nm={:.3e},{:.3e},{:.3e} base_mm={:.2},{:.2},{:.2} quat={:.5},{:.5},{:.5},{:.5} tip_mm={:.2},{:.2},{:.2} contacts={} stuck={stuck} slipping={slipping} tip={tip}",
        f.tick,
        f.time_s,
        f.inserted_length_m * 1e3,
        force[0],
        force[1],
        force[2],
        d.axial_force_n,
        torque[0],
        torque[1],
        torque[2],
        p[0] * 1e3,
        p[1] * 1e3,
        p[2] * 1e3,
        q[0],
        q[1],
        q[2],
        q[3],
        t[0] * 1e3,
        t[1] * 1e3,
        t[2] * 1e3,
        d.contacts.len(),
    );
    for (i, tg) in d.targets.iter().enumerate() {
        let name = if tg.name.is_empty() { i.to_string() } else { tg.name.clone() };
        let _ = write!(
            s,
            " target_{name}_mm={:.3} target_{name}_hit={} target_{name}_missed={}",
            tg.distance_m * 1e3,
            u8::from(tg.hit),
            u8::from(tg.missed)
        );
    }
    if f.missed_ticks > 0 {
        let _ = write!(s, " missed={}", f.missed_ticks);
    }
    s
}

/// The tick statistics line of the live view.
fn stats_line(stats: Option<&pb::SessionStats>) -> String {
    match stats {
        Some(s) => format!(
            "ticks   compute p50 {:.1} µs  p99 {:.1} µs  max {:.1} µs   lateness p99 {:.1} µs   missed deadlines {}   dropped {}",
            s.compute_p50_us, s.compute_p99_us, s.compute_max_us, s.lateness_p99_us, s.missed_deadlines, s.dropped_records
        ),
        None => "ticks   (statistics pending)".to_owned(),
    }
}

/// The live terminal view: a few lines, redrawn in place.
pub struct LiveView {
    drawn_lines: usize,
}

impl LiveView {
    pub fn new() -> Self {
        Self { drawn_lines: 0 }
    }

    /// The text of the view (without the cursor movements).
    pub fn render(session: &str, f: &pb::Frame, stats: Option<&pb::SessionStats>, frames: u64) -> Vec<String> {
        if let Some(d) = &f.d3 {
            let mut lines = Self::render3(session, f, d, frames);
            lines.push(stats_line(stats));
            return lines;
        }
        let (stuck, slipping, tip) = node_counts(f);
        let t = f.tip_m.unwrap_or_default();
        let b = f.base.unwrap_or_default();
        let mut lines = vec![
            format!("needlesim session {session}   tick {}   t {:.3} s   frames {frames}", f.tick, f.time_s),
            format!(
                "depth   {:8.3} mm    base ({:.2}, {:.2}) mm  {:.1}°    tip ({:.2}, {:.2}) mm",
                f.inserted_length_m * 1e3,
                b.x_m * 1e3,
                b.y_m * 1e3,
                b.theta_rad.to_degrees(),
                t.x * 1e3,
                t.y * 1e3
            ),
            format!("force   axial {:+9.5} N   lateral {:+9.5} N   torque {:+.3e} N·m", f.force_axial_n, f.force_lateral_n, f.torque_nm),
            format!("nodes   stuck {stuck:3}   slipping {slipping:3}   tip {tip:2}"),
        ];
        if f.targets.is_empty() {
            lines.push("targets (none)".to_owned());
        }
        for (i, tg) in f.targets.iter().enumerate() {
            let name = if tg.name.is_empty() { i.to_string() } else { tg.name.clone() };
            lines.push(format!("target  {name:<12} {:8.3} mm{}", tg.distance_m * 1e3, if tg.hit { "   HIT" } else { "" }));
        }
        lines.push(stats_line(stats));
        lines
    }

    /// The view of a 3D frame (without the statistics line).
    fn render3(session: &str, f: &pb::Frame, d: &pb::Tick3, frames: u64) -> Vec<String> {
        let (stuck, slipping, tip) = contact_counts3(d);
        let (p, q) = pose3_parts(d.base.as_ref());
        let (force, torque, t) = (xyz(d.force_n.as_ref()), xyz(d.torque_nm.as_ref()), xyz(d.tip_m.as_ref()));
        let mut lines = vec![
            format!("needlesim session {session} (3D)   tick {}   t {:.3} s   frames {frames}", f.tick, f.time_s),
            format!(
                "depth   {:8.3} mm    base ({:.2}, {:.2}, {:.2}) mm  q ({:.4}, {:.4}, {:.4}, {:.4})",
                f.inserted_length_m * 1e3,
                p[0] * 1e3,
                p[1] * 1e3,
                p[2] * 1e3,
                q[0],
                q[1],
                q[2],
                q[3]
            ),
            format!("tip     ({:.2}, {:.2}, {:.2}) mm", t[0] * 1e3, t[1] * 1e3, t[2] * 1e3),
            format!(
                "force   ({:+9.5}, {:+9.5}, {:+9.5}) N   axial {:+9.5} N   torque ({:+.3e}, {:+.3e}, {:+.3e}) N·m",
                force[0], force[1], force[2], d.axial_force_n, torque[0], torque[1], torque[2]
            ),
            format!("contacts {:3}   stuck {stuck:3}   slipping {slipping:3}   tip {tip:2}", d.contacts.len()),
        ];
        if d.targets.is_empty() {
            lines.push("targets (none)".to_owned());
        }
        for (i, tg) in d.targets.iter().enumerate() {
            let name = if tg.name.is_empty() { i.to_string() } else { tg.name.clone() };
            let state = if tg.hit {
                "   HIT"
            } else if tg.missed {
                "   MISSED"
            } else {
                ""
            };
            lines.push(format!("target  {name:<12} {:8.3} mm (radius {:.2} mm){state}", tg.distance_m * 1e3, tg.radius_m * 1e3));
        }
        lines
    }

    /// Redraws: moves up over the previous drawing and clears each line it writes.
    pub fn draw(&mut self, lines: &[String]) -> String {
        let mut out = String::new();
        if self.drawn_lines > 0 {
            let _ = write!(out, "\x1b[{}A\r", self.drawn_lines);
        }
        for l in lines {
            let _ = writeln!(out, "\x1b[2K{l}");
        }
        // A shorter drawing than the last one: clear what is left below.
        out.push_str("\x1b[J");
        self.drawn_lines = lines.len();
        out
    }
}
