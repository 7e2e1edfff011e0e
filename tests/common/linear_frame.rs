//! An independent linear frame for checking georod's frames: straight Timoshenko beam elements
//! (axial, bending and shear flexibility; the element stiffness is exact for loads at its ends)
//! with rigid joints, a lumped mass, dense assembly, held dofs, a static solve and the
//! generalized eigenproblem. Written from the textbook element, sharing no code with the core.
use nalgebra::{DMatrix, DVector};

pub struct Beam {
    pub nodes: [usize; 2],
    pub ea: f64,
    /// Shear stiffness `G As`.
    pub gas: f64,
    pub ei: f64,
    pub rho_a: f64,
    pub rho_i: f64,
}

#[derive(Default)]
pub struct LinearFrame {
    pub nodes: Vec<[f64; 2]>,
    pub beams: Vec<Beam>,
    pub held: Vec<usize>,
}

impl LinearFrame {
    /// A node; returns its index (dofs `3 i + (u1, u2, w)`).
    pub fn node(&mut self, x: f64, y: f64) -> usize {
        self.nodes.push([x, y]);
        self.nodes.len() - 1
    }

    /// A straight member from node `a` to node `b` cut into `n` beams (new nodes between).
    #[allow(clippy::too_many_arguments)]
    pub fn member(
        &mut self,
        a: usize,
        b: usize,
        n: usize,
        ea: f64,
        gas: f64,
        ei: f64,
        rho_a: f64,
        rho_i: f64,
    ) {
        let (xa, xb) = (self.nodes[a], self.nodes[b]);
        let mut previous = a;
        for k in 1..=n {
            let next = if k == n {
                b
            } else {
                let t = k as f64 / n as f64;
                self.node(xa[0] + t * (xb[0] - xa[0]), xa[1] + t * (xb[1] - xa[1]))
            };
            self.beams.push(Beam {
                nodes: [previous, next],
                ea,
                gas,
                ei,
                rho_a,
                rho_i,
            });
            previous = next;
        }
    }

    pub fn dofs(&self) -> usize {
        3 * self.nodes.len()
    }

    fn transform(&self, beam: &Beam) -> (f64, DMatrix<f64>) {
        let [a, b] = beam.nodes;
        let (dx, dy) = (
            self.nodes[b][0] - self.nodes[a][0],
            self.nodes[b][1] - self.nodes[a][1],
        );
        let l = (dx * dx + dy * dy).sqrt();
        let (c, s) = (dx / l, dy / l);
        let mut t = DMatrix::zeros(6, 6);
        for n in 0..2 {
            let o = 3 * n;
            t[(o, o)] = c;
            t[(o, o + 1)] = s;
            t[(o + 1, o)] = -s;
            t[(o + 1, o + 1)] = c;
            t[(o + 2, o + 2)] = 1.0;
        }
        (l, t)
    }

    fn scatter(target: &mut DMatrix<f64>, beam: &Beam, k: &DMatrix<f64>) {
        let dofs: Vec<usize> = beam
            .nodes
            .iter()
            .flat_map(|&n| [3 * n, 3 * n + 1, 3 * n + 2])
            .collect();
        for (r, &i) in dofs.iter().enumerate() {
            for (c, &j) in dofs.iter().enumerate() {
                target[(i, j)] += k[(r, c)];
            }
        }
    }

    /// The stiffness: per beam, `EA / l` axially and the Timoshenko bending block with
    /// `phi = 12 EI / (G As l^2)`.
    pub fn stiffness(&self) -> DMatrix<f64> {
        let mut k = DMatrix::zeros(self.dofs(), self.dofs());
        for beam in &self.beams {
            let (l, t) = self.transform(beam);
            let phi = 12.0 * beam.ei / (beam.gas * l * l);
            let b = beam.ei / (l * l * l * (1.0 + phi));
            let a = beam.ea / l;
            #[rustfmt::skip]
            let local = DMatrix::from_row_slice(6, 6, &[
                a, 0.0, 0.0, -a, 0.0, 0.0,
                0.0, 12.0 * b, 6.0 * l * b, 0.0, -12.0 * b, 6.0 * l * b,
                0.0, 6.0 * l * b, (4.0 + phi) * l * l * b, 0.0, -6.0 * l * b, (2.0 - phi) * l * l * b,
                -a, 0.0, 0.0, a, 0.0, 0.0,
                0.0, -12.0 * b, -6.0 * l * b, 0.0, 12.0 * b, -6.0 * l * b,
                0.0, 6.0 * l * b, (2.0 - phi) * l * l * b, 0.0, -6.0 * l * b, (4.0 + phi) * l * l * b,
            ]);
            Self::scatter(&mut k, beam, &(t.transpose() * local * t));
        }
        k
    }

    /// The lumped mass: half of each beam's `rho A l` on its nodes' translations and half its
    /// `rho I l` on their rotations.
    pub fn lumped_mass(&self) -> DVector<f64> {
        let mut m = DVector::zeros(self.dofs());
        for beam in &self.beams {
            let (l, _) = self.transform(beam);
            for &n in &beam.nodes {
                m[3 * n] += 0.5 * beam.rho_a * l;
                m[3 * n + 1] += 0.5 * beam.rho_a * l;
                m[3 * n + 2] += 0.5 * beam.rho_i * l;
            }
        }
        m
    }

    fn free(&self) -> Vec<usize> {
        (0..self.dofs())
            .filter(|d| !self.held.contains(d))
            .collect()
    }

    /// The displacements under the nodal forces `f` (held dofs at zero).
    pub fn solve(&self, f: &[f64]) -> Vec<f64> {
        let free = self.free();
        let k = self.stiffness();
        let kf = DMatrix::from_fn(free.len(), free.len(), |r, c| k[(free[r], free[c])]);
        let ff = DVector::from_fn(free.len(), |r, _| f[free[r]]);
        let x = kf.lu().solve(&ff).expect("a stable frame");
        let mut u = vec![0.0; self.dofs()];
        for (r, &d) in free.iter().enumerate() {
            u[d] = x[r];
        }
        u
    }

    /// The natural frequencies (Hz), ascending: `K phi = omega^2 M phi` with the lumped mass.
    pub fn frequencies(&self) -> Vec<f64> {
        let free = self.free();
        let (k, m) = (self.stiffness(), self.lumped_mass());
        let scale: Vec<f64> = free.iter().map(|&d| 1.0 / m[d].sqrt()).collect();
        let a = DMatrix::from_fn(free.len(), free.len(), |r, c| {
            k[(free[r], free[c])] * scale[r] * scale[c]
        });
        let mut lambda: Vec<f64> = a.symmetric_eigenvalues().iter().copied().collect();
        lambda.sort_by(f64::total_cmp);
        lambda
            .iter()
            .map(|l| l.max(0.0).sqrt() / std::f64::consts::TAU)
            .collect()
    }
}
