//! Cost of a frame's time step against a straight rod's with the same number of elements:
//! prints microseconds per step for a straight clamped rod of N elements, an open 4-member
//! frame (a portal with its beam in two members: the members form a path, eliminated like a
//! chain) and a closed 4-member frame (a rectangular ring on a pin: a loop, whose elimination
//! fills one block per node), with their ratios to the rod, for N = 40, 400, 4000 (the ratios
//! between sizes show the cost linear in N).
//!
//! Run: `cargo bench --bench frames` (release profile). Each case runs its scene with a
//! harmonic load from its static state, steps of 1e-5 s, for about half a second, three times
//! interleaved with the others; the best of the three counts (noise only adds).
use georod::scene::Scene;
use georod::simulation::Simulation;
use std::sync::Arc;
use std::time::Instant;

/// The material, section, mesh and excitation of every case.
fn material(n: usize) -> String {
    format!(
        "[defaults]\nE = 210e9\nrho = 7850.0\ndt_max = 1e-5\nF = 1000.0\nOmega = 100.0\n\
         elements = {n}\n[section]\nb = 0.1\nh = 0.2\n"
    )
}

fn rod(n: usize) -> String {
    format!(
        "name = \"Rod\"\n{}[geometry]\nshape = \"straight\"\nL = 20.0\n\
         [[support]]\nname = \"a\"\nat = 0.0\nfix = [\"u1\", \"u2\", \"w\"]\n\
         [[support]]\nname = \"b\"\nat = 1.0\nfix = [\"u1\", \"u2\", \"w\"]\n\
         [[load]]\nname = \"p\"\nkind = \"point\"\nat = 0.3\ndirection = \"-e2\"\ntime = \"harmonic\"\n",
        material(n)
    )
}

/// Four members of 5 m: A-B-M-C-D (open, a portal whose beam is cut at M) or a ring.
fn frame(n: usize, closed: bool) -> String {
    let joints = [
        ("A", 0.0, 0.0),
        ("B", 0.0, 5.0),
        ("M", 5.0, 5.0),
        ("C", 10.0, 5.0),
        ("D", 10.0, 0.0),
    ];
    let mut s = format!("name = \"Frame\"\n{}", material(n));
    let used = if closed { 4 } else { 5 };
    for (name, x, y) in &joints[..used] {
        s += &format!("[[joint]]\nname = \"{name}\"\nx = {x}\ny = {y}\n");
    }
    let pairs: Vec<(&str, &str)> = if closed {
        vec![("A", "B"), ("B", "M"), ("M", "C"), ("C", "A")]
    } else {
        vec![("A", "B"), ("B", "M"), ("M", "C"), ("D", "C")]
    };
    for (k, (a, b)) in pairs.iter().enumerate() {
        s += &format!("[[member]]\nname = \"m{k}\"\nfrom = \"{a}\"\nto = \"{b}\"\n");
    }
    let supports: &[&str] = if closed { &["A"] } else { &["A", "D"] };
    for j in supports {
        s += &format!(
            "[[support]]\nname = \"s{j}\"\njoint = \"{j}\"\nfix = [\"u1\", \"u2\", \"w\"]\n"
        );
    }
    s + "[[load]]\nname = \"p\"\nkind = \"point\"\njoint = \"B\"\ndirection = \"e1\"\ntime = \"harmonic\"\n"
}

/// Microseconds per time step of the scene `text` (1e-5 s steps, about a second of timing).
fn measure(text: &str) -> f64 {
    let scene = Arc::new(Scene::parse(text, "bench.toml").expect("scene"));
    let values = scene.defaults();
    let mut sim = Simulation::new(scene, values).expect("initial state");
    sim.advance(1e-5).expect("step");
    let mut steps = 1usize;
    loop {
        let start = Instant::now();
        for _ in 0..steps {
            sim.advance(1e-5).expect("step");
        }
        let seconds = start.elapsed().as_secs_f64();
        if seconds > 0.5 || steps >= 1 << 22 {
            return 1e6 * seconds / steps as f64;
        }
        steps *= if seconds < 0.05 { 10 } else { 2 };
    }
}

/// Writes the cases' scene files into `target/bench/frames/` (for `scripts/bench_frames`,
/// which counts their instructions).
fn write_scenes() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/target/bench/frames");
    std::fs::create_dir_all(dir).expect("target/bench/frames");
    for n in [40, 400, 4000] {
        for (name, text) in [
            ("rod", rod(n)),
            ("open", frame(n, false)),
            ("ring", frame(n, true)),
        ] {
            std::fs::write(format!("{dir}/{name}{n}.toml"), text).expect("a scene file");
        }
    }
}

fn main() {
    write_scenes();
    println!(
        "| elements | rod us / step | open 4-member frame | ratio | closed 4-member ring | ratio |"
    );
    println!("|---:|---:|---:|---:|---:|---:|");
    for n in [40, 400, 4000] {
        let scenes = [rod(n), frame(n, false), frame(n, true)];
        let mut best = [f64::INFINITY; 3];
        for _ in 0..3 {
            for (b, text) in best.iter_mut().zip(&scenes) {
                *b = b.min(measure(text));
            }
        }
        let [r, open, closed] = best;
        println!(
            "| {n} | {r:.2} | {open:.2} | {:.2} | {closed:.2} | {:.2} |",
            open / r,
            closed / r
        );
    }
}
