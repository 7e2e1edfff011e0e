//! `fmi3DoStep`: the same step as `fmi2DoStep`, with FMI 3.0's out-arguments. The step is
//! never returned from early, never needs event handling and never asks to end the simulation;
//! `lastSuccessfulTime` is the instance's time after the call (the start of the step when it
//! was discarded: a failed step changes nothing).
use super::with_instance;
use crate::fmi::ffi::out_ref;
use crate::fmi::state_machine::Failure;
use crate::fmi::types3::*;

#[no_mangle]
pub unsafe extern "C" fn fmi3DoStep(
    instance: fmi3Instance,
    currentCommunicationPoint: fmi3Float64,
    communicationStepSize: fmi3Float64,
    _noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
    eventHandlingNeeded: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
    earlyReturn: *mut fmi3Boolean,
    lastSuccessfulTime: *mut fmi3Float64,
) -> fmi3Status {
    with_instance(instance, "fmi3DoStep", |inst| {
        // Every out-pointer is checked before the step: a refused call changes nothing.
        let flags = [
            out_ref(eventHandlingNeeded, "eventHandlingNeeded")?,
            out_ref(terminateSimulation, "terminateSimulation")?,
            out_ref(earlyReturn, "earlyReturn")?,
        ];
        let time = out_ref(lastSuccessfulTime, "lastSuccessfulTime")?;
        let result = inst.do_step(currentCommunicationPoint, communicationStepSize);
        // Answered for a completed and for a discarded step, not for a refused call.
        if matches!(result, Ok(()) | Err(Failure::Discard(_))) {
            for flag in flags {
                *flag = fmi3False;
            }
            *time = inst.time();
        }
        result
    })
}
