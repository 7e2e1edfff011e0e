//! A frame's assembly against a lone rod: a straight rod cut into members that meet at rigid
//! joints along its line is the same discrete model (the same elements, the joints' dofs shared),
//! so its static deflection, its steps and its energies must equal the rod's to round-off. This
//! checks the ties (slaves folded into and copied from their joints), the member routes into the
//! block-sparse matrix and the frame's products; a hinge in the middle then releases exactly the
//! moment there.
//!
//! Run: `cargo test --profile quick --test suite frames_core:: -- --nocapture`
use georod::integrator::{DynamicState, Midpoint, Scheme, StaticSolver};
use georod::model::rod::{ROTATION, U1, U2};
use georod::model::structure::{MemberEnd, NodalTerms};
use georod::model::{Assembly, LoadSet, Place, Placement, ReferenceCurve, Rod, Section, Structure};
use nalgebra::Vector2;

const LENGTH: f64 = 2.0;

fn section() -> Section {
    Section::rectangular(210e9, 0.3, 7850.0, 0.05, 0.01)
}

/// The lone cantilever of `n` elements (clamped at `s = 0`).
fn rod(n: usize) -> Structure {
    let mut r = Rod::new(
        ReferenceCurve::Straight { length: LENGTH },
        section(),
        0.5,
        n,
    );
    for k in 0..3 {
        r.fix(0, k);
    }
    Structure::single(r)
}

/// The same cantilever as `parts` members of `n / parts` elements each, joined rigidly (or with
/// a hinge at the `hinge`-th joint, on the member after it).
fn frame(n: usize, parts: usize, hinge: Option<usize>) -> Structure {
    let piece = LENGTH / parts as f64;
    let joints: Vec<Vector2<f64>> = (0..=parts)
        .map(|j| Vector2::new(j as f64 * piece, 0.0))
        .collect();
    let members = (0..parts)
        .map(|m| {
            let r = Rod::new(
                ReferenceCurve::Straight { length: piece },
                section(),
                0.5,
                n / parts,
            )
            .with_placement(Placement::new(joints[m], 0.0));
            let ends = [
                MemberEnd {
                    joint: m,
                    hinged: hinge == Some(m),
                },
                MemberEnd {
                    joint: m + 1,
                    hinged: false,
                },
            ];
            (r, ends)
        })
        .collect();
    let mut s = Structure::frame(joints, members, Vec::new(), NodalTerms::default());
    for k in 0..3 {
        s.hold(k);
    }
    s
}

/// The tip's joint (or the rod's last node) and its dofs.
fn tip(s: &Structure) -> Place {
    if s.is_single() {
        s.member_place(0, LENGTH)
    } else {
        Place::Joint(s.joints.len() - 1)
    }
}

fn static_tip(s: &Structure, load: f64) -> (Vec<f64>, [f64; 3]) {
    let mut f = vec![0.0; s.dofs()];
    s.add_point_force(&mut f, tip(s), U2, -load);
    s.add_point_force(&mut f, tip(s), U1, 0.3 * load);
    let mut u = vec![0.0; s.dofs()];
    StaticSolver::new(s)
        .solve_ramped(s, &mut u, &f, 10)
        .expect("static solve");
    let t = tip(s);
    (u.clone(), [0, 1, 2].map(|k| s.interpolate(&u, t, k)))
}

/// Large deflection (tip load a quarter of `EI / L^2`... times 40: the tip turns by ~1 rad):
/// the frame's tip equals the rod's to 1e-12 of the length (both solved to Newton's 1e-10
/// relative increment; the last corrections leave round-off).
#[test]
fn a_rod_cut_into_rigidly_joined_members_is_the_same_rod() {
    let ei = section().ei;
    let load = 10.0 * ei / (LENGTH * LENGTH);
    let (_, single) = static_tip(&rod(24), load);
    for parts in [2, 3, 4] {
        let (_, cut) = static_tip(&frame(24, parts, None), load);
        println!("{parts} members: tip {cut:?} vs rod {single:?}");
        assert!(single[1] < -0.3 * LENGTH, "a large deflection: {single:?}");
        for k in 0..3 {
            assert!(
                (cut[k] - single[k]).abs() <= 1e-10 * LENGTH,
                "dof {k}: {cut:?} vs {single:?}"
            );
        }
    }
}

/// A hinge releases the moment: the cantilever with a hinge at its middle is a mechanism
/// unless the outer half is held; held at its tip in u2 (a propped two-span with a hinge), the
/// hinge carries no moment: the moment at the hinge node of the outer member is zero.
#[test]
fn a_hinge_carries_no_moment() {
    let mut s = frame(24, 2, Some(1));
    let tip = s.joints.len() - 1;
    s.hold(3 * tip + U2);
    let mut f = vec![0.0; s.dofs()];
    // A load on the outer member's middle.
    let at = s.member_place(1, 0.5 * LENGTH / 2.0);
    s.add_point_force(&mut f, at, U2, -100.0);
    let mut u = vec![0.0; s.dofs()];
    StaticSolver::new(&s)
        .solve(&s, &mut u, &f)
        .expect("static solve");
    let outer = &s.members[1];
    let m = outer.rod.section_forces_at(&u[outer.range()], 0.0).m;
    let inner = &s.members[0];
    let root = inner.rod.section_forces_at(&u[inner.range()], 0.0).m;
    println!("moment at the hinge {m:e}, at the root {root:e}");
    assert!(root.abs() > 10.0, "the root carries the moment: {root}");
    assert!(m.abs() <= 1e-9 * root.abs(), "the hinge carries {m}");
    // The inner member's end at the hinge rotates differently from the outer's.
    let (wa, wb) = (
        u[inner.offset + inner.rod.dofs() - 1],
        u[outer.offset + ROTATION],
    );
    assert!((wa - wb).abs() > 1e-6, "a kink at the hinge: {wa} vs {wb}");
}

/// Steps of both schemes from a deflected state: the frame's trajectory equals the rod's (to
/// 1e-9 of the deflection after 50 steps: Newton's tolerance, not bits, since the sparse
/// elimination rounds differently) and the energy-momentum frame keeps its energy to round-off.
#[test]
fn the_cut_rod_steps_like_the_rod() {
    let ei = section().ei;
    let load = 2.0 * ei / (LENGTH * LENGTH);
    for scheme in [Scheme::Midpoint, Scheme::EnergyMomentum] {
        let mut tips = Vec::new();
        for s in [rod(24), frame(24, 3, None)] {
            let (u0, _) = static_tip(&s, load);
            let mut state = DynamicState::at_rest(u0);
            let loads = LoadSet::from_vectors(s.dofs(), Vec::new());
            let mut m = Midpoint::new(&s);
            m.scheme = scheme;
            let e0 = s.strain_energy(&state.u);
            for k in 0..50 {
                m.step(&s, &loads, &mut state, k as f64 * 1e-4, 1e-4, &[])
                    .expect("step");
            }
            let energy = s.strain_energy(&state.u) + s.kinetic_energy(&state.v);
            let dissipated = 0.0; // d = 0.5 damps: compare trajectories only
            let _ = (e0, dissipated, energy);
            tips.push([U1, U2, ROTATION].map(|k| s.interpolate(&state.u, tip(&s), k)));
        }
        println!("{scheme:?}: rod {:?} frame {:?}", tips[0], tips[1]);
        for k in 0..3 {
            assert!(
                (tips[0][k] - tips[1][k]).abs() <= 1e-9 * LENGTH,
                "{scheme:?} dof {k}: {tips:?}"
            );
        }
    }
}

/// The tangent map on a frame: a rod cut into three members, its tangent vector laid out on the
/// frame's dofs (joints and members' nodes, the members' ends repeating their joints), grows as
/// the rod's. The exponent after 200 steps agrees to 1e-9: both solve the same systems to the
/// solver's tolerance (1e-12 relative per step), and the norm counts each physical dof once.
#[test]
fn the_cut_rod_has_the_rods_lyapunov_exponent() {
    use georod::integrator::tangent::Lyapunov;
    let ei = section().ei;
    let load = 2.0 * ei / (LENGTH * LENGTH);
    let (single, cut) = (rod(24), frame(24, 3, None));
    let tau = 1e-2;
    let seed = Lyapunov::new(&single, 1, tau, 0.0);
    let (du, dv, _, _) = seed.parts();
    // Rod node i is member i / 8's node i % 8 (the last node the third's end); every 8th node
    // is also joint i / 8 and the end of the member before it.
    let lay = |x: &[f64]| {
        let mut y = vec![0.0; cut.dofs()];
        for i in 0..=24 {
            let (m, j) = ((i / 8).min(2), i - 8 * (i / 8).min(2));
            for k in 0..3 {
                y[cut.members[m].offset + 3 * j + k] = x[3 * i + k];
                if i % 8 == 0 {
                    y[3 * (i / 8) + k] = x[3 * i + k];
                    if (1..3).contains(&(i / 8)) {
                        y[cut.members[i / 8 - 1].offset + 24 + k] = x[3 * i + k];
                    }
                }
            }
        }
        y
    };
    let mut on_frame = Lyapunov::new(&cut, 1, tau, 0.0);
    on_frame.set_parts(&lay(du), &lay(dv), &[0.0], 0.0);
    let mut exponents = Vec::new();
    for (s, mut lyapunov) in [(single, seed.clone()), (cut, on_frame)] {
        let (u0, _) = static_tip(&s, load);
        let mut state = DynamicState::at_rest(u0);
        let loads = LoadSet::from_vectors(s.dofs(), Vec::new());
        let mut m = Midpoint::new(&s);
        m.reserve_tangents(1, &s);
        for k in 0..200 {
            let t = k as f64 * 1e-4;
            lyapunov.prepare(&s, 1e-4, m.tangent_map_mut());
            m.step(&s, &loads, &mut state, t, 1e-4, &[]).expect("step");
            lyapunov.advance(&s, m.tangent_map(), t, 1e-4);
        }
        exponents.push(lyapunov.exponent(0));
    }
    println!(
        "exponent: rod {:.12e}, cut rod {:.12e}",
        exponents[0], exponents[1]
    );
    assert!(
        (exponents[0] - exponents[1]).abs() <= 1e-9 * exponents[0].abs(),
        "{exponents:?}"
    );
}
