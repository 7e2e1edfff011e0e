//! Parameters and inputs of an instance as the value functions (`fmi/values.rs`) see them: the
//! value an input holds, input derivatives for the next step, and the simulation outputs are
//! read from.
use super::Instance;
use crate::fmi::state_machine::{error, mask, FmiResult, FmiState};
use crate::scene::variables::input_start;
use crate::scene::ParamValues;
use crate::simulation::Simulation;

impl Instance {
    /// The value of input `i` the next step holds: the host's, or its start value.
    pub(crate) fn input_value(&self, i: usize) -> f64 {
        self.inputs[i].unwrap_or_else(|| input_start(self.scene(), i, &self.params))
    }

    /// `fmi2SetRealInputDerivatives`: derivatives of inputs for the next step (orders 1 and 2).
    pub fn set_input_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        values: &[f64],
    ) -> FmiResult {
        self.require(mask::SET_INPUT_DERIVATIVES)?;
        let mut set = Vec::with_capacity(vrs.len());
        for ((&vr, &order), &value) in vrs.iter().zip(orders).zip(values) {
            let Some(var) = self.interface.by_vr(vr) else {
                return error(format!("unknown value reference {vr}"));
            };
            let crate::scene::variables::Role::Input(i) = var.role else {
                return error(format!("`{}` (vr {vr}) is not an input", var.name));
            };
            if !(1..=2).contains(&order) {
                return error(format!(
                    "`{}`: derivative order {order}: this FMU interpolates with orders 1 and 2",
                    var.name
                ));
            }
            if !value.is_finite() {
                return error(format!("`{}`: derivative {value} is not finite", var.name));
            }
            set.push((i, order as usize, value));
        }
        for d in set {
            self.derivatives.retain(|&(i, o, _)| (i, o) != (d.0, d.1));
            self.derivatives.push(d);
        }
        Ok(())
    }

    pub(crate) fn simulation_mut(&mut self) -> Option<&mut Simulation> {
        self.sim.as_mut()
    }

    pub(crate) fn set_params_and_inputs(&mut self, params: ParamValues, inputs: &[(usize, f64)]) {
        self.params = params;
        for &(i, x) in inputs {
            self.inputs[i] = Some(x);
        }
    }

    /// The simulation the outputs are read from.
    pub(crate) fn output_simulation(&mut self) -> FmiResult<&Simulation> {
        match self.state {
            FmiState::Instantiated | FmiState::InitializationMode => {
                Ok(&*self.initial_simulation()?)
            }
            _ => match &self.sim {
                Some(sim) => Ok(sim),
                None => error(
                    "no simulation state to read outputs from (initialization failed); reset the instance",
                ),
            },
        }
    }
}
