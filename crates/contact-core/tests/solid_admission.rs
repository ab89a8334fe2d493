//! The 3D contact solve is admitted against its time limit as the 2D one
//! is: the numeric factorization, which does not poll the clock, starts
//! only if its predicted time (`FactorCost::predicted_secs`, from the
//! symbolic analysis in the nested-dissection order) fits in the time left.
//!
//! One test in its own binary: it sets this process's machine scale
//! (`linalg::rate`), which every factorization of the process reads and
//! learns into, so no other test may run beside it.

use std::time::Duration;

use contact_core::cancel::Deadline;
use contact_core::error::CoreError;
use contact_core::linalg::cholesky::SymbolicFactor;
use contact_core::linalg::{rate, LinalgError};
use contact_core::mesh3d::generate::box_mesh;
use contact_core::mesh3d::Order;
use contact_core::scene::Settings;
use contact_core::solid::dofs::dof_map;
use contact_core::solid::obstacle::{rows, Plane};
use contact_core::solid::ordering::{nested_dissection, predicted_secs};
use contact_core::solid::{signorini, stiffness, FaceLoad, SolidBody, Support};

/// A box on a plane under a uniform pressure, with an hour to solve it:
/// with the machine scale set so that its factorization is predicted at two
/// hours (a machine that much slower than the reference) it is refused
/// before it starts, the refusal carrying the cost of the analysis in the
/// nested-dissection order exactly (the same integers and the same sum);
/// at scale 1 the same solve is admitted and converges. The order and the
/// analysis are predicted on the same scale (`solid::ordering`) and must
/// fit the hour: the box is large enough (24³ cells, about 45k DOF) that
/// its factor costs more than they do, 0.59 s against 0.18 s on the
/// example's 47k-DOF T4 box.
#[test]
fn a_3d_factorization_predicted_past_the_time_left_is_not_started() {
    let mesh = box_mesh([0.0; 3], [1.0; 3], 1.0 / 24.0, None, Order::T4);
    let body = SolidBody {
        mesh: &mesh,
        youngs_modulus: 2.0,
        poisson_ratio: 0.3,
        supports: ["x_min", "x_max", "y_min", "y_max"]
            .iter()
            .enumerate()
            .map(|(k, f)| Support::roller(f, k / 2))
            .collect(),
        loads: vec![FaceLoad::Pressure {
            faces: "z_max".into(),
            p: 0.01,
        }],
        body_force: [0.0; 3],
    };
    let plane = Plane::try_new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let r = rows(&body, "z_min", plane).unwrap();
    let dofs = dof_map(&body, Some(&r.nodes)).unwrap();
    let k = stiffness::assemble(&body, &dofs).expect("no deadline here");
    let (fwd, inv) = nested_dissection(&mesh, &dofs).unwrap();
    let want = SymbolicFactor::try_new_ordered(&k.k, &fwd, &inv).unwrap().cost();
    let [ordering, analysis] = predicted_secs(Order::T4, dofs.n_free);
    let scale = 7200.0 / want.reference_secs();
    let _d = Deadline::install(Duration::from_secs(3600));
    rate::set_scale(scale);
    println!(
        "{} DOFs: nnz(L) {}, {:.3e} multiply-adds, predicted {:.3e} s at scale {scale:.3e}, its order and analysis \
         {:.3e} s",
        dofs.n_free,
        want.nnz,
        want.flops,
        want.predicted_secs(),
        (ordering + analysis) * scale
    );
    assert!(want.predicted_secs() > 3600.0);
    assert!(
        (ordering + analysis) * scale < 3600.0,
        "the order and analysis are admitted"
    );
    match signorini::solve(&body, &r, &Settings::default()) {
        Err(CoreError::Linalg(LinalgError::Overrun { cost, left_s })) => {
            assert_eq!((cost.nnz, cost.flops), (want.nnz, want.flops));
            assert!(left_s > 0.0 && left_s <= 3600.0, "left {left_s}");
        }
        other => panic!("expected an overrun, got {:?}", other.map(|c| c.converged)),
    }
    rate::set_scale(1.0);
    let c = signorini::solve(&body, &r, &Settings::default()).unwrap();
    assert!(c.converged);
}
