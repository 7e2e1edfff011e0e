//! Value references come in blocks (scene parameters from 100, inputs from 1000, sensors from
//! 2000, reactions from 3000, shape samples from 10000 and 20000, shape fields from 30000 in
//! blocks of 10000, frequencies from 52): a scene with more parameters,
//! inputs, sensors or supports than its block holds is refused with the key and the maximum; a
//! scene at every maximum at once is accepted and its value references are all different.
use georod::scene::readouts::MAX_MODES;
use georod::scene::variables::{
    variables, Causality, OutputId, Role, MAX_INPUTS, MAX_SCENE_PARAMS, MAX_SENSORS, MAX_SUPPORTS,
};
use georod::scene::{Quantity, Scene};
use std::collections::BTreeSet;
use std::fmt::Write;

/// How many of each item a generated scene has.
#[derive(Clone, Copy)]
struct Counts {
    params: usize,
    input_loads: usize,
    /// Supports that hold u1, u2, w and follow inputs (3 inputs each).
    moving_supports: usize,
    /// Supports that hold u2 (the first one also u1).
    fixed_supports: usize,
    sensors: usize,
    shape_points: usize,
}

const SMALL: Counts = Counts {
    params: 1,
    input_loads: 1,
    moving_supports: 0,
    fixed_supports: 2,
    sensors: 1,
    shape_points: 5,
};

/// Every support on its own node of a mesh of 2400 elements.
const ELEMENTS: usize = 2400;

fn scene_text(n: Counts) -> String {
    let mut t =
        String::from(
        "name = \"Big\"\n[geometry]\nshape = \"straight\"\nL = 10.0\n[defaults]\nE = 1.2e4\nrho = 1e-6\n",
    );
    writeln!(t, "elements = {ELEMENTS}").unwrap();
    for i in 0..n.params {
        writeln!(t, "[[parameter]]\nname = \"p{i}\"\nstart = {i}.0").unwrap();
    }
    let supports = n.moving_supports + n.fixed_supports;
    assert!(supports <= ELEMENTS + 1);
    for k in 0..supports {
        let at = k as f64 / ELEMENTS as f64;
        let (fix, motion) = match k {
            k if k < n.moving_supports => ("[\"u1\", \"u2\", \"w\"]", "input"),
            k if k == n.moving_supports => ("[\"u1\", \"u2\"]", "none"),
            _ => ("[\"u2\"]", "none"),
        };
        writeln!(
            t,
            "[[support]]\nname = \"s{k}\"\nat = {at:?}\nfix = {fix}\nmotion = \"{motion}\""
        )
        .unwrap();
    }
    for i in 0..n.input_loads {
        writeln!(
            t,
            "[[load]]\nname = \"f{i}\"\nkind = \"point\"\nat = 0.5\ndirection = \"-e2\"\ntime = \"input\""
        )
        .unwrap();
    }
    for i in 0..n.sensors {
        writeln!(
            t,
            "[[sensor]]\nname = \"y{i}\"\nat = 0.5\nquantity = \"u2\""
        )
        .unwrap();
    }
    writeln!(t, "[shape]\npoints = {}", n.shape_points).unwrap();
    t
}

fn refused(n: Counts) -> String {
    match Scene::parse(&scene_text(n), "big.toml") {
        Ok(_) => panic!("accepted"),
        Err(e) => {
            let message = e.to_string();
            println!("{message}");
            message
        }
    }
}

#[test]
fn more_than_a_block_holds_is_refused_with_the_key_and_the_maximum() {
    let cases = [
        (
            Counts {
                params: MAX_SCENE_PARAMS + 1,
                ..SMALL
            },
            "[[parameter]] #901 \"p900\"",
            "at most 900",
        ),
        (
            Counts {
                input_loads: MAX_INPUTS + 1,
                ..SMALL
            },
            "[[load]] #1001 \"f1000\", key `time`",
            "at most 1000",
        ),
        (
            // 333 moving supports (999 inputs) and 2 input loads: the second load is one too many.
            Counts {
                moving_supports: 333,
                input_loads: 2,
                ..SMALL
            },
            "[[load]] #2 \"f1\", key `time`",
            "at most 1000",
        ),
        (
            Counts {
                sensors: MAX_SENSORS + 1,
                ..SMALL
            },
            "[[sensor]] #1001 \"y1000\"",
            "at most 1000",
        ),
        (
            Counts {
                fixed_supports: MAX_SUPPORTS + 1,
                ..SMALL
            },
            "[[support]] #2334 \"s2333\"",
            "at most 2333",
        ),
    ];
    for (counts, key, max) in cases {
        let message = refused(counts);
        assert!(message.starts_with("big.toml: "), "{message}");
        assert!(message.contains(key), "`{message}` lacks `{key}`");
        assert!(message.contains(max), "`{message}` lacks `{max}`");
    }
}

#[test]
fn a_scene_at_every_maximum_has_unique_value_references_inside_their_blocks() {
    assert_eq!(
        (MAX_SCENE_PARAMS, MAX_INPUTS, MAX_SENSORS, MAX_SUPPORTS),
        (900, 1000, 1000, 2333)
    );
    let n = Counts {
        params: MAX_SCENE_PARAMS,
        input_loads: 1,
        moving_supports: 333,
        fixed_supports: MAX_SUPPORTS - 333,
        sensors: MAX_SENSORS,
        shape_points: 10_000,
    };
    // Every quantity as a shape field (right after `points`, in [shape]) and the most modes.
    let fields: Vec<String> = Quantity::NAMES.iter().map(|q| format!("\"{q}\"")).collect();
    let text = format!(
        "{}fields = [{}]\n[modes]\ncount = {MAX_MODES}\n",
        scene_text(n),
        fields.join(", ")
    );
    let scene = Scene::parse(&text, "big.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.inputs.len(), MAX_INPUTS);
    let vars = variables(&scene);
    let mut seen = BTreeSet::new();
    for v in &vars {
        assert!(
            seen.insert(v.vr),
            "value reference {} used twice ({})",
            v.vr,
            v.name
        );
    }
    let names: BTreeSet<&str> = vars.iter().map(|v| v.name.as_str()).collect();
    assert_eq!(names.len(), vars.len(), "a name used twice");
    // Each kind inside its block.
    for v in &vars {
        let range = match v.role {
            Role::Parameter(i) if i < scene.params.len() - MAX_SCENE_PARAMS => 0..100,
            Role::Parameter(_) => 100..1000,
            Role::Input(_) => 1000..2000,
            Role::Output(OutputId::Standard(_))
            | Role::Output(OutputId::Lyapunov { .. })
            | Role::Output(OutputId::LyapunovTime)
            | Role::Output(OutputId::Frequency(_)) => 32..100,
            Role::Output(OutputId::Sensor(_)) => 2000..3000,
            Role::Output(OutputId::Reaction { .. }) => 3000..10_000,
            Role::Output(OutputId::ShapeX(_)) => 10_000..20_000,
            Role::Output(OutputId::ShapeY(_)) => 20_000..30_000,
            Role::Output(OutputId::ShapeField { field, .. }) => {
                let base = 30_000 + 10_000 * field as u32;
                base..base + 10_000
            }
            Role::Output(OutputId::SpringForce(_)) => 1_000_000..1_100_000,
            Role::Output(OutputId::SupportFrame { .. }) => 1_100_000..1_200_000,
            Role::Output(OutputId::BarForce { .. }) => 1_200_000..1_300_000,
            Role::Output(OutputId::LinkForce(_)) => 1_300_000..1_400_000,
            Role::Output(OutputId::StopForce(_)) => 1_400_000..1_500_000,
            Role::Output(OutputId::StopContact(_)) => 1_500_000..u32::MAX,
        };
        assert!(
            range.contains(&v.vr),
            "{} has vr {} outside {range:?}",
            v.name,
            v.vr
        );
    }
    let count = |c: Causality| vars.iter().filter(|v| v.causality == c).count();
    assert_eq!(count(Causality::Input), MAX_INPUTS);
    assert_eq!(
        count(Causality::Output),
        // 8 standard outputs, lyapunov[1..4] and lyapunov_time (no harmonic load: no
        // lyapunov_per_period).
        8 + georod::integrator::tangent::MAX_EXPONENTS
            + 1
            + MAX_SENSORS
            + 3 * MAX_SUPPORTS
            + 2 * 10_000
            + Quantity::NAMES.len() * 10_000
            + MAX_MODES
    );
}
