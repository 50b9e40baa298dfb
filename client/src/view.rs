//! How frames are shown: one `key=value` line per frame (`--plain`, replay), or a compact view
//! redrawn in place with ANSI escapes.

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

/// One line per frame, stable and easy to parse:
/// `tick=… t_s=… depth_mm=… f_axial_n=… f_lateral_n=… torque_nm=… tip_mm=x,y stuck=… slipping=… tip=… [target_<name>_mm=… target_<name>_hit=0|1]… [missed=…]`.
pub fn plain_line(f: &pb::Frame) -> String {
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
        lines.push(match stats {
            Some(s) => format!(
                "ticks   compute p50 {:.1} µs  p99 {:.1} µs  max {:.1} µs   lateness p99 {:.1} µs   missed deadlines {}   dropped {}",
                s.compute_p50_us, s.compute_p99_us, s.compute_max_us, s.lateness_p99_us, s.missed_deadlines, s.dropped_records
            ),
            None => "ticks   (statistics pending)".to_owned(),
        });
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
