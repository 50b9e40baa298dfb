//! 6-DOF pose arithmetic the server and the bridge share: unit quaternions, rotation vectors, the
//! pose perturbation the channel's 6×6 stiffness is defined on, and the planar (2D) embedding.
//!
//! # Conventions
//!
//! - A pose is a position `p` (m, world frame) and a unit quaternion `q = (w, x, y, z)` whose
//!   rotation `R(q)` takes the device's (needle's) body frame to the world frame.
//! - A wrench is `(F, τ)` = `(Fx, Fy, Fz, τx, τy, τz)`: force (N) on the base point (the hand) and
//!   torque (N·m) about the base point, both in world coordinates.
//! - A pose perturbation is `δ = (δp, δθ)` (m, rad): a translation `δp` of the base point and a
//!   small rotation vector `δθ` in world coordinates applied on the left, `R ← exp(δθ̂) R`. The
//!   difference of two poses is [`pose_delta`]: `δ(a, b) = (p_a − p_b, log(R_a R_bᵀ))`.
//! - The 6×6 stiffness `K = ∂(F, τ)/∂δ` (row = wrench component, column = perturbation component),
//!   so its blocks have units N/m (force–position), N/rad (force–rotation), N·m/m (torque–position)
//!   and N·m/rad (torque–rotation). The local linear model is `w(a) ≈ w(b) + K δ(a, b)`.
//!
//! # The planar embedding (2D sessions and 2D devices)
//!
//! A 2D pose `(x, y, θ)` is the 6-DOF pose `p = (x, y, 0)`, `q = (cos θ/2, 0, 0, sin θ/2)` (a
//! rotation θ about +z). Back, `θ = 2·atan2(q_z, q_w)`: the twist of `q` about z (swing–twist
//! decomposition), which is θ again for `|θ| < 2π` (to rounding) and the in-plane part of any
//! spatial orientation. A 2D wrench `(Fx, Fy, τ)` is `(Fx, Fy, 0, 0, 0, τ)`, and since a rotation
//! about z composes additively, `δθ_z = δθ`: the 2D stiffness `J = ∂(Fx, Fy, τ)/∂(x, y, θ)` (3×3)
//! is the 6×6 restricted to the axes [`PLANAR_AXES`] = (0, 1, 5): `K[a_i][a_j] = J[i][j]`, every
//! other entry 0 ([`embed_planar_stiffness`], [`restrict_planar_stiffness`], exact both ways).

/// The 6-DOF axes of a planar pose (x, y, θ): x, y and the rotation about z.
pub const PLANAR_AXES: [usize; 3] = [0, 1, 5];

/// The identity rotation `(w, x, y, z)`.
pub const IDENTITY: [f64; 4] = [1.0, 0.0, 0.0, 0.0];

/// The unit quaternion of a rotation by `theta_rad` about +z.
pub fn quat_about_z(theta_rad: f64) -> [f64; 4] {
    let (s, c) = (0.5 * theta_rad).sin_cos();
    [c, 0.0, 0.0, s]
}

/// The twist angle of `q` about +z, `2·atan2(q_z, q_w)` (rad): θ for [`quat_about_z`]`(θ)`, `|θ| < 2π`.
pub fn planar_angle(q: [f64; 4]) -> f64 {
    2.0 * q[3].atan2(q[0])
}

/// The 2D pose `(x, y, θ)` as a 6-DOF pose (position, orientation).
pub fn pose_from_planar(q: [f64; 3]) -> ([f64; 3], [f64; 4]) {
    ([q[0], q[1], 0.0], quat_about_z(q[2]))
}

/// The 2D pose `(x, y, θ)` of a 6-DOF pose: x, y and the twist about z (z and the swing are dropped).
pub fn pose_to_planar(position_m: [f64; 3], orientation: [f64; 4]) -> [f64; 3] {
    [position_m[0], position_m[1], planar_angle(orientation)]
}

/// The 2D stiffness `∂(Fx, Fy, τ)/∂(x, y, θ)` (3×3 row-major) as the 6×6 (see the module docs).
pub fn embed_planar_stiffness(j: &[f64; 9]) -> [[f64; 6]; 6] {
    let mut k = [[0.0; 6]; 6];
    for (i, &ai) in PLANAR_AXES.iter().enumerate() {
        for (c, &ac) in PLANAR_AXES.iter().enumerate() {
            k[ai][ac] = j[3 * i + c];
        }
    }
    k
}

/// The planar 3×3 block of a 6×6 stiffness (row-major), the inverse of [`embed_planar_stiffness`].
pub fn restrict_planar_stiffness(k: &[[f64; 6]; 6]) -> [f64; 9] {
    std::array::from_fn(|idx| k[PLANAR_AXES[idx / 3]][PLANAR_AXES[idx % 3]])
}

/// The 2D wrench `(Fx, Fy, τ)` as `(Fx, Fy, 0, 0, 0, τ)`.
pub fn wrench_from_planar(w: [f64; 3]) -> [f64; 6] {
    [w[0], w[1], 0.0, 0.0, 0.0, w[2]]
}

/// The planar components `(Fx, Fy, τz)` of a 6-DOF wrench.
pub fn wrench_to_planar(w: [f64; 6]) -> [f64; 3] {
    [w[0], w[1], w[5]]
}

/// The Hamilton product `a·b` (the rotation `R(a) R(b)`).
pub fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// The conjugate (the inverse of a unit quaternion).
pub fn quat_conj(q: [f64; 4]) -> [f64; 4] {
    [q[0], -q[1], -q[2], -q[3]]
}

/// `q / |q|`, or `None` for a zero or non-finite quaternion.
pub fn quat_normalize(q: [f64; 4]) -> Option<[f64; 4]> {
    let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    (n.is_finite() && n > 0.0).then(|| q.map(|v| v / n))
}

/// The rotation vector `φ` (rad, axis × angle, `|φ| ≤ π`) with `exp(φ̂) = R(q)`.
pub fn quat_log(q: [f64; 4]) -> [f64; 3] {
    // q and −q are the same rotation: take w ≥ 0 so the angle is at most π.
    let q = if q[0] < 0.0 { q.map(|v| -v) } else { q };
    let s = (q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
    // angle = 2·atan2(s, w); φ = axis·angle = (v/s)·angle; for small s, angle/s → 2/w.
    let scale = if s < 1e-12 { 2.0 / q[0] } else { 2.0 * s.atan2(q[0]) / s };
    [q[1] * scale, q[2] * scale, q[3] * scale]
}

/// The unit quaternion of the rotation vector `φ` (rad): `exp(φ̂)`.
pub fn quat_exp(phi: [f64; 3]) -> [f64; 4] {
    let angle = (phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2]).sqrt();
    let (s, c) = (0.5 * angle).sin_cos();
    // sin(angle/2)/angle → 1/2 as angle → 0.
    let k = if angle < 1e-12 { 0.5 } else { s / angle };
    [c, phi[0] * k, phi[1] * k, phi[2] * k]
}

/// The perturbation `δ(a, b) = (p_a − p_b, log(R_a R_bᵀ))` that takes pose b to pose a (see the module docs).
pub fn pose_delta(pa: [f64; 3], qa: [f64; 4], pb: [f64; 3], qb: [f64; 4]) -> [f64; 6] {
    let r = quat_log(quat_mul(qa, quat_conj(qb)));
    [pa[0] - pb[0], pa[1] - pb[1], pa[2] - pb[2], r[0], r[1], r[2]]
}

/// Pose b perturbed by `δ`: `(p_b + δp, exp(δθ̂) R_b)`.
pub fn pose_apply(pb: [f64; 3], qb: [f64; 4], d: [f64; 6]) -> ([f64; 3], [f64; 4]) {
    ([pb[0] + d[0], pb[1] + d[1], pb[2] + d[2]], quat_mul(quat_exp([d[3], d[4], d[5]]), qb))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Seeded uniform samples in [-1, 1).
    fn rng(seed: u64) -> impl FnMut() -> f64 {
        use rand::{Rng, SeedableRng};
        let mut g = rand::rngs::SmallRng::seed_from_u64(seed);
        move || g.random_range(-1.0..1.0)
    }

    #[test]
    fn planar_poses_round_trip() {
        for theta in [0.0, 0.3, -0.3, 1.5, -std::f64::consts::FRAC_PI_2, 3.0, -3.1, 4.0, -6.0, 6.2] {
            let (p, q) = pose_from_planar([0.01, -0.02, theta]);
            assert_eq!(p, [0.01, -0.02, 0.0]);
            assert!((q.iter().map(|v| v * v).sum::<f64>() - 1.0).abs() < 1e-15);
            let back = pose_to_planar(p, q);
            assert_eq!(&back[..2], &[0.01, -0.02]);
            assert!((back[2] - theta).abs() <= 4.0 * f64::EPSILON * theta.abs().max(1.0), "θ {theta} came back as {}", back[2]);
        }
    }

    #[test]
    fn planar_stiffness_and_wrench_round_trip_exactly_into_the_right_entries() {
        let j: [f64; 9] = std::array::from_fn(|i| (i as f64 + 1.0) * if i % 2 == 0 { -100.0 } else { 7.5 });
        let k = embed_planar_stiffness(&j);
        assert_eq!(restrict_planar_stiffness(&k), j);
        // ∂Fx/∂θ is K[0][5]; ∂τ/∂y is K[5][1]; nothing outside the planar axes.
        assert_eq!(k[0][5], j[2]);
        assert_eq!(k[5][1], j[7]);
        for (r, row) in k.iter().enumerate() {
            for (c, v) in row.iter().enumerate() {
                if !(PLANAR_AXES.contains(&r) && PLANAR_AXES.contains(&c)) {
                    assert_eq!(*v, 0.0, "K[{r}][{c}]");
                }
            }
        }
        let w = [1.5, -2.5, 0.125];
        assert_eq!(wrench_to_planar(wrench_from_planar(w)), w);
    }

    #[test]
    fn the_planar_delta_is_the_2d_difference() {
        // A rotation about z composes additively: δθ_z = θ_a − θ_b, and δ is the 2D difference.
        let (pa, qa) = pose_from_planar([0.02, 0.01, 0.7]);
        let (pb, qb) = pose_from_planar([0.015, 0.012, 0.4]);
        let d = pose_delta(pa, qa, pb, qb);
        let expect = [0.005, -0.002, 0.0, 0.0, 0.0, 0.3];
        for i in 0..6 {
            assert!((d[i] - expect[i]).abs() < 1e-14, "{d:?}");
        }
    }

    /// The perturbation's rotation is in world coordinates (`R ← exp(δθ̂)R`), not the body's: a base
    /// turned 90° about z and then 0.1 rad about world x (quaternion written out by hand,
    /// `q_x(0.1)·q_z(π/2) = (c₁c₂, s₁c₂, −s₁s₂, c₁s₂)`) differs from it by δθ = (0.1, 0, 0); in the
    /// body frame the same turn would read (0, −0.1, 0).
    #[test]
    fn the_rotation_of_a_perturbation_is_in_world_coordinates() {
        let (s1, c1) = 0.05f64.sin_cos();
        let (s2, c2) = std::f64::consts::FRAC_PI_4.sin_cos();
        let qb = [c2, 0.0, 0.0, s2];
        let qa = [c1 * c2, s1 * c2, -s1 * s2, c1 * s2];
        let d = pose_delta([0.0; 3], qa, [0.0; 3], qb);
        let expect = [0.0, 0.0, 0.0, 0.1, 0.0, 0.0];
        assert!(d.iter().zip(&expect).all(|(a, b)| (a - b).abs() < 1e-15), "{d:?}");
        let (_, q) = pose_apply([0.0; 3], qb, expect);
        assert!(q.iter().zip(&qa).all(|(a, b)| (a - b).abs() < 1e-15), "{q:?} vs {qa:?}");
    }

    #[test]
    fn exp_and_log_invert_and_delta_inverts_apply() {
        let mut r = rng(17);
        for _ in 0..200 {
            let phi = [r() * 1.5, r() * 1.5, r() * 1.5];
            let back = quat_log(quat_exp(phi));
            for i in 0..3 {
                assert!((back[i] - phi[i]).abs() < 1e-12, "{phi:?} → {back:?}");
            }
            let qb = quat_normalize([r(), r(), r(), r()]).unwrap();
            let pb = [r(), r(), r()];
            let d = [r() * 0.01, r() * 0.01, r() * 0.01, r() * 0.5, r() * 0.5, r() * 0.5];
            let (pa, qa) = pose_apply(pb, qb, d);
            let got = pose_delta(pa, qa, pb, qb);
            for i in 0..6 {
                assert!((got[i] - d[i]).abs() < 1e-12, "{d:?} → {got:?}");
            }
        }
        // The tiny-angle branch.
        assert_eq!(quat_log(IDENTITY), [0.0; 3]);
        let tiny = quat_log(quat_exp([1e-14, 0.0, -2e-14]));
        assert!((tiny[0] - 1e-14).abs() < 1e-28 && (tiny[2] + 2e-14).abs() < 1e-28);
        assert_eq!(quat_normalize([0.0; 4]), None);
    }
}
