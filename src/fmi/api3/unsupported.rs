//! The FMI 3.0 functions this Co-Simulation FMU does not support, exported with the standard's
//! signatures so that any host links: each checks its instance handle and answers `fmi3Error`
//! with a logged reason. Model Exchange and Scheduled Execution instantiation answer NULL.
use super::with_instance;
use crate::fmi::ffi::string;
use crate::fmi::logging::{Callback, Logger};
use crate::fmi::state_machine::error;
use crate::fmi::types3::*;

/// Exports functions `fn(instance, ...) -> fmi3Status` that answer `fmi3Error` with `why`.
macro_rules! refused {
    ($($name:ident($($arg:ident: $ty:ty),*) => $why:literal;)*) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(instance: fmi3Instance, $($arg: $ty),*) -> fmi3Status {
            $(let _ = $arg;)*
            with_instance(instance, stringify!($name), |_| error($why))
        }
    )*};
}

refused! {
    fmi3EnterEventMode() => "this FMU has no event mode (hasEventMode=\"false\")";
    fmi3EnterStepMode() => "step mode is entered by fmi3ExitInitializationMode: this FMU has no event mode (hasEventMode=\"false\")";
    fmi3EvaluateDiscreteStates() => "this FMU has no discrete states to evaluate (Co-Simulation without event mode)";
    fmi3UpdateDiscreteStates(
        discreteStatesNeedUpdate: *mut fmi3Boolean,
        terminateSimulation: *mut fmi3Boolean,
        nominalsOfContinuousStatesChanged: *mut fmi3Boolean,
        valuesOfContinuousStatesChanged: *mut fmi3Boolean,
        nextEventTimeDefined: *mut fmi3Boolean,
        nextEventTime: *mut fmi3Float64
    ) => "this FMU has no event mode (hasEventMode=\"false\")";
    fmi3GetNumberOfVariableDependencies(
        valueReference: fmi3ValueReference,
        nDependencies: *mut usize
    ) => "variable dependencies are not provided (ModelStructure lists no dependencies: every output depends on every known)";
    fmi3GetVariableDependencies(
        dependent: fmi3ValueReference,
        elementIndicesOfDependent: *mut usize,
        independents: *mut fmi3ValueReference,
        elementIndicesOfIndependents: *mut usize,
        dependencyKinds: *mut fmi3DependencyKind,
        nDependencies: usize
    ) => "variable dependencies are not provided (ModelStructure lists no dependencies: every output depends on every known)";
    fmi3GetDirectionalDerivative(
        unknowns: *const fmi3ValueReference,
        nUnknowns: usize,
        knowns: *const fmi3ValueReference,
        nKnowns: usize,
        seed: *const fmi3Float64,
        nSeed: usize,
        sensitivity: *mut fmi3Float64,
        nSensitivity: usize
    ) => "directional derivatives are not supported (providesDirectionalDerivatives=\"false\")";
    fmi3GetAdjointDerivative(
        unknowns: *const fmi3ValueReference,
        nUnknowns: usize,
        knowns: *const fmi3ValueReference,
        nKnowns: usize,
        seed: *const fmi3Float64,
        nSeed: usize,
        sensitivity: *mut fmi3Float64,
        nSensitivity: usize
    ) => "adjoint derivatives are not supported (providesAdjointDerivatives=\"false\")";
    fmi3GetOutputDerivatives(
        valueReferences: *const fmi3ValueReference,
        nValueReferences: usize,
        orders: *const fmi3Int32,
        values: *mut fmi3Float64,
        nValues: usize
    ) => "output derivatives are not supported (maxOutputDerivativeOrder=\"0\")";
    fmi3GetIntervalDecimal(
        valueReferences: *const fmi3ValueReference,
        nValueReferences: usize,
        intervals: *mut fmi3Float64,
        qualifiers: *mut fmi3IntervalQualifier
    ) => "this FMU has no clocks";
    fmi3GetIntervalFraction(
        valueReferences: *const fmi3ValueReference,
        nValueReferences: usize,
        counters: *mut fmi3UInt64,
        resolutions: *mut fmi3UInt64,
        qualifiers: *mut fmi3IntervalQualifier
    ) => "this FMU has no clocks";
    fmi3GetShiftDecimal(
        valueReferences: *const fmi3ValueReference,
        nValueReferences: usize,
        shifts: *mut fmi3Float64
    ) => "this FMU has no clocks";
    fmi3GetShiftFraction(
        valueReferences: *const fmi3ValueReference,
        nValueReferences: usize,
        counters: *mut fmi3UInt64,
        resolutions: *mut fmi3UInt64
    ) => "this FMU has no clocks";
    fmi3SetIntervalDecimal(
        valueReferences: *const fmi3ValueReference,
        nValueReferences: usize,
        intervals: *const fmi3Float64
    ) => "this FMU has no clocks";
    fmi3SetIntervalFraction(
        valueReferences: *const fmi3ValueReference,
        nValueReferences: usize,
        counters: *const fmi3UInt64,
        resolutions: *const fmi3UInt64
    ) => "this FMU has no clocks";
    fmi3SetShiftDecimal(
        valueReferences: *const fmi3ValueReference,
        nValueReferences: usize,
        shifts: *const fmi3Float64
    ) => "this FMU has no clocks";
    fmi3SetShiftFraction(
        valueReferences: *const fmi3ValueReference,
        nValueReferences: usize,
        counters: *const fmi3UInt64,
        resolutions: *const fmi3UInt64
    ) => "this FMU has no clocks";
    fmi3ActivateModelPartition(
        clockReference: fmi3ValueReference,
        activationTime: fmi3Float64
    ) => "Scheduled Execution is not supported";
    fmi3EnterContinuousTimeMode() => "Model Exchange is not supported (Co-Simulation only)";
    fmi3CompletedIntegratorStep(
        noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
        enterEventMode: *mut fmi3Boolean,
        terminateSimulation: *mut fmi3Boolean
    ) => "Model Exchange is not supported (Co-Simulation only)";
    fmi3SetTime(time: fmi3Float64) => "Model Exchange is not supported (Co-Simulation only)";
    fmi3SetContinuousStates(
        continuousStates: *const fmi3Float64,
        nContinuousStates: usize
    ) => "Model Exchange is not supported (Co-Simulation only)";
    fmi3GetContinuousStateDerivatives(
        derivatives: *mut fmi3Float64,
        nContinuousStates: usize
    ) => "Model Exchange is not supported (Co-Simulation only)";
    fmi3GetEventIndicators(
        eventIndicators: *mut fmi3Float64,
        nEventIndicators: usize
    ) => "Model Exchange is not supported (Co-Simulation only)";
    fmi3GetContinuousStates(
        continuousStates: *mut fmi3Float64,
        nContinuousStates: usize
    ) => "Model Exchange is not supported (Co-Simulation only)";
    fmi3GetNominalsOfContinuousStates(
        nominals: *mut fmi3Float64,
        nContinuousStates: usize
    ) => "Model Exchange is not supported (Co-Simulation only)";
    fmi3GetNumberOfEventIndicators(
        nEventIndicators: *mut usize
    ) => "Model Exchange is not supported (Co-Simulation only)";
    fmi3GetNumberOfContinuousStates(
        nContinuousStates: *mut usize
    ) => "Model Exchange is not supported (Co-Simulation only)";
}

/// Logs why an interface is refused at instantiation (through the host's logger, if any).
unsafe fn refuse_instantiation(
    func: &str,
    instance_name: fmi3String,
    env: fmi3InstanceEnvironment,
    log_message: Option<fmi3LogMessageCallback>,
    why: &str,
) -> fmi3Instance {
    let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let name = string(instance_name).unwrap_or_default();
        let log = Logger::new(log_message.map(Callback::Fmi3), env, &name, false);
        log.error(&format!("{func}: {why}"));
    }));
    std::ptr::null_mut()
}

#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateModelExchange(
    instanceName: fmi3String,
    _instantiationToken: fmi3String,
    _resourcePath: fmi3String,
    _visible: fmi3Boolean,
    _loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: Option<fmi3LogMessageCallback>,
) -> fmi3Instance {
    refuse_instantiation(
        "fmi3InstantiateModelExchange",
        instanceName,
        instanceEnvironment,
        logMessage,
        "this FMU supports Co-Simulation only (use fmi3InstantiateCoSimulation)",
    )
}

#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
    instanceName: fmi3String,
    _instantiationToken: fmi3String,
    _resourcePath: fmi3String,
    _visible: fmi3Boolean,
    _loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: Option<fmi3LogMessageCallback>,
    _clockUpdate: Option<fmi3ClockUpdateCallback>,
    _lockPreemption: Option<fmi3LockPreemptionCallback>,
    _unlockPreemption: Option<fmi3UnlockPreemptionCallback>,
) -> fmi3Instance {
    refuse_instantiation(
        "fmi3InstantiateScheduledExecution",
        instanceName,
        instanceEnvironment,
        logMessage,
        "this FMU supports Co-Simulation only (use fmi3InstantiateCoSimulation)",
    )
}
