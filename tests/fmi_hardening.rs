//! The FMU against a hostile host, through the C API: corrupt and crafted serialized states,
//! the output-only `*FMUstate` of fmi2DeSerializeFMUstate, freed / foreign / garbage state
//! handles, states the host never frees, and stopTime. After every refusal the instance must
//! still work exactly like an untouched twin.
#![cfg(any(
    target_arch = "x86_64",
    all(target_arch = "aarch64", not(target_vendor = "apple"))
))]

mod fmi_host;

use fmi_host::*;
use georod::fmi::api::*;
use georod::fmi::fmu_state::{self, StateData};
use georod::fmi::instance::Instance;
use georod::fmi::types::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::ptr::null_mut;

// ----- helpers --------------------------------------------------------------------------------

/// An initialized BuckledBeam instance after 3 steps under load.
fn running() -> Fmu {
    let fmu = Fmu::new(BEAM);
    assert_eq!(fmu.set_real(vr::F, 0.9), fmi2Status::OK);
    fmu.init();
    run(&fmu, 3);
    fmu
}

fn as_bytes(b: &[fmi2Byte]) -> Vec<u8> {
    b.iter().map(|&x| x as u8).collect()
}

fn as_c(b: &[u8]) -> Vec<fmi2Byte> {
    b.iter().map(|&x| x as fmi2Byte).collect()
}

fn instance(fmu: &Fmu) -> &Instance {
    unsafe { Instance::from_raw(fmu.c) }.expect("a live instance")
}

/// The instance's state as Rust data (to craft states a checksum cannot catch).
fn state_data(fmu: &Fmu) -> StateData {
    instance(fmu).get_fmu_state().expect("a state")
}

/// The bytes of `data` as this instance's FMU writes them (scene and GUID).
fn serialize_data(fmu: &Fmu, data: &StateData) -> Vec<u8> {
    let inst = instance(fmu);
    fmu_state::serialize(data, inst.scene(), &inst.interface().guid).unwrap()
}

// ----- serialized states ----------------------------------------------------------------------

#[test]
fn every_single_byte_corruption_is_refused() {
    let (fmu, twin) = (running(), running());
    let keep = get_state(&fmu);
    let good = as_bytes(&serialize(&fmu, keep));
    for at in 0..good.len() {
        for mask in [0x01u8, 0x80, 0xff] {
            let mut bad = good.clone();
            bad[at] ^= mask;
            fmu.clear();
            let (status, out) = deserialize(&fmu, &as_c(&bad), keep);
            assert_eq!(status, fmi2Status::Error, "byte {at} ^ {mask:#x} accepted");
            assert_eq!(out, keep, "the slot is written only on success");
            let msg = fmu.messages().pop().expect("a refusal is logged");
            assert!(
                msg.text.starts_with("fmi2DeSerializeFMUstate: "),
                "{}",
                msg.text
            );
        }
    }
    // The kept state is intact and the instance runs on like its twin.
    assert_eq!(as_bytes(&serialize(&fmu, keep)), good);
    same_as_twin(&fmu, &twin);
}

#[test]
fn truncated_and_extended_buffers_are_refused() {
    let (fmu, twin) = (running(), running());
    let s = get_state(&fmu);
    let good = serialize(&fmu, s);
    for n in 0..good.len() {
        let (status, out) = deserialize(&fmu, &good[..n], null_mut());
        fmu.expect_error(
            status,
            &[if n < 24 {
                "too short"
            } else {
                "does not match"
            }],
        );
        assert!(out.is_null());
    }
    for extra in [1, 8, 4096] {
        let mut longer = good.clone();
        longer.extend(std::iter::repeat_n(7 as fmi2Byte, extra));
        fmu.expect_error(
            deserialize(&fmu, &longer, null_mut()).0,
            &["does not match"],
        );
    }
    same_as_twin(&fmu, &twin);
}

#[test]
fn crafted_states_with_a_valid_checksum_are_checked_field_by_field() {
    let (fmu, twin) = (running(), running());
    let base = state_data(&fmu);
    type Craft = fn(&mut StateData);
    let cases: [(Craft, &str); 11] = [
        (
            |d| d.snapshot.as_mut().unwrap().time = f64::NAN,
            "snapshot time = NaN",
        ),
        (
            |d| d.snapshot.as_mut().unwrap().clock.origin = f64::NAN,
            "clock origin = NaN",
        ),
        (
            |d| d.snapshot.as_mut().unwrap().clock.step = f64::INFINITY,
            "clock step = inf",
        ),
        (
            |d| d.snapshot.as_mut().unwrap().time += 1e-3,
            "disagrees with its clock",
        ),
        (
            |d| d.snapshot.as_mut().unwrap().velocities[4] = f64::NAN,
            "velocity 4 = NaN",
        ),
        (
            |d| d.snapshot.as_mut().unwrap().energy.dissipated = -f64::INFINITY,
            "dissipated",
        ),
        (
            |d| {
                d.snapshot
                    .as_mut()
                    .unwrap()
                    .displacements
                    .pop()
                    .map(drop)
                    .unwrap()
            },
            "length 32",
        ),
        (|d| d.experiment.start_time = f64::NAN, "startTime = NaN"),
        (|d| d.experiment.stop_time = Some(-1.0), "stopTime = -1"),
        (|d| d.inputs[0] = Some(f64::INFINITY), "f_ctrl = inf"),
        (|d| d.params.0[0] = f64::NAN, "`E`"),
    ];
    for (craft, part) in cases {
        let mut d = base.clone();
        craft(&mut d);
        let bytes = as_c(&serialize_data(&fmu, &d));
        let (status, out) = deserialize(&fmu, &bytes, null_mut());
        fmu.expect_error(status, &["fmi2DeSerializeFMUstate", part]);
        assert!(out.is_null());
    }
    // Another GUID (another build of the same scene) and an impossible vector length, re-signed.
    let good = serialize_data(&fmu, &base);
    let resign = |mut b: Vec<u8>| {
        let crc = fmu_state::checksum(&b);
        b[12..16].copy_from_slice(&crc.to_le_bytes());
        as_c(&b)
    };
    let guid_at = fmu_state::PREFIX_LEN + 8;
    let mut other_guid = good.clone();
    other_guid[guid_at + 1] ^= 1;
    let (status, _) = deserialize(&fmu, &resign(other_guid), null_mut());
    fmu.expect_error(status, &["another build", "GUID"]);
    let dofs = (base.snapshot.as_ref().unwrap().displacements.len() as u64).to_le_bytes();
    let len_at = good
        .windows(8)
        .position(|w| w == dofs)
        .expect("the vector length");
    let mut huge = good.clone();
    huge[len_at..len_at + 8].copy_from_slice(&(u64::MAX / 16).to_le_bytes());
    fmu.expect_error(deserialize(&fmu, &resign(huge), null_mut()).0, &["corrupt"]);
    // The untouched state is still accepted, and nothing changed the instance.
    let (status, mut out) = deserialize(&fmu, &as_c(&good), null_mut());
    assert_eq!(status, fmi2Status::OK, "{:?}", fmu.messages());
    unsafe { assert_eq!(fmi2FreeFMUstate(fmu.c, &mut out), fmi2Status::OK) };
    // Finite fields whose outputs are not (energy_error overflows, E_kin of v = 1e200): a
    // well-formed state, refused when set, and the instance stays as it was.
    let crafts: [Craft; 2] = [
        |d| {
            let e = &mut d.snapshot.as_mut().unwrap().energy;
            (e.initial_energy, e.external_work) = (-1.7e308, -1.7e308);
        },
        |d| d.snapshot.as_mut().unwrap().velocities[4] = 1e200,
    ];
    for (craft, part) in crafts.into_iter().zip(["energy_error", "E_kin"]) {
        let mut d = base.clone();
        craft(&mut d);
        let (status, mut s) = deserialize(&fmu, &as_c(&serialize_data(&fmu, &d)), null_mut());
        assert_eq!(status, fmi2Status::OK, "{:?}", fmu.messages());
        let set = unsafe { fmi2SetFMUstate(fmu.c, s) };
        fmu.expect_error(set, &["fmi2SetFMUstate", "non-finite", part]);
        unsafe { assert_eq!(fmi2FreeFMUstate(fmu.c, &mut s), fmi2Status::OK) };
    }
    same_as_twin(&fmu, &twin);
}

#[test]
fn deserialize_never_reads_its_output_argument() {
    let fmu = running();
    let held = get_state(&fmu);
    let bytes = serialize(&fmu, held);
    // Garbage in the slot (unmapped, misaligned): never dereferenced, overwritten.
    let (status, mut fresh) = deserialize(&fmu, &bytes, 0x13 as fmi2FMUstate);
    assert_eq!(status, fmi2Status::OK, "{:?}", fmu.messages());
    // A state the host holds in the slot: a new state, the held one stays valid and unchanged.
    let (status, mut second) = deserialize(&fmu, &bytes, held);
    assert_eq!(status, fmi2Status::OK);
    assert!(second != held && second != fresh && !fresh.is_null());
    assert_eq!(serialize(&fmu, held), bytes);
    assert_eq!(serialize(&fmu, second), bytes);
    unsafe {
        for s in [&mut fresh, &mut second] {
            assert_eq!(fmi2SetFMUstate(fmu.c, *s), fmi2Status::OK);
            assert_eq!(fmi2FreeFMUstate(fmu.c, s), fmi2Status::OK);
        }
    }
    let mut held = held;
    unsafe { assert_eq!(fmi2FreeFMUstate(fmu.c, &mut held), fmi2Status::OK) };
}

// ----- state handles --------------------------------------------------------------------------

#[test]
fn freed_foreign_and_garbage_handles_are_refused_before_use() {
    let (fmu, twin, other) = (running(), running(), running());
    let not_live = "not a live FMU state of this instance";
    // Freed: the host kept a copy of the handle; using it, or freeing it again, is refused.
    let mut s = get_state(&fmu);
    let stale = s;
    unsafe { assert_eq!(fmi2FreeFMUstate(fmu.c, &mut s), fmi2Status::OK) };
    assert!(s.is_null());
    refused_everywhere(&fmu, stale, not_live);
    // Another instance's state: refused here, untouched and usable there.
    let theirs = get_state(&other);
    let theirs_bytes = serialize(&other, theirs);
    refused_everywhere(&fmu, theirs, not_live);
    assert_eq!(serialize(&other, theirs), theirs_bytes);
    unsafe { assert_eq!(fmi2SetFMUstate(other.c, theirs), fmi2Status::OK) };
    // Garbage: a readable buffer (must stay unread-through and unchanged), unmapped, misaligned.
    let mut fake = [0x5au64; 32];
    refused_everywhere(&fmu, fake.as_mut_ptr() as fmi2FMUstate, not_live);
    assert_eq!(fake, [0x5au64; 32]);
    refused_everywhere(&fmu, 0x10 as fmi2FMUstate, not_live);
    refused_everywhere(&fmu, 0xdead_beef_0001 as fmi2FMUstate, not_live);
    unsafe { fmu.expect_error(fmi2SetFMUstate(fmu.c, null_mut()), &["FMUstate is NULL"]) };
    same_as_twin(&fmu, &twin);
}

/// Handles are tokens that never come back: after 1000 states got and freed (far more than any
/// allocator-reuse window), every stale handle is still refused, also while newer states are
/// live, and a held state is still updated in place under its own handle.
#[test]
fn stale_handles_stay_refused_however_many_states_follow() {
    let (fmu, twin) = (running(), running());
    let mut held = get_state(&fmu);
    let (held_before, bytes) = (held, serialize(&fmu, held));
    let mut stale = std::collections::HashSet::new();
    for k in 0..1000 {
        let mut s = match k % 2 {
            0 => get_state(&fmu),
            _ => deserialize(&fmu, &bytes, null_mut()).1,
        };
        assert!(
            stale.insert(s as usize) && s != held,
            "handle {s:p} given out twice"
        );
        unsafe { assert_eq!(fmi2FreeFMUstate(fmu.c, &mut s), fmi2Status::OK) };
        unsafe { assert_eq!(fmi2GetFMUstate(fmu.c, &mut held), fmi2Status::OK) };
        assert_eq!(
            held, held_before,
            "fmi2GetFMUstate updates its own state in place"
        );
    }
    let live: Vec<_> = (0..100).map(|_| get_state(&fmu)).collect();
    assert!(live.iter().all(|h| !stale.contains(&(*h as usize))));
    for &h in &stale {
        refused_everywhere(
            &fmu,
            h as fmi2FMUstate,
            "not a live FMU state of this instance",
        );
    }
    same_as_twin(&fmu, &twin);
}

#[test]
fn get_fmu_state_updates_its_own_states_and_never_uses_other_values() {
    let (fmu, other) = (running(), running());
    let mut own = get_state(&fmu);
    let before = own;
    run(&fmu, 1);
    unsafe { assert_eq!(fmi2GetFMUstate(fmu.c, &mut own), fmi2Status::OK) };
    assert_eq!(
        own, before,
        "a live state of this instance is updated in place"
    );
    // Another instance's state or garbage in the slot: a new state, with a warning.
    let theirs = get_state(&other);
    let theirs_bytes = serialize(&other, theirs);
    for value in [theirs, 0x18 as fmi2FMUstate] {
        let mut slot = value;
        let status = unsafe { fmi2GetFMUstate(fmu.c, &mut slot) };
        assert_eq!(status, fmi2Status::Warning);
        let msg = fmu.messages().pop().unwrap();
        assert_eq!(msg.status, fmi2Status::Warning);
        assert!(
            msg.text.contains("neither NULL nor a live state"),
            "{}",
            msg.text
        );
        assert!(slot != value && !slot.is_null());
        assert_eq!(serialize(&fmu, slot), serialize(&fmu, own));
    }
    assert_eq!(serialize(&other, theirs), theirs_bytes);
}

// States left unfreed go with the instance: counted by a per-thread allocation ledger.

struct Ledger;

thread_local! {
    // Const-initialized: reading it never allocates, so the allocator may use it.
    static LIVE_BYTES: Cell<isize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Ledger {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LIVE_BYTES.with(|b| b.set(b.get() + layout.size() as isize));
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE_BYTES.with(|b| b.set(b.get() - layout.size() as isize));
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static GLOBAL: Ledger = Ledger;

#[test]
fn free_instance_frees_the_states_the_host_did_not() {
    let cycle = |states: usize| {
        let live = LIVE_BYTES.with(Cell::get);
        {
            let fmu = running();
            let bytes = serialize(&fmu, get_state(&fmu));
            for _ in 0..states {
                get_state(&fmu);
                deserialize(&fmu, &bytes, null_mut());
            }
        } // fmi2FreeInstance, none of the states freed by the host
        LIVE_BYTES.with(Cell::get) - live
    };
    cycle(1); // first-use allocations of the runtime (thread-locals, formatting) happen here
    assert_eq!(cycle(0), 0);
    assert_eq!(cycle(50), 0, "states leaked at fmi2FreeInstance");
}

// ----- stopTime -------------------------------------------------------------------------------

#[test]
fn steps_past_stop_time_are_refused_and_change_nothing() {
    let (fmu, twin) = (Fmu::new(BEAM), Fmu::new(BEAM));
    let stop = 5.0 * H;
    unsafe {
        assert_eq!(
            fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 1, stop),
            fmi2Status::OK
        );
        assert_eq!(fmi2EnterInitializationMode(fmu.c), fmi2Status::OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), fmi2Status::OK);
    }
    twin.init();
    assert_eq!(run(&fmu, 3), run(&twin, 3));
    let t = fmu.time();
    let before = fmu.outputs();
    fmu.expect_error(
        fmu.step(t, 3.0 * H),
        &["stopTime = 5e-4", "would end at t = 6"],
    );
    fmu.expect_error(fmu.step(t, 2.0 * H * (1.0 + 1e-6)), &["stopTime"]);
    assert_eq!((fmu.time(), fmu.outputs()), (t, before), "nothing computed");
    // Still in stepComplete: a shorter step, then one ending at stopTime up to round-off.
    same_as_twin(&fmu, &twin);
    assert_eq!(fmu.step(fmu.time(), H * (1.0 + 1e-12)), fmi2Status::OK);
    fmu.expect_error(fmu.step(fmu.time(), H), &["past stopTime"]);
}
