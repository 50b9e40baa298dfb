//! Structures to spare: spheres and axis-aligned boxes in world coordinates (circles and
//! rectangles in 2D, embedded at $z = 0$), their signed distance, and its minimum over the
//! inserted shaft.
//!
//! **Signed distance.** Sphere: $\phi(p) = |p - c| - r$. Box $[a, b]$: with
//! $q = |p - m| - h$ ($m$ the centre, $h$ the half-extents, componentwise),
//! $\phi(p) = |\max(q, 0)| + \min(\max_i q_i, 0)$. Negative inside; $-\phi$ is the depth of
//! intrusion. In 2D the third component is ignored (a circle, a rectangle).
//!
//! **Clearance of the shaft.** The inserted part of the needle is the segment
//! $S = \{x_{tip} - s\,a : 0 \le s \le L_{in}\}$ ($a$ the axis at the tip, $L_{in}$ the
//! inserted length; exact for the rigid needle, the chord for a bent one). Its clearance is
//! $c = \min_{p\in S} \phi(p)$. The signed distance to a convex set is a convex function, so its
//! restriction to the segment is convex in $s$ and the minimum is found by golden-section search
//! (80 steps: the interval shrinks by $0.618^{80} \approx 2\cdot10^{-17}$); a sphere's is in
//! closed form (the closest point of the segment to the centre).

/// A structure's shape. `dims` of a shape is 2 or 3: in 2D only x and y count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A sphere (a circle in 2D).
    Sphere { centre_m: [f64; 3], radius_m: f64 },
    /// An axis-aligned box (a rectangle in 2D), corners `min_m` < `max_m`.
    Box { min_m: [f64; 3], max_m: [f64; 3] },
}

impl Shape {
    /// Signed distance of `p` (module docs); `dims` = 2 ignores z.
    pub fn signed_distance(&self, p: [f64; 3], dims: usize) -> f64 {
        match *self {
            Shape::Sphere { centre_m, radius_m } => {
                let mut s = 0.0;
                for i in 0..dims {
                    s += (p[i] - centre_m[i]).powi(2);
                }
                s.sqrt() - radius_m
            }
            Shape::Box { min_m, max_m } => {
                let mut outside = 0.0;
                let mut max_q = f64::NEG_INFINITY;
                for i in 0..dims {
                    let m = 0.5 * (min_m[i] + max_m[i]);
                    let h = 0.5 * (max_m[i] - min_m[i]);
                    let q = (p[i] - m).abs() - h;
                    outside += q.max(0.0).powi(2);
                    max_q = max_q.max(q);
                }
                outside.sqrt() + max_q.min(0.0)
            }
        }
    }

    /// Minimum signed distance over the segment from `tip` back along `axis` by `length_m`
    /// (module docs), and the point where it is reached.
    pub fn segment_clearance(&self, tip: [f64; 3], axis: [f64; 3], length_m: f64, dims: usize) -> (f64, [f64; 3]) {
        let at = |s: f64| [tip[0] - s * axis[0], tip[1] - s * axis[1], tip[2] - s * axis[2]];
        let len = length_m.max(0.0);
        if let Shape::Sphere { centre_m, .. } = *self {
            // Closest point of the segment to the centre: s* = clamp((tip - c)·a, 0, L).
            let mut d = 0.0;
            for i in 0..dims {
                d += (tip[i] - centre_m[i]) * axis[i];
            }
            let p = at(d.clamp(0.0, len));
            return (self.signed_distance(p, dims), p);
        }
        let (mut lo, mut hi) = (0.0, len);
        const G: f64 = 0.618_033_988_749_894_8;
        let mut x1 = hi - G * (hi - lo);
        let mut x2 = lo + G * (hi - lo);
        let mut f1 = self.signed_distance(at(x1), dims);
        let mut f2 = self.signed_distance(at(x2), dims);
        for _ in 0..80 {
            if f1 <= f2 {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - G * (hi - lo);
                f1 = self.signed_distance(at(x1), dims);
            } else {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + G * (hi - lo);
                f2 = self.signed_distance(at(x2), dims);
            }
        }
        // The ends too: a convex function's minimum on a closed interval may sit at one.
        let mut best = (f1.min(f2), at(if f1 <= f2 { x1 } else { x2 }));
        for s in [0.0, len] {
            let f = self.signed_distance(at(s), dims);
            if f < best.0 {
                best = (f, at(s));
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_signed_distance_inside_outside_and_corner() {
        let b = Shape::Box { min_m: [0.0, 0.0, 0.0], max_m: [2.0, 4.0, 6.0] };
        assert!((b.signed_distance([1.0, 1.0, 3.0], 3) + 1.0).abs() < 1e-15); // 1 from the x = 0 face
        assert!((b.signed_distance([3.0, 2.0, 3.0], 3) - 1.0).abs() < 1e-15);
        assert!((b.signed_distance([3.0, 5.0, 3.0], 3) - 2f64.sqrt()).abs() < 1e-15);
        // 2D ignores z.
        assert!((b.signed_distance([3.0, 2.0, 100.0], 2) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn segment_clearance_of_a_box_equals_a_dense_scan() {
        let b = Shape::Box { min_m: [0.01, -0.005, -0.004], max_m: [0.02, 0.005, 0.004] };
        let axis = [0.6, 0.8, 0.0];
        for (k, tip) in [[0.03, 0.01, 0.0], [0.015, 0.0, 0.001], [0.05, 0.07, 0.0], [0.0, -0.02, 0.01]].into_iter().enumerate() {
            let (c, _) = b.segment_clearance(tip, axis, 0.04, 3);
            let scan = (0..=400_000)
                .map(|i| {
                    let s = 0.04 * i as f64 / 400_000.0;
                    b.signed_distance([tip[0] - s * axis[0], tip[1] - s * axis[1], tip[2] - s * axis[2]], 3)
                })
                .fold(f64::INFINITY, f64::min);
            // The scan's grid step is 1e-7 m, so it overestimates the minimum by at most that.
            assert!(c <= scan + 1e-12 && scan - c < 1.1e-7, "case {k}: golden {c} scan {scan}");
        }
    }

    #[test]
    fn sphere_clearance_is_the_closest_point_of_the_segment() {
        let s = Shape::Sphere { centre_m: [0.0, 0.01, 0.0], radius_m: 0.002 };
        // The segment along +x through y = 0, from x = -0.01 to the tip at x = 0.02: closest at x = 0.
        let (c, p) = s.segment_clearance([0.02, 0.0, 0.0], [1.0, 0.0, 0.0], 0.03, 3);
        assert!((c - 0.008).abs() < 1e-15 && p[0].abs() < 1e-15);
        // Shorter: the shaft ends at x = 0.005, so the closest point is its end.
        let (c, _) = s.segment_clearance([0.02, 0.0, 0.0], [1.0, 0.0, 0.0], 0.015, 3);
        assert!((c - ((0.005f64).powi(2) + 0.01f64.powi(2)).sqrt() + 0.002).abs() < 1e-15);
    }
}
