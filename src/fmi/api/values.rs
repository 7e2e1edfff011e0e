//! Variables: `fmi2Get*` / `fmi2Set*` for Real, Integer, Boolean and String (this FMU has no
//! Boolean or String variables), input derivatives, and the derivatives it does not provide
//! (directional and output derivatives: refused).
use super::{input, output, with_instance};
use crate::fmi::state_machine::{error, mask};
use crate::fmi::types::*;

#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2GetReal", |inst| {
        inst.require(mask::GET)?;
        inst.get_real(input(vr, nvr, "vr[]")?, output(value, nvr, "value[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    with_instance(c, "fmi2GetInteger", |inst| {
        inst.require(mask::GET)?;
        inst.get_integer(input(vr, nvr, "vr[]")?, output(value, nvr, "value[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2GetBoolean", |inst| {
        inst.require(mask::GET)?;
        output(value, nvr, "value[]")?;
        inst.no_variables_of_type("fmi2GetBoolean", "Boolean", input(vr, nvr, "vr[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2String,
) -> fmi2Status {
    with_instance(c, "fmi2GetString", |inst| {
        inst.require(mask::GET)?;
        output(value, nvr, "value[]")?;
        inst.no_variables_of_type("fmi2GetString", "String", input(vr, nvr, "vr[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2SetReal", |inst| {
        inst.require(mask::SET)?;
        inst.set_real(input(vr, nvr, "vr[]")?, input(value, nvr, "value[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    with_instance(c, "fmi2SetInteger", |inst| {
        inst.require(mask::SET)?;
        inst.set_integer(input(vr, nvr, "vr[]")?, input(value, nvr, "value[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    with_instance(c, "fmi2SetBoolean", |inst| {
        inst.require(mask::SET)?;
        input(value, nvr, "value[]")?;
        inst.no_variables_of_type("fmi2SetBoolean", "Boolean", input(vr, nvr, "vr[]")?)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2String,
) -> fmi2Status {
    with_instance(c, "fmi2SetString", |inst| {
        inst.require(mask::SET)?;
        input(value, nvr, "value[]")?;
        inst.no_variables_of_type("fmi2SetString", "String", input(vr, nvr, "vr[]")?)
    })
}

// ----- not supported --------------------------------------------------------------------------

#[no_mangle]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: fmi2Component,
    _vUnknown_ref: *const fmi2ValueReference,
    _nUnknown: usize,
    _vKnown_ref: *const fmi2ValueReference,
    _nKnown: usize,
    _dvKnown: *const fmi2Real,
    _dvUnknown: *mut fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2GetDirectionalDerivative", |inst| {
        inst.require(mask::DIRECTIONAL_DERIVATIVE)?;
        error("directional derivatives are not supported (providesDirectionalDerivative=false)")
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    order: *const fmi2Integer,
    value: *const fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2SetRealInputDerivatives", |inst| {
        inst.require(mask::SET_INPUT_DERIVATIVES)?;
        inst.set_input_derivatives(
            input(vr, nvr, "vr[]")?,
            input(order, nvr, "order[]")?,
            input(value, nvr, "value[]")?,
        )
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    with_instance(c, "fmi2GetRealOutputDerivatives", |inst| {
        inst.require(mask::GET_OUTPUT_DERIVATIVES)?;
        error("output derivatives are not supported (MaxOutputDerivativeOrder=0)")
    })
}
