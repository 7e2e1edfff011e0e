//! The platform libraries an FMU carries (`binaries/<platform>/<model><suffix>`), each checked
//! before it is packed: the object format and architecture of its platform, a shared library,
//! and every FMI 2.0 Co-Simulation function exported. A library built elsewhere (a darwin64 one
//! from a Mac) goes through the same checks as the ones built here.
use object::read::macho::{FatArch, MachOFatFile32, MachOFatFile64};
use object::{Architecture, BinaryFormat, FileKind, Object, ObjectKind};
use std::fmt;

/// The platforms an FMU can carry a library for (FMI 2.0 folder names).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Platform {
    Linux64,
    Win64,
    Darwin64,
}

impl Platform {
    pub const ALL: [Platform; 3] = [Platform::Linux64, Platform::Win64, Platform::Darwin64];

    /// The folder under `binaries/`.
    pub fn folder(self) -> &'static str {
        match self {
            Platform::Linux64 => "linux64",
            Platform::Win64 => "win64",
            Platform::Darwin64 => "darwin64",
        }
    }

    /// The folder under `binaries/` in an FMI 3.0 FMU (its platform tuple). A darwin64 library
    /// goes under `x86_64-darwin`; FMI 3.0 names Apple silicon `aarch64-darwin`, which an
    /// arm64 or universal library would also fit: not packed there yet.
    pub fn fmi3_folder(self) -> &'static str {
        match self {
            Platform::Linux64 => "x86_64-linux",
            Platform::Win64 => "x86_64-windows",
            Platform::Darwin64 => "x86_64-darwin",
        }
    }

    /// The file name ending of a shared library on this platform.
    pub fn suffix(self) -> &'static str {
        match self {
            Platform::Linux64 => ".so",
            Platform::Win64 => ".dll",
            Platform::Darwin64 => ".dylib",
        }
    }

    pub fn from_folder(name: &str) -> Result<Platform, String> {
        Platform::ALL
            .into_iter()
            .find(|p| p.folder() == name)
            .ok_or_else(|| format!("unknown platform `{name}`: use linux64, win64 or darwin64"))
    }

    /// Where scripts/build_libs (which scripts/build_fmus runs) leaves this platform's library,
    /// under the cargo target folder.
    pub fn built_path(self) -> Option<&'static str> {
        match self {
            Platform::Linux64 => Some("libs/libgeorod.so"),
            Platform::Win64 => Some("libs/georod.dll"),
            Platform::Darwin64 => None,
        }
    }

    /// How to get this platform's library, for the message that it is missing.
    pub fn how_to_build(self) -> &'static str {
        match self {
            Platform::Linux64 => {
                "scripts/build_fmus builds it for glibc 2.17 with cargo-zigbuild and ziglang \
                 (PyPI, pinned in python/requirements.txt, installed by scripts/bootstrap)"
            }
            Platform::Win64 => {
                "scripts/build_fmus builds it with Debian's rustc-web, cargo-web, rust-web-src and \
                 gcc-mingw-w64-x86-64 (scripts/install_platform_deps installs them)"
            }
            Platform::Darwin64 => {
                "build it on a Mac (cargo build --release --lib) and add it with \
                 --binary darwin64=libgeorod.dylib (docs/platforms.md)"
            }
        }
    }

    /// What this platform's library must be, for messages.
    fn expected(self) -> &'static str {
        match self {
            Platform::Linux64 => "an ELF shared library for x86_64",
            Platform::Win64 => "a PE32+ DLL for x86_64",
            Platform::Darwin64 => {
                "a Mach-O dynamic library for x86_64 or arm64 (or a universal one)"
            }
        }
    }
}

impl fmt::Display for Platform {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.folder())
    }
}

/// The FMI 2.0 functions a Co-Simulation FMU's library exports (FMI 2.0.x standard, 2.1 and 4.1).
pub const FMI2_FUNCTIONS: [&str; 34] = [
    "fmi2GetTypesPlatform",
    "fmi2GetVersion",
    "fmi2SetDebugLogging",
    "fmi2Instantiate",
    "fmi2FreeInstance",
    "fmi2SetupExperiment",
    "fmi2EnterInitializationMode",
    "fmi2ExitInitializationMode",
    "fmi2Terminate",
    "fmi2Reset",
    "fmi2GetReal",
    "fmi2GetInteger",
    "fmi2GetBoolean",
    "fmi2GetString",
    "fmi2SetReal",
    "fmi2SetInteger",
    "fmi2SetBoolean",
    "fmi2SetString",
    "fmi2GetFMUstate",
    "fmi2SetFMUstate",
    "fmi2FreeFMUstate",
    "fmi2SerializedFMUstateSize",
    "fmi2SerializeFMUstate",
    "fmi2DeSerializeFMUstate",
    "fmi2GetDirectionalDerivative",
    "fmi2SetRealInputDerivatives",
    "fmi2GetRealOutputDerivatives",
    "fmi2DoStep",
    "fmi2CancelStep",
    "fmi2GetStatus",
    "fmi2GetRealStatus",
    "fmi2GetIntegerStatus",
    "fmi2GetBooleanStatus",
    "fmi2GetStringStatus",
];

/// Every function of the FMI 3.0 standard (`fmi3FunctionTypes.h`), which the library exports
/// (those a co-simulation FMU need not support answer `fmi3Error`).
pub const FMI3_FUNCTIONS: [&str; 75] = [
    "fmi3GetVersion",
    "fmi3SetDebugLogging",
    "fmi3InstantiateModelExchange",
    "fmi3InstantiateCoSimulation",
    "fmi3InstantiateScheduledExecution",
    "fmi3FreeInstance",
    "fmi3EnterInitializationMode",
    "fmi3ExitInitializationMode",
    "fmi3EnterEventMode",
    "fmi3Terminate",
    "fmi3Reset",
    "fmi3GetFloat32",
    "fmi3GetFloat64",
    "fmi3GetInt8",
    "fmi3GetUInt8",
    "fmi3GetInt16",
    "fmi3GetUInt16",
    "fmi3GetInt32",
    "fmi3GetUInt32",
    "fmi3GetInt64",
    "fmi3GetUInt64",
    "fmi3GetBoolean",
    "fmi3GetString",
    "fmi3GetBinary",
    "fmi3GetClock",
    "fmi3SetFloat32",
    "fmi3SetFloat64",
    "fmi3SetInt8",
    "fmi3SetUInt8",
    "fmi3SetInt16",
    "fmi3SetUInt16",
    "fmi3SetInt32",
    "fmi3SetUInt32",
    "fmi3SetInt64",
    "fmi3SetUInt64",
    "fmi3SetBoolean",
    "fmi3SetString",
    "fmi3SetBinary",
    "fmi3SetClock",
    "fmi3GetNumberOfVariableDependencies",
    "fmi3GetVariableDependencies",
    "fmi3GetFMUState",
    "fmi3SetFMUState",
    "fmi3FreeFMUState",
    "fmi3SerializedFMUStateSize",
    "fmi3SerializeFMUState",
    "fmi3DeserializeFMUState",
    "fmi3GetDirectionalDerivative",
    "fmi3GetAdjointDerivative",
    "fmi3EnterConfigurationMode",
    "fmi3ExitConfigurationMode",
    "fmi3GetIntervalDecimal",
    "fmi3GetIntervalFraction",
    "fmi3GetShiftDecimal",
    "fmi3GetShiftFraction",
    "fmi3SetIntervalDecimal",
    "fmi3SetIntervalFraction",
    "fmi3SetShiftDecimal",
    "fmi3SetShiftFraction",
    "fmi3EvaluateDiscreteStates",
    "fmi3UpdateDiscreteStates",
    "fmi3EnterContinuousTimeMode",
    "fmi3CompletedIntegratorStep",
    "fmi3SetTime",
    "fmi3SetContinuousStates",
    "fmi3GetContinuousStateDerivatives",
    "fmi3GetEventIndicators",
    "fmi3GetContinuousStates",
    "fmi3GetNominalsOfContinuousStates",
    "fmi3GetNumberOfEventIndicators",
    "fmi3GetNumberOfContinuousStates",
    "fmi3EnterStepMode",
    "fmi3GetOutputDerivatives",
    "fmi3DoStep",
    "fmi3ActivateModelPartition",
];

/// The FMI versions a library serves, by the functions it must export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Api {
    Fmi2,
    Fmi3,
}

impl Api {
    fn functions(self) -> &'static [&'static str] {
        match self {
            Api::Fmi2 => &FMI2_FUNCTIONS,
            Api::Fmi3 => &FMI3_FUNCTIONS,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Api::Fmi2 => "FMI 2.0",
            Api::Fmi3 => "FMI 3.0",
        }
    }
}

/// Checks that `lib` is a shared library of `platform` exporting every function of `api`.
pub fn check_library(platform: Platform, lib: &[u8], api: Api) -> Result<(), String> {
    let wrong = |found: String| {
        format!(
            "not a {platform} library: expected {}, found {found}",
            platform.expected()
        )
    };
    let kind = FileKind::parse(lib).map_err(|_| wrong("no known object format".to_string()))?;
    if platform == Platform::Darwin64 && kind == FileKind::MachOFat32 {
        // A universal library: every slice must pass.
        let fat = MachOFatFile32::parse(lib).map_err(|e| wrong(e.to_string()))?;
        for arch in fat.arches() {
            check_library(
                platform,
                arch.data(lib).map_err(|e| wrong(e.to_string()))?,
                api,
            )?;
        }
        return Ok(());
    }
    if platform == Platform::Darwin64 && kind == FileKind::MachOFat64 {
        let fat = MachOFatFile64::parse(lib).map_err(|e| wrong(e.to_string()))?;
        for arch in fat.arches() {
            check_library(
                platform,
                arch.data(lib).map_err(|e| wrong(e.to_string()))?,
                api,
            )?;
        }
        return Ok(());
    }
    let file = object::File::parse(lib).map_err(|e| wrong(e.to_string()))?;
    let (format, arch) = (file.format(), file.architecture());
    let fits = match platform {
        Platform::Linux64 => format == BinaryFormat::Elf && arch == Architecture::X86_64,
        Platform::Win64 => format == BinaryFormat::Pe && arch == Architecture::X86_64,
        Platform::Darwin64 => {
            format == BinaryFormat::MachO
                && matches!(arch, Architecture::X86_64 | Architecture::Aarch64)
        }
    };
    if !fits {
        return Err(wrong(format!("{format:?} for {arch:?}")));
    }
    if file.kind() != ObjectKind::Dynamic {
        return Err(wrong(format!(
            "a {format:?} file of kind {:?}, not a shared library",
            file.kind()
        )));
    }
    let exports = file.exports().map_err(|e| wrong(e.to_string()))?;
    let names: Vec<&[u8]> = exports
        .iter()
        .map(|e| {
            let name = e.name();
            // Mach-O symbols carry the C compiler's leading underscore.
            match platform {
                Platform::Darwin64 => name.strip_prefix(b"_").unwrap_or(name),
                _ => name,
            }
        })
        .collect();
    let missing: Vec<&str> = (api.functions().iter())
        .filter(|f| !names.contains(&f.as_bytes()))
        .copied()
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "the {platform} library does not export {} of the {} functions: {}",
            missing.len(),
            api.name(),
            missing.join(", ")
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn platform_names() {
        for p in Platform::ALL {
            assert_eq!(Platform::from_folder(p.folder()), Ok(p));
        }
        let e = Platform::from_folder("win32").unwrap_err();
        assert!(e.contains("unknown platform `win32`"), "{e}");
    }

    #[test]
    fn not_an_object_file_is_refused() {
        let e = check_library(Platform::Win64, b"[geometry]\nshape = 1\n", Api::Fmi2).unwrap_err();
        assert_eq!(
            e,
            "not a win64 library: expected a PE32+ DLL for x86_64, found no known object format"
        );
    }

    #[cfg(all(target_os = "linux", target_arch = "x86_64"))]
    #[test]
    fn an_elf_without_fmi_functions_or_of_another_platform_is_refused() {
        // This test executable: an x86_64 ELF that exports no FMI function.
        let me = std::fs::read(std::env::current_exe().unwrap()).unwrap();
        let e = check_library(Platform::Linux64, &me, Api::Fmi2).unwrap_err();
        assert!(
            e.contains("not a shared library") || e.contains("does not export 34 of"),
            "{e}"
        );
        let e = check_library(Platform::Darwin64, &me, Api::Fmi2).unwrap_err();
        assert!(
            e.starts_with("not a darwin64 library: expected a Mach-O"),
            "{e}"
        );
    }
}
