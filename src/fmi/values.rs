//! `fmi2Get*` / `fmi2Set*` on an instance: value references are looked up in the scene's
//! variable list, each value is checked, and a set applies only if every value is accepted.
use super::instance::Instance;
use super::state_machine::{error, mask, state_list, Failure, FmiResult, FmiState};
use crate::scene::variables::{Causality, Role, Timing, Variable};
use crate::scene::VarType;

/// `` `name` (vr N) `` for messages.
fn describe(var: &Variable) -> String {
    format!("`{}` (vr {})", var.name, var.vr)
}

/// The FMI function family that reads and writes a type (enumerations use the Integer ones).
fn type_name(t: VarType) -> &'static str {
    match t {
        VarType::Real => "Real",
        VarType::Integer => "Integer",
    }
}

impl Instance {
    /// The variable of this scene with value reference `vr` and type `ty`.
    fn variable(&self, vr: u32, ty: VarType, func: &str) -> FmiResult<Variable> {
        let Some(var) = self.interface().by_vr(vr) else {
            return error(format!(
                "unknown value reference {vr}: not a variable of the {} FMU",
                self.scene().name
            ));
        };
        if type_name(var.var_type) != type_name(ty) {
            let actual = type_name(var.var_type);
            return error(format!(
                "{} is an {actual} variable, not {} (use {}{actual})",
                describe(var),
                type_name(ty),
                &func[..7] // "fmi2Get" or "fmi2Set"
            ));
        }
        Ok(var.clone())
    }

    /// `fmi2GetBoolean` / `fmi2GetString` / the setters: this FMU has no such variables.
    pub fn no_variables_of_type(&self, func: &str, type_name: &str, vrs: &[u32]) -> FmiResult {
        self.require(if func.starts_with("fmi2Get") {
            mask::GET
        } else {
            mask::SET
        })?;
        let Some(&vr) = vrs.first() else {
            return Ok(());
        };
        let scene = &self.scene().name;
        match self.interface().by_vr(vr) {
            Some(var) => error(format!(
                "{} is not a {type_name} variable: the {scene} FMU has no {type_name} variables",
                describe(var),
            )),
            None => error(format!(
                "unknown value reference {vr}: the {scene} FMU has no {type_name} variables"
            )),
        }
    }

    fn get_values(&mut self, func: &str, ty: VarType, vrs: &[u32], out: &mut [f64]) -> FmiResult {
        self.require(mask::GET)?;
        let vars = vrs
            .iter()
            .map(|&vr| self.variable(vr, ty, func))
            .collect::<FmiResult<Vec<_>>>()?;
        let before_init = matches!(
            self.state(),
            FmiState::Instantiated | FmiState::InitializationMode
        );
        for (o, var) in out.iter_mut().zip(&vars) {
            *o = match var.role {
                Role::Parameter(i) => self.params().get(i),
                Role::Input(i) => self.input_value(i),
                Role::Output(crate::scene::variables::OutputId::Standard(
                    crate::scene::variables::StandardOutput::NewtonIterations,
                )) if before_init => 0.0,
                Role::Output(id) => self.output_simulation()?.output(id),
            };
        }
        self.log.trace(|| format!("{func}({vrs:?}) -> {out:?}"));
        Ok(())
    }

    pub fn get_real(&mut self, vrs: &[u32], out: &mut [f64]) -> FmiResult {
        self.get_values("fmi2GetReal", VarType::Real, vrs, out)
    }

    pub fn get_integer(&mut self, vrs: &[u32], out: &mut [i32]) -> FmiResult {
        let mut values = vec![0.0; vrs.len()];
        self.get_values("fmi2GetInteger", VarType::Integer, vrs, &mut values)?;
        for (o, v) in out.iter_mut().zip(values) {
            *o = v.clamp(i32::MIN as f64, i32::MAX as f64) as i32;
        }
        Ok(())
    }

    /// Checks every value first and applies them only if all are accepted.
    fn set_values(&mut self, func: &str, ty: VarType, vrs: &[u32], values: &[f64]) -> FmiResult {
        self.require(mask::SET)?;
        let scene = self.scene().clone();
        let mut params = self.params().clone();
        let mut inputs: Vec<(usize, f64)> = Vec::new();
        for (&vr, &value) in vrs.iter().zip(values) {
            let var = self.variable(vr, ty, func)?;
            let allowed = match (var.causality, var.timing) {
                (Causality::Output, _) => {
                    return error(format!("{} is an output: it cannot be set", describe(&var)));
                }
                (Causality::Parameter, Timing::Fixed) => mask::FIXED_PARAMETER,
                _ => mask::SET,
            };
            if allowed & self.state().bit() == 0 {
                let causality = if var.causality == Causality::Input {
                    "input"
                } else {
                    "parameter"
                };
                return error(format!(
                    "{} is a {} {causality}: it can be set in {} only, not in {}",
                    describe(&var),
                    var.timing.name(),
                    state_list(allowed),
                    self.state().name()
                ));
            }
            match var.role {
                Role::Parameter(i) => {
                    let name = &scene.params[i].name;
                    scene
                        .set(&mut params, name, value)
                        .map_err(|e| Failure::Error(format!("{e} (vr {vr})")))?;
                }
                Role::Input(i) => {
                    if !value.is_finite() {
                        return error(format!(
                            "{}: {value} is not a finite number",
                            describe(&var)
                        ));
                    }
                    inputs.push((i, value));
                }
                Role::Output(_) => unreachable!("refused above"),
            }
        }
        if self.state() == FmiState::StepComplete {
            if let Some(sim) = self.simulation_mut() {
                for (i, (&new, &old)) in params.0.iter().zip(&sim.values().0.clone()).enumerate() {
                    if new != old {
                        sim.set_param(i, new)
                            .map_err(|e| Failure::Error(e.to_string()))?;
                    }
                }
            }
        }
        self.set_params_and_inputs(params, &inputs);
        self.log.trace(|| format!("{func}({vrs:?}, {values:?})"));
        Ok(())
    }

    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> FmiResult {
        self.set_values("fmi2SetReal", VarType::Real, vrs, values)
    }

    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> FmiResult {
        let values: Vec<f64> = values.iter().map(|&v| v as f64).collect();
        self.set_values("fmi2SetInteger", VarType::Integer, vrs, &values)
    }
}
