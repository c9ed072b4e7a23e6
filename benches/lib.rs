//! What the reports and the examples share: `ode_solvers`' Dop853 on
//! qdot's compiled right-hand side, set up in one place so that the report
//! (`work_precision.rs`) and the driver measurements
//! (`examples/driver_cost.rs`) time the same configuration.

use qdot::simulate::compile::CompiledDynamics;
use qdot::simulate::problems::Problem;
use qdot::simulate::System as _;
use std::cell::RefCell;

/// The compiled dynamics behind `ode_solvers`' `&self` interface.
pub struct OdeSolversRhs<'a, const D: usize>(pub &'a RefCell<CompiledDynamics>);

impl<const D: usize> ode_solvers::System<f64, ode_solvers::SVector<f64, D>>
    for OdeSolversRhs<'_, D>
{
    fn system(
        &self,
        t: f64,
        y: &ode_solvers::SVector<f64, D>,
        dy: &mut ode_solvers::SVector<f64, D>,
    ) {
        self.0.borrow_mut().rhs(t, y.as_slice(), dy.as_mut_slice());
    }
}

/// `ode_solvers`' Dop853 from `p.y0` over [0, `p.t_end`] at rtol = atol =
/// `tol` (state as a stack vector of dimension D, the crate's fastest
/// form), with Hairer's controller constants and sparse output: every
/// accepted step is recorded and no dense-output coefficients are computed
/// (Dense costs DOP853 three extra evaluations per step).
pub fn ode_solvers_dop853<'a, const D: usize>(
    p: &Problem,
    sys: &'a RefCell<CompiledDynamics>,
    tol: f64,
) -> ode_solvers::Dop853<f64, ode_solvers::SVector<f64, D>, OdeSolversRhs<'a, D>> {
    ode_solvers::Dop853::from_param(
        OdeSolversRhs::<D>(sys),
        0.0,
        p.t_end,
        p.t_end,
        ode_solvers::SVector::<f64, D>::from_column_slice(&p.y0),
        tol,
        tol,
        0.9,
        0.0,
        0.333,
        6.0,
        p.t_end,
        0.0,
        50_000_000,
        u32::MAX,
        ode_solvers::OutputType::Sparse,
    )
}
