//! Shared helpers of the physics tests: a deterministic PRNG, dense copies of the block-tridiagonal
//! matrices, a dense generalized symmetric eigen solver, and closed-form reference solutions
//! (Timoshenko beam frequencies, the shear-deformable buckling load, the exact elastica), and
//! the adapters to the scene layer used by the tests (see [`simulation`]).
#![allow(dead_code)]

pub mod contact;
pub mod linear_frame;
pub mod moving;
pub mod scenes;

use georod::model::loads::{LoadShape, LoadTime};
use georod::model::rod::{U1, U2};
use georod::model::{LoadSet, ReferenceCurve, Rod, Section};
use georod::simulation::{AdvanceReport, SimError, Simulation};
use georod::solver::BlockTridiagonal;
use nalgebra::DMatrix;
use std::f64::consts::PI;

/// SplitMix64: a tiny deterministic generator (no crate), good enough for test states.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * unit
    }
}

/// The scenes' material: `E = 1.2e4`, `nu = 0.2`, `rho = 1e-6`.
pub const E: f64 = 1.2e4;
pub const NU: f64 = 0.2;
pub const RHO: f64 = 1.0e-6;

pub fn section(b: f64, h: f64) -> Section {
    Section::rectangular(E, NU, RHO, b, h)
}

/// A straight rod of length `length` along `e1`, `n` elements, no constraints.
pub fn straight_rod(length: f64, b: f64, h: f64, damping: f64, n: usize) -> Rod {
    Rod::new(
        ReferenceCurve::Straight { length },
        section(b, h),
        damping,
        n,
    )
}

/// Dense copy of a block-tridiagonal matrix, column by column through `mul` with unit vectors.
pub fn dense(a: &BlockTridiagonal) -> DMatrix<f64> {
    let n = 3 * a.blocks();
    let mut m = DMatrix::zeros(n, n);
    let mut e = vec![0.0; n];
    let mut col = vec![0.0; n];
    for j in 0..n {
        e[j] = 1.0;
        a.mul(&e, &mut col);
        e[j] = 0.0;
        for i in 0..n {
            m[(i, j)] = col[i];
        }
    }
    m
}

/// Dense tangent `K_T(u)` of a rod (no constraints applied).
pub fn dense_tangent(rod: &Rod, u: &[f64]) -> DMatrix<f64> {
    let mut jac = BlockTridiagonal::new(rod.nodes());
    let mut f = vec![0.0; rod.dofs()];
    rod.internal_force_and_tangent(u, &mut f, &mut jac, 1.0);
    dense(&jac)
}

/// Dense consistent mass matrix of a rod.
pub fn dense_mass(rod: &Rod) -> DMatrix<f64> {
    let mut m = BlockTridiagonal::new(rod.nodes());
    rod.add_mass(&mut m, 1.0);
    dense(&m)
}

/// Indices of the free (unconstrained) dofs.
pub fn free_dofs(rod: &Rod) -> Vec<usize> {
    (0..rod.dofs()).filter(|&i| !rod.fixed[i]).collect()
}

/// The submatrix of rows and columns `idx`.
pub fn submatrix(a: &DMatrix<f64>, idx: &[usize]) -> DMatrix<f64> {
    DMatrix::from_fn(idx.len(), idx.len(), |i, j| a[(idx[i], idx[j])])
}

/// Generalized symmetric eigenproblem `K x = lambda M x` (M positive definite): Cholesky
/// `M = L L^T`, symmetric eigen of `L^-1 K L^-T`. Returns the eigenvalues ascending and the
/// M-orthonormal eigenvectors (columns) in the same order.
pub fn generalized_eigen(k: &DMatrix<f64>, m: &DMatrix<f64>) -> (Vec<f64>, DMatrix<f64>) {
    let chol = m
        .clone()
        .cholesky()
        .expect("mass matrix not positive definite");
    let l = chol.l();
    let l_inv = l
        .clone()
        .try_inverse()
        .expect("Cholesky factor not invertible");
    let mut a = &l_inv * k * l_inv.transpose();
    a = 0.5 * (&a + a.transpose());
    let dim = a.nrows();
    let eig = a.symmetric_eigen();
    let mut order: Vec<usize> = (0..eig.eigenvalues.len()).collect();
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    let values = order.iter().map(|&i| eig.eigenvalues[i]).collect();
    let y = DMatrix::from_fn(dim, order.len(), |r, c| eig.eigenvectors[(r, order[c])]);
    let vectors = l_inv.transpose() * y;
    (values, vectors)
}

/// Smallest eigenvalue of a symmetric matrix.
pub fn lowest_eigenvalue(a: &DMatrix<f64>) -> f64 {
    let sym = 0.5 * (a + a.transpose());
    sym.symmetric_eigen().eigenvalues.min()
}

/// Timoshenko beam (shear coefficient 1, with rotary inertia), simply supported, mode `n`:
/// with `k = n pi / L`, the roots `w^2` of
/// `det [[GA k^2 - rhoA w^2, -GA k], [-GA k, EI k^2 + GA - rhoI w^2]] = 0`; returns the lower
/// root (the bending branch) as a circular frequency.
pub fn timoshenko_bending_omega(sec: &Section, length: f64, n: usize) -> f64 {
    let k = n as f64 * PI / length;
    let (ga, ei, ra, ri) = (sec.ga, sec.ei, sec.rho_a, sec.rho_i);
    // (GA k^2 - ra x)(EI k^2 + GA - ri x) - GA^2 k^2 = 0, x = w^2.
    let a = ra * ri;
    let b = -(ra * (ei * k * k + ga) + ri * ga * k * k);
    let c = ga * k * k * (ei * k * k + ga) - ga * ga * k * k;
    let disc = (b * b - 4.0 * a * c).sqrt();
    // The smaller root, computed without cancellation: x = 2c / (-b + disc).
    let x = 2.0 * c / (-b + disc);
    x.sqrt()
}

/// Axial natural frequency of a bar fixed at both ends, mode `n`: `n pi / L sqrt(E / rho)`.
pub fn axial_omega(sec: &Section, length: f64, n: usize) -> f64 {
    n as f64 * PI / length * (sec.ea / sec.rho_a).sqrt()
}

/// The axial force `P` (compression) at which the straight, uniformly compressed, pinned-pinned
/// rod of model.md loses stability, from the second variation of its energy about the state
/// `u1' = -eps`, `u2 = w = 0` with the mode `u2 = A sin(k s)`, `w = B cos(k s)`, `k = pi / L`:
/// `P^2 + GA (1 - eps) P - GA EI k^2 = 0`, `P = EA eps`. Solved by fixed-point iteration on
/// `eps`. For `GA -> inf` and `eps -> 0` it is Euler's `pi^2 EI / L^2`.
pub fn critical_axial_force(sec: &Section, length: f64) -> f64 {
    let k = PI / length;
    let mut p = PI * PI * sec.ei / (length * length);
    for _ in 0..100 {
        let lambda = 1.0 - p / sec.ea;
        let g = sec.ga * lambda;
        // Positive root without cancellation: p = 2 c / (g + sqrt(g^2 + 4 c)), c = GA EI k^2.
        let c = sec.ga * sec.ei * k * k;
        p = 2.0 * c / (g + (g * g + 4.0 * c).sqrt());
    }
    p
}

/// The exact (inextensible, unshearable) cantilever elastica under a tip force of fixed direction
/// with `lambda = P L^2 / EI`: `phi'' = -lambda cos(phi)` for the downward rotation `phi`,
/// `phi(0) = 0`, `phi'(L) = 0`. Returns `(vertical deflection / L, horizontal shortening / L,
/// tip rotation)`. See [`cantilever_tip`].
pub fn elastica_tip(lambda: f64) -> (f64, f64, f64) {
    cantilever_tip(lambda, f64::INFINITY, NU)
}

/// The exact solution of the continuum of model.md (Reissner's rod: stretch, shear, no shear
/// correction) for a cantilever of slenderness `L/h` (rectangular section) under a tip force
/// `P` of fixed direction `-e2`, `lambda = P L^2 / EI`. Units `EI = L = 1`, so
/// `EA = 12 (L/h)^2`, `GA = EA / (2 (1 + nu))`; `L/h = inf` is the inextensible elastica.
///
/// With `theta` the rotation (counter-clockwise), `t = (cos, sin) theta`, `n = (-sin, cos) theta`,
/// the force resultant is the tip force everywhere, `N = (0, -lambda)`; `S1 = N.t`, `S2 = N.n`,
/// `x' = (1 + S1/EA) t + (S2/GA) n`, `theta' = M`, `M' = -(x' x N)`; `theta(0) = 0`, `M(1) = 0`.
/// RK4 (4000 steps, error ~1e-14) and bisection on `M(0)` in `[-1.2 lambda, 0]` (`M(1)` is
/// positive at the upper and negative at the lower end).
/// Returns `(vertical deflection / L, horizontal shortening / L, downward tip rotation)`.
pub fn cantilever_tip(lambda: f64, slenderness: f64, nu: f64) -> (f64, f64, f64) {
    const STEPS: usize = 4000;
    let ea = 12.0 * slenderness * slenderness;
    let ga = ea / (2.0 * (1.0 + nu));
    let rhs = |y: [f64; 4]| {
        let (sin, cos) = y[0].sin_cos();
        let (s1, s2) = (-lambda * sin, -lambda * cos);
        let (e1, e2) = (s1 / ea, s2 / ga);
        let dx = (1.0 + e1) * cos - e2 * sin;
        let dy = (1.0 + e1) * sin + e2 * cos;
        // M' = -(x' x N) = -(dx N_2 - dy N_1) = lambda dx.
        [y[1], lambda * dx, dx, dy]
    };
    let integrate = |m0: f64| -> [f64; 4] {
        let h = 1.0 / STEPS as f64;
        let mut y = [0.0, m0, 0.0, 0.0];
        for _ in 0..STEPS {
            let k1 = rhs(y);
            let k2 = rhs(std::array::from_fn(|i| y[i] + 0.5 * h * k1[i]));
            let k3 = rhs(std::array::from_fn(|i| y[i] + 0.5 * h * k2[i]));
            let k4 = rhs(std::array::from_fn(|i| y[i] + h * k3[i]));
            for i in 0..4 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        y
    };
    let (mut lo, mut hi) = (-1.2 * lambda, 0.0);
    assert!(integrate(lo)[1] < 0.0 && integrate(hi)[1] > 0.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if integrate(mid)[1] < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let y = integrate(0.5 * (lo + hi));
    (-y[3], 1.0 - y[2], -y[0])
}

/// The pinned-pinned rod of the BuckledBeam scene (`u1 = u2 = 0` at `s = 0`, `u2 = 0` and
/// `u1 = -Delta` prescribed at `s = L`, rotations free).
pub fn pinned_rod(length: f64, n: usize) -> Rod {
    let mut rod = straight_rod(length, 1.0, 1.0, 0.0, n);
    let last = rod.last_node();
    rod.fix(0, U1);
    rod.fix(0, U2);
    rod.fix(last, U1);
    rod.fix(last, U2);
    rod
}

/// The straight, uniformly shortened state `u1 = -Delta s / L`, `u2 = w = 0` (an equilibrium).
pub fn straight_compressed_state(rod: &Rod, shortening: f64) -> Vec<f64> {
    let mut u = vec![0.0; rod.dofs()];
    for i in 0..rod.nodes() {
        u[3 * i + U1] = -shortening * rod.node_s[i] / rod.curve.length();
    }
    u
}

/// Negative eigenvalues of the constrained tangent at the straight state, from the pivots of its
/// block LDL^T factorization (Sylvester's law of inertia); `None` where the tangent is singular
/// to working precision (at the threshold itself).
pub fn negative_eigenvalues(rod: &Rod, shortening: f64) -> Option<usize> {
    let u = straight_compressed_state(rod, shortening);
    let mut jac = BlockTridiagonal::new(rod.nodes());
    let mut f = vec![0.0; rod.dofs()];
    rod.internal_force_and_tangent(&u, &mut f, &mut jac, 1.0);
    jac.constrain(rod.constrained());
    jac.factor_with_inertia().ok()?;
    Some(jac.negative_eigenvalues())
}

/// Bisection for the smallest shortening with a negative eigenvalue, to relative 1e-13 (or to
/// a point where the tangent is singular to working precision).
pub fn buckling_threshold(rod: &Rod, upper: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, upper);
    assert_eq!(negative_eigenvalues(rod, lo), Some(0));
    assert!(negative_eigenvalues(rod, hi).is_some_and(|n| n > 0));
    while hi - lo > 1e-13 * hi {
        let mid = 0.5 * (lo + hi);
        match negative_eigenvalues(rod, mid) {
            Some(0) => lo = mid,
            Some(_) => hi = mid,
            None => return mid,
        }
    }
    0.5 * (lo + hi)
}

/// Observed convergence order between two successive meshes (element count doubled).
pub fn order(coarse: f64, fine: f64) -> f64 {
    (coarse.abs() / fine.abs()).log2()
}

/// `|a - b|_inf`.
pub fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// `|a|_inf`.
pub fn max_abs(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Lines of a printed table, written in one piece when dropped (also when a test panics), so
/// that tests running in parallel do not interleave their tables under `--nocapture`.
pub struct Table(String);

impl Table {
    pub fn new(title: &str) -> Table {
        Table(format!("\n{title}\n"))
    }

    pub fn row(&mut self, line: std::fmt::Arguments) {
        use std::fmt::Write;
        writeln!(self.0, "{line}").unwrap();
    }
}

impl Drop for Table {
    fn drop(&mut self) {
        println!("{}", self.0);
    }
}

// ----- scenes ---------------------------------------------------------------------------------

/// The scene file `scenes/<name>.toml` of this repository.
pub fn scene(name: &str) -> std::sync::Arc<georod::scene::Scene> {
    let path = format!("{}/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    std::sync::Arc::new(georod::scene::Scene::load(&path).unwrap_or_else(|e| panic!("{e}")))
}

/// Every scene file of this repository (`scenes/*.toml`, then `examples/*.toml`), loaded.
pub fn scene_files() -> Vec<std::sync::Arc<georod::scene::Scene>> {
    let mut paths = Vec::new();
    for dir in ["scenes", "examples"] {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
        let mut here: Vec<_> = (std::fs::read_dir(&dir).unwrap())
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
        here.sort();
        paths.extend(here);
    }
    paths
        .iter()
        .map(|p| {
            std::sync::Arc::new(georod::scene::Scene::load(p).unwrap_or_else(|e| panic!("{e}")))
        })
        .collect()
}

/// A scene's simulation with some parameters overridden by name.
pub fn simulation(name: &str, overrides: &[(&str, f64)]) -> georod::simulation::Simulation {
    let scene = scene(name);
    let values = scene
        .values_with(overrides.iter().copied())
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    georod::simulation::Simulation::new(scene, values).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A parameter's current value.
pub fn param(sim: &georod::simulation::Simulation, name: &str) -> f64 {
    let i = sim.scene().param_index(name).expect("a parameter");
    sim.values().get(i)
}

/// Sets a parameter (tunable, or fixed to its current value).
pub fn set_param(sim: &mut georod::simulation::Simulation, name: &str, value: f64) {
    let i = sim.scene().param_index(name).expect("a parameter");
    sim.set_param(i, value).unwrap_or_else(|e| panic!("{e}"));
}

/// Sets an input by name.
pub fn set_input(sim: &mut georod::simulation::Simulation, name: &str, value: f64) {
    let i = (sim.scene().inputs.iter())
        .position(|input| input.name == name)
        .expect("an input");
    sim.set_input(i, value).unwrap();
}

/// An output by name (sensors, reactions, energies).
pub fn output(sim: &georod::simulation::Simulation, name: &str) -> f64 {
    sim.output_by_name(name)
        .unwrap_or_else(|| panic!("no output {name}"))
}

/// The first `k` Lyapunov exponents of a simulation (outputs `lyapunov[1]` .. `lyapunov[k]`).
pub fn lyapunov_exponents(sim: &Simulation, k: usize) -> Vec<f64> {
    (1..=k)
        .map(|j| output(sim, &format!("lyapunov[{j}]")))
        .collect()
}

/// One communication step of `h` with the control force `f_ctrl` held.
pub fn advance(sim: &mut Simulation, h: f64, f_ctrl: f64) -> Result<AdvanceReport, SimError> {
    set_input(sim, "f_ctrl", f_ctrl);
    sim.advance(h)
}

/// The loads of fixed direction along `-e2`: `F cos(Omega t)` per unit length on the whole rod
/// (`distributed`) or at `s = S/2`, plus a constant point force at `s = S/2`.
pub fn loads(rod: &Rod, distributed: bool, f: f64, omega: f64, point_force: f64) -> LoadSet {
    let middle = LoadShape::Point {
        s: 0.5 * rod.curve.length(),
        component: U2,
        sign: -1.0,
    };
    let excitation = if distributed {
        LoadShape::Distributed {
            component: U2,
            sign: -1.0,
        }
    } else {
        middle
    };
    let mut loads = LoadSet::new(
        rod,
        &[
            (excitation, LoadTime::Harmonic { group: 0 }),
            (middle, LoadTime::Constant),
        ],
    );
    loads.set_magnitudes(&[f, point_force]);
    loads.frequency = omega;
    loads
}

/// Asserts that the scene `text` is refused with a message containing every one of `parts`
/// (`what` names the case in a failure).
pub fn assert_refused(what: &str, text: &str, parts: &[&str]) {
    let e = georod::scene::Scene::parse(text, "bad.toml")
        .err()
        .unwrap_or_else(|| panic!("{what}: accepted"))
        .to_string();
    for part in parts {
        assert!(e.contains(part), "{what}: `{e}` lacks `{part}`");
    }
}

/// The simulation of a scene given as text, with some parameters overridden by name.
pub fn simulation_of(text: &str, overrides: &[(&str, f64)]) -> Simulation {
    let scene = std::sync::Arc::new(
        georod::scene::Scene::parse(text, "test.toml").unwrap_or_else(|e| panic!("{e}")),
    );
    let values = scene
        .values_with(overrides.iter().copied())
        .unwrap_or_else(|e| panic!("{e}"));
    Simulation::new(scene, values).unwrap_or_else(|e| panic!("{e}"))
}
