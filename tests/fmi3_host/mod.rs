//! A host for the FMI 3.0 API tests: instances with their own message log (the FMI 3.0 logger is
//! an ordinary C function: no variadic arguments), called the way a host calls them, straight
//! from Rust. The scenes' resources come from the FMI 2.0 host (`fmi_host::resources`).
#![allow(dead_code)]

use crate::fmi_host;

use georod::fmi::api3::*;
use georod::fmi::types3::*;
use georod::packaging::variables3::Layout3;
use std::cell::RefCell;
use std::ffi::{c_void, CString};
use std::os::raw::c_char;

#[derive(Clone, Debug)]
pub struct Msg3 {
    pub status: fmi3Status,
    pub category: String,
    pub text: String,
}

pub type Log3 = RefCell<Vec<Msg3>>;

pub extern "C" fn capture3(
    env: *mut c_void,
    status: fmi3Status,
    category: *const c_char,
    message: *const c_char,
) {
    let msg = unsafe {
        Msg3 {
            status,
            category: fmi_host::text(category),
            text: fmi_host::text(message),
        }
    };
    if !env.is_null() {
        unsafe { &*(env as *const Log3) }.borrow_mut().push(msg);
    }
}

/// The native resource folder of a scene (FMI 3.0 passes a path, not a URI) and its token.
pub fn resources3(scene: &str) -> (CString, CString) {
    let (guid, uri) = fmi_host::resources(scene);
    let uri = uri.to_str().unwrap();
    let path = uri.strip_prefix("file://").unwrap().replace("%20", " ");
    (guid, CString::new(format!("{path}/")).unwrap())
}

/// The FMI 3.0 variables of a scene.
pub fn layout(scene: &str) -> (Vec<georod::scene::variables::Variable>, Layout3) {
    let (_, path) = fmi_host::scene_files()
        .into_iter()
        .find(|(name, _)| name == scene)
        .unwrap();
    let vars = georod::scene::variables::variables(&georod::scene::Scene::load(&path).unwrap());
    let layout = Layout3::new(&vars);
    (vars, layout)
}

pub fn instantiate(name: &str, token: &CString, path: &CString, log: &Log3) -> fmi3Instance {
    let name = CString::new(name).unwrap();
    unsafe {
        fmi3InstantiateCoSimulation(
            name.as_ptr(),
            token.as_ptr(),
            path.as_ptr(),
            fmi3False,
            fmi3False,
            fmi3False,
            fmi3False,
            std::ptr::null(),
            0,
            log as *const Log3 as *mut c_void,
            Some(capture3),
            None,
        )
    }
}

/// One FMI 3.0 instance with its own message log.
pub struct Fmu3 {
    pub c: fmi3Instance,
    pub log: Box<Log3>,
}

impl Fmu3 {
    pub fn new(scene: &str) -> Fmu3 {
        let log: Box<Log3> = Box::default();
        let (token, path) = resources3(scene);
        let c = instantiate("inst3", &token, &path, &log);
        assert!(!c.is_null(), "instantiate failed: {:?}", log.borrow());
        Fmu3 { c, log }
    }

    pub fn messages(&self) -> Vec<Msg3> {
        self.log.borrow().clone()
    }

    pub fn init(&self) {
        unsafe {
            assert_eq!(
                fmi3EnterInitializationMode(self.c, fmi3False, 0.0, 0.0, fmi3False, 0.0),
                fmi3Status::OK
            );
            assert_eq!(
                fmi3ExitInitializationMode(self.c),
                fmi3Status::OK,
                "{:?}",
                self.messages()
            );
        }
    }

    /// `nValues` values of `vrs` (scalars and whole arrays).
    pub fn floats(&self, vrs: &[u32], n_values: usize) -> Vec<f64> {
        let mut v = vec![f64::NAN; n_values];
        let s =
            unsafe { fmi3GetFloat64(self.c, vrs.as_ptr(), vrs.len(), v.as_mut_ptr(), n_values) };
        assert_eq!(s, fmi3Status::OK, "{:?}", self.messages());
        v
    }

    /// Steps once; returns (status, lastSuccessfulTime, [eventHandlingNeeded,
    /// terminateSimulation, earlyReturn]).
    pub fn step(&self, t: f64, h: f64) -> (fmi3Status, f64, [u8; 3]) {
        let (mut event, mut terminate, mut early, mut last) = (7u8, 7u8, 7u8, f64::NAN);
        let s = unsafe {
            fmi3DoStep(
                self.c,
                t,
                h,
                fmi3True,
                &mut event,
                &mut terminate,
                &mut early,
                &mut last,
            )
        };
        (s, last, [event, terminate, early])
    }

    /// Fails the test unless the last call was refused with a message containing every `part`.
    pub fn expect_error(&self, status: fmi3Status, parts: &[&str]) {
        assert_eq!(status, fmi3Status::Error, "messages: {:?}", self.messages());
        let msg = self
            .log
            .borrow()
            .last()
            .cloned()
            .expect("an error is always logged");
        assert_eq!(
            (msg.status, msg.category.as_str()),
            (fmi3Status::Error, "logStatusError")
        );
        for part in parts {
            assert!(
                msg.text.contains(part),
                "`{}` does not contain `{part}`",
                msg.text
            );
        }
    }
}

impl Drop for Fmu3 {
    fn drop(&mut self) {
        unsafe { fmi3FreeInstance(self.c) };
    }
}

/// The energies and the shape arrays of the beam, as bits (for exact comparisons).
pub fn bits(fmu: &Fmu3) -> Vec<u64> {
    let (_, layout) = layout(fmi_host::BEAM);
    let vrs: Vec<u32> = layout
        .variables
        .iter()
        .filter(|v| v.name.starts_with('E') || v.array)
        .map(|v| v.vr)
        .collect();
    let n = vrs.iter().map(|&vr| layout.by_vr(vr).unwrap().len).sum();
    fmu.floats(&vrs, n).iter().map(|x| x.to_bits()).collect()
}

/// Steps `n` times from `from`; returns the time reached.
pub fn run(fmu: &Fmu3, from: f64, n: usize) -> f64 {
    let mut t = from;
    for _ in 0..n {
        let (s, last, _) = fmu.step(t, 1e-4);
        assert_eq!(s, fmi3Status::OK, "{:?}", fmu.messages());
        t = last;
    }
    t
}
