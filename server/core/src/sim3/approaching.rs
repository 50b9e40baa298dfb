//! The approaching nodes (module docs, stage 4): the nodes of the tetrahedra on the axis ahead
//! of the tip, kept across ticks and sorted nearest first, for the prefetch between steps.

use std::sync::Arc;

use crate::contact::ContactPoint;

use super::{BasePose3, LOOKAHEAD_RING, LOOKAHEAD_SAMPLES_PER_TICK, MAX_APPROACHING, Simulation3, add, dot, sub};

impl Simulation3 {
    fn push_approaching(&mut self, node: usize) {
        if self.model.is_fixed(node) {
            return;
        }
        if self.cache.contains(node) {
            self.stamp[node] = self.tick + 1;
        } else if !self.out.approaching.contains(&node) {
            if self.out.approaching.len() < MAX_APPROACHING {
                self.out.approaching.push(node);
            } else {
                self.stats.approaching_overflow += 1;
            }
        }
    }

    /// The approaching nodes (for prefetch), kept across ticks: nodes now cached or out of the
    /// band around the axis ahead of the tip (lateral distance and arc length within a
    /// tetrahedron diameter of the lookahead segment) leave the list; the axis ahead and a ring
    /// of six points around each of its stations are located [`LOOKAHEAD_SAMPLES_PER_TICK`]
    /// samples per tick, round robin (a point location costs microseconds: the whole segment
    /// each tick would cost tens), and the candidates' nodes (a waiting point's, then the tip's)
    /// go first. Sorted nearest first. $O(\text{list})$, no allocation.
    pub(super) fn update_approaching(
        &mut self,
        candidates: [Option<ContactPoint>; 2],
        u_d: [f64; 3],
        axis_pose: &BasePose3,
        frame: &[[f64; 3]; 3],
    ) {
        let len = self.params.needle_length_m;
        let look = self.params.lookahead_m;
        let h = self.setup.sample_step_m;
        let band = self.setup.max_diam_m;
        let base = axis_pose.position_m;
        let model = Arc::clone(&self.model);
        let nodes_m = model.mesh().nodes_m();
        let t = frame[0];
        let (s_lo, s_hi) = (len - 4.0 * h - band, len + look + band);
        let coords = |j: usize| {
            let d = sub(add(nodes_m[j], u_d), base);
            let s = dot(t, d);
            let lat = sub(d, [s * t[0], s * t[1], s * t[2]]);
            (s, dot(lat, lat).sqrt())
        };
        let cache = &self.cache;
        self.out.approaching.retain(|&j| {
            let (s, lat) = coords(j);
            !cache.contains(j) && lat <= band && s >= s_lo && s <= s_hi
        });
        if look > 0.0 {
            // Sample i of the round robin: station i mod n along the axis, offset across it by
            // the ring position i div n (none, or 0.5 h in one of six directions 60° apart).
            // An axis along a mesh line runs on tetrahedron edges and faces, where a point
            // location finds one of the tetrahedra around it; the material point a capture
            // locates later (deformed, through the fixed point) may lie in any of them.
            let n = ((look + 4.0 * h) / h).ceil() as u64 + 1;
            let (nrm, bin) = (frame[1], frame[2]);
            for k in 0..LOOKAHEAD_SAMPLES_PER_TICK {
                let i = (LOOKAHEAD_SAMPLES_PER_TICK * self.tick + k) % (LOOKAHEAD_RING * n);
                let (station, ring) = (i % n, i / n);
                let mut q = sub(axis_pose.point_at(len - 4.0 * h + station as f64 * h), u_d);
                if ring > 0 {
                    let phi = std::f64::consts::FRAC_PI_3 * ring as f64;
                    let (c, sn) = (0.5 * h * phi.cos(), 0.5 * h * phi.sin());
                    q = add(q, [c * nrm[0] + sn * bin[0], c * nrm[1] + sn * bin[1], c * nrm[2] + sn * bin[2]]);
                }
                if let Ok(loc) = self.model.locate(q) {
                    for node in loc.nodes {
                        self.push_approaching(node);
                    }
                }
            }
        }
        let key = |j: &usize| coords(*j).0;
        self.out.approaching.sort_unstable_by(|a, b| key(a).total_cmp(&key(b)));
        // The candidates' nodes go first, the first candidate's before the second's.
        for c in candidates.into_iter().rev().flatten() {
            for k in 0..4 {
                let node = c.nodes()[k].index();
                if self.model.is_fixed(node) || self.cache.contains(node) {
                    continue;
                }
                if let Some(pos) = self.out.approaching.iter().position(|&j| j == node) {
                    self.out.approaching.remove(pos);
                } else if self.out.approaching.len() == MAX_APPROACHING {
                    self.out.approaching.pop();
                    self.stats.approaching_overflow += 1;
                }
                self.out.approaching.insert(0, node);
            }
        }
    }
}
