//! FMU states of an instance: a copy of everything a restart needs ([`StateData`]), restored
//! into the kept simulation when its fixed parameters fit, and the serialized form (format and
//! checks in `fmi/fmu_state.rs`).
use super::lifecycle::same_fixed;
use super::Instance;
use crate::fmi::state_data::StateData;
use crate::fmi::state_machine::{error, mask, Failure, FmiResult, FmiState};
use crate::simulation::Simulation;

impl Instance {
    pub fn get_fmu_state(&self) -> FmiResult<StateData> {
        self.require(mask::ANY)?;
        let snapshot = match self.state {
            FmiState::Instantiated | FmiState::InitializationMode => None,
            _ => self.sim.as_ref().map(Simulation::snapshot),
        };
        self.log.event(|| {
            format!(
                "FMU state taken in state {} at t = {}",
                self.state.name(),
                self.time()
            )
        });
        Ok(StateData {
            scene: self.scene().name.clone(),
            fmi_state: self.state,
            experiment: self.experiment.clone(),
            params: self.params.clone(),
            inputs: self.inputs.clone(),
            snapshot,
        })
    }

    /// The serialized form of the state behind `handle` (one this instance gave out).
    pub fn serialize_state(&self, handle: crate::fmi::types::fmi2FMUstate) -> FmiResult<Vec<u8>> {
        let data = self.states.get(handle, "FMUstate")?;
        crate::fmi::fmu_state::serialize(data, self.scene(), &self.interface.guid)
            .map_err(Failure::Error)
    }

    /// A serialized state read back and checked against this instance.
    pub fn deserialize_state(&self, bytes: &[u8]) -> FmiResult<StateData> {
        let (scene, guid) = (self.scene(), &self.interface.guid);
        crate::fmi::fmu_state::deserialize(bytes, scene, guid, self.params.elements())
            .map_err(Failure::Error)
    }

    /// Checks that an FMU state fits this instance (scene and element count).
    pub fn check_compatible(&self, scene: &str, elements: usize) -> FmiResult {
        if scene != self.scene().name {
            return error(format!(
                "the FMU state belongs to the {scene} scene, this instance is a {}",
                self.scene().name
            ));
        }
        if elements != self.params.elements() {
            return error(format!(
                "the FMU state has {elements} elements, this instance has {} (set `elements` first)",
                self.params.elements()
            ));
        }
        Ok(())
    }

    pub fn set_fmu_state(&mut self, data: &StateData) -> FmiResult {
        self.require(mask::ANY)?;
        self.check_compatible(&data.scene, data.params.elements())?;
        let simulated = !matches!(
            data.fmi_state,
            FmiState::Instantiated | FmiState::InitializationMode
        );
        if simulated && data.snapshot.is_none() && data.fmi_state != FmiState::Error {
            return error(format!(
                "the FMU state ({}) holds no simulation state",
                data.fmi_state.name()
            ));
        }
        match data.snapshot.as_ref().filter(|_| simulated) {
            Some(snapshot) => {
                let scene = self.scene().clone();
                let reusable = self
                    .sim
                    .as_ref()
                    .is_some_and(|s| same_fixed(&scene, s.values(), &data.params));
                if reusable {
                    let sim = self.sim.as_mut().expect("checked");
                    let backup = sim.snapshot();
                    if let Err(e) = sim.restore(snapshot) {
                        sim.restore(&backup)
                            .expect("a snapshot of this simulation restores");
                        return error(e.to_string());
                    }
                } else {
                    let mut sim = Simulation::new(scene, data.params.clone())
                        .map_err(|e| Failure::Error(e.to_string()))?;
                    sim.restore(snapshot)
                        .map_err(|e| Failure::Error(e.to_string()))?;
                    self.sim = Some(sim);
                }
            }
            None => {
                // A state from before initialization: the kept simulation (if any) goes back to
                // t = 0, ready to be reused by fmi2ExitInitializationMode.
                if let Some(sim) = &mut self.sim {
                    sim.reset();
                }
            }
        }
        self.experiment = data.experiment.clone();
        self.params = data.params.clone();
        self.inputs.clone_from(&data.inputs);
        self.derivatives.clear();
        self.enter(data.fmi_state);
        self.log
            .event(|| format!("FMU state restored at t = {}", self.time()));
        Ok(())
    }
}
