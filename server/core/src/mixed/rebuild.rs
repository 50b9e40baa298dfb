//! The from-scratch hybrid matrix (a dense factorisation of the working compliance): the
//! reference for the $O(d^2)$ updates, never called inside a real-time step.

use super::blocks::to_local;
use super::{Condition, MixedError, MixedSolver};
use crate::compliance::ContactBlocks;
use crate::ids::Axis;

impl<const D: usize> MixedSolver<D> {
    /// Rebuilds $H$ from $C_{\mathcal{WW}}$ (plus each slot's series compliance) from scratch with
    /// a dense factorisation: the reference for the $O(d^2)$ updates, $O(d^3)$ and allocating,
    /// never called inside a real-time step.
    ///
    /// Errors: those of [`MixedSolver::hybrid_from_scratch`].
    pub fn rebuild<C: ContactBlocks<D> + ?Sized>(&mut self, cache: &C) -> Result<(), MixedError> {
        let h = self.hybrid_from_scratch(cache)?;
        let d = self.n_dofs();
        for i in 0..d {
            for j in 0..d {
                self.h[i * self.stride + j] = h[(i, j)];
            }
        }
        self.stats.n_rebuilds += 1;
        Ok(())
    }

    /// The hybrid matrix for the current contacts, frames and kinds, computed from scratch (a
    /// dense Cholesky of $C_{PP}$).
    ///
    /// Errors: [`MixedError::NotCached`] when a contact's columns are missing,
    /// [`MixedError::SingularPivot`] (naming the first displacement-prescribed DOF, pivot 0)
    /// when $C_{PP}$ is not positive definite.
    pub fn hybrid_from_scratch<C: ContactBlocks<D> + ?Sized>(&self, cache: &C) -> Result<faer::Mat<f64>, MixedError> {
        let d = self.n_dofs();
        let mut cl = faer::Mat::<f64>::zeros(d, d);
        for a in 0..self.n_nodes {
            for b in 0..self.n_nodes {
                let (ca, cb) = (&self.contact_of_slot[a], &self.contact_of_slot[b]);
                let mut blk = cache.contact_block(ca, cb).ok_or(MixedError::NotCached { contact: cb.id() })?;
                if a == b {
                    for (row, srow) in blk.iter_mut().zip(&self.series[a]) {
                        for (v, s) in row.iter_mut().zip(srow) {
                            *v += s;
                        }
                    }
                }
                let l = to_local(&blk, &self.frame[a], &self.frame[b]);
                for i in 0..D {
                    for j in 0..D {
                        cl[(D * a + i, D * b + j)] = l[i][j];
                    }
                }
            }
        }
        let sym = cl.transpose().to_owned();
        let cl = (&cl + &sym) * faer::Scale(0.5);
        let p: Vec<usize> = (0..d).filter(|&k| self.kind[k] == Condition::Displacement).collect();
        let f: Vec<usize> = (0..d).filter(|&k| self.kind[k] == Condition::Force).collect();
        let cpp = faer::Mat::from_fn(p.len(), p.len(), |i, j| cl[(p[i], p[j])]);
        let cpf = faer::Mat::from_fn(p.len(), f.len(), |i, j| cl[(p[i], f[j])]);
        let mut h = faer::Mat::<f64>::zeros(d, d);
        let (hpp, hpf) = if p.is_empty() {
            (faer::Mat::zeros(0, 0), faer::Mat::zeros(0, f.len()))
        } else {
            let llt = cpp.llt(faer::Side::Lower).map_err(|_| {
                let k = p[0];
                MixedError::SingularPivot { contact: self.contact_of_slot[k / D].id(), axis: Axis::of_local_dof::<D>(k), pivot: 0.0 }
            })?;
            let inv = faer::linalg::solvers::DenseSolveCore::inverse(&llt);
            let hpf = -(&inv * &cpf);
            (inv, hpf)
        };
        for (i, &pi) in p.iter().enumerate() {
            for (j, &pj) in p.iter().enumerate() {
                h[(pi, pj)] = hpp[(i, j)];
            }
            for (j, &fj) in f.iter().enumerate() {
                h[(pi, fj)] = hpf[(i, j)];
                // H_FP = C_FP C_PP^-1 = -H_PF^T.
                h[(fj, pi)] = -hpf[(i, j)];
            }
        }
        for &fi in &f {
            for (j, &fj) in f.iter().enumerate() {
                // C_FF - C_FP C_PP^-1 C_PF = C_FF + C_FP H_PF.
                let mut v = cl[(fi, fj)];
                for (k, &pk) in p.iter().enumerate() {
                    v += cl[(fi, pk)] * hpf[(k, j)];
                }
                h[(fi, fj)] = v;
            }
        }
        Ok(h)
    }
}
