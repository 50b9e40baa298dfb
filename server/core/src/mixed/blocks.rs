//! The $D \times D$ block algebra of the solver (products, the change to local frames, small
//! pivots and inverses), the checks and re-orthonormalisation of a frame, the 2D rotations, and
//! the solve's dot product.

use super::{Block, FRAME_TOL, MixedError};
use crate::contact::ContactPoint;

pub(super) fn rot(angle_rad: f64) -> [[f64; 2]; 2] {
    let (s, c) = angle_rad.sin_cos();
    [[c, -s], [s, c]]
}

/// The 2D frame of angle $\theta$: rows $t = (\cos\theta, \sin\theta)$,
/// $n = (-\sin\theta, \cos\theta)$, i.e. $R(\theta)^\top$.
pub fn frame_of_angle(angle_rad: f64) -> Block<2> {
    let (s, c) = angle_rad.sin_cos();
    [[c, s], [-s, c]]
}

/// $F_a M F_b^\top$ for $D \times D$ blocks (a world block to the local frames of $a$ and $b$).
/// The sums run in index order from the first product, so in 2D this is bit for bit the former
/// $R_a^\top M R_b$.
#[inline]
pub(super) fn to_local<const D: usize>(m: &Block<D>, fa: &Block<D>, fb: &Block<D>) -> Block<D> {
    let mb: Block<D> = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut acc = m[i][0] * fb[j][0];
            for k in 1..D {
                acc += m[i][k] * fb[j][k];
            }
            acc
        })
    });
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut acc = fa[i][0] * mb[0][j];
            for k in 1..D {
                acc += fa[i][k] * mb[k][j];
            }
            acc
        })
    })
}

/// The product $AB$ of two $D \times D$ blocks.
#[inline]
pub(super) fn mul<const D: usize>(a: &Block<D>, b: &Block<D>) -> Block<D> {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut acc = a[i][0] * b[0][j];
            for k in 1..D {
                acc += a[i][k] * b[k][j];
            }
            acc
        })
    })
}

/// $A B^\top$.
#[inline]
pub(super) fn mul_t<const D: usize>(a: &Block<D>, b: &Block<D>) -> Block<D> {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut acc = a[i][0] * b[j][0];
            for k in 1..D {
                acc += a[i][k] * b[j][k];
            }
            acc
        })
    })
}

/// The product of two 2 × 2 blocks.
pub(super) fn mul2(a: [[f64; 2]; 2], b: [[f64; 2]; 2]) -> [[f64; 2]; 2] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j]))
}

/// The principal pivot of a small block on index `k` (the formulas of the module doc); the
/// caller has checked $m_{kk} \ne 0$.
pub(super) fn pivot_block<const D: usize>(m: &Block<D>, k: usize) -> Block<D> {
    let inv_p = 1.0 / m[k][k];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| match (i == k, j == k) {
            (true, true) => inv_p,
            (true, false) => -m[k][j] * inv_p,
            (false, true) => m[i][k] * inv_p,
            (false, false) => m[i][j] - m[i][k] * m[k][j] * inv_p,
        })
    })
}

/// The inverse of a $D \times D$ block by Gauss–Jordan elimination with partial pivoting; `None`
/// when a pivot is zero or not finite.
pub(super) fn invert<const D: usize>(m: &Block<D>) -> Option<Block<D>> {
    let mut a = *m;
    let mut inv: Block<D> = std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }));
    for col in 0..D {
        let mut piv = col;
        for r in col + 1..D {
            if a[r][col].abs() > a[piv][col].abs() {
                piv = r;
            }
        }
        let p = a[piv][col];
        if !(p != 0.0 && p.is_finite()) {
            return None;
        }
        a.swap(col, piv);
        inv.swap(col, piv);
        let inv_p = 1.0 / p;
        for j in 0..D {
            a[col][j] *= inv_p;
            inv[col][j] *= inv_p;
        }
        for r in 0..D {
            if r != col {
                let f = a[r][col];
                if f != 0.0 {
                    for j in 0..D {
                        a[r][j] -= f * a[col][j];
                        inv[r][j] -= f * inv[col][j];
                    }
                }
            }
        }
    }
    Some(inv)
}

/// The determinant of a 2 × 2 or 3 × 3 block.
fn det<const D: usize>(m: &Block<D>) -> f64 {
    match D {
        2 => m[0][0] * m[1][1] - m[0][1] * m[1][0],
        3 => {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        }
        _ => unreachable!("a solver is 2D or 3D"),
    }
}

/// Checks that `f` is a finite rotation ([`MixedError::NonFinite`], [`MixedError::NotARotation`]).
pub(super) fn check_frame<const D: usize>(f: &Block<D>, contact: ContactPoint) -> Result<(), MixedError> {
    if !f.iter().flatten().all(|v| v.is_finite()) {
        return Err(MixedError::NonFinite { what: "the frame", contact: contact.id() });
    }
    let fft = mul_t(f, f);
    let mut err: f64 = 0.0;
    for i in 0..D {
        for j in 0..D {
            err = err.max((fft[i][j] - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    let d = det(f);
    if !(err <= FRAME_TOL && d > 0.0) {
        return Err(MixedError::NotARotation { contact: contact.id(), orthonormality_error: err, det: d });
    }
    Ok(())
}

/// The frame `f` (a rotation to [`FRAME_TOL`]) made orthonormal to rounding: Gram–Schmidt on
/// $t$ and $n$, and in 3D $b = t \times n$. Frames are stored this way so that a frame change's
/// $G = F' F^\top$ is the exact map between the two local bases (with $F^\top$ standing for
/// $F^{-1}$); otherwise frames composed over many ticks would drift from orthonormality and
/// $H$ from the frames with them.
pub(super) fn orthonormalized<const D: usize>(f: &Block<D>) -> Block<D> {
    let dot = |a: &[f64; D], b: &[f64; D]| (0..D).map(|k| a[k] * b[k]).sum::<f64>();
    let mut out = *f;
    let nt = dot(&out[0], &out[0]).sqrt();
    out[0] = out[0].map(|v| v / nt);
    let tn = dot(&out[0], &out[1]);
    out[1] = std::array::from_fn(|k| out[1][k] - tn * out[0][k]);
    let nn = dot(&out[1], &out[1]).sqrt();
    out[1] = out[1].map(|v| v / nn);
    if D == 3 {
        let (t, n) = (out[0], out[1]);
        out[2] = std::array::from_fn(|k| t[(k + 1) % D] * n[(k + 2) % D] - t[(k + 2) % D] * n[(k + 1) % D]);
    }
    out
}

/// $a \cdot b$ with eight independent partial sums, so that the additions pipeline and
/// vectorise (one chain of additions is latency-bound: this is the solve's inner loop).
#[inline]
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    let mut tail = 0.0;
    for (x, y) in ra.iter().zip(rb) {
        tail += x * y;
    }
    ((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7])) + tail
}

/// $R(\theta)\,v$.
pub fn local_to_world(v: [f64; 2], angle_rad: f64) -> [f64; 2] {
    let (s, c) = angle_rad.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// $R(\theta)^\top v$.
pub fn world_to_local(v: [f64; 2], angle_rad: f64) -> [f64; 2] {
    let (s, c) = angle_rad.sin_cos();
    [c * v[0] + s * v[1], -s * v[0] + c * v[1]]
}
