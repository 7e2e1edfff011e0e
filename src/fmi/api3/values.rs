//! Variables: `fmi3Get*` / `fmi3Set*`. A value reference names a scalar or a whole array
//! (`nValues` counts elements); the references are mapped to the FMI 2.0 scalars of their
//! elements ([`crate::packaging::variables3::Layout3`]) and handed to the same instance methods
//! as `fmi2GetReal` / `fmi2SetReal`. The FMU has Float64 and Int32 variables; the functions of
//! every other type (Int64's included, which check their references like the others) accept
//! only an empty list.
use super::with_instance;
use crate::fmi::ffi::{input, output};
use crate::fmi::instance::Instance;
use crate::fmi::state_machine::{error, mask, FmiResult};
use crate::fmi::types3::*;
use crate::packaging::variables3::TIME_VR;
use crate::scene::VarType;

/// The FMI 3.0 type of a variable.
fn type3(t: VarType) -> &'static str {
    match t {
        VarType::Real => "Float64",
        VarType::Integer => "Int32",
    }
}

/// The FMI 2.0 value references of the elements behind `vrs`, which must all be variables of
/// FMI 3.0 type `ty` with `n_values` elements in all. `func` is the calling function.
fn elements(
    inst: &Instance,
    func: &str,
    ty: &str,
    vrs: &[u32],
    n_values: usize,
) -> FmiResult<Vec<u32>> {
    let interface = inst.interface();
    let layout = &interface.layout3;
    let mut out = Vec::with_capacity(n_values);
    for &vr in vrs {
        if vr == TIME_VR && ty == "Float64" {
            out.push(TIME_VR);
            continue;
        }
        let Some(var) = layout.by_vr(vr) else {
            return error(format!(
                "unknown value reference {vr}: not a variable of the {} FMU (an array element \
                 has no value reference of its own in FMI 3.0: read the array)",
                interface.scene.name
            ));
        };
        let actual = type3(interface.variables[var.first].var_type);
        if actual != ty {
            return error(format!(
                "`{}` (vr {vr}) is a {actual} variable, not {ty} (use {}{actual})",
                var.name,
                &func[..7]
            ));
        }
        out.extend_from_slice(layout.element_vrs(var));
    }
    if out.len() != n_values {
        return error(format!(
            "nValues = {n_values}, but the {} value references have {} elements",
            vrs.len(),
            out.len()
        ));
    }
    Ok(out)
}

/// The values of FMI 2.0 value references and `time` (which FMI 2.0 has no variable for).
fn get_float64(inst: &mut Instance, vrs: &[u32], values: &mut [f64]) -> FmiResult {
    if !vrs.contains(&TIME_VR) {
        return inst.get_real(vrs, values);
    }
    let scalars: Vec<u32> = vrs.iter().copied().filter(|&vr| vr != TIME_VR).collect();
    let mut read = vec![0.0; scalars.len()];
    inst.get_real(&scalars, &mut read)?;
    let mut read = read.into_iter();
    for (value, &vr) in values.iter_mut().zip(vrs) {
        *value = if vr == TIME_VR {
            inst.time()
        } else {
            read.next().unwrap_or(f64::NAN)
        };
    }
    Ok(())
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetFloat64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3Float64,
    nValues: usize,
) -> fmi3Status {
    const F: &str = "fmi3GetFloat64";
    with_instance(instance, F, |inst| {
        inst.require(mask::GET)?;
        let vrs = input(valueReferences, nValueReferences, "valueReferences")?;
        let values = output(values, nValues, "values")?;
        let vrs = elements(inst, F, "Float64", vrs, nValues)?;
        get_float64(inst, &vrs, values)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt32(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3Int32,
    nValues: usize,
) -> fmi3Status {
    const F: &str = "fmi3GetInt32";
    with_instance(instance, F, |inst| {
        inst.require(mask::GET)?;
        let vrs = input(valueReferences, nValueReferences, "valueReferences")?;
        let values = output(values, nValues, "values")?;
        let vrs = elements(inst, F, "Int32", vrs, nValues)?;
        inst.get_integer(&vrs, values)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3Int64,
    nValues: usize,
) -> fmi3Status {
    const F: &str = "fmi3GetInt64";
    with_instance(instance, F, |inst| {
        inst.require(mask::GET)?;
        let vrs = input(valueReferences, nValueReferences, "valueReferences")?;
        let values = output(values, nValues, "values")?;
        let vrs = elements(inst, F, "Int64", vrs, nValues)?;
        let mut narrow = vec![0; nValues];
        inst.get_integer(&vrs, &mut narrow)?;
        for (v, n) in values.iter_mut().zip(narrow) {
            *v = n.into();
        }
        Ok(())
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetFloat64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3Float64,
    nValues: usize,
) -> fmi3Status {
    const F: &str = "fmi3SetFloat64";
    with_instance(instance, F, |inst| {
        inst.require(mask::SET)?;
        let vrs = input(valueReferences, nValueReferences, "valueReferences")?;
        let values = input(values, nValues, "values")?;
        let vrs = elements(inst, F, "Float64", vrs, nValues)?;
        if vrs.contains(&TIME_VR) {
            return error(format!(
                "`time` (vr {TIME_VR}) is the independent variable: it cannot be set"
            ));
        }
        inst.set_real(&vrs, values)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt32(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3Int32,
    nValues: usize,
) -> fmi3Status {
    const F: &str = "fmi3SetInt32";
    with_instance(instance, F, |inst| {
        inst.require(mask::SET)?;
        let vrs = input(valueReferences, nValueReferences, "valueReferences")?;
        let values = input(values, nValues, "values")?;
        let vrs = elements(inst, F, "Int32", vrs, nValues)?;
        inst.set_integer(&vrs, values)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3Int64,
    nValues: usize,
) -> fmi3Status {
    const F: &str = "fmi3SetInt64";
    with_instance(instance, F, |inst| {
        inst.require(mask::SET)?;
        let vrs = input(valueReferences, nValueReferences, "valueReferences")?;
        let values = input(values, nValues, "values")?;
        let vrs = elements(inst, F, "Int64", vrs, nValues)?;
        let mut narrow = Vec::with_capacity(nValues);
        for (&v, vr) in values.iter().zip(&vrs) {
            let Ok(n) = i32::try_from(v) else {
                return error(format!(
                    "{v} (element of vr {vr}) is not an item of the enumeration"
                ));
            };
            narrow.push(n);
        }
        inst.set_integer(&vrs, &narrow)
    })
}

/// A getter or setter of a type this FMU has no variables of: pointers are checked, and an
/// empty list is accepted; any value reference is refused (unknown, or of another type).
fn no_variables(
    instance: fmi3Instance,
    func: &'static str,
    ty: &'static str,
    vrs: FmiResult<&[u32]>,
    values: FmiResult<()>,
    n_values: usize,
) -> fmi3Status {
    with_instance(instance, func, |inst| {
        inst.require(if func.starts_with("fmi3Get") {
            mask::GET
        } else {
            mask::SET
        })?;
        let vrs = vrs?;
        values?;
        elements(inst, func, ty, vrs, n_values).map(|_| ())
    })
}

/// Exports `fmi3Get<Type>` / `fmi3Set<Type>` for types this FMU has no variables of.
macro_rules! no_variables_of_type {
    ($($get:ident, $set:ident, $ty:ty, $name:literal;)*) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $get(
            instance: fmi3Instance,
            valueReferences: *const fmi3ValueReference,
            nValueReferences: usize,
            values: *mut $ty,
            nValues: usize,
        ) -> fmi3Status {
            no_variables(
                instance,
                stringify!($get),
                $name,
                input(valueReferences, nValueReferences, "valueReferences"),
                output(values, nValues, "values").map(|_| ()),
                nValues,
            )
        }

        #[no_mangle]
        pub unsafe extern "C" fn $set(
            instance: fmi3Instance,
            valueReferences: *const fmi3ValueReference,
            nValueReferences: usize,
            values: *const $ty,
            nValues: usize,
        ) -> fmi3Status {
            no_variables(
                instance,
                stringify!($set),
                $name,
                input(valueReferences, nValueReferences, "valueReferences"),
                input(values, nValues, "values").map(|_| ()),
                nValues,
            )
        }
    )*};
}

no_variables_of_type! {
    fmi3GetFloat32, fmi3SetFloat32, fmi3Float32, "Float32";
    fmi3GetInt8, fmi3SetInt8, fmi3Int8, "Int8";
    fmi3GetUInt8, fmi3SetUInt8, fmi3UInt8, "UInt8";
    fmi3GetInt16, fmi3SetInt16, fmi3Int16, "Int16";
    fmi3GetUInt16, fmi3SetUInt16, fmi3UInt16, "UInt16";
    fmi3GetUInt32, fmi3SetUInt32, fmi3UInt32, "UInt32";
    fmi3GetUInt64, fmi3SetUInt64, fmi3UInt64, "UInt64";
    fmi3GetBoolean, fmi3SetBoolean, fmi3Boolean, "Boolean";
    fmi3GetString, fmi3SetString, fmi3String, "String";
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetBinary(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    valueSizes: *mut usize,
    values: *mut fmi3Binary,
    nValues: usize,
) -> fmi3Status {
    let pointers = output(valueSizes, nValues, "valueSizes")
        .and_then(|_| output(values, nValues, "values"))
        .map(|_| ());
    let vrs = input(valueReferences, nValueReferences, "valueReferences");
    no_variables(instance, "fmi3GetBinary", "Binary", vrs, pointers, nValues)
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetBinary(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    valueSizes: *const usize,
    values: *const fmi3Binary,
    nValues: usize,
) -> fmi3Status {
    let pointers = input(valueSizes, nValues, "valueSizes")
        .and_then(|_| input(values, nValues, "values"))
        .map(|_| ());
    let vrs = input(valueReferences, nValueReferences, "valueReferences");
    no_variables(instance, "fmi3SetBinary", "Binary", vrs, pointers, nValues)
}

/// Clocks have one value per reference (no `nValues`).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetClock(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3Clock,
) -> fmi3Status {
    let pointers = output(values, nValueReferences, "values").map(|_| ());
    let vrs = input(valueReferences, nValueReferences, "valueReferences");
    no_variables(
        instance,
        "fmi3GetClock",
        "Clock",
        vrs,
        pointers,
        nValueReferences,
    )
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetClock(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3Clock,
) -> fmi3Status {
    let pointers = input(values, nValueReferences, "values").map(|_| ());
    let vrs = input(valueReferences, nValueReferences, "valueReferences");
    no_variables(
        instance,
        "fmi3SetClock",
        "Clock",
        vrs,
        pointers,
        nValueReferences,
    )
}
