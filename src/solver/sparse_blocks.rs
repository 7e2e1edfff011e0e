//! TEMPORARY dense stand-in for the block-sparse solver (same API), to develop frames against.
use super::SingularMatrix;
use nalgebra::{DMatrix, Matrix3};
use std::sync::Arc;

#[derive(Clone, Debug)]
pub struct BlockPattern {
    nodes: usize,
    adjacency: Vec<Vec<usize>>,
}

impl BlockPattern {
    pub fn new(nodes: usize, edges: &[(usize, usize)]) -> BlockPattern {
        let mut adjacency = vec![Vec::new(); nodes];
        for &(i, j) in edges {
            adjacency[i].push(j);
            adjacency[j].push(i);
        }
        for (i, a) in adjacency.iter_mut().enumerate() {
            a.push(i);
            a.sort();
            a.dedup();
        }
        BlockPattern { nodes, adjacency }
    }
    pub fn nodes(&self) -> usize {
        self.nodes
    }
    pub fn slot(&self, i: usize, j: usize) -> Option<usize> {
        self.adjacency[i]
            .binary_search(&j)
            .ok()
            .map(|_| i * self.nodes + j)
    }
}

#[derive(Clone, Debug)]
pub struct SparseBlocks {
    pattern: Arc<BlockPattern>,
    a: DMatrix<f64>,
    lu: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
    ties: Vec<(usize, usize)>,
    inertia: usize,
}

impl SparseBlocks {
    pub fn new(pattern: Arc<BlockPattern>) -> SparseBlocks {
        let n = 3 * pattern.nodes;
        SparseBlocks {
            pattern,
            a: DMatrix::zeros(n, n),
            lu: None,
            ties: Vec::new(),
            inertia: 0,
        }
    }
    pub fn with_ties(mut self, ties: Vec<(usize, usize)>) -> SparseBlocks {
        self.ties = ties;
        self
    }
    pub fn pattern(&self) -> &BlockPattern {
        &self.pattern
    }
    pub fn set_zero(&mut self) {
        self.a.fill(0.0);
        self.lu = None;
    }
    pub fn copy_from(&mut self, other: &SparseBlocks) {
        self.a.copy_from(&other.a);
        self.lu = None;
    }
    pub fn add_block(&mut self, slot: usize, block: &Matrix3<f64>, scale: f64) {
        let (i, j) = (slot / self.pattern.nodes, slot % self.pattern.nodes);
        for r in 0..3 {
            for c in 0..3 {
                self.a[(3 * i + r, 3 * j + c)] += scale * block[(r, c)];
            }
        }
    }
    pub fn add_pair_slots(
        &mut self,
        slots: [usize; 4],
        aa: &Matrix3<f64>,
        ab: &Matrix3<f64>,
        bb: &Matrix3<f64>,
        scale: f64,
    ) {
        self.add_block(slots[0], aa, scale);
        self.add_block(slots[1], ab, scale);
        self.add_block(slots[2], &ab.transpose(), scale);
        self.add_block(slots[3], bb, scale);
    }
    pub fn add_entry(&mut self, r: usize, c: usize, value: f64) {
        assert!(
            self.pattern.slot(r / 3, c / 3).is_some(),
            "entry ({r}, {c}) not in the pattern"
        );
        self.a[(r, c)] += value;
    }
    pub fn add_diagonal(&mut self, dof: usize, value: f64) {
        self.a[(dof, dof)] += value;
    }
    pub fn constrain(&mut self, dofs: &[usize]) {
        for &d in dofs {
            self.a.row_mut(d).fill(0.0);
            self.a.column_mut(d).fill(0.0);
            self.a[(d, d)] = 1.0;
        }
    }
    pub fn constrain_direction(&mut self, node: usize, n: [f64; 2]) {
        let dim = self.a.nrows();
        let mut p = DMatrix::<f64>::identity(dim, dim);
        let (i, j) = (3 * node, 3 * node + 1);
        p[(i, i)] -= n[0] * n[0];
        p[(i, j)] -= n[0] * n[1];
        p[(j, i)] -= n[1] * n[0];
        p[(j, j)] -= n[1] * n[1];
        self.a = &p * &self.a * &p;
        self.a[(i, i)] += n[0] * n[0];
        self.a[(i, j)] += n[0] * n[1];
        self.a[(j, i)] += n[1] * n[0];
        self.a[(j, j)] += n[1] * n[1];
    }
    fn do_factor(&mut self, inertia: bool) -> Result<(), SingularMatrix> {
        if inertia {
            let sym = 0.5 * (&self.a + self.a.transpose());
            let eig = sym.symmetric_eigenvalues();
            self.inertia = eig.iter().filter(|&&l| l < 0.0).count();
        }
        let lu = self.a.clone().lu();
        let d = lu.u().diagonal();
        let scale = self.a.amax().max(1e-300);
        if d.iter().any(|x| !x.is_finite() || x.abs() <= 1e-14 * scale) {
            return Err(SingularMatrix { block: 0 });
        }
        self.lu = Some(lu);
        Ok(())
    }
    pub fn factor(&mut self) -> Result<(), SingularMatrix> {
        self.do_factor(false)
    }
    pub fn factor_symmetric(&mut self) -> Result<(), SingularMatrix> {
        self.do_factor(false)
    }
    pub fn factor_with_inertia(&mut self) -> Result<(), SingularMatrix> {
        self.do_factor(true)
    }
    pub fn negative_eigenvalues(&self) -> usize {
        self.inertia
    }
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        let b = nalgebra::DVector::from_column_slice(rhs);
        let x = self
            .lu
            .as_ref()
            .expect("factored")
            .solve(&b)
            .expect("solve");
        rhs.copy_from_slice(x.as_slice());
        for &(s, m) in &self.ties {
            rhs[s] = rhs[m];
        }
    }
    pub fn solve_pair(&self, a: &mut [f64], b: &mut [f64]) {
        self.solve_in_place(a);
        self.solve_in_place(b);
    }
    pub fn mul(&self, x: &[f64], out: &mut [f64]) {
        let y = &self.a * nalgebra::DVector::from_column_slice(x);
        out.copy_from_slice(y.as_slice());
    }
    pub fn row_entries(&self, dof: usize) -> Vec<(usize, f64)> {
        (0..self.a.ncols())
            .filter(|&c| self.a[(dof, c)] != 0.0)
            .map(|c| (c, self.a[(dof, c)]))
            .collect()
    }
}
