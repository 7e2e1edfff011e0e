//! A host for the FMI API tests: instances with their own message log, called the way a host calls
//! them (raw pointers, C strings, a logger callback), straight from Rust.
//!
//! The logger: `fmi2CallbackLogger` is C-variadic, and stable Rust cannot *define* a variadic
//! function. The FMU always calls it with exactly one variadic argument, a `char*`, as
//! `logger(env, name, status, category, "%s", text)`. The test logger is therefore an ordinary
//! six-argument `extern "C" fn` transmuted to the variadic pointer type. On x86_64 System V (and
//! Windows x64, and AArch64 Linux) a variadic call passes its integer/pointer arguments exactly
//! like a non-variadic call with the same argument types (the first six in rdi, rsi, rdx, rcx,
//! r8, r9; `al` holds the number of vector registers used, which a non-variadic callee ignores),
//! so the callee receives the six arguments correctly. Apple AArch64 passes variadic arguments on
//! the stack, hence the `cfg` on the test files that use this module.
#![allow(dead_code, non_upper_case_globals)]

use georod::fmi::api::*;
use georod::fmi::types::*;
use std::cell::RefCell;
use std::ffi::{c_void, CStr, CString};
use std::os::raw::c_char;
use std::sync::OnceLock;

pub const BEAM: &str = "BuckledBeam";
pub const PINNED: &str = "PinnedArch";
/// The paper's scenes, whose variables `vr` lists.
pub const PAPER_SCENES: [&str; 3] = ["BuckledBeam", "PinnedArch", "ClampedArch"];

/// Every scene file the FMUs are made from (scenes/*.toml, examples/*.toml): (name, path).
pub fn scene_files() -> Vec<(String, std::path::PathBuf)> {
    let mut files = Vec::new();
    for dir in ["scenes", "examples"] {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                let name = path.file_stem().unwrap().to_str().unwrap().to_string();
                files.push((name, path));
            }
        }
    }
    files.sort();
    files
}

/// Value references of the paper scenes' variables (checked against the scene files by
/// `value_references_match_the_scene_files`).
pub mod vr {
    pub const E: u32 = 0;
    pub const nu: u32 = 1;
    pub const d: u32 = 3;
    pub const L: u32 = 6;
    pub const elements: u32 = 7;
    pub const dt_max: u32 = 8;
    pub const F: u32 = 9;
    pub const Omega: u32 = 10;
    pub const well: u32 = 12;
    pub const H: u32 = 13;
    pub const pre_shortening: u32 = 100;
    pub const f_ctrl: u32 = 1000;
    pub const E_kin: u32 = 32;
    pub const E_strain: u32 = 33;
    pub const newton_iterations: u32 = 34;
    pub const W_ext: u32 = 35;
    pub const W_ctrl: u32 = 36;
    pub const E_damped: u32 = 37;
    pub const energy_error: u32 = 38;
    pub const w_mid: u32 = 2000;
    pub const v_mid: u32 = 2001;
}

/// The unzipped resources of a scene's FMU (the scene file as `scene.toml`) and its GUID:
/// `(guid, file: URI of the folder)`, made once per test process for every scene file.
pub fn resources(scene: &str) -> (CString, CString) {
    static MADE: OnceLock<Vec<(String, String, String)>> = OnceLock::new();
    let made = MADE.get_or_init(|| {
        let root = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join(format!("georod fmi_api {}", std::process::id()));
        scene_files()
            .into_iter()
            .map(|(name, source)| {
                let dir = root.join(&name).join("resources");
                std::fs::create_dir_all(&dir).unwrap();
                let scene = georod::scene::Scene::load(&source).unwrap();
                std::fs::write(dir.join("scene.toml"), &scene.source).unwrap();
                let guid = georod::packaging::model_description::model_description(&scene).guid;
                let uri = format!("file://{}", dir.display()).replace(' ', "%20");
                (name, guid, uri)
            })
            .collect()
    });
    let (_, guid, uri) = made
        .iter()
        .find(|(name, ..)| name == scene)
        .unwrap_or_else(|| panic!("no scene file for {scene}"));
    (
        CString::new(guid.as_str()).unwrap(),
        CString::new(uri.as_str()).unwrap(),
    )
}

#[derive(Clone, Debug)]
pub struct Msg {
    pub env: usize,
    pub name: String,
    pub status: fmi2Status,
    pub category: String,
    pub format: String,
    pub text: String,
}

pub type Log = RefCell<Vec<Msg>>;

thread_local! {
    /// Messages sent with a NULL componentEnvironment.
    pub static NULL_ENV_LOG: Log = const { RefCell::new(Vec::new()) };
}

pub unsafe fn text(p: *const c_char) -> String {
    if p.is_null() {
        "<NULL>".to_string()
    } else {
        CStr::from_ptr(p).to_string_lossy().into_owned()
    }
}

pub extern "C" fn capture(
    env: *mut c_void,
    name: *const c_char,
    status: fmi2Status,
    category: *const c_char,
    format: *const c_char,
    arg: *const c_char,
) {
    let msg = unsafe {
        Msg {
            env: env as usize,
            name: text(name),
            status,
            category: text(category),
            format: text(format),
            text: text(arg),
        }
    };
    if env.is_null() {
        NULL_ENV_LOG.with(|l| l.borrow_mut().push(msg));
    } else {
        unsafe { &*(env as *const Log) }.borrow_mut().push(msg);
    }
}

pub type Capture = extern "C" fn(
    *mut c_void,
    *const c_char,
    fmi2Status,
    *const c_char,
    *const c_char,
    *const c_char,
);

pub fn logger() -> fmi2CallbackLogger {
    // SAFETY: see the module documentation (fixed "%s" call shape).
    unsafe { std::mem::transmute::<Capture, fmi2CallbackLogger>(capture) }
}

pub fn callbacks(env: *mut c_void) -> Box<fmi2CallbackFunctions> {
    Box::new(fmi2CallbackFunctions {
        logger: Some(logger()),
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: env,
    })
}

/// One instance with its own message log (passed as componentEnvironment).
pub struct Fmu {
    pub c: fmi2Component,
    pub log: Box<Log>,
    pub _callbacks: Box<fmi2CallbackFunctions>,
}

impl Fmu {
    pub fn new(scene: &str) -> Fmu {
        Fmu::with(scene, "inst", false)
    }

    pub fn with(scene: &str, name: &str, logging_on: bool) -> Fmu {
        let log: Box<Log> = Box::default();
        let cb = callbacks(&*log as *const Log as *mut c_void);
        let name = CString::new(name).unwrap();
        let (guid, uri) = resources(scene);
        let c = unsafe {
            fmi2Instantiate(
                name.as_ptr(),
                fmi2CoSimulation,
                guid.as_ptr(),
                uri.as_ptr(),
                &*cb,
                fmi2False,
                logging_on as fmi2Boolean,
            )
        };
        assert!(!c.is_null(), "instantiate failed: {:?}", log.borrow());
        Fmu {
            c,
            log,
            _callbacks: cb,
        }
    }

    pub fn messages(&self) -> Vec<Msg> {
        self.log.borrow().clone()
    }

    pub fn clear(&self) {
        self.log.borrow_mut().clear();
    }

    pub fn init(&self) {
        unsafe {
            assert_eq!(
                fmi2SetupExperiment(self.c, fmi2False, 0.0, 0.0, fmi2False, 0.0),
                fmi2Status::OK
            );
            assert_eq!(fmi2EnterInitializationMode(self.c), fmi2Status::OK);
            assert_eq!(
                fmi2ExitInitializationMode(self.c),
                fmi2Status::OK,
                "{:?}",
                self.messages()
            );
        }
    }

    pub fn reals(&self, vrs: &[u32]) -> Vec<f64> {
        let mut v = vec![f64::NAN; vrs.len()];
        let s = unsafe { fmi2GetReal(self.c, vrs.as_ptr(), vrs.len(), v.as_mut_ptr()) };
        assert_eq!(s, fmi2Status::OK, "{:?}", self.messages());
        v
    }

    pub fn real(&self, vr: u32) -> f64 {
        self.reals(&[vr])[0]
    }

    pub fn integer(&self, vr: u32) -> i32 {
        let mut v = -99;
        let s = unsafe { fmi2GetInteger(self.c, &vr, 1, &mut v) };
        assert_eq!(s, fmi2Status::OK, "{:?}", self.messages());
        v
    }

    pub fn set_real(&self, vr: u32, value: f64) -> fmi2Status {
        unsafe { fmi2SetReal(self.c, &vr, 1, &value) }
    }

    pub fn set_integer(&self, vr: u32, value: i32) -> fmi2Status {
        unsafe { fmi2SetInteger(self.c, &vr, 1, &value) }
    }

    pub fn step(&self, t: f64, h: f64) -> fmi2Status {
        unsafe { fmi2DoStep(self.c, t, h, fmi2True) }
    }

    pub fn time(&self) -> f64 {
        let mut t = f64::NAN;
        assert_eq!(
            unsafe { fmi2GetRealStatus(self.c, fmi2LastSuccessfulTime, &mut t) },
            fmi2Status::OK
        );
        t
    }

    /// The outputs, bit patterns (for exact comparisons).
    pub fn outputs(&self) -> Vec<u64> {
        let mut v: Vec<u64> = self
            .reals(&[vr::w_mid, vr::v_mid, vr::E_kin, vr::E_strain])
            .iter()
            .map(|x| x.to_bits())
            .collect();
        v.push(self.integer(vr::newton_iterations) as u64);
        v
    }

    /// Fails the test unless the last call was refused with a message containing every `part`.
    pub fn expect_error(&self, status: fmi2Status, parts: &[&str]) {
        assert_eq!(status, fmi2Status::Error, "messages: {:?}", self.messages());
        let msg = self
            .log
            .borrow()
            .last()
            .cloned()
            .expect("an error is always logged");
        assert_eq!(msg.status, fmi2Status::Error);
        assert_eq!(msg.category, "logStatusError");
        for part in parts {
            assert!(
                msg.text.contains(part),
                "`{}` does not contain `{part}`",
                msg.text
            );
        }
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        unsafe { fmi2FreeInstance(self.c) };
    }
}

pub const H: f64 = 1e-4;

/// Steps `n` times from the current time; returns the outputs after each step.
pub fn run(fmu: &Fmu, n: usize) -> Vec<Vec<u64>> {
    (0..n)
        .map(|_| {
            let t = fmu.time();
            assert_eq!(fmu.step(t, H), fmi2Status::OK, "{:?}", fmu.messages());
            fmu.outputs()
        })
        .collect()
}

// ----- FMU states ----------------------------------------------------------------------------

/// A new FMU state of the instance (fmi2GetFMUstate into a NULL slot).
pub fn get_state(fmu: &Fmu) -> fmi2FMUstate {
    let mut s: fmi2FMUstate = std::ptr::null_mut();
    assert_eq!(unsafe { fmi2GetFMUstate(fmu.c, &mut s) }, fmi2Status::OK);
    s
}

/// The serialized bytes of state `s`.
pub fn serialize(fmu: &Fmu, s: fmi2FMUstate) -> Vec<fmi2Byte> {
    let mut size = 0;
    let mut bytes = unsafe {
        assert_eq!(
            fmi2SerializedFMUstateSize(fmu.c, s, &mut size),
            fmi2Status::OK
        );
        vec![0 as fmi2Byte; size]
    };
    let status = unsafe { fmi2SerializeFMUstate(fmu.c, s, bytes.as_mut_ptr(), size) };
    assert_eq!(status, fmi2Status::OK, "{:?}", fmu.messages());
    bytes
}

/// Deserializes into a slot that holds `slot` on entry; returns the status and the slot after.
pub fn deserialize(
    fmu: &Fmu,
    bytes: &[fmi2Byte],
    slot: fmi2FMUstate,
) -> (fmi2Status, fmi2FMUstate) {
    let mut out = slot;
    let status = unsafe { fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr(), bytes.len(), &mut out) };
    (status, out)
}

/// Asserts the instance steps on exactly like its twin (both advance one step).
pub fn same_as_twin(fmu: &Fmu, twin: &Fmu) {
    assert_eq!(fmu.time(), twin.time());
    assert_eq!(run(fmu, 1), run(twin, 1), "{:?}", fmu.messages());
}

/// Every function that takes a state refuses `h` with a message containing `part`.
pub fn refused_everywhere(fmu: &Fmu, h: fmi2FMUstate, part: &str) {
    let mut size = 0usize;
    let mut buf = [0 as fmi2Byte; 16];
    let mut slot = h;
    unsafe {
        fmu.expect_error(
            fmi2SetFMUstate(fmu.c, h),
            &["fmi2SetFMUstate: FMUstate", part],
        );
        fmu.expect_error(
            fmi2FreeFMUstate(fmu.c, &mut slot),
            &["fmi2FreeFMUstate", part],
        );
        assert_eq!(slot, h, "a refused free leaves the host's handle alone");
        fmu.expect_error(fmi2SerializedFMUstateSize(fmu.c, h, &mut size), &[part]);
        fmu.expect_error(
            fmi2SerializeFMUstate(fmu.c, h, buf.as_mut_ptr(), 16),
            &[part],
        );
    }
    assert_eq!(size, 0);
    assert!(buf.iter().all(|&b| b == 0));
}
