//! The FMI 3.0 API against corrupt serialized states: every single-byte corruption and every
//! truncation is refused by `fmi3DeserializeFMUState`, and the instance steps on like its twin.
#![cfg(not(all(target_vendor = "apple", target_arch = "aarch64")))]
use crate::fmi3_host;

use crate::fmi_host::BEAM;
use fmi3_host::*;
use georod::fmi::api3::*;
use georod::fmi::types3::*;

#[test]
fn every_corrupt_or_truncated_state_is_refused_and_changes_nothing() {
    let (fmu, twin) = (Fmu3::new(BEAM), Fmu3::new(BEAM));
    fmu.init();
    twin.init();
    let t = run(&fmu, 0.0, 2);
    run(&twin, 0.0, 2);
    let mut keep: fmi3FMUState = std::ptr::null_mut();
    let mut size = 0;
    let mut good;
    unsafe {
        assert_eq!(fmi3GetFMUState(fmu.c, &mut keep), fmi3Status::OK);
        assert_eq!(
            fmi3SerializedFMUStateSize(fmu.c, keep, &mut size),
            fmi3Status::OK
        );
        good = vec![0u8; size];
        assert_eq!(
            fmi3SerializeFMUState(fmu.c, keep, good.as_mut_ptr(), size),
            fmi3Status::OK
        );
    }
    let refused = |bytes: &[u8], what: String| {
        let mut out = keep;
        let s = unsafe { fmi3DeserializeFMUState(fmu.c, bytes.as_ptr(), bytes.len(), &mut out) };
        assert_eq!(s, fmi3Status::Error, "{what} accepted");
        assert_eq!(out, keep, "{what}: the slot is written only on success");
        let msg = fmu.messages().pop().expect("a refusal is logged");
        assert!(
            msg.text.starts_with("fmi3DeserializeFMUState: "),
            "{}",
            msg.text
        );
    };
    for at in 0..size {
        for mask in [0x01u8, 0xff] {
            let mut bad = good.clone();
            bad[at] ^= mask;
            refused(&bad, format!("byte {at} ^ {mask:#x}"));
        }
    }
    for n in 0..size {
        refused(&good[..n], format!("{n} of {size} bytes"));
    }
    good.push(0);
    refused(&good, "one byte more".to_string());
    assert_eq!(run(&fmu, t, 3).to_bits(), run(&twin, t, 3).to_bits());
    assert_eq!(
        bits(&fmu),
        bits(&twin),
        "the instance steps on like its untouched twin"
    );
}
