//! Stepping and status: `fmi2DoStep`, `fmi2CancelStep` (there is never an asynchronous step to
//! cancel) and the `fmi2Get*Status` queries.
use super::{out_ref, with_instance};
use crate::fmi::instance::Instance;
use crate::fmi::state_machine::{error, mask, FmiResult};
use crate::fmi::types::*;

fn status_kind_arg(kind: fmi2StatusKind) -> FmiResult<&'static str> {
    match kind {
        fmi2DoStepStatus => Ok("fmi2DoStepStatus"),
        fmi2PendingStatus => Ok("fmi2PendingStatus"),
        fmi2LastSuccessfulTime => Ok("fmi2LastSuccessfulTime"),
        fmi2Terminated => Ok("fmi2Terminated"),
        other => error(format!(
            "{} is not a valid status kind",
            status_kind_name(other)
        )),
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: fmi2Component,
    currentCommunicationPoint: fmi2Real,
    communicationStepSize: fmi2Real,
    _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2DoStep", |inst| {
        inst.do_step(currentCommunicationPoint, communicationStepSize)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    with_instance(c, "fmi2CancelStep", Instance::cancel_step)
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Status,
) -> fmi2Status {
    with_instance(c, "fmi2GetStatus", |inst| {
        inst.require(mask::STATUS)?;
        out_ref(value, "value")?;
        inst.status_unavailable("fmi2GetStatus", status_kind_arg(s)?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2GetRealStatus", |inst| {
        inst.require(mask::STATUS)?;
        let value = out_ref(value, "value")?;
        let kind = status_kind_arg(s)?;
        if s != fmi2LastSuccessfulTime {
            return inst.status_unavailable("fmi2GetRealStatus", kind);
        }
        *value = inst.last_successful_time()?;
        Ok(())
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Integer,
) -> fmi2Status {
    with_instance(c, "fmi2GetIntegerStatus", |inst| {
        inst.require(mask::STATUS)?;
        out_ref(value, "value")?;
        inst.status_unavailable("fmi2GetIntegerStatus", status_kind_arg(s)?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2GetBooleanStatus", |inst| {
        inst.require(mask::STATUS)?;
        let value = out_ref(value, "value")?;
        let kind = status_kind_arg(s)?;
        if s != fmi2Terminated {
            return inst.status_unavailable("fmi2GetBooleanStatus", kind);
        }
        *value = if inst.terminated()? {
            fmi2True
        } else {
            fmi2False
        };
        Ok(())
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2String,
) -> fmi2Status {
    with_instance(c, "fmi2GetStringStatus", |inst| {
        inst.require(mask::STATUS)?;
        out_ref(value, "value")?;
        inst.status_unavailable("fmi2GetStringStatus", status_kind_arg(s)?)
    })
}
