//! One load step of friction (Coulomb's law, or any `contact::friction_law`):
//! a primal–dual active set (semismooth Newton) on the Alart–Curnier
//! complementarity functions.
//!
//! The normal rows N and the tangential rows T (`contact::friction`) are
//! condensed together from one factorization, W = [B_N; B_T] K⁻¹ [B_N; B_T]ᵀ,
//! so that for the normal forces λ and the tangential multipliers τ (friction
//! force −τ along the tangent)
//!
//! ```text
//! gap   w  = W_NN λ + W_NT τ + q,    q = g − B_N K⁻¹ f
//! slip  Δs = e − W_TN λ − W_TT τ,    e = B_T K⁻¹ f + ū_t − u_t(previous step)
//! ```
//!
//! and the step's conditions are λ ≥ 0, w ≥ 0, λ w = 0 and, in contact,
//! |τ| ≤ μ λ with Δs = 0 where |τ| < μ λ and τ = μ λ sign(Δs) where Δs ≠ 0
//! (the friction force opposes the slip: −τ Δs ≤ 0). Against another body
//! the law holds for τ + λ n · t instead of τ (`Tangents::along`: the normal
//! rows' direction is not quite normal to the tangent there). The slip is the
//! increment over the step (incremental, small-slip Coulomb law), measured
//! from the tangential displacement the previous step ended with.
//!
//! A load-controlled punch adds its free motions β (`methods::FreeBlock`): the rows read
//! the motion relative to the punch, w += C_N β and Δs −= C_T β, and the
//! punch is in equilibrium with its loads P under the normal and the
//! friction forces, C_Nᵀλ + C_Tᵀτ = −P. The Newton system gains β and these
//! equations; with |Q| > μ|P| on a sliding punch it has no solution, which
//! Fichera's test with the friction cone refuses before (`solve::frictional`). The rigid
//! modes R of a body held only by contact are motions of the same block,
//! C_N = −B_N R and C_T = −B_T R (they move the rows' own points), with the
//! equilibrium Rᵀ(f − B_Nᵀλ − B_Tᵀτ) = 0, i.e. P = Rᵀf.
//!
//! Why this method: in 2D the cone is an interval, so the Alart–Curnier
//! functions min(λ, c w) = 0 and τ = proj_[−μλ̃, μλ̃](τ + c_t Δs), λ̃ = λ − c w,
//! are piecewise linear with four pieces per point (open, stick, slip + and
//! slip −). Their semismooth Newton step is the linear system of the current
//! pieces, and Newton's update of the pieces is the active-set update, as in
//! the frictionless `active_set` (Hüeber, Stadler and Wohlmuth, SIAM J. Sci.
//! Comput. 30, 2008). It reuses the warm start of the previous step's states
//! (a load path changes a few points per step) and stops when the states
//! repeat, with the answer exact up to the linear algebra. A Tresca fixed
//! point on p would solve a QP per outer iteration and converge only
//! linearly in its outer loop. The system of a state set is not symmetric
//! (the slip rows tie τ to λ), so it is solved by LU; its size is the number
//! of points in contact plus those among them with a tangential row.
//!
//! The files: `newton`, the iteration on the states, written once for both
//! linear algebras (`NewtonSystem`) with its restarts and the Alart–Curnier
//! residual that ends it; `condensed`, its systems solved densely on the
//! condensed rows; `full`, on the whole system (`formulation: full`);
//! `gauss_seidel`, the condensed path's fallback when the iteration cycles.

pub mod condensed;
pub mod full;
pub mod gauss_seidel;
mod newton;

pub use newton::{Friction, History, State};
